"""Runs that record the joint histogram of (n, t) (``[record] joint = true``): joint.csv, its
audit (marginals against counts.csv, the checkpoint, the file's form), resume and threads, the
loader ``load_joint``; scenes without the record unchanged."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from scene_texts import TINY

from reports.runs import driver, rundir
from reports.runs.counts import CheckpointError, Tally
from reports.runs.integrity import parse_counts
from reports.runs.joint import load_joint
from reports.runs.joint_file import JOINT_COLUMNS, joint_text, parse_joint
from reports.runs.plan import make_plan
from reports.runs.recheck import recheck
from reports.runs.scenes import parse_scene

JOINT = TINY.replace('name = "tiny"', 'name = "tiny-joint"') + "[record]\njoint = true\n"
# an escape scene whose horizon in time censors particles too (both kinds of bounds)
ESCAPE_JOINT = """
name = "escape-joint"
kind = "escape"
eps = 0.6
particles = 600
seed = 9
chunk_size = 128
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [1.0, 2.5]
widths = [0.3]
[horizon]
collisions = 30
time = 150.0
[record]
joint = true
verify_samples = 20
"""


@pytest.fixture(scope="module")
def joint_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("joint") / "run"
    driver.run(parse_scene(JOINT), out, progress=False)
    return out


@pytest.fixture
def run_copy(joint_run, tmp_path):
    return Path(shutil.copytree(joint_run, tmp_path / "run"))


def manifest_of(run_dir):
    return json.loads((run_dir / "manifest.json").read_text())


def rehash(run_dir, name):
    """Record an edited file's hash in the manifest, as a careful forger would."""
    manifest = manifest_of(run_dir)
    manifest["hashes"][name] = rundir.sha256_file(run_dir / name)
    (run_dir / "manifest.json").write_text(json.dumps(manifest))


def joint_lines(run_dir):
    return (run_dir / "joint.csv").read_text().splitlines()


def write_joint(run_dir, lines):
    (run_dir / "joint.csv").write_text("\n".join(lines) + "\n")
    rehash(run_dir, "joint.csv")


def problems(run_dir):
    ok, lines = recheck(run_dir)
    start = next(i for i, x in enumerate(lines) if x.startswith("not audited: "))
    return ok, lines[start + 1:-1]


# ---- the run and its files -------------------------------------------------------------------

def test_a_joint_run_writes_joint_csv_and_passes_its_audit(joint_run):
    manifest = manifest_of(joint_run)
    assert manifest["scene"]["joint"] is True and "density" not in manifest["scene"]
    assert manifest["hashes"]["joint.csv"] == rundir.sha256_file(joint_run / "joint.csv")
    assert joint_lines(joint_run)[0] == ",".join(JOINT_COLUMNS)
    ok, lines = recheck(joint_run)
    assert ok, lines
    assert "joint.csv (against the checkpoint, its marginals against counts.csv)" in lines[2]


def test_load_joint_gives_each_curve_with_the_marginals_of_counts_csv(joint_run):
    record = load_joint(joint_run)
    plan = make_plan(parse_scene(JOINT))
    counts, _, count_problems, _ = parse_counts(plan, (joint_run / "counts.csv").read_text())
    assert not count_problems
    assert sorted(record.escapes) == ["P11", "P12", "P21", "P22"]
    assert record.experiment["P21"] == "from hole 2" and record.particles == 200
    for e, exp in enumerate(plan.experiments):
        for j, curve in enumerate(exp.curves):
            np.testing.assert_array_equal(record.escapes[curve].sum(axis=1), counts.esc_n[e, j])
            np.testing.assert_array_equal(record.escapes[curve].sum(axis=0), counts.esc_t[e, j])
        np.testing.assert_array_equal(record.censored[exp.name].sum(axis=1), counts.cens_n[e])
        total = sum(record.escapes[c].sum() for c in exp.curves) + record.censored[
            exp.name].sum() + record.stuck[exp.name].sum()
        assert total == 200
    np.testing.assert_array_equal(record.n_edges, plan.n_edges)
    np.testing.assert_array_equal(record.t_edges, plan.t_edges)


def test_the_censored_bounds_of_both_horizons_are_in_the_record(tmp_path):
    out = tmp_path / "run"
    driver.run(parse_scene(ESCAPE_JOINT), out, progress=False)
    assert recheck(out)[0]
    record = load_joint(out)
    censored = sum(record.censored.values())
    k_n = np.searchsorted(record.n_edges, 30, side="right") - 1
    k_t = np.searchsorted(record.t_edges, 150.0, side="right") - 1
    by_time = censored[:, k_t + 1:].sum()  # bound t > 150: censored by the time horizon
    by_collisions = censored[k_n:, :k_t].sum()  # bound n = 30 at t < 150
    assert by_time > 0 and by_collisions > 0
    assert by_time + by_collisions + censored[:, k_t].sum() == censored.sum()


def test_a_scene_without_the_record_writes_no_joint_file(tmp_path):
    out = tmp_path / "plain"
    manifest = driver.run(parse_scene(TINY), out, progress=False)
    assert not (out / "joint.csv").exists() and "joint.csv" not in manifest["hashes"]
    assert "joint" not in manifest["scene"]
    with np.load(out / "checkpoint.npz") as z:
        assert not any(name.startswith("joint") for name in z.files)
    with pytest.raises(ValueError, match="records no joint histogram"):
        load_joint(out)


def test_threads_and_resume_give_the_same_joint_csv(tmp_path, monkeypatch):
    scene = parse_scene(ESCAPE_JOINT)
    driver.run(scene, tmp_path / "one", progress=False, threads=1)
    driver.run(scene, tmp_path / "two", progress=False, threads=2)
    # a run stopped after its first chunks, then resumed
    real, seen = driver.Tally.merge, []

    def stop_after_three(self, result, kind):
        if len(seen) == 3:
            raise KeyboardInterrupt
        seen.append(result.chunk)
        return real(self, result, kind)

    monkeypatch.setattr(driver.Tally, "merge", stop_after_three)
    with pytest.raises(driver.RunInterrupted):
        driver.run(scene, tmp_path / "cut", progress=False)
    monkeypatch.setattr(driver.Tally, "merge", real)
    assert manifest_of(tmp_path / "cut")["chunks_done"] == 3
    driver.run(scene, tmp_path / "cut", resume=True, progress=False)
    first = (tmp_path / "one" / "joint.csv").read_bytes()
    assert (tmp_path / "two" / "joint.csv").read_bytes() == first
    assert (tmp_path / "cut" / "joint.csv").read_bytes() == first
    assert recheck(tmp_path / "cut")[0]


# ---- the audit of joint.csv -------------------------------------------------------------------

def edit_joint(run_dir, edit):
    """joint.csv rewritten (in the run's own format) after ``edit`` of its dense record."""
    plan = make_plan(parse_scene(JOINT))
    joint, found = parse_joint(plan, (run_dir / "joint.csv").read_text())
    assert not found
    edit(joint)
    (run_dir / "joint.csv").write_text(joint_text(plan, joint))
    rehash(run_dir, "joint.csv")


def test_a_particle_moved_to_another_time_bin_breaks_the_time_marginal(run_copy):
    def move(joint):
        b, c = np.argwhere(joint[0, 0])[0]
        joint[0, 0, b, c] -= 1
        joint[0, 0, b, c + 1] += 1

    edit_joint(run_copy, move)
    ok, found = problems(run_copy)
    assert not ok
    marginals = [x for x in found if "marginal" in x]
    assert len(marginals) == 1
    assert marginals[0].startswith("joint.csv: from hole 1, P11: the time marginal has")
    assert any(x.startswith("joint.csv:") and "the checkpoint has" in x for x in found)
    with pytest.raises(ValueError, match="the time marginal"):
        load_joint(run_copy)


def test_a_swap_that_keeps_both_marginals_is_caught_by_the_checkpoint(run_copy):
    """Two particles of one curve exchange their times: both marginals hold, the pairing does
    not; the file then differs from the one written from the checkpoint."""
    def swap(joint):
        cells = np.argwhere(joint[1, 0])
        (b1, c1), (b2, c2) = next((p, q) for p in cells for q in cells
                                  if p[0] != q[0] and p[1] != q[1])
        for (b, c), d in (((b1, c1), -1), ((b2, c2), -1), ((b1, c2), 1), ((b2, c1), 1)):
            joint[1, 0, b, c] += d

    edit_joint(run_copy, swap)
    ok, found = problems(run_copy)
    assert not ok and all("marginal" not in x for x in found)
    assert any(x.startswith("joint.csv:") and "the checkpoint has" in x for x in found)


def with_field(lines, k, value):
    """The lines with field k of the first row replaced."""
    fields = lines[1].split(",")
    fields[k] = value
    return [lines[0], ",".join(fields), *lines[2:]]


@pytest.mark.parametrize(("edit", "message"), [
    (lambda ls: [ls[0].replace("count", "n"), *ls[1:]], "joint.csv:1: header"),
    (lambda ls: [*ls, ls[1]], "again"),
    (lambda ls: with_field(ls, 0, "from hole 9"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 1, "P33"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 2, "1.5"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 3, "0.11"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 4, "0"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 4, "-3"), "joint.csv:2: not a row of this run"),
    (lambda ls: with_field(ls, 4, "2.0"), "joint.csv:2: not a row of this run"),
])
def test_a_malformed_joint_csv_fails_the_audit_by_line(run_copy, edit, message):
    write_joint(run_copy, edit(joint_lines(run_copy)))
    ok, found = problems(run_copy)
    assert not ok and any(message in x for x in found), found


def test_a_missing_joint_csv_fails_the_audit(run_copy):
    (run_copy / "joint.csv").unlink()
    ok, found = problems(run_copy)
    assert not ok
    assert "joint.csv: missing (the manifest records its hash)" in found
    assert "joint.csv is missing or not UTF-8 text" in found


def test_a_joint_hash_dropped_from_the_manifest_fails_the_audit(run_copy):
    manifest = manifest_of(run_copy)
    del manifest["hashes"]["joint.csv"]
    (run_copy / "manifest.json").write_text(json.dumps(manifest))
    ok, found = problems(run_copy)
    assert not ok and "manifest.json: no hash recorded for joint.csv" in found


# ---- the checkpoint ---------------------------------------------------------------------------

def test_the_checkpoint_keeps_the_joint_record_sparse_and_whole(joint_run, tmp_path):
    tally = Tally.load(joint_run / "checkpoint.npz")
    with np.load(joint_run / "checkpoint.npz") as z:
        index, count = z["joint_index"], z["joint_count"]
    assert len(index) == np.count_nonzero(tally.joint) and np.all(np.diff(index) > 0)
    assert count.sum() == tally.joint.sum() == 400
    tally.save(tmp_path / "again.npz")
    np.testing.assert_array_equal(Tally.load(tmp_path / "again.npz").joint, tally.joint)


def _forged_checkpoint(joint_run, tmp_path, change):
    """The checkpoint's arrays and bookkeeping changed by ``change``, its digest recomputed."""
    from reports.runs.counts import _digest

    with np.load(joint_run / "checkpoint.npz") as z:
        arrays = {name: z[name] for name in z.files if name not in ("meta", "digest")}
        meta = json.loads(str(z["meta"]))
    change(arrays, meta)
    meta_json = json.dumps(meta)
    path = tmp_path / "forged.npz"
    np.savez(path, **arrays, meta=np.array(meta_json), digest=np.array(_digest(arrays, meta_json)))
    return path


@pytest.mark.parametrize(("change", "message"), [
    (lambda a, m: m.__setitem__("joint_shape", [10**6, 10**6, 10**6, 10**6]), "at most"),
    (lambda a, m: m.__setitem__("joint_shape", [2, 4, 3]), "is not"),
    (lambda a, m: a.__setitem__("joint_index", a["joint_index"][::-1].copy()), "increasing"),
    (lambda a, m: a.__setitem__("joint_count", -a["joint_count"]), "positive"),
    (lambda a, m: a.pop("joint_count"), "only"),
])
def test_a_forged_joint_record_in_the_checkpoint_is_refused(joint_run, tmp_path, change,
                                                           message):
    path = _forged_checkpoint(joint_run, tmp_path, change)
    with pytest.raises(CheckpointError, match=message):
        Tally.load(path)


def test_a_checkpoint_joint_record_off_its_marginals_fails_the_invariants(joint_run, tmp_path):
    from reports.runs.integrity import tally_problems

    tally = Tally.load(joint_run / "checkpoint.npz")
    plan = make_plan(parse_scene(JOINT))
    assert tally_problems(plan, tally) == []
    b, c = np.argwhere(tally.joint[0, 0])[0]
    tally.joint[0, 0, b, c] -= 1
    tally.joint[0, 1, b, c] += 1  # one particle moved from P11 to P12: totals still hold
    found = tally_problems(plan, tally)
    assert found and all(x.startswith("checkpoint joint record: from hole 1, P1") for x in found)
    tally.joint = None
    assert tally_problems(plan, tally) == ["no joint record, but the scene asks for one"]


def test_the_disk_estimate_counts_the_joint_record():
    from reports.runs.plan import JOINT_CURVE_BYTES, estimate

    joint, plain = make_plan(parse_scene(JOINT)), make_plan(parse_scene(TINY))
    assert estimate(joint)[1] - estimate(plain)[1] == 4 * JOINT_CURVE_BYTES  # P11 .. P22
    assert estimate(joint)[0] == estimate(plain)[0]


def test_particles_settled_by_verify_are_in_the_joint_record(monkeypatch):
    """Every first flight flagged as undecided: collision 1 is settled by verify here, outside
    the kernel; the particles that escape or are censored there are recorded here too."""
    from reports.runs import chunk

    scene = parse_scene(ESCAPE_JOINT.replace("time = 150.0", "time = 6.0"))
    plan = make_plan(scene)
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
    out, _ = chunk.simulate_chunk(plan, 0, 0)
    assert out.settled == 128 and len(calls) == 2
    first = out.esc_n[0, 0] + out.cens_t[np.searchsorted(plan.t_edges, 6.0, side="right") - 1:]
    assert first.sum() > 0  # some end at the settled collision itself
    for o, (by_n, by_t) in enumerate([(out.esc_n[0], out.esc_t[0]), (out.cens_n, out.cens_t)]):
        np.testing.assert_array_equal(out.joint[o].sum(axis=1), by_n)
        np.testing.assert_array_equal(out.joint[o].sum(axis=0), by_t)
    assert out.joint.sum() == 128
