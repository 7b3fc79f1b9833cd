"""Exported path ribbons: one layer of upward triangles covering the preview's ribbon."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from render_fixtures import road

from scenewright.render.meshes import path_mesh
from scenewright.render.ribbon import ribbon_mesh


def _cover_counts(mesh, points: np.ndarray) -> np.ndarray:
    """How many of ``mesh``'s triangles contain each (x, z) point strictly inside."""
    tri = mesh.vertices[mesh.faces][:, :, [0, 2]]  # (n, 3, 2)
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]

    def side(p, q, r):
        return (q[:, None, 0] - p[:, None, 0]) * (r[None, :, 1] - p[:, None, 1]) - (
            q[:, None, 1] - p[:, None, 1]
        ) * (r[None, :, 0] - p[:, None, 0])

    s1, s2, s3 = side(a, b, points), side(b, c, points), side(c, a, points)
    eps = 1e-7
    inside = ((s1 > eps) & (s2 > eps) & (s3 > eps)) | ((s1 < -eps) & (s2 < -eps) & (s3 < -eps))
    return inside.sum(axis=0)


def _samples(mesh, count: int = 4000) -> np.ndarray:
    lo, hi = mesh.bounds[0][[0, 2]], mesh.bounds[1][[0, 2]]
    return np.random.default_rng(0).uniform(lo, hi, size=(count, 2))


def test_a_turning_road_is_covered_once_where_the_preview_covers_it_more():
    path = road("road_1", [[0, 0], [8, 0], [12, 5], [12, 12], [4, 14]], width=3.0)
    ribbon, preview = ribbon_mesh(path), path_mesh(path)
    points = _samples(preview)
    assert _cover_counts(preview, points).max() >= 2  # the preview's joints overlap
    ours, theirs = _cover_counts(ribbon, points), _cover_counts(preview, points)
    assert ours.max() == 1
    # The same outline: a point the preview covers the ribbon covers too, and back
    # (but for the polygons' sides standing in for the preview's round joins).
    assert np.mean((ours > 0) != (theirs > 0)) < 0.005
    assert np.allclose(ribbon.face_normals, [0.0, 1.0, 0.0])


@settings(max_examples=40, deadline=None)
@given(
    st.lists(
        st.tuples(st.integers(-20, 20), st.integers(-20, 20)), min_size=2, max_size=6, unique=True
    ),
    st.floats(0.5, 3.0),
)
def test_no_point_is_covered_twice(points, width):
    """Where the segments are long enough for their mitres (as the layout's paths are),
    no two triangles overlap, whatever the turns."""
    points = [np.array(p, dtype=float) * 4.0 for p in points]
    steps = np.diff(points, axis=0)
    turns = [
        np.arccos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1))
        for u, v in zip(steps[:-1], steps[1:], strict=False)
    ]
    shortest = min(np.linalg.norm(steps, axis=1))
    if any(turn > np.radians(120) for turn in turns) or shortest < 4 * width:
        return  # a hairpin's mitre reaches past its segments: no exact one layer
    if _comes_back_near_itself(points, width):
        return  # a road that crosses itself covers the crossing twice by its nature
    ribbon = ribbon_mesh(road("road_1", points, width=width))
    assert _cover_counts(ribbon, _samples(ribbon, 1500)).max() <= 1
    assert np.allclose(ribbon.face_normals, [0.0, 1.0, 0.0])


def _comes_back_near_itself(points, width: float) -> bool:
    """Whether two segments that do not meet pass within a road's width of each other."""
    along = np.linspace(0.0, 1.0, 50)[:, None]
    samples = [a + along * (b - a) for a, b in zip(points[:-1], points[1:], strict=False)]
    for i in range(len(samples)):
        for j in range(i + 2, len(samples)):
            gaps = np.linalg.norm(samples[i][:, None] - samples[j][None, :], axis=2)
            if gaps.min() < 2 * width:
                return True
    return False
