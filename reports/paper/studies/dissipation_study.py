"""Dissipation suppresses Fermi acceleration: <v_n> saturates, V_sat against (1 - r).

The study (``STUDY``): eps = 2 (at eps = 0.6 particles with r < 1 fall onto the v = pi attractor
or stick, so there is no plateau to measure), starts uniform in the paper's escape box
3.85 < phi < 4.15, 2 < v < 4, no holes; the same starts for every physics:

* restitution r < 1 (docs/model.md: v1 - u = -r*(v_in - u)) for several 1 - r;
* linear drag eta = k*v and quadratic drag eta = k*v*|v| with elastic impacts;
* the elastic, drag-free model as the reference that keeps growing (Fermi acceleration);
* the stuck fraction at eps = 0.6 (|eps| <= 1: a particle whose impacts accumulate never
  leaves the plate) for a few r, from ``Moments.stuck_n``.

<v_n> over the particles that reached collision n comes from ``fastpath.kernels.moments`` (64 blocks
of consecutive particles). The built-in scene ``dissipation-saturation`` (kind "velocity",
``reports.runs.velocity``) runs r = 1 and three of these r through the trusted run engine
(verification sample, ``bouncer verify``), with the same convention: stuck particles are
counted apart, not in the means. The plateau V_sat is the mean of <v_n> over the grid points (log
spaced) in the last decade of n, [n_max/10, n_max], and the saturation test is the slope of
log<v_n> against log n over that window. The exponent beta of V_sat ~ (1 - r)^beta is the
least-squares slope of log V_sat against log(1 - r).

Published values: E. D. Leonel and co-workers study exactly this (A. L. P. Livorati,
D. G. Ladeira, E. D. Leonel, Phys. Rev. E 78, 056205 (2008), inelastic impacts; F. A. de Souza,
L. E. A. Simoes, M. R. da Silva, E. D. Leonel, Math. Probl. Eng. 2009, 409857 (2009), linear
drag; A. M. Cespedes, UNESP dissertation (2015), V_rms exponents "from the analytical
expression of the mean square velocity"). From this workplace we could read only their
abstracts, none with a number; the second says "the average velocity starts growing at
first and then bends towards a regime of constant value, thus confirming that the introduction
of drag force is a sufficient condition to suppress Fermi acceleration". We found no published
value of beta, so beta is compared with our own random-phase estimate, not with a citation:
with v_in ~ -v at large v, an impact gives v1 = r*v + (1 + r)*u with u = -eps*sin(phase);
uncorrelated phases (<u> = 0, <u^2> = eps^2/2) make the stationary second moment
<v^2> = r^2 <v^2> + (1 + r)^2 eps^2/2, i.e. <v^2> = (1 + r)*eps^2/(2*(1 - r)), and a fixed
shape of the velocity distribution gives V_sat ~ (1 - r)^(-1/2).

The velocity strip (``velocity_strip``; claim ``dissipation-velocity-strip``). The one
published scaling statement with numbers we could read: J. J. Barroso, M. V. Carneiro,
E. E. N. Macau, Phys. Rev. E 79, 026206 (2009), abstract: chaotic orbits of the inelastic
bouncer are "bounded by a velocity strip v = +-Gamma/(1 - r)" (Gamma the nondimensional shaking
acceleration; the symbols are garbled in the stored copy and restored here). In our units the
strip follows from the model alone. In flight the energy v**2/2 + y is constant and the plate
height |y| <= |eps|, so the landing speed obeys v_in**2 <= v**2 + 4|eps|; an impact gives
v1 = (1 + r)*u - r*v_in with |u| <= |eps| and v_in < u (an approach): for v_in <= 0,
v1 <= (1 + r)|eps| + r*sqrt(v**2 + 4|eps|), for 0 < v_in < u, v1 < (1 + r)|eps|; and
v1 > u >= -|eps|. So |v| <= V implies |v1| <= g(V) = (1 + r)|eps| + r*sqrt(V**2 + 4|eps|) for
V >= |eps|, and g is increasing with slope < r < 1: its fixed point

    V*(r) = (|eps| + r*sqrt(eps**2 + 4|eps|*(1 - r)/(1 + r)))/(1 - r)  ~  2|eps|/(1 - r)

bounds every later velocity of an orbit that starts with |v| <= V* (a particle riding the
plate has |v| = |u| <= |eps|). The strip's width scales as (1 - r)^-1, Barroso et al.'s law; it
is a bound, not the plateau (V_sat grows only as (1 - r)^beta, beta = -0.6 here). The check is
that no velocity of the study's orbits leaves it, and by how much the orbits stay inside.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

import fastpath
from fastpath import moments
from reports.paper.studies.sampling import (
    ESCAPE_BOX,
    bootstrap_blocks,
    slope_fit,
    uniform_box,
    verify_sample,
)
from reports.paper.studies.seeds import SAMPLING_SEED
from reports.stats.analysis import SHIFT_DECADES

BLOCKS = 64
RANDOM_PHASE_BETA = -0.5  # our estimate (module docstring), not a published value

STUDY = {
    "eps": 2.0,
    "one_minus_r": (0.005, 0.01, 0.02, 0.05, 0.1),
    "drag": {"linear": (0.001, 0.003, 0.01), "quadratic": (0.0003, 0.001)},
    "sticking_eps": 0.6,
    "sticking_r": (0.5, 0.8, 0.9, 0.95),
    False: {"particles": 1000, "n_max": 10_000, "verify": 60},
    True: {"particles": 128, "n_max": 3000, "verify": 12},
}


@dataclass
class Curve:
    """<v_n> of one physics: the block sums (for the bootstrap) and the plateau numbers."""

    label: str
    physics: dict
    mean_v: np.ndarray
    sum_v: np.ndarray  # (blocks, len(n))
    count: np.ndarray  # (blocks, len(n))
    stuck: int  # particles stuck for good by n_max
    reached: int  # particles that reached n_max
    collisions: int
    flagged: int
    plateau: float
    slope: float
    slope_err: float
    slope_sys: float


STRIP_ORBITS = {False: 64, True: 8}  # orbits per r (n_max collisions each) for the strip


def velocity_strip(r, eps):
    """V*(r): the fixed point of g(V) = (1 + r)|eps| + r*sqrt(V**2 + 4|eps|), the edge of the
    velocity strip |v| <= V* that no orbit with restitution r < 1 leaves (module docstring)."""
    e = abs(eps)
    return (e + r * math.sqrt(e * e + 4.0 * e * (1.0 - r) / (1.0 + r))) / (1.0 - r)


def strip_maxima(phi0, v0, eps, one_minus_r, n_max):
    """Per 1 - r, max |v_n| over ``fastpath.orbit`` of each start (n_max collisions), over the
    first and over the second half of the starts (two independent samples)."""
    out = []
    for x in one_minus_r:
        tops = []
        for p, v in zip(phi0, v0, strict=True):
            orb = fastpath.orbit(float(p), float(v), eps, n_max, on_uncertain="stop",
                                 restitution=1.0 - float(x))
            tops.append(float(np.max(np.abs(orb.v))))
        half = max(1, len(tops) // 2)
        out.append((max(tops[:half]), max(tops[half:], default=max(tops[:half]))))
    return out


@dataclass
class Dissipation:
    """The study's curves, the exponent of V_sat in (1 - r) and the stuck fractions."""

    eps: float
    particles: int
    n: np.ndarray
    window: tuple
    elastic: Curve
    restitution: list  # Curve per 1 - r, in STUDY order
    drag: list  # Curve per (law, k)
    one_minus_r: np.ndarray
    beta: float
    beta_err: float
    beta_sys: float
    amp: float
    sticking: list  # (r, stuck fraction, particles) at STUDY["sticking_eps"]
    verification: dict
    seconds: float
    strip_max: list = None  # max |v_n| over STRIP_ORBITS orbits, per 1 - r (velocity strip)
    strip_orbits: int = 0
    strip_halves: list = None  # the same over each half of the orbits, per 1 - r


def plateau(n, mean_v, lo, hi):
    """Mean of <v_n> over the grid points lo <= n <= hi (NaN if fewer than 3 are finite)."""
    use = (n >= lo) & (n <= hi) & np.isfinite(mean_v)
    return float(np.mean(mean_v[use])) if use.sum() >= 3 else math.nan


def log_slope(x, y, lo=-math.inf, hi=math.inf):
    """Least-squares slope of log y against log x over lo <= x <= hi (NaN if < 3 points)."""
    use = (x >= lo) & (x <= hi) & np.isfinite(y) & (y > 0)
    if use.sum() < 3:
        return math.nan
    return slope_fit(np.log(x[use]), np.log(y[use]))[0]


def _window_starts(window):
    f = 10 ** SHIFT_DECADES
    return [window[0] / f, window[0], window[0] * f]


def _curve(label, physics, phi0, v0, eps, n, window):
    mom = moments(phi0, v0, eps, n, blocks=BLOCKS, **physics)
    mean_v = mom.mean_v_n
    slope = log_slope(n, mean_v, *window)
    err = bootstrap_blocks(mom.sum_v_n, mom.count_n, lambda c: log_slope(n, c, *window))
    slopes = [log_slope(n, mean_v, lo, window[1]) for lo in _window_starts(window)]
    slopes = [s for s in slopes if math.isfinite(s)]
    sys = 0.5 * (max(slopes) - min(slopes)) if slopes else math.nan
    return Curve(label, physics, mean_v, mom.sum_v_n, mom.count_n,
                 int(mom.stuck_n.sum(axis=0)[-1]), int(mom.particles_n[-1]), mom.collisions,
                 mom.flagged, plateau(n, mean_v, *window), slope, err, sys)


def exponent(x, plateaus):
    """beta and log amplitude of plateaus ~ amp * x**beta (least squares in log-log)."""
    x, y = np.asarray(x, float), np.asarray(plateaus, float)
    use = np.isfinite(y) & (y > 0)
    if use.sum() < 3:
        return math.nan, math.nan
    return slope_fit(np.log(x[use]), np.log(y[use]))


def _beta_of_stacked(n, x, window):
    """The statistic for the bootstrap: mean curves of all x side by side -> beta."""
    k = len(n)

    def stat(stacked):
        return exponent(x, [plateau(n, stacked[i * k:(i + 1) * k], *window)
                            for i in range(len(x))])[0]
    return stat


def _beta_systematic(n, x, curves, window):
    """Half-range of beta over the plateau window's start moved 10**(+-1/4) and over dropping
    the smallest or the largest 1 - r."""
    betas = []
    for lo in _window_starts(window):
        plats = [plateau(n, c.mean_v, lo, window[1]) for c in curves]
        betas.append(exponent(x, plats)[0])
        betas.append(exponent(x[1:], plats[1:])[0])
        betas.append(exponent(x[:-1], plats[:-1])[0])
    betas = [b for b in betas if math.isfinite(b)]
    return 0.5 * (max(betas) - min(betas)) if betas else math.nan


@functools.lru_cache(maxsize=2)
def dissipation_study(quick=False):
    """Run the study (cached: figure and claims share it); see the module docstring."""
    cfg = STUDY[bool(quick)]
    eps = STUDY["eps"]
    t0 = time.perf_counter()
    rng = np.random.default_rng(SAMPLING_SEED)
    m = cfg["particles"]
    phi0, v0 = uniform_box(rng, ESCAPE_BOX, m)
    n = np.unique(np.round(np.logspace(0, math.log10(cfg["n_max"]), 41)).astype(np.int64))
    nf = n.astype(float)
    window = (cfg["n_max"] / 10.0, float(cfg["n_max"]))
    elastic = _curve("elastic", {}, phi0, v0, eps, n, window)
    omr = np.array(STUDY["one_minus_r"])
    rest = [_curve(f"1 - r = {x:g}", {"restitution": 1.0 - x}, phi0, v0, eps, n, window)
            for x in omr]
    drag = [_curve(f"{law} drag k = {k:g}", {"drag": k, "drag_law": law}, phi0, v0, eps, n,
                   window)
            for law, ks in STUDY["drag"].items() for k in ks]
    beta, amp = exponent(omr, [c.plateau for c in rest])
    stacked_num = np.hstack([c.sum_v for c in rest])
    stacked_den = np.hstack([c.count for c in rest])
    beta_err = bootstrap_blocks(stacked_num, stacked_den, _beta_of_stacked(nf, omr, window))
    beta_sys = _beta_systematic(nf, omr, rest, window)
    sticking = []
    for r in STUDY["sticking_r"]:
        mom = moments(phi0, v0, STUDY["sticking_eps"], n, blocks=BLOCKS, restitution=r)
        sticking.append((r, float(mom.stuck_n.sum(axis=0)[-1]) / m, m))
    starts = list(zip(phi0[:2], v0[:2], strict=True))
    physics_list = [{"restitution": 1.0 - omr[0]}, {"restitution": 1.0 - omr[-1]},
                    {"drag": STUDY["drag"]["linear"][-1], "drag_law": "linear"},
                    {"drag": STUDY["drag"]["quadratic"][-1], "drag_law": "quadratic"}]
    ver = verify_sample(starts, eps, min(cfg["n_max"], 3000), cfg["verify"],
                        physics_list=physics_list)
    k = STRIP_ORBITS[bool(quick)]
    halves = strip_maxima(phi0[:k], v0[:k], eps, omr, cfg["n_max"])
    return Dissipation(eps, m, nf, window, elastic, rest, drag, omr, beta, beta_err, beta_sys,
                       math.exp(amp) if math.isfinite(amp) else math.nan, sticking, ver,
                       time.perf_counter() - t0, [max(h) for h in halves], k, halves)
