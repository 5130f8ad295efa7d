"""Dissipation suppresses Fermi acceleration: <v_n> saturates, V_sat against (1 - r).

The study (``STUDY``): eps = 2 (at eps = 0.6 particles with r < 1 fall onto the v = pi attractor
or stick, so there is no plateau to measure), starts uniform in the seed's escape box
3.85 < phi < 4.15, 2 < v < 4, no holes; the same starts for every physics:

* restitution r < 1 (DESIGN fact 12: v1 - u = -r*(v_in - u)) for several 1 - r;
* linear drag eta = k*v and quadratic drag eta = k*v*|v| with elastic impacts;
* the elastic, drag-free model as the reference that keeps growing (Fermi acceleration);
* the stuck fraction at eps = 0.6 (|eps| <= 1: a particle whose impacts accumulate never
  leaves the plate) for a few r, from ``Moments.stuck_n``.

<v_n> over the particles that reached collision n comes from ``fastpath.moments`` (64 blocks
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
drag). We could read only the abstract of the second: "the average velocity starts growing at
first and then bends towards a regime of constant value, thus confirming that the introduction
of drag force is a sufficient condition to suppress Fermi acceleration". We found no published
value of beta, so beta is compared with our own random-phase estimate, not with a citation:
with v_in ~ -v at large v, an impact gives v1 = r*v + (1 + r)*u with u = -eps*sin(phase);
uncorrelated phases (<u> = 0, <u^2> = eps^2/2) make the stationary second moment
<v^2> = r^2 <v^2> + (1 + r)^2 eps^2/2, i.e. <v^2> = (1 + r)*eps^2/(2*(1 - r)), and a fixed
shape of the velocity distribution gives V_sat ~ (1 - r)^(-1/2).
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

import fastpath
from fastpath.moments import moments
from reports.paper.claims import CONFIRMED, INCONCLUSIVE, REFUTED, Claim
from reports.paper.sampling import SEED, bootstrap_blocks, slope_fit
from reports.runs.chunk import check_sample

BOX = ((3.85, 4.15), (2.0, 4.0))  # the seed's escape start box
BLOCKS = 64
RANDOM_PHASE_BETA = -0.5  # our estimate (module docstring), not a published value
RESOLUTION = 0.25  # half the distance from -1/2 to 0 (no suppression) and to -1
WINDOW_SHIFT_DECADES = 0.25

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
    f = 10 ** WINDOW_SHIFT_DECADES
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


def verify_dissipative(starts, eps, physics_list, n_max, samples, seed=SEED):
    """Spot-check collisions of dissipative orbits by ``verify``: for each physics, orbits from
    ``starts``, collisions at log-uniform indices <= n_max recomputed from the same float64
    state (``reports.runs.chunk.check_sample`` with the physics). Departures from the plate
    (w0 = 0 after a sticking episode) are skipped: verify takes only w0 > 0."""
    rng = np.random.default_rng(seed)
    worst, over, done = 0.0, 0, 0
    per = max(1, math.ceil(samples / (len(starts) * len(physics_list))))
    for physics in physics_list:
        full = {"drag": 0.0, "drag_law": "linear", "restitution": 1.0, **physics}
        for phi0, v0 in starts:
            orb = fastpath.orbit(phi0, v0, eps, n_max, on_uncertain="stop", **physics)
            last = len(orb.v) - 2
            if last < 0:
                continue
            idx = np.unique(np.floor((last + 1) ** rng.random(per)).astype(np.int64) - 1)
            for k in idx:
                phi, v = float(orb.phi[k]), float(orb.v[k])
                if not v + eps * math.sin(phi) > 0.0:
                    continue
                tau = float(fastpath.step(phi, v, eps, **physics)[2])
                _, error, overstep = check_sample(phi, v, tau, eps, full)
                worst = max(worst, error)
                over += bool(overstep)
                done += 1
    return {"sampled": done, "worst_error": worst, "overstepped": over}


@functools.lru_cache(maxsize=2)
def dissipation_study(quick=False):
    """Run the study (cached: figure and claims share it); see the module docstring."""
    cfg = STUDY[bool(quick)]
    eps = STUDY["eps"]
    t0 = time.perf_counter()
    rng = np.random.default_rng(SEED)
    m = cfg["particles"]
    phi0 = rng.uniform(*BOX[0], m)
    v0 = rng.uniform(*BOX[1], m)
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
    ver = verify_dissipative(starts, eps, physics_list, min(cfg["n_max"], 3000), cfg["verify"])
    return Dissipation(eps, m, nf, window, elastic, rest, drag, omr, beta, beta_err, beta_sys,
                       math.exp(amp) if math.isfinite(amp) else math.nan, sticking, ver,
                       time.perf_counter() - t0)


def saturation_verdict(elastic, curves):
    """Verdict of "dissipation makes <v_n> saturate" from the slopes over the plateau window.

    U = 1.96 sigma (bootstrap over particle blocks) + the window family's half-range, per curve.
    inconclusive when the elastic slope is not above its U (no Fermi acceleration in the window
    to suppress); else refuted: some dissipative curve grows as fast as the elastic one (slope
    >= elastic slope - U - U_elastic: no suppression seen); confirmed: every dissipative slope
    within U of 0; inconclusive otherwise.
    """
    def u(c):
        return 1.96 * c.slope_err + c.slope_sys

    u_el = u(elastic)
    if not all(math.isfinite(u(c)) and math.isfinite(c.slope) for c in [elastic, *curves]):
        return INCONCLUSIVE
    if not elastic.slope > u_el:
        return INCONCLUSIVE
    if any(c.slope >= elastic.slope - u(c) - u_el for c in curves):
        return REFUTED
    if all(abs(c.slope) <= u(c) for c in curves):
        return CONFIRMED
    return INCONCLUSIVE


def exponent_verdict(beta, sigma, systematic, expected=RANDOM_PHASE_BETA):
    """U = 1.96 sigma + systematic. refuted: |beta - expected| > U; confirmed: within U and
    U <= RESOLUTION (1/4: tells -1/2 from 0 and from -1); inconclusive otherwise."""
    u = 1.96 * sigma + systematic
    if not (math.isfinite(u) and math.isfinite(beta)):
        return INCONCLUSIVE
    off = abs(beta - expected)
    return REFUTED if off > u else CONFIRMED if u <= RESOLUTION else INCONCLUSIVE


def dissipation_claims(d):
    """Claims ``dissipation-saturates`` and ``dissipation-exponent`` (rules in the verdict
    functions' docstrings)."""
    curves = d.restitution + d.drag
    sat = saturation_verdict(d.elastic, curves)
    worst = max(curves, key=lambda c: abs(c.slope) / (1.96 * c.slope_err + c.slope_sys))
    u_beta = 1.96 * d.beta_err + d.beta_sys
    where = (f"eps = {d.eps:g}, {d.particles} starts in the seed's escape box, plateau window "
             f"n in [{d.window[0]:g}, {d.window[1]:g}]")
    return [
        Claim(
            id="dissipation-saturates", figure="dissipation",
            seed_says="Dissipation suppresses Fermi acceleration: <v> grows, then bends to a "
                      "constant (de Souza, Simoes, da Silva, Leonel, Math. Probl. Eng. 2009, "
                      "409857, abstract, linear drag; checked here for restitution and both "
                      "drag laws)",
            verdict=sat,
            evidence=f"{where}: slope of log<v_n> vs log n, elastic {d.elastic.slope:.3f} +- "
                     f"{d.elastic.slope_err:.3f}; dissipative slopes "
                     + ", ".join(f"{c.label}: {c.slope:.3f} +- {c.slope_err:.3f}"
                                 for c in curves)
                     + f" (+- bootstrap over {BLOCKS} particle blocks); the farthest from 0 is "
                     f"{worst.label} at {abs(worst.slope):.3f} against U = "
                     f"{1.96 * worst.slope_err + worst.slope_sys:.3f}.",
            particles_per_curve=d.particles,
            statistical={c.label: c.slope_err for c in [d.elastic, *curves]},
            systematic={c.label: c.slope_sys for c in [d.elastic, *curves]}, run=None,
            rule="every dissipative slope within 1.96 sigma + window systematic of 0 while the "
                 "elastic one grows; refuted if one grows as fast as the elastic curve"),
        Claim(
            id="dissipation-exponent", figure="dissipation",
            seed_says="V_sat ~ (1 - r)^beta: NO PUBLISHED VALUE FOUND (Livorati, Ladeira, "
                      "Leonel, PRE 78, 056205 (2008) not readable here); compared with our "
                      "random-phase estimate beta = -1/2",
            verdict=exponent_verdict(d.beta, d.beta_err, d.beta_sys),
            evidence=f"{where}: least-squares slope of log V_sat against log(1 - r) for 1 - r "
                     f"in {', '.join(f'{x:g}' for x in d.one_minus_r)} = {d.beta:.3f} +- "
                     f"{d.beta_err:.3f} (bootstrap over {BLOCKS} particle blocks) +- "
                     f"{d.beta_sys:.3f} (plateau window and fit range); |beta + 1/2| = "
                     f"{abs(d.beta - RANDOM_PHASE_BETA):.3f} against U = {u_beta:.3f}.",
            particles_per_curve=d.particles,
            statistical={"beta": d.beta_err}, systematic={"beta": d.beta_sys}, run=None,
            rule="|beta + 1/2| <= 1.96 sigma + systematic, with U <= 1/4"),
    ]
