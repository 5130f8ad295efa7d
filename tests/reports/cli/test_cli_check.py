"""``bouncer check``: exit 0 when every property holds, 1 when one fails (with the smallest
failing input), 2 for bad input with a one-line message and no traceback."""

import argparse
import os
import pathlib
import subprocess
import sys

import pytest

from reports.cli.check import add_parser, check_command, main

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.mark.slow
def test_fastpath_passes(capsys):
    code = main(["check", "fastpath:flight_time", "--step", "fastpath:step", "--suite", "fast"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "all properties hold" in out
    assert out.count("PASS") == 6


@pytest.mark.slow
def test_planted_defect_fails_with_smallest_input(capsys):
    code = main(["check", "examples.planted_defects:biased_flight_time", "--suite", "accuracy"])
    out = capsys.readouterr().out
    assert code == 1
    assert "FAIL  accuracy" in out
    assert "smallest failing input" in out
    assert "accuracy: examples.planted_defects:biased_flight_time at phi=" in out


@pytest.mark.slow
def test_file_path_and_options(capsys):
    code = main(["check", "examples/planted_defects.py:holmes_flight_time", "--suite",
                 "fixed_points", "--max-examples", "7", "--seed", "5", "-k", "4"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "k = 4, seed 5, up to 7 inputs" in out


@pytest.mark.slow
@pytest.mark.parametrize(
    "argv, text",
    [
        (["check", "no_such_module_xyz:f"], "cannot import module 'no_such_module_xyz'"),
        (["check", "math:pi"], "is not callable"),
        (["check", "math:nothing_here"], "has no attribute"),
        (["check", "fastpath"], "expected MODULE:FUNCTION"),
        (["check", "fastpath:flight_time", "--suite", "bogus"], "unknown suite 'bogus'"),
        (["check", "fastpath:flight_time", "--suite", "energy"], "needs --step"),
        (["check", "fastpath:flight_time", "--step", "math:nothing"], "has no attribute"),
        (["check", "fastpath:flight_time", "--max-examples", "0"], "--max-examples"),
        (["check", "fastpath:flight_time", "--budget", "0"], "--budget"),
        (["check", "fastpath:flight_time", "--call-timeout", "-1"], "--call-timeout"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, text, capsys):
    code = main(argv)
    captured = capsys.readouterr()
    assert code == 2
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("bouncer: error: ")
    assert text in lines[0]
    assert "Traceback" not in captured.err + captured.out


def test_parser_builder_composes_with_other_subcommands():
    parser = argparse.ArgumentParser(prog="bouncer")
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("demo")
    add_parser(sub)
    args = parser.parse_args(["check", "m:f", "--step", "m:g", "--suite", "fast"])
    assert args.func is check_command
    assert (args.target, args.step, args.suite, args.seed, args.k) == ("m:f", "m:g", "fast", 0, 16)


@pytest.mark.slow
def test_users_own_file_in_the_current_directory(tmp_path):
    """A fresh process in the user's directory: their module imports, exit 1, no traceback."""
    (tmp_path / "mysolver.py").write_text(
        "def flight_time(phi, v, eps):\n    return 2.0 * v  # Holmes\n"
    )
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    run = subprocess.run(
        [sys.executable, "-m", "reports.cli", "check", "mysolver:flight_time",
         "--suite", "accuracy", "--max-examples", "20"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300,
    )
    assert run.returncode == 1, run.stderr
    assert "FAIL  accuracy" in run.stdout
    assert "Traceback" not in run.stderr
    bad = subprocess.run(
        [sys.executable, "-m", "reports.cli", "check", "mysolver:nope"],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=300,
    )
    assert bad.returncode == 2
    assert bad.stderr.strip() == "bouncer: error: module 'mysolver' has no attribute 'nope'"


@pytest.mark.slow
def test_budget_spent_exits_3_with_counts_and_progress_on_stderr(capsys):
    code = main(["check", "examples.planted_defects:slow_flight_time", "--suite", "fast",
                 "--budget", "4"])
    captured = capsys.readouterr()
    assert code == 3, captured.out
    assert "INCONCLUSIVE" in captured.out and "inputs when the budget ran out" in captured.out
    assert "bouncer check: no_overstep (20 inputs) ..." in captured.err  # stderr is no tty here


@pytest.mark.slow
def test_a_hang_exits_1_naming_the_input(capsys):
    code = main(["check", "examples.planted_defects:hanging_flight_time", "--suite",
                 "accuracy", "--call-timeout", "0.5", "--no-progress"])
    captured = capsys.readouterr()
    assert code == 1
    assert "did not return within the call timeout of 0.5 s" in captured.out
    assert "accuracy: examples.planted_defects:hanging_flight_time at phi=" in captured.out
    assert captured.err == ""


WRONG_SOLVER = "def flight_time(phi, v, eps):\n    return 2.0 * v\n"


@pytest.mark.parametrize(
    "ending, text",
    [
        ("import sys\nprint('script output')\nsys.exit(0)\n", "called sys.exit(0)"),
        ("import sys\nsys.exit(3)\n", "called sys.exit(3)"),
        ("import os\nos._exit(0)\n", "died (exit code 0) while importing script_style"),
        ("raise SystemExit('done')\n", "called sys.exit('done')"),
    ],
    ids=["sys.exit(0)", "sys.exit(3)", "os._exit(0)", "SystemExit"],
)
def test_a_module_that_exits_while_importing_is_bad_input_not_a_pass(ending, text, tmp_path,
                                                                      monkeypatch, capsys):
    """A wrong solver in a script ending with an exit is never judged as passing: the exit is
    the module's, nothing was checked, exit status 2 with one line."""
    (tmp_path / "script_style.py").write_text(WRONG_SOLVER + ending)
    monkeypatch.chdir(tmp_path)
    code = main(["check", "script_style:flight_time", "--suite", "fixed_points",
                 "--no-progress"])
    captured = capsys.readouterr()
    assert code == 2
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("bouncer: error: ")
    assert text in lines[0]
    assert "all properties hold" not in captured.out


def test_a_call_that_exits_fails_its_property(tmp_path, monkeypatch, capsys):
    (tmp_path / "exits.py").write_text(
        "import sys\ndef flight_time(phi, v, eps):\n    sys.exit(0)\n")
    monkeypatch.chdir(tmp_path)
    code = main(["check", "exits:flight_time", "--suite", "fixed_points", "--no-progress"])
    out = capsys.readouterr().out
    assert code == 1
    assert "FAIL  fixed_points" in out and "SystemExit" in out


def test_a_check_that_does_not_finish_exits_1_with_one_line(monkeypatch, capsys):
    import verify.check

    def broken(*args, **kwargs):
        raise RuntimeError("lost the worker's answer")

    monkeypatch.setattr(verify.check, "check_integrator", broken)
    code = main(["check", "fastpath:flight_time", "--no-progress"])
    captured = capsys.readouterr()
    assert code == 1
    assert captured.err == ("bouncer: error: the check did not finish: RuntimeError: lost the"
                            " worker's answer\n")
    assert captured.out == ""
