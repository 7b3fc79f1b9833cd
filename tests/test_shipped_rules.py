"""The rule sets shipped with the package: they load cleanly, expand on every seed, and
make the scenes their comments promise (object budgets, roads, groups, relevancies)."""

import re
from collections import Counter
from functools import cache

import pytest

from scenewright.core.relations import RELATIONS
from scenewright.core.room import ROOM_KINDS
from scenewright.core.scene_graph import SceneGraph
from scenewright.generator import rules_ast as ast
from scenewright.generator.expand import expand
from scenewright.generator.rules import Rules, check_rules, load_rules, shipped_rule_sets

ROOMS = ("bedroom", "living_room", "kitchen", "study", "classroom", "bathroom")
SHIPPED = ("village", "desk", *ROOMS)
SEEDS = range(1000)


@cache
def expansions(name: str) -> tuple[SceneGraph, ...]:
    rules = load_rules(name)
    return tuple(expand(rules, seed) for seed in SEEDS)


@pytest.fixture(scope="module", autouse=True)
def _forget_expansions():
    """The expansions are shared by this module's tests and dropped once they are done:
    kept to the end of the run, their million objects made every later full garbage
    collection in the test process take about a second."""
    yield
    expansions.cache_clear()


def objects(graph: SceneGraph):
    return graph.nodes("object")


def test_the_three_sets_are_shipped():
    assert set(SHIPPED) <= set(shipped_rule_sets())


@pytest.mark.parametrize("name", SHIPPED)
def test_loads_without_errors(name):
    assert [str(d) for d in check_rules(name) if d.is_error] == []


@pytest.mark.parametrize("name", SHIPPED)
def test_every_node_is_a_catalog_type_and_every_edge_a_known_label(name):
    catalog = load_rules(name).catalog
    for graph in expansions(name):
        for node in graph.nodes():
            if node.kind in ROOM_KINDS:
                continue  # the room's walls and openings are no catalog types
            assert node.type in catalog and catalog[node.type].kind == node.kind
        assert {edge.label for edge in graph.edges()} <= RELATIONS.names()


# -- object budgets -------------------------------------------------------------------


def noted_bounds(rules: Rules) -> dict[str, tuple[int, int]]:
    """The object counts "[LOW..HIGH]" the comment above each production of ``rules``
    states, by production: what the rule set's author wrote, to hold against
    ``object_bounds``."""
    lines = rules.path.read_text().splitlines()
    noted = {}
    for name, production in rules.productions.items():
        line = production.location.line - 2
        while line >= 0 and lines[line].startswith("#"):
            found = re.search(r"\[(\d+)\.\.(\d+)\]", lines[line])
            if found:
                noted[name] = (int(found.group(1)), int(found.group(2)))
            line -= 1
    return noted


def object_bounds(rules: Rules) -> dict[str, tuple[int, int]]:
    """For every production, the fewest and most objects an expansion of it can create.

    Read off the productions: a count range multiplies, an optional statement may
    create nothing, a production gives the extremes over its alternatives. This checks
    the budget for every seed, not only the sampled ones.
    """
    memo: dict[str, tuple[int, int]] = {}

    def production(name: str) -> tuple[int, int]:
        if name not in memo:
            memo[name] = (0, 10**9)  # a recursive rule set would show as unbounded
            bounds = [
                block(alternative.statements)
                for alternative in rules.productions[name].alternatives
            ]
            memo[name] = (min(lo for lo, _ in bounds), max(hi for _, hi in bounds))
        return memo[name]

    def block(statements) -> tuple[int, int]:
        low = high = 0
        for statement in statements:
            subject = statement.subject
            if isinstance(subject, ast.Call):
                each = production(subject.nonterminal)
            elif subject.kind == "name" and subject.name in rules.catalog:
                own = int(rules.catalog[subject.name].kind == "object")
                inner = block(statement.block) if statement.block else (0, 0)
                each = (own + inner[0], own + inner[1])
            else:  # a reference to existing nodes adds edges only
                each = (0, 0)
            times_low, times_high = (
                (statement.count.low, statement.count.high) if statement.count else (1, 1)
            )
            if statement.probability is not None and statement.probability < 1:
                times_low = 0
            low += int(times_low) * each[0]
            high += int(times_high) * each[1]
        return low, high

    for name in rules.productions:
        production(name)
    return memo


@pytest.mark.parametrize(
    "name, bounds",
    [
        ("village", (25, 40)),
        ("desk", (1, 8)),
        ("bedroom", (3, 16)),
        ("living_room", (4, 14)),
        ("kitchen", (7, 12)),
        ("study", (3, 13)),
        ("classroom", (15, 29)),
        ("bathroom", (3, 6)),
        ("office", (2, 12)),
        ("meeting_room", (5, 11)),
        ("treasury", (1, 9)),
        ("barracks", (2, 12)),
        ("library", (3, 15)),
        ("guard_room", (2, 9)),
    ],
)
def test_object_budget_holds_for_every_seed(name, bounds):
    rules = load_rules(name)
    assert object_bounds(rules)[rules.start] == bounds
    counts = [len(objects(graph)) for graph in expansions(name)]
    assert bounds[0] <= min(counts) and max(counts) <= bounds[1]


def test_village_budget_notes_match_the_productions():
    """Each village production's comment states its object range as ``[min..max]``."""
    rules = load_rules("village")
    lines = rules.path.read_text().splitlines()
    noted = {}
    for name, production in rules.productions.items():
        line = production.location.line - 2  # the comment block ends just above
        while line >= 0 and lines[line].startswith("#"):
            found = re.search(r"\[(\d+)(?:\.\.(\d+))?\]", lines[line])
            if found:
                low = int(found.group(1))
                noted[name] = (low, int(found.group(2) or low))
            line -= 1
    assert sorted(noted) == sorted(rules.productions), "every production carries a note"
    assert noted == object_bounds(rules)


def test_village_sizes_vary_across_seeds():
    counts = Counter(len(objects(graph)) for graph in expansions("village"))
    assert len(counts) >= 8  # many scene sizes, not a few fixed ones


# -- village structure ----------------------------------------------------------------


def test_village_roads_meet_at_an_intersection_or_a_single_road_crosses():
    seen = Counter()
    for graph in expansions("village"):
        roads = [n.id for n in graph.nodes("path")]
        junctions = [n.id for n in graph.nodes("junction")]
        if junctions:
            assert len(junctions) == 1 and 2 <= len(roads) <= 4
            connected = {
                e.source for e in graph.edges("PathConnectedTo") if e.target == junctions[0]
            }
            assert connected == set(roads)
        else:
            assert len(roads) == 1
        seen[len(roads)] += 1
    assert set(seen) == {1, 2, 3, 4}


def test_village_extent_fits_the_layout():
    params = load_rules("village").params
    assert params.extent == (60.0, 60.0) and not params.walls


def test_every_market_stand_is_a_table_with_a_sign_and_goods_on_it_by_a_road():
    stands = 0
    for graph in expansions("village")[:200]:
        roads = {n.id for n in graph.nodes("path")}
        for stand in graph.nodes("group"):
            if stand.type != "market_stand":
                continue
            stands += 1
            members = graph.children(stand.id)
            types = Counter(member.type for member in members)
            assert types["table"] == 1 and types["sign"] == 1
            table = next(m.id for m in members if m.type == "table")
            supported = {
                e.source for e in graph.edges() if e.target == table and RELATIONS[e.label].support
            }
            goods = {m.id for m in members if m.type not in ("table", "sign", "chair", "barrel")}
            assert goods and goods == supported
            assert any(
                e.target in roads and e.label == "NextTo"
                for e in graph.edges()
                if e.source == stand.id
            )
    assert stands > 0


def test_blacksmith_lines_up_forge_brazier_and_anvil_with_a_hammer_on_it():
    for graph in expansions("village")[:200]:
        labels = {
            (graph.node(e.source).type, e.label, graph.node(e.target).type) for e in graph.edges()
        }
        if any(n.type == "blacksmith" for n in graph.nodes("group")):
            assert ("brazier", "NextToFront", "forge") in labels
            assert ("anvil", "NextToFront", "brazier") in labels
            assert ("hammer", "OnTopOf", "anvil") in labels


def test_groups_are_never_empty():
    for name in SHIPPED:
        for graph in expansions(name)[:200]:
            for group in graph.nodes("group"):
                assert graph.children(group.id), f"{name}: empty {group.id}"


# -- desk: relevancy and styles (the And-Or graph of the desk paper) ------------------


def test_desk_relevancies_and_computer_styles_follow_the_rules():
    graphs = expansions("desk")
    present = Counter()
    styles = Counter()
    for graph in graphs:
        present.update({node.type for node in objects(graph)})
        styles.update(node.style for node in objects(graph) if node.type == "computer")
    share = {name: present[name] / len(graphs) for name in present}
    assert share["table"] == 1.0
    assert share["chair"] == pytest.approx(0.9, abs=0.04)
    assert share["paper"] == pytest.approx(0.25, abs=0.04)
    assert styles["laptop"] / (styles["laptop"] + styles["tablet"]) == pytest.approx(
        2 / 3, abs=0.05
    )


def test_indoor_sets_are_rooms_with_walls():
    assert load_rules("desk").params.walls and load_rules("desk").params.extent == (3.0, 3.0)
    assert load_rules("bedroom").params.walls and load_rules("bedroom").params.extent == (4.6, 4.0)


@pytest.mark.parametrize("name", ROOMS)
def test_room_sets_have_a_door_and_a_window_and_put_furniture_against_walls(name):
    room = load_rules(name).params.room
    assert room.doors and room.windows
    wall_labels = {"AgainstWall", "InCorner", "UnderWindow", "BesideWindow"}
    for graph in expansions(name)[:100]:
        assert any(edge.label in wall_labels for edge in graph.edges())


def test_bedroom_nightstands_flank_the_bed_and_lamps_stand_on_furniture():
    for graph in expansions("bedroom")[:300]:
        assert [n.type for n in objects(graph)].count("bed") == 1
        for node in objects(graph):
            out = {
                (e.label, graph.node(e.target).type) for e in graph.edges() if e.source == node.id
            }
            if node.type == "nightstand":
                assert out & {("BesideLeft", "bed"), ("BesideRight", "bed"), ("Beside", "bed")}
            if node.type == "lamp":
                assert any(
                    RELATIONS[label].support and target in ("nightstand", "desk")
                    for label, target in out
                )


# -- the vocabulary ------------------------------------------------------------------


def test_seats_are_seated_at_their_tables_in_every_shipped_room():
    """A chair or stool at a desk or table stands by a seat label (within reach, facing
    it), never by the 2 m NextTo*; the kitchen seats its chairs round the table."""
    seats = {"chair", "office_chair"}
    tables = {"desk", "dining_table", "student_desk", "teacher_desk", "table"}
    seen = set()
    for name in ("desk", *ROOMS):
        for graph in expansions(name)[:50]:
            for edge in graph.edges():
                source, target = graph.node(edge.source), graph.node(edge.target)
                if source.type in seats and target.type in tables:
                    assert RELATIONS[edge.label].seat, (name, edge)
                    seen.add(edge.label)
    assert seen == {"SeatedAt", "SeatedAtBack", "SeatedAround"}


def test_every_label_family_is_used_by_the_shipped_sets():
    used = {edge.label for name in SHIPPED for graph in expansions(name) for edge in graph.edges()}
    families = {
        "NextTo*": [
            label
            for label in used
            if RELATIONS[label].family == "next_to"
            and not RELATIONS[label].implicit
            and not RELATIONS[label].chooses
        ],
        "OnTopOf*": [label for label in used if label.startswith("OnTopOf")],
        "IsPartOf*": [label for label in used if label.startswith("IsPartOf")],
        "Facing*": [label for label in used if RELATIONS[label].family == "facing"],
        "Choose*": [label for label in used if "Choose" in label],
        "PathConnectedTo": [label for label in used if label == "PathConnectedTo"],
        "Implicit*": [label for label in used if RELATIONS[label].implicit],
    }
    assert [family for family, labels in families.items() if not labels] == []
