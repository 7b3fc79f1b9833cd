"""Algorithm 1 (object exploration): its cost on a worked example, isolation, adaptivity."""

from __future__ import annotations

import json

import pytest

from scenewright.completion.features import room_parts
from scenewright.completion.plan_model import (
    CategoryPair,
    CategoryStats,
    PlanEntry,
    PlanModel,
    RoomTypeModel,
    TypeCategory,
)
from scenewright.completion.selection import (
    choose_categories,
    explore_categories,
    nearest_plans,
    usual_categories,
)
from scenewright.core.errors import InputError
from scenewright.core.room import Room


def _plan_entry(name: str, feature: list[float], counts: dict[str, int]) -> PlanEntry:
    """A plan of type t with the fields Algorithm 1 reads, the others empty."""
    return PlanEntry(name, "t", 0.0, counts, {}, {}, feature, [])


def _model(weights: dict[tuple[str, str], float]) -> PlanModel:
    """Four categories a (2 m^2 of floor), b (1), c (0.5), d (0.25); plans p1 and p2 are
    like the room (occupancy 0.3 and 0.2), p3 is not."""
    floor = {"a": 2.0, "b": 1.0, "c": 0.5, "d": 0.25}
    pairs = [CategoryPair(list(pair), w, None, w) for pair, w in weights.items()]
    return PlanModel(
        categories={name: CategoryStats("stay", [1.0, 1.0], area) for name, area in floor.items()},
        types={"t": RoomTypeModel(3, 10.0, {}, pairs)},
        plans=[
            _plan_entry("p1", [0.5, 0.3, 0.8, 0.5], {"a": 1, "b": 1, "c": 1, "d": 1}),
            _plan_entry("p2", [0.5, 0.2, 0.8, 0.5], {"a": 1, "b": 1, "c": 2}),
            _plan_entry("p3", [0.0, 0.9, 0.1, 0.1], {"d": 4}),
        ],
    )


def test_worked_example():
    """By hand, K = 2, omega = 0.02, room 10 m^2, requested a. The references are p1, p2
    (occupancy 0.3, 0.2); c counts twice (1 and 2 in them: 1.5, rounded to even 2).
    {a, b, c, d}: R = (2 + 1 + 2 * 0.5 + 0.25) / 10 = 0.425, mean |R - r| = 0.175,
    weights 1.5: C = 0.175 - 0.03 = 0.145. E: b 0.5, c 0.233, d 0.1: remove d.
    {a, b, c}: R = 0.4, 0.15 - 0.02 * 1.4 = 0.122. E: b 0.5, c 0.3: remove c.
    {a, b}: R = 0.3, 0.05 - 0.016 = 0.034. Remove b. {a}: R = 0.2, 0.05 - 0 = 0.05.
    The best is {a, b}."""
    model = _model({("a", "b"): 0.8, ("a", "c"): 0.4, ("b", "c"): 0.2, ("c", "d"): 0.1})
    result = explore_categories(model, "t", {"a": 1}, 10.0, (0.5, 0.8, 0.5), k=2)
    assert result.references == ("p1", "p2")
    assert [step["removed"] for step in result.steps] == ["d", "c", "b"]
    assert [step["cost"] for step in result.steps] == pytest.approx([0.122, 0.034, 0.05])
    assert result.categories == ("a", "b") and result.counts == {"a": 1, "b": 1}
    assert result.cost == pytest.approx(0.034)


def test_a_category_left_without_neighbours_goes_with_the_one_removed():
    model = _model({("a", "b"): 0.1, ("b", "c"): 0.9})
    result = explore_categories(model, "t", {"a": 1}, 10.0, (0.5, 0.8, 0.5), k=2)
    assert result.steps[0] == {"removed": "b", "isolated": ["c"], "cost": pytest.approx(0.05)}
    assert len(result.steps) == 1


def test_requested_categories_stay_and_count_as_asked():
    model = _model({("a", "b"): 0.8, ("c", "d"): 0.1})
    result = explore_categories(model, "t", {"d": 3, "a": 1}, 10.0, (0.5, 0.8, 0.5), k=2)
    assert result.categories[:2] == ("a", "d") and result.counts["d"] == 3
    with pytest.raises(InputError, match="no plan has a 'piano'"):
        explore_categories(model, "t", {"piano": 1}, 10.0, (0.5, 0.8, 0.5))
    with pytest.raises(InputError, match="no type 'gym'"):
        explore_categories(model, "gym", {"a": 1}, 10.0, (0.5, 0.8, 0.5))


def test_nearest_plans_use_the_room_only_parts_of_the_feature():
    model = _model({})
    assert [p.id for p in nearest_plans(model, "t", (0.0, 0.1, 0.1), k=1)] == ["p3"]
    assert [p.id for p in nearest_plans(model, "t", (0.5, 0.8, 0.5))] == ["p1", "p2", "p3"]


@pytest.fixture(scope="module")
def shipped_model():
    from scenewright.completion import shipped_plans_dir
    from scenewright.completion.floor_plan import load_plans
    from scenewright.completion.model_builder import build_model, model_json

    # As a model file gives it: read back from its JSON.
    return PlanModel.from_dict(json.loads(model_json(build_model(load_plans(shipped_plans_dir())))))


@pytest.mark.parametrize(
    ("room_type", "requested"),
    [
        ("bedroom", {"bed": 1, "bookshelf": 1}),
        ("living_room", {"sofa": 1}),
        ("study", {"desk": 1}),
        ("dining_room", {"dining_table": 1}),
    ],
)
def test_more_categories_are_added_to_larger_rooms(shipped_model, room_type, requested):
    added = []
    for width, depth in ((3.0, 3.0), (4.0, 3.5), (5.0, 4.0), (6.0, 5.0)):
        room = Room.rectangle(width, depth).with_opening("door", "wall_3", width - 0.8, 0.9)
        room = room.with_opening("window", "wall_1", width / 2, 1.4, 1.2, 0.9)
        parts = room_parts(room, shipped_model.types[room_type].mean_area)
        result = explore_categories(shipped_model, room_type, requested, room.area, parts)
        assert set(requested) <= set(result.categories)
        added.append(len(result.categories) - len(requested))
    assert added == sorted(added) and added[-1] > added[0], added


def test_three_treadmills_make_a_gym_and_gyms_join_no_home_room(shipped_model):
    from scenewright.completion.selection import choose_types

    assert choose_types(shipped_model, {"treadmill": 3}, 20.0).types == ("gym",)
    for asked in ("bed", "sofa", "desk", "dining_table"):
        for area in (25.0, 35.0, 45.0, 60.0):
            assert "gym" not in choose_types(shipped_model, {asked: 1}, area).types, (asked, area)


# -- the co-occurrence step, complete's default (usual_categories) --


def test_cooccurrence_adds_the_nearest_plans_usual_number_most_seen_with_the_request():
    """By hand, K = 2: the references are p1 and p2, which hold 3 and 2 categories beyond
    a (2.5, rounded to even: 2). Seen with a: b 0.9, c 0.5, d 0.1 (the co-occurrence, not
    W: d's W is the largest), so b and c are added; c counts twice (1 and 2 in p1, p2)."""
    model = _model({("a", "b"): 0.9, ("a", "c"): 0.5, ("a", "d"): 0.1})
    model.types["t"].categories.update(
        {
            name: TypeCategory(p, 4)
            for name, p in {"a": 2 / 3, "b": 2 / 3, "c": 2 / 3, "d": 2 / 3}.items()
        }
    )
    model.types["t"].pairs[2] = CategoryPair(["a", "d"], 0.1, "touch", 5.0)  # W does not decide
    result = usual_categories(model, "t", {"a": 1}, 10.0, (0.5, 0.8, 0.5), k=2)
    assert result.categories == ("a", "b", "c")
    assert result.counts == {"a": 1, "b": 1, "c": 2}
    assert result.references == ("p1", "p2")
    # A room like p3 (whose plan holds one category) gets the number p3 and the nearer
    # of the others hold: K = 1 there is p3 alone, one category beyond the request.
    assert usual_categories(model, "t", {"a": 1}, 10.0, (0.0, 0.1, 0.1), k=1).categories == (
        "a",
        "b",
    )
    with pytest.raises(InputError, match="no plan has a 'piano'"):
        usual_categories(model, "t", {"piano": 1}, 10.0, (0.5, 0.8, 0.5))


def test_the_category_step_is_chosen_by_name():
    assert choose_categories("co-occurrence") is usual_categories
    assert choose_categories("algorithm1") is explore_categories
    with pytest.raises(InputError, match="choose one of co-occurrence, algorithm1"):
        choose_categories("greedy")
