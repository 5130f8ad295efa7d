"""Velocity scenes (kind "velocity"): <v_n> through the run engine, exact and deterministic."""

import json
import math
import random
import shutil
from pathlib import Path

import numpy as np
import pytest
from scene_texts import SMALL_VELOCITY as SMALL

import fastpath
from fastpath import moments
from reports.cli import main
from reports.runs import driver, executor
from reports.runs.chunk import run_chunk
from reports.runs.counts import Tally
from reports.runs.plan import chunk_starts, make_plan
from reports.runs.recheck import recheck
from reports.runs.rundir import RunInterrupted
from reports.runs.scenes import load_scene, parse_scene
from reports.runs.velocity import file_problems, velocity_text

U = 2.0**-53


# |eps| <= 1 and r = 0.5: the impacts accumulate and particles stick to the plate for good
STICKY = SMALL.replace("eps = 2.0", "eps = 0.6").replace("[1.0, 0.9]", "[0.5]")


def _csv(path):
    return Path(path).read_text(encoding="utf-8")


def _fresh(text):
    """The scene parsed again (its own object: run() compares stored and given scenes)."""
    return parse_scene(text)


@pytest.fixture(scope="module")
def small_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("velocity") / "run"
    manifest = driver.run(_fresh(SMALL), out, progress=False)
    return out, manifest


def test_builtin_scene_is_the_studys_eps_and_a_velocity_kind():
    from reports.paper.studies.dissipation_study import STUDY

    scene = load_scene("dissipation-saturation")
    assert scene.kind == "velocity" and scene.eps == STUDY["eps"]
    assert scene.restitutions[0] == 1.0 and all(r < 1 for r in scene.restitutions[1:])
    assert {round(1 - r, 12) for r in scene.restitutions[1:]} <= set(STUDY["one_minus_r"])
    assert [x.name for x in scene.experiments()] == [f"r={r:.4g}" for r in scene.restitutions]


@pytest.mark.slow
def test_run_outputs_and_invariants(small_run):
    out, manifest = small_run
    assert manifest["status"] == "complete"
    assert set(manifest["curves"]) == {"r=1", "r=0.9"}
    assert manifest["scene"]["physics_per_curve"] == {
        "r=1": {}, "r=0.9": {"drag": 0.0, "drag_law": "linear", "restitution": 0.9}}
    text = _csv(out / "velocity.csv")
    assert text.splitlines()[0] == "curve,n,moving,stuck,mean_v,mean_v2,se_v"
    plan = make_plan(_fresh(SMALL))
    assert file_problems(plan, text) == []
    rows = [line.split(",") for line in text.splitlines()[1:]]
    assert len(rows) == 2 * len(plan.n_grid)
    assert [int(r[1]) for r in rows[:len(plan.n_grid)]] == list(plan.n_grid)
    assert all(int(r[2]) == 300 and int(r[3]) == 0 for r in rows)  # eps > 1: none sticks
    ok, lines = recheck(out)
    assert ok, lines
    ver = manifest["verification"]
    assert ver["sampled"] >= 30 and ver["overstepped"] == 0


def test_means_agree_with_fastpath_moments_on_the_same_starts():
    """r < 1: the kernel and ``fastpath.kernels.moments`` make the same collisions
    (fastpath.dissipative.carried), so the means differ only by the rounding of the float sums: each
    sum of m terms of one sign is within (m - 1)*u*sum|v| of exact, and the chunk's blocks differ
    from moments' blocks."""
    scene = _fresh(SMALL)
    plan = make_plan(scene)
    for e, r in enumerate(scene.restitutions):
        if r == 1.0:
            continue
        result = run_chunk(scene, plan.seed, e, 0)
        phi, v, *_ = chunk_starts(plan, e, 0)
        mom = moments(phi, v, scene.eps, plan.n_grid, restitution=r)
        assert mom.flagged == 0 and result.counts.settled == 0
        m = len(phi)
        assert list(result.counts.moving) == list(mom.particles_n) == [m] * len(plan.n_grid)
        ours = np.array([float(s / m) for s in result.counts.sum_v])
        bound = 2 * (m + 1) * U * mom.mean_v_n  # v > 0 here, so sum|v| = sum v
        assert np.all(np.abs(ours - mom.mean_v_n) <= bound)
        ours2 = np.array([float(s / m) for s in result.counts.sum_v2])
        assert np.all(np.abs(ours2 - mom.mean_v2_n) <= 2 * (m + 1) * U * mom.mean_v2_n)


def test_elastic_curve_is_fastpath_step_iterated():
    """r = 1: each collision is ``fastpath.step`` (what the sample audit re-derives), so the
    means are those of step iterated from the same starts, to the same summation bound.
    (``fastpath.kernels.moments`` carries sines across an orbit, ``fastpath.orbit``'s arithmetic:
    its chaotic orbits part from step's after a few collisions at eps = 2.)"""
    scene = _fresh(SMALL)
    plan = make_plan(scene)
    result = run_chunk(scene, plan.seed, 0, 1)
    phi, v, *_ = chunk_starts(plan, 0, 1)
    assert result.counts.settled == 0
    m, grid = len(phi), list(plan.n_grid)
    sums = {}
    for n in range(grid[-1] + 1):
        if n in grid:
            sums[n] = (math.fsum(v), math.fsum(v * v))
        phi, v, _ = fastpath.step(phi, v, scene.eps)
    for j, n in enumerate(grid):
        s1, s2 = sums[n]
        assert abs(float(result.counts.sum_v[j]) - s1) <= (m + 1) * U * s1
        assert abs(float(result.counts.sum_v2[j]) - s2) <= (m + 1) * U * s2


@pytest.mark.slow
def test_same_counts_with_one_and_two_threads_and_any_merge_order():
    scene = _fresh(SMALL)
    plan = make_plan(scene)
    for e in range(2):
        one, two = (run_chunk(scene, plan.seed, e, 1, threads=k) for k in (1, 2))
        assert list(one.counts.moving) == list(two.counts.moving)
        assert list(one.counts.sum_v) == list(two.counts.sum_v)  # exact Fractions
        assert list(one.counts.sum_v2) == list(two.counts.sum_v2)
        assert one.rows == two.rows
    results = [run_chunk(scene, plan.seed, e, k) for e, k in plan.chunks]
    texts = set()
    for order in range(3):
        tally = Tally.empty(plan)
        shuffled = list(results)
        random.Random(order).shuffle(shuffled)
        for result in shuffled:
            tally.merge(result, scene.kind)
        texts.add(velocity_text(plan, tally))
    assert len(texts) == 1


@pytest.mark.slow
def test_resume_gives_the_uninterrupted_result(small_run, tmp_path, monkeypatch):
    full, _ = small_run
    real = executor.run_chunk
    calls = []

    def stop_after_three(*args):
        calls.append(args[2:4])
        if len(calls) > 3:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(executor, "run_chunk", stop_after_three)
    with pytest.raises(RunInterrupted):
        driver.run(_fresh(SMALL), tmp_path / "cut", progress=False)
    manifest = json.loads((tmp_path / "cut" / "manifest.json").read_text())
    assert manifest["status"] == "partial" and 0 < manifest["chunks_done"] < manifest["chunks"]
    monkeypatch.setattr(executor, "run_chunk", real)
    done = driver.run(_fresh(SMALL), tmp_path / "cut", resume=True, progress=False)
    assert done["status"] == "complete"
    for name in ("velocity.csv", "sample.csv"):
        assert _csv(full / name) == _csv(tmp_path / "cut" / name), name
    assert recheck(tmp_path / "cut")[0]


def test_tampered_velocity_csv_fails_bouncer_verify(small_run, tmp_path, capsys):
    run = tmp_path / "run"
    shutil.copytree(small_run[0], run)
    lines = _csv(run / "velocity.csv").splitlines(keepends=True)
    cells = lines[5].split(",")
    cells[4] = repr(float(cells[4]) * (1 + 2**-40))  # one mean, nudged
    lines[5] = ",".join(cells)
    (run / "velocity.csv").write_text("".join(lines))
    assert main(["verify", str(run), "--quiet"]) == 1
    out = capsys.readouterr().out
    assert "velocity.csv: SHA-256 differs" in out and "velocity.csv:6:" in out
    # with the manifest's hash updated to match, the file still differs from the checkpoint
    manifest = json.loads((run / "manifest.json").read_text())
    from reports.runs.rundir import sha256_file

    manifest["hashes"]["velocity.csv"] = sha256_file(run / "velocity.csv")
    (run / "manifest.json").write_text(json.dumps(manifest))
    ok, lines = recheck(run)
    assert not ok and any(x.startswith("velocity.csv:6: the checkpoint has") for x in lines)


def test_file_problems_catch_counts_that_do_not_add_up():
    plan = make_plan(_fresh(SMALL))
    good = velocity_text(plan, _tally_of_chunks(plan))
    rows = good.splitlines()
    cells = rows[3].split(",")
    cells[2] = str(int(cells[2]) - 1)  # one particle lost at a grid point
    bad = "\n".join([*rows[:3], ",".join(cells), *rows[4:]]) + "\n"
    assert any("moving" in p and ":4:" in p for p in file_problems(plan, bad))
    cells = rows[3].split(",")
    cells[5] = repr(float(cells[4]) ** 2 * (1 - 2**-20))  # <v^2> below <v>^2
    bad = "\n".join([*rows[:3], ",".join(cells), *rows[4:]]) + "\n"
    assert any("mean_v**2 > mean_v2" in p for p in file_problems(plan, bad))


def _tally_of_chunks(plan):
    tally = Tally.empty(plan)
    for e, k in plan.chunks:
        tally.merge(run_chunk(plan.scene, plan.seed, e, k), plan.scene.kind)
    return tally


def test_stuck_particles_are_reported_apart_and_agree_with_moments(tmp_path):
    scene = _fresh(STICKY)
    plan = make_plan(scene)
    manifest = driver.run(scene, tmp_path / "s", progress=False)
    curve = manifest["curves"]["r=0.5"]
    assert curve["stuck"] > 0 and curve["moving"] + curve["stuck"] == 300
    assert recheck(tmp_path / "s")[0]
    result = run_chunk(scene, plan.seed, 0, 0)
    phi, v, *_ = chunk_starts(plan, 0, 0)
    mom = moments(phi, v, scene.eps, plan.n_grid, restitution=0.5)
    assert mom.flagged == 0 and result.counts.settled == 0
    assert list(result.counts.moving) == list(mom.particles_n)
    assert list(result.counts.stuck_at) == list(mom.stuck_n.sum(axis=0))


def test_tampered_checkpoint_sums_fail_the_invariants(small_run, tmp_path):
    from reports.runs.integrity import tally_problems

    plan = make_plan(_fresh(SMALL))
    tally = Tally.load(small_run[0] / "checkpoint.npz")
    assert tally_problems(plan, tally) == []
    tally.moving[1, 2] -= 1
    assert any("moving" in p for p in tally_problems(plan, tally))
    tally.moving[1, 2] += 1
    tally.sum_v[0, 3] = tally.sum_v[0, 3] * 100  # beyond Cauchy-Schwarz with sum_v2
    assert any("sum_v**2 <= moving*sum_v2" in p for p in tally_problems(plan, tally))


@pytest.mark.parametrize("change, message", [
    ("[1.0, 1.5]", "restitution=1.5"),
    ("[1.0, 1.0]", "lists a value twice"),
    ("[0.0]", "restitution=0.0"),
    ("[]", "non-empty list"),
    ("[1.0, \"x\"]", "physics.restitution must be a number"),
])
def test_bad_values_exit_2_with_one_line(tmp_path, capsys, change, message):
    text = SMALL.replace("[1.0, 0.9]", change)
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("text, message", [
    (SMALL.replace("collisions = 300", "collisions = 300\ntime = 1e4"),
     "horizon is horizon.collisions only"),
    (SMALL + "[holes]\ncentres = [0.0]\nwidths = [0.3]\n", "a velocity scene has no [holes]"),
    (SMALL.replace("[record]", "[record]\nclocks = [\"time\"]"), "records no clocks"),
    (SMALL.replace("[horizon]\ncollisions = 300", "[horizon]\ntime = 1e4"),
     "horizon is horizon.collisions only"),
])
def test_velocity_scene_refuses_what_it_does_not_record(tmp_path, capsys, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    assert main(["run", str(path), "--out", str(tmp_path / "o"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err


def test_a_list_of_restitutions_only_in_velocity_scenes():
    escape = SMALL.replace('kind = "velocity"', 'kind = "escape"') + (
        "[holes]\ncentres = [2.0]\nwidths = [0.3]\n")
    with pytest.raises(ValueError, match=r"a list only in velocity scenes"):
        parse_scene(escape)
    assert parse_scene(escape.replace("[1.0, 0.9]", "0.9")).restitution == 0.9


def test_flagged_particles_are_settled_by_verify_and_counted_once(monkeypatch):
    """Pretend float64 could not decide any first flight: the kernel's first pass records the
    starts (n = 0) and flags every particle; collision 1 is settled by verify and the particles
    resume in the kernel from n = 1, each grid point counting every particle once."""
    from reports.runs import chunk

    scene = _fresh(SMALL)
    plan = make_plan(scene)
    base, _ = chunk.simulate_velocity_chunk(plan, 0, 0)
    real = chunk.moments_chunk
    calls = []

    def undecided_first(physics, starts, grid, as_step, sample, sums, flags):
        calls.append(len(starts.phi))
        if len(calls) > 1:
            return real(physics, starts, grid, as_step, sample, sums, flags)
        # max_collisions 0: record the start, make no collision
        real(physics, starts, grid._replace(max_collisions=0), as_step, sample, sums, flags)
        flags.status[:] = 1  # FlightStatus.UNCERTAIN
        flags.state[:] = np.column_stack(starts)

    monkeypatch.setattr(chunk, "moments_chunk", undecided_first)
    settled, _ = chunk.simulate_velocity_chunk(plan, 0, 0)
    m = len(chunk_starts(plan, 0, 0)[0])
    assert settled.settled == m and len(calls) == 2
    assert list(settled.moving) == [m] * len(plan.n_grid)
    assert settled.sum_v[0] == base.sum_v[0]  # the starts, once
    # collision 1 from verify (correctly rounded) against fastpath's (error ~ kappa*u each)
    assert float(settled.sum_v[1]) == pytest.approx(float(base.sum_v[1]), rel=1e-12)
    assert settled.collisions == base.collisions


def test_plot_draws_the_velocity_curves(small_run, tmp_path):
    out = tmp_path / "v.png"
    assert main(["plot", str(small_run[0]), "--out", str(out)]) == 0
    assert out.stat().st_size > 10_000
    assert main(["plot", str(small_run[0]), "--fit", "power", "--window", "1", "10"]) == 2


@pytest.mark.slow
def test_drag_with_restitution_runs_and_passes_bouncer_verify(tmp_path):
    """Drag together with r < 1 (sticking with drag): every curve takes the drag; the run's
    sampled collisions are re-derived bit for bit by ``bouncer verify``, and a particle stuck
    for good under linear drag (|eps|*sqrt(1 + k^2) <= 1 at eps = 0.6, k = 0.1) is counted."""
    text = STICKY.replace("[physics]", "[physics]\ndrag = 0.1\ndrag_law = \"linear\"")
    manifest = driver.run(_fresh(text), tmp_path / "run", progress=False)
    assert manifest["status"] == "complete"
    assert manifest["scene"]["physics_per_curve"]["r=0.5"]["drag"] == 0.1
    ok, lines = recheck(tmp_path / "run")
    assert ok, "\n".join(lines[-5:])
    rows = (tmp_path / "run" / "velocity.csv").read_text().splitlines()
    assert int(rows[-1].split(",")[3]) > 0  # stuck at the horizon
