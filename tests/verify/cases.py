"""Shared states for the verify tests (not a test module)."""

from __future__ import annotations

import math
from contextlib import contextmanager

import mpmath
import numpy as np
from mpmath import mp

from verify.numerics.inputs import exact_real


def small_w0_velocity(phi: float, eps: float, w0: float) -> float:
    """A float ``v`` with ``v + eps*sin(phi)`` (exact) close to ``w0`` and positive."""
    v = -eps * math.sin(phi) + w0
    with mp.workdps(60):
        assert mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi)) > 0
    return v


def float_gap(phi: float, v: float, eps: float, t: np.ndarray) -> np.ndarray:
    """Independent float64 evaluation of ``d`` on a grid (product form)."""
    return 2 * eps * np.sin(phi + t / 2) * np.sin(t / 2) + t * (v - t / 2)


EPS_VALUES = [0.0, 1e-8, 0.2429, 0.6, 0.999999, 1.0, 1.000001, 3.0, 100.0, -0.6, -3.0]

# (phi, v, eps) covering phases 0, pi and next to them, large v, unreduced phase
STATES = [
    (phi, v, eps)
    for eps in EPS_VALUES
    for phi, v in [
        (0.0, 2.0),
        (math.pi, 2.5),
        (math.nextafter(0.0, 1.0), 1.0),
        (math.nextafter(math.pi, 4.0), 3.0),
        (1e6 + 0.3, 2.0),
        (0.3, 1e6),
        (4.0, 3.0),
    ]
    if v + eps * math.sin(phi) > 1e-9
]


@contextmanager
def mpmath_dps(dps: int):
    """Set mpmath's own ``mp`` and ``iv`` to ``dps`` digits for a test's independent
    computations (verify never touches them: it works in its own per-thread contexts)."""
    old_mp, old_iv = mpmath.mp.prec, mpmath.iv.prec
    mpmath.mp.dps = mpmath.iv.dps = dps
    try:
        yield mpmath.mp.prec
    finally:
        mpmath.mp.prec, mpmath.iv.prec = old_mp, old_iv


def internal(*xs):
    """Exact values in verify's own (per-thread) context, for calling verify's internals (which
    compute in that context and expect its numbers)."""
    return tuple(exact_real("x", x) for x in xs)
