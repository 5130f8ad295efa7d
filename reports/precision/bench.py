"""``bouncer bench``: speed of the exact map against the Holmes map, measured in one process.

1. ns per collision of ``fastpath.orbit`` for N collisions at eps = 0.6 from the middle of the
   seed's start box, (phi, v) = (4.0, 3.0): the exact map (``method="auto"``: bracketed Halley;
   ``method="seed"``: the seed's lower-bound steps) and the Holmes map. The models take turns,
   R times, on one core (numba's parallel kernels are not involved), and the fastest of each is
   kept, so load from other processes on a shared machine inflates neither side of the ratio
   more than the other. Iterations per flight come from the same orbits.
2. Ensemble throughput of ``paper-escape`` with P particles per curve on all cores: collisions/s
   and particles/s, from the run's own counts and wall time (verification included).
3. Peak resident memory of the process.
4. Dissipation (``dissipative_section``): ns per collision of ``fastpath.orbit`` with linear
   drag, quadratic drag and restitution r < 1, next to the elastic orbit at the same eps (2: at
   eps <= 1 an r < 1 orbit sticks for good and stops) and start, interleaved as in 1, printed
   as ratios to the elastic orbit.

Printed as ratios measured in this run, never asserted in a test: machines are shared and noisy.
"""

from __future__ import annotations

import resource
import tempfile
import time
from dataclasses import dataclass

import fastpath
from reports.runs.driver import run
from reports.runs.scenes import load_scene

ORBIT_MODELS = (("exact", "auto"), ("exact", "seed"), ("holmes", "auto"))
START = (4.0, 3.0)


@dataclass
class OrbitTiming:
    label: str
    ns_per_collision: float
    mean_iterations: float | None
    max_iterations: int | None


def time_orbits(eps=0.6, collisions=10_000_000, repeats=5, start=START):
    """{label: OrbitTiming}, the best of ``repeats`` interleaved runs of each model."""
    for model, method in ORBIT_MODELS:  # compile (or load from the cache) outside the timing
        fastpath.orbit(*start, eps, 10, model=model, method=method)
    best = {}
    for _ in range(repeats):
        for model, method in ORBIT_MODELS:
            t0 = time.perf_counter()
            orb = fastpath.orbit(*start, eps, collisions, model=model, method=method)
            ns = (time.perf_counter() - t0) / collisions * 1e9
            label = "Holmes map" if model == "holmes" else f"exact ({method})"
            its = orb.iterations
            timing = OrbitTiming(label, ns, float(its.mean()) if its is not None else None,
                                 int(its.max()) if its is not None else None)
            if label not in best or ns < best[label].ns_per_collision:
                best[label] = timing
    return best


def ensemble_throughput(particles=100_000, scene_name="paper-escape", threads=None):
    """Run a scene into a temporary directory: (collisions/s, particles/s, wall s, manifest)."""
    scene = load_scene(scene_name)
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        manifest = run(scene, f"{tmp}/run", particles=particles, progress=False, threads=threads)
        wall = time.perf_counter() - t0
    total = manifest["particles"] * len(manifest["curves"])
    return manifest["collisions"] / wall, total / wall, wall, manifest


def peak_memory_mib():
    """Peak resident memory of this process so far (Linux reports ru_maxrss in KiB)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def orbit_table(best, collisions, eps, repeats):
    """Markdown table of ``time_orbits`` results, with the ratio to the Holmes map."""
    holmes = best["Holmes map"].ns_per_collision
    lines = [
        f"`fastpath.orbit`, {collisions:,} collisions at eps = {eps:g} from (phi, v) = "
        f"{START}, one core, best of {repeats} interleaved runs:",
        "",
        "| model | ns / collision | x Holmes | iterations / flight (mean) | (max) |",
        "|---|---|---|---|---|",
    ]
    for t in best.values():
        its = (f"{t.mean_iterations:.3f} | {t.max_iterations}" if t.mean_iterations is not None
               else "- | -")
        lines.append(f"| {t.label} | {t.ns_per_collision:.1f} | "
                     f"{t.ns_per_collision / holmes:.2f} | {its} |")
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
