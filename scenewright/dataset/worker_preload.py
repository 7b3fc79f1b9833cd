"""What a dataset's fork server loads once, before it forks a worker.

Every pool worker is forked from the fork server (``run.WorkerPool``), so whatever
the server has imported or built, each worker has at no cost. Besides the pipeline
(``run.WORKER_MODULES``), the server loads here what every worker would otherwise
redo for itself before its first scene: trimesh and pyrender with its offscreen OpenGL
platform chosen (imports of about 1 s, no OpenGL context: contexts are never inherited,
each worker creates its own) and the rules language's LALR parser (its tables, built
from the grammar). About a second less for each worker to start (docs/datasets.md).

A failure here is left for the worker to report: it is the worker that needs pyrender,
and its error says what to install (``render.offscreen``); the fork server itself would
die of it, since it only catches ``ImportError`` while it preloads.
"""

from __future__ import annotations

from scenewright.generator.rules_lark import lalr_parser
from scenewright.render import offscreen

lalr_parser()
try:
    offscreen.load_pyrender()
except Exception:  # reported by the worker that renders (module docstring)
    pass
