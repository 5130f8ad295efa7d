"""The sampled studies behind claims that need each particle's n and t together, its largest
velocity or where it is late (``reports.paper.studies.follow``): starts drawn here with a fixed
seed, so every study is deterministic. Sizes (``SIZES``) run in minutes on two cores; quick mode is
a smoke test.

* ``escape_sample(centre)``: the paper's escape setup (eps = 0.6, start box 3.85 < phi < 4.15,
  2 < v < 4, one hole of width 0.3), uniform starts, or with ``density="smooth"`` the density
  proportional to sin(pi (phi - 3.85)/0.3) sin(pi (v - 2)/2) on the same box (drawn by inverting
  its marginal distribution functions, (1 - cos(pi u))/2 on each side).
* ``transport_sample(width, entry, replica=0)``: the paper's transport setup (holes of width h
  at 0 and pi, starts uniform on hole ``entry`` in phase with 2 < v < 4); replicas 1, 2, ... are
  independent samples of the same size.
* ``island_box_sample(centre)``: starts in the box of the scene escape-island-start with one
  hole, and their classification (``reports.paper.studies.islands``).
"""

from __future__ import annotations

import functools
import math
import zlib

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.studies.follow import follow
from reports.paper.studies.islands import classify
from reports.paper.studies.sampling import EPS, ESCAPE_BOX, uniform_box
from reports.paper.studies.seeds import FOLLOWED_SEED
from reports.runs.scenes import load_scene

HOLE_WIDTH = 0.3
TRANSPORT_V = (2.0, 4.0)
MAX_COLLISIONS = 100_000
MAX_TIME = 1e7
SIZES = {False: {"escape": 1_000_000, "transport": 1_000_000, "island": 4000},
         True: {"escape": 4000, "transport": 4000, "island": 200}}
ISLAND_COLLISIONS = 3000
SNAPSHOT_LENGTH = 200


def _rng(*key):
    """A generator for one study, keyed by its name and parameters (crc32: stable across runs)."""
    return np.random.default_rng(np.random.SeedSequence(
        FOLLOWED_SEED, spawn_key=[zlib.crc32(str(k).encode()) for k in key]))


def smooth_box(rng, box, m):
    """m starts with density ~ sin(pi u) sin(pi w) on the box (u, w its scaled coordinates)."""
    (p0, p1), (v0, v1) = box
    u = np.arccos(1.0 - 2.0 * rng.random(m)) / math.pi
    w = np.arccos(1.0 - 2.0 * rng.random(m)) / math.pi
    return p0 + (p1 - p0) * u, v0 + (v1 - v0) * w


def hole_lo(centre, width):
    return math.fmod(centre - width / 2 + TWO_PI, TWO_PI)


@functools.lru_cache(maxsize=16)
def escape_sample(centre, quick=False, density="uniform", snapshot_at=()):
    """``Followed`` of the paper's escape setup through the hole at ``centre``."""
    m = SIZES[bool(quick)]["escape"]
    rng = _rng("escape", f"{centre:g}", density)
    draw = smooth_box if density == "smooth" else uniform_box
    phi, v = draw(rng, ESCAPE_BOX, m)
    return follow(phi, v, EPS, [hole_lo(centre, HOLE_WIDTH)], [HOLE_WIDTH], MAX_COLLISIONS,
                  MAX_TIME, snapshot_at=tuple(snapshot_at), snapshot_length=SNAPSHOT_LENGTH,
                  seed=FOLLOWED_SEED)


@functools.lru_cache(maxsize=8)
def transport_sample(width, entry, quick=False, replica=0):
    """``Followed`` of the transport setup for holes of ``width`` at 0 and pi, starting on hole
    ``entry`` (1 or 2); exit 0 is hole 1, exit 1 hole 2. ``replica`` k > 0: an independent
    sample of the same size (its own starts), for a claim whose family replicates the study."""
    m = SIZES[bool(quick)]["transport"]
    rng = _rng("transport", f"{width:g}", entry, *((replica,) if replica else ()))
    centre = 0.0 if entry == 1 else math.pi
    phi = np.mod(centre + width * (rng.random(m) - 0.5), TWO_PI)
    v = rng.uniform(*TRANSPORT_V, m)
    los = [hole_lo(0.0, width), hole_lo(math.pi, width)]
    return follow(phi, v, EPS, los, [width, width], MAX_COLLISIONS, MAX_TIME, seed=FOLLOWED_SEED)


@functools.lru_cache(maxsize=4)
def island_box_sample(centre, quick=False):
    """(starts phi, v, their ``Classified``, ``Followed`` with one hole of width 0.3 at
    ``centre`` for ISLAND_COLLISIONS collisions) in the box of scene escape-island-start."""
    scene = load_scene("escape-island-start")
    m = SIZES[bool(quick)]["island"]
    rng = _rng("island", f"{centre:g}")
    phi, v = uniform_box(rng, (scene.start_phi, scene.start_v), m)
    phi = np.mod(phi, TWO_PI)
    cls = classify(phi, v, EPS)
    fol = follow(phi, v, EPS, [hole_lo(centre, HOLE_WIDTH)], [HOLE_WIDTH], ISLAND_COLLISIONS,
                 seed=FOLLOWED_SEED)
    return phi, v, cls, fol
