"""Dataset rows: captions of the picture and the grounding column, on the real pipeline."""

import io
import json
from importlib import resources

import jsonschema
import numpy as np
import pytest
from PIL import Image
from render_fixtures import or_skip_without_opengl

from scenewright.cli import main
from scenewright.core.errors import InputError
from scenewright.dataset.produce import PictureCaptions, produce_scene, with_picture_captions
from scenewright.dataset.spec import dataset_spec


def produced(spec, index):
    """``produce_scene`` in this process; skips without OpenGL (not under CI)."""
    return or_skip_without_opengl(lambda: produce_scene(spec, index))


@pytest.fixture(scope="module")
def products():
    spec = with_picture_captions(dataset_spec("desk", 3, captions=2, size=(96, 96)), frame="camera")
    return [produced(spec, index) for index in range(3)]


def scene_of(product) -> dict:
    return json.loads(
        next(data for name, data in product.files.items() if name.startswith("scenes/"))
    )


def test_every_span_names_what_it_links_to_with_the_rendered_boxes(products):
    for product in products:
        row, scene = product.row, scene_of(product)
        nouns = {
            o["id"]: (o["noun"], o.get("plural") or "") for o in scene["objects"] + scene["paths"]
        }
        rendered = scene["render"]["objects"]
        assert set(row["grounding"]) == {"caption", "caption_1", "text"}
        for column, mentions in row["grounding"].items():
            assert mentions, column
            for mention in mentions:
                start, end = mention["span"]
                phrase = row[column][start:end].lower()
                assert (
                    phrase == "it"
                    or any(nouns[i][0] in phrase or nouns[i][1] in phrase for i in mention["ids"])
                    or any(o["noun"] in phrase for o in scene["objects"] if o["kind"] == "group")
                ), phrase
                assert mention["boxes"] == [rendered[i]["bbox"] for i in mention["ids"]]


def test_segments_are_the_labels_whose_pixels_make_up_each_box():
    product = produced(dataset_spec("desk", 1, size=(96, 96), segmentation=True), 0)
    labels = np.asarray(Image.open(io.BytesIO(product.files["segmentation/000000.png"])))
    names = json.loads(product.files["segmentation/000000_ids.json"])
    checked = 0
    for mentions in product.row["grounding"].values():
        for mention in mentions:
            for entity_id, box, segment in zip(
                mention["ids"], mention["boxes"], mention["segments"], strict=True
            ):
                if segment is None:  # not drawn (only the full text names such)
                    assert box is None
                    continue
                assert names[str(segment)] == entity_id
                rows, columns = np.nonzero(labels == segment)
                assert box == [columns.min(), rows.min(), columns.max() + 1, rows.max() + 1]
                checked += 1
    assert checked > 5


def test_captions_name_only_what_the_picture_shows_well_enough(products):
    for product in products:
        row, rendered = product.row, scene_of(product)["render"]["objects"]
        for column in ("caption", "caption_1"):
            for mention in row["grounding"][column]:
                for entity_id, (x0, y0, x1, y1) in zip(
                    mention["ids"], mention["boxes"], strict=True
                ):
                    assert (
                        rendered[entity_id]["visible"] >= 0.25 and max(x1 - x0, y1 - y0) >= 96 // 16
                    )


def test_referring_expressions_name_seen_objects_once(products):
    for product in products:
        row, rendered = product.row, scene_of(product)["render"]["objects"]
        assert row["refexps"]
        assert len({e["id"] for e in row["refexps"]}) == len(row["refexps"])
        for expression in row["refexps"]:
            x0, y0, x1, y1 = rendered[expression["id"]]["bbox"]
            assert (
                rendered[expression["id"]]["visible"] >= 0.25 and max(x1 - x0, y1 - y0) >= 96 // 16
            )
            assert expression["program"][0] == {
                "function": "scene",
                "inputs": [],
                "value_inputs": [],
            }


def test_grounding_can_be_turned_off_and_defaults_keep_a_plain_spec():
    plain = dataset_spec("desk", 1, size=(32, 32))
    assert (
        with_picture_captions(plain, grounding=True, frame="scene", min_visible=0.25, min_size=None)
        is plain
    )
    off = with_picture_captions(plain, grounding=False)
    assert isinstance(off, PictureCaptions) and off.settings()["grounding"] is False
    assert not {"grounding", "refexps"} & set(produced(off, 0).row)
    assert {"grounding", "refexps"} <= set(produced(plain, 0).row)


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"min_visible": 2.0}, "between 0 and 1"),
        ({"min_size": -3}, ">= 0"),
        ({"frame": "viewer"}, "unknown caption frame"),
    ],
)
def test_bad_caption_options_are_refused(options, message):
    with pytest.raises(InputError, match=message):
        with_picture_captions(dataset_spec("desk", 1), **options)


def test_the_command_refuses_a_bad_threshold_in_one_line(tmp_path, capsys):
    assert (
        main(["dataset", "desk", "-n", "1", "-o", str(tmp_path / "d"), "--min-visible", "1.5"]) == 2
    )
    error = capsys.readouterr().err
    assert error.count("\n") == 1 and "between 0 and 1" in error
    assert not (tmp_path / "d").exists()


def test_rows_follow_the_shipped_row_schema(products):
    schema = json.loads(
        resources.files("scenewright.dataset")
        .joinpath("schema/metadata_row.schema.json")
        .read_text()
    )
    jsonschema.Draft202012Validator.check_schema(schema)
    for product in products:
        jsonschema.validate(product.row, schema)
    broken = dict(
        products[0].row,
        grounding={"caption": [{"span": [0, 3], "ids": [], "boxes": []}], "text": []},
    )
    with pytest.raises(jsonschema.ValidationError):
        jsonschema.validate(broken, schema)


def test_a_rerun_with_other_caption_settings_is_refused(tmp_path, capsys):
    """Caption settings are stored only when not the defaults: a rerun with the defaults
    must still see that the dataset was made with others."""
    out = str(tmp_path / "data")
    common = ["-q", "dataset", "desk", "-n", "1", "-o", out, "--size", "32x32", "--workers", "1"]
    assert or_skip_without_opengl(lambda: main([*common, "--frame", "camera"])) == 0
    capsys.readouterr()
    assert main(common) == 2
    assert "made with other settings (frame 'camera' -> 'scene')" in capsys.readouterr().err


@pytest.mark.slow
def test_a_word_budget_shortens_the_text_column_and_grounds_what_it_says(tmp_path, capsys):
    """--text-words: the row's text is the most detailed description within the budget,
    grounded like the full one; scene.json keeps the full description; a rerun with
    another budget is refused."""
    spec = dataset_spec("village", 1, size=(64, 64), text_words=60)
    product = produced(spec, 0)
    row, scene = product.row, scene_of(product)
    assert len(row["text"].split()) <= 60 < len(scene["description"]["text"].split())
    for mention in row["grounding"]["text"]:
        start, end = mention["span"]
        assert 0 <= start < end <= len(row["text"])
    assert row["grounding"]["text"]  # the budgeted text is grounded too
    out = str(tmp_path / "data")
    common = ["-q", "dataset", "desk", "-n", "1", "-o", out, "--size", "32x32", "--workers", "1"]
    assert main([*common, "--text-words", "30"]) == 0
    capsys.readouterr()
    assert main(common) == 2
    assert "made with other settings (text_words 30 -> None)" in capsys.readouterr().err
