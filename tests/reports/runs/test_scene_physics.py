"""The optional [physics] table of a scene: restitution, drag, drag_law."""

import hashlib
import re

import pytest

from reports.cli import main
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
centres = [0.0]
widths = [0.3]
[horizon]
collisions = 100
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
widths = [1.0]
[horizon]
collisions = 100
"""

PORTRAIT = """
name = "t"
kind = "phase-space"
eps = 0.6
particles = 10
seed = 1
[start]
phi = [0.0, 6.0]
v = [2.0, 4.0]
[horizon]
collisions = 100
"""

@pytest.mark.parametrize("text", [ESCAPE, TRANSPORT])
def test_physics_table_parses_for_escape_and_transport(text):
    physics = '[physics]\nrestitution = 0.9\ndrag = 0.01\ndrag_law = "quadratic"\n'
    scene = parse_scene(text + physics)
    assert (scene.restitution, scene.drag, scene.drag_law) == (0.9, 0.01, "quadratic")
    assert not scene.elastic
    assert scene.physics() == {"drag": 0.01, "drag_law": "quadratic", "restitution": 0.9}


@pytest.mark.parametrize("physics", ["restitution = 0.9", "drag = 0.01",
                                     'drag = 0.0\nrestitution = 0.5'])
def test_a_phase_space_scene_refuses_dissipation_when_parsed(physics):
    """The portrait kernel is elastic: a dissipative phase-space scene is refused by the scene
    check, before a run starts, not accepted and refused later by the run."""
    with pytest.raises(ValueError, match=r"^s: a phase-space scene with \[physics\]") as err:
        parse_scene(PORTRAIT + f"[physics]\n{physics}\n", "s")
    assert str(err.value).endswith("needs a dissipative portrait kernel, which fastpath does not"
                                   " have; escape and transport scenes take [physics]")
    assert parse_scene(PORTRAIT + '[physics]\nrestitution = 1.0\ndrag = 0.0\n').elastic


@pytest.mark.parametrize("text", [ESCAPE, TRANSPORT, PORTRAIT])
def test_no_physics_table_is_the_elastic_model(text):
    scene = parse_scene(text)
    assert (scene.restitution, scene.drag, scene.drag_law) == (1.0, 0.0, "linear")
    assert scene.elastic and scene.physics() == {}
    # the defaults written out are the same scene (source aside)
    same = parse_scene(text + '[physics]\nrestitution = 1.0\ndrag = 0.0\ndrag_law = "linear"\n')
    assert same == scene and same.elastic


def test_builtin_scenes_unchanged_by_physics():
    """The elastic built-ins keep their text (hence run hashes) and parse to the elastic model."""
    for name, text in builtin_scenes().items():
        scene = load_scene(name)
        assert scene.source == text
        if "[physics]" not in text:
            assert scene.elastic and scene.physics() == {}, name
    for name, sha in ELASTIC_BUILTINS_SHA256.items():
        assert hashlib.sha256(builtin_scenes()[name].encode()).hexdigest() == sha, name


# sha256 of the elastic built-ins' files: their text is part of every run's hashes, so a change
# must be deliberate (and the committed runs made again from the new text)
ELASTIC_BUILTINS_SHA256 = {
    "paper-escape": "3526d2d9b6db6763d9d83cf8db63510ea928025928196028a73abd0cdf5815d4",
    "paper-transport": "4c9b8f4dddf61a1e8853d753132a9c8b9c07f09c573c620d3fefe3a97bd8cb3d",
    "paper-phase-space": "ebf284f10897c5097543a3504d7e92354a491c1b64f1273162d471e18a9ea727",
}

BAD = [
    ("restitution = 1.5", r"physics.restitution must be in \(0, 1\], got restitution=1.5"),
    ("restitution = 0.0", r"physics.restitution must be in \(0, 1\], got restitution=0.0"),
    ("restitution = -0.5", r"physics.restitution must be in \(0, 1\], got restitution=-0.5"),
    ("restitution = nan", "physics.restitution must be finite, got nan"),
    ("restitution = inf", "physics.restitution must be finite, got inf"),
    ('restitution = "0.9"', "physics.restitution must be a number, got '0.9'"),
    ("restitution = true", "physics.restitution must be a number, got True"),
    ("drag = -0.1", r"physics.drag must be >= 0, got drag=-0.1"),
    ("drag = inf", "physics.drag must be finite, got inf"),
    ("drag = nan", "physics.drag must be finite, got nan"),
    ('drag_law = "cubic"',
     "physics.drag_law must be one of linear, quadratic, got drag_law='cubic'"),
    ("drag_law = 2", "physics.drag_law must be one of linear, quadratic, got drag_law=2"),
    ("friction = 0.1", r"unknown key\(s\) in \[physics\]: friction"),
]


@pytest.mark.parametrize(("line", "message"), BAD)
def test_bad_physics_is_rejected_naming_the_value(line, message):
    with pytest.raises(ValueError, match=message):
        parse_scene(ESCAPE + "[physics]\n" + line + "\n")


def test_physics_must_be_a_table():
    with pytest.raises(ValueError, match=r"\[physics\] must be a table"):
        parse_scene('physics = 0.9\n' + ESCAPE)


@pytest.mark.parametrize(("line", "message"), BAD[:3] + BAD[7:8] + BAD[10:11])
def test_cli_bad_physics_exits_2_with_one_line(line, message, tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(ESCAPE + "[physics]\n" + line + "\n")
    assert main(["run", str(path), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bouncer: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    assert str(path) in err
    assert re.search(message, err), err
    assert not (tmp_path / "r").exists()
