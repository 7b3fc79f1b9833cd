"""`scenewright complete`: a request becomes a furnished, laid-out scene (completion.complete)."""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from scenewright.cli import main
from scenewright.completion import complete as completion_module
from scenewright.completion.complete import ROOM_FULL, complete, fewer_pieces, masked
from scenewright.completion.contents import choose_contents
from scenewright.completion.explanation import summary_of
from scenewright.completion.furnishing import build_graph
from scenewright.completion.request import parse_request
from scenewright.core.errors import InputError
from scenewright.core.geometry import make_rect, rect_overlap


def _swing_rect(room, door):
    points = room.swing_zone(door)
    xs, zs = [p[0] for p in points], [p[1] for p in points]
    return make_rect(
        (min(xs) + max(xs)) / 2, (min(zs) + max(zs)) / 2, max(xs) - min(xs), max(zs) - min(zs), 0.0
    )


def test_a_5x4_bedroom_with_a_bed_and_a_bookshelf_is_completed_and_laid_out(model, catalog):
    request = parse_request("5x4", ["S:0.8:0.9"], ["N:2.5:1.4"], ["bed,bookshelf"], catalog)
    scene = complete(request, 1, model=model, catalog=catalog)
    types = {o.type for o in scene.placed_objects()}
    assert {"bed", "bookshelf"} <= types
    assert len(types) >= 6  # the request plus what the bedroom plans hold with them
    assert {"nightstand", "wardrobe"} <= types
    assert scene.completion["types"] == ["bedroom"]
    assert scene.layout.ok, scene.layout.problems
    swing = _swing_rect(scene.room, scene.room.doors[0])
    for obj in scene.placed_objects():
        if obj.position[1] > 0.01:
            continue  # stands on another piece
        footprint = make_rect(obj.position[0], obj.position[2], obj.size[0], obj.size[2], obj.yaw)
        assert rect_overlap(footprint, swing) < 1e-3, obj.id
    by_label = {(r.source.split("_")[0], r.label) for r in scene.relations}
    assert ("nightstand", "BesideLeft") in by_label and ("desk", "UnderWindow") in by_label


def test_three_treadmills_in_a_living_room_sized_room_make_a_laid_out_gym(model, catalog):
    """The paper's adaptivity: what is asked for decides the room's type."""
    request = parse_request("5x4", ["S:0.8:0.9"], ["N:2.5:1.4"], ["treadmill=3"], catalog)
    scene = complete(request, 0, model=model, catalog=catalog)
    assert scene.completion["types"] == ["gym"]
    assert scene.layout.ok, scene.layout.problems
    types = [o.type for o in scene.placed_objects()]
    assert types.count("treadmill") == 3 and len(set(types)) >= 2
    labels = {(r.source, r.label) for r in scene.relations}
    assert (
        "treadmill_1",
        "AgainstWall",
    ) in labels  # its console to a wall, the others in a row beside it


def test_a_small_gym_keeps_its_machines_and_the_bench_stands_before_the_rack(model, catalog):
    request = parse_request(
        "3.6x3.4",
        ["S:0.5:0.8"],
        ["W:1.7:1.2"],
        ["weight_bench,dumbbell_rack,exercise_bike"],
        catalog,
    )
    scene = complete(request, 0, model=model, catalog=catalog)
    assert scene.completion["types"] == ["gym"]
    assert scene.layout.ok, scene.layout.problems
    assert {"weight_bench", "dumbbell_rack", "exercise_bike"} <= {
        o.type for o in scene.placed_objects()
    }
    assert ("weight_bench_1", "NextToFront", "dumbbell_rack_1") in {
        (r.source, r.label, r.target) for r in scene.relations
    }


def test_a_larger_room_gets_more_categories(model, catalog):
    def added(size):
        request = parse_request(size, ["S:0.6:0.8"], ["N:1.5:1.0"], ["bed,bookshelf"], catalog)
        return sum(choose_contents(model, request).counts.values()) - 2

    assert added("3x3") < added("4x3.5") < added("5x4")


def test_the_default_steps_are_the_baselines_and_the_papers_are_an_option(model, catalog):
    request = parse_request("5x4", ["S:0.8:0.9"], ["N:2.5:1.4"], ["bed,bookshelf"], catalog)
    default, paper = (
        choose_contents(model, request),
        choose_contents(model, replace(request, **PAPER)),
    )
    bedrooms = [plan.id for plan in model.plans if plan.type == "bedroom"]
    # The type's mean mask: every bedroom plan weighs the same.
    assert sorted(default.mask.weights) == sorted(bedrooms)
    assert len(set(default.mask.weights.values())) == 1
    assert len(paper.mask.weights) < len(bedrooms)  # Equation 4: the nearest plans' cluster
    # Co-occurrence adds fewer categories here than Algorithm 1, all of them among its own.
    added = {name for name in default.counts if name not in request.requested}
    assert added and added < set(paper.counts)
    assert default.explorations["bedroom"].cost == 0.0 and paper.explorations["bedroom"].steps


def test_the_record_lists_every_category_with_its_scores_and_the_mask_weights(model, catalog):
    request = parse_request("4x3.6", ["S:3.2:0.85"], ["E:1.8:1.3"], ["desk"], catalog)
    contents = choose_contents(model, request)
    scene = complete(request, 2, model=model, catalog=catalog)
    record = scene.completion
    assert record["types"] == ["study"]
    chosen = record["selection"]["study"]["categories"]
    assert [c["category"] for c in chosen][0] == "desk" and chosen[0]["requested"]
    assert all(0.0 < c["p"] <= 1.0 for c in chosen)
    assert sum(record["mask"]["references"].values()) == pytest.approx(1.0)
    assert record["counts"] == {
        n: c for n, c in contents.counts.items() if n not in record["left_out"]
    }


@pytest.mark.parametrize(
    "argv, fragment",
    [
        (["--room", "5by4", "--with", "bed"], "give W x D"),
        (["--room", "5x4", "--door", "Q:1:0.9", "--with", "bed"], "no wall 'Q'"),
        (["--room", "5x4", "--door", "S:4.8:0.9", "--with", "bed"], "runs past the end"),
        (["--room", "5x4", "--window", "N:2:x", "--with", "bed"], "'x' is not a number"),
        (["--room", "5x4", "--with", "bedd"], "did you mean 'bed'"),
        (["--room", "5x4", "--with", "chair=0"], "whole number from 1"),
        (["--room", "5x4", "--with", "tredmill"], "did you mean 'treadmill'"),
        (["--room", "5x4", "--with", "bathtub"], "no plan of any type has a 'bathtub'"),
        (["--room", "5x4", "--with", "chair=20"], "at most"),
        (["--room", "5x4", "--with", "bed", "--categories", "greedy"], "invalid choice: 'greedy'"),
        (["--room", "5x4", "--with", "bed", "--mask", "median"], "invalid choice: 'median'"),
    ],
)
def test_bad_requests_exit_2_on_one_line_and_write_nothing(capsys, tmp_path, argv, fragment):
    target = tmp_path / "out"
    assert main(["complete", *argv, "--no-render", "-o", str(target)]) == 2
    err = capsys.readouterr().err
    assert fragment in err and err.count("\n") == 1 and "Traceback" not in err
    assert not target.exists() or not any(target.iterdir())


@pytest.mark.slow
def test_the_same_request_and_seed_give_the_same_scene_json_and_explain_draws_the_mask(tmp_path):
    argv = [
        "complete",
        "--room",
        "3.2x3",
        "--door",
        "S:0.6:0.8",
        "--window",
        "N:1.6:1.0",
        "--with",
        "desk",
        "--seed",
        "5",
        "--no-render",
        "-q",
    ]
    assert main([*argv, "--explain", "-o", str(tmp_path / "a")]) == 0
    assert main([*argv, "-o", str(tmp_path / "b")]) == 0
    first, second = (
        (tmp_path / "a" / "scene.json").read_bytes(),
        (tmp_path / "b" / "scene.json").read_bytes(),
    )
    assert first == second and b'"completion"' in first
    assert (tmp_path / "a" / "mask.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not (tmp_path / "b" / "mask.png").exists()


@settings(max_examples=40, deadline=None)
@given(
    width=st.floats(2.0, 9.0),
    depth=st.floats(2.0, 9.0),
    wall=st.sampled_from("NESW"),
    where=st.floats(0.0, 1.0),
    sill=st.floats(0.3, 1.0),
)
def test_any_fitting_door_and_window_land_on_the_wall_named(width, depth, wall, where, sill):
    catalog = {"bed": None}
    length = width if wall in "NS" else depth
    offset = 0.45 + where * (length - 0.9)
    request = parse_request(f"{width}x{depth}", [f"{wall}:{offset}:0.9"], [], ["bed"], catalog)
    door = request.room.doors[0]
    side = {"N": "north", "E": "east", "S": "south", "W": "west"}[wall]
    assert request.room.part(door.wall).side == side
    assert door.offset == pytest.approx(offset) and door.width == pytest.approx(0.9)
    assert request.room.area == pytest.approx(width * depth)
    other = "N" if wall != "N" else "S"
    windowed = parse_request(
        f"{width}x{depth}", [], [f"{other}:1.0:0.8:{sill}"], ["bed=2"], catalog
    )
    assert windowed.room.windows[0].sill == pytest.approx(sill) and windowed.requested == {"bed": 2}


def test_an_l_shaped_study_without_a_window_keeps_its_laptop_on_the_desk(model, catalog):
    request = parse_request("0,0 6,0 6,3 3,3 3,5 0,5", ["1:1:0.9"], [], ["desk"], catalog)
    scene = complete(request, 0, model=model, catalog=catalog)
    assert "laptop" in scene.completion["counts"] and "laptop" not in scene.completion["left_out"]
    assert any(r.source.startswith("laptop") and r.target == "desk_1" for r in scene.relations)
    assert ("desk_1", "AgainstWall") in {(r.source, r.label) for r in scene.relations}


def test_a_dining_table_starts_free_with_its_chairs_spread_round_it(model, catalog):
    from scenewright.completion.furnishing import build_graph
    from scenewright.completion.starting_poses import starting_poses
    from scenewright.core.geometry import rect_distance

    request = parse_request("4.5x4", ["W:1:0.9"], ["N:2.2:1.4"], ["dining_table"], catalog)
    contents = choose_contents(model, request)
    graph, _, placements = build_graph(model, contents, request.room, catalog)
    poses = starting_poses(graph, request.room, contents.mask, placements)
    table = graph.node("dining_table_1")
    pose = poses[table.id]
    table_rect = make_rect(pose.x, pose.z, table.size[0], table.size[2], pose.yaw)
    chairs = [n for n in graph.nodes("object") if n.type == "chair"]
    assert len(chairs) == 6
    rects = [
        make_rect(poses[c.id].x, poses[c.id].z, c.size[0], c.size[2], poses[c.id].yaw)
        for c in chairs
    ]
    for chair, rect in zip(chairs, rects, strict=False):
        assert rect_distance(rect, table_rect) < 0.1, chair.id  # at the table
        assert request.room.footprint_excess([(rect.cx, rect.cz)]) == 0.0
    assert all(rect_overlap(a, b) < 1e-9 for i, a in enumerate(rects) for b in rects[i + 1 :])


def test_polygon_rooms_are_read_as_corners(catalog):
    request = parse_request("0,0 6,0 6,3 3,3 3,5 0,5", ["2:1:0.9"], [], ["desk"], catalog)
    assert request.room.area == pytest.approx(6 * 3 + 3 * 2) and len(request.room.walls) == 6
    with pytest.raises(InputError, match="at least 3 corners"):
        parse_request("0,0 1,1", [], [], ["desk"], catalog)


# -- a room too full to lay out gives up its weakest added pieces (fewer_pieces) --

#: The paper's steps (Algorithm 1, Equation 4), which fill a room fuller than the
#: defaults do: the rooms below are crowded with them.
PAPER = {"categories": "algorithm1", "mask": "equation4"}

#: A 3.2 x 3.2 m room asked for a desk and a filing cabinet: the study it becomes holds
#: two bookshelves, and with both no layout seed 0 tries is ok.
CROWDED = ("3.2x3.2", "S:1.2:0.85", "N:1.2:1.2", "desk,filing_cabinet")


def _contents(model, catalog, room, door, window, wanted):
    request = parse_request(room, [door], [window], [wanted], catalog)
    contents = choose_contents(model, request)
    graph, _, _ = build_graph(model, contents, request.room, catalog)
    return request, contents, graph


def test_the_weakest_added_piece_the_problems_name_goes_one_at_a_time(model, catalog):
    request, contents, graph = _contents(model, catalog, "5x4", "S:0.8:0.9", "N:2.5:1.4", "bed")
    assert contents.counts["nightstand"] == 2
    problems = [
        "nightstand_2 cannot be reached from the door (no 0.6 m wide way)",
        "bed_1 overlaps wardrobe_1 by 3 %",
    ]
    fewer = fewer_pieces(model, contents, request, graph, problems)
    # The bed is requested; of the named added pieces the wardrobe is tied to it less
    # than the night tables, and it is the only one of its kind: it goes whole.
    changed = {
        name: (contents.counts[name], fewer.counts.get(name, 0))
        for name in contents.counts
        if fewer.counts.get(name, 0) != contents.counts[name]
    }
    assert changed == {"wardrobe": (1, 0)}
    again = fewer_pieces(model, fewer, request, graph, problems[:1])
    assert again.counts["nightstand"] == 1 and again.counts["bed"] == 1


def test_a_desk_given_up_takes_its_added_chair_along_and_a_requested_one_never_goes(model, catalog):
    request, contents, graph = _contents(
        model, catalog, "4x3.6", "S:3.2:0.85", "E:1.8:1.3", "bookshelf"
    )
    assert contents.counts.get("desk") == 1 and contents.counts.get("office_chair")
    fewer = fewer_pieces(model, contents, request, graph, ["desk_1 overlaps bookshelf_1 by 5 %"])
    assert "desk" not in fewer.counts and "office_chair" not in fewer.counts
    assert fewer.counts["bookshelf"] == contents.counts["bookshelf"]
    only_requested = replace(contents, counts={"bookshelf": contents.counts["bookshelf"]})
    assert (
        fewer_pieces(model, only_requested, request, graph, ["bookshelf_1 overlaps x by 5 %"])
        is None
    )


def test_a_crowded_room_is_ok_with_a_piece_fewer_and_says_which(model, catalog, monkeypatch):
    room, door, window, wanted = CROWDED
    request = replace(parse_request(room, [door], [window], [wanted], catalog), **PAPER)
    scene = complete(request, 0, model=model, catalog=catalog)
    assert scene.layout.ok, scene.layout.problems
    record = scene.completion
    assert record["given_up"] == {"bookshelf": 1}
    assert "bookshelf" not in record["left_out"] and record["counts"]["bookshelf"] == 1
    assert {"desk", "filing_cabinet"} <= set(record["counts"])
    assert {o.type for o in scene.placed_objects()} >= {"desk", "filing_cabinet", "bookshelf"}
    assert "1 bookshelf fewer" in summary_of(record)
    # Without giving anything up, the same seed's layout is not ok.
    monkeypatch.setattr(completion_module, "FIT_ATTEMPTS", 0)
    crowded = complete(request, 0, model=model, catalog=catalog)
    assert not crowded.layout.ok
    assert crowded.completion["given_up"] == {} and crowded.completion["counts"]["bookshelf"] == 2


def test_a_category_given_up_whole_is_left_out_with_why(model, catalog):
    request = replace(
        parse_request("3.2x3.4", ["E:2.2:0.9"], ["N:2:1.2"], ["bed"], catalog), **PAPER
    )  # too small for a wardrobe too
    scene = complete(request, 0, model=model, catalog=catalog)
    assert scene.layout.ok, scene.layout.problems
    record = scene.completion
    whole = {name for name in record["given_up"] if name not in record["counts"]}
    assert whole and all(record["left_out"][name] == ROOM_FULL for name in whole)
    assert "bed" in record["counts"]


@pytest.fixture(scope="module")
def furnished(tmp_path_factory):
    """A completed 4.5 x 4 m bedroom, as scene.json."""
    folder = tmp_path_factory.mktemp("furnished")
    argv = [
        "complete",
        "--room",
        "4.5x4",
        "--door",
        "S:0.6:0.9",
        "--window",
        "N:2:1.2",
        "--with",
        "bed",
        "--seed",
        "3",
        "--no-render",
        "-q",
        "-o",
        str(folder / "room"),
    ]
    assert main(argv) == 0
    return folder / "room" / "scene.json"


def test_adding_to_a_furnished_room_keeps_every_piece_where_it_stood(furnished, tmp_path, capsys):
    import json

    before = json.loads(furnished.read_text())
    assert (
        main(
            [
                "complete",
                str(furnished),
                "--add",
                "dresser",  # against a wall: every corner of this room is taken
                "--seed",
                "1",
                "--no-render",
                "-o",
                str(tmp_path / "more"),
            ]
        )
        == 0
    )
    assert "kept" in capsys.readouterr().out
    after = json.loads((tmp_path / "more" / "scene.json").read_text())
    assert after["layout"]["ok"]
    placed = {o["id"]: o for o in after["objects"] if o["kind"] == "object"}
    for obj in (o for o in before["objects"] if o["kind"] == "object"):
        assert (
            placed[obj["id"]]["position"] == obj["position"]
            and placed[obj["id"]]["yaw"] == obj["yaw"]
        )
    kinds = [o["type"] for o in placed.values()]
    assert kinds.count("dresser") == [o["type"] for o in before["objects"]].count("dresser") + 1


@pytest.mark.parametrize(
    "extra, fragment",
    [
        (["--add", "piano", "--room", "5x4"], "--room describes an empty room"),
        ([], "needs --add"),
        (["--add", "tredmill"], "not an indoor catalog entry"),
        (["--add", "bathtub"], "no plan of any type has a 'bathtub'"),
    ],
)
def test_bad_additions_exit_2_on_one_line(furnished, tmp_path, capsys, extra, fragment):
    assert main(["complete", str(furnished), *extra, "--no-render", "-o", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert fragment in err and err.count("\n") == 1


def test_add_needs_a_scene_and_a_scene_needs_a_room(tmp_path, capsys):
    assert (
        main(
            [
                "complete",
                "--room",
                "5x4",
                "--with",
                "bed",
                "--add",
                "piano",
                "-o",
                str(tmp_path / "x"),
            ]
        )
        == 2
    )
    assert "--add adds to a scene.json" in capsys.readouterr().err
    assert (
        main(["-q", "generate", "village", "--seed", "1", "--no-render", "-o", str(tmp_path / "v")])
        == 0
    )
    assert (
        main(
            [
                "complete",
                str(tmp_path / "v" / "scene.json"),
                "--add",
                "piano",
                "-o",
                str(tmp_path / "y"),
            ]
        )
        == 2
    )
    assert "only an indoor scene can be completed" in capsys.readouterr().err


@pytest.mark.slow
def test_a_tries_restart_waits_its_own_patience(model, catalog):
    # A crowded room: both chains fail. The restart alone gives up sooner; the first
    # chain is the same either way.
    from dataclasses import replace as with_params

    from scenewright.completion.layout_mask import floor_mask
    from scenewright.generator.layout import layout_scene

    request = parse_request("3.7x5.2", ["N:2.61:0.91"], ["W:2.74:1.53"], ["bed"], set(catalog))
    contents = choose_contents(model, replace(request, **PAPER))
    graph, _, start = completion_module._graph_and_start(model, contents, request.room, catalog)
    mask = floor_mask(contents.mask, request.room, masked(model, graph))
    params = completion_module.FIT_PARAMS
    assert params.restarts == 1 and params.restart_patience < params.patience

    def run(**changes):
        return layout_scene(graph, 0, start=start, mask=mask, params=with_params(params, **changes))

    first = run(restarts=0)
    patient, hasty = run(restart_patience=None), run()
    assert not first.ok and not patient.ok and not hasty.ok  # the room is crowded: both chains ran
    assert first.steps < hasty.steps < patient.steps
