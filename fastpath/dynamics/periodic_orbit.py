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

Nothing here is proved: ``verify.periodic_orbit`` certifies an orbit found here.
"""

import math
from dataclasses import dataclass

import numpy as np

from fastpath.dynamics._checks import departing, integer, model_code
from fastpath.dynamics._internals import CONVERGED, NOT_DEPARTING, FlightStatus, UncertainCollision
from fastpath.dynamics.kernels import (
    UNIT_ROUNDOFF,
    newton_block,
    orbit_monodromy,
    product_rounding_scale,
)
from fastpath.inputs import real_scalar as real

ELLIPTIC, HYPERBOLIC, UNDECIDED = "elliptic", "hyperbolic", "undecided"
MAX_ITERATIONS = 60
NOT_CONVERGED = -1  # newton_block's status when the iteration does not settle
# Relative rounding of a Jacobian entry and of one 2x2 product, in units of u: the entries take
# ~10 operations after a flight time good to a few u (relative to its conditioning).
TRACE_ROUNDING = 32.0


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


def build_orbit(phi, v, eps, period, winding, shift, model, iterations=0, start_error=None):
    """The PeriodicOrbit through (phi, v) as given (no Newton step): its states, monodromy,
    residue and stability, and the residual |G|. ``start_error``: the displacements
    (dphi, dv) of the start's own error where the caller knows them (a symmetric orbit found on
    its symmetry line); by default they come from G's rounding through (M - I)^-1."""
    code = model_code(model)
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    time, v_end, _, m11, m12, m21, m22, status, _ = orbit_monodromy(
        phi, v, eps, period, code, phi_k, v_k, tau_k, jac)
    if status != CONVERGED:
        _raise_for_status(status, phi, v, eps, "the orbit")
    monodromy = np.array([[m11, m12], [m21, m22]])
    trace, det = m11 + m22, m11 * m22 - m12 * m21
    residue = (2.0 - trace) / 4.0
    error = TRACE_ROUNDING * UNIT_ROUNDOFF * product_rounding_scale(jac) / 4.0
    if start_error is None:
        error += _position_error(phi, v, eps, period, code, monodromy, time, v_k, residue)
    else:
        error += _residue_change(phi, v, eps, period, code, residue, [start_error])
    decided = residue if shift == 0 else stability_residue(trace, det)
    residual = max(abs(time - 2.0 * math.pi * winding), abs(v_end - v - math.pi * shift))
    return PeriodicOrbit(phi_k, v_k, tau_k, eps, period, winding, shift, model, monodromy, trace,
                         det, residue, error, classify(decided, error), residual, iterations)


def _residue_at(phi, v, eps, period, code):
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    *_, m11, m12, m21, m22, status, _ = orbit_monodromy(phi, v, eps, period, code, phi_k, v_k,
                                                       tau_k, jac)
    return (2.0 - m11 - m22) / 4.0 if status == CONVERGED else math.nan


def _position_error(phi, v, eps, period, code, monodromy, time, speeds, residue):
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
    return _residue_change(phi, v, eps, period, code, residue, moves)


def _residue_change(phi, v, eps, period, code, residue, moves):
    """The largest |R(x +- dx) - R(x)| over the displacements dx (inf if one fails)."""
    worst = 0.0
    for dx in moves:
        for sign in (1.0, -1.0):
            moved = _residue_at(phi + sign * dx[0], v + sign * dx[1], eps, period, code)
            worst = max(worst, abs(moved - residue))
    return worst if math.isfinite(worst) else math.inf


def periodic_orbit(phi, v, eps, period, *, winding=None, velocity_shift=0, model="exact",
                   max_iterations=MAX_ITERATIONS):
    """Find a periodic orbit of the collision map near (phi, v) by Newton's method on F^p - id.

    phi, v, eps: the guess and the amplitude (finite reals; the guess must depart,
    v + eps*sin(phi) > 0). period p >= 1. winding m: the orbit's total time is 2*pi*m; by
    default the nearest integer to the guess's own p flights / (2*pi). velocity_shift l: v_p =
    v + pi*l (l != 0: an accelerator block, v grows by pi*l every p collisions). model: "exact"
    or "holmes" (the Holmes map in its standard-map form). Returns a :class:`PeriodicOrbit`;
    raises ValueError for bad input, :class:`OrbitNotFound` when Newton does not converge, and
    ``fastpath.UncertainCollision`` for a flight float64 cannot decide.
    """
    phi, v, eps = real("phi", phi), real("v", v), real("eps", eps)
    period = integer("period", period, minimum=1)
    shift = integer("velocity_shift", velocity_shift)
    code = model_code(model)
    max_iterations = integer("max_iterations", max_iterations, minimum=1)
    departing(phi, v, eps, "the guess")
    if winding is None:
        phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
        jac = np.empty((period, 4))
        time, *_, status, _ = orbit_monodromy(phi, v, eps, period, code, phi_k, v_k, tau_k, jac)
        if status != CONVERGED:
            _raise_for_status(status, phi, v, eps, "the guess's orbit")
        winding = round(time / (2.0 * math.pi))
    winding = integer("winding", winding, minimum=1)
    phi1, v1, g1, g2, step, its, status = newton_block(phi, v, eps, period, winding, shift, code,
                                                      max_iterations)
    if status == NOT_CONVERGED:
        raise OrbitNotFound(
            f"Newton's method from phi={phi!r}, v={v!r} (eps={eps!r}, period {period}, winding "
            f"{winding}, velocity shift {shift}) did not converge in {its} iterations: last "
            f"residual {max(abs(g1), abs(g2)):.3g}, last step {step:.3g}; try a closer guess")
    if status != CONVERGED:
        _raise_for_status(status, phi1, v1, eps, "Newton's method")
    return build_orbit(phi1, v1, eps, period, winding, shift, model, its)
