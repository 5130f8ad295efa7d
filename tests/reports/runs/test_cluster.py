"""Runs on a Dask cluster: bit-identical to local runs, resume across the two, a killed worker.

One 2-worker ``distributed.LocalCluster`` (processes, loopback only) serves the module. The local
reference runs first, so the workers load the numba kernels from the on-disk cache.
"""

import functools
import json
import os
import random
from pathlib import Path

import numpy as np
import pytest

from reports.cli import main
from reports.runs import chunk, cluster, counts, driver, executor, sweep
from reports.runs.manifest import load_provenance
from reports.runs.plan import make_plan
from reports.runs.rundir import RunFailed
from reports.runs.scenes import parse_scene

distributed = pytest.importorskip("distributed")

# 2 curves x 4 chunks of <= 512 starts
SCENE = """
name = "cluster-small"
kind = "escape"
eps = 0.6
particles = 1800
seed = 17
chunk_size = 512
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [1.0, 2.5]
widths = [0.3]
[horizon]
collisions = 2000
time = 1e5
[record]
verify_samples = 120
"""
CHUNKS = 8
RESULTS = ("survival.csv", "counts.csv", "sample.csv")


class Interrupt(Exception):
    """Stands for a kill of the client after some chunks."""


@pytest.fixture(scope="module")
def scene():
    return parse_scene(SCENE)


@pytest.fixture(scope="module")
def reference(scene, tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "local"
    manifest = driver.run(scene, out, progress=False)
    assert manifest["status"] == "complete" and manifest["chunks"] == CHUNKS
    return out


@pytest.fixture(scope="module")
def local_cluster(reference):
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as lc:
        yield lc


@pytest.fixture
def client(local_cluster):
    with distributed.Client(local_cluster, set_as_default=False) as c:
        yield c


def same_results(a, b):
    for name in RESULTS:
        assert (Path(a) / name).read_bytes() == (Path(b) / name).read_bytes(), name
    ma = json.loads((Path(a) / "manifest.json").read_text())
    mb = json.loads((Path(b) / "manifest.json").read_text())
    assert ma["status"] == mb["status"] == "complete"
    assert ma["collisions"] == mb["collisions"] and ma["curves"] == mb["curves"]
    for key in ("sampled", "worst_error", "uncertain_settled", "overstepped"):
        assert ma["verification"][key] == mb["verification"][key], key


def counting(client, monkeypatch):
    """Count the tasks submitted through ``client``."""
    submitted = []
    real = client.submit

    def submit(*args, **kwargs):
        submitted.append(kwargs.get("key"))
        return real(*args, **kwargs)

    monkeypatch.setattr(client, "submit", submit)
    return submitted


def test_merge_is_keyed_by_chunk_index(scene):
    """Chunks merged in any order, with duplicates, give the state of the in-order merge."""
    plan = make_plan(scene)
    results = [chunk.run_chunk(scene, plan.seed, e, k, plan.particles) for e, k in plan.chunks]
    again = chunk.run_chunk(scene, plan.seed, 1, 2, plan.particles)
    assert again.rows == results[6].rows and again.counts.collisions == results[6].counts.collisions
    ordered, shuffled = counts.Tally.empty(plan), counts.Tally.empty(plan)
    for r in results:
        assert ordered.merge(r, scene.kind)
    mixed = results + results[:3]
    random.Random(1).shuffle(mixed)
    merged = [shuffled.merge(r, scene.kind) for r in mixed]
    assert sum(merged) == CHUNKS  # the duplicates were ignored
    for name in ("esc_n", "esc_t", "cens_n", "cens_t"):
        np.testing.assert_array_equal(getattr(ordered, name), getattr(shuffled, name))
    assert ordered.samples == shuffled.samples and ordered.finished == shuffled.finished
    assert ordered.collisions == shuffled.collisions
    assert driver.summary(ordered, scene) == driver.summary(shuffled, scene)


def chunks_computed(run_dir):
    """The chunks the last session of the run computed (its provenance record)."""
    return load_provenance(run_dir)["session"]["chunks_computed"]


@pytest.mark.slow
def test_cluster_run_is_bit_identical_to_local(scene, reference, local_cluster, tmp_path,
                                               capsys):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE)
    out = tmp_path / "dask"
    assert main(["run", str(path), "--out", str(out), "--quiet",
                 "--scheduler", local_cluster.scheduler_address]) == 0
    assert "2 workers, 8 chunks computed there" in capsys.readouterr().out
    same_results(reference, out)
    session = load_provenance(out)["session"]
    assert session["scheduler"] == local_cluster.scheduler_address and session["workers"] == 2


@pytest.mark.slow
def test_resume_local_run_on_the_cluster(scene, reference, client, tmp_path, monkeypatch):
    real = executor.local

    def three_then_killed(jobs):
        for i, item in enumerate(real(jobs)):
            if i == 3:
                raise Interrupt
            yield item

    monkeypatch.setattr(executor, "local", three_then_killed)
    monkeypatch.setattr(driver, "CHECKPOINT_INTERVAL_S", 0.0)  # a checkpoint after every chunk
    with pytest.raises(Interrupt):
        driver.run(scene, tmp_path / "r", progress=False)
    monkeypatch.setattr(executor, "local", real)
    partial = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert partial["status"] == "partial" and partial["chunks_done"] == 3
    submitted = counting(client, monkeypatch)
    driver.run(scene, tmp_path / "r", resume=True, progress=False, scheduler=client)
    assert len(submitted) == CHUNKS - 3 == chunks_computed(tmp_path / "r")
    same_results(reference, tmp_path / "r")


@pytest.mark.slow
@pytest.mark.parametrize("stop", [Interrupt, KeyboardInterrupt])
def test_checkpoint_cadence(scene, reference, tmp_path, monkeypatch, stop):
    """With the default interval the checkpoint after the first chunk is the only one in a
    short run: a crash after three chunks leaves one chunk checkpointed; Ctrl-C writes the three
    merged chunks on its way out. Both resume to the uninterrupted result."""
    real = executor.local

    def three_then_stopped(jobs):
        for i, item in enumerate(real(jobs)):
            if i == 3:
                raise stop
            yield item

    monkeypatch.setattr(executor, "local", three_then_stopped)
    with pytest.raises(Interrupt if stop is Interrupt else driver.RunInterrupted):
        driver.run(scene, tmp_path / "r", progress=False)
    monkeypatch.setattr(executor, "local", real)
    partial = json.loads((tmp_path / "r" / "manifest.json").read_text())
    assert partial["status"] == "partial"
    assert partial["chunks_done"] == (1 if stop is Interrupt else 3)
    assert len(counts.Tally.load(tmp_path / "r" / "checkpoint.npz").finished) == (
        partial["chunks_done"])
    driver.run(scene, tmp_path / "r", resume=True, progress=False)
    assert chunks_computed(tmp_path / "r") == CHUNKS - partial["chunks_done"]
    same_results(reference, tmp_path / "r")


@pytest.mark.slow
def test_resume_cluster_run_locally(scene, reference, client, tmp_path, monkeypatch):
    real_map = cluster.map_chunks

    def killed_after_five(*args, **kwargs):
        for i, item in enumerate(real_map(*args, **kwargs)):
            if i == 5:
                raise Interrupt
            yield item

    monkeypatch.setattr(cluster, "map_chunks", killed_after_five)
    monkeypatch.setattr(driver, "CHECKPOINT_INTERVAL_S", 0.0)  # a checkpoint after every chunk
    with pytest.raises(Interrupt):
        driver.run(scene, tmp_path / "r", progress=False, scheduler=client)
    monkeypatch.setattr(cluster, "map_chunks", real_map)
    assert json.loads((tmp_path / "r" / "manifest.json").read_text())["chunks_done"] == 5
    calls = []
    real_chunk = chunk.run_chunk

    def count_chunk(*args, **kwargs):
        calls.append(args[2:4])
        return real_chunk(*args, **kwargs)

    monkeypatch.setattr(executor, "run_chunk", count_chunk)
    driver.run(scene, tmp_path / "r", resume=True, progress=False)
    assert len(calls) == CHUNKS - 5 == chunks_computed(tmp_path / "r")
    same_results(reference, tmp_path / "r")


@pytest.mark.slow
def test_sweep_on_the_cluster_equals_the_local_sweep(scene, client, tmp_path):
    grid = {"centre": [1.0, 2.5], "eps": [0.5, 0.7]}
    kw = dict(grid=grid, n_star=20, particles=600, verify_samples=40, progress=False)
    here = sweep.sweep(scene, tmp_path / "here", **kw)
    there = sweep.sweep(scene, tmp_path / "there", scheduler=client, **kw)
    assert there["session"]["chunks_computed"] == here["session"]["chunks_computed"] == 8
    for name in ("sweep.csv", "sample.csv"):
        assert (tmp_path / "here" / name).read_bytes() == (tmp_path / "there" / name).read_bytes()


@pytest.mark.slow
def test_failed_chunk_fails_the_run(scene, client, tmp_path):
    def unsettled(*args):
        result = chunk.run_chunk(*args)
        result.failure = "verify could not settle the flagged collision (test)"
        return result

    with pytest.raises(RunFailed, match="could not settle"):
        for key, result in cluster.map_chunks(client, [((0, 0), (scene, 17, 0, 0, 1800, None))],
                                              function=unsettled):
            assert key == (0, 0)
            chunk.check_result(result)
    result = chunk.run_chunk(scene, 17, 0, 0, 1800)
    result.code = "0" * 16
    with pytest.raises(RunFailed, match="other sources"):
        chunk.check_result(result)


@pytest.mark.slow
def test_unreachable_scheduler_exits_2(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", "1s")
    path = tmp_path / "scene.toml"
    path.write_text(SCENE)
    assert main(["run", str(path), "--out", str(tmp_path / "x"), "--quiet",
                 "--scheduler", "tcp://127.0.0.1:9"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bouncer: error: cannot connect to the Dask scheduler") and (
        err.count("\n") == 1), err


def test_missing_distributed_is_a_one_line_error(monkeypatch):
    monkeypatch.setitem(__import__("sys").modules, "distributed", None)
    with pytest.raises(ValueError, match=r"bouncer-verify\[cluster\]"):
        cluster.check_available()


@pytest.mark.slow
def test_a_killed_worker_loses_and_doubles_nothing(scene, reference, client, tmp_path,
                                                   monkeypatch):
    """The first task to start makes its worker process exit (os._exit) before it returns;
    the nanny restarts the worker, the scheduler reruns the chunk; the result is the local one.
    Last in the module: it restarts a worker of the shared cluster."""
    marker = str(tmp_path / "died")

    def dying(*args):
        import os as os_

        from reports.runs.chunk import run_chunk

        try:
            fd = os_.open(marker, os_.O_CREAT | os_.O_EXCL | os_.O_WRONLY)
        except FileExistsError:
            return run_chunk(*args)
        os_.write(fd, str(os_.getpid()).encode())
        os_.close(fd)
        os_._exit(1)

    pids = set(client.run(os.getpid).values())
    monkeypatch.setattr(cluster, "map_chunks",
                        functools.partial(cluster.map_chunks, function=dying))
    driver.run(scene, tmp_path / "r", progress=False, scheduler=client)
    died = int(Path(marker).read_text())
    assert died in pids  # a worker of the cluster really died mid-run
    assert chunks_computed(tmp_path / "r") == CHUNKS
    same_results(reference, tmp_path / "r")
