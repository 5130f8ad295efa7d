"""The textbook Holmes-map loops: the yardsticks of ``bouncer bench``.

An escape ensemble (``bare_holmes_chunk``): per particle, from its start (phi, v) at t = 0,
collision n = 1, 2, ...:

    t = t + 2*v,    phi = (phi + 2*v) mod 2*pi,    v = |v - 2*eps*sin(phi)|,

until phi falls in the hole [lo, lo + width) mod 2*pi (an escape at index n, time t) or the
horizon is passed (censored), counted into the histogram rows of the particle's block
(``fastpath.kernels.histogram``: the same bins and blocks as the exact ensemble) over the same
threads (``fastpath.kernels.threads``). This is the loop one writes first: numba's float ``%``
and libm's sine, no exact phase reduction (``fastpath.kernels.escape.holmes_escape_chunk``
reduces the phase exactly, docs/performance.md), no verification, no flags. An orbit
(``bare_holmes_orbit``): the same step, n times, into arrays phi, v, t as ``fastpath.orbit``
returns them. The ratios that ``bouncer bench`` prints against these are the honest ones.
"""

import math

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import TWO_PI
from fastpath.kernels.histogram import censor, escape
from fastpath.kernels.threads import over_threads


@jit
def _mod_two_pi(x):
    """x mod 2*pi as x - 2*pi*floor(x/(2*pi)): the cheapest form (numba's float ``%`` calls
    fmod, which made this loop 1.x times slower)."""
    return x - TWO_PI * np.floor(x / TWO_PI)


def bare_holmes_chunk(eps, starts, holes, horizon, bins, counts):
    """The loop above for the particles ``starts`` (``fastpath.kernels.arrays``: phi, v; t and
    n are taken as 0), with ``holes``, ``horizon``, ``bins`` into ``counts`` (added to), as
    ``holmes_escape_chunk`` takes them."""
    m = len(starts.phi)
    per_block = (m + len(counts.collisions) - 1) // len(counts.collisions)

    def run_group(first_block, end_block):
        _bare_blocks(eps, (first_block, end_block, per_block), starts.phi, starts.v, holes.lo,
                     holes.width, horizon.max_collisions, horizon.max_time, bins, counts)

    over_threads(run_group, len(counts.collisions))


@jit
def _bare_blocks(eps, span, phi0, v0, hole_lo, hole_width, max_n, max_t, bins, counts):
    first, end, per_block = span
    m = len(phi0)
    for b in range(first, end):
        done = 0
        for i in range(b * per_block, min(m, (b + 1) * per_block)):
            phi, v, t, n = phi0[i], v0[i], 0.0, 0
            while True:
                if n >= max_n:
                    censor(counts, bins, b, n, t)
                    break
                t1 = t + 2.0 * v
                if t1 > max_t:
                    censor(counts, bins, b, n, t1)
                    break
                phi = _mod_two_pi(phi + 2.0 * v)
                v = abs(v - 2.0 * eps * math.sin(phi))
                t = t1
                n += 1
                done += 1
                j = -1
                for h in range(len(hole_lo)):
                    if _mod_two_pi(phi - hole_lo[h]) < hole_width[h]:
                        j = h
                        break
                if j >= 0:
                    escape(counts, bins, b, j, n, t)
                    break
        counts.collisions[b] += done


def bare_holmes_orbit(phi0, v0, eps, n):
    """(phi, v, t), arrays of n + 1 entries: n steps of the loop above from (phi0, v0)."""
    phi, v, t = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    _bare_orbit(float(phi0), float(v0), float(eps), phi, v, t)
    return phi, v, t


@jit
def _bare_orbit(phi0, v0, eps, phi, v, t):
    phi[0], v[0], t[0] = phi0, v0, 0.0
    for k in range(len(phi) - 1):
        t[k + 1] = t[k] + 2.0 * v[k]
        phi[k + 1] = _mod_two_pi(phi[k] + 2.0 * v[k])
        v[k + 1] = abs(v[k] - 2.0 * eps * math.sin(phi[k + 1]))
