"""Fitting a rule set's weights to example derivations, and writing them back.

Known answers (rules with set weights, many derivations, the fit within a few standard
errors), the posterior itself, the rewriter (only numbers change; what it writes loads
and means the fitted numbers), parameters no example drew, examples made before the
numbers moved, and the command line's outputs and bad inputs.
"""

import json
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_cli import assert_one_line_error, run

from scenewright.cli import main
from scenewright.generator import load_rules
from scenewright.generator.expand import expand, expand_with
from scenewright.generator.rules import parse_rules_tree
from scenewright.learning.derivations import derivations_of, signature
from scenewright.learning.rewrite import rewrite_rules
from scenewright.learning.weights import fit_weights, fit_weights_em, posterior

TRUTH = """\
# a test grammar with every kind of parameter
scene s { extent 20 x 20  start S  max_nodes 200 }

object crate { noun "crate"  size 0.5 x 0.5 x 0.5
    style red 3 { colour #aa2222 }
    style blue { colour #2222aa }
}
object barrel { noun "barrel"  size 0.6 x 0.9 x 0.6 }
group stack { noun "stack" }

S -> { 4 Pile }
Pile -> 0.7: { stack { 1..3 {1 2 1} crate; 0.3? barrel } }
      | 0.3: { stack { 2..4 crate } }
"""

#: The lines of Pile's two alternatives.
FIRST, SECOND = (
    TRUTH.splitlines().index(line) + 1 for line in TRUTH.splitlines() if "{ stack {" in line
)

#: The truth's parameters: counts and optionals by their line, the others by name.
TRUE = {
    ("alternative", "Pile"): [0.7, 0.3],
    ("count", FIRST): [0.25, 0.5, 0.25],
    ("count", SECOND): [1 / 3, 1 / 3, 1 / 3],
    ("optional", FIRST): [0.7, 0.3],
    ("style", "crate"): [0.75, 0.25],
}


def flattened(text: str) -> str:
    """The same rules with every number it may fit set to a flat guess."""
    text = re.sub(r"\b0\.[37]: ", "1: ", text)
    text = (
        text.replace("1..3 {1 2 1}", "1..3")
        .replace("0.3?", "0.5?")
        .replace("style red 3", "style red")
    )
    return text


def write(folder: Path, name: str, text: str) -> Path:
    path = folder / name
    path.write_text(text)
    return path


def derivations(rules, seeds) -> list[list[dict]]:
    return [expand(rules, seed).derivation for seed in seeds]


def key(parameter):
    return parameter.kind, (
        parameter.site.line if parameter.kind in ("count", "optional") else parameter.name
    )


def test_posterior_is_the_dirichlet_mean_and_deviation():
    mean, error = posterior([3, 1], prior=0.5)
    assert mean == pytest.approx([0.7, 0.3])
    assert error == pytest.approx(np.sqrt(mean * (1 - mean) / 6))
    assert posterior([0, 0, 0])[0] == pytest.approx([1 / 3] * 3)  # nothing drawn: the prior


def test_fit_recovers_known_weights_from_flattened_rules(tmp_path):
    truth = load_rules(write(tmp_path, "truth.rules", TRUTH))
    flat = load_rules(write(tmp_path, "flat.rules", flattened(TRUTH)))
    fit = fit_weights(
        flat, derivations(truth, range(600))
    )  # traces of the truth, counted against the flat file
    found = {key(parameter): parameter for parameter in fit.parameters}
    assert set(found) == set(TRUE)
    for name, truth_values in TRUE.items():
        parameter = found[name]
        assert parameter.identified
        for estimate, error, true_value in zip(
            parameter.estimate, parameter.standard_error, truth_values, strict=False
        ):
            assert abs(estimate - true_value) <= max(3 * error, 0.03), (name, parameter)
    assert found[("optional", FIRST)].written == pytest.approx(
        (0.5, 0.5)
    )  # what the flat file said


def test_rewritten_rules_change_only_numbers_and_load_with_the_fitted_values(tmp_path):
    flat_text = flattened(TRUTH)
    truth = load_rules(write(tmp_path, "truth.rules", TRUTH))
    path = write(tmp_path, "flat.rules", flat_text)
    fit = fit_weights(load_rules(path), derivations(truth, range(200)))
    text = rewrite_rules(parse_rules_tree(path), fit)[str(path)]

    def words(source: str) -> list[str]:  # everything but numbers, weights and weight prefixes
        source = re.sub(r"\{[0-9. ]+\}|[0-9.]+:|[0-9.]+\?", " ", source)
        return re.sub(r"[0-9.]+", " ", source).split()

    assert words(text) == words(flat_text)
    assert text.count("\n") == flat_text.count("\n")
    assert text.splitlines()[0] == flat_text.splitlines()[0]  # comments kept
    fitted = load_rules(write(tmp_path, "fitted.rules", text))
    found = {key(parameter): parameter for parameter in fit.parameters}
    pile = fitted.productions["Pile"]
    assert [a.weight for a in pile.alternatives] == pytest.approx(
        found[("alternative", "Pile")].estimate, abs=5e-4
    )
    counts = pile.alternatives[0].statements[0].block[0].count
    assert np.asarray(counts.weights) == pytest.approx(found[("count", FIRST)].estimate, abs=5e-4)
    assert [s.weight for s in fitted.catalog["crate"].styles] == pytest.approx(
        found[("style", "crate")].estimate, abs=5e-4
    )


@settings(
    max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(seeds=st.lists(st.integers(0, 10**6), min_size=1, max_size=12, unique=True))
def test_any_fit_rewrites_into_rules_that_load_and_refit_to_the_same_numbers(tmp_path, seeds):
    path = write(tmp_path, "flat.rules", flattened(TRUTH))
    flat = load_rules(path)
    fit = fit_weights(flat, derivations(flat, seeds))
    fitted_path = write(
        tmp_path, "fitted.rules", rewrite_rules(parse_rules_tree(path), fit)[str(path)]
    )
    # The examples were drawn from the flat file; their columns moved where weights were
    # written in before a number on the same line, and they must still be counted.
    refit = fit_weights(load_rules(fitted_path), derivations(flat, seeds))
    assert [p.draws for p in refit.parameters] == [p.draws for p in fit.parameters]
    for before, after in zip(fit.parameters, refit.parameters, strict=False):
        assert after.written == pytest.approx(before.estimate, abs=2e-3)


def test_a_parameter_no_example_drew_is_unidentified_and_keeps_its_number(tmp_path):
    text = (
        TRUTH.replace("S -> { 4 Pile }", "S -> { 4 Pile; 0? Rare }")
        + "Rare -> 5: { barrel } | 1: { crate }\n"
    )
    path = write(tmp_path, "rare.rules", text)
    rules = load_rules(path)
    fit = fit_weights(rules, derivations(rules, range(30)))
    assert [(p.kind, p.name) for p in fit.unidentified] == [("alternative", "Rare")]
    rewritten = rewrite_rules(parse_rules_tree(path), fit)[str(path)]
    assert "Rare -> 5: { barrel } | 1: { crate }" in rewritten
    assert (
        "0.016? Rare" in rewritten
    )  # never taken in 30 draws: (0 + 0.5) / (30 + 1) under the prior
    assert fit.to_dict()["unidentified"] == [
        f"alternative Rare at rare.rules:{len(TRUTH.splitlines()) + 1}:1"
    ]


def test_a_trace_of_other_rules_is_refused(tmp_path):
    rules = load_rules(write(tmp_path, "truth.rules", TRUTH))
    with pytest.raises(ValueError, match="which these rules do not have"):
        fit_weights(rules, [expand(load_rules("desk"), 1).derivation])


# -- examples without their derivation: the derivations that could have made them, EM ----

#: Scenes of one to three A's, where a crate and a barrel may be one A or two.
AMBIGUOUS = """\
scene s { extent 20 x 20  start S  max_nodes 200 }
object crate { noun "crate"  size 0.5 x 0.5 x 0.5 }
object barrel { noun "barrel"  size 0.6 x 0.9 x 0.6 }
S -> { 1..3 {1 2 1} A }
A -> 0.5: { crate } | 0.3: { barrel } | 0.2: { crate; barrel }
"""


def without_some(derivation: list[dict]) -> list[dict]:
    """A derivation less its ``some`` draws, which the search does not enumerate."""
    return [
        {k: v for k, v in record.items() if k != "nodes"}
        for record in derivation
        if record["kind"] != "some"
    ]


@pytest.mark.parametrize("name", ["desk", "bedroom", "study"])
def test_the_derivations_of_a_scene_include_its_own_and_all_make_a_scene_like_it(name):
    rules = load_rules(name)
    for seed in range(3):
        graph = expand(rules, seed)
        found = derivations_of(rules, graph)
        assert without_some(graph.derivation) in [without_some(d) for d in found]
        for derivation in found:
            assert signature(replay(rules, derivation)) == signature(graph)


def replay(rules, derivation):
    """The graph a derivation makes (its ``some`` draws answered with the first node)."""
    from scenewright.learning.derivations import _Scripted

    script = [
        int(record["value"]) - record.get("low", 0)
        for record in derivation
        if record["kind"] != "some"
    ]
    return expand_with(rules, _Scripted(script))


def test_a_scene_no_derivation_makes_has_none(tmp_path):
    rules = load_rules(write(tmp_path, "amb.rules", AMBIGUOUS))
    assert derivations_of(rules, expand(load_rules("desk"), 0)) == []  # other types
    four_crates = AMBIGUOUS.replace("S -> { 1..3 {1 2 1} A }", "S -> { 4 crate }")
    assert (
        derivations_of(rules, expand(load_rules(write(tmp_path, "four.rules", four_crates)), 0))
        == []
    )


def test_em_recovers_weights_from_examples_without_derivations(tmp_path):
    truth = load_rules(write(tmp_path, "amb.rules", AMBIGUOUS))
    flat_text = (
        AMBIGUOUS.replace(" {1 2 1}", "")
        .replace("0.5:", "1:")
        .replace("0.3:", "1:")
        .replace("0.2:", "1:")
    )
    rules = load_rules(write(tmp_path, "flat.rules", flat_text))
    graphs = [expand(truth, seed) for seed in range(150)]
    candidates = [derivations_of(rules, graph) for graph in graphs]
    assert sum(len(found) > 1 for found in candidates) > 50  # really ambiguous
    em = fit_weights_em(rules, candidates)
    assert em.ambiguous == sum(len(found) > 1 for found in candidates) and em.iterations > 1
    true = {"alternative": [0.5, 0.3, 0.2], "count": [0.25, 0.5, 0.25]}
    for fitted in em.parameters:
        assert fitted.written == pytest.approx([1 / 3] * 3)  # it started flat
        # Its standard errors leave out which derivation made each example: a wider band.
        for estimate, error, value in zip(
            fitted.estimate, fitted.standard_error, true[fitted.kind], strict=False
        ):
            assert abs(estimate - value) <= max(3 * error, 0.07)
        assert (
            np.abs(np.subtract(fitted.estimate, true[fitted.kind])).sum() < 0.15
        )  # flat: 0.33 away


def test_em_with_one_derivation_per_example_is_the_closed_form(tmp_path):
    rules = load_rules(write(tmp_path, "amb.rules", AMBIGUOUS))
    derivations = [expand(rules, seed).derivation for seed in range(40)]
    em = fit_weights_em(rules, [[d] for d in derivations])
    assert em.iterations == 0
    assert [p.estimate for p in em.parameters] == [
        p.estimate for p in fit_weights(rules, derivations).parameters
    ]


#: A room whose alternatives differ only in where things stand: which side of the bed a
#: nightstand is on, and whether the chest stands against a wall or by the bed's foot.
ROOM = """\
scene r { room 4 x 4  start R  max_nodes 20 }
object bed { noun "bed"  size 1.4 x 0.5 x 2 }
object nightstand { noun "nightstand"  size 0.45 x 0.55 x 0.4 }
object lamp { noun "lamp"  size 0.25 x 0.4 x 0.25 }
object chest { noun "chest"  size 0.9 x 0.5 x 0.45 }
R -> { bed as b AgainstWall some wall; Side(b); 0.6? chest AgainstWall some wall }
Side(b) -> 0.8: { nightstand as n NextToLeft b FacingSameDirection b; 0.7? lamp OnTopOf n }
         | 0.2: { nightstand as n NextToRight b FacingSameDirection b; 0.7? lamp OnTopOf n }
"""


def handwritten(scene) -> dict:
    """The hand-written example of a generated scene: boxes, poses and styles only."""
    objects = [
        {
            "id": o.id,
            "type": o.type,
            "size": list(o.size),
            "position": list(o.position),
            "yaw": float(np.degrees(o.yaw)),
            **({"style": o.style} if o.style else {}),
        }
        for o in scene.placed_objects()
    ]
    return {
        "room": {"corners": [list(c) for c in scene.room.corners], "height": 2.6},
        "objects": objects,
    }


def test_examples_read_from_geometry_fit_like_their_derivations(tmp_path):
    from scenewright.api import build_scene
    from scenewright.examples import load_example
    from scenewright.learning.fit import example_candidates

    truth = write(tmp_path, "truth.rules", ROOM)
    flat = load_rules(
        write(
            tmp_path,
            "flat.rules",
            ROOM.replace("0.8:", "1:")
            .replace("0.2:", "1:")
            .replace("0.6?", "0.5?")
            .replace("0.7?", "0.5?"),
        )
    )
    scenes = [
        scene for scene in (build_scene(str(truth), seed) for seed in range(40)) if scene.layout.ok
    ]
    assert len(scenes) >= 36
    measured, traced = [], []
    for index, scene in enumerate(scenes):
        example = load_example(
            write(tmp_path, f"{index}.json", json.dumps(handwritten(scene)))
        ).scene
        assert example.relations == [
            r for r in example.relations if r.label == "OnTopOf"
        ]  # geometry alone
        found = example_candidates(flat, f"{index}.json", example)
        assert len(found) == 1  # the side the nightstand stands on decides
        measured.append(found)
        traced.append([scene.derivation])
    by_geometry, by_trace = fit_weights_em(flat, measured), fit_weights_em(flat, traced)
    assert [p.estimate for p in by_geometry.parameters] == [p.estimate for p in by_trace.parameters]
    side = next(p for p in by_geometry.parameters if p.name == "Side")
    assert side.estimate[0] > 0.6  # the truth's 0.8 against the flat 0.5


def test_fit_command_reads_a_folder_of_hand_written_examples(capsys, tmp_path):
    from scenewright.api import build_scene

    truth = write(tmp_path, "truth.rules", ROOM)
    folder = tmp_path / "mine"
    folder.mkdir()
    for seed in range(6):
        write(folder, f"room_{seed}.json", json.dumps(handwritten(build_scene(str(truth), seed))))
    report = tmp_path / "fit.json"
    code, stdout, err = run(
        capsys,
        "fit",
        str(truth),
        str(folder),
        "-o",
        str(tmp_path / "f.rules"),
        "--report",
        str(report),
    )
    assert code == 0, err
    assert "from 6 examples" in stdout
    assert json.loads(report.read_text())["examples"] == 6
    (folder / "room_0.json").write_text(
        json.dumps(
            {
                "extent": [4, 4],
                "objects": [{"id": "t", "type": "table", "size": [1, 0.7, 1], "position": [0, 0]}],
            }
        )
    )
    code, _, err = run(capsys, "fit", str(truth), str(folder), "-o", str(tmp_path / "g.rules"))
    assert (
        code == 2 and "room_0.json: no derivation of truth.rules makes a scene like this one" in err
    )
    assert "its types: table" in err and not (tmp_path / "g.rules").exists()


#: ROOM with a styled nightstand: examples that leave the style out must still fit.
STYLED_ROOM = ROOM.replace(
    'object nightstand { noun "nightstand"  size 0.45 x 0.55 x 0.4 }',
    'object nightstand { noun "nightstand"  size 0.45 x 0.55 x 0.4\n'
    "    style oak 3 { colour #886644 }\n    style white { colour #eeeeee } }",
)


def test_fit_takes_an_example_without_a_style_as_of_a_style_not_known(capsys, tmp_path):
    from scenewright.api import build_scene

    truth = write(tmp_path, "truth.rules", STYLED_ROOM)
    folder = tmp_path / "mine"
    folder.mkdir()
    styled = 0
    for seed in range(6):
        document = handwritten(build_scene(str(truth), seed))
        for obj in document["objects"]:
            styled += obj.pop("style", None) is not None  # the user wrote no style
        write(folder, f"room_{seed}.json", json.dumps(document))
    assert styled >= 4
    report = tmp_path / "fit.json"
    code, stdout, err = run(
        capsys,
        "fit",
        str(truth),
        str(folder),
        "-o",
        str(tmp_path / "f.rules"),
        "--report",
        str(report),
    )
    assert code == 0, err
    parameters = {p["name"]: p for p in json.loads(report.read_text())["parameters"]}
    side = next(p for name, p in parameters.items() if name == "Side")
    assert side["draws"] != [0, 0]  # the sides are still read from the geometry
    # No example says a nightstand's style: the style is unidentified and keeps its
    # written 3:1, rather than being pulled anywhere by the derivations of every style.
    style = parameters["nightstand"]
    assert not style["identified"] and style["draws"] == [0, 0]
    assert "style oak 3 {" in (tmp_path / "f.rules").read_text()


def test_fit_names_the_file_type_and_style_the_rules_do_not_have(capsys, tmp_path):
    from scenewright.api import build_scene

    truth = write(tmp_path, "truth.rules", STYLED_ROOM)
    scene = next(s for s in (build_scene(str(truth), seed) for seed in range(10)) if s.layout.ok)
    document = handwritten(scene)
    stand = next(o for o in document["objects"] if o["type"] == "nightstand")
    stand["style"] = "walnut"
    write(tmp_path, "odd.json", json.dumps(document))
    code, _, err = run(
        capsys, "fit", str(truth), str(tmp_path / "odd.json"), "-o", str(tmp_path / "f.rules")
    )
    assert_one_line_error(err)
    assert code == 2
    assert "odd.json" in err and "nightstand" in err and "'walnut'" in err and "oak, white" in err
    assert not (tmp_path / "f.rules").exists()


# -- the command line -------------------------------------------------------------------


@pytest.fixture(scope="module")
def study_examples(tmp_path_factory) -> list[str]:
    folder = tmp_path_factory.mktemp("examples")
    paths = []
    for seed in (1, 2, 3):
        assert (
            main(
                [
                    "-q",
                    "generate",
                    "study",
                    "--seed",
                    str(seed),
                    "-o",
                    str(folder / str(seed)),
                    "--no-render",
                ]
            )
            == 0
        )
        paths.append(str(folder / str(seed) / "scene.json"))
    return paths


def test_fit_command_writes_the_rules_their_includes_and_the_report(
    capsys, tmp_path, study_examples
):
    out = tmp_path / "fitted" / "study.rules"
    report = tmp_path / "fitted" / "fit.json"
    code, stdout, _ = run(
        capsys, "fit", "study", *study_examples, "-o", str(out), "--report", str(report)
    )
    assert code == 0, stdout
    assert "fitted 21 parameters from 3 examples" in stdout
    assert (out.parent / "catalog" / "indoor.rules").is_file()  # the include, beside it
    assert load_rules(out).name == "study"
    document = json.loads(report.read_text())
    assert document["examples"] == 3 and document["prior"] == 0.5
    parameter = document["parameters"][0]
    assert set(parameter) == {
        "kind",
        "name",
        "at",
        "identified",
        "options",
        "draws",
        "estimate",
        "standard_error",
        "written",
    }
    assert sum(document["parameters"][0]["draws"]) == 3  # Workplace is drawn once a scene
    assert "style bed at indoor.rules:12:1" in document["unidentified"]


def test_fit_command_fits_examples_that_keep_no_derivation(capsys, tmp_path, study_examples):
    bare = []
    for index, path in enumerate(study_examples):
        scene = json.loads(Path(path).read_text())
        scene["derivation"] = []
        bare.append(str(write(tmp_path, f"{index}.json", json.dumps(scene))))
    report = tmp_path / "fit.json"
    code, stdout, _ = run(
        capsys,
        "fit",
        "study",
        *bare,
        "-o",
        str(tmp_path / "out" / "f.rules"),
        "--report",
        str(report),
    )
    assert code == 0, stdout
    document = json.loads(report.read_text())
    assert document["examples"] == 3
    assert (
        document["ambiguous_examples"] == 2 and document["em_iterations"] > 1
    )  # seeds 1 and 2: two derivations
    workplace = document["parameters"][0]
    assert workplace["name"] == "Workplace" and sum(workplace["draws"]) == pytest.approx(3)


def test_fit_command_bad_inputs_are_one_line_errors(capsys, tmp_path, study_examples):
    out = str(tmp_path / "x.rules")
    code, _, err = run(capsys, "fit", "village", study_examples[0], "-o", out)
    assert code == 2
    assert_one_line_error(err, "not a scene of village.rules", "these rules do not have")
    bare = json.loads(Path(study_examples[0]).read_text())
    bare["derivation"] = []
    for thing in bare["objects"]:
        if thing["type"] == "desk":
            thing["type"] = "bed"  # a catalog type the study never makes
            thing["style"] = None  # (a desk's style is none of a bed's: its own error)
    write(tmp_path, "bare.json", json.dumps(bare))
    code, _, err = run(capsys, "fit", "study", str(tmp_path / "bare.json"), "-o", out)
    assert code == 2
    assert_one_line_error(
        err, "bare.json: no derivation of study.rules makes a scene like this one"
    )
    code, _, err = run(capsys, "fit", "study", study_examples[0], "-o", out, "--prior", "0")
    assert code == 2 and "must be above 0" in err
    assert not Path(out).exists()
    own = write(tmp_path, "mine.rules", TRUTH)
    truth_scene = tmp_path / "truth"
    assert main(
        ["-q", "generate", str(own), "--seed", "1", "-o", str(truth_scene), "--no-render"]
    ) in (0, 1)
    code, _, err = run(capsys, "fit", str(own), str(truth_scene / "scene.json"), "-o", str(own))
    assert code == 2
    assert_one_line_error(err, "would overwrite the input")
    assert own.read_text() == TRUTH
