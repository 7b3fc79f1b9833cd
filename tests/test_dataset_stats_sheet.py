"""stats.png: the statistics sheet drawn with Pillow."""

import io

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from PIL import Image

from scenewright.dataset.stats_sheet import HEIGHT, RED, WIDTH, nice_ticks, stats_sheet


def stats(failed_after_retries: int = 0, errors: dict | None = None) -> dict:
    return {
        "scenes": 12,
        "written": 11,
        "failed": 1,
        "failed_layouts": 1,
        "errors": errors or {},
        "retries": {
            "scenes_retried": 2,
            "by_objects": [
                {"objects": "5-7", "scenes": 8, "retried": 2, "failed_after_retries": 0},
                {
                    "objects": "8-10",
                    "scenes": 4,
                    "retried": 1,
                    "failed_after_retries": failed_after_retries,
                },
            ],
        },
        "objects": {"chair": 30, "table": 12, "a_type_with_a_very_long_name_indeed_here": 1},
        "relations": {"NextTo": {"total": 20, "satisfied": 18}},
        "words": {
            "text": {
                "count": 12,
                "median": 46,
                "histogram": {"edges": [30.0, 40.0, 50.0], "counts": [4, 8]},
            },
            "caption": {"count": 0, "median": 0, "histogram": {"edges": [], "counts": []}},
        },
        "seconds_per_stage": {"layout": {"mean": 0.07}, "render": {"mean": 0.0004}},
    }


def picture(data: dict) -> np.ndarray:
    image = Image.open(io.BytesIO(stats_sheet(data)))
    assert image.size == (WIDTH, HEIGHT)
    return np.asarray(image.convert("RGB"))


def test_failures_after_retries_are_drawn_red_and_only_then():
    red = np.all(picture(stats(failed_after_retries=2)) == RED, axis=-1)
    assert red.sum() > 100
    assert not np.all(picture(stats()) == RED, axis=-1).any()


def test_the_sheet_is_the_same_bytes_each_time_and_an_empty_run_draws():
    assert stats_sheet(stats()) == stats_sheet(stats())
    empty = stats()
    empty.update(objects={}, relations={}, errors={}, seconds_per_stage={})
    empty["retries"]["by_objects"] = []
    empty["words"] = {}
    assert picture(empty).min() == 0  # the frames and the title, nothing else to draw


def test_errors_take_the_empty_panel():
    errors = {"layout": {"messages": {"no room for the wardrobe " * 8: 3}}}
    without, with_errors = picture(stats()), picture(stats(errors=errors))
    corner = (slice(HEIGHT // 2 + 20, HEIGHT), slice(2 * WIDTH // 3, WIDTH))
    assert (without[corner] == 255).all()
    assert (with_errors[corner] < 128).any()


@given(st.floats(0.0, 1e6), st.booleans())
def test_ticks_start_at_zero_reach_the_top_and_stay_few(top, whole):
    ticks = nice_ticks(top, whole)
    assert ticks[0] == 0 and ticks[-1] >= top - 1e-9
    assert 2 <= len(ticks) <= 8
    if whole:
        assert all(float(t).is_integer() for t in ticks)
