"""Registry of flight-time methods for the precision comparison (work-precision) reports.

Every method answers one question: the smallest positive root tau of the gap

    d(tau) = eps*(cos(phi) - cos(phi+tau)) + tau*(v - tau/2)

for a departure (phi, v) at plate amplitude eps. A :class:`Method` carries a scalar
``flight_time(phi, v, eps)``, a ``solve`` that also reports what the method knows (iterations,
status, the collision's (phi1, v1)), an optional vectorised ``batch`` used for timing, and a
``kind``: ``float64``, ``arbitrary precision`` or ``certified``. :func:`default_methods` lists the
built-in ones; :func:`method_from_callable` wraps a user's function (``--compare MODULE:FUNCTION``).

The methods are set up as a careful user would, not to lose:

- ``solve_ivp``: the physics ODE y'' = -1 integrated in flight time s from y(0) = eps*cos(phi),
  y'(0) = v (RK45, the given rtol, atol = rtol*max(1, |v|, |eps|), default max_step), with the
  terminal event gap(s) = y(s) - eps*cos(phi + s) crossing zero downwards. scipy looks for an
  event only where the gap changes sign between the ends of a step: a pair of close roots inside
  one step is stepped over, and RK45 takes long steps here because the solution is a parabola.
- ``brentq``: the gap in the cancellation-free form 2*eps*sin(phi + s/2)*sin(s/2) + s*(v - s/2),
  bracketed by the first sign change on the grid s_k = s_lo + k*h, h = BRACKET_GRID (0.1), from
  the analytic lower bound s_lo = 2*w0/(1+|eps|) to the time the particle is surely below the
  plate. A pair of roots closer than h is missed, as by any sampled bracket search.
- ``mpmath findroot``: the Anderson-Bjoerck (bracketing, safe) solver on the same bracket, with the
  gap evaluated at the method's dps and the (absolute) tolerance scaled by min(1, s_lo)**2 so that
  short flights keep their relative accuracy; it shares brentq's blind spot for close pairs.
- ``verify``: the certified interval path (the reference itself, at lower dps).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import mpmath
import numpy as np
from mpmath import mp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import fastpath
import verify
from fastpath.arithmetic.phase import TWO_PI

FLOAT64 = "float64"
ARBITRARY = "arbitrary precision"
CERTIFIED = "certified"

BRACKET_GRID = 0.1  # step of the sampled bracket search used by brentq and mpmath findroot
SOLVE_IVP_RTOLS = (1e-6, 1e-9, 1e-12)
FINDROOT_DPS = (20, 30)
FINDROOT_MAXSTEPS = 400  # mpmath's default (30) stops a wide bracket before it converges
VERIFY_DPS = (20, 50)


@dataclass(frozen=True)
class Outcome:
    """One flight as a method reports it.

    tau, phi1, v1: float or mpf (NaN when the method failed). iterations: the method's own count
    (solver iterations, function or box evaluations; None where it has none). status: "ok",
    "uncertain" (the method says it cannot decide) or "error: <message>".
    """

    tau: float | mpmath.mpf
    phi1: float | mpmath.mpf
    v1: float | mpmath.mpf
    iterations: int | None = None
    status: str = "ok"


@dataclass(frozen=True)
class Method:
    """A flight-time method.

    name: label in tables and figures. kind: FLOAT64, ARBITRARY or CERTIFIED. model: "exact" or
    "holmes" (the Holmes map's tau = 2v; its error is the model's). solve: detailed outcome.
    batch: vectorised tau for arrays (timing), None to time ``flight_time`` in a loop.
    timing_states: at most this many states are timed (slow methods), None for all.
    vectorised: ``batch`` is one compiled call (timed on the states tiled to a large batch).
    iterations_label: what ``Outcome.iterations`` counts.
    """

    name: str
    kind: str
    solve: Callable[[float, float, float], Outcome]
    batch: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray] | None = None
    model: str = "exact"
    timing_states: int | None = None
    vectorised: bool = False
    iterations_label: str = ""
    description: str = ""

    def flight_time(self, phi, v, eps):
        """tau for one departure (float or mpf); raises ValueError if the method failed."""
        out = self.solve(phi, v, eps)
        if out.status.startswith("error"):
            raise ValueError(f"{self.name}: {out.status}")
        return out.tau

    def safe_solve(self, phi, v, eps) -> Outcome:
        """``solve`` with any exception turned into an ``error`` outcome."""
        try:
            return self.solve(phi, v, eps)
        except Exception as err:  # noqa: BLE001 - failures are data in a comparison
            msg = f"{type(err).__name__}: {err}"
            return Outcome(math.nan, math.nan, math.nan, None, f"error: {msg[:160]}")


# ---------------------------------------------------------------------------------------------
# helpers shared by the float64 methods


def collision_from_tau(phi, v, eps, tau):
    """(phi1, v1) in float64 from a float tau: phi1 = (phi + tau) mod 2*pi, v1 = tau - v - 2*eps*
    sin(phi + tau). What a user of a generic root finder computes after it."""
    if not math.isfinite(tau):
        return math.nan, math.nan
    arg = phi + tau
    return math.fmod(arg, TWO_PI) % TWO_PI, tau - v - 2.0 * eps * math.sin(arg)


def upper_time(phi, v, eps):
    """A time by which the particle is surely below the plate's lowest point (a root exists)."""
    return v + math.sqrt(v * v + 2.0 * abs(eps) * (math.cos(phi) * math.copysign(1, eps) + 1.0))


def gap_array(phi, v, eps, s):
    """The gap at flight times s (numpy), cancellation-free half-angle form."""
    return 2.0 * eps * np.sin(phi + 0.5 * s) * np.sin(0.5 * s) + s * (v - 0.5 * s)


def scan_bracket(phi, v, eps, h=BRACKET_GRID):
    """(a, b, points) with gap(a) > 0 >= gap(b): the first sign change on the grid of step h
    starting at the analytic lower bound 2*w0/(1+|eps|). Raises ValueError if none is found."""
    w0 = v + eps * math.sin(phi)
    if not w0 > 0.0:
        raise ValueError(f"not a departure: w0 = {w0!r} <= 0")
    start = 2.0 * w0 / (1.0 + abs(eps))
    end = upper_time(phi, v, eps) + h
    a, points, chunk = start, 0, 64
    while a < end:
        s = a + h * np.arange(1, chunk + 1)
        d = gap_array(phi, v, eps, s)
        neg = np.flatnonzero(d <= 0.0)
        if len(neg):
            k = int(neg[0])
            lo = a if k == 0 else float(s[k - 1])
            return lo, float(s[k]), points + k + 1
        points += chunk
        a = float(s[-1])
        chunk = min(4 * chunk, 65536)
    raise ValueError("no sign change of the gap found on the scan grid")


# ---------------------------------------------------------------------------------------------
# fastpath and Holmes


def _fastpath_solve(method):
    def solve(phi, v, eps):
        res = fastpath.flight(phi, v, eps, method=method)
        code = fastpath.FlightStatus(int(res.status))
        tau = float(res.tau)
        if code == fastpath.FlightStatus.NOT_DEPARTING:
            return Outcome(math.nan, math.nan, math.nan, int(res.iterations),
                           "error: not a departure")
        if method == "auto" and code == fastpath.FlightStatus.CONVERGED:
            phi1, v1, _ = fastpath.step(phi, v, eps)
        else:
            phi1, v1 = collision_from_tau(phi, v, eps, tau)
        status = "ok" if code == fastpath.FlightStatus.CONVERGED else "uncertain"
        return Outcome(tau, phi1, v1, int(res.iterations), status)

    return solve


def _fastpath_batch(method):
    def batch(phi, v, eps):
        return fastpath.flight(phi, v, eps, method=method).tau

    return batch


def _holmes_solve(phi, v, eps):
    phi1, v1 = fastpath.holmes_step(phi, v, eps)
    return Outcome(2.0 * v, phi1, v1, None, "ok")


def _holmes_batch(phi, v, eps):
    return fastpath.holmes_step(phi, v, eps)[0]


# ---------------------------------------------------------------------------------------------
# scipy


def _solve_ivp_solver(rtol):
    def solve(phi, v, eps):
        atol = rtol * max(1.0, abs(v), abs(eps))

        def rhs(s, y):
            return [y[1], -1.0]

        def event(s, y):
            return y[0] - eps * math.cos(phi + s)

        event.terminal = True
        event.direction = -1
        t_end = upper_time(phi, v, eps) + 1.0
        sol = solve_ivp(rhs, (0.0, t_end), [eps * math.cos(phi), v], rtol=rtol, atol=atol,
                        events=event)
        if not sol.t_events[0].size:
            return Outcome(math.nan, math.nan, math.nan, int(sol.nfev),
                           f"error: no event found ({sol.message})")
        tau = float(sol.t_events[0][0])
        return Outcome(tau, *collision_from_tau(phi, v, eps, tau), int(sol.nfev), "ok")

    return solve


def _brentq_solve(phi, v, eps):
    lo, hi, points = scan_bracket(phi, v, eps)

    def f(s):
        return 2.0 * eps * math.sin(phi + 0.5 * s) * math.sin(0.5 * s) + s * (v - 0.5 * s)

    tau, info = brentq(f, lo, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, full_output=True,
                       disp=False)
    status = "ok" if info.converged else f"error: brentq {info.flag}"
    return Outcome(tau, *collision_from_tau(phi, v, eps, tau), points + info.function_calls,
                   status)


# ---------------------------------------------------------------------------------------------
# mpmath


def _findroot_solver(dps):
    def solve(phi, v, eps):
        lo, hi, points = scan_bracket(phi, v, eps)
        calls = [0]
        with mp.workdps(dps):
            mphi, mv, meps = mp.mpf(phi), mp.mpf(v), mp.mpf(eps)

            def f(s):
                calls[0] += 1
                return 2 * meps * mp.sin(mphi + s / 2) * mp.sin(s / 2) + s * (mv - s / 2)

            # findroot's tolerances are absolute: scale them to the flight so that short flights
            # get the method's relative accuracy
            tol = mp.eps * min(1, mp.mpf(lo)) ** 2
            tau = mp.findroot(f, (mp.mpf(lo), mp.mpf(hi)), solver="anderson", tol=tol,
                              maxsteps=FINDROOT_MAXSTEPS, verify=False)
            arg = mphi + tau
            two_pi = 2 * mp.pi
            phi1 = arg - two_pi * mp.floor(arg / two_pi)
            v1 = tau - mv - 2 * meps * mp.sin(arg)
        return Outcome(tau, phi1, v1, points + calls[0], "ok")

    return solve


def _verify_solver(dps):
    def solve(phi, v, eps):
        try:
            cert = verify.certify_flight(phi, v, eps, dps=dps)
        except verify.UndecidableCollision as err:
            return Outcome(math.nan, math.nan, math.nan, None, f"uncertain ({err.what[:80]})")
        phi1, v1, tau = verify.step(phi, v, eps, dps=dps)
        return Outcome(tau, phi1, v1, int(cert.boxes), "ok")

    return solve


def _loop_batch(solve):
    def batch(phi, v, eps):
        return np.array([float(solve(p, w, e).tau) for p, w, e in zip(phi, v, eps, strict=True)])

    return batch


# ---------------------------------------------------------------------------------------------
# registry


def default_methods() -> list[Method]:
    """The built-in methods, fastest first within each kind."""
    methods = [
        Method("fastpath auto", FLOAT64, _fastpath_solve("auto"), _fastpath_batch("auto"),
               vectorised=True,
               iterations_label="gap evaluations (Halley) or lower-bound steps",
               description="fastpath.flight(method='auto'): bracketed Halley for |eps| < 1, "
               "the paper's lower-bound steps otherwise"),
        Method("fastpath lower_bound", FLOAT64, _fastpath_solve("lower_bound"),
               _fastpath_batch("lower_bound"), vectorised=True,
               iterations_label="lower-bound steps",
               description="fastpath.flight(method='lower_bound'): the paper's lower-bound "
               "steps for every flight"),
        Method("Holmes map", FLOAT64, _holmes_solve, _holmes_batch, model="holmes", vectorised=True,
               description="tau = 2v, phi1 = phi + 2v, v1 = |v - 2 eps sin(phi1)| "
               "(error = modelling error against the exact map)"),
    ]
    for rtol in SOLVE_IVP_RTOLS:
        solve = _solve_ivp_solver(rtol)
        methods.append(Method(f"solve_ivp rtol={rtol:.0e}", FLOAT64, solve, _loop_batch(solve),
                              iterations_label="RHS evaluations",
                              description="scipy RK45 with a terminal event on the gap"))
    methods.append(Method("brentq grid 0.1", FLOAT64, _brentq_solve, _loop_batch(_brentq_solve),
                          iterations_label="scan points + brentq calls",
                          description=f"scipy brentq on a bracket from a grid of step "
                          f"{BRACKET_GRID}"))
    for dps in FINDROOT_DPS:
        solve = _findroot_solver(dps)
        methods.append(Method(f"mpmath findroot dps={dps}", ARBITRARY, solve, _loop_batch(solve),
                              iterations_label="scan points + gap evaluations",
                              description="mpmath.findroot(solver='anderson') on the grid "
                              "bracket"))
    for dps in VERIFY_DPS:
        solve = _verify_solver(dps)
        methods.append(Method(f"verify dps={dps}", CERTIFIED, solve, _loop_batch(solve),
                              iterations_label="interval boxes",
                              description="verify.certify_flight + verify.step"))
    return methods


def method_from_callable(name: str, fn: Callable, kind: str = FLOAT64,
                         batch: Callable | None = None) -> Method:
    """Wrap a user's ``fn(phi, v, eps) -> tau`` (float or mpf) as a Method.

    (phi1, v1) follow from tau in float64 (or in mpmath for an mpf tau). ``batch``, if given,
    takes arrays and returns an array of tau and is used for timing.
    """

    def solve(phi, v, eps):
        tau = fn(phi, v, eps)
        if isinstance(tau, mpmath.mpf):
            arg = mp.mpf(phi) + tau
            two_pi = 2 * mp.pi
            return Outcome(tau, arg - two_pi * mp.floor(arg / two_pi),
                           tau - mp.mpf(v) - 2 * mp.mpf(eps) * mp.sin(arg))
        tau = float(tau)
        return Outcome(tau, *collision_from_tau(phi, v, eps, tau))

    return Method(name, kind, solve, batch or _loop_batch(solve),
                  vectorised=batch is not None,
                  description=f"user method {getattr(fn, '__module__', '?')}:"
                  f"{getattr(fn, '__qualname__', repr(fn))}")
