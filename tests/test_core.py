"""The core model: frames (scalar = vectorised), seeded streams, the relation registry."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.api import build_scene
from scenewright.core import frames
from scenewright.core.errors import InputError
from scenewright.core.relations import RELATIONS, Relation, RelationLabel, UnknownLabel
from scenewright.core.scene import assemble_scene
from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.core.seeds import MAX_SEED, check_seed, stage_stream, stream
from scenewright.describer import describe
from scenewright.describer.paraphrase import Choices
from scenewright.generator import expand, load_rules
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import layout_scene
from scenewright.generator.layout.families import evaluate, satisfied
from scenewright.generator.layout.params import LayoutParams
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.state import State

# -- frames ---------------------------------------------------------------------------

coordinate = st.floats(-50, 50, allow_nan=False)
angle = st.floats(-10, 10, allow_nan=False)
length = st.floats(0.01, 20, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(coordinate, coordinate, angle, length, length, coordinate, coordinate)
def test_scalar_and_vectorised_frames_agree(cx, cz, yaw, width, depth, px, pz):
    corners = frames.footprint_corners(cx, cz, yaw, width, depth)
    many = frames.footprint_corners_many(
        np.array([[cx, cz]]), np.array([yaw]), np.array([[width, depth]])
    )
    assert np.allclose(many[0], corners)
    assert np.allclose(
        frames.footprint_reach_many(np.array([yaw]), np.array([[width, depth]]))[0],
        frames.footprint_reach(yaw, width, depth),
    )
    local = frames.to_local(cx, cz, yaw, px, pz)
    assert np.allclose(
        frames.to_local_many(np.array([[cx, cz]]), np.array([yaw]), np.array([[[px, pz]]]))[0, 0],
        local,
    )
    assert np.allclose(frames.to_world(cx, cz, yaw, *local), (px, pz), atol=1e-9)
    assert np.allclose(frames.forward_many(np.array([yaw]))[0], frames.forward(yaw))
    # the reach is the half size of the corners' bounding box
    xs, zs = [c[0] for c in corners], [c[1] for c in corners]
    assert np.allclose(
        frames.footprint_reach(yaw, width, depth),
        ((max(xs) - min(xs)) / 2, (max(zs) - min(zs)) / 2),
    )


def test_the_convention_north_east_forward_left():
    assert np.allclose(frames.forward(0.0), (0.0, 1.0))  # yaw 0 faces south (+Z)
    assert np.allclose(frames.forward(math.pi / 2), (1.0, 0.0))  # a quarter turn faces east
    assert np.allclose(frames.left(0.0), (1.0, 0.0))  # its left is local +X
    assert np.allclose(
        frames.to_world(1.0, 2.0, math.pi / 2, 0.0, 1.0), (2.0, 2.0)
    )  # one metre ahead
    assert math.isclose(frames.yaw_of(*frames.forward(0.7)), 0.7)
    matrix = frames.transform_matrix(1.0, 0.5, 2.0, math.pi / 2)
    assert np.allclose(
        matrix @ [0.0, 0.0, 1.0, 1.0], [2.0, 0.5, 2.0, 1.0]
    )  # local +Z ahead, to the east


# -- seeds ----------------------------------------------------------------------------


def test_every_stage_has_its_own_stream():
    seed = 11
    streams = {
        "expansion": stream(seed, "expansion"),
        **{f"layout {k}": stream(seed, "layout", k) for k in range(3)},
        **{f"describer {k}": stream(seed, "describer", k) for k in range(1, 4)},
        **{f"camera {k}": stream(seed, "camera", k) for k in range(2)},
        # what expansion and layout chain 0 used before: numpy takes both as one seed
        "default_rng(seed), default_rng([seed, 0])": np.random.default_rng(seed),
    }
    draws = {name: tuple(rng.integers(0, 2**62, size=8)) for name, rng in streams.items()}
    assert len(set(draws.values())) == len(draws), "two streams gave the same numbers"
    assert (
        tuple(stream(seed, "layout", 1).integers(0, 2**62, size=8)) == draws["layout 1"]
    )  # and they are fixed


def test_the_pipeline_draws_from_those_streams(monkeypatch):
    """Expansion, each layout chain and each describer variant ask for their own stream."""
    asked: list[tuple[str, int]] = []
    import scenewright.core.seeds as seeds

    original = seeds.stream

    def spy(seed, stage, index=0):
        asked.append((stage, index))
        return original(seed, stage, index)

    monkeypatch.setattr(seeds, "stream", spy)
    monkeypatch.setattr("scenewright.describer.paraphrase.stream", spy)
    scene = build_scene("desk", 4)
    describe(scene, variant=2)
    assert asked[0] == ("expansion", 0)
    assert ("layout", 0) in asked and ("describer", 2) in asked
    assert len(asked) == len(set(asked))  # no stream is asked for twice


def test_seeds_are_checked_at_the_boundary():
    assert check_seed(0) == 0 and check_seed(np.int64(5)) == 5 and check_seed(MAX_SEED) == MAX_SEED
    for bad in (-1, MAX_SEED + 1, 1.5, "7", True, None):
        with pytest.raises(InputError, match="seed must be a whole number"):
            check_seed(bad)
    with pytest.raises(InputError, match="got -1"):
        build_scene("desk", -1)


def test_generators_and_none_are_accepted_as_seeds():
    rules = load_rules("desk")
    first = expand(rules, np.random.default_rng(3))
    assert first.to_dict() == expand(rules, np.random.default_rng(3)).to_dict()
    assert expand(rules, 3).to_dict() == expand(rules, stream(3, "expansion")).to_dict()
    assert len(expand(rules, None)) > 0
    rng = np.random.default_rng(1)
    assert stage_stream(rng, "layout") is rng
    graph = expand(rules, 3)
    a = layout_scene(graph, np.random.default_rng(9))
    b = layout_scene(graph, np.random.default_rng(9))
    assert a.poses == b.poses


def test_variant_choices_use_the_describer_stream():
    assert Choices.for_variant(5, 0)._rng is None
    drawn = Choices.for_variant(5, 2)._rng.integers(0, 2**62, size=4)
    assert np.array_equal(drawn, stream(5, "describer", 2).integers(0, 2**62, size=4))


def test_cli_refuses_a_negative_seed():
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "scenewright.cli",
            "generate",
            "village",
            "--seed",
            "-1",
            "-o",
            "unused",
        ],
        capture_output=True,
        text=True,
        check=False,
    )
    assert result.returncode == 2
    assert (
        result.stderr.count("\n") == 1
        and "--seed" in result.stderr
        and "Traceback" not in result.stderr
    )


# -- the relation registry --------------------------------------------------------------


def test_every_label_of_table_1_is_registered_with_its_implicit_form():
    names = RELATIONS.names()
    assert {
        "NextTo",
        "NextToChooseDirection",
        "OnTopOfFrontEdge",
        "IsPartOfMiddle",
        "FacingAwayFrom",
    } <= names
    assert "ImplicitNextToLeft" in names and "ImplicitPathConnectedTo" not in names
    implicit = RELATIONS["ImplicitOnTopOf"]
    assert (
        implicit.implicit
        and not implicit.described
        and implicit.support
        and implicit.base == "OnTopOf"
    )
    assert (
        RELATIONS["PathConnectedTo"].family == "structural"
        and not RELATIONS["PathConnectedTo"].described
    )


def test_an_unregistered_label_fails_at_once():
    graph = SceneGraph()
    table = CatalogEntry("table", "object", "table")
    a, b = graph.add_node(table), graph.add_node(table)
    with pytest.raises(UnknownLabel, match="unknown relation label 'NextToo'"):
        graph.add_relation(a, b, "NextToo")
    with pytest.raises(UnknownLabel):
        RELATIONS["Alongside"]


def test_an_incomplete_or_duplicate_label_is_refused():
    with pytest.raises(ValueError, match="has no wording"):
        RELATIONS.register(RelationLabel("NextToSomewhere", "next_to", "near"))
    with pytest.raises(ValueError, match="family 'glue'"):
        RELATIONS.register(RelationLabel("GluedTo", "glue", "glued to", ("is glued to",)))
    with pytest.raises(ValueError, match="registered twice"):
        RELATIONS.register(RelationLabel("NextTo", "next_to", "next to", ("is next to",)))
    assert "NextToSomewhere" not in RELATIONS


NORTH_EAST = RelationLabel(
    "NextToNorthEast",
    "next_to",
    "north-east of",
    ("is north-east of",),
    directions={"northeast": (math.sqrt(0.5), -math.sqrt(0.5))},
    frame="world",
    place=True,
)


def _two_crates(label: str, a_at: tuple[float, float]):
    graph = SceneGraph(params=SceneParams(extent=(20.0, 20.0)))
    crate = CatalogEntry("crate", "object", "crate", size=(1.0, 1.0, 1.0))
    a, b = graph.add_node(crate), graph.add_node(crate)
    graph.add_relation(a, b, label)
    problem = compile_problem(graph)
    state = State(problem)
    state.set_pose(0, *a_at, 0.0)
    state.set_pose(1, 0.0, 0.0, 0.0)
    return graph, problem, state


def test_a_new_label_is_picked_up_by_energy_check_wording_and_describer():
    """One registry entry, no other change: the layout scores and checks it, and the
    describer words it."""
    params = LayoutParams()
    with RELATIONS.extended(NORTH_EAST):
        assert "ImplicitNextToNorthEast" in RELATIONS
        graph, problem, state = _two_crates("NextToNorthEast", (1.2, -1.2))
        term = problem.relations[0]
        good = evaluate(term, state, params)
        assert satisfied(term, good, params) and good.energy < 0.1
        state.set_pose(0, -1.2, 1.2, 0.0)  # south-west instead
        bad = evaluate(term, state, params)
        assert not satisfied(term, bad, params) and bad.energy > 1.0

        # the sampler finds a layout where it holds, and the text states it
        result = layout_scene(graph, 3)
        assert result.ok, result.problems
        scene = assemble_scene(graph, result, rules="test", seed=3)
        text = describe(scene).text
        assert "is north-east of" in text, text
        assert ("crate_1", "NextToNorthEast", "crate_2") in describe(scene).facts
    assert "NextToNorthEast" not in RELATIONS  # the test's addition is gone again


def test_path_connections_are_relations_of_the_scene():
    scene = build_scene("village", 7)
    connected = [r for r in scene.relations if r.label == "PathConnectedTo"]
    assert connected and all(r.satisfied for r in connected)
    assert {(p.id, p.start) for p in scene.paths if p.start} == {
        (r.source, r.target) for r in connected
    }
    # every edge of the graph is one relation of the scene, in the same order
    graph = expand(load_rules("village"), 7)
    assert [(e.source, e.target, e.label) for e in graph.edges()] == [
        (r.source, r.target, r.label) for r in scene.relations
    ]
    assert all(isinstance(r, Relation) for r in scene.relations)


def test_the_scene_gives_back_its_graph_whole():
    scene = build_scene("village", 7)
    graph = expand(load_rules("village"), 7)
    back = scene.graph().to_dict()
    original = graph.to_dict()
    assert back["nodes"] == original["nodes"] and back["edges"] == original["edges"]
    assert back["derivation"] == original["derivation"] and back["derivation"]
    assert back["params"] == {**original["params"], "templates": scene.templates}


def test_the_layout_scores_every_family_of_the_registry():
    from scenewright.core.relations import FAMILIES
    from scenewright.generator.layout.families import LAYOUT_FAMILIES

    assert set(FAMILIES) - {"structural"} == set(LAYOUT_FAMILIES)


# -- the package structure ----------------------------------------------------------------

ROOT = __import__("pathlib").Path(__file__).parents[1]
#: Folder -> the scenewright packages its modules may import (besides their own).
ALLOWED_IMPORTS = {
    "core": set(),
    "generator": {"core"},
    "describer": {"core"},
    # The renderer writes its files whole through the atomic writer, a small file utility
    # of the application package (no pipeline, API, CLI or dataset code).
    "render": {"core", "atomic"},
}


@pytest.mark.parametrize("folder", sorted(ALLOWED_IMPORTS))
def test_stages_import_only_the_core(folder):
    """No stage imports another stage, the API, the CLI or datasets; the core imports none.
    A name imported under ``if TYPE_CHECKING:`` only types an annotation (the describer
    takes a picture's ``render.visibility.PictureView`` as it is given): not counted."""
    import ast

    def runtime_nodes(tree):
        pending = [tree]
        while pending:
            node = pending.pop()
            if (
                isinstance(node, ast.If)
                and isinstance(node.test, ast.Name)
                and node.test.id == "TYPE_CHECKING"
            ):
                pending.extend(node.orelse)
                continue
            yield node
            pending.extend(ast.iter_child_nodes(node))

    found = set()
    for path in (ROOT / folder).rglob("*.py"):
        for node in runtime_nodes(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                names = [node.module]
            elif isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            for name in names:
                parts = name.split(".")
                if parts[0] == "scenewright":
                    package = parts[1] if len(parts) > 1 else "scenewright"
                    if package != folder:
                        found.add((path.name, package))
    assert {
        (module, package) for module, package in found if package not in ALLOWED_IMPORTS[folder]
    } == set()
