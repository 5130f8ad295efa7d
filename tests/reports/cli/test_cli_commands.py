"""The ``bouncer`` command: exit status 0 ok, 2 bad input (one line, no traceback), 1 failure."""

import csv
import json

import pytest

from reports.cli import main

TINY = """
name = "tiny"
kind = "transport"
eps = 0.6
particles = 200
seed = 3
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [1.0]
[horizon]
collisions = 200
"""


@pytest.fixture
def tiny_run(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(TINY)
    assert main(["run", str(path), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    return tmp_path / "run"


def one_line_error(capsys):
    err = capsys.readouterr().err
    assert err.startswith("bouncer: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


def test_scenes_lists_the_builtins(capsys):
    assert main(["scenes"]) == 0
    out = capsys.readouterr().out
    assert "paper-escape" in out and "paper-transport" in out and "paper-phase-space" in out


@pytest.mark.slow
def test_run_plot_verify(tiny_run, capsys):
    assert json.loads((tiny_run / "manifest.json").read_text())["status"] == "complete"
    assert main(["plot", str(tiny_run)]) == 0
    assert (tiny_run / "survival.png").stat().st_size > 0
    assert main(["plot", str(tiny_run), "--fit", "exponential", "--window", "1", "20",
                 "--clock", "collisions"]) == 0
    assert "exponential (gamma = " in capsys.readouterr().out  # bouncer fit's likelihood
    assert main(["plot", str(tiny_run), "--fit", "regimes", "--clock", "collisions"]) == 0
    assert "late regime, best" in capsys.readouterr().out
    assert main(["verify", str(tiny_run)]) == 0
    assert "OK" in capsys.readouterr().out


def test_verify_catches_a_tampered_sample(tiny_run, capsys):
    path = tiny_run / "sample.csv"
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    rows[0]["tau"] = repr(float(rows[0]["tau"]) * (1 + 1e-9))  # a jump past the collision
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    assert main(["verify", str(tiny_run)]) == 1
    out = capsys.readouterr().out
    assert "OVERSTEP" in out and "FAILED" in out


@pytest.mark.parametrize("args", [
    ["run", "no-such-scene"],
    ["run", "paper-escape", "--particles", "0", "--out", "{tmp}/x"],
    ["run", "paper-escape", "--threads", "99", "--out", "{tmp}/x"],
    ["run", "paper-escape", "--seed", "-1", "--out", "{tmp}/x"],
    ["run", "paper-escape", "--resume", "--out", "{tmp}/x"],
    ["plot", "{tmp}"],
    ["verify", "{tmp}"],
])
def test_bad_input_exits_2_with_one_line(args, tmp_path, capsys):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in args]
    assert main(argv) == 2
    one_line_error(capsys)


def test_invalid_scene_file_exits_2(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(TINY.replace("widths = [1.0]", "widths = [0.0]"))
    assert main(["run", str(path), "--out", str(tmp_path / "r")]) == 2
    assert "width must be in (0, 2*pi)" in one_line_error(capsys)


def test_existing_run_dir_exits_2_and_force_overwrites(tiny_run, capsys):
    capsys.readouterr()
    scene = tiny_run.parent / "tiny.toml"
    assert main(["run", str(scene), "--out", str(tiny_run), "--quiet"]) == 2
    assert "--force" in one_line_error(capsys)
    assert main(["run", str(scene), "--out", str(tiny_run), "--quiet", "--force"]) == 0
    assert main(["run", str(scene), "--out", str(tiny_run), "--quiet", "--resume"]) == 0
    assert json.loads((tiny_run / "manifest.json").read_text())["status"] == "complete"


def test_failure_exits_1(tmp_path, monkeypatch, capsys):
    from reports.runs import chunk

    real = chunk.check_sample
    monkeypatch.setattr(chunk, "check_sample", lambda *a: (*real(*a)[:2], True))
    path = tmp_path / "tiny.toml"
    path.write_text(TINY)
    assert main(["run", str(path), "--out", str(tmp_path / "run"), "--quiet"]) == 1
    assert "OVERSTEP" in capsys.readouterr().err


def test_version(capsys):
    from importlib import metadata

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out == f"bouncer {metadata.version('bouncer-verify')}\n"


def test_every_subcommand_and_option_has_a_help_line():
    import argparse

    from reports.cli import SUBCOMMANDS, build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {c.dest: c.help for c in sub._choices_actions}
    assert sorted(sub.choices) == sorted(SUBCOMMANDS)
    missing = [f"{name} {a.option_strings or a.dest}" for name, sp in sub.choices.items()
               for a in sp._actions if not a.help] + [n for n in sub.choices if not helps[n]]
    assert missing == []
    assert all(a.help for a in parser._actions)


@pytest.mark.parametrize("command", ["run", "report"])
@pytest.mark.parametrize("text, value", [("1e6", 10**6), ("2000", 2000), ("2.5e3", 2500)])
def test_particles_takes_integers_written_as_floats(command, text, value):
    from reports.cli import build_parser

    argv = [command, "paper-escape", "--particles", text] if command == "run" else \
        [command, "--particles", text]
    assert build_parser().parse_args(argv).particles == value


def test_the_default_run_directory_stays_under_runs(tmp_path, monkeypatch, capsys):
    """runs/NAME through a symbolic link to another folder is refused, and nothing is written
    there."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "tiny.toml").write_text(TINY)
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "runs").mkdir()
    (tmp_path / "runs" / "tiny").symlink_to(tmp_path / "elsewhere")
    assert main(["run", "tiny.toml", "--quiet"]) == 2
    assert "resolves to" in one_line_error(capsys) and not any((tmp_path / "elsewhere").iterdir())
    (tmp_path / "runs" / "tiny").unlink()
    assert main(["run", "tiny.toml", "--quiet"]) == 0
    assert (tmp_path / "runs" / "tiny" / "manifest.json").is_file()
