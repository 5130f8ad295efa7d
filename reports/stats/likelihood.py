"""Maximum likelihood for survival laws on binned, censored counts, with profile intervals.

Window. A fit uses the bins between survival-clock boundaries x_a < ... < x_b (see
``histogram``) and conditions on survival past x_a. With E_j escapes in bin (x_j, x_{j+1}] and
w_i particles known only to survive past z_i (competing escapes at their bin means, and every
particle still present at x_b with z = x_b), the log-likelihood is

    l = sum_j E_j log[(S(x_j) - S(x_{j+1})) / S(x_a)] + sum_i w_i log[S(z_i) / S(x_a)],

the multinomial log-likelihood without its constant (the same for every law, so differences and
AIC are unaffected).

Laws. Each is a scale s > 0 times a shape h(x) with h(x_a) = 0, H = s*h the cumulative hazard
since x_a, S(x)/S(x_a) = exp(-H):

    exponential             S ~ exp(-gamma x)      h = x - x_a              s = gamma
    power law               S ~ x**-alpha          h = log(x/x_a)           s = alpha
    stretched exponential   S ~ exp(-c x**beta)    h = expm1(beta L)/beta   s = c*beta*x_a**beta
                                                   (L = log(x/x_a))

so the stretched law is the exponential at beta = 1 and tends to the power law with
alpha = c*beta as beta -> 0 (h -> L): beta = 0 is its boundary, where it *is* the power law.
beta is restricted to [0, BETA_MAX].

For a fixed shape, l(s) = sum_j E_j [-s h_j + log(1 - exp(-s d_j))] - s K (d_j = h_{j+1} - h_j,
K = sum_i w_i h(z_i)) is strictly concave in s, so the scale is the unique root of
l'(s) = sum_j E_j [d_j/expm1(s d_j) - h_j] - K, found by Newton's method inside a bracket. The
stretched law's beta is found by maximising the profile l(beta) = max_s l (grid, then golden
section).

Intervals (95%) are profile-likelihood intervals {theta: 2 (l_max - l_profile(theta)) <= 3.841}
(chi^2_1 quantile); an end that reaches a boundary of the parameter range is reported as that
boundary (beta: 0 or BETA_MAX; c: inf when the power-law limit is inside the interval).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from scipy.optimize import brentq
from scipy.stats import chi2

from fastpath.arithmetic.rounding import UNIT_ROUNDOFF

BETA_MAX = 4.0
Q95 = 0.5 * float(chi2.ppf(0.95, 1))  # log-likelihood drop at the ends of a 95% interval
LAWS = ("exponential", "power_law", "stretched_exponential")
PARAMS = {"exponential": ("gamma",), "power_law": ("alpha",),
          "stretched_exponential": ("c", "beta")}
_GRID = 25        # beta grid points before the golden section
_GOLDEN = 60      # golden-section steps (0.618**60 ~ 3e-13 of the bracket)
SEARCH_GOLDEN = 24  # steps when only l matters (0.618**24 ~ 1e-5 of the bracket: l to ~1e-10 of
                    # its curvature), as in the regime search
_INV_PHI = 0.6180339887498949
_LOG_BETA_MIN = math.log(1e-16)  # c's profile searches beta down to here


@dataclass(frozen=True)
class Window:
    """The data of one fit: boundaries ``x`` (m+1, finite), ``escapes`` (m), and ``weights``
    particles known to survive past ``points`` (competing escapes and survivors past x[-1])."""

    x: np.ndarray
    escapes: np.ndarray
    points: np.ndarray
    weights: np.ndarray

    @property
    def start(self):
        return float(self.x[0])

    @property
    def end(self):
        return float(self.x[-1])

    @property
    def at_risk(self):
        return int(self.escapes.sum() + self.weights.sum())


def window_of(curve, a, b):
    """Window of bins a..b-1 of a ``histogram.Curve`` (boundaries x_a..x_b).

    Raises ValueError if x_a <= 0 (power law undefined), if a horizon censoring bound lies
    inside (see ``histogram``), or if there are no escapes in it.
    """
    x = curve.x
    if not 0 <= a < b < len(x) or not math.isfinite(x[b]):
        raise ValueError(f"window bins {a}..{b} outside the finite grid of {len(x) - 1} bins")
    if x[a] <= 0:
        raise ValueError(f"window start x = {x[a]:g} must be > 0")
    if curve.censored[a:b].any():
        raise ValueError(f"horizon censoring inside the window [{x[a]:g}, {x[b]:g}]")
    escapes = curve.escapes[a:b].astype(np.float64)
    if escapes.sum() == 0:
        raise ValueError(f"no escapes in the window [{x[a]:g}, {x[b]:g}]")
    beyond = (curve.escapes[b:].sum() + curve.competing[b:].sum() + curve.censored[b:].sum())
    comp = curve.competing[a:b]
    points = np.append(curve.mid[a:b][comp > 0], x[b])
    weights = np.append(comp[comp > 0], beyond).astype(np.float64)
    return Window(x[a:b + 1].astype(np.float64), escapes, points, weights)


# ---------------------------------------------------------------- compiled kernels


@numba.njit(cache=True)
def _derivs(s, h, e, k):
    """l(s), l'(s), l''(s) for shape values h at the boundaries, escapes e, K = k."""
    lk = -s * k
    g = -k
    c = 0.0
    for j in range(len(e)):
        if e[j] == 0.0:
            continue
        d = h[j + 1] - h[j]
        sd = s * d
        lk += e[j] * (-s * h[j] + math.log(-math.expm1(-sd)))
        g += e[j] * (d / math.expm1(sd) - h[j]) if sd < 700.0 else -e[j] * h[j]
        if sd < 1400.0:
            sh = math.sinh(0.5 * sd)
            c -= e[j] * d * d / (4.0 * sh * sh)
    return lk, g, c


@numba.njit(cache=True)
def _scale_mle(h, e, k):
    """(s, l) maximising l(s) for a fixed shape; s = inf if the window has no information."""
    a = k
    n = 0.0
    exposure = k
    for j in range(len(e)):
        a += e[j] * h[j]
        n += e[j]
        exposure += e[j] * 0.5 * (h[j] + h[j + 1])
    if a <= 0.0:
        return math.inf, 0.0
    s = n / exposure
    lo, hi = s, s
    while _derivs(lo, h, e, k)[1] < 0.0:
        lo *= 0.25
    while _derivs(hi, h, e, k)[1] > 0.0:
        hi *= 4.0
    for _ in range(200):
        _, g, c = _derivs(s, h, e, k)
        if g > 0.0:
            lo = s
        elif g < 0.0:
            hi = s
        else:
            break
        new = s - g / c if c < 0.0 else -1.0
        if not lo < new < hi:
            new = math.sqrt(lo * hi)
        done = abs(new - s) <= 1e-15 * s
        s = new
        if done or hi - lo <= 4e-16 * hi:
            break
    return s, _derivs(s, h, e, k)[0]


@numba.njit(cache=True)
def _stretched_shape(log_ratio, beta):
    """h = expm1(beta L)/beta (= L at beta = 0)."""
    if beta == 0.0:
        return log_ratio.copy()
    return np.expm1(beta * log_ratio) / beta


@numba.njit(cache=True)
def _stretched_k(log_points, weights, beta):
    h = _stretched_shape(log_points, beta)
    k = 0.0
    for i in range(len(weights)):
        k += weights[i] * h[i]
    return k


@numba.njit(cache=True)
def _stretched_profile(beta, log_x, e, log_points, weights):
    """(s, l) with beta fixed: the profile likelihood of beta."""
    return _scale_mle(_stretched_shape(log_x, beta), e, _stretched_k(log_points, weights, beta))


@numba.njit(cache=True)
def _stretched_mle(log_x, e, log_points, weights, beta_max, golden):
    """(beta, s, l) of the stretched law: grid over [0, beta_max], then golden section."""
    best, best_l = 0, -math.inf
    for i in range(_GRID):
        lk = _stretched_profile(beta_max * i / (_GRID - 1), log_x, e, log_points, weights)[1]
        if lk > best_l:
            best, best_l = i, lk
    lo = beta_max * max(best - 1, 0) / (_GRID - 1)
    hi = beta_max * min(best + 1, _GRID - 1) / (_GRID - 1)
    b1 = hi - _INV_PHI * (hi - lo)
    b2 = lo + _INV_PHI * (hi - lo)
    l1 = _stretched_profile(b1, log_x, e, log_points, weights)[1]
    l2 = _stretched_profile(b2, log_x, e, log_points, weights)[1]
    for _ in range(golden):
        if l1 >= l2:
            hi, b2, l2 = b2, b1, l1
            b1 = hi - _INV_PHI * (hi - lo)
            l1 = _stretched_profile(b1, log_x, e, log_points, weights)[1]
        else:
            lo, b1, l1 = b1, b2, l2
            b2 = lo + _INV_PHI * (hi - lo)
            l2 = _stretched_profile(b2, log_x, e, log_points, weights)[1]
    beta = 0.5 * (lo + hi)
    s, lk = _stretched_profile(beta, log_x, e, log_points, weights)
    # a maximum on the boundary of [0, beta_max], up to the rounding of l (about u |l| per
    # term; 1e3 u |l| covers a sum of up to ~1e3 bins): the golden section cannot resolve more
    tol = 1e3 * UNIT_ROUNDOFF * (abs(lk) + 1.0)
    for edge in (0.0, beta_max):
        se, le = _stretched_profile(edge, log_x, e, log_points, weights)
        if le >= lk - tol:
            beta, s, lk = edge, se, le
    return beta, s, lk


@numba.njit(cache=True)
def _c_fixed(log_c, log_beta, x0, log_x, e, log_points, weights):
    """l at c = exp(log_c), beta = exp(log_beta): s = c beta x0**beta."""
    beta = math.exp(log_beta)
    s = math.exp(log_c + log_beta + beta * math.log(x0))
    return _derivs(s, _stretched_shape(log_x, beta), e, _stretched_k(log_points, weights, beta))[0]


@numba.njit(cache=True)
def _c_profile(log_c, x0, log_x, e, log_points, weights, beta_max):
    """max over beta in [BETA_MIN_LOG, beta_max] of l with c fixed, searched in log beta (a
    large c has its best beta near alpha/c, far below any linear grid)."""
    top = math.log(beta_max)
    n = 4 * _GRID
    best, best_l = 0, -math.inf
    for i in range(n):
        lk = _c_fixed(log_c, _LOG_BETA_MIN + (top - _LOG_BETA_MIN) * i / (n - 1), x0, log_x, e,
                      log_points, weights)
        if lk > best_l:
            best, best_l = i, lk
    lo = _LOG_BETA_MIN + (top - _LOG_BETA_MIN) * max(best - 1, 0) / (n - 1)
    hi = _LOG_BETA_MIN + (top - _LOG_BETA_MIN) * min(best + 1, n - 1) / (n - 1)
    u1 = hi - _INV_PHI * (hi - lo)
    u2 = lo + _INV_PHI * (hi - lo)
    l1 = _c_fixed(log_c, u1, x0, log_x, e, log_points, weights)
    l2 = _c_fixed(log_c, u2, x0, log_x, e, log_points, weights)
    for _ in range(_GOLDEN):
        if l1 >= l2:
            hi, u2, l2 = u2, u1, l1
            u1 = hi - _INV_PHI * (hi - lo)
            l1 = _c_fixed(log_c, u1, x0, log_x, e, log_points, weights)
        else:
            lo, u1, l1 = u1, u2, l2
            u2 = lo + _INV_PHI * (hi - lo)
            l2 = _c_fixed(log_c, u2, x0, log_x, e, log_points, weights)
    return max(best_l, l1, l2)


# ---------------------------------------------------------------- fits


@dataclass(frozen=True)
class LawFit:
    """Maximum-likelihood fit of one law on one window."""

    law: str
    params: dict      # name -> value
    ci95: dict        # name -> (lo, hi), profile likelihood
    loglik: float
    scale: float      # s of the module docstring
    window: Window

    @property
    def k(self):
        return len(PARAMS[self.law])

    @property
    def aic(self):
        return 2 * self.k - 2 * self.loglik

    def log_survival(self, x):
        """log S(x)/S(x_a) of the fitted law."""
        return -self.scale * shape(self.law, x, self.window.start, self.params.get("beta"))


def shape(law, x, x0, beta=None):
    """h(x) of ``law`` (module docstring) with h(x0) = 0."""
    x = np.asarray(x, dtype=np.float64)
    if law == "exponential":
        return x - x0
    if law == "power_law":
        return np.log(x / x0)
    if law == "stretched_exponential":
        return _stretched_shape(np.atleast_1d(np.log(x / x0)), float(beta)).reshape(x.shape)
    raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")


def cell_log_probs(law, scale, beta, w):
    """log-probabilities of the window's cells: the bins, then the censoring points."""
    hb = shape(law, w.x, w.start, beta)
    hz = shape(law, w.points, w.start, beta)
    with np.errstate(over="ignore"):
        bins = -scale * hb[:-1] + np.log(-np.expm1(-scale * np.diff(hb)))
    return bins, -scale * hz


def _k(law, w, beta=None):
    return float(np.dot(w.weights, shape(law, w.points, w.start, beta)))


def _loglik(law, w, scale, beta=None):
    hb = shape(law, w.x, w.start, beta)
    return _derivs(scale, hb, w.escapes, _k(law, w, beta))[0]


def _no_information(w):
    return ValueError(f"the window [{w.start:g}, {w.end:g}] holds all escapes in its first bin "
                      f"and no survivors: no decay law can be fitted")


def _scale_interval(law, w, s_hat, l_hat, beta=None):
    """Profile interval of the scale of a one-parameter law (l is concave in s); ``beta``: the
    stretched law's fixed exponent."""
    target = l_hat - Q95

    def f(log_s):
        return _loglik(law, w, math.exp(log_s), beta) - target

    ends = []
    for step in (-1.0, 1.0):
        far = math.log(s_hat) + step
        while f(far) > 0:
            far += step
        ends.append(math.exp(brentq(f, math.log(s_hat), far, xtol=1e-14, rtol=1e-13)))
    return tuple(ends)


def fit_law(law, w, intervals=True, golden=_GOLDEN):
    """Maximum-likelihood ``LawFit`` of ``law`` on window ``w`` (profile 95% intervals).
    ``golden``: golden-section steps of the stretched law's beta (``SEARCH_GOLDEN`` where only
    the maximised likelihood is wanted)."""
    if law in ("exponential", "power_law"):
        h = shape(law, w.x, w.start)
        s, lk = _scale_mle(h, w.escapes, _k(law, w))
        if not math.isfinite(s):
            raise _no_information(w)
        name = PARAMS[law][0]
        ci = {name: _scale_interval(law, w, s, lk)} if intervals else {}
        return LawFit(law, {name: s}, ci, lk, s, w)
    if law != "stretched_exponential":
        raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")
    log_x = np.log(w.x / w.start)
    log_z = np.log(w.points / w.start)
    beta, s, lk = _stretched_mle(log_x, w.escapes, log_z, w.weights, BETA_MAX, golden)
    if not math.isfinite(s):
        raise _no_information(w)
    c = s / (beta * w.start ** beta) if beta > 0 else math.inf
    ci = _stretched_intervals(w, log_x, log_z, beta, c, lk) if intervals else {}
    return LawFit(law, {"c": c, "beta": beta}, ci, lk, s, w)


def fit_stretched_fixed(w, beta):
    """Maximum-likelihood ``LawFit`` of the stretched law exp(-c x**beta) with ``beta`` fixed
    (> 0), c with its 95% profile interval: the paper's exp(-c_2 sqrt(t)) is beta = 1/2."""
    if not beta > 0:
        raise ValueError(f"a fixed stretched exponent must be > 0, got {beta!r}")
    law = "stretched_exponential"
    h = shape(law, w.x, w.start, beta)
    s, lk = _scale_mle(h, w.escapes, _k(law, w, beta))
    if not math.isfinite(s):
        raise _no_information(w)
    to_c = 1.0 / (beta * w.start ** beta)
    lo, hi = _scale_interval(law, w, s, lk, beta)
    return LawFit(law, {"c": s * to_c, "beta": float(beta)}, {"c": (lo * to_c, hi * to_c)},
                  lk, s, w)


def _stretched_intervals(w, log_x, log_z, beta, c, l_hat):
    target = l_hat - Q95

    def f_beta(b):
        return _stretched_profile(b, log_x, w.escapes, log_z, w.weights)[1] - target

    lo = 0.0 if f_beta(0.0) >= 0 or beta == 0 else brentq(f_beta, 0.0, beta, xtol=1e-12)
    hi = (BETA_MAX if f_beta(BETA_MAX) >= 0 or beta == BETA_MAX
          else brentq(f_beta, beta, BETA_MAX, xtol=1e-12))

    def f_c(log_c):
        return _c_profile(log_c, w.start, log_x, w.escapes, log_z, w.weights, BETA_MAX) - target

    return {"c": _c_interval(f_c, c, w, hi), "beta": (lo, hi)}


def _c_interval(f_c, c, w, beta_hi):
    """Ends of c's profile interval: roots of f_c(log c) = 0 around the maximum; at c_hat = inf
    (beta = 0, the power-law limit) the upper end is inf and the search starts from
    c = alpha/beta_hi, the c of the power law's alpha at the upper end of beta's interval."""
    if math.isfinite(c):
        centre = math.log(c)
        ends = []
        for step in (-1.0, 1.0):
            far = centre + step
            while f_c(far) > 0 and abs(far - centre) < 60:
                far += step
            if f_c(far) > 0:  # never drops below the target: unbounded on this side
                ends.append(0.0 if step < 0 else math.inf)
            else:
                ends.append(math.exp(brentq(f_c, far, centre, xtol=1e-12, rtol=1e-10)))
        return tuple(ends)
    alpha = fit_law("power_law", w, intervals=False).scale
    near = math.log(alpha / max(beta_hi, 1e-12))
    step = -1.0 if f_c(near) > 0 else 1.0
    far = near
    for _ in range(60):
        if (f_c(far) > 0) != (f_c(near) > 0):
            break
        near, far = far, far + step
    else:
        return (0.0 if step < 0 else math.inf, math.inf)
    return (math.exp(brentq(f_c, min(near, far), max(near, far), xtol=1e-12, rtol=1e-10)),
            math.inf)
