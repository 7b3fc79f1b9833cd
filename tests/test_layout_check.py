"""The chain's check maps the verdicts (graph edges, structural ones included) back to the
relation terms it steers its moves to."""

from scenewright.core.scene_graph import SceneGraph, SceneParams
from scenewright.core.seeds import stage_stream
from scenewright.generator.catalog import CatalogEntry
from scenewright.generator.layout import LayoutParams
from scenewright.generator.layout.problem import compile_problem
from scenewright.generator.layout.report import assess, unsatisfied_terms
from scenewright.generator.layout.sampler import start_chain

TABLE = CatalogEntry("table", "object", "table", size=(1.6, 0.8, 0.9))
POT = CatalogEntry("pot", "object", "pot", size=(0.4, 0.3, 0.4))
WELL = CatalogEntry("well", "object", "well", size=(1.4, 0.8, 1.4))
BUCKET = CatalogEntry("bucket", "object", "bucket", size=(0.3, 0.3, 0.3))
ROAD = CatalogEntry("road", "path", "road", width=3.0, max_length=20.0, segments=2)
CROSSING = CatalogEntry("crossing", "junction", "crossing", size=(4.0, 0.05, 4.0))


def crossing_with_wares() -> SceneGraph:
    """Two roads from a crossing (structural edges first in graph order), then a pot in
    the middle of a table and a bucket on a well's rim, both beside a road."""
    graph = SceneGraph(params=SceneParams(extent=(30.0, 30.0)))
    crossing = graph.add_node(CROSSING)
    roads = [graph.add_node(ROAD) for _ in range(2)]
    for road in roads:
        graph.add_relation(road, crossing, "PathConnectedTo")
    table, pot = graph.add_node(TABLE), graph.add_node(POT)
    well, bucket = graph.add_node(WELL), graph.add_node(BUCKET)
    graph.add_relation(pot, table, "OnTopOfMiddle")
    graph.add_relation(bucket, well, "IsPartOfEdge")
    graph.add_relation(table, roads[0], "NextTo")
    graph.add_relation(well, roads[1], "NextTo")
    return graph


def placed(seed: int):
    problem = compile_problem(crossing_with_wares())
    energy, mover = start_chain(problem, LayoutParams(), stage_stream(seed, "layout", 0))
    return problem, energy, mover


def test_unsatisfied_terms_name_the_terms_not_the_graph_edges():
    problem, energy, _ = placed(3)
    pot = problem.ids.index("pot_1")
    table = problem.ids.index("table_1")
    energy.propose({pot: (energy.state.x[table] + 0.5, energy.state.z[table], 0.0)}, {})
    energy.accept()
    relations, _ = assess(energy)
    assert sum(index is None for *_, index in problem.edges) == 2  # the roads' starts
    wrong = [problem.relations[t] for t in unsatisfied_terms(energy, relations)]
    assert ("pot_1", "OnTopOfMiddle") in [(term.source, term.label) for term in wrong]
    held = [r for r in relations if r.satisfied]
    assert all(
        (term.source, term.label) not in [(r.source, r.label) for r in held] for term in wrong
    )


def test_the_chain_focuses_on_the_relations_that_do_not_hold(monkeypatch):
    from scenewright.generator.layout import sampler

    problem, energy, mover = placed(2)
    pot, table = problem.ids.index("pot_1"), problem.ids.index("table_1")
    energy.propose({pot: (energy.state.x[table] + 3.0, energy.state.z[table], 0.0)}, {})
    energy.accept()
    focused = []
    monkeypatch.setattr(mover, "focus", lambda terms, boxes: focused.append(list(terms)))
    sampler.anneal(
        energy, mover, LayoutParams(min_steps=0, check_every=1), stage_stream(2, "layout", 9), 1
    )
    assert [problem.relations[t].source for t in focused[0]] == ["pot_1"]
