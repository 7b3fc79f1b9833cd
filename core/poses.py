"""What a layout returns: poses, path control points, and an honest report.

Plain data only, part of the core model so the scene can be assembled from it without
importing the layout stage. ``ok`` is true only when every relation is satisfied, no two objects
(or an object and a path) overlap beyond the tolerance, and everything lies inside the
scene extent; ``problems`` says in words what failed otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .relations import Relation


@dataclass(frozen=True)
class Pose:
    """Base centre (x, y, z) in metres and yaw in radians about +Y.

    Yaw 0 means the object's forward (local +Z) points along world +Z (south); a yaw of
    pi/2 turns forward to +X (east).
    """

    x: float
    y: float
    z: float
    yaw: float = 0.0


@dataclass
class LayoutResult:
    """The placed scene: a pose for every object and junction, points for every path."""

    poses: dict[str, Pose]
    paths: dict[str, np.ndarray]  # path id -> (n, 2) control points in (x, z)
    relations: list[Relation]  # every edge of the graph, each with its verdict
    energy: float
    parts: dict[str, float]  # "relations", "collisions", "paths", "path_shape", "extent"
    steps: int
    acceptance: float
    seconds: float
    ok: bool
    problems: list[str] = field(default_factory=list)
