"""Periodic orbits of the collision map in float64: Newton's method on F^p - id.

A periodic orbit of period p with winding m (and, for an accelerator mode, velocity shift l) is a
zero of

    G(phi, v) = (t_p - 2*pi*m,  v_p - v - pi*l),

where t_p is the sum of the p flight times from (phi, v) (the unreduced phase advance) and v_p
the velocity after p collisions. Newton's method uses the exact Jacobian M - I, M = DF^p the
product of the collision Jacobians (``fastpath.dynamics.kernels``). The residue
R = (2 - tr M)/4 (Greene) classifies the orbit: elliptic for 0 < R < 1, hyperbolic for R < 0 or
R > 1. Over a periodic orbit det M = 1; for l != 0 (the exact map is not periodic in v) det M is
w_0/w_p, and the classification uses tr M/sqrt(det M) instead of tr M.

The same rules as ``verify.periodic_orbit`` (which proves them), in float64:

* Minimal period. A zero of F^p - id may be an orbit of a shorter period d | p (the fixed point
  (0, pi) is a zero of every F^p - id). Each divisor d (ascending) is tested at the converged
  state: if d collisions bring it back to itself, |F^d(x) - x - (2*pi*m_d, pi*l_d)| <= SAME
  (phase, and v relative to 1 + |v|) with m_d, l_d the nearest integers, the orbit is
  RELABELLED to period d (``period``, ``winding``, ``velocity_shift``, states and monodromy of
  the d collisions). Two states closer than SAME are taken as one: float64 cannot tell a
  genuine period-p orbit that close to a shorter one (a period doubling within ~1e-16 of its
  birth).
* Velocity shifts of the exact map (model "exact", l != 0): the shifted relations that repeat
  block after block are exactly the period-1 modes with l > 0 (``verify.dynamics.accelerator``
  proves it). A decelerating shift (l < 0) raises OrbitNotFound; a block of p >= 2 collisions
  with a shift is searched as p blocks of a period-1 mode (shift l/p; OrbitNotFound if l/p is
  not an integer or Newton finds none) and relabelled to period 1; a mode's later flights at
  velocities pi*(m + k*l) <= 2*|eps| are computed and must end at 2*pi*(m + k*l) (beyond, the
  bound of ``verify.dynamics.accelerator`` holds), else OrbitNotFound. The Holmes model
  (standard-map form) commutes with v -> v + pi: every shifted block there is a mode.
* A winding taken from the guess (``winding=None``) that rounds below 1 (the guess's p flights
  last less than pi) raises OrbitNotFound: no orbit with a positive winding is near it.

Nothing here is proved: ``verify.periodic_orbit`` certifies an orbit found here.
"""

import math
from dataclasses import dataclass

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dynamics.kernels import newton_block, orbit_monodromy, product_rounding_scale
from fastpath.elastic.collision import collide_from
from fastpath.elastic.flight import GENERAL
from fastpath.inputs import departing, integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.physics import Elastic, model_name
from fastpath.status import CONVERGED, NOT_DEPARTING, FlightStatus, UncertainCollision

ELLIPTIC, HYPERBOLIC, UNDECIDED = "elliptic", "hyperbolic", "undecided"
MAX_ITERATIONS = 60
NOT_CONVERGED = -1  # newton_block's status when the iteration does not settle
# Relative rounding of a Jacobian entry and of one 2x2 product, in units of u: the entries take
# ~10 operations after a flight time good to a few u (relative to its conditioning).
TRACE_ROUNDING = 32.0
SAME = 1e-8  # two states of an orbit this close (phase; v relative to 1 + |v|) are one
MAX_SLOW_BLOCKS = 1_000  # a mode's later flights checked one by one below v = 2*|eps|


class OrbitNotFound(ArithmeticError):
    """Newton's method from the guess did not reach a periodic orbit (or left the model)."""


@dataclass(frozen=True)
class PeriodicOrbit:
    """A periodic orbit found in float64.

    ``phi``, ``v``, ``tau``: the p states (phases in [0, 2*pi)) and the flight times from them;
    ``monodromy``: DF^p at the first state; ``trace``, ``determinant``, ``residue``
    (= (2 - trace)/4); ``residue_error``: a first-order rounding estimate of the residue: the
    product's rounding, 32*u*S/4 with S of ``kernels.product_rounding_scale``, plus the change
    of the residue when the start moves by its own error (G's rounding through (M - I)^-1):
    an estimate, not a proof;
    ``stability``: "elliptic", "hyperbolic" or "undecided" (within residue_error of 0 or 1);
    ``residual``: |G| at the returned state; ``iterations``: Newton steps taken.
    """

    phi: np.ndarray
    v: np.ndarray
    tau: np.ndarray
    eps: float
    period: int
    winding: int
    velocity_shift: int
    model: str
    monodromy: np.ndarray
    trace: float
    determinant: float
    residue: float
    residue_error: float
    stability: str
    residual: float
    iterations: int


def classify(residue, error):
    """"elliptic" (0 < R < 1), "hyperbolic" (R < 0 or R > 1) beyond ``error``, else "undecided"."""
    if error < residue < 1.0 - error:
        return ELLIPTIC
    if residue < -error or residue > 1.0 + error:
        return HYPERBOLIC
    return UNDECIDED


def stability_residue(trace, determinant):
    """(2 - tr/sqrt(det))/4: the residue of a linearisation with determinant det (1 over a
    periodic orbit). 0 < it < 1 iff the eigenvalues are complex."""
    return (2.0 - trace / math.sqrt(determinant)) / 4.0 if determinant > 0 else math.nan


def _raise_for_status(status, phi, v, eps, where):
    if status == NOT_DEPARTING:
        raise OrbitNotFound(f"{where}: a state of the orbit does not depart (w0 <= 0), or the "
                            f"Holmes map's absolute value acts; near phi={phi!r}, v={v!r}, "
                            f"eps={eps!r}")
    raise UncertainCollision(f"{where}: a flight float64 cannot decide "
                             f"({FlightStatus(status).name}) near phi={phi!r}, v={v!r}, "
                             f"eps={eps!r}; settle it with verify")


def build_orbit(phi, v, physics, period, winding, shift, iterations=0, start_error=None):
    """The PeriodicOrbit through (phi, v) as given (no Newton step) of the map of ``physics``
    (``Elastic`` or ``Holmes``): its states, monodromy, residue and stability, and the residual
    |G|. ``start_error``: the displacements (dphi, dv) of the start's own error where the caller
    knows them (a symmetric orbit found on its symmetry line); by default they come from G's
    rounding through (M - I)^-1."""
    eps = physics.eps
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    time, v_end, _, m11, m12, m21, m22, status, _ = orbit_monodromy(
        phi, v, physics, period, phi_k, v_k, tau_k, jac)
    if status != CONVERGED:
        _raise_for_status(status, phi, v, eps, "the orbit")
    monodromy = np.array([[m11, m12], [m21, m22]])
    trace, det = m11 + m22, m11 * m22 - m12 * m21
    residue = (2.0 - trace) / 4.0
    error = TRACE_ROUNDING * UNIT_ROUNDOFF * product_rounding_scale(jac) / 4.0
    if start_error is None:
        error += _position_error(phi, v, physics, period, monodromy, time, v_k, residue)
    else:
        error += _residue_change(phi, v, physics, period, residue, [start_error])
    decided = residue if shift == 0 else stability_residue(trace, det)
    residual = max(abs(time - TWO_PI * winding), abs(v_end - v - math.pi * shift))
    return PeriodicOrbit(phi_k, v_k, tau_k, eps, period, winding, shift, model_name(physics),
                         monodromy, trace, det, residue, error, classify(decided, error),
                         residual, iterations)


def _residue_at(phi, v, physics, period):
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    *_, m11, m12, m21, m22, status, _ = orbit_monodromy(phi, v, physics, period, phi_k, v_k,
                                                       tau_k, jac)
    return (2.0 - m11 - m22) / 4.0 if status == CONVERGED else math.nan


def _position_error(phi, v, physics, period, monodromy, time, speeds, residue):
    """Effect on the residue of the float orbit's own position error. Newton stops where G is
    at its rounding, |dG| <= g ~ u times the summed times and speeds, so the start is off by
    dx = (M - I)^-1 dG; the residue is recomputed at the four starts x + (M - I)^-1 (+-g, +-g)
    (no linearisation: along a long orbit R is far from linear) and the largest change kept."""
    a = monodromy - np.eye(2)
    det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    if det == 0.0:
        return math.inf
    inverse = np.array([[a[1, 1], -a[0, 1]], [-a[1, 0], a[0, 0]]]) / det
    g_error = TRACE_ROUNDING * UNIT_ROUNDOFF * (time + np.sum(np.abs(speeds)) + abs(v))
    moves = [inverse @ (g_error * np.array(signs)) for signs in ((1.0, 1.0), (1.0, -1.0))]
    return _residue_change(phi, v, physics, period, residue, moves)


def _residue_change(phi, v, physics, period, residue, moves):
    """The largest |R(x +- dx) - R(x)| over the displacements dx (inf if one fails)."""
    worst = 0.0
    for dx in moves:
        for sign in (1.0, -1.0):
            moved = _residue_at(phi + sign * dx[0], v + sign * dx[1], physics, period)
            worst = max(worst, abs(moved - residue))
    return worst if math.isfinite(worst) else math.inf


def periodic_orbit(phi, v, eps, period, *, winding=None, velocity_shift=0, model="exact",
                   max_iterations=MAX_ITERATIONS):
    """Find a periodic orbit of the collision map near (phi, v) by Newton's method on F^p - id.

    phi, v, eps: the guess and the amplitude (finite reals; the guess must depart,
    v + eps*sin(phi) > 0). period p >= 1. winding m: the orbit's total time is 2*pi*m; by
    default the nearest integer to the guess's own p flights / (2*pi). velocity_shift l: v_p =
    v + pi*l (l != 0: an accelerator mode, v grows by pi*l every p collisions; for the exact map
    only period-1 modes with l > 0, module docstring). model: "exact" or "holmes" (the Holmes
    map in its standard-map form). Returns a :class:`PeriodicOrbit` whose ``period`` is the
    minimal one found (module docstring); raises ValueError for bad input,
    :class:`OrbitNotFound` when Newton does not converge or the relation is not an orbit of the
    map, and ``fastpath.UncertainCollision`` for a flight float64 cannot decide.
    """
    phi, v, eps = real("phi", phi), real("v", v), real("eps", eps)
    period = integer("period", period, minimum=1)
    shift = integer("velocity_shift", velocity_shift)
    physics = model_physics(model, eps)
    max_iterations = integer("max_iterations", max_iterations, minimum=1)
    if winding is not None:
        winding = integer("winding", winding, minimum=1)
    departing(phi, v, eps, "the guess")
    where = f"near phi={phi!r}, v={v!r} (eps={eps!r})"
    if type(physics) is Elastic and shift < 0:
        raise OrbitNotFound(f"velocity shift {shift} < 0 {where}: v falls by pi*{-shift} per "
                            f"block to 0 after finitely many; not an accelerator mode of the "
                            f"exact map (its time reverse, at phase -phi, has shift {-shift})")
    if type(physics) is Elastic and shift != 0 and period > 1:
        return _repeated_mode(phi, v, physics, period, winding, shift, max_iterations, where)
    if winding is None:
        winding = _own_winding(phi, v, physics, period, where)
    phi1, v1, g1, g2, step, its, status = newton_block(phi, v, physics, period, winding, shift,
                                                      max_iterations)
    if status == NOT_CONVERGED:
        raise OrbitNotFound(
            f"Newton's method from phi={phi!r}, v={v!r} (eps={eps!r}, period {period}, winding "
            f"{winding}, velocity shift {shift}) did not converge in {its} iterations: last "
            f"residual {max(abs(g1), abs(g2)):.3g}, last step {step:.3g}; try a closer guess")
    if status != CONVERGED:
        _raise_for_status(status, phi1, v1, eps, "Newton's method")
    period, winding, shift = _minimal(phi1, v1, physics, period, winding, shift)
    if type(physics) is Elastic and shift != 0:
        _mode_goes_on(phi1, v1, eps, winding, shift, where)
    return build_orbit(phi1, v1, physics, period, winding, shift, its)


def _own_winding(phi, v, physics, period, where):
    """The winding of the guess's own p flights (rounded); OrbitNotFound below 1."""
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    time, *_, status, _ = orbit_monodromy(phi, v, physics, period, phi_k, v_k, tau_k, jac)
    if status != CONVERGED:
        _raise_for_status(status, phi, v, physics.eps, "the guess's orbit")
    winding = round(time / TWO_PI)
    if winding < 1:
        raise OrbitNotFound(f"the guess's {period} flights {where} last {time:.10g} < pi: no "
                            f"orbit with a winding >= 1 near it (give winding= to search one)")
    return winding


def _repeated_mode(phi, v, physics, period, winding, shift, max_iterations, where):
    """p >= 2 collisions with a shift, exact map: only as p blocks of a period-1 mode."""
    refusal = (f"a block of {period} collisions with velocity shift {shift} {where} is an orbit "
               f"of the exact map only as {period} blocks of a period-1 accelerator mode")
    if shift % period:
        raise OrbitNotFound(f"{refusal}, whose shift would be {shift}/{period}")
    step = shift // period
    one = None
    if winding is not None:  # p blocks of (phi, pi*m1) -> (phi, pi*(m1 + l1)): p*m1 + l1*p(p-1)/2
        twice = 2 * winding - step * period * (period - 1)
        if twice % (2 * period) or twice < 2 * period:
            raise OrbitNotFound(f"{refusal}: winding {winding} is not that of {period} blocks "
                                f"of one")
        one = twice // (2 * period)
    try:
        return periodic_orbit(phi, v, physics.eps, 1, winding=one, velocity_shift=step,
                              model=model_name(physics),
                              max_iterations=max_iterations)
    except OrbitNotFound as err:
        raise OrbitNotFound(f"{refusal}, and none was found: {err}") from None


def _block(phi, v, physics, d):
    """(time, v_end, phase_end) of d collisions from (phi, v), or None if a flight fails."""
    phi_k, v_k, tau_k = np.empty(d), np.empty(d), np.empty(d)
    jac = np.empty((d, 4))
    time, v_end, phi_end, *_, status, _ = orbit_monodromy(phi, v, physics, d, phi_k, v_k,
                                                          tau_k, jac)
    return None if status != CONVERGED else (time, v_end, phi_end)


def _minimal(phi, v, physics, period, winding, shift):
    """(period, winding, shift) of the shortest block that closes at the converged state
    (module docstring: relabelled below ``SAME``)."""
    for d in range(1, period):
        if period % d:
            continue
        block = _block(phi, v, physics, d)
        if block is None:
            continue
        time, v_end, _ = block
        m_d = round(time / TWO_PI)
        l_d = round((v_end - v) / math.pi)
        closes = (abs(time - TWO_PI * m_d) <= SAME
                  and abs(v_end - v - math.pi * l_d) <= SAME * (1.0 + abs(v)))
        if closes and m_d >= 1 and (l_d == 0) == (shift == 0):
            return d, m_d, l_d
    return period, winding, shift


def _mode_goes_on(phi, v, eps, winding, shift, where):
    """The later flights of a period-1 mode of the exact map at velocities pi*(m + k*l) <=
    2*|eps| end at 2*pi*(m + k*l) (beyond, ``verify.dynamics.accelerator``'s bound)."""
    level = winding + shift
    checked = 0
    s, c = math.sin(phi), math.cos(phi)
    while math.pi * level <= 2.0 * abs(eps):
        if checked == MAX_SLOW_BLOCKS:
            raise OrbitNotFound(f"the accelerator mode {where} has more than {MAX_SLOW_BLOCKS} "
                                f"blocks below v = 2*|eps|")
        speed = math.pi * level
        *_, tau, _, status = collide_from(phi, s, c, speed, eps, GENERAL)
        if status != CONVERGED or abs(tau - 2.0 * speed) > SAME * (1.0 + tau):
            raise OrbitNotFound(f"the accelerator mode {where} does not go on: the flight from "
                                f"v = pi*{level} does not end at 2*pi*{level}")
        checked += 1
        level += shift


