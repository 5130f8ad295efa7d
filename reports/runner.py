"""Trusted ensemble runs: the driver around ``fastpath.ensemble`` with ``verify`` checks.

The run is a fixed list of chunks (experiment e, chunk k) of at most ``scene.chunk_size`` starts.
Chunk (e, k) draws its starts, its verification picks and their collision indices from
``numpy.random.SeedSequence(seed, spawn_key=(e, k))`` only, so a result depends on
(scene, seed, particles) and not on threads, chunk order or interruptions; counts are integers,
summed exactly. After each chunk:

1. flagged particles (a flight float64 cannot decide) are settled by ``verify.step`` and resume
   in ``fastpath`` until they escape or reach the horizon;
2. the chunk's sampled collisions are recomputed by ``verify.step`` from the same float64 state;
   the error of the fast flight time is measured in units of kappa*u (kappa from
   ``verify.condition_number``, u = 2**-53):  err = |tau_fast - tau_ref| / (tau_ref*kappa*u).
   tau_fast - tau_ref > 16*kappa*u*tau_ref means the fast path jumped past the first collision
   (an overstep): the run stops with status ``failed``;
3. merged counts and the finished chunks are checkpointed atomically, with the manifest
   (status ``partial``). ``resume`` skips finished chunks; the end result is identical.

Steps 1 and 2 are ``run_chunk(scene, seed, curve, chunk, particles)``, a pure function of its
arguments returning a ``ChunkResult`` (counts, the verified sample rows, overstepped rows, or a
failure as data), so it runs the same in this process or as a task on a Dask worker
(``reports.cluster``, ``run(..., scheduler=...)``). The merge (``Tally.merge``) is keyed by the
chunk index (curve, chunk): a chunk already merged is ignored, counts are integer sums, and the
sample rows and the list of finished chunks are kept sorted by index, so the merged state is a
function of the *set* of finished chunks only, whatever order they finish in.
"""

from __future__ import annotations

import bisect
import hashlib
import json
import math
import platform
import subprocess
import sys
import threading
import time
from contextlib import ExitStack, closing
from dataclasses import dataclass, field
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path

import numpy as np

import verify
from fastpath.ensemble import (
    NO_LIMIT,
    bin_index,
    escape_chunk,
    exit_hole,
    log_edges,
    portrait_chunk,
)
from reports import rundir
from reports.rundir import RunFailed
from reports.scenes import Scene, parse_scene
from reports.statistics import survival_curve, wilson

UNIT_ROUNDOFF = 2.0**-53
OVERSTEP_TOLERANCE = 16.0  # in units of kappa*u
VERIFY_DPS = 30
BLOCKS = 64  # histogram rows per chunk (not threads: results do not depend on threads)
PORTRAIT_BLOCKS = 8
COLLISION_DECADES = 8  # collision bins: 1 .. 1e8
TIME_FIRST, TIME_DECADES = 0.1, 9  # time bins: [0, 0.1), then 0.1 .. 1e8
SAMPLE_DEPTH = 10**6  # sampled collision indices are log-uniform in [1, min(horizon, this)]


@dataclass
class Plan:
    """What a run computes: the scene with its particle count and seed, chunks and bins."""

    scene: Scene
    particles: int
    seed: int
    experiments: list
    chunks_per_experiment: int
    samples_per_chunk: int
    n_edges: np.ndarray
    t_edges: np.ndarray

    @property
    def chunks(self):
        return [(e, k) for e in range(len(self.experiments))
                for k in range(self.chunks_per_experiment)]

    def chunk_particles(self, k):
        size = self.scene.chunk_size
        return min(size, self.particles - k * size)


def make_plan(scene, particles=None, seed=None):
    """The run plan; ``particles`` (per curve) and ``seed`` override the scene's."""
    particles = scene.particles if particles is None else int(particles)
    seed = scene.seed if seed is None else int(seed)
    if particles < 1:
        raise ValueError(f"--particles must be >= 1, got {particles}")
    if seed < 0:
        raise ValueError(f"--seed must be >= 0, got {seed}")
    experiments = scene.experiments()
    per_exp = math.ceil(particles / scene.chunk_size)
    total_chunks = per_exp * len(experiments)
    total = particles * len(experiments)
    # at least scene.verify_samples a run, scaled down for tiny runs (but never to none)
    wanted = min(scene.verify_samples, max(1, total // 10))
    samples = max(1, math.ceil(wanted / total_chunks))
    n_edges = log_edges(1.0, COLLISION_DECADES, scene.bins_per_decade, integer=True)
    t_edges = np.concatenate([[0.0], log_edges(TIME_FIRST, TIME_DECADES, scene.bins_per_decade)])
    return Plan(scene, particles, seed, experiments, per_exp, samples, n_edges, t_edges)


def chunk_starts(plan, e, k):
    """Starts (phi, v) and verification picks (slot, target) of chunk k of experiment e."""
    exp = plan.experiments[e]
    m = plan.chunk_particles(k)
    rng = np.random.default_rng(np.random.SeedSequence(plan.seed, spawn_key=(e, k)))
    phi = rng.uniform(exp.phi[0], exp.phi[1], m)
    v = rng.uniform(exp.v[0], exp.v[1], m)
    s = min(plan.samples_per_chunk, m)
    picks = rng.choice(m, size=s, replace=False)
    depth = min(plan.scene.max_collisions or SAMPLE_DEPTH, SAMPLE_DEPTH)
    targets = np.floor(depth ** rng.random(s)).astype(np.int64)
    slot = np.full(m, -1, np.int64)
    slot[picks] = np.arange(s)
    target = np.zeros(m, np.int64)
    target[picks] = targets
    return phi, v, slot, target, picks


@dataclass
class Tally:
    """Merged counts of finished chunks (the checkpoint's content)."""

    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    portrait: np.ndarray
    collisions: int = 0
    settled: int = 0
    finished: list = field(default_factory=list)
    samples: list = field(default_factory=list)
    elapsed: float = 0.0
    started: str = ""

    @classmethod
    def empty(cls, plan):
        n_exp = len(plan.experiments)
        holes = max([len(x.hole_lo) for x in plan.experiments] + [1])
        nb, tb = len(plan.n_edges), len(plan.t_edges)
        sc = plan.scene
        shape = (sc.phi_bins, sc.v_bins) if sc.kind == "phase-space" else (0, 0)
        return cls(np.zeros((n_exp, holes, nb), np.int64), np.zeros((n_exp, holes, tb), np.int64),
                   np.zeros((n_exp, nb), np.int64), np.zeros((n_exp, tb), np.int64),
                   np.zeros(shape, np.int64), started=_now())

    def save(self, path):
        meta = {"collisions": self.collisions, "settled": self.settled,
                "finished": self.finished, "samples": self.samples, "elapsed": self.elapsed,
                "started": self.started}
        rundir.save_npz_atomic(path, esc_n=self.esc_n, esc_t=self.esc_t, cens_n=self.cens_n,
                               cens_t=self.cens_t, portrait=self.portrait,
                               meta=np.array(json.dumps(meta)))

    @classmethod
    def load(cls, path):
        with np.load(path) as z:
            meta = json.loads(str(z["meta"]))
            return cls(z["esc_n"], z["esc_t"], z["cens_n"], z["cens_t"], z["portrait"],
                       meta["collisions"], meta["settled"],
                       sorted(tuple(c) for c in meta["finished"]),
                       sorted(meta["samples"], key=_sample_key), meta["elapsed"],
                       meta["started"])

    def merge(self, result, kind):
        """Add a finished chunk's ``ChunkResult``; False (and nothing changes) if its index
        (curve, chunk) is merged already. Keyed and sorted by index, so any completion order
        gives the same state."""
        key = (result.curve, result.chunk)
        at = bisect.bisect_left(self.finished, key)
        if at < len(self.finished) and self.finished[at] == key:
            return False
        e, counts = result.curve, result.counts
        self.esc_n[e, :len(counts.esc_n)] += counts.esc_n
        self.esc_t[e, :len(counts.esc_t)] += counts.esc_t
        self.cens_n[e] += counts.cens_n
        self.cens_t[e] += counts.cens_t
        if kind == "phase-space":
            self.portrait += counts.portrait
        self.collisions += counts.collisions
        self.settled += counts.settled
        for row in result.rows:
            bisect.insort(self.samples, list(row), key=_sample_key)
        self.finished.insert(at, key)
        return True


def _sample_key(row):
    return (int(row[0]), int(row[1]), int(row[2]))


@dataclass
class ChunkCounts:
    esc_n: np.ndarray
    esc_t: np.ndarray
    cens_n: np.ndarray
    cens_t: np.ndarray
    portrait: np.ndarray
    collisions: int = 0
    settled: int = 0


@dataclass
class ChunkResult:
    """What ``run_chunk`` returns (small and picklable: it travels back from a Dask worker).

    ``rows`` are the chunk's verified sample rows (``rundir.SAMPLE_COLUMNS``), ``bad`` those of
    them that overstepped; ``failure`` is the message of a collision verify could not settle
    (the run fails with it) or None; ``code`` a digest of the sources that computed it.
    """

    curve: int
    chunk: int
    counts: ChunkCounts
    rows: list
    bad: list
    failure: str | None = None
    seconds: float = 0.0
    code: str = ""


# numba's workqueue threading layer must not be entered by two threads at once (a Dask worker
# with several threads would); one kernel at a time per process, each parallel inside
_KERNEL_LOCK = threading.Lock()


def _kernel(plan, exp, state, slot, target, samples, out):
    """One pass of the fast kernel over the particles in ``state`` = (phi, v, t, n)."""
    sc = plan.scene
    phi, v, t, n = state
    m = len(phi)
    flags, flag_state = np.zeros(m, np.int8), np.zeros((m, 4))
    if sc.kind == "phase-space":
        blocks = min(PORTRAIT_BLOCKS, m)
        counts = np.zeros((blocks, sc.phi_bins, sc.v_bins), np.int64)
        collisions = np.zeros(blocks, np.int64)
        with _KERNEL_LOCK:
            portrait_chunk(phi, v, n, sc.eps, sc.max_collisions, sc.v_range[0], sc.v_range[1],
                           slot, target, counts, collisions, flags, flag_state, samples)
        out.portrait += counts.sum(axis=0)
    else:
        blocks = min(BLOCKS, m)
        holes, nb, tb = len(exp.hole_lo), len(plan.n_edges), len(plan.t_edges)
        esc_n, esc_t = np.zeros((blocks, holes, nb), np.int64), np.zeros((blocks, holes, tb),
                                                                         np.int64)
        cens_n, cens_t = np.zeros((blocks, nb), np.int64), np.zeros((blocks, tb), np.int64)
        collisions = np.zeros(blocks, np.int64)
        with _KERNEL_LOCK:
            escape_chunk(phi, v, t, n, sc.eps, np.array(exp.hole_lo), np.array(exp.hole_width),
                         sc.max_collisions or NO_LIMIT, sc.max_time or np.inf, plan.n_edges,
                         plan.t_edges, "collisions" in sc.clocks, "time" in sc.clocks, slot,
                         target, esc_n, esc_t, cens_n, cens_t, collisions, flags, flag_state,
                         samples)
        out.esc_n[:holes] += esc_n.sum(axis=0)
        out.esc_t[:holes] += esc_t.sum(axis=0)
        out.cens_n += cens_n.sum(axis=0)
        out.cens_t += cens_t.sum(axis=0)
    out.collisions += int(collisions.sum())
    return flags, flag_state


def settle(phi, v, eps):
    """The collision float64 could not decide, by ``verify.step``: floats (phi1, v1, tau)."""
    try:
        phi1, v1, tau = verify.step(phi, v, eps, dps=VERIFY_DPS)
    except (verify.UndecidableCollision, ValueError) as err:
        raise RunFailed(f"verify could not settle the flagged collision from phi={phi!r},"
                        f" v={v!r}: {err}") from None
    return float(phi1), float(v1), float(tau)


def simulate_chunk(plan, e, k):
    """Simulate chunk k of experiment e, settling flagged collisions by verify:
    (ChunkCounts, sample rows not yet verified)."""
    sc, exp = plan.scene, plan.experiments[e]
    phi, v, slot, target, picks = chunk_starts(plan, e, k)
    m = len(phi)
    holes, nb, tb = max(len(exp.hole_lo), 1), len(plan.n_edges), len(plan.t_edges)
    shape = (sc.phi_bins, sc.v_bins) if sc.kind == "phase-space" else (0, 0)
    out = ChunkCounts(np.zeros((holes, nb), np.int64), np.zeros((holes, tb), np.int64),
                      np.zeros(nb, np.int64), np.zeros(tb, np.int64), np.zeros(shape, np.int64))
    samples = np.zeros((len(picks), 6))
    state = (phi, v, np.zeros(m), np.zeros(m, np.int64))
    max_n = sc.max_collisions or NO_LIMIT
    max_t = sc.max_time or np.inf
    hole_lo, hole_w = np.array(exp.hole_lo), np.array(exp.hole_width)
    while len(state[0]):
        flags, flag_state = _kernel(plan, exp, state, slot, target, samples, out)
        resume = []
        for i in np.flatnonzero(flags):
            phi_i, v_i, t_i, n_i = flag_state[i]
            phi1, v1, tau = settle(phi_i, v_i, sc.eps)
            out.settled += 1
            t1, n1 = t_i + tau, int(n_i) + 1
            if t1 > max_t:  # as the kernel: censored before this collision
                out.cens_n[bin_index(plan.n_edges, float(n_i))] += 1
                out.cens_t[bin_index(plan.t_edges, t1)] += 1
                continue
            out.collisions += 1
            if sc.kind == "phase-space":
                lo, hi = sc.v_range
                if lo <= v1 < hi:
                    p = min(int(phi1 / (2 * math.pi) * sc.phi_bins), sc.phi_bins - 1)
                    q = min(int((v1 - lo) / (hi - lo) * sc.v_bins), sc.v_bins - 1)
                    out.portrait[p, q] += 1
                if n1 >= max_n:
                    continue
            else:
                j = exit_hole(phi1, hole_lo, hole_w)
                if j >= 0:
                    out.esc_n[j, bin_index(plan.n_edges, float(n1))] += 1
                    out.esc_t[j, bin_index(plan.t_edges, t1)] += 1
                    continue
            resume.append((i, phi1, v1, t1, n1))
        idx = np.array([r[0] for r in resume], np.int64)
        state = tuple(np.array([r[c] for r in resume], dtype)
                      for c, dtype in ((1, float), (2, float), (3, float), (4, np.int64)))
        slot, target = slot[idx], target[idx]
    rows = [[e, k, int(picks[s]), *map(float, samples[s])] for s in range(len(picks))
            if samples[s, 0] > 0]
    return out, rows


def run_chunk(scene, seed, curve, chunk, particles=None, threads=None):
    """Chunk ``chunk`` of curve (experiment) ``curve`` of the run of ``scene`` with ``seed`` and
    ``particles`` per curve (default: the scene's): simulated, flagged collisions settled and
    the sample verified, all here (in the worker, on a cluster). A pure function of its
    arguments; ``threads`` (numba threads of this call) does not change the result.

    A collision verify cannot settle is returned as ``failure`` (data, not an exception), so
    that Dask's retries are spent only on lost workers and unexpected errors.
    """
    t0 = time.perf_counter()
    plan = make_plan(scene, particles, seed)
    if not (0 <= curve < len(plan.experiments) and 0 <= chunk < plan.chunks_per_experiment):
        raise ValueError(f"no chunk ({curve}, {chunk}) in a run of {len(plan.experiments)}"
                         f" curves x {plan.chunks_per_experiment} chunks")
    if threads is not None:
        import numba

        numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    empty = ChunkCounts(*(np.zeros(0, np.int64) for _ in range(5)))
    try:
        counts, rows = simulate_chunk(plan, curve, chunk)
        bad = verify_rows(rows, scene.eps)
    except RunFailed as err:
        return ChunkResult(curve, chunk, empty, [], [], str(err),
                           time.perf_counter() - t0, CODE_DIGEST)
    return ChunkResult(curve, chunk, counts, rows, bad, None, time.perf_counter() - t0,
                       CODE_DIGEST)


# the verify modules behind verify.step and verify.condition_number (what a chunk calls)
_VERIFY_SOURCES = ("_inputs", "_precision", "certify", "collision", "conditioning", "errors",
                   "gap")


def _code_digest():
    """Digest of the sources a chunk's result depends on (all of fastpath, verify's step and
    condition number, runner, scenes), as imported: the client refuses results from workers
    that run other sources."""
    root = Path(__file__).resolve().parent.parent
    digest = hashlib.sha256()
    files = [*sorted((root / "fastpath").glob("*.py")),
             *(root / "verify" / f"{name}.py" for name in _VERIFY_SOURCES),
             root / "reports" / "runner.py", root / "reports" / "scenes.py"]
    for path in files:
        digest.update(path.name.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


CODE_DIGEST = _code_digest()


def check_sample(phi, v, tau, eps):
    """verify's flight time from the same float64 state: (tau_ref, error in kappa*u, overstep)."""
    tau_ref = verify.step(phi, v, eps, dps=VERIFY_DPS)[2]
    kappa = verify.condition_number(phi, v, eps, tau_ref)
    rel = (tau - tau_ref) / tau_ref
    error = float(abs(rel) / (kappa * UNIT_ROUNDOFF))
    return float(tau_ref), error, bool(rel > OVERSTEP_TOLERANCE * kappa * UNIT_ROUNDOFF)


def verify_rows(rows, eps):
    """Recompute the chunk's sample; rows gain tau_ref and error. Returns overstepped rows."""
    bad = []
    for row in rows:
        _, _, _, n, phi, v, phi1, v1, tau = row
        try:
            tau_ref, error, overstep = check_sample(phi, v, tau, eps)
        except (verify.UndecidableCollision, ValueError) as err:
            raise RunFailed(f"verify could not decide sampled collision {int(n)} from "
                            f"phi={phi!r}, v={v!r} that fastpath converged: {err}") from None
        row[3] = int(n)
        row.extend([tau_ref, error])
        if overstep:
            bad.append(row)
    return bad


def summary(tally):
    """The verification summary of the manifest."""
    worst = max(tally.samples, key=lambda r: r[10], default=None)
    out = {"sampled": len(tally.samples),
           "worst_error": worst[10] if worst else 0.0,
           "uncertain_settled": tally.settled,
           "overstepped": 0,
           "error_unit": "condition number x unit roundoff (kappa * 2**-53)",
           "overstep_tolerance": OVERSTEP_TOLERANCE,
           "verify_dps": VERIFY_DPS}
    if worst:
        out["worst_at"] = dict(zip(rundir.SAMPLE_COLUMNS, worst, strict=True))
    return out


def run(scene, out, particles=None, seed=None, resume=False, force=False, progress=True,
        threads=None, scheduler=None):
    """Run (or resume) ``scene`` into the directory ``out``; returns the final manifest.

    ``scheduler``: None runs the chunks here, one after another (numba threads inside each);
    a Dask scheduler address (``"tcp://host:8786"``) or a ``distributed.Client`` sends them as
    tasks to that cluster (``reports.cluster``). The result is bit-identical either way, and a
    run started one way resumes the other way without recomputing finished chunks.

    Raises ValueError for bad input (exit 2) and RunFailed when a check fails (exit 1).
    """
    plan = make_plan(scene, particles, seed)
    out = Path(out)
    if scheduler is not None:
        from reports import cluster

        cluster.check_available()
    resuming = rundir.prepare(out, resume, force)
    ckpt = out / "checkpoint.npz"
    if resuming:
        old = rundir.read_json(out / rundir.MANIFEST)
        stored = parse_scene((out / "scene.toml").read_text(encoding="utf-8"), "stored scene")
        if stored != scene or old["particles"] != plan.particles or old["seed"] != plan.seed:
            raise ValueError(f"--resume: {out} holds a run of scene {old['scene']['name']!r} with "
                             f"{old['particles']} particles and seed {old['seed']}; give the"
                             " same scene, --particles and --seed")
        if old["status"] == "complete":
            return old
        tally = Tally.load(ckpt) if ckpt.is_file() else Tally.empty(plan)
    else:
        rundir.write_atomic(out / "scene.toml", scene.source)
        tally = Tally.empty(plan)
    done = set(tally.finished)
    todo = [c for c in plan.chunks if c not in done]
    session = {"scheduler": None, "workers": None, "worker_threads": None,
               "chunks_computed": 0}
    _manifest(out, plan, tally, "partial", threads, session=session)
    total = plan.particles * len(plan.experiments)
    bar = _progress(plan, total - sum(plan.chunk_particles(k) for _, k in todo), total, progress)
    jobs = [((e, k), (scene, plan.seed, e, k, plan.particles, threads)) for e, k in todo]
    try:
        with _executor(scheduler, session) as execute, closing(execute(jobs)) as results:
            last = time.perf_counter()
            for _, result in results:
                check_result(result)
                if not tally.merge(result, scene.kind):
                    continue
                session["chunks_computed"] += 1
                now = time.perf_counter()
                tally.elapsed += now - last
                last = now
                if result.bad:
                    _fail(out, plan, tally, threads, result.bad, session)
                tally.save(ckpt)
                _manifest(out, plan, tally, "partial", threads, session=session)
                if bar is not None:
                    bar.update(plan.chunk_particles(result.chunk))
                    bar.set_postfix_str(f"{tally.collisions / max(tally.elapsed, 1e-9):.3g}"
                                        " coll/s", refresh=False)
    except RunFailed as err:
        if not getattr(err, "recorded", False):
            _manifest(out, plan, tally, "failed", threads, failure=str(err), session=session)
        raise
    finally:
        if bar is not None:
            bar.close()
    finished = set(tally.finished)
    missing = [c for c in plan.chunks if c not in finished]
    if missing:  # cannot happen unless an executor drops a task: never write a short result
        raise RunFailed(f"{len(missing)} chunk(s) never came back, first {missing[0]}")
    write_results(out, plan, tally)
    return _manifest(out, plan, tally, "complete", threads, session=session)


def check_result(result):
    """RunFailed for a chunk that failed (data from ``run_chunk``) or that other sources
    computed (a worker with another bouncer-verify: not bit-identical)."""
    if result.failure:
        raise RunFailed(result.failure)
    if result.code != CODE_DIGEST:
        raise RunFailed(f"chunk ({result.curve}, {result.chunk}) was computed by other sources"
                        f" (digest {result.code}, here {CODE_DIGEST}): install the same"
                        " bouncer-verify on the client and every worker")


def _local(jobs):
    for key, args in jobs:
        yield key, run_chunk(*args)


class _executor:
    """Context manager giving ``execute(jobs) -> iterator of (key, ChunkResult)``: here, or on
    the Dask cluster of ``scheduler`` (closing what it opened on exit)."""

    def __init__(self, scheduler, session):
        self.scheduler, self.session, self.stack = scheduler, session, None

    def __enter__(self):
        if self.scheduler is None:
            return _local
        from reports import cluster

        self.stack = ExitStack()
        client = self.stack.enter_context(cluster.connect(self.scheduler))
        self.session.update(cluster.describe(client))
        return lambda jobs: cluster.map_chunks(client, jobs)

    def __exit__(self, *exc):
        if self.stack is not None:
            self.stack.close()
        return False


def _fail(out, plan, tally, threads, bad, session=None):
    row = dict(zip(rundir.SAMPLE_COLUMNS, bad[0], strict=True))
    msg = (f"OVERSTEP: {len(bad)} sampled collision(s) where the fast flight time exceeds"
           f" verify's first root by more than {OVERSTEP_TOLERANCE:g}*kappa*u, first: {row}")
    ver = summary(tally)
    ver["overstepped"] = len(bad)
    _manifest(out, plan, tally, "failed", threads, failure=msg, verification=ver,
              session=session)
    write_results(out, plan, tally)
    err = RunFailed(msg)
    err.recorded = True
    raise err


def _progress(plan, initial, total, enabled):
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, unit="particle", unit_scale=True,
                desc=plan.scene.name, file=sys.stderr, smoothing=0.1)


def _now():
    return datetime.now(UTC).isoformat(timespec="seconds")


def _versions():
    out = {"python": platform.python_version()}
    for dist in ("bouncer-verify", "numpy", "numba", "mpmath", "scipy"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = None
    return out


def _git():
    here = Path(__file__).resolve().parent
    try:
        commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True,
                                text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain"], cwd=here, capture_output=True,
                               text=True, timeout=10, check=True).stdout.strip() != ""
    except (OSError, subprocess.SubprocessError):
        return None
    return {"commit": commit, "dirty": dirty}


def _manifest(out, plan, tally, status, threads, failure=None, verification=None, session=None):
    sc = plan.scene
    curves = {}
    for e, exp in enumerate(plan.experiments):
        clock = "esc_n" if "collisions" in sc.clocks else "esc_t"
        esc = getattr(tally, clock)[e]
        cens = tally.cens_n[e] if clock == "esc_n" else tally.cens_t[e]
        done = sum(plan.chunk_particles(k) for ee, k in tally.finished if ee == e)
        curves[exp.name] = {"particles_done": done, "censored": int(cens.sum()),
                            "escaped": {c: int(esc[j].sum()) for j, c in enumerate(exp.curves)}}
    manifest = {
        "status": status,
        "scene": {"name": sc.name, "kind": sc.kind, "file": "scene.toml", "eps": sc.eps,
                  "horizon": {"collisions": sc.max_collisions, "time": sc.max_time}},
        "seed": plan.seed,
        "particles": plan.particles,
        "particles_total": plan.particles * len(plan.experiments),
        "chunk_size": sc.chunk_size,
        "chunks": len(plan.chunks),
        "chunks_done": len(tally.finished),
        "threads": threads,
        "session": session,
        "versions": _versions(),
        "git": _git(),
        "started": tally.started,
        "updated": _now(),
        "finished": _now() if status == "complete" else None,
        "wall_time_s": round(tally.elapsed, 3),
        "collisions": tally.collisions,
        "collisions_per_s": round(tally.collisions / tally.elapsed) if tally.elapsed else None,
        "verification": verification or summary(tally),
        "curves": curves,
        "bins": {"collisions": {"first": 1, "decades": COLLISION_DECADES,
                                "per_decade": sc.bins_per_decade, "integer": True},
                 "time": {"first": TIME_FIRST, "decades": TIME_DECADES,
                          "per_decade": sc.bins_per_decade, "below_first": [0.0, TIME_FIRST]}},
        "survival_band": "95% Wilson score interval",
    }
    if failure:
        manifest["failure"] = failure
    rundir.write_json(out / rundir.MANIFEST, manifest)
    return manifest


def survival_rows(plan, tally):
    """Rows curve,clock,x,p,p_lo,p_hi of survival.csv (module docstring of statistics)."""
    rows = []
    for e, exp in enumerate(plan.experiments):
        for clock in plan.scene.clocks:
            if clock == "collisions":
                edges, esc, cens = plan.n_edges, tally.esc_n[e], tally.cens_n[e]
            else:
                edges, esc, cens = plan.t_edges, tally.esc_t[e], tally.cens_t[e]
            for j, curve in enumerate(exp.curves):
                x, surv, p = survival_curve(esc[j], cens, edges, plan.particles, clock,
                                            add_censored=plan.scene.kind == "escape")
                lo, hi = wilson(surv, plan.particles)
                for xi, pi, li, hi_ in zip(x, p, lo, hi, strict=True):
                    xs = str(int(xi)) if clock == "collisions" else repr(float(xi))
                    rows.append([curve, clock, xs, repr(float(pi)), repr(float(li)),
                                 repr(float(hi_))])
    return rows


def write_results(out, plan, tally):
    """survival.csv, counts.csv (or portrait.npy) and sample.csv from the merged tally."""
    sc = plan.scene
    if sc.kind == "phase-space":
        rundir.save_npy_atomic(out / "portrait.npy", tally.portrait)
    else:
        rundir.write_csv(out / "survival.csv", ["curve", "clock", "x", "p", "p_lo", "p_hi"],
                         survival_rows(plan, tally))
        rows = []
        for e, exp in enumerate(plan.experiments):
            for clock in sc.clocks:
                edges = plan.n_edges if clock == "collisions" else plan.t_edges
                esc = tally.esc_n[e] if clock == "collisions" else tally.esc_t[e]
                cens = tally.cens_n[e] if clock == "collisions" else tally.cens_t[e]
                outcomes = [(c, esc[j]) for j, c in enumerate(exp.curves)] + [("censored", cens)]
                for name, counts in outcomes:
                    for b in np.flatnonzero(counts):
                        rows.append([exp.name, clock, name, repr(float(edges[b])),
                                     int(counts[b])])
        rundir.write_csv(out / "counts.csv",
                         ["experiment", "clock", "outcome", "lower_edge", "count"], rows)
    samples = sorted(tally.samples, key=lambda r: (r[0], r[1], r[2]))
    rundir.write_csv(out / "sample.csv", rundir.SAMPLE_COLUMNS,
                     [[*map(int, r[:4]), *map(repr, map(float, r[4:]))] for r in samples])
