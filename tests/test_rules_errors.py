"""Error messages for bad rules files, word for word: one golden text per mistake.

Each case is a small file (a shared header plus the lines under test) and the exact
diagnostics ``check_rules`` prints for it. The files are written into a temporary
folder and named relatively, so the messages read as a user would see them. At the
end: the syntax-error explainer's table of example places still fits the grammar.
"""

import string
from pathlib import Path

import pytest
import trimesh
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lark.exceptions import UnexpectedCharacters, UnexpectedToken

from scenewright.core.errors import InputError
from scenewright.generator import (
    RulesError,
    check_rules,
    format_diagnostics,
    load_rules,
    rules_lark,
    rules_syntax_errors,
    rules_syntax_places,
)

RULES = Path(__file__).parent / "rules"

HEADER = 'scene s { start S }\nobject table { noun "table" }\n# the lines under test:\n'

GOLDEN = {
    "label": (
        'S -> {\n    table as t\n    sign NextTwo t\n}\nobject sign { noun "sign" }',
        """\
label.rules:6:10: error: unknown relation label 'NextTwo'; did you mean 'NextTo'?
    sign NextTwo t
         ^""",
    ),
    "syntax_in_words": (
        "S -> {\n    table as t NextTo\n}",
        """\
syntax_in_words.rules:5:22: error: unexpected end of line; expected a bound name, 'some TYPE', 'each TYPE' or 'TYPE #N'
    table as t NextTo
                     ^""",
    ),
    "syntax_after_subject": (
        "S -> { table = 3 }",
        """\
syntax_after_subject.rules:4:14: error: unexpected character '='; expected 'as', a relation label, an ordinal like #1, a block '{' or the end of the statement
    S -> { table = 3 }
                 ^""",
    ),
    "syntax_statement_start": (
        "S -> { table; ) }",
        """\
syntax_statement_start.rules:4:15: error: unexpected ')'; expected a statement (a type, a nonterminal, a bound name, 'some', 'each' or a count) or the end of the statement
    S -> { table; ) }
                  ^""",
    ),
    "syntax_subject_after_count": (
        "S -> { 2 0.5? ) }",
        """\
syntax_subject_after_count.rules:4:15: error: unexpected ')'; expected a type, a nonterminal, a bound name, 'some TYPE', 'each TYPE' or 'TYPE #N'
    S -> { 2 0.5? ) }
                  ^""",
    ),
    "syntax_alternative": (
        "S -> table",
        """\
syntax_alternative.rules:4:6: error: unexpected 'table'; expected an alternative: a block '{' or a weight like '2:'
    S -> table
         ^""",
    ),
    "syntax_in_entry": (
        'object chair { noun "chair" 3 }\nS -> { chair }',
        """\
syntax_in_entry.rules:4:29: error: unexpected '3'; expected a field (noun, plural, size, shape, mesh, colour, width, max_length, segments, clearance, access, wall_gap, network), 'style' or '}'
    object chair { noun "chair" 3 }
                                ^""",
    ),
    "syntax_top_level": (
        "S -> { table }\ntable",
        """\
syntax_top_level.rules:5:1: error: unexpected 'table'; expected a catalog entry (object, group, path, junction), a production, 'include', 'scene' or the end of the file
    table
    ^""",
    ),
    "unknown_type": (
        "S -> { tabel; table }",
        """\
unknown_type.rules:4:8: error: unknown type or name 'tabel'; did you mean 'table'?
    S -> { tabel; table }
           ^""",
    ),
    "undefined_and_unused": (
        "S -> { Stnad }\nStand -> { table }",
        """\
undefined_and_unused.rules:4:8: error: undefined nonterminal 'Stnad'; did you mean 'Stand'?
    S -> { Stnad }
           ^
undefined_and_unused.rules:5:1: warning: nonterminal 'Stand' is never used (start 'S' does not reach it)
    Stand -> { table }
    ^""",
    ),
    "unused_type": (
        'object lamp { noun "lamp" }\nS -> { table NextTo some lamp }',
        """\
unused_type.rules:4:8: warning: type 'lamp' is never created (no statement makes one)
    object lamp { noun "lamp" }
           ^""",
    ),
    "never_terminates": (
        "S -> { table; 0.5? Loop }\nLoop -> { table; Loop }",
        """\
never_terminates.rules:5:1: error: 'Loop' can never finish expanding: it always calls itself (make the call optional, e.g. '0.5? Loop' or '0..2 Loop', or add an alternative without it)
    Loop -> { table; Loop }
    ^""",
    ),
    "numbers": (
        "S -> 0: { 4..2 table } | { 1.5? table; 2.5 table }",
        """\
numbers.rules:4:6: error: alternative weight must be positive, not 0
    S -> 0: { 4..2 table } | { 1.5? table; 2.5 table }
         ^
numbers.rules:4:11: error: range 4..2 has min > max
    S -> 0: { 4..2 table } | { 1.5? table; 2.5 table }
              ^
numbers.rules:4:28: error: probability must be between 0 and 1, not 1.5
    S -> 0: { 4..2 table } | { 1.5? table; 2.5 table }
                               ^
numbers.rules:4:40: error: a count must be a whole number, not 2.5
    S -> 0: { 4..2 table } | { 1.5? table; 2.5 table }
                                           ^""",
    ),
    "unknown_field": (
        'object chair { noun "chair" color #ffffff }\nS -> { chair }',
        """\
unknown_field.rules:4:29: error: unknown catalog field 'color'; did you mean 'colour'?
    object chair { noun "chair" color #ffffff }
                                ^""",
    ),
    "fields": (
        (
            'object chair { noun "chair" noun "seat" size 1 x 0 x 1 colour #12345 width 2\n'
            "  style a 0 { segments 3 } style a { } }\nS -> { chair; table }"
        ),
        """\
fields.rules:4:29: error: duplicate field 'noun'
    object chair { noun "chair" noun "seat" size 1 x 0 x 1 colour #12345 width 2
                                ^
fields.rules:4:46: error: sizes must be positive
    object chair { noun "chair" noun "seat" size 1 x 0 x 1 colour #12345 width 2
                                                 ^
fields.rules:4:63: error: colour '#12345' is not of the form #rrggbb
    object chair { noun "chair" noun "seat" size 1 x 0 x 1 colour #12345 width 2
                                                                  ^
fields.rules:4:70: error: 'width' applies to paths only, not to an object
    object chair { noun "chair" noun "seat" size 1 x 0 x 1 colour #12345 width 2
                                                                         ^
fields.rules:5:11: error: style weight must be positive, not 0
    style a 0 { segments 3 } style a { } }
            ^
fields.rules:5:15: error: a style cannot set 'segments' (only noun, plural, size, shape, mesh, colour)
    style a 0 { segments 3 } style a { } }
                ^
fields.rules:5:28: error: duplicate style 'a' of 'chair'
    style a 0 { segments 3 } style a { } }
                             ^""",
    ),
    "duplicates": (
        'object table { noun "desk" }\nS -> { table }\nS -> { table }',
        """\
duplicates.rules:4:8: error: duplicate catalog entry 'table' (first declared at duplicates.rules:2:1)
    object table { noun "desk" }
           ^
duplicates.rules:6:1: error: duplicate production for 'S' (first at duplicates.rules:5:1)
    S -> { table }
    ^""",
    ),
    "references": (
        (
            "S -> { table as t; P(t, t); table NextTo tabel; table NextTo table; table NextTo table #0 }\n"
            "P(x) -> { table OnTopOf x }"
        ),
        """\
references.rules:4:20: error: 'P' takes 1 parameter (references.rules:5:1), but 2 are given
    S -> { table as t; P(t, t); table NextTo tabel; table NextTo table; table NextTo table #0 }
                       ^
references.rules:4:42: error: unbound name 'tabel'
    S -> { table as t; P(t, t); table NextTo tabel; table NextTo table; table NextTo table #0 }
                                             ^
references.rules:4:62: error: 'table' is a type, not a bound name; write 'some table', 'each table' or 'table #1'
    S -> { table as t; P(t, t); table NextTo tabel; table NextTo table; table NextTo table #0 }
                                                                 ^
references.rules:4:82: error: '#0': ordinals count from #1
    S -> { table as t; P(t, t); table NextTo tabel; table NextTo table; table NextTo table #0 }
                                                                                     ^""",
    ),
    "path_connection": (
        (
            'path road { noun "road" }\njunction crossing { noun "crossing" }\n'
            "S -> { crossing as c; road as r PathConnectedTo c; table PathConnectedTo c; road PathConnectedTo r; r PathConnectedTo some table }"
        ),
        """\
path_connection.rules:6:52: error: PathConnectedTo starts a path at a junction or on another path, but 'table' is an object
    S -> { crossing as c; road as r PathConnectedTo c; table PathConnectedTo c; road PathConnectedTo r; r PathConnectedTo some table }
                                                       ^
path_connection.rules:6:119: error: PathConnectedTo starts a path at a junction or on another path, but 'table' is an object
    S -> { crossing as c; road as r PathConnectedTo c; table PathConnectedTo c; road PathConnectedTo r; r PathConnectedTo some table }
                                                                                                                          ^""",
    ),
    "network": (
        (
            'path road { noun "road" network grid }\n'
            'junction crossing { noun "crossing" network gird }\n'
            "S -> { table; crossing as c; road PathConnectedTo c }"
        ),
        """\
network.rules:4:25: error: 'network' applies to junctions only, not to a path
    path road { noun "road" network grid }
                            ^
network.rules:5:45: error: network 'gird' is not one of organic, grid; did you mean 'grid'?
    junction crossing { noun "crossing" network gird }
                                                ^""",
    ),
    "wall_gap": (
        (
            'group set { noun "set" wall_gap 0.1 }\n'
            'object shelf { noun "shelf" wall_gap 0.6 }\n'
            'object bench { noun "bench" wall_gap -0.1 }\n'
            "S -> { table; set; shelf; bench }"
        ),
        """\
wall_gap.rules:4:24: error: 'wall_gap' applies to objects only, not to a group
    group set { noun "set" wall_gap 0.1 }
                           ^
wall_gap.rules:5:38: error: a wall gap must be at least 0 and at most 0.5 m, not 0.6
    object shelf { noun "shelf" wall_gap 0.6 }
                                         ^
wall_gap.rules:6:38: error: a wall gap must be at least 0 and at most 0.5 m, not -0.1
    object bench { noun "bench" wall_gap -0.1 }
                                         ^""",
    ),
    "block_on_object": (
        "S -> { table { table }; tabel { table } }",
        """\
block_on_object.rules:4:14: error: a block nests nodes in a new group, but 'table' is an object
    S -> { table { table }; tabel { table } }
                 ^
block_on_object.rules:4:25: error: unknown type or name 'tabel'; did you mean 'table'?
    S -> { table { table }; tabel { table } }
                            ^""",
    ),
    "bad_values": (
        (
            'object lamp { noun "  " segments 2.5 mesh "lamp.png" }\n'
            'path road { noun "road" segments 0 max_length -3 }\nobject chair { size 1 x 1 x 1 }\n'
            "S -> { lamp; road; chair; 3000 table; each table { table }; P { table } }\nP -> { }"
        ),
        """\
bad_values.rules:4:20: error: 'noun' must not be empty
    object lamp { noun "  " segments 2.5 mesh "lamp.png" }
                       ^
bad_values.rules:4:25: error: 'segments' applies to paths only, not to an object
    object lamp { noun "  " segments 2.5 mesh "lamp.png" }
                            ^
bad_values.rules:4:34: error: 'segments' must be a whole number of at least 1, not 2.5
    object lamp { noun "  " segments 2.5 mesh "lamp.png" }
                                     ^
bad_values.rules:4:43: error: mesh 'lamp.png' is not a .glb, .gltf, .obj, .ply or .stl file
    object lamp { noun "  " segments 2.5 mesh "lamp.png" }
                                              ^
bad_values.rules:5:34: error: 'segments' must be a whole number of at least 1, not 0
    path road { noun "road" segments 0 max_length -3 }
                                     ^
bad_values.rules:5:47: error: 'max_length' must be positive, not -3
    path road { noun "road" segments 0 max_length -3 }
                                                  ^
bad_values.rules:6:8: error: catalog entry 'chair' has no noun (add: noun "...")
    object chair { size 1 x 1 x 1 }
           ^
bad_values.rules:7:27: error: count 3000 exceeds max_nodes 2000 (raise it in the scene block, e.g. max_nodes 3000)
    S -> { lamp; road; chair; 3000 table; each table { table }; P { table } }
                              ^
bad_values.rules:7:50: error: a block nests nodes in a new group, but the subject refers to existing nodes
    S -> { lamp; road; chair; 3000 table; each table { table }; P { table } }
                                                     ^
bad_values.rules:7:63: error: a block nests nodes in a new group, but 'P' is a nonterminal call
    S -> { lamp; road; chair; 3000 table; each table { table }; P { table } }
                                                                  ^""",
    ),
    "names_and_parameters": (
        "S -> { table as table; P(table) }\nP(x, x) -> { table OnTopOf x }\nQ(table) -> { table }",
        """\
names_and_parameters.rules:4:17: error: 'table' is a type; bind the nodes to another name
    S -> { table as table; P(table) }
                    ^
names_and_parameters.rules:4:24: error: 'P' takes 2 parameters (names_and_parameters.rules:5:1), but 1 is given
    S -> { table as table; P(table) }
                           ^
names_and_parameters.rules:5:6: error: duplicate parameter 'x'
    P(x, x) -> { table OnTopOf x }
         ^
names_and_parameters.rules:6:1: warning: nonterminal 'Q' is never used (start 'S' does not reach it)
    Q(table) -> { table }
    ^
names_and_parameters.rules:6:3: error: parameter 'table' has the name of a type; choose another name
    Q(table) -> { table }
      ^""",
    ),
    "mutual_recursion": (
        "S -> { table; 0.5? A }\nA -> { table; B }\nB -> 2: { A } | { table; B }",
        """\
mutual_recursion.rules:5:1: error: 'A' can never finish expanding: it always calls 'B', which never finishes (make the call optional, e.g. '0.5? B' or '0..2 B', or add an alternative without it)
    A -> { table; B }
    ^
mutual_recursion.rules:6:1: error: 'B' can never finish expanding: it always calls 'A', which never finishes (make the call optional, e.g. '0.5? A' or '0..2 A', or add an alternative without it)
    B -> 2: { A } | { table; B }
    ^""",
    ),
    "unknown_setting": (
        "scene t { walls; extnt 3 x 3 }",
        """\
unknown_setting.rules:4:18: error: unknown scene setting 'extnt'; did you mean 'extent'?
    scene t { walls; extnt 3 x 3 }
                     ^""",
    ),
    # A misspelt setting is read as one word, even when a setting starts it.
    "setting_longer_than_a_setting": (
        "scene t { extents 3 x 3 }",
        """\
setting_longer_than_a_setting.rules:4:11: error: unknown scene setting 'extents'; did you mean 'extent'?
    scene t { extents 3 x 3 }
              ^""",
    ),
    "setting_starting_with_a_setting": (
        "scene t { start_symbol S }",
        """\
setting_starting_with_a_setting.rules:4:11: error: unknown scene setting 'start_symbol'; did you mean 'start'?
    scene t { start_symbol S }
              ^""",
    ),
    "field_longer_than_a_field": (
        'object chair { noun "chair" colours #ffffff }\nS -> { chair }',
        """\
field_longer_than_a_field.rules:4:29: error: unknown catalog field 'colours'; did you mean 'colour'?
    object chair { noun "chair" colours #ffffff }
                                ^""",
    ),
    "setting_with_a_hyphen": (
        "scene t { max-depth 4 }",
        """\
setting_with_a_hyphen.rules:4:11: error: unknown scene setting 'max-depth'; did you mean 'max_depth'?
    scene t { max-depth 4 }
              ^""",
    ),
    # A '}' missing: the block still open, where it opened, and where the '}' is missing.
    "unclosed_entry": (
        'object chair { noun "chair"\n    size 0.5 x 0.9 x 0.5\nS -> { chair; table }',
        """\
unclosed_entry.rules:4:14: error: the block of object 'chair' opened here is never closed (missing '}' before line 6)
    object chair { noun "chair"
                 ^""",
    ),
    "unclosed_on_one_line": (
        'object chair { noun "chair" object sign { noun "sign" }\nS -> { chair; sign; table }',
        """\
unclosed_on_one_line.rules:4:14: error: the block of object 'chair' opened here is never closed (missing '}' before 'object' on line 4)
    object chair { noun "chair" object sign { noun "sign" }
                 ^""",
    ),
    "unclosed_style": (
        'object lamp { noun "lamp"\n    style big 2 { noun "big lamp"\nS -> { lamp; table }',
        """\
unclosed_style.rules:5:17: error: the block of style 'big' opened here is never closed (missing '}' before line 6)
    style big 2 { noun "big lamp"
                ^""",
    ),
    "unclosed_production": (
        "S -> {\n    table\n    Top\n\nTop -> { table }",
        """\
unclosed_production.rules:4:6: error: the block of production 'S' opened here is never closed (missing '}' before line 8)
    S -> {
         ^""",
    ),
    "unclosed_alternative": (
        'S -> 2: { table }\n   | 1: { table\n\nobject chair { noun "chair" }',
        """\
unclosed_alternative.rules:5:9: error: the block of alternative 2 of production 'S' opened here is never closed (missing '}' before line 7)
    | 1: { table
         ^""",
    ),
    "unclosed_group_block": (
        'group stall { noun "stall" }\nS -> {\n    stall {\n        table',
        """\
unclosed_group_block.rules:6:11: error: the block of 'stall' opened here is never closed (missing '}' at the end of the file)
    stall {
          ^""",
    ),
    # A word in the other case than the language's convention for what stands there.
    "label_in_snake_case": (
        "S -> { table as t; table next_to t }",
        """\
label_in_snake_case.rules:4:26: error: unexpected 'next_to'; relation labels are CamelCase: did you mean 'NextTo'?
    S -> { table as t; table next_to t }
                             ^""",
    ),
    "label_starting_lower_case": (
        "S -> { table as t; table nextTo t }",
        """\
label_starting_lower_case.rules:4:26: error: unexpected 'nextTo'; relation labels are CamelCase: did you mean 'NextTo'?
    S -> { table as t; table nextTo t }
                             ^""",
    ),
    "label_with_capitals_missing": (
        "S -> { table as t; table Nextto t }",
        """\
label_with_capitals_missing.rules:4:26: error: unknown relation label 'Nextto'; relation labels are CamelCase: did you mean 'NextTo'?
    S -> { table as t; table Nextto t }
                             ^""",
    ),
    "type_declared_in_camel_case": (
        'object MarketStand { noun "market stand" }',
        """\
type_declared_in_camel_case.rules:4:8: error: unexpected 'MarketStand'; types are snake_case: did you mean 'market_stand'?
    object MarketStand { noun "market stand" }
           ^""",
    ),
    "type_referred_to_in_camel_case": (
        "S -> { table; table NextTo some Table }",
        """\
type_referred_to_in_camel_case.rules:4:33: error: unexpected 'Table'; types are snake_case: did you mean 'table'?
    S -> { table; table NextTo some Table }
                                    ^""",
    ),
    "type_created_in_camel_case": (
        "S -> { Table }",
        """\
type_created_in_camel_case.rules:2:8: warning: type 'table' is never created (no statement makes one)
    object table { noun "table" }
           ^
type_created_in_camel_case.rules:4:8: error: undefined nonterminal 'Table'; types are snake_case: did you mean 'table'?
    S -> { Table }
           ^""",
    ),
    "production_in_snake_case": (
        "S -> { Stand }\nstand -> { table }",
        """\
production_in_snake_case.rules:5:1: error: unexpected 'stand'; nonterminals are CamelCase: did you mean 'Stand'?
    stand -> { table }
    ^""",
    ),
    "nonterminal_used_in_snake_case": (
        "S -> { stand }\nStand -> { table }",
        """\
nonterminal_used_in_snake_case.rules:4:8: error: unknown type or name 'stand'; nonterminals are CamelCase: did you mean 'Stand'?
    S -> { stand }
           ^
nonterminal_used_in_snake_case.rules:5:1: warning: nonterminal 'Stand' is never used (start 'S' does not reach it)
    Stand -> { table }
    ^""",
    ),
    "call_in_snake_case": (
        "S -> { table as t; goods(t) }\nGoods(x) -> { table OnTopOf x }",
        """\
call_in_snake_case.rules:4:25: error: unexpected '(' after 'goods'; nonterminals are CamelCase: did you mean 'Goods'?
    S -> { table as t; goods(t) }
                            ^""",
    ),
    "bound_name_in_camel_case": (
        "S -> { table as T }",
        """\
bound_name_in_camel_case.rules:4:17: error: unexpected 'T'; bound names are snake_case: did you mean 't'?
    S -> { table as T }
                    ^""",
    ),
    "parameter_in_camel_case": (
        "S -> { table as t; P(t) }\nP(X) -> { table OnTopOf X }",
        """\
parameter_in_camel_case.rules:5:3: error: unexpected 'X'; parameters are snake_case: did you mean 'x'?
    P(X) -> { table OnTopOf X }
      ^""",
    ),
}

#: Golden messages for whole files (their own scene block, no shared header).
WHOLE_FILES = {
    "unclosed_scene": (
        'scene village {\n    extent 30 x 30\n    start Village\n\nobject table { noun "table" }\nVillage -> { table }',
        """\
unclosed_scene.rules:1:15: error: the block of scene 'village' opened here is never closed (missing '}' before line 5)
    scene village {
                  ^""",
    ),
    "start_in_snake_case": (
        "scene s { start village }\nVillage -> { }",
        """\
start_in_snake_case.rules:1:17: error: unexpected 'village'; nonterminals are CamelCase: did you mean 'Village'?
    scene s { start village }
                    ^""",
    ),
    # A keyword run on into the next word is the whole word, never the keyword and a
    # name: 'squareon' used to read as 'square on' and parse.
    "count_weights": (
        'scene s { start S }\nobject table { noun "table" }\nS -> { 1..3 {1 2} table; 2..3 {-1 1} table; 0..1 {0 0} table }',
        """\
count_weights.rules:3:13: error: range 1..3 has 3 counts but 2 weights
    S -> { 1..3 {1 2} table; 2..3 {-1 1} table; 0..1 {0 0} table }
                ^
count_weights.rules:3:31: error: count weights may not be negative, not -1
    S -> { 1..3 {1 2} table; 2..3 {-1 1} table; 0..1 {0 0} table }
                                  ^
count_weights.rules:3:50: error: count weights are all 0: at least one count must be possible
    S -> { 1..3 {1 2} table; 2..3 {-1 1} table; 0..1 {0 0} table }
                                                     ^""",
    ),
    "keyword_run_on": (
        "scene s {\n    room 5 x 4 { doors south 1.0 0.9 }\n    start S\n}\nS -> { }",
        """\
keyword_run_on.rules:2:18: error: unknown room item 'doors'; did you mean 'door'?
    room 5 x 4 { doors south 1.0 0.9 }
                 ^""",
    ),
    "setting_run_on": (
        "scene s {\n    squareon\n    start S\n}\nS -> { }",
        """\
setting_run_on.rules:2:5: error: unknown scene setting 'squareon'; did you mean 'square'?
    squareon
    ^""",
    ),
    "start_run_on": (
        "scene s {\n    room 5x4\n    startS\n}\nS -> { }",
        """\
start_run_on.rules:3:5: error: unknown scene setting 'startS'; did you mean 'start'?
    startS
    ^""",
    ),
}


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.mark.parametrize("name", sorted(GOLDEN))
def test_golden_messages(in_tmp, name):
    body, expected = GOLDEN[name]
    Path(f"{name}.rules").write_text(HEADER + body + "\n")
    assert format_diagnostics(check_rules(f"{name}.rules")) == expected


@pytest.mark.parametrize("name", sorted(WHOLE_FILES))
def test_golden_messages_of_whole_files(in_tmp, name):
    text, expected = WHOLE_FILES[name]
    Path(f"{name}.rules").write_text(text + "\n")
    assert format_diagnostics(check_rules(f"{name}.rules")) == expected


@pytest.mark.parametrize("kind", ["object", "group", "path", "junction"])
def test_a_missing_brace_names_the_entry_of_every_kind(in_tmp, kind):
    Path("entry.rules").write_text(HEADER + f'{kind} thing {{ noun "thing"\nS -> {{ table }}\n')
    (diagnostic,) = check_rules("entry.rules")
    assert (diagnostic.location.line, diagnostic.location.column) == (4, len(f"{kind} thing {{"))
    assert diagnostic.message == (
        f"the block of {kind} 'thing' opened here is never closed (missing '}}' before line 5)"
    )


def test_balanced_braces_are_not_reported_missing(in_tmp):
    # '}' before 'Extent' would let the parser read 'Extent' as a production's name, but
    # the braces match: the error is the word.
    Path("balanced.rules").write_text(HEADER + "scene t { Extent 3 x 3 }\n")
    (diagnostic,) = check_rules("balanced.rules")
    assert diagnostic.message == "unknown scene setting 'Extent'; did you mean 'extent'?"


def test_load_rules_raises_every_error_and_keeps_warnings_apart(in_tmp):
    Path("two.rules").write_text(HEADER + "S -> { tabel; sign NextTwo t }\nUnused -> { table }\n")
    with pytest.raises(RulesError) as caught:
        load_rules("two.rules")
    error = caught.value
    assert isinstance(error, InputError) and error.exit_code == 2
    assert [d.message.split(";")[0] for d in error.diagnostics] == [
        "unknown type or name 'tabel'",
        "unknown type or name 'sign'",
        "unknown relation label 'NextTwo'",
        "unbound name 't'",
    ]
    assert "warning" not in str(error)
    Path("warn.rules").write_text(HEADER + "S -> { table }\nUnused -> { table }\n")
    assert [w.severity for w in load_rules("warn.rules").warnings] == ["warning"]


@pytest.mark.parametrize(
    ("statements", "warned"),
    [
        (
            "0.6? table\n0..2 cup OnTopOf some table",
            True,
        ),  # in four scenes of ten there is no table
        ("0..1 table\ncup OnTopOf table #1", True),
        ("table\n0.6? table\ncup OnTopOf some table", False),  # one table is certain
        ("0.6? table\ncup NextTo each table", False),  # each of none is none
    ],
)
def test_a_reference_to_a_type_every_maker_of_which_may_make_none_is_warned(
    in_tmp, statements, warned
):
    Path("maybe.rules").write_text(
        HEADER + 'object cup { noun "cup" }\nS -> {\n' + statements + "\n}\n"
    )
    diagnostics = check_rules("maybe.rules")
    assert all(d.severity == "warning" for d in diagnostics)
    messages = [d.message for d in diagnostics if "may find none" in d.message]
    assert bool(messages) is warned, diagnostics
    if warned:
        assert messages[0].endswith(
            "where a scene has none its expansion stops here; refer to it only where one is certain"
        )


def test_scene_settings_and_a_second_scene_block(in_tmp):
    Path("scenes.rules").write_text(
        "scene s { start S max_depth 0 max_nodes 2.5 start T }\nscene t { start S }\nS(x) -> { }\n"
    )
    assert (
        format_diagnostics(check_rules("scenes.rules"))
        == """\
scenes.rules:1:17: error: start symbol 'S' takes parameters; it must take none
    scene s { start S max_depth 0 max_nodes 2.5 start T }
                    ^
scenes.rules:1:29: error: 'max_depth' must be a whole number of at least 1, not 0
    scene s { start S max_depth 0 max_nodes 2.5 start T }
                                ^
scenes.rules:1:41: error: 'max_nodes' must be a whole number of at least 1, not 2.5
    scene s { start S max_depth 0 max_nodes 2.5 start T }
                                            ^
scenes.rules:1:45: error: duplicate scene setting 'start'
    scene s { start S max_depth 0 max_nodes 2.5 start T }
                                                ^
scenes.rules:2:1: error: a second scene block (the first is at scenes.rules:1:1)
    scene t { start S }
    ^"""
    )


def test_scene_block_without_start(in_tmp):
    Path("nostart.rules").write_text(
        'scene s { extent 0 x 3 }\nobject table { noun "table" }\nS -> { table }\n'
    )
    assert (
        format_diagnostics(check_rules("nostart.rules"))
        == """\
nostart.rules:1:1: error: the scene block has no start symbol (add: start NONTERMINAL)
    scene s { extent 0 x 3 }
    ^
nostart.rules:1:18: error: the extent must be positive
    scene s { extent 0 x 3 }
                     ^"""
    )


def test_missing_scene_block(in_tmp):
    Path("noscene.rules").write_text("S -> { }\n")
    assert format_diagnostics(check_rules("noscene.rules")) == (
        "noscene.rules:1:1: error: no scene block; add one, e.g. scene village { extent 40 x 40  start Village }\n"
        "    S -> { }\n    ^"
    )


def test_undefined_start_symbol(in_tmp):
    Path("start.rules").write_text("scene s { start Villag }\nVillage -> { }\n")
    assert (
        check_rules("start.rules")[0].message
        == "start symbol 'Villag' has no production; did you mean 'Village'?"
    )


def test_mesh_files_are_found_relative_to_the_rules_file(in_tmp):
    (in_tmp / "sub" / "models").mkdir(parents=True)
    trimesh.creation.box().export(in_tmp / "sub" / "models" / "chair.glb")
    text = (
        HEADER + 'object chair { noun "chair" mesh "models/chair.glb" }\n'
        'object bench { noun "bench" mesh "models/bench.glb" }\nS -> { chair; bench; table }\n'
    )
    Path("sub/mesh.rules").write_text(text)
    (diagnostic,) = check_rules("sub/mesh.rules")
    assert (
        diagnostic.message == f"mesh file 'models/bench.glb' not found (looked in {in_tmp / 'sub'})"
    )
    Path("sub/mesh.rules").write_text(text.replace("bench.glb", "chair.glb"))
    assert load_rules("sub/mesh.rules").catalog["chair"].mesh == str(
        in_tmp / "sub" / "models" / "chair.glb"
    )


def test_templates_folder_is_found_relative_to_the_file_of_the_scene_block(in_tmp):
    (in_tmp / "sub" / "words").mkdir(parents=True)
    text = 'scene s {\n    start S\n    templates "wording"\n}\nobject table { noun "table" }\nS -> { table }\n'
    Path("sub/own.rules").write_text(text)
    (diagnostic,) = check_rules("sub/own.rules")
    assert str(diagnostic) == (
        f"sub/own.rules:3:15: error: templates folder 'wording' not found (looked in {in_tmp / 'sub'})\n"
        '    templates "wording"\n'
        "              ^"
    )
    Path("sub/own.rules").write_text(text.replace("wording", "words"))
    assert load_rules("sub/own.rules").params.templates == str(in_tmp / "sub" / "words")
    # a rule set that includes it keeps the folder relative to the scene block's file
    Path("top.rules").write_text('include "sub/own.rules"\n')
    assert load_rules("top.rules").params.templates == str(in_tmp / "sub" / "words")


def test_include_cycle_and_missing_include(in_tmp):
    Path("a.rules").write_text('include "lib/b.rules"\nscene s { start S }\nS -> { }\n')
    Path("lib").mkdir()
    Path("lib/b.rules").write_text('include "../a.rules"\n')
    assert format_diagnostics(check_rules("a.rules")) == (
        "lib/b.rules:1:9: error: include cycle: a.rules -> lib/b.rules -> a.rules\n"
        '    include "../a.rules"\n            ^'
    )
    Path("c.rules").write_text('include "nope.rules"\n')
    assert (
        check_rules("c.rules")[0].message
        == "cannot read included file 'nope.rules': No such file or directory"
    )


def test_unknown_rule_set_name(in_tmp):
    with pytest.raises(
        RulesError,
        match=r"no rules file 'vilage' \(and no shipped rule set of that name: .*village",
    ):
        load_rules("vilage")
    Path("campsite.rules").write_text("")
    with pytest.raises(RulesError, match=r"did you mean 'campsite.rules'\?"):
        load_rules("campsite")


# -- robustness: whatever the text, a RulesError with valid positions or Rules ------

VALID = (RULES / "market.rules").read_text()
TOKENS = VALID.replace("\n", " \n ").split(" ")


def assert_loads_or_fails_cleanly(tmp_path, text: str) -> None:
    path = tmp_path / "fuzz.rules"
    path.write_text(text, encoding="utf-8")
    try:
        load_rules(path)
    except RulesError as error:
        lines = text.split("\n")
        assert error.diagnostics
        for diagnostic in error.diagnostics:
            location = diagnostic.location
            if location.file != str(path):
                continue  # an included file (or a missing one) has its own lines
            assert 1 <= location.line <= len(lines), (diagnostic, text)
            assert 1 <= location.column <= len(lines[location.line - 1]) + 1, (diagnostic, text)
            for raw_name in ("_NL", "LBRACE", "RBRACE", "CAMEL", "NAME", "$END", "__ANON"):
                assert raw_name not in diagnostic.message, diagnostic


#: Text made of the language's own pieces (so the parser gets deep) mixed with any
#: characters at all (\r, form feeds, Unicode line separators, ...).
PIECES = list(string.ascii_letters + string.digits + ' \n\t{}()|;:#.?,-"_') + [
    "->",
    "..",
    "object",
    "group",
    "scene",
    "start",
    "include",
    "some",
    "each",
    "as",
    "NextTo",
    "noun",
    "size",
    " x ",
    "#1",
    "#8b5a2b",
    "\n|",
    '"a.rules"',
]
rules_like_text = st.lists(st.sampled_from(PIECES) | st.text(max_size=2), max_size=60).map("".join)
fuzz_settings = settings(
    max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)


@fuzz_settings
@given(text=rules_like_text)
def test_arbitrary_text_never_raises_anything_else(tmp_path, text):
    assert_loads_or_fails_cleanly(tmp_path, text)


@fuzz_settings
@given(
    edits=st.lists(
        st.tuples(
            st.sampled_from(["delete", "duplicate", "swap"]),
            st.integers(0, len(TOKENS) - 1),
            st.integers(0, len(TOKENS) - 1),
        ),
        min_size=1,
        max_size=4,
    )
)
def test_mutated_valid_file_never_raises_anything_else(tmp_path, edits):
    tokens = list(TOKENS)
    for action, i, j in edits:
        i, j = i % len(tokens), j % len(tokens)
        if action == "delete":
            del tokens[i]
        elif action == "duplicate":
            tokens.insert(i, tokens[i])
        else:
            tokens[i], tokens[j] = tokens[j], tokens[i]
    assert_loads_or_fails_cleanly(tmp_path, " ".join(tokens))


def test_a_file_that_is_not_utf8_text_is_a_rules_error(in_tmp):
    Path("latin1.rules").write_bytes("scene s { start S }\n# caf\xe9\n".encode("latin-1"))
    with pytest.raises(
        RulesError, match=r"^latin1\.rules:1:1: error: cannot read 'latin1\.rules': not UTF-8 text$"
    ):
        load_rules("latin1.rules")


# -- the syntax-error explainer's table of places -------------------------------------

#: Every construct of the language, in the forms the parser tells apart.
EVERY_CONSTRUCT = """\
include "other.rules"; object a { }
object b { ; noun "b"
    style s { ; noun "c"; } ; style t 2 { } colour #aaaaaa; width 2
    max_length 3 segments 2 mesh "m.glb" plural "bs" shape c size 1 x 1 x 1 }
scene s { ; walls;
    extent 1 x 2; ground g start S max_depth 2 max_nodes 3 templates "t" }
P(a, b) -> 2: { 1..2 0.5? a as c NextTo some b FacingTowards each d OnTopOf e #1 { f; G(a, some b, each c, d #2) } }
    | 3:
    { }
    | { A() }
S -> { 2 0.5? a as b NextTo c #2 FacingTowards some d { }; some a as b; each a NextTo b; a #1 as b NextTo each c
    A(b) as c NextTo d; A as b; A() NextTo b; 3 A(b, c) as d { a }
    0.5? some a NextTo b; 1..2 each a as b { } }
T -> { ; a

    b;; c { ; d; e } }
"""


def test_every_example_of_the_explainer_stops_at_its_end_in_its_own_place():
    for name, context in rules_syntax_places._CONTEXTS.items():
        for example in context.examples:
            stop = rules_syntax_places._example_stop(example)
            assert stop is not None and rules_lark.error_offset(stop, example) == len(example), (
                name,
                example,
            )
            assert rules_syntax_places._context(stop) is context, (name, example)


def test_the_examples_stop_after_every_field_and_setting_of_the_grammar():
    terminals = {terminal.name for terminal in rules_lark.lalr_parser().terminals}
    assert {sample.split()[0] for sample in rules_syntax_places._FIELDS} == set(
        rules_syntax_errors._keywords(terminals, "_field")
    )
    assert {sample.split()[0] for sample in rules_syntax_places._SETTINGS} == set(
        rules_syntax_errors._keywords(terminals, "_setting")
    )


@pytest.mark.parametrize(
    "text", [EVERY_CONSTRUCT, (RULES / "market.rules").read_text()], ids=["every", "market"]
)
def test_every_place_where_a_word_may_come_is_in_the_table(text):
    """Wherever a valid file may be cut short before a token, the explainer knows the
    place, unless only punctuation, a value or one keyword may come next (said alone)."""
    parser = rules_lark.lalr_parser()
    for token in parser.parse_interactive(text).iter_parse():
        prefix = text[: token.start_pos]
        try:
            parser.parse(prefix)
        except (UnexpectedToken, UnexpectedCharacters) as stop:
            accepts = stop.interactive_parser.accepts()
            words = [
                name
                for name in accepts
                if name in ("NAME", "CAMEL")
                or (name != "$END" and (rules_lark.terminal_literal(name) or "").isidentifier())
            ]
            if words and len(accepts) > 1:
                assert rules_syntax_places._context(stop) is not rules_syntax_places._ANYWHERE, (
                    prefix[-40:],
                    sorted(accepts),
                )
