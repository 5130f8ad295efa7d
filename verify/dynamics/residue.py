"""Residues of symmetric periodic orbits in multiprecision, and where they cross a level.

For Greene's criterion (``fastpath.dynamics.greene``) at periods where float64's rounding of the
residue is no longer small against the accuracy a crossing needs (periods of ~1600 and beyond).
Point arithmetic in a private ``mpmath`` context at ``dps`` digits, not intervals: each residue
is computed again at ``dps + CHECK_DPS`` digits and the difference is reported as its error (a
measured rounding error, not a proof; ``verify.periodic_orbit`` proves individual orbits).

Maps. ``"exact"``: the collision map; the flight is the first root of the gap
d(t) = eps*(cos(phi) - cos(phi + t)) + t*(v - t/2), here for |eps| < 1 only, where d is
strictly concave and the root is the only positive one: Newton's method from the Holmes time
2*v inside the bracket 2*w0/(1 + |eps|) <= tau <= 2*w0/(1 - |eps|), bisecting where a step
leaves it. ``"holmes"``: the Holmes map in its standard-map form, phi1 = phi + 2*v,
v1 = v - 2*eps*sin(phi1). The Jacobian of a collision is that of docs/dynamics.md:
a = eps*(sin(phi1) - sin(phi))/w1, b = tau/w1, c = 2*eps*cos(phi1),
DF = [[1 + a, b], [a - c*(1 + a), -1 + b - c*b]] (Holmes: [[1, 2], [-c, 1 - 2*c]]).

Symmetric orbits (the map is F = I1 o I0, Fix I1 = {phi = 0, pi}, Fix I0 = {phi + v = 0 mod pi}):
from (phase0, v) with phase0 = 0 or pi, an orbit of period q = 2n + 1 is periodic iff after n
collisions time_n + v_n = pi*m, and for q = 2n iff time_n = pi*m: a root in v alone, found by
Newton's method with the tangent of the start's v direction. The residue is (2 - tr M)/4 with
M the product of the q Jacobians. ``crossing`` finds where it equals a target by the Illinois
method in eps, each orbit from the v interpolated between the bracket's ends.
"""

from __future__ import annotations

from typing import NamedTuple

from verify.dynamics.numbers import contexts

CHECK_DPS = 20  # the residue is recomputed with this many more digits to measure its error
MAX_NEWTON = 40
MAX_FLIGHT = 200  # Newton/bisection steps of one flight
MAX_ILLINOIS = 60


class ResidueError(ArithmeticError):
    """An orbit or a crossing could not be followed (the message says where)."""


class SymmetricOrbit(NamedTuple):
    """The symmetric orbit through (phase0, v): its start velocity, residue and trace."""

    v: object
    residue: object
    trace: object


class Crossing(NamedTuple):
    """eps where the residue equals ``target``: within ``bracket`` (its width the iteration's
    stop), the orbit's start ``v``, the slope dR/deps, ``residue_error`` (the residue at the end
    recomputed with CHECK_DPS more digits) and ``eps_error`` = residue_error/|slope| + width.
    Numbers are mpf of the call's context."""

    eps: object
    bracket: tuple
    v: object
    slope: object
    residue_error: object
    eps_error: object
    orbits: int


def _flight(mp, phi, v, eps):
    """(tau, sin(phi + tau), cos(phi + tau)) of the exact map, |eps| < 1 (module docstring)."""
    c0, s0 = mp.cos_sin(phi)
    w0 = v + eps * s0
    if not w0 > 0:
        raise ResidueError(f"a state does not depart (w0 = {mp.nstr(w0, 8)})")
    lo, hi = 2 * w0 / (1 + abs(eps)), 2 * w0 / (1 - abs(eps))
    t = 2 * v
    c, s = mp.cos_sin(phi + t)
    t += 2 * eps * (c0 - c) / (v - eps * s + t / 2)  # Holmes time + its first correction
    if not lo < t < hi:
        t = (lo + hi) / 2
    tol = mp.mpf(2) ** (-mp.prec // 2 - 4) * (1 + t)
    for _ in range(MAX_FLIGHT):
        c, s = mp.cos_sin(phi + t)
        d = eps * (c0 - c) + t * (v - t / 2)
        if d > 0:
            lo = t
        else:
            hi = t
        slope = v - t + eps * s
        step = d / slope if slope != 0 else mp.inf
        t_next = t - step
        if not lo <= t_next <= hi:
            t_next = (lo + hi) / 2
        elif abs(step) <= tol:  # quadratic convergence: this step is good to ~tol**2
            c, s = mp.cos_sin(phi + t_next)
            return t_next, s, c
        t = t_next
    raise ResidueError("a flight did not converge")


def _collision(mp, phi, v, eps, model):
    """(phi1 reduced, v1, tau, (j11, j12, j21, j22)) of one collision."""
    if model == "holmes":
        tau = 2 * v
        phi1 = phi + tau
        s1, c1 = mp.sin(phi1), mp.cos(phi1)
        v1 = v - 2 * eps * s1
        if not (v > 0 and v1 > 0):
            raise ResidueError("the Holmes map's absolute value would act")
        c = 2 * eps * c1
        jac = (mp.one, mp.mpf(2), -c, 1 - 2 * c)
    else:
        tau, s1, c1 = _flight(mp, phi, v, eps)
        phi1 = phi + tau
        v1 = tau - v - 2 * eps * s1
        w1 = v1 + eps * s1
        a = eps * (s1 - mp.sin(phi)) / w1  # phi's sine again: cheap against the flight
        b = tau / w1
        c = 2 * eps * c1
        jac = (1 + a, b, a - c * (1 + a), -1 + b - c * b)
    return mp.fmod(phi1, 2 * mp.pi), v1, tau, jac


def _half(mp, v, eps, phase0, steps, model):
    """(time, v_n, dtime/dv, dv_n/dv) after ``steps`` collisions from (phase0, v)."""
    phi, time = phase0, mp.zero
    dphi, dv = mp.zero, mp.one
    for _ in range(steps):
        phi, v, tau, j = _collision(mp, phi, v, eps, model)
        time += tau
        dphi, dv = j[0] * dphi + j[1] * dv, j[2] * dphi + j[3] * dv
    # the unreduced phase advance is the time: d(time)/dv accumulates as the phase's tangent
    return time, v, dphi, dv


def _trace(mp, v, eps, phase0, period, model):
    phi = phase0
    m = (mp.one, mp.zero, mp.zero, mp.one)
    for _ in range(period):
        phi, v, _, j = _collision(mp, phi, v, eps, model)
        m = (j[0] * m[0] + j[1] * m[2], j[0] * m[1] + j[1] * m[3],
             j[2] * m[0] + j[3] * m[2], j[2] * m[1] + j[3] * m[3])
    return m[0] + m[3]


def _orbit(mp, v, eps, period, winding, phase0, model):
    """Newton's method in v for the symmetric condition; the orbit with its residue."""
    n, odd = period // 2, period % 2 == 1
    target = mp.pi * winding
    tol = mp.mpf(2) ** (-mp.prec + 10) * (1 + abs(v))
    for _ in range(MAX_NEWTON):
        time, vn, dt, dvn = _half(mp, v, eps, phase0, n, model)
        g, dg = (time + vn - target, dt + dvn) if odd else (time - target, dt)
        if dg == 0:
            raise ResidueError("the symmetric condition has a zero derivative")
        step = g / dg
        v -= step
        if abs(step) <= tol:
            trace = _trace(mp, v, eps, phase0, period, model)
            return SymmetricOrbit(v, (2 - trace) / 4, trace)
    raise ResidueError(f"Newton's method for the symmetric orbit of period {period} did not "
                       f"converge")


def _check_model(model, eps):
    if model not in ("exact", "holmes"):
        raise ValueError(f"model must be 'exact' or 'holmes', got model={model!r}")
    if model == "exact" and not abs(eps) < 1:
        raise ValueError(f"the exact map's flights are solved here for |eps| < 1 only, got "
                         f"eps={eps!r}")


def symmetric_orbit(v, eps, period, winding, *, phase0=0, model="exact", dps=40):
    """The symmetric orbit of ``period`` and ``winding`` through (phase0, v'), v' by Newton's
    method from v, at ``dps`` digits (values as mpf of a private context)."""
    _check_model(model, eps)
    mp = contexts(dps).mp
    phase = mp.pi if phase0 else mp.zero
    return _orbit(mp, mp.mpf(v), mp.mpf(eps), period, winding, phase, model)


def crossing(period, winding, bracket, v_ends, *, target, phase0=0, model="exact", dps=40,
             tolerance=1e-13) -> Crossing:
    """eps in ``bracket`` = (eps_lo, eps_hi) where the residue of the symmetric orbit equals
    ``target``; ``v_ends``: start velocities near the orbit at the two ends (the float64 ones).

    The residue must be below the target at eps_lo and above it at eps_hi (ResidueError
    otherwise). The Illinois method stops when the bracket is narrower than
    ``tolerance``*(1 + eps); the residue at the answer is recomputed with CHECK_DPS more digits
    for its error.
    """
    for e in bracket:
        _check_model(model, float(e))
    mp = contexts(dps).mp
    phase = mp.pi if phase0 else mp.zero
    target = mp.mpf(target)
    lo, hi = mp.mpf(bracket[0]), mp.mpf(bracket[1])
    count = 2
    a = _orbit(mp, mp.mpf(v_ends[0]), lo, period, winding, phase, model)
    b = _orbit(mp, mp.mpf(v_ends[1]), hi, period, winding, phase, model)
    r_lo, r_hi = a.residue - target, b.residue - target
    if not (r_lo < 0 < r_hi):
        raise ResidueError(f"the residue does not cross {mp.nstr(target, 8)} in the bracket "
                           f"(residues {mp.nstr(a.residue, 8)}, {mp.nstr(b.residue, 8)})")
    v_lo, v_hi = a.v, b.v
    side = 0
    for _ in range(MAX_ILLINOIS):
        if hi - lo <= tolerance * (1 + abs(hi)):
            break
        mid = hi - r_hi * (hi - lo) / (r_hi - r_lo)
        if not lo < mid < hi:
            mid = (lo + hi) / 2
        v_mid = v_lo + (v_hi - v_lo) * (mid - lo) / (hi - lo)
        orbit = _orbit(mp, v_mid, mid, period, winding, phase, model)
        count += 1
        r = orbit.residue - target
        if r < 0:
            lo, r_lo, v_lo = mid, r, orbit.v
            if side == -1:
                r_hi /= 2
            side = -1
        else:
            hi, r_hi, v_hi = mid, r, orbit.v
            if side == 1:
                r_lo /= 2
            side = 1
    else:
        raise ResidueError("the crossing's bracket did not close")
    eps = (lo + hi) / 2
    h = max(hi - lo, mp.mpf(10) ** (-dps // 2)) * (1 + eps)
    below = _orbit(mp, v_lo, eps - h, period, winding, phase, model)
    above = _orbit(mp, v_hi, eps + h, period, winding, phase, model)
    slope = (above.residue - below.residue) / (2 * h)
    here = _orbit(mp, v_lo, eps, period, winding, phase, model)
    fine = contexts(dps + CHECK_DPS).mp
    again = _orbit(fine, fine.mpf(here.v), fine.mpf(eps), period, winding,
                   fine.pi if phase0 else fine.zero, model)
    residue_error = abs(fine.mpf(here.residue) - again.residue)
    count += 4
    eps_error = residue_error / abs(slope) + (hi - lo)
    return Crossing(eps, (lo, hi), here.v, slope, mp.mpf(residue_error), mp.mpf(eps_error),
                    count)
