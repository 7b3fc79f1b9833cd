"""A dataset's questions.json: every row's questions in one file, in CLEVR's layout.

Made at the end of every run from metadata.jsonl (itself rebuilt from the scenes'
records), so a resumed or regrown dataset's file always covers exactly its rows.
Written a question at a time (never the whole list in memory) and atomically::

    {"info": {"rules": ..., "rules_digest": ..., "base_seed": ..., "count": N},
     "questions": [
      {"image_index": 0, "image_filename": "images/000000.png", "image": "000000",
       "question_index": 0, "question_family": "exist", "question": "Is there a tent?",
       "answer": "yes", "program": [{"function": "scene", "inputs": [], "value_inputs": []}, ...]},
      ...]}

``image_filename`` is relative to the dataset directory; ``question_index`` counts
through the file. Nothing is written when the dataset's questions are turned off.
"""

from __future__ import annotations

import json
from pathlib import Path

from scenewright.core.atomic import atomic_stream
from scenewright.dataset.spec import METADATA_FILE, DatasetSpec, image_number

QUESTIONS_FILE = "questions.json"


def publish_questions(root: Path, spec: DatasetSpec) -> int | None:
    """Write ``QUESTIONS_FILE`` from ``root``'s metadata.jsonl; return how many questions
    it holds (None, and nothing written, when ``spec`` turns questions or images off).
    An image's ``image_index`` counts images: scene i's view v is ``i * views + v``."""
    from scenewright.dataset.produce import captions_options

    if not captions_options(spec).questions or not spec.images:
        return None
    info = {
        "rules": spec.rules,
        "rules_digest": spec.rules_digest,
        "base_seed": spec.base_seed,
        "count": spec.count,
    }
    written = 0
    with (
        open(root / METADATA_FILE, encoding="utf-8") as rows,
        atomic_stream(root / QUESTIONS_FILE) as out,
    ):
        out.write('{"info": ' + json.dumps(info, ensure_ascii=False) + ',\n "questions": [')
        for line in rows:
            row = json.loads(line)
            for question in row.get("questions", ()):
                entry = {
                    "image_index": image_number(
                        int(row["scene_id"]), row.get("view", 0), spec.views
                    ),
                    "image_filename": row["file_name"],
                    "image": row["scene_id"],
                    "question_index": written,
                    "question_family": question["family"],
                    "question": question["question"],
                    "answer": question["answer"],
                    "program": question["program"],
                }
                out.write((",\n  " if written else "\n  ") + json.dumps(entry, ensure_ascii=False))
                written += 1
        out.write("\n]}\n")
    return written
