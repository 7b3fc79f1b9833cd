"""Road networks alike are told as one list item from three on, so a city's text does
not list each of its crossroads with its streets."""

from test_describer_e2e import check_true_and_complete, ungrammatical

from scenewright.api import build_scene
from scenewright.describer import describe

NETWORKS = """
scene hamlets { extent 200 x 200 ground grass start T max_depth 6 max_nodes 60 }
path street { noun "street" width 3 max_length 30 segments 2 }
junction crossroads { noun "intersection" size 4 x 0.05 x 4 }
object well { noun "well" size 1.4 x 0.8 x 1.4 shape well }
T -> { N; N; N; well }
N -> { crossroads as x; 2 street PathConnectedTo x }
"""

TWO = NETWORKS.replace("T -> { N; N; N; well }", "T -> { N; N; well }")


def test_three_networks_alike_are_counted_and_two_are_listed(tmp_path):
    three, two = tmp_path / "three.rules", tmp_path / "two.rules"
    three.write_text(NETWORKS)
    two.write_text(TWO)
    for style in ("full", "summary", "short"):
        text = describe(build_scene(three, 1), style=style).text
        assert "six streets meeting two at each of three intersections" in text, text
        assert "another intersection" not in text
    text = describe(build_scene(two, 1), style="full").text
    assert "two more streets meeting at another intersection" in text, text


def test_counted_networks_are_true_and_grammatical(tmp_path):
    three = tmp_path / "three.rules"
    three.write_text(NETWORKS)
    sentences = check_true_and_complete(build_scene(three, 1))
    assert ungrammatical(sentences) == []
