"""Trusted runs: outputs, thread independence, kill-and-resume, agreement with a verify-only run."""

import csv
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import verify
from reports.runs import chunk, driver
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.rundir import RunFailed
from reports.runs.scenes import parse_scene
from reports.runs.survival import wilson

ROOT = Path(__file__).resolve().parents[3]

SMALL = """
name = "small"
kind = "escape"
eps = 0.6
particles = 3000
seed = 11
chunk_size = 1024
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [1.0, 2.5]
widths = [0.3]
[horizon]
collisions = 3000
time = 1e5
"""

TRANSPORT = """
name = "small-transport"
kind = "transport"
eps = 0.6
particles = 2000
seed = 5
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [0.4]
[horizon]
collisions = 300
"""

# big enough to take a few seconds in many chunks: for the kill-and-resume test
SLOW = SMALL.replace("particles = 3000", "particles = 60000").replace(
    "chunk_size = 1024", "chunk_size = 2048").replace("collisions = 3000", "collisions = 100000")


def cli(*args, timeout=300):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run([sys.executable, "-m", "reports.cli", *map(str, args)], cwd=ROOT,
                          env=env, capture_output=True, text=True, timeout=timeout)


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


@pytest.mark.slow
def test_escape_run_outputs(tmp_path):
    scene = parse_scene(SMALL)
    manifest = driver.run(scene, tmp_path / "run", progress=False)
    assert manifest["status"] == "complete"
    ver = manifest["verification"]
    assert set(ver) >= {"sampled", "worst_error", "uncertain_settled", "overstepped"}
    assert ver["sampled"] >= 100 and ver["overstepped"] == 0 and ver["worst_error"] < 16
    for name, curve in manifest["curves"].items():
        assert sum(curve["escaped"].values()) + curve["censored"] == 3000, name
    assert manifest["collisions"] > 3000
    # survival.csv loads with numpy alone and starts at P(0) = 1
    data = np.genfromtxt(tmp_path / "run" / "survival.csv", delimiter=",", names=True,
                         dtype=None, encoding="utf-8")
    assert list(data.dtype.names) == ["curve", "clock", "x", "p", "p_lo", "p_hi"]
    first = data[(data["curve"] == "phi_c=1") & (data["clock"] == "collisions")]
    assert first["x"][0] == 0 and first["p"][0] == 1.0
    assert np.all(np.diff(first["p"]) <= 0) and np.all(first["p_lo"] <= first["p"])
    assert np.all(first["p"] <= first["p_hi"])
    assert not list((tmp_path / "run").glob(".*tmp*"))  # atomic writes leave no temporaries


@pytest.mark.slow
def test_transport_probabilities_sum_to_one(tmp_path):
    manifest = driver.run(parse_scene(TRANSPORT), tmp_path / "t", progress=False)
    by = {(r["curve"], r["clock"]): r for r in reversed(rows(tmp_path / "t" / "survival.csv"))}
    for i, exp in ((1, "from hole 1"), (2, "from hole 2")):
        censored = manifest["curves"][exp]["censored"] / 2000
        total = sum(float(by[f"P{i}{j}", "collisions"]["p"]) for j in (1, 2))
        assert total + censored == pytest.approx(1.0, abs=1e-12)
        total_t = sum(float(by[f"P{i}{j}", "time"]["p"]) for j in (1, 2))
        assert total_t + censored == pytest.approx(1.0, abs=1e-12)


@pytest.mark.slow
def test_results_do_not_depend_on_threads(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    for k in (1, 2):
        res = cli("run", path, "--out", tmp_path / f"t{k}", "--threads", k, "--quiet")
        assert res.returncode == 0, res.stderr
    for name in ("survival.csv", "counts.csv", "sample.csv"):
        assert (tmp_path / "t1" / name).read_bytes() == (tmp_path / "t2" / name).read_bytes()


@pytest.mark.slow
def test_kill_and_resume_gives_the_uninterrupted_result(tmp_path):
    path = tmp_path / "slow.toml"
    path.write_text(SLOW)
    full = cli("run", path, "--out", tmp_path / "full", "--quiet")
    assert full.returncode == 0, full.stderr
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-m", "reports.cli", "run", str(path), "--out",
                             str(tmp_path / "cut"), "--quiet"], cwd=ROOT, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    ckpt = tmp_path / "cut" / "checkpoint.npz"
    deadline = time.monotonic() + 120
    while not ckpt.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    manifest = json.loads((tmp_path / "cut" / "manifest.json").read_text())
    assert manifest["status"] == "partial", "the run finished before it could be killed"
    assert manifest["chunks_done"] < manifest["chunks"]
    assert ckpt.exists()  # killed after its first checkpoint: the resume starts from there
    again = cli("run", path, "--out", tmp_path / "cut")
    assert again.returncode == 2 and "--resume" in again.stderr
    resumed = cli("run", path, "--out", tmp_path / "cut", "--resume", "--quiet")
    assert resumed.returncode == 0, resumed.stderr
    for name in ("survival.csv", "counts.csv", "sample.csv"):
        assert (tmp_path / "full" / name).read_bytes() == (tmp_path / "cut" / name).read_bytes()
    done = json.loads((tmp_path / "cut" / "manifest.json").read_text())
    ref = json.loads((tmp_path / "full" / "manifest.json").read_text())
    assert done["status"] == "complete"
    assert done["collisions"] == ref["collisions"]
    assert done["verification"]["worst_error"] == ref["verification"]["worst_error"]


def test_existing_run_is_not_overwritten_without_force(tmp_path):
    scene = parse_scene(TRANSPORT.replace("particles = 2000", "particles = 50"))
    driver.run(scene, tmp_path / "r", progress=False)
    with pytest.raises(ValueError, match="--force"):
        driver.run(scene, tmp_path / "r", progress=False)
    assert driver.run(scene, tmp_path / "r", force=True, progress=False)["status"] == "complete"
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("keep me")
    with pytest.raises(ValueError, match="not a run directory"):
        driver.run(scene, tmp_path / "other", force=True, progress=False)
    assert (tmp_path / "other" / "notes.txt").read_text() == "keep me"
    with pytest.raises(ValueError, match="same scene"):
        driver.run(scene, tmp_path / "r", particles=60, resume=True, progress=False)


def test_overstep_fails_the_run_loudly(tmp_path, monkeypatch):
    real = chunk.check_sample

    def lying(phi, v, tau, eps):
        tau_ref, error, _ = real(phi, v, tau, eps)
        return tau_ref, error, True

    monkeypatch.setattr(chunk, "check_sample", lying)
    scene = parse_scene(TRANSPORT.replace("particles = 2000", "particles = 50"))
    with pytest.raises(RunFailed, match="OVERSTEP"):
        driver.run(scene, tmp_path / "bad", progress=False)
    manifest = json.loads((tmp_path / "bad" / "manifest.json").read_text())
    assert manifest["status"] == "failed" and manifest["verification"]["overstepped"] > 0


def test_flagged_particles_are_settled_by_verify_and_resume(monkeypatch):
    """Pretend float64 could not decide any first flight: the kernel's first pass flags every
    particle; the driver settles collision 1 with verify and the particles resume in fastpath."""
    scene = parse_scene(SMALL.replace("particles = 3000", "particles = 300"))
    plan = make_plan(scene)
    base, _ = chunk.simulate_chunk(plan, 0, 0)
    real = chunk.escape_chunk
    calls = []

    def undecided_first(physics, starts, *args):
        calls.append(len(starts.phi))
        if len(calls) > 1:
            return real(physics, starts, *args)
        flags = args[-1]
        flags.status[:] = 1  # FlightStatus.UNCERTAIN
        flags.state[:] = np.column_stack(starts)
        return None

    monkeypatch.setattr(chunk, "escape_chunk", undecided_first)
    settled, _ = chunk.simulate_chunk(plan, 0, 0)
    assert settled.settled == 300 and len(calls) == 2
    assert settled.esc_n.sum() + settled.cens_n.sum() == 300
    assert settled.esc_n[0, 0] == base.esc_n[0, 0]  # the settled first collisions agree
    assert settled.collisions == pytest.approx(base.collisions, rel=0.3)
    with pytest.raises(RunFailed, match="could not settle"):
        chunk.settle(0.0, -1.0, 0.6)  # not a departure: verify refuses, the run fails


@pytest.mark.slow
def test_survival_agrees_with_a_verify_only_simulation():
    """400 starts with a wide hole: fast survival P(n) vs an mpmath run of the same starts.

    The trajectories separate after a few tens of collisions (chaos), so the check is
    statistical: the verify-only survival lies in the fast curve's 95% Wilson band widened
    by the slow curve's own band (two estimates of one probability from N starts)."""
    text = SMALL.replace("particles = 3000", "particles = 400").replace(
        "centres = [1.0, 2.5]", "centres = [2.5]").replace("widths = [0.3]", "widths = [1.5]")
    text = text.replace("collisions = 3000", "collisions = 40")
    scene = parse_scene(text)
    plan = make_plan(scene)
    counts, _ = chunk.simulate_chunk(plan, 0, 0)
    phi0, v0, *_ = chunk_starts(plan, 0, 0)
    lo, width = plan.experiments[0].hole_lo[0], 1.5
    slow = np.full(len(phi0), 10**9)
    for i, (phi, v) in enumerate(zip(phi0, v0, strict=True)):
        for n in range(1, 41):
            phi, v, _ = verify.step(float(phi), float(v), 0.6, dps=20)
            phi, v = float(phi), float(v)
            if (phi - lo) % (2 * np.pi) < width:
                slow[i] = n
                break
    fast_escape = counts.esc_n[0]
    for n in (1, 2, 3, 5, 8, 12, 20):
        k = int(np.searchsorted(plan.n_edges, n + 1))  # bins from escape index n+1 on
        fast = int(fast_escape[k:].sum() + counts.cens_n.sum())
        slow_surv = int((slow > n).sum())
        f_lo, f_hi = wilson(fast, 400)
        s_lo, s_hi = wilson(slow_surv, 400)
        width_f, width_s = f_hi - f_lo, s_hi - s_lo
        assert abs(fast - slow_surv) / 400 <= (width_f + width_s) / 2, (n, fast, slow_surv)
