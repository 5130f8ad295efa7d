"""``bouncer fit``: JSON contract, figures, bad input (exit 2, one line, no traceback)."""

import argparse
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from reports.cli import fit as fit_cli
from reports.stats.calibration import draw, grid_edges

ROOT = Path(__file__).resolve().parents[3]
LAW_KEYS = {"exponential": {"gamma", "gamma_ci95", "loglik", "aic"},
            "power_law": {"alpha", "alpha_ci95", "loglik", "aic"},
            "stretched_exponential": {"c", "c_ci95", "beta", "beta_ci95", "loglik", "aic"}}


def write_csv(path, curve):
    """A ``lower,upper,count`` histogram of a synthetic collision-clock curve."""
    edges = grid_edges()
    rows = ["lower,upper,count"]
    for k in range(len(edges) - 1):
        if curve.censored[k]:
            rows.append(f"{edges[k]:g},inf,{curve.censored[k]}")
            break
        rows.append(f"{edges[k]:g},{edges[k + 1]:g},{curve.escapes[k]}")
    path.write_text("\n".join(rows) + "\n")
    return path


def write_run(folder, n=20_000, seed=0):
    """A run directory in the runner's format: one experiment, two outcomes, both clocks."""
    rng = np.random.default_rng(seed)
    folder.mkdir()
    bins = {"collisions": {"first": 1, "decades": 8, "per_decade": 20, "integer": True},
            "time": {"first": 0.1, "decades": 9, "per_decade": 20, "below_first": [0.0, 0.1]}}
    rows = ["experiment,clock,outcome,lower_edge,count"]
    n_edges = np.unique(np.round(10.0 ** (np.arange(161) / 20)))
    t_edges = np.concatenate([[0.0], 0.1 * 10.0 ** (np.arange(181) / 20)])
    n_esc = rng.geometric(0.05, size=n)
    t_esc = n_esc * rng.uniform(1.0, 3.0, size=n)
    hole = rng.random(n) < 0.7
    censored = n_esc > 1000
    for clock, values, edges in (("collisions", n_esc, n_edges), ("time", t_esc, t_edges)):
        for name, mask in (("A", hole & ~censored), ("B", ~hole & ~censored),
                           ("censored", censored)):
            k = np.searchsorted(edges, values[mask], side="right") - 1
            for b, c in zip(*np.unique(k, return_counts=True), strict=True):
                rows.append(f"exp,{clock},{name},{float(edges[b])!r},{c}")
    manifest = {"curves": {"exp": {"particles_done": n, "censored": int(censored.sum()),
                                   "escaped": {"A": int((hole & ~censored).sum()),
                                               "B": int((~hole & ~censored).sum())}}},
                "bins": bins}
    (folder / "manifest.json").write_text(json.dumps(manifest))
    (folder / "counts.csv").write_text("\n".join(rows) + "\n")
    return folder


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "reports.cli", "fit", *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT)


def test_json_contract_for_csv_and_run_directory(tmp_path):
    rng = np.random.default_rng(1)
    csv = write_csv(tmp_path / "h.csv", draw("power_law", 50_000, rng))
    run = write_run(tmp_path / "run")
    proc = run_cli(csv, run, "--json", "--clock", "collisions")
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert [(o["source"], o["curve"]) for o in out] == [(str(csv), "h"), (str(run), "A"),
                                                       (str(run), "B")]
    for o in out:
        assert o["clock"] == "collisions"
        assert o["best"] in (*LAW_KEYS, "inconclusive")
        for law, keys in LAW_KEYS.items():
            assert keys <= set(o["models"][law])
        assert o["window"][0] < o["window"][1]
        assert o["regimes"][-1]["to"] == o["window"][1]
        assert {"exponential", "power_law", "stretched_exponential"} <= set(o["systematic"])
    assert out[0]["particles"] == 50_000 and out[1]["particles"] == 20_000
    assert out[0]["best"] == "power_law"
    lo, hi = out[0]["models"]["power_law"]["alpha_ci95"]
    assert lo <= 1.5 <= hi
    # the run: at each collision a particle leaves through A with probability 0.035, through B
    # with 0.015 (exclusive), so each outcome's cause-specific survival is (1 - q)**n
    for o, q in zip(out[1:], (0.035, 0.015), strict=True):
        lo, hi = o["models"]["exponential"]["gamma_ci95"]
        assert lo <= -np.log(1 - q) <= hi


def test_table_and_figures(tmp_path):
    rng = np.random.default_rng(2)
    csv = write_csv(tmp_path / "h.csv", draw("exponential", 10_000, rng))
    args = argparse.Namespace(paths=[str(csv)], clock="collisions", json=False,
                              out=tmp_path / "figs", jobs=1)
    assert fit_cli.main(args) == 0
    pngs = list((tmp_path / "figs").glob("*.png"))
    assert len(pngs) == 1 and pngs[0].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_add_parser_registers_fit():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    fit_cli.add_parser(sub)
    args = parser.parse_args(["fit", "x.csv", "--json"])
    assert args.func is fit_cli.main and args.json and args.paths == ["x.csv"]


@pytest.mark.parametrize("text, message", [
    (None, "no such file"),
    ("lower,upper\n1,2\n", "header"),
    ("lower,upper,count\n1,2,x\n", "not a number"),
    ("lower,upper,count\n1,2,-3\n", "negative count"),
    ("lower,upper,count\n1,2,3\n2,1.5,3\n", "not increasing"),
    ("lower,upper,count\n1,2,3\n1.5,3,3\n", "not increasing"),
    ("lower,upper,count\n1,2,0\n2,3,0\n3,inf,5\n", "no escapes"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    if text is not None:
        path.write_text(text)
    proc = run_cli(path, "--json")
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0] and "Traceback" not in proc.stderr


def test_run_directory_that_does_not_add_up_is_rejected(tmp_path):
    run = write_run(tmp_path / "run")
    manifest = json.loads((run / "manifest.json").read_text())
    manifest["curves"]["exp"]["particles_done"] += 1
    (run / "manifest.json").write_text(json.dumps(manifest))
    proc = run_cli(run, "--json")
    assert proc.returncode == 2 and "particles_done" in proc.stderr


@pytest.mark.parametrize("kind", ["phase-space", "velocity", "escape"])
def test_run_without_counts_names_its_kind(tmp_path, kind):
    """A phase-space or velocity run records no survival counts: the one-line error says so
    (and where to look instead); a survival run that lost counts.csv still says it is missing."""
    run = tmp_path / "run"
    run.mkdir()
    (run / "manifest.json").write_text(json.dumps({"scene": {"name": "s", "kind": kind}}))
    proc = run_cli(run, "--json")
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    line, = proc.stderr.strip().splitlines()
    assert "no counts.csv" in line
    if kind == "escape":
        assert "survival counts" not in line
    else:
        assert f"a {kind} run has no survival counts to fit" in line and "bouncer plot" in line
