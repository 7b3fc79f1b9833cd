"""Synthetic village-like scene graphs of a chosen size, for tests and benchmarks.

They use the relation mix of the shipped village rules (market stands beside roads
with goods on their tables and a sign beside, houses and lamps next to roads, groups of
trees) without depending on the rules parser, so layout scaling can be measured at any
size: ``village_graph(n_objects, seed)``.
"""

from __future__ import annotations

import math

import numpy as np

from scenewright.core.scene_graph import SceneGraph, SceneParams

from ..catalog import CatalogEntry

TABLE = CatalogEntry("table", "object", "table", size=(1.6, 0.8, 0.9))
SIGN = CatalogEntry("sign", "object", "sign", size=(0.6, 1.6, 0.2))
POT = CatalogEntry("pot", "object", "pot of stew", size=(0.4, 0.3, 0.4))
HOUSE = CatalogEntry("house", "object", "house", size=(6.0, 5.0, 5.0))
LAMP = CatalogEntry("street_lamp", "object", "street lamp", size=(0.3, 3.0, 0.3))
TREE = CatalogEntry("pine_tree", "object", "pine tree", size=(1.5, 6.0, 1.5))
STAND = CatalogEntry("market_stand", "group", "market stand")
TREES = CatalogEntry("group_of_trees", "group", "group of trees")
ROAD = CatalogEntry("road", "path", "road", width=3.0, max_length=30.0, segments=3)
CROSSING = CatalogEntry("intersection", "junction", "intersection", size=(4.0, 0.05, 4.0))


def village_graph(n_objects: int, seed: int = 0) -> SceneGraph:
    """About ``n_objects`` objects on an extent that grows with them (constant density)."""
    rng = np.random.default_rng(seed)
    roads_count = max(3, round(n_objects / 12))  # about a dozen objects along each road
    side = max(50.0, 9.0 * math.sqrt(n_objects))
    graph = SceneGraph(params=SceneParams(name="village", extent=(side, side)))
    roads = []
    crossing = graph.add_node(CROSSING, rule="Village")
    for index in range(roads_count):
        road = graph.add_node(ROAD, rule="Roads")
        if index < 3:
            graph.add_relation(road, crossing, "PathConnectedTo")
        roads.append(road)
    made = 0
    while made < n_objects:
        road = roads[int(rng.integers(len(roads)))]
        kind = rng.random()
        if kind < 0.4:
            stand = graph.add_node(STAND, rule="MarketStand")
            table = graph.add_node(TABLE, parent=stand, rule="MarketStand")
            sign = graph.add_node(SIGN, parent=stand, rule="MarketStand")
            graph.add_relation(sign, table, "NextToRight")
            made += 2
            for _ in range(int(rng.integers(1, 3))):
                pot = graph.add_node(POT, parent=stand, rule="Goods")
                graph.add_relation(pot, table, "OnTopOf")
                made += 1
            graph.add_relation(stand, road, "NextTo")
        elif kind < 0.6:
            house = graph.add_node(HOUSE, rule="House")
            graph.add_relation(house, road, "NextTo")
            made += 1
        elif kind < 0.8:
            lamp = graph.add_node(LAMP, rule="Lamp")
            graph.add_relation(lamp, road, "NextTo")
            made += 1
        else:
            trees = graph.add_node(TREES, rule="Trees")
            for _ in range(3):
                graph.add_node(TREE, parent=trees, rule="Trees")
            made += 3
    return graph
