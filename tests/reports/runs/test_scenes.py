"""Scene files: the built-ins load, and every validation error has a clear message."""

import pytest

from reports.runs.scenes import builtin_scenes, load_scene, parse_scene

ESCAPE = """
name = "t"
kind = "escape"
eps = 0.6
particles = 100
seed = 1
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [0.0, 2.5]
widths = [0.3]
[horizon]
collisions = 100
time = 1000.0
"""

TRANSPORT = """
name = "t"
kind = "transport"
eps = 0.6
particles = 100
seed = 1
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [0.4, 1.0]
[horizon]
collisions = 100
"""


def test_builtins_load():
    names = set(builtin_scenes())
    assert {"paper-escape", "paper-transport", "paper-phase-space"} <= names
    esc = load_scene("paper-escape")
    assert [e.name for e in esc.experiments()] == [
        "phi_c=0", "phi_c=0.5", "phi_c=1", "phi_c=1.5", "phi_c=2", "phi_c=2.5"]
    assert esc.eps == 0.6 and esc.start_phi == (3.85, 4.15) and esc.hole_widths == (0.3,)
    tr = load_scene("paper-transport")
    assert tr.hole_widths == (0.1, 0.4, 1.0, 2.2)
    assert tr.experiments()[0].curves == ("h=0.1/P11", "h=0.1/P12")
    assert load_scene("paper-phase-space").kind == "phase-space"


def test_valid_examples_parse():
    assert len(parse_scene(ESCAPE).experiments()) == 2
    exps = parse_scene(TRANSPORT).experiments()
    assert [e.curves for e in exps][:2] == [("h=0.4/P11", "h=0.4/P12"), ("h=0.4/P21", "h=0.4/P22")]
    assert exps[0].phi == (-0.2, 0.2)


def test_scene_from_file(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text(ESCAPE)
    assert load_scene(path).name == "t"
    with pytest.raises(ValueError, match="no scene"):
        load_scene(tmp_path / "missing.toml")


BAD = [
    (ESCAPE.replace('seed = 1', 'seed = 1\ncolour = "red"'), "unknown key.*colour"),
    (ESCAPE.replace("v = [2.0, 4.0]", "v = [2.0, 4.0]\nw = 1"), r"unknown key.*\[start\].*w"),
    (ESCAPE.replace("widths = [0.3]", "widths = [0.0]"), r"width must be in \(0, 2\*pi\)"),
    (ESCAPE.replace("widths = [0.3]", "widths = [-1.0]"), r"width must be in \(0, 2\*pi\)"),
    (ESCAPE.replace("widths = [0.3]", "widths = [6.3]"), r"width must be in \(0, 2\*pi\)"),
    (ESCAPE.replace("phi = [3.85, 4.15]", "phi = [4.15, 3.85]"), "is empty"),
    (ESCAPE.replace("v = [2.0, 4.0]", "v = [2.0, 2.0]"), "is empty"),
    (ESCAPE.replace("v = [2.0, 4.0]", "v = [0.1, 4.0]"), "non-departures"),
    (ESCAPE.replace("centres = [0.0, 2.5]", "centres = [4.0]"), "overlaps the hole"),
    (ESCAPE.replace("centres = [0.0, 2.5]", "centres = [10.2]"), "overlaps the hole"),
    (ESCAPE.replace("collisions = 100\ntime = 1000.0", ""), "needs collisions and/or time"),
    (ESCAPE.replace("collisions = 100", "collisions = 0"), "horizon.collisions must be >= 1"),
    (ESCAPE.replace("collisions = 100", "collisions = 1.5"), "must be an integer"),
    (ESCAPE.replace("time = 1000.0", "time = -1.0"), r"horizon.time must be in \(0, 1e8\]"),
    (ESCAPE.replace("time = 1000.0", "time = inf"), "must be finite"),
    (ESCAPE.replace('kind = "escape"', 'kind = "billiard"'), "kind must be one of"),
    (ESCAPE.replace("eps = 0.6", "eps = nan"), "eps must be finite"),
    (ESCAPE.replace("eps = 0.6", 'eps = "big"'), "eps must be a number"),
    (ESCAPE.replace("particles = 100", "particles = 0"), "particles must be >= 1"),
    (ESCAPE.replace("seed = 1", "seed = -3"), "seed must be >= 0"),
    (ESCAPE.replace('name = "t"', ""), "name must be a non-empty string"),
    (ESCAPE.replace("centres = [0.0, 2.5]", "centres = []"), "non-empty list"),
    (ESCAPE + '[record]\nclocks = ["steps"]\n', "record.clocks"),
    (ESCAPE + "[record]\nbins_per_decade = 0\n", "bins_per_decade must be >= 1"),
    (ESCAPE + "[record]\nphi_bins = 10\n", "belong to phase-space"),
    (ESCAPE.replace("phi = [3.85, 4.15]", "phi = [0.0, 7.0]"), "spans"),
    (TRANSPORT.replace("v = [2.0, 4.0]", "v = [2.0, 4.0]\nphi = [0.0, 1.0]"),
     "start.phi is not used"),
    (TRANSPORT.replace("widths = [0.4, 1.0]", "widths = [3.5]"), "overlap"),
    (TRANSPORT.replace("v = [2.0, 4.0]", "v = [0.2, 4.0]"), "non-departures"),
    ("name = 'x'\nkind = 'phase-space'\neps = 0.6\nparticles = 1\nseed = 0\n"
     "[start]\nphi = [0.0, 6.0]\nv = [1.0, 5.0]\n[horizon]\ntime = 5.0\n",
     "horizon.collisions only"),
    ("not toml = = 1", "not valid TOML"),
    ("start = 3\n" + ESCAPE.replace("[start]\nphi = [3.85, 4.15]\nv = [2.0, 4.0]\n", ""),
     r"\[start\] must be a table"),
]


@pytest.mark.parametrize(("text", "message"), BAD)
def test_invalid_scenes_are_rejected_with_a_message(text, message):
    with pytest.raises(ValueError, match=message) as info:
        parse_scene(text, origin="test.toml")
    assert str(info.value).startswith("test.toml: ")
    assert "\n" not in str(info.value)


def test_scene_is_frozen():
    scene = parse_scene(ESCAPE)
    with pytest.raises(AttributeError):
        scene.eps = 1.0
