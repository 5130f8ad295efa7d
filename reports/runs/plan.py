"""The plan of a run: its chunks, their starts and verification picks, and the histogram bins.

The run is a fixed list of chunks (experiment e, chunk k) of at most ``scene.chunk_size`` starts.
Chunk (e, k) draws its starts, its verification picks and their collision indices from
``numpy.random.SeedSequence(seed, spawn_key=(e, k))`` only, so a result depends on
(scene, seed, particles) and not on threads, chunk order or interruptions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastpath.ensemble import (
    log_edges,
)
from reports.runs.scenes import Scene

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
