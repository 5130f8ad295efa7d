"""``bouncer orbits``: find and certify periodic orbits from the shell; JSON; bad input."""

import json
import math
import subprocess
import sys

import pytest

from reports.cli import main


def run_cli(capsys, *args):
    code = main(["orbits", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_fixed_point_found_and_certified_as_json(capsys):
    code, out, err = run_cli(capsys, "0.01", "3.15", "--eps", "0.3", "--certify", "--json")
    assert code == 0 and err == ""
    data = json.loads(out)
    assert data["winding"] == 1
    assert abs(data["v"][0] - math.pi) < 1e-12
    assert abs(data["residue"] - 0.3) < 1e-12
    lo, hi = (float(x) for x in data["certified"]["residue"])
    assert lo <= 0.3 <= hi or abs(lo - 0.3) < 1e-15
    assert data["certified"]["stability"] == "elliptic"


def test_period_two_orbit_table(capsys):
    code, out, _ = run_cli(capsys, "1.03", "2.11", "--eps", "1.2", "--period", "2")
    assert code == 0
    assert "period 2" in out and "hyperbolic" in out


def test_accelerator_block(capsys):
    code, out, _ = run_cli(capsys, "4.9", "12.57", "--eps", "1.6", "--shift", "1", "--json",
                           "--certify")
    data = json.loads(out)
    assert code == 0 and data["velocity_shift"] == 1
    assert data["certified"]["stability"] == "elliptic"


@pytest.mark.parametrize("args", [
    ["0", "nan", "--eps", "0.3"],
    ["0", "-1", "--eps", "0.3"],
    ["0", "3.14", "--eps", "0.3", "--period", "0"],
    ["0", "3.14", "--eps", "0.3", "--model", "holmes", "--certify"],
    ["0", "3.14", "--eps", "0.3", "--certify", "--dps", "5"],
])
def test_bad_input_exits_2_with_one_line(capsys, args):
    code, out, err = run_cli(capsys, *args)
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("bouncer: error:")


def test_no_orbit_exits_1_with_one_line(capsys):
    code, out, err = run_cli(capsys, "0", "3.14", "--eps", "0.0")
    assert code == 1 and out == ""
    assert err.count("\n") == 1


@pytest.mark.slow
def test_command_line_entry_point_runs_without_a_traceback():
    done = subprocess.run([sys.executable, "-m", "reports.cli", "orbits", "0", "x", "--eps",
                           "0.3"], capture_output=True, text=True)
    assert done.returncode == 2
    assert "Traceback" not in done.stderr


@pytest.mark.parametrize("eps,period", [("0.6", "2"), ("0.6", "3"), ("1.5", "2")])
def test_a_fixed_point_asked_at_a_longer_period_prints_its_minimal_period(capsys, eps, period):
    code, out, err = run_cli(capsys, "0", "3.141592653589793", "--eps", eps, "--period",
                             period, "--certify")
    assert code == 0 and err == ""
    assert "periodic orbit: period 1," in out
    assert f"asked for period {period}" in out
    assert "minimal period 1," in out


def test_a_one_off_shifted_block_exits_1_with_one_line(capsys):
    code, out, err = run_cli(capsys, "3.8980936554827061", "60.422221713212743", "--eps", "1.05",
                             "--period", "2", "--shift", "1", "--certify")
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and "accelerator mode" in err
