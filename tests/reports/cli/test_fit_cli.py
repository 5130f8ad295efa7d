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


BINS = {"collisions": {"first": 1, "decades": 8, "per_decade": 20, "integer": True},
        "time": {"first": 0.1, "decades": 9, "per_decade": 20, "below_first": [0.0, 0.1]}}


def manifest_of(kind, curves, particles):
    """A manifest of the runner's schema (``reports.runs.manifest.SCHEMA``) with these curves:
    what ``bouncer fit`` reads of it are the curves and the bins."""
    return {"status": "complete",
            "scene": {"name": "synthetic", "kind": kind, "file": "scene.toml", "eps": 0.6,
                      "horizon": {"collisions": 1000, "time": None}},
            "seed": 0, "particles": particles, "particles_total": particles * len(curves),
            "chunk_size": 65536, "chunks": len(curves), "chunks_done": len(curves),
            "collisions": 0,
            "verification": {"sampled": 0, "worst_error": 0.0, "uncertain_settled": 0,
                             "overstepped": 0, "error_unit": "kappa * u",
                             "overstep_tolerance": 16.0, "verify_dps": 30},
            "curves": curves, "bins": BINS, "survival_band": "95% Wilson score interval",
            "hashes": {}}


def write_run(folder, n=20_000, seed=0):
    """A run directory in the runner's format: one experiment, two outcomes, both clocks."""
    rng = np.random.default_rng(seed)
    folder.mkdir()
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
    manifest = manifest_of("escape", {"exp": {
        "particles_done": n, "censored": int(censored.sum()), "stuck": 0,
        "escaped": {"A": int((hole & ~censored).sum()), "B": int((~hole & ~censored).sum())}}}, n)
    (folder / "manifest.json").write_text(json.dumps(manifest))
    (folder / "counts.csv").write_text("\n".join(rows) + "\n")
    return folder


def run_cli(*args):
    return subprocess.run([sys.executable, "-m", "reports.cli", "fit", *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT)


@pytest.mark.slow
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


@pytest.mark.slow
def test_table_and_figures(tmp_path):
    rng = np.random.default_rng(2)
    csv = write_csv(tmp_path / "h.csv", draw("exponential", 10_000, rng))
    args = argparse.Namespace(paths=[str(csv)], clock="collisions", json=False,
                              out=tmp_path / "figs", jobs=1)
    assert fit_cli.main(args) == 0
    pngs = list((tmp_path / "figs").glob("*.png"))
    assert len(pngs) == 1 and pngs[0].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.slow
def test_figures_of_a_run_go_beside_it_never_into_it(tmp_path):
    """The run directory holds what its manifest records: the PNGs go to RUN_DIR-fit beside
    it (or to --out)."""
    run = write_run(tmp_path / "run", n=2000)
    before = sorted(p.name for p in run.iterdir())
    args = argparse.Namespace(paths=[str(run)], clock="collisions", json=False, out=None,
                              jobs=1)
    assert fit_cli.main(args) == 0
    assert sorted(p.name for p in run.iterdir()) == before
    pngs = sorted(p.name for p in (tmp_path / "run-fit").iterdir())
    assert pngs == ["fit-A-collisions.png", "fit-B-collisions.png"]  # no experiment repeated


def test_add_parser_registers_fit():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers()
    fit_cli.add_parser(sub)
    args = parser.parse_args(["fit", "x.csv", "--json"])
    assert args.func is fit_cli.main and args.json and args.paths == ["x.csv"]


@pytest.mark.slow
@pytest.mark.parametrize("text, message", [
    (None, "no such file"),
    ("lower,upper\n1,2\n", "header"),
    ("lower,upper,count\n1,2,x\n", "not a number"),
    ("lower,upper,count\n1,2,-3\n", "negative count"),
    ("lower,upper,count\n1,2,3\n2,1.5,3\n", "not increasing"),
    ("lower,upper,count\n1,2,3\n1.5,3,3\n", "not increasing"),
    ("lower,upper,count\n1,2,0\n2,3,0\n3,inf,5\n", "no escapes"),
    ("lower,upper,count\n0,1,1e300\n1,2,5\n", "count 1e300 is above 2**53"),
    ("lower,upper,count\n0,1,9223372036854775807\n1,2,5\n", "is above 2**53"),
    ("lower,upper,count\n0,1,4503599627370496\n1,2,4503599627370497\n",
     "add up to more than 2**53"),
    ("lower,upper,count\n1e300,1.5e300,10\n1.5e300,1.7e300,5\n", "outside [0, 2**53]"),
    ("lower,upper,count\n-5,1,10\n1,2,5\n", "outside [0, 2**53]"),
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


@pytest.mark.slow
@pytest.mark.parametrize("edit, field", [
    (lambda m: m.__setitem__("bins", []), "field bins"),
    (lambda m: m["curves"]["exp"].__setitem__("particles_done", "20000"), "field curves.exp"),
    (lambda m: [1, 2, 3], "is not of type 'object'"),
])
def test_run_directory_with_a_malformed_manifest_is_one_line(tmp_path, edit, field):
    run = write_run(tmp_path / "run", n=200)
    manifest = json.loads((run / "manifest.json").read_text())
    manifest = edit(manifest) or manifest
    (run / "manifest.json").write_text(json.dumps(manifest))
    proc = run_cli(run, "--json")
    assert proc.returncode == 2 and proc.stdout == "" and "Traceback" not in proc.stderr
    line, = proc.stderr.strip().splitlines()
    assert f"{run / 'manifest.json'}: " in line and field in line


@pytest.mark.slow
def test_run_directory_that_does_not_add_up_is_rejected(tmp_path):
    run = write_run(tmp_path / "run")
    manifest = json.loads((run / "manifest.json").read_text())
    manifest["curves"]["exp"]["particles_done"] += 1
    (run / "manifest.json").write_text(json.dumps(manifest))
    proc = run_cli(run, "--json")
    assert proc.returncode == 2 and "particles_done" in proc.stderr


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["phase-space", "velocity", "escape"])
def test_run_without_counts_names_its_kind(tmp_path, kind):
    """A phase-space or velocity run records no survival counts: the one-line error says so
    (and where to look instead); a survival run that lost counts.csv still says it is missing."""
    run = tmp_path / "run"
    run.mkdir()
    curve = ({"particles_done": 5, "moving": 5, "stuck": 0, "mean_v_at_horizon": 3.0}
             if kind == "velocity" else
             {"particles_done": 5, "censored": 5, "stuck": 0, "escaped": {}})
    (run / "manifest.json").write_text(json.dumps(manifest_of(kind, {"c": curve}, 5)))
    proc = run_cli(run, "--json")
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    line, = proc.stderr.strip().splitlines()
    assert "no counts.csv" in line
    if kind == "escape":
        assert "survival counts" not in line
    else:
        assert f"a {kind} run has no survival counts to fit" in line and "bouncer plot" in line
