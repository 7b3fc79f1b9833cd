"""Datasets: N scenes from one rule set, in the Hugging Face ``imagefolder`` layout.

- ``spec``: what a dataset is (``DatasetSpec``), the names of its files and the
  numbering of its scenes; every other module here builds on it;
- ``run``: the run (``run_dataset``): the directory, resuming, the worker pool, the
  records, metadata.jsonl;
- ``produce``: one scene in a worker: generated, laid out again when its layout
  fails, described, rendered and encoded (``produce_scene``);
- ``coco``, ``questions``, ``stats``: annotations/instances.json, questions.json and
  the statistics of a dataset;
- ``cluster``: the run on a dask.distributed cluster;
- ``worker_preload``: what the fork server loads once for all its workers.
"""
