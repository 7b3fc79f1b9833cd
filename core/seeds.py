"""Seeds: one ``SeedSequence`` per scene, an independent child stream per stage.

A scene's seed makes one ``numpy.random.SeedSequence``; every stage draws from its own
child of it, named by a fixed spawn key, so no stage's draws depend on how many numbers
another stage drew, and no two streams coincide:

    expansion            (0,)
    layout chain k       (1, k)      restart k of the layout
    describer variant k  (2, k)      paraphrase variant k
    camera view k        (3, k)      sampled camera of view k
    layout retry k       (4, k)      the layout seed of a dataset's retry k (``retry_seed``)
    questions of view k  (5, k)      which questions are asked of picture k (``describer.questions``)
    relations test k     (6, k)      the tests of type pair k (``learning.relation_finding``)
    learn check k        (7, k)      scene k made from induced rules (``learning.learn``)
    context layout k     (8, k)      layout k of a context fit's iterative scaling (``learning.context``)
    prompt               (9, 0)      which prompt a dataset scene composes (``dataset --prompts``)
    stage ``name``       (STAGE_KEYS[name], k) for later stages

Public functions take ``seed: int | numpy.random.Generator | None``, as numpy and
networkx do: an int names the scene's streams, a Generator is used as the stream itself
(a stage that needs several children spawns them from it), None draws fresh entropy
(not reproducible). ``check_seed`` validates an int at the boundary with a one-line
``InputError``.
"""

from __future__ import annotations

import numpy as np

from .errors import InputError

SeedLike = int | np.integer | np.random.Generator | None

#: The first element of each stage's spawn key. New stages take new numbers; existing
#: numbers never change, so existing scenes keep their bytes.
STAGE_KEYS: dict[str, int] = {
    "expansion": 0,
    "layout": 1,
    "describer": 2,
    "camera": 3,
    "retry": 4,
    "questions": 5,
    "relations": 6,
    "learn": 7,
    "context": 8,
    "prompt": 9,
    "plan": 10,
    "room": 11,
}

#: The largest seed accepted: seeds are stored in scene.json and file names as plain
#: integers, and 2**63 - 1 round-trips through every JSON reader.
MAX_SEED = 2**63 - 1


def check_seed(seed: object, what: str = "seed") -> int:
    """``seed`` as an int when it is one in [0, 2**63 - 1]; otherwise ``InputError``."""
    if isinstance(seed, (bool, np.bool_)) or not isinstance(seed, (int, np.integer)):
        raise InputError(f"{what} must be a whole number from 0 to {MAX_SEED}, got {seed!r}")
    if not 0 <= int(seed) <= MAX_SEED:
        raise InputError(f"{what} must be a whole number from 0 to {MAX_SEED}, got {int(seed)}")
    return int(seed)


def stream(seed: int | np.integer, stage: str, index: int = 0) -> np.random.Generator:
    """The Generator of ``stage`` (child ``index``) of the scene with ``seed``."""
    key = (STAGE_KEYS[stage],) if stage == "expansion" else (STAGE_KEYS[stage], index)
    return np.random.Generator(
        np.random.PCG64(np.random.SeedSequence(check_seed(seed), spawn_key=key))
    )


def stage_stream(seed: SeedLike, stage: str, index: int = 0) -> np.random.Generator:
    """One Generator for a stage: child ``index`` of an int seed, or the Generator given."""
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None:
        return np.random.default_rng()
    return stream(seed, stage, index)


def retry_seed(seed: int, attempt: int) -> int:
    """The layout seed of attempt ``attempt`` at laying out the scene with ``seed``.

    Attempt 0 is the scene's own seed; attempt k > 0 (a dataset's retry after a failed
    layout) draws a 32-bit seed from the scene's ``retry`` child k, so it depends on
    nothing but ``(seed, k)`` and its layout streams are independent of every earlier
    attempt's.
    """
    if attempt == 0:
        return check_seed(seed)
    return int(stream(seed, "retry", attempt).integers(0, 2**32))
