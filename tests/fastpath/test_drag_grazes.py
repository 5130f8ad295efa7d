"""Constructed near-grazes with drag: never a step past the first root.

At eps > 1, and at |eps| < 1 with strong drag: a particle near its terminal velocity no longer
feels gravity, so the plate's acceleration alone makes the gap convex (d'' = -1 - eta(V) +
eps*cos, with -1 - eta(V) -> 0): several roots even below eps = 1.

A dip of the gap (a local minimum d(t_m) > 0 before the landing, found by a float scan) is made
tangent at 60 digits by moving v (d(t_m) grows with v: dY/dv > 0), then v is moved off the
tangency by relative amounts from 1e-3 down to 0: below it the particle touches the plate in the
dip (the first root is there), above it the dip is a miss. Every outcome is judged by
``test_drag_reference.judge``: CONVERGED at the reference's first root, or UNCERTAIN at a dip
within a few rounding bounds of zero.
"""

import math

import drag_reference as ref
import numpy as np
import pytest
from fastpath_figures import record
from mpmath import mp
from test_drag_reference import judge

from fastpath.dissipative.drag import gap_state
from fastpath.physics import LAWS

OFFSETS = [1e-3, 1e-7, 1e-11, 1e-14, 0.0, -1e-14, -1e-11, -1e-7, -1e-3]


def scan_for_dip(eps, k, law, seed):
    """(phi, v, t_m): a departure whose gap has a positive local minimum before its landing."""
    rng = np.random.default_rng(seed)
    for _ in range(2000):
        phi = rng.uniform(-math.pi, math.pi)
        v = rng.uniform(0.05, 3.0)
        if v + eps * math.sin(phi) < 0.05:
            continue
        ts = np.linspace(1e-3, 12.0, 1200)
        d = np.array([gap_state(phi, v, eps, k, law, t)[0] for t in ts])
        neg = np.flatnonzero(d <= 0)
        end = neg[0] if len(neg) else len(d) - 1
        for j in range(1, end - 1):
            if d[j] < d[j - 1] and d[j] <= d[j + 1] and d[j] < 0.05:
                return phi, v, ts[j]
    raise AssertionError("no dip found")


def tangent_velocity(phi, v, k, law, eps, t_m):
    """v* (mpf) at which the dip's minimum is exactly 0 (Newton in v at 60 digits)."""
    with mp.workdps(ref.DPS):
        v = mp.mpf(v)
        t = t_m
        for _ in range(60):
            s, m = ref.local_minimum(phi, v, eps, k, law, t)
            h = mp.mpf(10) ** -30
            s2, m2 = ref.local_minimum(phi, v + h, eps, k, law, s)
            step = m / ((m2 - m) / h)
            v, t = v - step, s
            if abs(step) < mp.mpf(10) ** -50:
                return v, s
        raise AssertionError("tangency did not converge")


@pytest.mark.parametrize("law", sorted(LAWS))
@pytest.mark.parametrize(
    "eps, k, seed", [(1.5, 0.05, 1), pytest.param(2.5, 0.3, 2, marks=pytest.mark.slow),
                     pytest.param(1.2, 1e-6, 3, marks=pytest.mark.slow), (0.9, 1.5, 4),
                     (0.95, 3.0, 5)]
)
def test_near_grazes_never_overstep(law, eps, k, seed):
    code = LAWS[law]
    phi, v, t_m = scan_for_dip(eps, k, code, seed)
    v_star, _ = tangent_velocity(phi, v, k, code, eps, t_m)
    outcomes = []
    for offset in OFFSETS:
        v_case = float(v_star * (1 + mp.mpf(offset)))
        status, units, _ = judge(phi, v_case, eps, k, law, "auto")
        outcomes.append(status if units is None else round(units, 2))
    record(f"drag graze {law} eps={eps} drag={k}: outcome per offset {OFFSETS}", outcomes)
