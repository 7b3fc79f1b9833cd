"""How often the processes scenewright runs collect cyclic garbage.

What a command or a dataset worker allocates is mostly freed by reference counting or
lives to the end (modules, the catalog, the scene being made), so Python's default of a
collection every 700 allocations spends its time traversing objects that were never
garbage: about 5 % of a cold ``generate``. The command's process and the dataset's
workers collect every ``THRESHOLDS[0]`` allocations instead. The library never changes
the collector of a program that imports it.
"""

from __future__ import annotations

import gc

#: The collector's thresholds (Python's default is 700, 10, 10).
THRESHOLDS = (20_000, 20, 20)


def collect_less() -> None:
    """Set this process's collector to ``THRESHOLDS``: for processes scenewright runs."""
    gc.set_threshold(*THRESHOLDS)
