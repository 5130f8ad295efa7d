"""Accelerator modes: blocks of p collisions that advance (phi, v) by (2*pi*m, pi*l), l != 0.

In the Holmes map's standard-map form (v1 = v - 2*eps*sin(phi1), K = 4*eps) the map commutes
with v -> v + pi, so such a block repeats forever: v grows by pi*l every p collisions. The exact
map is not periodic in v: the shifted relations that repeat block after block are exactly its
period-1 modes with l > 0 (``verify.dynamics.accelerator`` proves it): a flight of duration
2*pi*m from phase phi lands at phase phi at the same plate height, so tau = 2v exactly
(v = pi*m), and v1 - v = -2*eps*sin(phi) = pi*l needs |eps| >= pi*|l|/2, the Holmes condition;
the next block starts at v + pi*l, again a multiple of pi. Any other shifted block of the exact
map is a one-off (its next block is not its shifted copy) and is not kept.

``search`` runs Newton's method from a grid of starts (``kernels.block_search``) and keeps the
distinct modes with l != 0 (for the exact map, those ``periodic_orbit`` accepts). A search finds
what its grid reaches: it proves nothing about blocks it does not find.
"""

import math

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from fastpath.dynamics.kernels import block_search
from fastpath.dynamics.periodic_orbit import OrbitNotFound, build_orbit, periodic_orbit
from fastpath.inputs import integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.physics import Elastic
from fastpath.status import CONVERGED

MAX_ITERATIONS = 40
_SAME = 1e-7  # two blocks whose states agree to this (phase mod 2*pi, v mod pi) are one


def search(eps, period, *, model="holmes", grid=24, v_base=20 * math.pi):
    """Distinct accelerator blocks of ``period`` collisions found by Newton's method from a
    grid x grid of starts, phi in [0, 2*pi), v in [v_base, v_base + pi).

    Returns a list of ``PeriodicOrbit`` (velocity_shift != 0), sorted by residue.
    """
    eps = real("eps", eps)
    period = integer("period", period, minimum=1)
    grid = integer("grid", grid, minimum=1)
    v_base = real("v_base", v_base)
    physics = model_physics(model, eps)
    phases = (np.arange(grid) + 0.5) * TWO_PI / grid
    speeds = v_base + (np.arange(grid) + 0.5) * math.pi / grid
    phi0, v0 = (a.ravel() for a in np.meshgrid(phases, speeds))
    out = np.empty((len(phi0), 6))
    block_search(phi0, v0, physics, period, MAX_ITERATIONS, out)
    found = []
    keys = []
    for phi, v, m, shift, _, status in out:
        if status != CONVERGED or shift == 0:
            continue
        try:
            if type(physics) is Elastic:  # only the exact map's modes (periodic_orbit's rules)
                orbit = periodic_orbit(phi, v, eps, period, winding=int(m),
                                       velocity_shift=int(shift), model=model)
                if orbit.period != period:
                    continue  # a mode of a shorter period: found at that period
            else:
                orbit = build_orbit(phi, v, physics, period, int(m), int(shift))
        except OrbitNotFound:
            continue
        key = _canonical(orbit)
        if any(_same(key, other) for other in keys):
            continue
        keys.append(key)
        found.append(orbit)
    return sorted(found, key=lambda o: o.residue)


def _canonical(orbit):
    """The orbit's states as (phase mod 2*pi, v mod pi) pairs."""
    return [(p % TWO_PI, v % math.pi) for p, v in zip(orbit.phi, orbit.v, strict=True)]


def _same(a, b):
    if len(a) != len(b):
        return False
    p0, v0 = a[0]
    return any(_close(p0, p, TWO_PI) and _close(v0, v, math.pi) for p, v in b)


def _close(x, y, period):
    d = abs(x - y) % period
    return min(d, period - d) < _SAME
