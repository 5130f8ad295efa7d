"""The plan of a run: its chunks, their starts and verification picks, and the histogram bins.

The run is a fixed sequence of chunks (experiment e, chunk k) of at most ``scene.chunk_size``
starts, generated lazily (``Plan.chunks`` is an iterator: memory does not grow with the particle
count). Chunk (e, k) draws its starts, its verification picks and their collision indices from
``numpy.random.SeedSequence(seed, spawn_key=(e, k))`` only, so a result depends on
(scene, seed, particles) and not on threads, chunk order or interruptions.

Every chunk carries verification picks, except in runs of more than ``MAX_SAMPLED_CHUNKS``
chunks: there only the chunks whose global index e*chunks_per_experiment + k is a multiple of
``sample_stride`` do, so the verification sample (held in memory and in the checkpoint) stays
bounded. The picks are drawn after the starts, so the counts do not depend on the stride.

``estimate`` gives the time and disk a run needs; ``check_size`` refuses absurd sizes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastpath.kernels.histogram import log_edges
from reports.runs.scenes import Scene

BLOCKS = 64  # histogram rows per chunk (not threads: results do not depend on threads)


PORTRAIT_BLOCKS = 8


COLLISION_DECADES = 8  # collision bins: 1 .. 1e8


TIME_FIRST, TIME_DECADES = 0.1, 9  # time bins: [0, 0.1), then 0.1 .. 1e8


SAMPLE_DEPTH = 10**6  # sampled collision indices are log-uniform in [1, min(horizon, this)]


MAX_SAMPLED_CHUNKS = 2**14  # more chunks than this: only every sample_stride-th one is sampled


# Assumed throughput for estimates: the paper-scale run of paper-escape (10^8 particles per curve,
# 6e8 in all, 1558 s on 2 cores, 28.8 collisions per particle on average;
# docs/report/paper-scale/paper-escape-1e8/manifest.json). Scene-dependent: a longer horizon
# or a smaller hole costs more per particle.
PARTICLES_PER_S = 6e8 / 1558.12


MAX_RUN_S = 365.25 * 86400  # refuse runs estimated above one year of that machine's time


SAMPLE_ROW_BYTES = 500  # one verified sample row: ~250 B in sample.csv, as much in the checkpoint


# joint.csv and the checkpoint's joint record, per curve: 35-47 KB at 10^5-10^6 particles per
# curve (paper-escape, paper-transport), growing ~25% per decade of particles
JOINT_CURVE_BYTES = 100_000


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
    sample_stride: int = 1

    @property
    def chunks(self):
        """Iterator over every chunk (e, k) in the fixed order (not a list: see module doc)."""
        return ((e, k) for e in range(len(self.experiments))
                for k in range(self.chunks_per_experiment))

    @property
    def n_chunks(self):
        return self.chunks_per_experiment * len(self.experiments)

    @property
    def particles_total(self):
        return self.particles * len(self.experiments)

    def chunk_particles(self, k):
        size = self.scene.chunk_size
        return min(size, self.particles - k * size)

    def prefix_particles(self, count):
        """Starts in chunks 0 .. count-1 of one experiment."""
        return min(count * self.scene.chunk_size, self.particles)

    def sampled(self, e, k):
        """Whether chunk (e, k) carries verification picks."""
        return (e * self.chunks_per_experiment + k) % self.sample_stride == 0

    @property
    def sampled_chunks(self):
        return -(-self.n_chunks // self.sample_stride)

    @property
    def n_grid(self):
        """Collision indices where a velocity scene records <v_n>: 0, the integer collision
        bin edges below the horizon N (log spaced, ``bins_per_decade``), and N itself."""
        n_max = self.scene.max_collisions
        inner = self.n_edges[self.n_edges < n_max].astype(np.int64)
        return np.concatenate([[0], inner, [n_max]]).astype(np.int64)


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
    stride = math.ceil(total_chunks / MAX_SAMPLED_CHUNKS)
    sampled_chunks = math.ceil(total_chunks / stride)
    # at least scene.verify_samples a run, scaled down for tiny runs (but never to none)
    wanted = min(scene.verify_samples, max(1, total // 10))
    samples = max(1, math.ceil(wanted / sampled_chunks))
    n_edges = log_edges(1.0, COLLISION_DECADES, scene.bins_per_decade, integer=True)
    t_edges = np.concatenate([[0.0], log_edges(TIME_FIRST, TIME_DECADES, scene.bins_per_decade)])
    return Plan(scene, particles, seed, experiments, per_exp, samples, n_edges, t_edges, stride)


def estimate(plan):
    """(seconds, bytes) a run needs: seconds = particles / PARTICLES_PER_S (2 cores, a
    paper-escape-like scene), bytes = the verification sample twice (sample.csv, checkpoint)
    plus 1 MB of histograms and manifest, plus ``JOINT_CURVE_BYTES`` per curve of a joint
    record."""
    seconds = plan.particles_total / PARTICLES_PER_S
    rows = min(plan.sampled_chunks * plan.samples_per_chunk, plan.particles_total)
    joint = JOINT_CURVE_BYTES * sum(len(x.curves) for x in plan.experiments) if \
        plan.scene.joint else 0
    return seconds, rows * SAMPLE_ROW_BYTES + 10**6 + joint


def check_size(plan):
    """ValueError for a run estimated above ``MAX_RUN_S``, with its estimated time and disk."""
    seconds, disk = estimate(plan)
    if seconds > MAX_RUN_S:
        raise ValueError(
            f"--particles {plan.particles}: {plan.particles_total:.3g} particles in all would take"
            f" about {seconds / MAX_RUN_S:.3g} years here ({PARTICLES_PER_S:.3g} particles/s, the"
            f" paper-scale paper-escape run on 2 cores) and {disk / 1e6:.3g} MB of disk; the limit"
            f" is {MAX_RUN_S * PARTICLES_PER_S:.2g} particles in all (one year): use fewer")


def draw_starts(rng, phi_box, v_box, m, density):
    """m starts (phi, v) on the box phi_box x v_box from ``rng``, phi drawn first, with the
    scene's ``density`` (``scenes.DENSITIES``):

        uniform   phi = phi_lo + (phi_hi - phi_lo) * U                        (U uniform)
        sine      density ~ sin(pi x) sin(pi y), x, y the box's scaled coordinates:
                  x = arccos(1 - 2U) / pi, the inverse of its distribution (1 - cos(pi x)) / 2

    (the uniform draws are ``Generator.uniform``, as they always were)."""
    if density == "uniform":
        return rng.uniform(phi_box[0], phi_box[1], m), rng.uniform(v_box[0], v_box[1], m)
    if density == "sine":
        x = np.arccos(1.0 - 2.0 * rng.random(m)) / math.pi
        y = np.arccos(1.0 - 2.0 * rng.random(m)) / math.pi
        return (phi_box[0] + (phi_box[1] - phi_box[0]) * x,
                v_box[0] + (v_box[1] - v_box[0]) * y)
    raise ValueError(f"unknown start density {density!r}")


def chunk_starts(plan, e, k):
    """Starts (phi, v) and verification picks (slot, target) of chunk k of experiment e."""
    exp = plan.experiments[e]
    m = plan.chunk_particles(k)
    rng = np.random.default_rng(np.random.SeedSequence(plan.seed, spawn_key=(e, k)))
    phi, v = draw_starts(rng, exp.phi, exp.v, m, plan.scene.density)
    s = min(plan.samples_per_chunk, m) if plan.sampled(e, k) else 0
    picks = rng.choice(m, size=s, replace=False)
    depth = min(plan.scene.max_collisions or SAMPLE_DEPTH, SAMPLE_DEPTH)
    targets = np.floor(depth ** rng.random(s)).astype(np.int64)
    slot = np.full(m, -1, np.int64)
    slot[picks] = np.arange(s)
    target = np.zeros(m, np.int64)
    target[picks] = targets
    return phi, v, slot, target, picks
