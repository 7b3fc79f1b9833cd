"""The shipped town rule set: its object budget holds for every seed, its notes say it
truly, and its scenes are the town its comments promise (road networks, homes with
gardens beside roads, a market, parks, street lamps)."""

from collections import Counter
from functools import cache

import pytest
from test_shipped_rules import noted_bounds, object_bounds

from scenewright.generator.expand import expand
from scenewright.generator.rules import check_rules, load_rules, shipped_rule_sets

SEEDS = range(100)


@cache
def towns():
    rules = load_rules("town")
    return tuple(expand(rules, seed) for seed in SEEDS)


@pytest.fixture(scope="module", autouse=True)
def _forget_towns():
    """The towns are shared by this module's tests and dropped once they are done (as in
    test_shipped_rules)."""
    yield
    towns.cache_clear()


def test_town_is_shipped_and_validates():
    assert "town" in shipped_rule_sets()
    assert [str(d) for d in check_rules("town") if d.is_error] == []


def test_object_budget_holds_and_the_notes_say_it():
    rules = load_rules("town")
    bounds = object_bounds(rules)
    assert bounds[rules.start] == (243, 419)
    counts = [len(graph.nodes("object")) for graph in towns()]
    assert 243 <= min(counts) and max(counts) <= 419 and len(set(counts)) > 10
    assert noted_bounds(rules) == bounds


@pytest.mark.slow
def test_towns_have_road_networks_homes_a_market_parks_and_lamps():
    for graph in towns():
        junctions = graph.nodes("junction")
        assert 2 <= len(junctions) <= 3
        for junction in junctions:
            roads = [e.source for e in graph.edges("PathConnectedTo") if e.target == junction.id]
            assert 3 <= len(roads) <= 4
        paths = {node.id for node in graph.nodes("path")}
        groups = Counter(node.type for node in graph.nodes("group"))
        assert 52 <= groups["home"] <= 60 and groups["market"] == 1 and groups["park"] == 2
        beside_roads = {e.source for e in graph.edges("NextTo") if e.target in paths}
        for group in graph.nodes("group"):
            if group.type in ("home", "market", "park"):
                assert group.id in beside_roads, group.id
            if group.type == "home":
                assert [m.type for m in graph.children(group.id)].count("house") == 1
        lamps = [node for node in graph.nodes("object") if node.type == "street_lamp"]
        assert 10 <= len(lamps) <= 18
