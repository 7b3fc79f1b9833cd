"""Write the rules language's stored parser tables (generator/rules_lark_tables.json).

Run after an edit of generator/rules.lark or an upgrade of lark (`make parser-tables`);
until then the parser is built from the grammar at each command's start, as correct but
slower. Two writes of one grammar may order the tables differently (lark numbers its
rules as it meets them); the parser they load is the same.
"""

from pathlib import Path

from scenewright.generator.rules_lark import TABLES, write_tables

target = Path(__file__).resolve().parent.parent / "generator" / TABLES
write_tables(target)
print(f"wrote {target.name}")
