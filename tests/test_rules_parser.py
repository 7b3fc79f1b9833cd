"""Parsing rules text into the AST: every construct, separators, comments, includes."""

import json
from pathlib import Path

import pytest

from scenewright.generator import rules_ast as ast
from scenewright.generator.catalog import SourceLocation
from scenewright.generator.rules import check_rules, load_rules
from scenewright.generator.rules_errors import Diagnostic
from scenewright.generator.rules_includes import parse_tree
from scenewright.generator.rules_parser import parse_text

RULES = Path(__file__).parent / "rules"
SHIPPED = Path(__file__).parent.parent / "grammar_rules"


def parse(text: str) -> ast.RulesFile:
    parsed = parse_text(text, "t.rules")
    assert not isinstance(parsed, Diagnostic), str(parsed)
    return parsed


def only_statement(text: str) -> ast.Statement:
    (production,) = parse(f"P -> {{ {text} }}").productions
    (statement,) = production.alternatives[0].statements
    return statement


def test_catalog_entry_fields_and_styles():
    (entry,) = parse(
        'object crate { noun "crate" plural "crates" size 1 x 2.5 x 3 shape box\n'
        ' mesh "m.glb" colour #A0b0c0 style big 2 { size 2 x 2 x 2 } style small { noun "box" } }'
    ).entries
    fields = {f.name: f.value for f in entry.fields}
    assert (entry.kind, entry.name) == ("object", "crate")
    assert fields == {
        "noun": "crate",
        "plural": "crates",
        "size": (1.0, 2.5, 3.0),
        "shape": "box",
        "mesh": "m.glb",
        "colour": "#A0b0c0",
    }
    assert [(s.name, s.weight) for s in entry.styles] == [("big", 2.0), ("small", None)]


def test_path_fields_and_scene_block():
    parsed = parse(
        'path road { noun "road" width 3 max_length 30 segments 3 }\n'
        "scene village { extent 60 x 40; ground grass\n walls\n start Village max_depth 5 max_nodes 9\n"
        ' templates "words" }'
    )
    assert {f.name: f.value for f in parsed.entries[0].fields} == {
        "noun": "road",
        "width": 3.0,
        "max_length": 30.0,
        "segments": 3.0,
    }
    (scene,) = parsed.scenes
    assert scene.name == "village"
    assert [(s.name, s.value) for s in scene.settings] == [
        ("extent", (60.0, 40.0)),
        ("ground", "grass"),
        ("walls", True),
        ("start", "Village"),
        ("max_depth", 5.0),
        ("max_nodes", 9.0),
        ("templates", "words"),
    ]


def test_statement_with_count_probability_binding_relations_and_block():
    statement = only_statement(
        "2..4 0.5? market_stand as s NextTo road #1 FacingTowards some well { table }"
    )
    assert statement.count.low == 2 and statement.count.high == 4
    assert statement.probability == 0.5
    assert statement.subject == ast.Reference("name", "market_stand", statement.subject.location)
    assert statement.binding == "s"
    assert [
        (r.label, r.target.kind, r.target.name, r.target.index) for r in statement.relations
    ] == [("NextTo", "nth", "road", 1), ("FacingTowards", "some", "well", 0)]
    assert [s.subject.name for s in statement.block] == ["table"]


def test_subjects_that_refer_and_call():
    assert only_statement("each lamp NextTo x").subject.kind == "each"
    assert only_statement("road #2 NextTo x").subject.index == 2
    call = only_statement("3 Goods(t, some road, lamp #1)").subject
    assert isinstance(call, ast.Call) and call.nonterminal == "Goods"
    assert [a.kind for a in call.arguments] == ["name", "some", "nth"]
    assert only_statement("Goods").subject == ast.Call("Goods", (), SourceLocation("t.rules", 1, 8))


def test_alternatives_on_their_own_lines_with_weights_and_comments():
    (production,) = parse(
        "P(a, b) ->\n"
        "    2: { x }   # the common case\n"
        "    # an alternative on its own line\n"
        "\n"
        "  | 0.5: {\n"
        "        y; z\n"
        "    }\n"
        "  |\n"
        "    { }\n"
    ).productions
    assert [p.name for p in production.params] == ["a", "b"]
    assert [a.weight for a in production.alternatives] == [2.0, 0.5, None]
    assert [len(a.statements) for a in production.alternatives] == [1, 2, 0]


def test_locations_are_one_based_line_and_column():
    (production,) = parse("\n\nP -> {\n    table NextTwo t\n}").productions
    statement = production.alternatives[0].statements[0]
    assert (statement.location.line, statement.location.column) == (4, 5)
    assert (statement.relations[0].location.line, statement.relations[0].location.column) == (4, 11)


def test_keywords_are_only_keywords_where_they_may_stand():
    # `shape` and `start` are field/setting words, yet fine as type names elsewhere.
    parsed = parse(
        'object shape { noun "shape" }\nobject start { noun "x" }\nP -> { shape NextTo s; start }'
    )
    assert [e.name for e in parsed.entries] == ["shape", "start"]


def test_hash_is_a_comment_unless_a_colour_or_ordinal_is_expected():
    parsed = parse(
        '#abcdef is a comment\nobject a { noun "a" colour #123456 } # #1 too\nP -> { a #2 NextTo b #10 }'
    )
    assert parsed.entries[0].fields[1].value == "#123456"
    statement = parsed.productions[0].alternatives[0].statements[0]
    assert (statement.subject.index, statement.relations[0].target.index) == (2, 10)


def test_includes_are_followed_relative_to_the_including_file(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "things.rules").write_text('include "more.rules"\nobject a { noun "a" }\n')
    (tmp_path / "lib" / "more.rules").write_text('object b { noun "b" }\n')
    main = tmp_path / "main.rules"
    main.write_text(
        'include "lib/things.rules"\ninclude "lib/more.rules"\nscene s { start S }\nS -> { a; b }\n'
    )
    tree = parse_tree(main, "main.rules")
    assert not tree.diagnostics
    # each file once, included files before the file that includes them
    assert [f.path for f in tree.files] == ["lib/more.rules", "lib/things.rules", "main.rules"]
    assert sorted(load_rules(main).catalog.entries) == ["a", "b"]


def test_market_fixture_loads_into_catalog_and_params():
    rules = load_rules(RULES / "market.rules")
    assert rules.name == "market" and rules.start == "Market"
    assert (rules.max_depth, rules.max_nodes) == (8, 200)
    assert rules.params.extent == (30.0, 20.0) and rules.params.ground == "grass"
    crate = rules.catalog["crate"]
    assert [(s.name, s.weight) for s in crate.styles] == [("wooden", 3.0), ("metal", 1.0)]
    assert crate.shape == "box"  # the default builder
    assert rules.catalog["table"].colour == pytest.approx((0x8B / 255, 0x5A / 255, 0x2B / 255))
    assert rules.catalog["road"].segments == 2 and rules.catalog["road"].kind == "path"
    assert set(rules.productions) == {"Market", "MarketStand", "Goods"}
    assert rules.warnings == ()


def test_the_language_reference_examples_load_and_expand(tmp_path):
    from scenewright.generator import expand

    reference = (Path(__file__).parents[1] / "docs" / "rules-language.md").read_text()
    blocks = reference.split("```")[1::2]
    (tmp_path / "desk.rules").write_text(blocks[0])
    rules = load_rules(tmp_path / "desk.rules")
    assert rules.warnings == () and rules.params.walls
    assert expand(rules, 0).nodes("object")[0].type == "table"
    more_kinds = parse(blocks[1])
    assert [e.kind for e in more_kinds.entries] == ["object", "group", "path", "junction"]


def test_windows_line_ends_parse_and_positions_count_lines_at_newlines(tmp_path):
    path = tmp_path / "crlf.rules"
    path.write_bytes(
        b'scene s { start S }\r\nobject a { noun "a" }\r\n\r\nS -> { a as x\r\n  a NextTwo x }\r\n'
    )
    (diagnostic,) = check_rules(path)
    assert (diagnostic.location.line, diagnostic.location.column) == (5, 5)
    assert diagnostic.source_line == "  a NextTwo x }"


def test_the_parser_can_be_built_from_several_threads_at_once():
    """Dask runs tasks in threads: the first rules load of each must not race."""
    import threading

    from scenewright.generator import rules_lark

    rules_lark._parser.cache_clear()
    failures: list[BaseException] = []

    def load() -> None:
        try:
            rules_lark.lalr_parser()
        except BaseException as error:  # noqa: BLE001 - any failure is the finding
            failures.append(error)

    threads = [threading.Thread(target=load) for _ in range(8)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert failures == []


def test_the_stored_parser_tables_are_of_this_grammar_and_parse_as_the_built_parser():
    """The tables a command loads instead of building the parser: made from today's
    rules.lark with the installed lark (else `make parser-tables`), and parsing every
    shipped rule set to the same tree, and failing at the same token, as a parser built
    from the grammar."""
    from lark import Lark
    from lark.exceptions import LarkError

    from scenewright.generator import rules_lark

    stored = rules_lark.stored_tables()
    assert stored is not None
    assert stored["made_from"] == rules_lark.made_from(rules_lark._grammar()), (
        "generator/rules_lark_tables.json is out of date: run `make parser-tables`"
    )
    loaded = rules_lark.lalr_parser()
    built = Lark(rules_lark._grammar(), postlex=rules_lark._WholeKeywords(), **rules_lark.OPTIONS)
    built.options.postlex.keywords = loaded.options.postlex.keywords
    texts = [path.read_text() for path in sorted(SHIPPED.glob("*.rules"))]
    texts.append(texts[0].replace("{", "{ doors", 1))  # a syntax error
    for text in texts:
        outcomes = []
        for parser in (loaded, built):
            try:
                outcomes.append(parser.parse(text))
            except LarkError as error:
                where = (getattr(error, "line", None), getattr(error, "column", None))
                expected = sorted(getattr(error, "expected", None) or ())
                outcomes.append((type(error).__name__, where, expected))
        assert outcomes[0] == outcomes[1]


@pytest.mark.parametrize(
    "damage",
    [
        lambda: json.loads("{not json"),
        lambda: {"made_from": None},
        lambda: {"parser": {}},
        lambda: {"made_from": rules_lark_made_from(), "parser": {"data": {}, "memo": {}}},
    ],
)
def test_damaged_stored_tables_build_the_parser_instead(monkeypatch, damage):
    from scenewright.generator import rules_lark

    monkeypatch.setattr(rules_lark, "stored_tables", damage)
    rules_lark._parser.cache_clear()
    try:
        parsed = parse_text((SHIPPED / "desk.rules").read_text(), "desk.rules")
        assert parsed.productions
    finally:
        rules_lark._parser.cache_clear()


def rules_lark_made_from():
    from scenewright.generator import rules_lark

    return rules_lark.made_from(rules_lark._grammar())


def test_a_text_parsed_again_is_not_parsed_twice_and_keeps_its_own_file_name(monkeypatch):
    from scenewright.generator import rules_parser

    text = 'object crate { noun "crate" size 1 x 1 x 1 }\nP -> { crate }\n'
    first = parse_text(text, "again.rules")
    calls = []
    real = rules_parser.lalr_parser
    monkeypatch.setattr(rules_parser, "lalr_parser", lambda: calls.append(1) or real())
    assert parse_text(text, "again.rules") is first
    assert calls == []
    renamed = parse_text(text, "other.rules")
    assert calls == [1]
    (entry,) = renamed.entries
    assert entry.location.file == "other.rules"
    edited = parse_text(text.replace("crate }", "crate crate }"), "again.rules")
    assert calls == [1, 1] and edited is not first
    # A syntax error is worded afresh each time, never kept.
    assert isinstance(parse_text("P -> {", "bad.rules"), Diagnostic)
    assert isinstance(parse_text("P -> {", "bad.rules"), Diagnostic)
    assert calls == [1, 1, 1, 1]
