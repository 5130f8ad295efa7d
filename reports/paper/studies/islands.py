"""Where the elliptic islands are: starts classified as regular or chaotic by their orbits.

At eps = 0.6 a chaotic orbit diffuses in velocity (Fermi acceleration: <v_n> ~ n^(1/2), a spread
of tens after 2000 collisions), while an orbit on an invariant curve of an island keeps its
velocity within the island's height (about 1 for the large islands around (0, pi m)). A start is

    regular              if its velocity stays within a band of ``REGULAR_BAND`` = 5 over
                         ``CLASSIFY_COLLISIONS`` = 2000 collisions (max v - min v < 5): a
                         quarter of the spread a chaotic orbit reaches by then (<v_n> ~
                         0.5 n^(1/2), about 22 at n = 2000), and above the velocity range of
                         the regular orbits around (0, pi) (about 2.1, from 2.2 to 4.3);
    on the large island  if it is regular and locked to the period-1 resonance of the fixed
                         point (0, pi): its mean flight time t_N/N is 2 pi to within
                         ``LOCK_TOLERANCE`` = 1% (an orbit circling the fixed point has flights
                         of 2 pi on average; a chaotic orbit's mean flight time grows with its
                         velocity, other islands have other resonances).

Chaotic orbits that stick to an island for all 2000 collisions count as regular: a small bias
towards the islands, the same for every strip (the classified fraction of a start box agrees
with the share of its starts that never escape through a hole in the chaotic sea to about 1%).

The fraction of a phase strip [lo, hi] x [pi/2, 3 pi/2] (one velocity period, around the island
(0, pi)) on islands is estimated from uniform random starts, with 95% Wilson intervals. The phase
space is nearly periodic in v with period pi (the paper's Section 2): the strip of period m,
[lo, hi] x [pi (m - 1/2), pi (m + 1/2)], holds the island around (0, pi m), whose orbits are
locked to the resonance of mean flight time 2 pi m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.paper.studies.follow import _step_all
from reports.runs.survival import wilson

CLASSIFY_COLLISIONS = 2000
REGULAR_BAND = 5.0
LOCK_TOLERANCE = 0.01


def centred(phi):
    """Phase in (-pi, pi]."""
    return np.pi - np.mod(np.pi - np.asarray(phi, dtype=np.float64), TWO_PI)


@dataclass
class Classified:
    """Per start: regular, and on the large island around (0, pi)."""

    regular: np.ndarray
    large: np.ndarray
    phase_lo: np.ndarray  # lowest and highest centred phase its orbit visits
    phase_hi: np.ndarray


def velocity_period(m):
    """The velocity band of period m >= 1: (pi (m - 1/2), pi (m + 1/2)), around (0, pi m)."""
    return (math.pi * (m - 0.5), math.pi * (m + 0.5))


def classify(phi, v, eps, collisions=CLASSIFY_COLLISIONS, m=1):
    """``Classified`` starts (module docstring); "on the large island" is the island around
    (0, pi m), locked to a mean flight time of 2 pi m. Starts that do not leave the plate
    (v + eps sin(phi) <= 0) are chaotic by definition here (they are not island orbits)."""
    return classify_together([(phi, v, m)], eps, collisions)[0]


def classify_together(starts, eps, collisions=CLASSIFY_COLLISIONS):
    """``classify`` of several sets of starts, ``starts`` a list of (phi, v, m): every orbit is
    its own, so each set is classified as ``classify`` would alone, but all of them move in one
    loop over one array (one call of the kernel per collision, not one per set)."""
    sizes = [len(np.atleast_1d(p)) for p, _, _ in starts]
    phi = np.concatenate([np.asarray(p, dtype=np.float64).ravel() for p, _, _ in starts])
    v = np.concatenate([np.asarray(w, dtype=np.float64).ravel() for _, w, _ in starts])
    ok = v + eps * np.sin(phi) > 1e-9
    p, w = phi[ok], v[ok]
    v_lo, v_hi = w.copy(), w.copy()
    c_lo, c_hi = centred(p), centred(p)
    t = np.zeros(len(p))
    for _ in range(collisions):
        p, w, tau, _ = _step_all(p, w, eps)
        t += tau
        np.minimum(v_lo, w, out=v_lo)
        np.maximum(v_hi, w, out=v_hi)
        c = centred(p)
        np.minimum(c_lo, c, out=c_lo)
        np.maximum(c_hi, c, out=c_hi)
    regular = np.zeros(len(phi), bool)
    regular[ok] = v_hi - v_lo < REGULAR_BAND
    mean_flight = np.full(len(phi), math.nan)
    mean_flight[ok] = t / collisions
    lo, hi = np.full(len(phi), math.nan), np.full(len(phi), math.nan)
    lo[ok], hi[ok] = c_lo, c_hi
    out, first = [], 0
    for size, (_, _, m) in zip(sizes, starts, strict=True):
        part = slice(first, first + size)
        first += size
        reg = regular[part]
        # a start that does not leave the plate is not regular, so never on the island
        large = reg & (np.abs(mean_flight[part] - TWO_PI * m) < LOCK_TOLERANCE * TWO_PI * m)
        out.append(Classified(reg, large, lo[part], hi[part]))
    return out


@dataclass
class Strip:
    """Fractions of a phase strip [lo, hi] x velocity_period(m) on islands (``large``: the
    island around (0, pi m)), with 95% Wilson intervals."""

    lo: float
    hi: float
    samples: int
    regular: int
    large: int
    m: int = 1

    @property
    def regular_fraction(self):
        return self.regular / self.samples

    @property
    def large_fraction(self):
        return self.large / self.samples

    @property
    def small_fraction(self):
        return (self.regular - self.large) / self.samples

    def ci95(self, count):
        return tuple(float(x) for x in wilson(count, self.samples))


def strip_fractions(lo, hi, eps, samples=2000, seed=0, m=1):
    """``Strip`` of the phases [lo, hi] (taken mod 2 pi) x velocity_period(m) from uniform random
    starts."""
    return strips_together([(lo, hi, m)], eps, samples, seed)[0]


def strips_together(strips, eps, samples=2000, seed=0):
    """``strip_fractions`` of each (lo, hi, m) of ``strips``, each from its own starts, their
    orbits classified in one loop (``classify_together``)."""
    starts = []
    for lo, hi, m in strips:
        rng = np.random.default_rng(seed)
        starts.append((np.mod(rng.uniform(lo, hi, samples), TWO_PI),
                       rng.uniform(*velocity_period(m), samples), m))
    return [Strip(float(lo), float(hi), samples, int(cls.regular.sum()), int(cls.large.sum()), m)
            for (lo, hi, m), cls in zip(strips, classify_together(starts, eps), strict=True)]


def box_starts(phi_box, v_box, samples, seed=0):
    """Uniform random starts (phi mod 2 pi, v) in a box."""
    rng = np.random.default_rng(seed)
    return np.mod(rng.uniform(*phi_box, samples), TWO_PI), rng.uniform(*v_box, samples)


__all__ = ["box_starts", "centred", "classify", "classify_together", "strip_fractions",
           "strips_together"]
