"""The plan image at scale: a 300-object town of our own (no layout needed: objects on a
jittered grid along roads), drawn with labels that never cover one another, the
unsatisfied relations always shown, and a picture that grows with the scene."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image
from render_fixtures import road, scene_of, thing

from scenewright.core.relations import Relation
from scenewright.render import plan_image
from scenewright.render.plan_image import (
    BASE_INCHES,
    RELATION,
    Label,
    draw_plan,
    figure_inches,
    place_labels,
)
from scenewright.render.plan_page import DPI, PlanPage

TYPES = ("house", "shed", "crate", "lamp", "bush", "bench")


def town(count: int = 300, seed: int = 0, *, broken: int = 12):
    """``count`` objects over 120 x 120 m in homesteads of five (a house and four small
    things within a few metres of it, so their labels crowd) on a jittered grid, four
    roads, a NextTo between consecutive objects, ``broken`` of them unsatisfied."""
    rng = np.random.default_rng(seed)
    homes = -(-count // 5)
    side = int(np.ceil(np.sqrt(homes)))
    spacing = 110.0 / side
    objects = []
    for k in range(count):
        home, member = divmod(k, 5)
        row, col = divmod(home, side)
        x = -55 + (col + 0.5) * spacing + rng.uniform(-1, 1)
        z = -55 + (row + 0.5) * spacing + rng.uniform(-1, 1)
        if member:
            angle = rng.uniform(0, 2 * np.pi)
            x, z = x + 3.5 * np.cos(angle), z + 3.5 * np.sin(angle)
        kind = "house" if member == 0 else TYPES[1 + k % (len(TYPES) - 1)]
        size = (4.0, 3.0, 4.0) if member == 0 else (0.8, 1.0, 0.8)
        objects.append(thing(f"{kind}_{k + 1}", (x, 0, z), size, yaw=float(rng.uniform(0, 6.28))))
    roads = [road(f"road_{k}", [[-60, -45 + 30 * k], [60, -45 + 30 * k]]) for k in range(4)]
    scene = scene_of(objects, roads, extent=(120.0, 120.0))
    pairs = list(zip(objects[:-1], objects[1:], strict=False))
    broken_at = set(rng.choice(len(pairs), size=broken, replace=False).tolist())
    scene.relations = [
        Relation(
            a.id,
            b.id,
            "NextTo",
            value=-1.0 if k in broken_at else 0.0,
            satisfied=k not in broken_at,
        )
        for k, (a, b) in enumerate(pairs)
    ]
    scene.layout.ok = broken == 0
    scene.layout.problems = [
        f"{a.id} is not next to {b.id}" for k, (a, b) in enumerate(pairs) if k in broken_at
    ]
    return scene


@pytest.mark.slow
def test_a_300_object_plan_names_most_objects_without_one_label_over_another(tmp_path, monkeypatch):
    kept = {}
    real = plan_image.place_labels

    def keep_and_place(page, labels):
        kept["page"] = page
        return real(page, labels)

    monkeypatch.setattr(plan_image, "place_labels", keep_and_place)
    titles = []
    save = PlanPage.save
    monkeypatch.setattr(
        PlanPage,
        "save",
        lambda page, path, title, *a: titles.append(title) or save(page, path, title, *a),
    )
    scene = town()
    image = draw_plan(scene, tmp_path / "plan.png")
    texts = kept["page"].texts
    for one, other in itertools.combinations(texts, 2):
        assert not one.box.overlaps(other.box)
    names = {text.text for text in texts}
    objects = [o.id for o in scene.objects]
    assert sum(o in names for o in objects) >= 0.8 * len(objects)
    red = [text.text for text in texts if text.colour == "red"]
    assert len(red) == 12  # every unsatisfied relation keeps its label
    for problem in scene.layout.problems:  # and the objects it names keep theirs
        words = problem.split()
        assert {words[0], words[-1]} <= names
    left_out = len(scene.objects) + len(scene.paths) + 12 - len(texts)
    (title,) = titles
    assert (f"({left_out} of" in title) == (left_out > 0) and "12 problems" in title

    pixels = np.asarray(Image.open(image).convert("RGB")).astype(int)
    assert pixels.shape[1] > 1.5 * BASE_INCHES * DPI  # the picture grew with the scene
    red_pixels = (pixels[..., 0] > 200) & (pixels[..., 1] < 60) & (pixels[..., 2] < 60)
    assert red_pixels.sum() > 12 * 30  # the dashed lines of the 12 unsatisfied relations


def test_labels_that_find_no_room_are_left_out_and_the_rest_never_overlap():
    page = PlanPage((0.0, 10.0), (0.0, 10.0), 4 * DPI)
    crowd = [Label(f"object_{k}", (5.0, 5.0), 3, size=8) for k in range(40)]  # all on one spot
    crowd.append(Label("NextTo", (5.0, 5.0), RELATION, size=8, colour="red"))
    placed = place_labels(page, crowd)
    assert placed == len(page.texts) < len(crowd)
    assert page.texts[0].text == "NextTo"  # the relation went first, on its anchor
    assert page.texts[0].box.x0 < page.anchor(5.0, 5.0)[0] < page.texts[0].box.x1
    for one, other in itertools.combinations(page.texts, 2):
        assert not one.box.overlaps(other.box)


@settings(max_examples=15, deadline=None)
@given(st.lists(st.tuples(st.floats(0, 10), st.floats(0, 10), st.integers(0, 3)), max_size=60))
def test_placed_labels_never_overlap_and_stay_inside(anchors):
    page = PlanPage((0.0, 10.0), (0.0, 10.0), 3 * DPI)
    labels = [Label(f"thing_{k}", (x, z), rank) for k, (x, z, rank) in enumerate(anchors)]
    placed = place_labels(page, labels)
    assert placed == len(page.texts)
    for text in page.texts:
        assert text.box.within(page.plot)
    for one, other in itertools.combinations(page.texts, 2):
        assert not one.box.overlaps(other.box)


@pytest.mark.parametrize(
    "labels, inches", [(10, BASE_INCHES), (60, BASE_INCHES), (240, 2 * BASE_INCHES), (10**6, 24.0)]
)
def test_the_picture_grows_with_the_square_root_of_its_labels(labels, inches):
    assert figure_inches(labels) == pytest.approx(inches)
