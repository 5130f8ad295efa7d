"""``bouncer sweep``: the escape-rate map over a grid, checked against single runs."""

import csv
import json
import math

import pytest

from reports.cli import main
from reports.runs import driver, sweep
from reports.runs.scenes import parse_scene

BASE = """
name = "sweep-base"
kind = "escape"
eps = 0.6
particles = 100
seed = 23
chunk_size = 256
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.3]
[horizon]
collisions = 1000
"""


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.mark.slow
def test_sweep_map_matches_single_runs(tmp_path):
    base = parse_scene(BASE)
    grid = {"centre": [1.0, 2.5, 4.0], "eps": [0.4, 0.7]}
    manifest = sweep.sweep(base, tmp_path / "s", grid=grid, n_star=25, particles=600,
                           verify_samples=30, progress=False)
    assert manifest["status"] == "complete" and manifest["points"] == 6
    assert manifest["skipped"] == 2  # the hole at 4.0 overlaps the start box
    assert manifest["axes"] == {"centre": [1.0, 2.5, 4.0], "eps": [0.4, 0.7]}
    assert manifest["fixed"] == {"width": 0.3}
    assert manifest["verification"]["sampled"] >= 6
    assert manifest["verification"]["overstepped"] == 0
    out = rows(tmp_path / "s" / "sweep.csv")
    assert [(float(r["eps"]), float(r["centre"])) for r in out] == [
        (e, c) for e in (0.4, 0.7) for c in (1.0, 2.5, 4.0)]  # y outer, x inner
    assert (tmp_path / "s" / "escape-rate.png").stat().st_size > 0
    for r in out:
        if float(r["centre"]) == 4.0:
            assert r["rate"] == "" and "overlaps the hole" in r["note"]
            continue
        # the point as a run of its own: survivors of n* collisions = censored at horizon n*
        text = sweep.point_text(base, float(r["eps"]), float(r["centre"]), 0.3, 25, 600, 5)
        single = driver.run(parse_scene(text), tmp_path / f"p{r['eps']}-{r['centre']}",
                            progress=False)
        survivors = single["curves"][f"phi_c={float(r['centre']):.4g}"]["censored"]
        assert int(r["survivors"]) == survivors
        p = survivors / 600
        assert float(r["p"]) == p and float(r["rate"]) == -math.log(p) / 25
        assert float(r["rate_lo"]) <= float(r["rate"]) <= float(r["rate_hi"])
        assert int(r["collisions"]) == single["collisions"]


def test_one_axis_and_saturated_cells(tmp_path):
    base = parse_scene(BASE)
    manifest = sweep.sweep(base, tmp_path / "w", grid={"width": [0.5, 3.0]}, n_star=400,
                           particles=50, verify_samples=4, progress=False)
    assert manifest["fixed"] == {"eps": 0.6, "centre": 2.0}
    out = rows(tmp_path / "w" / "sweep.csv")
    assert len(out) == 2
    wide = out[1]  # a hole of width 3 at 2.0: nobody survives 400 collisions
    assert wide["survivors"] == "0" and wide["rate"] == "inf"
    assert math.isfinite(float(wide["rate_lo"]))


def test_sweep_cli(tmp_path, capsys):
    path = tmp_path / "base.toml"
    path.write_text(BASE)
    out = tmp_path / "cli"
    assert main(["sweep", str(path), "--centre", "1", "2.5", "2", "--eps", "0.5", "0.6", "2",
                 "--particles", "200", "--n-star", "10", "--verify-samples", "8",
                 "--out", str(out), "--quiet"]) == 0
    assert "4 points (0 skipped)" in capsys.readouterr().out
    assert len(rows(out / "sweep.csv")) == 4
    assert json.loads((out / "manifest.json").read_text())["status"] == "complete"
    assert main(["sweep", str(path), "--centre", "1", "2.5", "2", "--out", str(out)]) == 2
    assert "--force" in capsys.readouterr().err


@pytest.mark.parametrize("args", [
    ["--eps", "0.2", "0.8", "3", "--centre", "0", "1", "2", "--width", "0.1", "0.3", "2"],
    ["--eps", "0.2", "0.8", "0"],
    ["--eps", "0.2", "0.8", "2.5"],
    ["--eps", "0.8", "0.2", "3"],
    ["--n-star", "0"],
    ["--particles", "0"],
    ["--centre", "3.9", "4.1", "2"],  # every point overlaps the start box
])
def test_bad_sweeps_exit_2(args, tmp_path, capsys):
    path = tmp_path / "base.toml"
    path.write_text(BASE)
    assert main(["sweep", str(path), "--out", str(tmp_path / "x"), "--quiet", *args]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bouncer: error: ") and err.count("\n") == 1, err


def test_sweep_needs_an_escape_scene(tmp_path, capsys):
    assert main(["sweep", "paper-transport", "--out", str(tmp_path / "x")]) == 2
    assert "escape scene" in capsys.readouterr().err
