"""Four plausible but defective flight-time solvers, for ``bouncer check`` to catch.

Each is a ``flight_time(phi, v, eps) -> float`` as a user might write it. ``DEFECTS`` maps each
name to the property of ``verify.check_integrator`` that must catch it:

1. ``holmes_flight_time``: the Holmes approximation ``tau = 2*v`` used as if exact
   (exact only at the fixed points ``(0, pi*m)``).                               -> accuracy
2. ``scanner_flight_time``: steps in fixed increments ``h = 0.05`` until the gap changes sign,
   then bisects. Accurate at every root it finds, but two roots closer than ``h`` (a near-graze,
   eps > 1) leave no sign change on the grid: it skips that collision.        -> no_overstep
3. ``naive_gap_flight_time``: the paper's lower-bound steps on the textbook gap
   ``eps*(cos(phi) - cos(phi+tau)) + tau*(v - tau/2)``; the cosine difference cancels for short
   flights, so at small departure speed (w0 ~ 1e-10) tau is wrong in most digits.  -> accuracy
4. ``biased_flight_time``: ``fastpath.flight_time`` times ``1 + 1e-9``.            -> accuracy

Try them::

    bouncer check examples.planted_defects:naive_gap_flight_time
    bouncer check examples/planted_defects.py:scanner_flight_time --suite no_overstep

Below them, solvers that hang, exit or segfault on some inputs, and one that is right but slow
(0.05 s a call): the check runs every callable in a worker process under a call timeout and an
overall budget, so these become findings (or, for the slow one, a pass) instead of a stuck or
killed checker::

    bouncer check examples.planted_defects:hanging_flight_time
"""

import ctypes
import math
import os
import time

import numba

import fastpath

SCAN_STEP = 0.05
BIAS = 1e-9


def holmes_flight_time(phi, v, eps):
    """Defect 1: the Holmes flight time 2*v (the high-velocity approximation) as if exact."""
    return 2.0 * v


@numba.njit(cache=False)
def _gap(phi, v, eps, t):
    """The gap in product form (no cancellation): the scanner's defect is only its grid."""
    return 2.0 * eps * math.sin(phi + 0.5 * t) * math.sin(0.5 * t) + t * (v - 0.5 * t)


@numba.njit(cache=False)
def _scan(phi, v, eps, h):
    w0 = v + eps * math.sin(phi)
    if not w0 > 0.0:
        return math.nan
    lo = 2.0 * w0 / (1.0 + abs(eps))  # rigorous: the gap is positive on (0, lo]
    hi = lo + h
    while _gap(phi, v, eps, hi) > 0.0:
        lo = hi
        hi = lo + h
    while True:  # bisection down to adjacent floats: gap(lo) > 0 >= gap(hi)
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return hi
        if _gap(phi, v, eps, mid) > 0.0:
            lo = mid
        else:
            hi = mid


def scanner_flight_time(phi, v, eps):
    """Defect 2: a fixed-step scan (h = 0.05) for the first sign change, then bisection."""
    return float(_scan(float(phi), float(v), float(eps), SCAN_STEP))


@numba.njit(cache=False)
def _naive(phi, v, eps):
    w0 = v + eps * math.sin(phi)
    if not w0 > 0.0:
        return math.nan
    a = 1.0 + abs(eps)
    t = 2.0 * w0 / a
    for _ in range(1_000_000):
        d = eps * (math.cos(phi) - math.cos(phi + t)) + t * (v - 0.5 * t)  # cancels for small t
        if d <= 0.0:
            return t
        r = v - t + eps * math.sin(phi + t)
        root = math.sqrt(r * r + 2.0 * a * d)
        s = (r + root) / a if r >= 0.0 else 2.0 * d / (root - r)
        if t + s == t:
            return t
        t += s
    return t


def naive_gap_flight_time(phi, v, eps):
    """Defect 3: the paper's lower-bound steps on the cancelling gap eps*(cos(phi) - cos(phi+t))."""
    return float(_naive(float(phi), float(v), float(eps)))


def biased_flight_time(phi, v, eps):
    """Defect 4: fastpath's flight time with a relative bias of 1e-9."""
    return fastpath.flight_time(phi, v, eps) * (1.0 + BIAS)


DEFECTS = {
    "holmes_flight_time": (holmes_flight_time, "accuracy"),
    "scanner_flight_time": (scanner_flight_time, "no_overstep"),
    "naive_gap_flight_time": (naive_gap_flight_time, "accuracy"),
    "biased_flight_time": (biased_flight_time, "accuracy"),
}


# --------------------------------------------------------------------------- faults
# Solvers that do not return a wrong number but misbehave: ``bouncer check`` runs them in a
# worker process, so each becomes a finding that names the input. All are right elsewhere.

SLOW_SECONDS = 0.05  # per call of slow_flight_time
HANG_BELOW_W0 = 1e-3  # hanging_flight_time never returns for departure speeds below this


def _w0(phi, v, eps):
    return float(v) + float(eps) * math.sin(float(phi))


def hanging_flight_time(phi, v, eps):
    """Fault 1: an iteration that never ends for slow departures (w0 < 1e-3)."""
    if _w0(phi, v, eps) < HANG_BELOW_W0:
        while True:
            time.sleep(60.0)
    return fastpath.flight_time(phi, v, eps)


def exiting_flight_time(phi, v, eps):
    """Fault 2: a library that calls exit() on slow departures (w0 < 1e-3)."""
    if _w0(phi, v, eps) < HANG_BELOW_W0:
        os._exit(3)
    return fastpath.flight_time(phi, v, eps)


def segfault_flight_time(phi, v, eps):
    """Fault 3: a native extension that dereferences NULL for large v (v > 1e3)."""
    if float(v) > 1e3:
        ctypes.string_at(0)  # reads address 0: SIGSEGV
    return fastpath.flight_time(phi, v, eps)


def slow_flight_time(phi, v, eps):
    """Not a fault: fastpath's flight time, 0.05 s per call (a correct but slow solver)."""
    time.sleep(SLOW_SECONDS)
    return fastpath.flight_time(phi, v, eps)
