"""Greene's residue criterion for the break-up of an invariant spanning curve, in float64.

An invariant curve with rotation number omega (mean phase advance per collision 2*pi*omega, i.e.
velocity near pi*omega) is approached by periodic orbits of period q and winding m with
m/q -> omega. Greene: the residues R of these orbits tend to 0 while the curve exists and grow
without bound once it is broken; at the break-up they tend to a constant close to 1/4
(0.2500888 for the standard map's golden curve). So eps_k, where the residue of the k-th
approximant crosses 1/4, converges to the critical amplitude eps_c.

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

from fastpath.dynamics._checks import integer, model_code
from fastpath.dynamics._internals import CONVERGED
from fastpath.dynamics.kernels import UNIT_ROUNDOFF, half_orbit, symmetric_newton
from fastpath.dynamics.periodic_orbit import TRACE_ROUNDING, OrbitNotFound, build_orbit
from fastpath.inputs import real_scalar as real

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
TARGET = 0.25
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
    code = model_code(model)
    v1, g, _, its, status = symmetric_newton(v, eps, phase, period, winding, code, MAX_NEWTON)
    if status != CONVERGED:
        raise OrbitNotFound(f"no symmetric orbit of period {period}, winding {winding} found from "
                            f"v={v!r} at eps={eps!r} (status {status}, residual {g:.3g})")
    return build_orbit(phase, v1, eps, period, winding, 0, model, its,
                       start_error=_start_error(v1, eps, phase, period, code))


def _start_error(v, eps, phase, period, code):
    """(0, dv): the start lies exactly on its symmetry line; v is off by the rounding of the
    half-orbit condition g (~u times the half orbit's time and speeds) over |g'|."""
    time, vn, dt, dvn, status = half_orbit(v, eps, phase, period // 2, code)
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
    code = model_code(model)
    count = 0

    def solve(eps, v_guess):
        nonlocal count
        count += 1
        v, _, _, _, status = symmetric_newton(v_guess, eps, phase, q, m, code, MAX_NEWTON)
        if status != CONVERGED:
            return None
        return v, build_orbit(phase, v, eps, q, m, 0, model).residue

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
    orbit = build_orbit(phase, v_lo, lo, q, m, 0, model,
                        start_error=_start_error(v_lo, lo, phase, q, code))
    if below is None or above is None:
        raise OrbitNotFound(f"lost the symmetric orbit {approximant} near eps={eps!r}")
    slope = (above[1] - below[1]) / (2.0 * h)
    eps_error = orbit.residue_error / abs(slope) + (hi - lo)
    return Crossing(approximant, eps, (lo, hi), v_lo, slope, orbit.residue_error, eps_error,
                    count)


@dataclass(frozen=True)
class CriticalAmplitude:
    """eps_c of one band by Greene's criterion: the crossings of the approximants, the last
    crossing ``eps_c``, the geometric ratio of the last differences and ``uncertainty``: the
    sum of the remaining geometric tail (at least the last difference times that ratio) plus
    the rounding ``eps_error`` of the last crossing; and the Aitken extrapolation."""

    band: int
    prefix: tuple
    model: str
    crossings: list
    eps_c: float
    uncertainty: float
    ratio: float
    aitken: float


def critical_amplitude(band, prefix=(), *, model="exact", levels=10, smallest=3,
                       target=TARGET):
    """Greene's estimate of the break-up amplitude of the curve omega = band + noble(prefix)."""
    model_code(model)
    crossings = [residue_crossing(a, model=model, target=target)
                 for a in approximants(band, prefix, levels, smallest)]
    eps = np.array([c.eps for c in crossings])
    if len(eps) < 3:
        raise ValueError(f"levels must be >= 3 for an uncertainty, got {levels}")
    d1, d2 = eps[-1] - eps[-2], eps[-2] - eps[-3]
    ratio = d1 / d2 if d2 != 0 else math.nan
    r = abs(ratio)
    tail = abs(d1) * r / (1.0 - r) if r < 1 else math.inf
    uncertainty = max(tail, abs(d1) * r) if math.isfinite(tail) else math.inf
    uncertainty += crossings[-1].eps_error
    aitken = eps[-1] - d1 * d1 / (d1 - d2) if d1 != d2 else eps[-1]
    return CriticalAmplitude(band, tuple(prefix), model, crossings, float(eps[-1]),
                             float(uncertainty), float(ratio), float(aitken))
