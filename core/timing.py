"""Wall time per stage: the ``timings`` a Scene carries (seconds by stage name).

Every stage that adds its time to a scene's ``timings`` uses ``timed``, so each key is
summed the same way whoever does the work (``expand``, ``layout``, ``complete``,
``describe``, ``render``, ``export``).
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def timed(timings: dict[str, float], stage: str, clock=time.perf_counter) -> Iterator[None]:
    """Add the wall time of the ``with`` block to ``timings[stage]`` (or its time by
    another ``clock``, such as ``time.process_time`` for CPU time)."""
    start = clock()
    try:
        yield
    finally:
        timings[stage] = timings.get(stage, 0.0) + clock() - start
