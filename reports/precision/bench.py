"""``bouncer bench``: speed of the exact map against the Holmes map, measured in one process.

1. ns per collision of ``fastpath.orbit`` for N collisions at eps = 0.6 from the middle of the
   paper's start box, (phi, v) = (4.0, 3.0): the exact map (``method="auto"``: bracketed Halley;
   ``method="lower_bound"``: the paper's lower-bound steps), fastpath's Holmes map and the bare
   Holmes loop (``reports.precision.bare_holmes``: the textbook step into the same arrays). The
   models take turns, R times, on one core (no parallel kernel is involved), and the fastest
   of each is kept, so load from other processes on a shared machine inflates neither side of
   the ratio more than the other. Iterations per flight come from the same orbits; the ratios
   are to the bare loop.
2. The ensemble workload users run, the paper's escape scene (``paper-escape``: eps = 0.6, starts
   at 2 < v < 4, six holes), P particles per curve, all threads, against Holmes-map ensembles on
   the same starts, holes, horizon and bins (no verification, no flags, starts drawn before the
   clock starts): the bare loop (``reports.precision.bare_holmes``, the reference of the ratios)
   and fastpath's (``fastpath.kernels.escape.holmes_escape_chunk``, the phase reduced exactly):
   * kernel only: ``escape_chunk`` over the same chunks of starts, no verification sample;
   * end to end: ``bouncer run`` into a temporary directory (start generation, the verification
     sample recomputed by verify, histograms, checkpoints, manifest), wall time.
   The four are timed in turns, R times, and the fastest of each is kept. The ratio is the wall
   time of the exact ensemble over the bare loop's (the same particles to their exits; the two
   maps make slightly different numbers of collisions, so collisions/s are printed too).
3. Peak resident memory of the process.
4. Dissipation (``dissipative_section``): ns per collision of ``fastpath.orbit`` with linear
   drag, quadratic drag and restitution r < 1, next to the elastic orbit at the same eps (2: at
   eps <= 1 an r < 1 orbit sticks for good and stops) and start, interleaved as in 1, printed
   as ratios to the elastic orbit.
5. Cold start (``time_cold_start``): what a new user waits for, each command in a fresh
   interpreter with an empty numba cache (every kernel it uses compiled), then once more with
   the cache it filled: the README's quick start and a first ``bouncer run paper-escape``.

Printed as ratios measured in this run, never asserted in a test: machines are shared and noisy.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass

import numba
import numpy as np

import fastpath
from fastpath.kernels.arrays import NO_LIMIT, Bins, EscapeCounts, Holes, Horizon, Starts
from fastpath.kernels.escape import holmes_escape_chunk
from fastpath.physics import holmes
from reports.precision.bare_holmes import bare_holmes_chunk, bare_holmes_orbit
from reports.runs.chunk import kernel
from reports.runs.counts import Counts
from reports.runs.driver import run
from reports.runs.plan import BLOCKS, chunk_starts, make_plan
from reports.runs.scenes import load_scene

ORBIT_MODELS = (("exact", "auto"), ("exact", "lower_bound"), ("holmes", "auto"))
START = (4.0, 3.0)


@dataclass
class OrbitTiming:
    label: str
    ns_per_collision: float
    mean_iterations: float | None
    max_iterations: int | None


BARE_HOLMES = "Holmes map, bare loop"


def time_orbits(eps=0.6, collisions=10_000_000, repeats=5, start=START):
    """{label: OrbitTiming}, the best of ``repeats`` interleaved runs of each model and of the
    bare Holmes loop."""
    for model, method in ORBIT_MODELS:  # compile (or load from the cache) outside the timing
        fastpath.orbit(*start, eps, 10, model=model, method=method)
    bare_holmes_orbit(*start, eps, 10)
    best = {}

    def keep(timing):
        old = best.get(timing.label)
        if old is None or timing.ns_per_collision < old.ns_per_collision:
            best[timing.label] = timing

    for _ in range(repeats):
        for model, method in ORBIT_MODELS:
            t0 = time.perf_counter()
            orb = fastpath.orbit(*start, eps, collisions, model=model, method=method)
            ns = (time.perf_counter() - t0) / collisions * 1e9
            label = "Holmes map (fastpath)" if model == "holmes" else f"exact ({method})"
            its = orb.iterations
            keep(OrbitTiming(label, ns, float(its.mean()) if its is not None else None,
                             int(its.max()) if its is not None else None))
        t0 = time.perf_counter()
        bare_holmes_orbit(*start, eps, collisions)
        keep(OrbitTiming(BARE_HOLMES, (time.perf_counter() - t0) / collisions * 1e9, None, None))
    return best


@dataclass
class EnsembleTiming:
    label: str
    wall: float
    collisions: int
    particles: int
    curves: int


def _chunks(plan):
    """Every chunk's starts and verification picks, drawn once (outside the timings)."""
    return [(e, chunk_starts(plan, e, k)) for e in range(len(plan.experiments))
            for k in range(plan.chunks_per_experiment)]


def _kernel_pass(plan, chunks, model):
    """All chunks through the run's exact kernel call (``chunk.kernel``, no sample), fastpath's
    Holmes kernel ("holmes") or the bare Holmes loop ("bare") on the same bins and blocks:
    collisions."""
    sc = plan.scene
    total = 0
    for e, (phi, v, *_rest) in chunks:
        exp = plan.experiments[e]
        m, holes = len(phi), len(exp.hole_lo)
        if model in ("holmes", "bare"):
            counts = EscapeCounts.zeros(BLOCKS, holes, len(plan.n_edges), len(plan.t_edges))
            args = (Starts(phi=phi, v=v, t=np.zeros(m), n=np.zeros(m, np.int64)),
                    Holes(lo=np.array(exp.hole_lo), width=np.array(exp.hole_width)),
                    Horizon(max_collisions=sc.max_collisions or NO_LIMIT,
                            max_time=sc.max_time or np.inf),
                    Bins(n_edges=plan.n_edges, t_edges=plan.t_edges, record_n=True,
                         record_t=True), counts)
            if model == "holmes":
                holmes_escape_chunk(holmes(sc.eps), *args)
            else:
                bare_holmes_chunk(sc.eps, *args)
            total += int(counts.collisions.sum())
        else:
            out = Counts.zeros(plan, holes)
            kernel(plan, exp, (phi, v, np.zeros(m), np.zeros(m, np.int64)), np.full(m, -1),
                   np.zeros(m, np.int64), np.zeros((0, 6)), out)
            total += int(out.collisions)
    return total


ENSEMBLES = {"end to end": None, "kernel only": "exact", "Holmes map (fastpath)": "holmes",
             BARE_HOLMES: "bare"}


def time_ensembles(particles=1_000_000, scene_name="paper-escape", repeats=3, threads=None):
    """{label: EnsembleTiming}: the exact ensemble end to end and kernel only, and the Holmes
    ensemble on the same starts, fastest of ``repeats`` turns (module docstring)."""
    if threads is not None:
        numba.set_num_threads(max(1, min(int(threads), numba.config.NUMBA_NUM_THREADS)))
    scene = load_scene(scene_name)
    plan = make_plan(scene, particles)
    chunks = _chunks(plan)
    total = particles * len(plan.experiments)
    small = make_plan(scene, 100)  # compile (or load from the cache) outside the timing
    for model in ("exact", "holmes", "bare"):
        _kernel_pass(small, _chunks(small)[:1], model)
    best = {}
    for _ in range(repeats):
        for label, model in ENSEMBLES.items():
            t0 = time.perf_counter()
            if model is None:
                with tempfile.TemporaryDirectory() as tmp:
                    manifest = run(scene, f"{tmp}/run", particles=particles, progress=False,
                                   threads=threads)
                collisions = manifest["collisions"]
            else:
                collisions = _kernel_pass(plan, chunks, model)
            wall = time.perf_counter() - t0
            if label not in best or wall < best[label].wall:
                best[label] = EnsembleTiming(label, wall, collisions, total, len(plan.experiments))
    return best


def ensemble_table(best, scene_name="paper-escape"):
    """Markdown table of ``time_ensembles``: wall time, throughput, ratio to the bare Holmes
    loop."""
    bare = best[BARE_HOLMES]
    t = best["end to end"]
    lines = [
        f"`{scene_name}`, {t.particles:,} particles ({t.particles // t.curves:,} per curve x"
        f" {t.curves} curves),"
        f" {numba.get_num_threads()} threads, fastest of the turns:",
        "",
        "| ensemble | wall s | collisions/s | particles/s | x bare Holmes loop (wall) |",
        "|---|---|---|---|---|",
    ]
    for label in ENSEMBLES:
        e = best[label]
        name = f"exact, {label}" if ENSEMBLES[label] in (None, "exact") else label
        lines.append(f"| {name} | {e.wall:.2f} | {e.collisions / e.wall:.3g} |"
                     f" {e.particles / e.wall:.3g} | {e.wall / bare.wall:.2f} |")
    return "\n".join(lines)


def headline_ratios(best):
    """(end to end, kernel only): the exact ensemble's wall time over the bare Holmes loop's."""
    bare = best[BARE_HOLMES].wall
    return best["end to end"].wall / bare, best["kernel only"].wall / bare


def peak_memory_mib():
    """Peak resident memory of this process so far (Linux reports ru_maxrss in KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def orbit_table(best, collisions, eps, repeats):
    """Markdown table of ``time_orbits`` results, with the ratio to the bare Holmes loop."""
    bare = best[BARE_HOLMES].ns_per_collision
    lines = [
        f"`fastpath.orbit`, {collisions:,} collisions at eps = {eps:g} from (phi, v) = "
        f"{START}, one core, best of {repeats} interleaved runs:",
        "",
        "| model | ns / collision | x bare Holmes loop | iterations / flight (mean) | (max) |",
        "|---|---|---|---|---|",
    ]
    for t in best.values():
        its = (f"{t.mean_iterations:.3f} | {t.max_iterations}" if t.mean_iterations is not None
               else "- | -")
        lines.append(f"| {t.label} | {t.ns_per_collision:.1f} | "
                     f"{t.ns_per_collision / bare:.2f} | {its} |")
    return "\n".join(lines)


DISSIPATIVE_MODELS = (
    ("elastic", {}),
    ("linear drag k = 0.01", {"drag": 0.01, "drag_law": "linear"}),
    ("quadratic drag k = 0.001", {"drag": 0.001, "drag_law": "quadratic"}),
    ("restitution r = 0.95", {"restitution": 0.95}),
)
DISSIPATIVE_EPS = 2.0  # r < 1 at eps <= 1 sticks for good: the orbit would stop early


def time_dissipative_orbits(collisions=1_000_000, repeats=3, eps=DISSIPATIVE_EPS, start=START):
    """{label: (ns per collision, collisions made)}, best of ``repeats`` interleaved
    ``fastpath.orbit`` runs of the elastic model and the dissipative ones
    (``DISSIPATIVE_MODELS``) at the same eps and start; per collision made (an r < 1 orbit
    counts the impacts of its chattering; an orbit stopped early counts what it made)."""
    for _, physics in DISSIPATIVE_MODELS:  # compile (or load from the cache) outside the timing
        fastpath.orbit(*start, eps, 10, **physics)
    best = {}
    for _ in range(repeats):
        for label, physics in DISSIPATIVE_MODELS:
            t0 = time.perf_counter()
            orb = fastpath.orbit(*start, eps, collisions, on_uncertain="stop", **physics)
            made = max(1, len(orb.v) - 1)
            ns = (time.perf_counter() - t0) / made * 1e9
            if label not in best or ns < best[label][0]:
                best[label] = (ns, made)
    return best


def dissipative_table(best, collisions, eps, repeats, start=START):
    """Markdown table of ``time_dissipative_orbits`` with the ratio to the elastic orbit."""
    elastic = best["elastic"][0]
    lines = [f"Dissipative `fastpath.orbit`, {collisions:,} collisions at eps = {eps:g} from "
             f"(phi, v) = {start}, one core, best of {repeats} interleaved runs:", "",
             "| physics | ns / collision | x elastic | collisions made |", "|---|---|---|---|"]
    lines += [f"| {label} | {ns:.1f} | {ns / elastic:.2f} | {made:,} |"
              for label, (ns, made) in best.items()]
    return "\n".join(lines)


DISSIPATIVE_MAX_COLLISIONS = 1_000_000


def dissipative_section(collisions, repeats):
    """The dissipative table of ``bouncer bench`` (at most 10^6 collisions per orbit)."""
    collisions = min(int(collisions), DISSIPATIVE_MAX_COLLISIONS)
    best = time_dissipative_orbits(collisions, repeats)
    return dissipative_table(best, collisions, DISSIPATIVE_EPS, repeats)


# The README's quick start, as a new user runs it first (``time_cold_start``; the test of the
# docs checks that the README still holds this code).
QUICK_START = """\
import fastpath
import verify

tau = fastpath.flight_time(4.0, 3.0, 0.6)             # time to the next collision from (phi, v)
phi1, v1, tau = fastpath.step(4.0, 3.0, 0.6)           # one collision: phase in [0, 2*pi), velocity
orbit = fastpath.orbit(4.0, 3.0, 0.6, 10_000)         # arrays .phi .v .t of 10,001 collisions
result = fastpath.flight([0.0, 1.0, 2.0], 3.0, 3.0)   # arrays .tau .iterations .status
tau_ref = verify.flight_time(4.0, 3.0, 0.6)           # certified: no earlier collision exists
kappa = verify.condition_number(4.0, 3.0, 0.6, tau_ref)
print(f"error {abs(tau - tau_ref) / tau_ref / (kappa * 2**-53):.2f} kappa*u")   # 0.10 kappa*u
"""
COLD_START_PARTICLES = 20_000


def cold_start_commands(particles=COLD_START_PARTICLES):
    """(label, argv) of ``time_cold_start``; ``{tmp}`` stands for a temporary folder."""
    return [("README quick start (Python)", [sys.executable, "-c", QUICK_START]),
            (f"bouncer run paper-escape --particles {particles}",
             [sys.executable, "-m", "reports.cli", "run", "paper-escape", "--particles",
              str(particles), "--out", "{tmp}/run", "--quiet", "--force"])]


def time_cold_start(commands=None):
    """[(label, cold s, warm s)]: each command in a fresh interpreter, first with an empty
    numba cache of its own (``NUMBA_CACHE_DIR``: every kernel it uses is compiled), then again
    with the cache it filled (the kernels are loaded), wall time."""
    rows = []
    for label, argv in cold_start_commands() if commands is None else commands:
        with tempfile.TemporaryDirectory() as tmp:
            env = {**os.environ, "NUMBA_CACHE_DIR": os.path.join(tmp, "numba")}
            walls = []
            for _ in range(2):
                t0 = time.perf_counter()
                done = subprocess.run([a.replace("{tmp}", tmp) for a in argv], env=env,
                                      capture_output=True, text=True)
                walls.append(time.perf_counter() - t0)
                if done.returncode:
                    raise RuntimeError(f"{label}: exit status {done.returncode}:"
                                       f" {done.stderr.strip()[-500:]}")
            rows.append((label, *walls))
    return rows


def cold_start_table(rows):
    """Markdown table of ``time_cold_start``."""
    lines = [f"A new user's first calls, {os.cpu_count()} cores, each in a fresh interpreter:"
             " with an empty numba cache (compiling) and again (loading from the cache):", "",
             "| command | cold s | warm s |", "|---|---|---|"]
    lines += [f"| `{label}` | {cold:.1f} | {warm:.1f} |" for label, cold, warm in rows]
    return "\n".join(lines)
