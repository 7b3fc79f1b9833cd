"""``scenewright dataset --prompts FILE``: each scene composed from one request of the file,
drawn with the scene's seed, its row recording the prompt and the spans used and unused."""

from __future__ import annotations

import json
from importlib import resources

import jsonschema
import pytest

from scenewright.cli import main
from scenewright.composer.request import tokenize
from scenewright.composer.vocabulary import FUNCTION_WORDS
from scenewright.core.seeds import stream
from scenewright.dataset.spec import METADATA_FILE, scene_seed

PROMPTS = """\
# three room requests; a comment and a blank line are not prompts

a bedroom with a double bed against the north wall and a nightstand on each side of the bed
a kitchn with a fridge
a study with a desk under the window and a chair pulled up to the desk
"""
REQUESTS = [line for line in PROMPTS.splitlines() if line and not line.startswith("#")]


def run(capsys, *argv) -> tuple[int, str]:
    code = main([str(a) for a in argv])
    return code, capsys.readouterr().err


def rows(root) -> list[dict]:
    return [json.loads(line) for line in (root / METADATA_FILE).read_text().splitlines()]


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """Six scenes composed from the three prompts, twice, in two directories."""
    folder = tmp_path_factory.mktemp("prompts")
    prompts = folder / "rooms.txt"
    prompts.write_text(PROMPTS, encoding="utf-8")
    outputs = []
    for name in ("a", "b"):
        out = folder / name
        argv = ["dataset", "--prompts", prompts, "-n", 6, "-o", out, "--no-images", "--quiet"]
        assert main([str(a) for a in argv]) == 0
        outputs.append(out)
    return prompts, outputs


def test_each_row_records_its_prompt_drawn_with_the_scene_seed(made):
    _, (out, again) = made
    made_rows = rows(out)
    assert len(made_rows) == 6
    assert (out / METADATA_FILE).read_bytes() == (again / METADATA_FILE).read_bytes()
    for index, row in enumerate(made_rows):
        seed = scene_seed(0, index)
        assert row["seed"] == seed and row["rules"] == "composed" and row["ok"]
        drawn = int(stream(seed, "prompt").integers(len(REQUESTS)))
        assert row["prompt_index"] == drawn and row["prompt"] == REQUESTS[drawn]
        scene = json.loads((out / row["scene_file_name"]).read_text())
        assert scene["description"]["text"] == row["text"]
    assert len({row["prompt_index"] for row in made_rows}) > 1  # not one prompt for all


def test_used_and_unused_spans_cover_the_prompt_and_follow_the_schema(made):
    _, (out, _) = made
    schema = json.loads(
        resources.files("scenewright.dataset")
        .joinpath("schema/metadata_row.schema.json")
        .read_text()
    )
    columns = ("prompt", "prompt_index", "prompt_used", "prompt_unused")
    seen_typo = False
    for row in rows(out):
        for column in columns:
            jsonschema.validate(row[column], schema["properties"][column])
        prompt = row["prompt"]
        spans = [tuple(s) for s in row["prompt_used"]]
        spans += [(u["start"], u["end"]) for u in row["prompt_unused"]]
        for token in tokenize(prompt):  # every word but an unused "a", "the", ...
            if token.low not in FUNCTION_WORDS and token.low not in ".,;:!?":
                assert any(a <= token.start < b for a, b in spans), (token.text, prompt)
        for unused in row["prompt_unused"]:
            assert prompt[unused["start"] : unused["end"]] == unused["text"]
        if row["prompt"] == REQUESTS[1]:
            seen_typo = True
            assert [u["text"] for u in row["prompt_unused"]] == ["kitchn"]
            assert "did you mean 'kitchen'" in row["prompt_unused"][0]["message"]
            assert "a refrigerator" in row["text"]
        else:
            assert row["prompt_unused"] == []
        if row["prompt"] == REQUESTS[0]:
            assert "is just to the left of the double bed" in row["text"]
    assert seen_typo


def test_a_changed_prompts_file_is_refused_on_resume(made, capsys):
    prompts, (out, _) = made
    changed = prompts.with_name("changed.txt")
    changed.write_text(PROMPTS, encoding="utf-8")
    code, err = run(capsys, "dataset", "--prompts", changed, "-n", 6, "-o", out, "--no-images")
    assert code == 2 and "other settings" in err and "prompts" in err


@pytest.mark.parametrize(
    ("text", "args", "says"),
    [
        ("# only a comment\n\n", [], "no prompt in it"),
        (PROMPTS, ["--context", "x.context.json"], "without a learned context"),
        (None, [], "give a rule set, or --prompts"),
    ],
)
def test_bad_prompts_exit_2_with_one_line(tmp_path, capsys, text, args, says):
    argv = ["dataset", "-n", 2, "-o", tmp_path / "out", "--no-images", *args]
    if text is not None:
        prompts = tmp_path / "p.txt"
        prompts.write_text(text, encoding="utf-8")
        argv += ["--prompts", prompts]
    code, err = run(capsys, *argv)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and says in lines[0] and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_a_missing_prompts_file_is_bad_input(tmp_path, capsys):
    code, err = run(
        capsys, "dataset", "--prompts", tmp_path / "none.txt", "-n", 1, "-o", tmp_path / "o"
    )
    assert code == 2 and "cannot read the prompts" in err and len(err.strip().splitlines()) == 1
