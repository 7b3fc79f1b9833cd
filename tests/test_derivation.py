"""The derivation trace: every random draw of expansion, in order, with the nodes it made;
replaying it; its tally per rule parameter; scene.json and the expand command carry it."""

import copy
import json

import numpy as np
import pytest

from scenewright.api import build_scene
from scenewright.cli import main
from scenewright.core.scene import Scene
from scenewright.core.scene_graph import SceneGraph
from scenewright.core.schema_check import SceneSchemaError, validate_scene_dict
from scenewright.generator import expand, load_rules, shipped_rule_sets
from scenewright.generator.derivation import ChoiceCounts, Site, choice_counts

STALLS = """\
scene stalls { extent 20 x 20 start Market }
include "parts/goods.rules"
object table { noun "table" size 1.6 x 0.8 x 0.9 shape table }
object pot {
    noun "pot"
    style big 1 { noun "big pot" }
    style small 3 { noun "small pot" }
}
object sack { noun "sack" size 0.4 x 0.6 x 0.3 }
object sign { noun "sign" size 0.6 x 1.6 x 0.15 }
group stall { noun "stall" }

Market -> {
    2 table
    1..3 Stall
    0.5? sign NextTo some table
}
Stall -> 2: { stall { table as t; Goods(t) } }
       | 1: { }
"""

GOODS = """\
Goods(on) -> 3: { pot OnTopOf on }
           | 1: { 0..2 sack NextTo on }
"""


@pytest.fixture
def stalls(tmp_path):
    """The stalls rule set: its parameters in two files, the second in a subfolder."""
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "goods.rules").write_text(GOODS)
    path = tmp_path / "stalls.rules"
    path.write_text(STALLS)
    return load_rules(path)


#: The trace of the stalls with seed 3: two stalls (the range drew 2), the first selling
#: one sack (Goods' second alternative, its range drew 1), the second a small pot; the
#: sign was put up, next to the fourth table. ``Market`` (one alternative) and ``2 table``
#: (no range) draw nothing and leave no record.
SEED_3 = [
    {
        "kind": "count",
        "rule": "Market",
        "at": [15, 5],
        "file": "stalls.rules",
        "low": 1,
        "high": 3,
        "value": 2,
        "nodes": ["stall_1", "table_3", "sack_1", "stall_2", "table_4", "pot_1"],
    },
    {
        "kind": "alternative",
        "rule": "Stall",
        "at": [18, 1],
        "file": "stalls.rules",
        "options": 2,
        "value": 0,
        "nodes": ["stall_1", "table_3", "sack_1"],
    },
    {
        "kind": "alternative",
        "rule": "Goods",
        "at": [1, 1],
        "file": "goods.rules",
        "options": 2,
        "value": 1,
        "nodes": ["sack_1"],
    },
    {
        "kind": "count",
        "rule": "Goods",
        "at": [2, 19],
        "file": "goods.rules",
        "low": 0,
        "high": 2,
        "value": 1,
        "nodes": ["sack_1"],
    },
    {
        "kind": "alternative",
        "rule": "Stall",
        "at": [18, 1],
        "file": "stalls.rules",
        "options": 2,
        "value": 0,
        "nodes": ["stall_2", "table_4", "pot_1"],
    },
    {
        "kind": "alternative",
        "rule": "Goods",
        "at": [1, 1],
        "file": "goods.rules",
        "options": 2,
        "value": 0,
        "nodes": ["pot_1"],
    },
    {
        "kind": "style",
        "rule": "Goods",
        "at": [4, 1],
        "file": "stalls.rules",
        "options": 2,
        "type": "pot",
        "value": 1,
        "nodes": ["pot_1"],
    },
    {
        "kind": "optional",
        "rule": "Market",
        "at": [16, 5],
        "file": "stalls.rules",
        "probability": 0.5,
        "value": True,
        "nodes": ["sign_1"],
    },
    {
        "kind": "some",
        "rule": "Market",
        "at": [16, 22],
        "file": "stalls.rules",
        "options": 4,
        "type": "table",
        "value": 3,
        "nodes": ["table_4"],
    },
]


class Replay(np.random.Generator):
    """A random stream that answers each draw with the next record of a derivation,
    checking that the draw is the one the record says."""

    def __init__(self, derivation: list[dict]):
        super().__init__(np.random.PCG64(0))
        self.records = list(derivation)

    def next(self, *kinds: str) -> dict:
        record = self.records.pop(0)
        assert record["kind"] in kinds
        return record

    def choice(self, options, p=None):
        record = self.next("alternative", "style", "count")
        if record["kind"] == "count":  # a weighted count (``2..4 {1 1 2}``) draws its index
            assert options == record["high"] - record["low"] + 1 and len(p) == options
            return record["value"] - record["low"]
        assert record["options"] == options and len(p) == options
        return record["value"]

    def integers(self, low, high=None):
        record = self.next("count", "some")
        if record["kind"] == "count":
            assert (low, high) == (record["low"], record["high"] + 1)
        else:
            assert (low, high) == (record["options"], None)
        return record["value"]

    def random(self):
        return 0.0 if self.next("optional")["value"] else 1.0  # taken when below the probability


def replay(rules, derivation):
    stream = Replay(derivation)
    graph = expand(rules, stream)
    assert stream.records == []  # every record was a draw
    return graph


def test_the_trace_records_every_draw_with_its_kind_value_and_nodes(stalls):
    graph = expand(stalls, 3)
    assert [n.id for n in graph.nodes()] == [
        "table_1",
        "table_2",
        "stall_1",
        "table_3",
        "sack_1",
        "stall_2",
        "table_4",
        "pot_1",
        "sign_1",
    ]
    assert graph.derivation == SEED_3
    # what the records say is what the graph holds
    assert graph.node("pot_1").style == "small"
    assert ("sign_1", "table_4", "NextTo") in {(e.source, e.target, e.label) for e in graph.edges()}


def test_skipped_options_and_empty_draws_made_no_nodes(stalls):
    for seed in range(40):
        graph = expand(stalls, seed)
        for record in graph.derivation:
            if record["kind"] == "optional":
                assert [graph.node(n).type for n in record["nodes"]] == (
                    ["sign"] if record["value"] else []
                )
            if (
                record["kind"] == "alternative"
                and record["rule"] == "Stall"
                and record["value"] == 1
            ):
                assert record["nodes"] == []
            if record["kind"] == "count" and record["rule"] == "Goods":
                assert [graph.node(n).type for n in record["nodes"]] == ["sack"] * record["value"]
            if record["kind"] == "count" and record["rule"] == "Market":
                stall_draws = [r["value"] for r in graph.derivation if r["rule"] == "Stall"]
                assert len(stall_draws) == record["value"]  # one Stall per repetition
                made = [n for n in record["nodes"] if graph.node(n).type == "stall"]
                assert len(made) == stall_draws.count(0)  # the empty alternative makes no stall


def test_replaying_the_recorded_values_rebuilds_the_graph(stalls):
    for seed in range(30):
        graph = expand(stalls, seed)
        again = replay(stalls, graph.derivation)
        assert [n.type for n in again.nodes()] == [n.type for n in graph.nodes()]
        assert again.to_dict() == graph.to_dict()


def test_the_recorded_values_decide_the_graph(stalls):
    skipped = copy.deepcopy(SEED_3[:-2]) + [{**SEED_3[-2], "value": False, "nodes": []}]
    graph = replay(stalls, skipped)
    assert [n.id for n in graph.nodes()] == [
        "table_1",
        "table_2",
        "stall_1",
        "table_3",
        "sack_1",
        "stall_2",
        "table_4",
        "pot_1",
    ]
    assert graph.derivation == skipped


@pytest.mark.parametrize(
    "name",
    [pytest.param(n, marks=pytest.mark.slow) if n == "city" else n for n in shipped_rule_sets()],
)
def test_shipped_rule_sets_trace_nodes_that_exist_and_one_style_per_styled_node(name):
    rules = load_rules(name)
    styled = {entry.name for entry in rules.catalog if len(entry.styles) > 1}
    for seed in range(50):
        graph = expand(rules, seed)
        order = {node.id: node.order for node in graph.nodes()}
        styles = [r for r in graph.derivation if r["kind"] == "style"]
        assert len(styles) == sum(node.type in styled for node in graph.nodes())
        for record in graph.derivation:
            assert all(node in order for node in record["nodes"]), record
            if record["kind"] in ("alternative", "count", "optional"):
                made = [order[node] for node in record["nodes"]]
                if made:  # one run of consecutive nodes: what expanding the option created
                    assert made == list(range(made[0], made[0] + len(made))), record
            else:
                (node,) = record["nodes"]
                assert graph.node(node).type == record["type"]
                if record["kind"] == "style":
                    assert (
                        graph.node(node).style
                        == rules.catalog[record["type"]].styles[record["value"]].name
                    )
        if seed < 5:
            assert replay(rules, graph.derivation).to_dict() == graph.to_dict()


def test_same_seed_same_trace(stalls):
    first = expand(stalls, 11).derivation
    assert expand(load_rules(stalls.path), 11).derivation == first
    village = load_rules("village")
    assert json.dumps(expand(village, 7).derivation) == json.dumps(expand(village, 7).derivation)
    assert len({json.dumps(expand(stalls, seed).derivation) for seed in range(8)}) > 1


def test_choice_counts_tally_every_parameter_of_the_rules(stalls):
    counts = choice_counts(stalls, SEED_3)
    assert counts == ChoiceCounts(
        alternatives={"Stall": [2, 0], "Goods": [1, 1]},
        counts={
            Site("stalls.rules", 15, 5): {1: 0, 2: 1, 3: 0},
            Site("goods.rules", 2, 19): {0: 0, 1: 1, 2: 0},
        },
        optional={Site("stalls.rules", 16, 5): {False: 0, True: 1}},
        styles={"pot": {"big": 0, "small": 1}},
    )
    assert str(Site("goods.rules", 2, 19)) == "goods.rules:2:19"
    # nothing drawn yet: every parameter with every option at 0
    assert choice_counts(stalls).alternatives == {"Stall": [0, 0], "Goods": [0, 0]}


def test_choice_counts_add_up_over_derivations(stalls):
    traces = [expand(stalls, seed).derivation for seed in range(200)]
    counts = choice_counts(stalls, *traces)
    records = [record for trace in traces for record in trace]
    assert sum(counts.alternatives["Stall"]) == sum(r["rule"] == "Stall" for r in records)
    assert counts.styles["pot"]["small"] == sum(
        r["kind"] == "style" and r["value"] == 1 for r in records
    )
    assert sum(counts.optional[Site("stalls.rules", 16, 5)].values()) == 200
    assert counts.counts[Site("stalls.rules", 15, 5)] == {
        value: sum(
            r["kind"] == "count" and r["rule"] == "Market" and r["value"] == value for r in records
        )
        for value in (1, 2, 3)
    }


def test_choice_counts_refuse_a_trace_of_other_rules(stalls):
    with pytest.raises(ValueError, match="which these rules do not have"):
        choice_counts(stalls, expand(load_rules("village"), 7).derivation)
    with pytest.raises(ValueError, match="which these rules do not have"):
        choice_counts(stalls, [{**SEED_3[0], "value": 4}])


def test_graph_dict_and_expand_command_carry_the_trace(stalls, capsys):
    graph = expand(stalls, 3)
    assert SceneGraph.from_dict(graph.to_dict()).derivation == SEED_3
    data = graph.to_dict()
    del data["derivation"]
    assert SceneGraph.from_dict(data).derivation == []
    assert main(["expand", str(stalls.path), "--seed", "3", "--format", "json"]) == 0
    assert json.loads(capsys.readouterr().out)["derivation"] == SEED_3


def test_scene_json_with_a_derivation_validates(stalls):
    scene = build_scene(stalls, seed=3)
    data = json.loads(scene.to_json())
    assert data["derivation"] == SEED_3
    validate_scene_dict(data)
    assert Scene.from_json(scene.to_json()).derivation == SEED_3
    for rules in shipped_rule_sets():
        validate_scene_dict({**data, "derivation": expand(load_rules(rules), 1).derivation})
    broken = copy.deepcopy(data)
    broken["derivation"][2]["at"] = [1]
    with pytest.raises(SceneSchemaError) as caught:
        validate_scene_dict(broken)
    assert caught.value.path == "$.derivation[2].at"
