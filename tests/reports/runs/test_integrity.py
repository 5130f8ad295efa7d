"""Fault injection: edited, truncated and deleted run files, faults of the filesystem, a second
writer, Ctrl-C. Each fault must give a one-line error (exit 2) or a failed audit (exit 1)
naming the file, never a traceback and never a silent success."""

import csv
import io
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from scene_texts import TINY

from reports.cli import main
from reports.runs import plan, rundir
from reports.runs.counts import Finished, Tally
from reports.runs.integrity import tally_problems
from reports.runs.scenes import parse_scene

ROOT = Path(__file__).resolve().parents[3]


# a few seconds in many chunks: time to interrupt it
SLOW = """
name = "slow"
kind = "escape"
eps = 0.6
particles = 40000
seed = 11
chunk_size = 1024
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [1.0]
widths = [0.3]
[horizon]
collisions = 100000
"""


@pytest.fixture(scope="module")
def clean_run(tmp_path_factory):
    base = tmp_path_factory.mktemp("clean")
    (base / "tiny.toml").write_text(TINY)
    assert main(["run", str(base / "tiny.toml"), "--out", str(base / "run"), "--quiet"]) == 0
    return base


@pytest.fixture
def run_dir(clean_run, tmp_path):
    """A fresh copy of a complete run and its scene file."""
    shutil.copy(clean_run / "tiny.toml", tmp_path / "tiny.toml")
    return Path(shutil.copytree(clean_run / "run", tmp_path / "run"))


def audit(path, capsys):
    code = main(["verify", str(path), "--quiet"])
    return code, capsys.readouterr().out


def one_line_error(capsys):
    err = capsys.readouterr().err
    assert err.startswith("bouncer: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


def edit_csv(path, edit):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    edit(rows)
    with open(path, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows)


# ---- the manifest and the audit -------------------------------------------------------------

def test_manifest_hashes_every_file(run_dir, capsys):
    hashes = json.loads((run_dir / "manifest.json").read_text())["hashes"]
    assert set(hashes) == {"scene.toml", "checkpoint.npz", "survival.csv", "counts.csv",
                           "sample.csv", "provenance.json"}
    for name, digest in hashes.items():
        assert rundir.sha256_file(run_dir / name) == digest, name
    code, out = audit(run_dir, capsys)
    assert code == 0 and out.rstrip().endswith("OK"), out


def test_edited_count_is_caught_by_file_and_line(run_dir, capsys):
    edit_csv(run_dir / "counts.csv", lambda rows: rows[3].__setitem__(4, str(int(rows[3][4]) + 1)))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "FAILED" in out
    assert "counts.csv: SHA-256 differs" in out
    assert "counts.csv:4: the checkpoint has" in out  # the edited line, numbered from the header
    assert "+ 0 stuck = 201, but 200 particles were run" in out
    assert "survival.csv:" in out  # no longer the curve re-derived from counts.csv


def test_survival_is_rederived_from_counts(run_dir, capsys):
    """An edited survival.csv with its hash updated still differs from the re-derived curve."""
    edit_csv(run_dir / "survival.csv", lambda rows: rows[2].__setitem__(3, "0.5"))
    manifest = json.loads((run_dir / "manifest.json").read_text())
    manifest["hashes"]["survival.csv"] = rundir.sha256_file(run_dir / "survival.csv")
    (run_dir / "manifest.json").write_text(json.dumps(manifest))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "survival.csv:3: the curve from counts.csv has" in out
    assert "SHA-256" not in out


@pytest.mark.parametrize("name", ["survival.csv", "counts.csv", "checkpoint.npz"])
def test_deleted_file_is_caught(run_dir, capsys, name):
    (run_dir / name).unlink()
    code, out = audit(run_dir, capsys)
    assert code == 1 and f"{name}: missing" in out


def test_without_checkpoint_counts_still_rederive_the_curves(run_dir, capsys):
    """A run kept without its checkpoint: counts.csv alone is checked and re-derived."""
    (run_dir / "checkpoint.npz").unlink()
    edit_csv(run_dir / "counts.csv", lambda rows: rows[3].__setitem__(4, str(int(rows[3][4]) + 1)))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "+ 0 stuck = 201, but 200 particles were run" in out
    assert "survival.csv:" in out


def test_deleted_sample_rows_are_caught(run_dir, capsys):
    edit_csv(run_dir / "sample.csv", lambda rows: rows.__delitem__(slice(2, None)))
    code, out = audit(run_dir, capsys)
    assert code == 1
    assert "sample.csv: SHA-256 differs" in out and "sample.csv: 2 lines" in out


@pytest.mark.parametrize(("key", "change"), [
    ("worst_error", lambda m: m["verification"].__setitem__("worst_error", 0.01)),
    ("collisions", lambda m: m.__setitem__("collisions", m["collisions"] + 1)),
    ("censored", lambda m: m["curves"]["from hole 1"].__setitem__(
        "censored", m["curves"]["from hole 1"]["censored"] + 7)),
])
def test_edited_manifest_figures_are_caught(run_dir, capsys, key, change):
    manifest = json.loads((run_dir / "manifest.json").read_text())
    change(manifest)
    (run_dir / "manifest.json").write_text(json.dumps(manifest))
    code, out = audit(run_dir, capsys)
    assert code == 1 and f"manifest.json: {'verification.' if key == 'worst_error' else ''}" in out
    assert key in out.split("checked:")[1]


def test_edited_sample_error_is_recomputed(run_dir, capsys):
    edit_csv(run_dir / "sample.csv", lambda rows: rows[1].__setitem__(10, "0.0"))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "sample.csv:2: verify gives tau_ref" in out


# ---- the checkpoint on resume ---------------------------------------------------------------

def partial(run_dir):
    """Make the copied run partial again (as after a kill), keeping its checkpoint."""
    manifest = json.loads((run_dir / "manifest.json").read_text())
    manifest["status"] = "partial"
    (run_dir / "manifest.json").write_text(json.dumps(manifest))


def resume(run_dir):
    return main(["run", str(run_dir.parent / "tiny.toml"), "--out", str(run_dir), "--resume",
                 "--quiet"])


def rewrite_checkpoint(path, edit, keep_digest):
    """Edit the checkpoint's arrays: in place, keeping its recorded digest, or saved afresh with
    a digest of its own (what a careful forger, or a bug in the writer, would do)."""
    if not keep_digest:
        tally = Tally.load(path)
        edit(vars(tally))
        tally.save(path)
        return
    with np.load(path) as z:
        arrays = {k: z[k] for k in z.files}
    edit(arrays)
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    path.write_bytes(buf.getvalue())


def bump(arrays):
    arrays["esc_n"] = arrays["esc_n"].copy()
    arrays["esc_n"][0, 0, 3] += 40  # would make P(0) = 1.2 on that curve


@pytest.mark.parametrize(("fault", "message"), [
    (lambda p: p.write_bytes(p.read_bytes()[: len(p.read_bytes()) // 2]), "is unreadable"),
    (lambda p: p.write_bytes(p.read_bytes()[:100] + bytes([p.read_bytes()[100] ^ 1])
                             + p.read_bytes()[101:]), "checkpoint"),
    (lambda p: rewrite_checkpoint(p, bump, keep_digest=True), "fails its content hash"),
    (lambda p: rewrite_checkpoint(p, bump, keep_digest=False), "fails its invariants"),
    (lambda p: p.unlink(), "is missing but the manifest records"),
])
def test_bad_checkpoint_is_refused_on_resume(run_dir, capsys, fault, message):
    partial(run_dir)
    fault(run_dir / "checkpoint.npz")
    capsys.readouterr()
    assert resume(run_dir) == 2
    err = one_line_error(capsys)
    assert message in err and "--force" in err and "checkpoint.npz" in err, err


def test_invariant_names_the_curve():
    scene = parse_scene(TINY)
    p = plan.make_plan(scene)
    tally = Tally.empty(p)
    tally.finished.add((0, 0))
    tally.cens_n[0, 5] = 63
    problems = tally_problems(p, tally)
    assert "curve 'from hole 1', clock collisions: 0 escaped + 63 censored + 0 stuck = 63," \
        " but 64 particles were run" in problems[0]
    tally.cens_n[0, 5] = 64
    tally.cens_t[0, 5] = 64
    assert tally_problems(p, tally) == []


def test_checkpoint_round_trip_keeps_the_state(tmp_path):
    p = plan.make_plan(parse_scene(TINY))
    results = [driver_chunk(p, e, k) for e, k in p.chunks]
    tally = Tally.empty(p)
    for r in reversed(results):
        tally.merge(r, "transport")
    digest = tally.save(tmp_path / "c.npz")
    assert digest == rundir.sha256_file(tmp_path / "c.npz")
    back = Tally.load(tmp_path / "c.npz")
    assert back.finished == tally.finished and back.samples == tally.samples
    assert back.finished.extra == set() and back.finished.prefix == [4, 4]
    np.testing.assert_array_equal(back.esc_t, tally.esc_t)


def driver_chunk(p, e, k):
    from reports.runs.chunk import run_chunk

    return run_chunk(p.scene, p.seed, e, k, p.particles)


# ---- filesystem faults and bad paths --------------------------------------------------------

def test_out_under_a_file_and_out_a_file(tmp_path, capsys):
    (tmp_path / "tiny.toml").write_text(TINY)
    (tmp_path / "f").write_text("x")
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "f" / "r")]) == 2
    assert f"{tmp_path / 'f'}" in one_line_error(capsys)
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "f")]) == 2
    assert "is a file, not a directory" in one_line_error(capsys)
    assert (tmp_path / "f").read_text() == "x"


def test_binary_scene_file_is_named(tmp_path, capsys):
    (tmp_path / "bin.toml").write_bytes(bytes(range(256)))
    assert main(["run", str(tmp_path / "bin.toml"), "--out", str(tmp_path / "r")]) == 2
    assert str(tmp_path / "bin.toml") in one_line_error(capsys)


def test_directory_read_only_mid_run(tmp_path, capsys, monkeypatch):
    """The 6th atomic write (the manifest after the first checkpoint: mid-run) fails as on a
    read-only directory: one line naming the file, exit 2; the run then resumes to the
    uninterrupted result."""
    (tmp_path / "tiny.toml").write_text(TINY)
    real, calls = rundir.write_atomic, []

    def failing(path, data):
        calls.append(path)
        if len(calls) == 6:
            raise PermissionError(13, "Permission denied", str(path))
        return real(path, data)

    monkeypatch.setattr(rundir, "write_atomic", failing)
    out = tmp_path / "r"
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(out), "--quiet"]) == 2
    err = one_line_error(capsys)
    assert f"{out}/" in err and "Permission denied" in err and "--resume" in err
    monkeypatch.setattr(rundir, "write_atomic", real)
    assert resume(out) == 0
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "ref"),
                 "--quiet"]) == 0
    for name in ("survival.csv", "counts.csv", "sample.csv"):
        assert (out / name).read_bytes() == (tmp_path / "ref" / name).read_bytes()


def test_unwritable_output_directory(tmp_path, capsys, monkeypatch):
    (tmp_path / "tiny.toml").write_text(TINY)

    def refuse(self, *args, **kwargs):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "mkdir", refuse)
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "r")]) == 2
    assert f"{tmp_path / 'r'}: Permission denied" in one_line_error(capsys)


# ---- a second writer -----------------------------------------------------------------------

HOLD = """
import sys, time
from reports.runs.lock import RunLock
with RunLock(sys.argv[1]):
    print("held", flush=True)
    time.sleep(60)
"""


@pytest.mark.slow
def test_second_writer_is_refused_and_nothing_deleted(run_dir, capsys):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    holder = subprocess.Popen([sys.executable, "-c", HOLD, str(run_dir)], cwd=ROOT, env=env,
                              stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        before = sorted(p.name for p in run_dir.iterdir())
        scene = str(run_dir.parent / "tiny.toml")
        for flag in ("--resume", "--force"):
            assert main(["run", scene, "--out", str(run_dir), flag, "--quiet"]) == 2
            err = one_line_error(capsys)
            assert f"pid {holder.pid} on " in err and "since" in err, err
        assert sorted(p.name for p in run_dir.iterdir()) == before
    finally:
        holder.kill()
        holder.wait()
    # the OS released the killed holder's lock: the next writer proceeds
    assert main(["run", str(run_dir.parent / "tiny.toml"), "--out", str(run_dir), "--force",
                 "--quiet"]) == 0


# ---- flat memory in N, absurd sizes ------------------------------------------------------

def test_plan_is_lazy_and_finished_is_compact():
    p = plan.make_plan(parse_scene(TINY), particles=10**13)
    assert p.n_chunks == 2 * -(-10**13 // 64)
    chunks = p.chunks
    assert next(chunks) == (0, 0) and next(chunks) == (0, 1)
    fin = Finished.none(2)
    for k in (2, 0, 5, 1):
        assert fin.add((1, k))
    assert not fin.add((1, 0))
    assert fin.prefix == [0, 3] and fin.extra == {(1, 5)} and len(fin) == 4
    assert (1, 5) in fin and (1, 4) not in fin and (0, 0) not in fin
    assert fin.particles_done(p, 1) == 4 * 64
    assert Finished.from_json([[1, 2], [1, 0], [1, 5], [1, 1]]) == fin  # earlier checkpoints
    assert Finished.from_json(fin.to_json()) == fin


def test_absurd_size_is_refused_with_time_and_disk(tmp_path, capsys, monkeypatch):
    from reports.runs import driver

    def never(out):
        raise AssertionError(f"an absurd run reached its directory {out}")

    monkeypatch.setattr(driver, "RunLock", never)  # refused before any file or any work
    assert main(["run", "paper-escape", "--particles", "1e15", "--out",
                 str(tmp_path / "r")]) == 2
    err = one_line_error(capsys)
    assert "years" in err and "MB of disk" in err and "particles/s" in err
    assert not (tmp_path / "r").exists()


def test_sample_stride_bounds_the_sample_and_keeps_the_counts(monkeypatch):
    scene = parse_scene(TINY)
    full = plan.make_plan(scene)
    monkeypatch.setattr(plan, "MAX_SAMPLED_CHUNKS", 3)
    strided = plan.make_plan(scene)
    assert full.sample_stride == 1 and strided.sample_stride == 3
    assert [c for c in strided.chunks if strided.sampled(*c)] == [(0, 0), (0, 3), (1, 2)]
    from reports.runs.chunk import simulate_chunk

    a, rows_a = simulate_chunk(full, 0, 1)
    b, rows_b = simulate_chunk(strided, 0, 1)
    assert rows_a and not rows_b
    for name in ("esc_n", "esc_t", "cens_n", "cens_t"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert a.collisions == b.collisions


# ---- Ctrl-C ---------------------------------------------------------------------------------

@pytest.mark.slow
def test_sigint_leaves_a_resumable_checkpoint(tmp_path):
    (tmp_path / "slow.toml").write_text(SLOW)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    cmd = [sys.executable, "-m", "reports.cli", "run", str(tmp_path / "slow.toml"), "--quiet"]
    ref = subprocess.run([*cmd, "--out", str(tmp_path / "ref")], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=300)
    assert ref.returncode == 0, ref.stderr
    # a shell that starts the test runner in the background leaves SIGINT ignored, and a
    # child then never sees Ctrl-C: give the run the default disposition, as a terminal does
    proc = subprocess.Popen([*cmd, "--out", str(tmp_path / "cut")], cwd=ROOT, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    ckpt = tmp_path / "cut" / "checkpoint.npz"
    deadline = time.monotonic() + 120
    while not ckpt.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "checkpointed in" in err and "--resume" in err
    manifest = json.loads((tmp_path / "cut" / "manifest.json").read_text())
    assert manifest["status"] == "partial" and manifest["chunks_done"] < manifest["chunks"]
    tally = Tally.load(ckpt)  # consistent: passes its digest and its invariants
    assert tally_problems(plan.make_plan(parse_scene(SLOW)), tally) == []
    assert manifest["hashes"]["checkpoint.npz"] == rundir.sha256_file(ckpt)
    resume_cmd = err.split("continue with: ")[1].split()
    assert resume_cmd[:2] == ["bouncer", "run"]
    again = subprocess.run([sys.executable, "-m", "reports.cli", *resume_cmd[1:], "--quiet"],
                           cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    for name in ("survival.csv", "counts.csv", "sample.csv"):
        assert (tmp_path / "cut" / name).read_bytes() == (tmp_path / "ref" / name).read_bytes()
