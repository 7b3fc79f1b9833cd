"""Test-suite settings: property tests draw the same examples on every run.

The suite promises fixed seeds; hypothesis's default draws new examples each run, so a
rare counterexample could make one CI run fail and the next pass. ``derandomize``
fixes the draws; run with ``--hypothesis-seed=random``-style exploration by setting
``SCENEWRIGHT_EXPLORE=1`` to hunt for new counterexamples locally.
"""

import gc
import os

import pytest
from hypothesis import settings
from render_fixtures import renderer_or_skip
from threadpoolctl import threadpool_limits

from scenewright.completion.model_builder import shipped_model
from scenewright.core.collector import collect_less
from scenewright.generator import indoor_catalog

settings.register_profile("fixed", derandomize=True)
settings.register_profile("explore", derandomize=False)
settings.load_profile("explore" if os.environ.get("SCENEWRIGHT_EXPLORE") else "fixed")

# The test processes collect cyclic garbage as the console command does (``collector``)
# and leave what exists once the tests are collected (modules, the collected tests) out
# of every later collection: with Python's defaults, traversing that large, long-lived
# heap again and again took about a tenth of the suite's CPU time.
collect_less()


# One thread for numpy's BLAS in each test process: the suite runs a process per core,
# and OpenBLAS's own threads only contended with the other process (the relation tests
# took twice the CPU). Results do not depend on it. The variable does the same for the
# processes started from here (the suite's workers, the commands and scripts the tests
# run), as the console command sets it for itself: starting OpenBLAS's thread pools
# would cost each of them a few tenths of a second of CPU.
threadpool_limits(limits=1, user_api="blas")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def pytest_collection_finish(session):
    gc.collect()
    gc.freeze()


@pytest.fixture(scope="session")
def model():
    """The completion model learned from the shipped floor plans (one per worker: no
    test changes it, and learning it takes most of a second)."""
    return shipped_model()


@pytest.fixture(scope="module")
def catalog():
    """The shipped indoor catalog."""
    return indoor_catalog()


@pytest.fixture(scope="module")
def renderer():
    """A small offscreen renderer (160 x 120); the test skips where OpenGL is missing."""
    renderer = renderer_or_skip(160, 120)
    yield renderer
    renderer.close()
