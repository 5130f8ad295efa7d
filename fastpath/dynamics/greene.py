"""Greene's residue criterion for the break-up of an invariant spanning curve, in float64.

An invariant curve with rotation number omega (mean phase advance per collision 2*pi*omega, i.e.
velocity near pi*omega) is approached by periodic orbits of period q and winding m with
m/q -> omega. Greene: the residues R of these orbits tend to 0 while the curve exists and grow
without bound once it is broken; at the break-up they tend to the critical residue
R_c = 0.2500888 (Greene 1979; the same for every noble curve, MacKay 1983). So eps_k, where the
residue of the k-th approximant crosses R_c, converges to the critical amplitude eps_c
geometrically, with the ratio of successive differences near -0.376 (measured). A crossing of
any other level converges too, but more slowly and from one side: the crossings of 1/4 lie
below eps_c by an amount that shrinks only like the growth of the residue's slope.

Uncertainty of eps_c (``critical_amplitude``; the basis, written down): eps_c is the last
crossing eps_n. With d_k = eps_k - eps_(k-1) and r the largest |d_k/d_(k-1)| over the last
RATIO_WINDOW ratios (r < 1), the remaining geometric tail is at most |d_n|*r/(1 - r) if the
ratios stay below r; to it are added the last crossing's own rounding (``Crossing.eps_error``)
and the effect of the critical residue's last digit, CRITICAL_RESIDUE_ERROR/|dR/deps|. The
Aitken extrapolation eps_n - d_n**2/(d_n - d_(n-1)) is reported beside it (its change between
levels is a second, empirical measure). float64 gives the residue to ``residue_error``: where
that, divided by the slope, is not far below the tail (periods of ~1600 and beyond, where the
slope's growth no longer outpaces the rounding), ``verify.dynamics.residue`` computes the same
crossings in multiprecision.

Orbits: the map is reversible (``kernels.symmetric_newton``), so each approximant has a symmetric
orbit through the line phi = 0 (the plate's top, where the fixed points (0, pi*m) are elliptic
for 0 < eps < 1): a one-dimensional root in v, followed by continuation in eps from eps = 0
(where v = pi*m/q exactly). Its residue is positive below the break-up.

Rotation numbers: band j plus a noble fraction [0; prefix..., 1, 1, ...] (``noble``): the golden
mean gamma = 0.618... (prefix ()), gamma**2 = 0.381... (prefix (2,)), ...; velocity near
pi*omega. The approximants are the convergents of its continued fraction.

Everything here is float64 (``verify.periodic_orbit`` certifies individual orbits).
"""

import math
from dataclasses import dataclass

import numpy as np

from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dynamics.kernels import half_orbit, symmetric_newton
from fastpath.dynamics.periodic_orbit import TRACE_ROUNDING, OrbitNotFound, build_orbit
from fastpath.inputs import integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.status import CONVERGED

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
CRITICAL_RESIDUE = 0.2500888  # Greene (1979): residues of noble approximants at the break-up
CRITICAL_RESIDUE_ERROR = 5e-8  # half a unit of its last digit
TARGET = CRITICAL_RESIDUE
RATIO_WINDOW = 3  # ratios of successive differences whose largest bounds the tail
STANDARD_MAP_K_C = 0.971635406  # Greene (1979), MacKay (1983): golden curve of the standard map
MAX_NEWTON = 60
_MIN_STEP = 1e-7  # continuation step in eps below which a branch is given up
_SLOPE_STEP = 1e-8  # relative step of the central difference dR/deps at a crossing
_NEWTON_NOISE = 1e-12  # relative scatter of a converged v (rounding of the half orbit)


def _growth_limit(residue):
    """Largest residue accepted after one continuation step from ``residue``: steps are shortened
    where |residue| grows fast (near the crossing), so that Newton's start is close enough to
    stay on the branch; nearby orbits of the same type can be 1e-5 apart there."""
    return 2.0 * abs(residue) + 0.1


@dataclass(frozen=True)
class Approximant:
    """A periodic orbit type: ``period`` q and ``winding`` m (total time 2*pi*m)."""

    period: int
    winding: int

    @property
    def rotation(self):
        return self.winding / self.period


def noble(prefix=()):
    """The noble number [0; prefix..., 1, 1, 1, ...] in (0, 1): () is the golden mean
    (sqrt(5) - 1)/2 = 0.618..., (2,) its square 0.381..., (3,) = 1/(3 + 0.618...)."""
    x = GOLDEN
    for a in reversed(_prefix(prefix)):
        x = 1.0 / (a + x)
    return x


def _prefix(prefix):
    prefix = tuple(prefix)
    if not all(isinstance(a, int) and not isinstance(a, bool) and a >= 1 for a in prefix):
        raise ValueError(f"prefix must hold integers >= 1, got prefix={prefix!r}")
    return prefix


def approximants(band, prefix=(), levels=12, smallest=3):
    """The convergents (q, m) of omega = band + [0; prefix..., 1, 1, ...] with q >= smallest.

    With convergents p/q of the fractional part, m = band*q + p (total time 2*pi*m).
    """
    band = integer("band", band, minimum=0)
    quotients = _prefix(prefix)
    levels = integer("levels", levels, minimum=1)
    p_prev, p = 1, 0  # convergents of [0; a1, a2, ...]: p_(-1) = 1, p_0 = 0
    q_prev, q = 0, 1
    out = []
    k = 0
    while len(out) < levels:
        a = quotients[k] if k < len(quotients) else 1
        p_prev, p = p, a * p + p_prev
        q_prev, q = q, a * q + q_prev
        k += 1
        if q >= smallest and (not out or out[-1].period != q):
            out.append(Approximant(q, band * q + p))
    return out


def symmetric_orbit(v, eps, period, winding, *, phase=0.0, model="exact"):
    """The symmetric periodic orbit through (phase, v'), v' found by Newton's method from v
    (``kernels.symmetric_newton``); phase 0 (the elliptic family) or pi. Returns a
    ``PeriodicOrbit``; raises OrbitNotFound when Newton does not converge."""
    v, eps, phase = real("v", v), real("eps", eps), real("phase", phase)
    period = integer("period", period, minimum=1)
    winding = integer("winding", winding, minimum=1)
    if phase not in (0.0, math.pi):
        raise ValueError(f"phase must be 0 or pi (a symmetry line), got phase={phase!r}")
    physics = model_physics(model, eps)
    v1, g, _, its, status = symmetric_newton(phase, v, physics, period, winding, MAX_NEWTON)
    if status != CONVERGED:
        raise OrbitNotFound(f"no symmetric orbit of period {period}, winding {winding} found from "
                            f"v={v!r} at eps={eps!r} (status {status}, residual {g:.3g})")
    return build_orbit(phase, v1, physics, period, winding, 0, its,
                       start_error=_start_error(phase, v1, physics, period))


def _start_error(phase, v, physics, period):
    """(0, dv): the start lies exactly on its symmetry line; v is off by the rounding of the
    half-orbit condition g (~u times the half orbit's time and speeds) over |g'|."""
    time, vn, dt, dvn, status = half_orbit(phase, v, physics, period // 2)
    slope = dt + dvn if period % 2 == 1 else dt
    if status != CONVERGED or slope == 0.0:
        return (0.0, math.inf)
    g_error = TRACE_ROUNDING * UNIT_ROUNDOFF * (time + abs(vn) + abs(v) * period)
    return (0.0, g_error / abs(slope))


@dataclass(frozen=True)
class Crossing:
    """Where the residue of one approximant crosses ``target``: ``eps`` (bracketed by
    ``bracket``), the orbit's start velocity ``v``, the slope dR/deps there, the rounding bound
    ``residue_error`` of the residue there (``PeriodicOrbit.residue_error``), ``eps_error`` =
    residue_error/|slope| + the bracket's width, and the number of orbits computed."""

    approximant: Approximant
    eps: float
    bracket: tuple
    v: float
    slope: float
    residue_error: float
    eps_error: float
    orbits: int


def residue_crossing(approximant, *, phase=0.0, model="exact", target=TARGET, eps_step=0.01,
                     eps_max=2.0, tolerance=1e-12):
    """The smallest eps > 0 where the residue of the symmetric orbit ``approximant`` reaches
    ``target``, following the orbit from eps = 0 (v = pi*m/q) by continuation in eps.

    The step halves where Newton fails or the residue grows by more than ``_growth_limit``
    (down to 1e-7: then OrbitNotFound). The crossing is refined by the Illinois method on
    R(eps) - target to ``tolerance`` in eps, each orbit started from the interpolation of the
    bracket's ends (a solution farther than their distance is refused as another branch).
    """
    q, m = approximant.period, approximant.winding
    model_physics(model, 0.0)  # a ValueError for an unknown model before any work
    count = 0

    def described(eps):
        return model_physics(model, eps)

    def solve(eps, v_guess):
        nonlocal count
        count += 1
        physics = described(eps)
        v, _, _, _, status = symmetric_newton(phase, v_guess, physics, q, m, MAX_NEWTON)
        if status != CONVERGED:
            return None
        return v, build_orbit(phase, v, physics, q, m, 0).residue

    eps, v, slope = 0.0, math.pi * m / q, 0.0
    residue = 0.0
    step = eps_step
    while True:
        if eps + step > eps_max:
            raise OrbitNotFound(f"residue of {approximant} stays below {target} up to "
                                f"eps={eps_max}")
        found = solve(eps + step, v + slope * step)
        if found is None or (abs(found[1]) > _growth_limit(residue) and step > _MIN_STEP):
            step /= 2.0
            if step < _MIN_STEP:
                raise OrbitNotFound(f"lost the symmetric orbit {approximant} near eps={eps!r}")
            continue
        v_new, r_new = found
        if r_new >= target:
            break
        slope = (v_new - v) / step
        eps, v, residue = eps + step, v_new, r_new
        step = min(2.0 * step, eps_step)
    lo, hi, r_lo, r_hi, v_lo, v_hi = eps, eps + step, residue, r_new, v, v_new
    side = 0
    while hi - lo > tolerance:
        mid = hi - (r_hi - target) * (hi - lo) / (r_hi - r_lo)
        if not lo < mid < hi:
            mid = 0.5 * (lo + hi)
        v_pred = v_lo + (v_hi - v_lo) * (mid - lo) / (hi - lo)
        found = solve(mid, v_pred)
        if found is None or abs(found[0] - v_pred) > abs(v_hi - v_lo) + _NEWTON_NOISE * v_pred:
            raise OrbitNotFound(f"lost the symmetric orbit {approximant} near eps={mid!r}")
        v_mid, r_mid = found
        if r_mid < target:
            lo, r_lo, v_lo = mid, r_mid, v_mid
            if side == -1:
                r_hi = target + (r_hi - target) / 2.0
            side = -1
        else:
            hi, r_hi, v_hi = mid, r_mid, v_mid
            if side == 1:
                r_lo = target + (r_lo - target) / 2.0
            side = 1
    eps = 0.5 * (lo + hi)
    h = _SLOPE_STEP * max(eps, 1.0)
    below, above = solve(eps - h, v_lo), solve(eps + h, v_lo)
    orbit = build_orbit(phase, v_lo, described(lo), q, m, 0,
                        start_error=_start_error(phase, v_lo, described(lo), q))
    if below is None or above is None:
        raise OrbitNotFound(f"lost the symmetric orbit {approximant} near eps={eps!r}")
    slope = (above[1] - below[1]) / (2.0 * h)
    eps_error = orbit.residue_error / abs(slope) + (hi - lo)
    return Crossing(approximant, eps, (lo, hi), v_lo, slope, orbit.residue_error, eps_error,
                    count)


@dataclass(frozen=True)
class CriticalAmplitude:
    """eps_c of one band by Greene's criterion: the crossings of the approximants, the last
    crossing ``eps_c``, ``ratio`` the last ratio of successive differences, ``tail_ratio`` the
    largest |ratio| over the last RATIO_WINDOW, ``uncertainty`` (module docstring: the geometric
    tail with that ratio, the last crossing's rounding and the critical residue's last digit),
    ``aitken`` the Aitken extrapolation and ``target`` the residue crossed."""

    band: int
    prefix: tuple
    model: str
    crossings: list
    eps_c: float
    uncertainty: float
    ratio: float
    aitken: float
    tail_ratio: float = math.nan
    target: float = TARGET


def tail_uncertainty(eps, eps_error, slope, target=TARGET):
    """(uncertainty, last ratio, tail ratio, Aitken value) of the last of the crossings ``eps``
    (module docstring); ``eps_error`` and ``slope`` of the last crossing."""
    eps = np.asarray(eps, dtype=float)
    if len(eps) < 3:
        raise ValueError(f"at least 3 crossings are needed for an uncertainty, got {len(eps)}")
    d = np.diff(eps)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratios = d[1:] / d[:-1]
    recent = np.abs(ratios[-RATIO_WINDOW:])
    r = float(np.max(recent)) if np.all(np.isfinite(recent)) else math.inf
    tail = abs(d[-1]) * r / (1.0 - r) if r < 1.0 else math.inf
    digit = CRITICAL_RESIDUE_ERROR / abs(slope) if target == CRITICAL_RESIDUE else 0.0
    d1, d2 = d[-1], d[-2]
    aitken = eps[-1] - d1 * d1 / (d1 - d2) if d1 != d2 else eps[-1]
    return tail + eps_error + digit, float(ratios[-1]), r, float(aitken)


def extrapolate(eps, errors):
    """(A, uncertainty): the Aitken extrapolation A_n of the last three crossings ``eps`` and its
    uncertainty (basis, written down): twice the change A_n - A_(n-1) over the last level (the
    extrapolations converge geometrically; twice the last change bounds what remains while
    their ratio stays below 2/3), plus the crossings' own errors ``errors`` carried through
    the formula, sum |dA/deps_i|*error_i over the last three (dA/deps_n = 1/(1 - rho)**2,
    dA/deps_(n-2) = (rho/(1 - rho))**2, rho = d_n/d_(n-1), and the middle one their
    complement to 1); A_(n-1)'s own errors are counted too (at most 4 crossings used)."""
    eps = np.asarray(eps, dtype=float)
    errors = np.asarray(errors, dtype=float)
    if len(eps) < 4:
        raise ValueError(f"at least 4 crossings are needed to extrapolate, got {len(eps)}")

    def aitken(e0, e1, e2):
        d1, d2 = e2 - e1, e1 - e0
        return e2 - d1 * d1 / (d1 - d2) if d1 != d2 else e2

    def carried(e0, e1, e2, err):
        rho = (e2 - e1) / (e1 - e0)
        w_last, w_first = 1.0 / (1.0 - rho) ** 2, (rho / (1.0 - rho)) ** 2
        weights = (w_first, abs(1.0 - w_last - w_first), w_last)
        return sum(w * e for w, e in zip(weights, err, strict=True))

    last = aitken(*eps[-3:])
    before = aitken(*eps[-4:-1])
    rounding = max(carried(*eps[-3:], errors[-3:]), carried(*eps[-4:-1], errors[-4:-1]))
    return float(last), float(2.0 * abs(last - before) + rounding)


def critical_amplitude(band, prefix=(), *, model="exact", levels=10, smallest=3,
                       target=TARGET):
    """Greene's estimate of the break-up amplitude of the curve omega = band + noble(prefix)."""
    model_physics(model, 0.0)  # a ValueError for an unknown model before any work
    if levels < 3:
        raise ValueError(f"levels must be >= 3 for an uncertainty, got {levels}")
    crossings = [residue_crossing(a, model=model, target=target)
                 for a in approximants(band, prefix, levels, smallest)]
    last = crossings[-1]
    uncertainty, ratio, r, aitken = tail_uncertainty([c.eps for c in crossings],
                                                     last.eps_error, last.slope, target)
    return CriticalAmplitude(band, tuple(prefix), model, crossings, float(last.eps),
                             float(uncertainty), ratio, aitken, r, target)
