"""The procedural mesh builders: one for every shipped shape, well formed and facing +Z."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.generator.rules import load_rules, shipped_rule_sets
from scenewright.render.builders import BUILDERS
from scenewright.render.meshes import fit_to_size

#: A test colour no builder uses as a secondary colour, so its faces can be told apart.
MAIN = (0.5, 0.1, 0.9)


def shipped_looks() -> dict[str, tuple[float, float, float]]:
    """Every shape name the shipped rule sets use (styles included), with a size for it."""
    looks: dict[str, tuple[float, float, float]] = {}
    for name in shipped_rule_sets():
        for entry in load_rules(name).catalog:
            if entry.kind != "object":
                continue
            for style in entry.styles or (None,):
                styled = entry.with_style(style)
                looks.setdefault(styled.shape or "box", styled.size)
    return looks


LOOKS = shipped_looks()


def test_every_shipped_shape_has_a_builder():
    assert LOOKS, "the shipped rule sets declare no objects"
    assert sorted(set(LOOKS) - set(BUILDERS)) == []


@pytest.mark.parametrize("shape", sorted(LOOKS))
def test_builder_makes_a_small_coloured_mesh_of_the_right_proportions(shape):
    size = np.array(LOOKS[shape])
    mesh = BUILDERS[shape](tuple(size), MAIN)
    assert 0 < len(mesh.faces) < 500
    assert len(mesh.visual.face_colors) == len(mesh.faces)
    if shape != "box":
        assert len(np.unique(mesh.visual.face_colors, axis=0)) >= 2, "one flat colour"
    # Built at the catalog size: fitting scales by little, so the proportions hold.
    extents = mesh.bounds[1] - mesh.bounds[0]
    assert np.all(np.abs(extents / size - 1.0) < 0.2), extents
    # Stands on the ground, centred on the origin.
    assert abs(mesh.bounds[0][1]) <= 0.03 * size[1]
    centre_xz = (mesh.bounds[0] + mesh.bounds[1])[[0, 2]] / 2
    assert np.all(np.abs(centre_xz) <= 0.1 * size[[0, 2]])


@pytest.mark.parametrize("shape", sorted(LOOKS))
def test_fitted_mesh_fills_the_size_exactly(shape):
    size = LOOKS[shape]
    fitted = fit_to_size(BUILDERS[shape](size, MAIN), size)
    w, h, d = size
    np.testing.assert_allclose(fitted.bounds, [[-w / 2, 0.0, -d / 2], [w / 2, h, d / 2]], atol=1e-9)


def test_builders_are_deterministic():
    for shape, size in LOOKS.items():
        first, second = BUILDERS[shape](size, MAIN), BUILDERS[shape](size, MAIN)
        np.testing.assert_array_equal(first.vertices, second.vertices)
        np.testing.assert_array_equal(first.visual.face_colors, second.visual.face_colors)


# -- orientation: the front of every object is +Z ------------------------------------


def face_centres(mesh, where):
    """Centres of the faces selected by ``where(centres) -> bool mask``."""
    centres = mesh.triangles_center
    return centres[where(centres)]


def test_chair_back_rest_is_behind_the_seat():
    w, h, d = LOOKS["chair"]
    above_seat = face_centres(BUILDERS["chair"]((w, h, d), MAIN), lambda c: c[:, 1] > 0.7 * h)
    assert len(above_seat) and np.all(above_seat[:, 2] < -0.35 * d)


def test_bed_headboard_and_pillow_are_at_the_back():
    w, h, d = LOOKS["bed"]
    mesh = BUILDERS["bed"]((w, h, d), MAIN)
    above_mattress = face_centres(mesh, lambda c: c[:, 1] > 0.75 * h)
    assert len(above_mattress) and np.all(above_mattress[:, 2] < -0.45 * d)
    pillow = face_centres(mesh, lambda c: (c[:, 1] > 0.6 * h) & (np.abs(c[:, 2]) < 0.45 * d))
    assert len(pillow) and pillow[:, 2].mean() < -0.2 * d


def test_laptop_screen_stands_at_the_back():
    w, h, d = LOOKS["laptop"]
    screen = face_centres(BUILDERS["laptop"]((w, h, d), MAIN), lambda c: c[:, 1] > 0.5 * h)
    assert len(screen) and np.all(screen[:, 2] < -0.4 * d)


def test_wagon_shaft_points_forward():
    w, h, d = LOOKS["wagon"]
    front = face_centres(BUILDERS["wagon"]((w, h, d), MAIN), lambda c: c[:, 2] > 0.3 * d)
    # Only the low, narrow shaft poles reach the front quarter; the cart body stays back.
    assert len(front) and np.all(front[:, 1] < 0.7 * h) and np.all(np.abs(front[:, 0]) < 0.25 * w)


def test_desk_lamp_shade_hangs_over_the_front():
    w, h, d = LOOKS["desk_lamp"]
    shade = face_centres(
        BUILDERS["desk_lamp"]((w, h, d), MAIN), lambda c: (c[:, 1] > 0.6 * h) & (c[:, 1] < 0.9 * h)
    )
    assert len(shade) and shade[:, 2].mean() > 0.1 * d


@pytest.mark.parametrize("shape", ["treadmill", "exercise_bike", "rowing_machine"])
def test_cardio_machines_have_their_console_or_flywheel_at_the_back(shape):
    """One gets on at the front (+Z) and faces the back (-Z): the console (a treadmill's,
    a bike's) or the flywheel housing (a rower's) is the high part, and it is behind."""
    w, h, d = LOOKS[shape]
    high = face_centres(BUILDERS[shape]((w, h, d), MAIN), lambda c: c[:, 1] > 0.9 * h)
    assert len(high) and np.all(high[:, 2] < -0.2 * d), high[:, 2].max()


def test_weight_bench_pads_run_along_it_on_feet_across_it():
    w, h, d = LOOKS["weight_bench"]
    mesh = BUILDERS["weight_bench"]((w, h, d), MAIN)
    pads = face_centres(mesh, lambda c: c[:, 1] > 0.85 * h)
    assert np.ptp(pads[:, 2]) > 0.8 * d and np.all(np.abs(pads[:, 0]) < 0.3 * w)
    feet = face_centres(mesh, lambda c: c[:, 1] < 0.05 * h)
    assert np.abs(feet[:, 0]).max() > 0.4 * w


@pytest.mark.parametrize(
    "shape", ["house", "townhouse", "shed", "tower", "sign", "windmill", "wardrobe"]
)
def test_detailed_face_looks_forward(shape):
    """Doors, sign boards and sails are on the front (+Z): the +Z half has more faces."""
    w, h, d = LOOKS[shape]
    centres = BUILDERS[shape]((w, h, d), MAIN).triangles_center
    in_front, behind = np.sum(centres[:, 2] > 0.25 * d), np.sum(centres[:, 2] < -0.25 * d)
    assert in_front > behind


def test_trees_stand_on_a_narrow_trunk():
    for shape in ("pine_tree", "oak_tree"):
        w, h, d = LOOKS[shape]
        vertices = BUILDERS[shape]((w, h, d), MAIN).vertices
        low = vertices[vertices[:, 1] < 0.1 * h]
        assert len(low) and np.all(np.hypot(low[:, 0], low[:, 2]) < 0.15 * w)
        assert np.abs(vertices[:, 0]).max() > 0.45 * w  # the crown spreads wide above it


# -- any size a user's rules may give a shipped shape ----------------------------------

sizes = st.tuples(*[st.floats(0.05, 20.0, allow_nan=False)] * 3)  # w, h, d in metres


@settings(max_examples=60, deadline=None)
@given(shape=st.sampled_from(sorted(BUILDERS)), size=sizes)
def test_builders_accept_any_size(shape, size):
    mesh = BUILDERS[shape](size, MAIN)
    assert 0 < len(mesh.faces) < 500 and np.isfinite(mesh.vertices).all()
    fitted = fit_to_size(mesh, size)
    w, h, d = size
    np.testing.assert_allclose(
        fitted.bounds, [[-w / 2, 0.0, -d / 2], [w / 2, h, d / 2]], rtol=1e-9, atol=1e-9
    )
