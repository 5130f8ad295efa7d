"""The rotation angle at the elliptic fixed point (0, pi): cos(theta) = 1 - 2 eps.
"""

from __future__ import annotations

import math

import numpy as np

import fastpath
from fastpath.arithmetic.phase import TWO_PI
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from reports.paper.checks.physics_table import Check, agree

ROTATION_EPS = (0.1, 0.3, 0.45, 0.6, 0.85, 0.95)


ROTATION_OFFSET = 1e-5


ROTATION_COLLISIONS = 2000


def rotation_angle(eps, offset=ROTATION_OFFSET, collisions=ROTATION_COLLISIONS):
    """(cos theta, det M) from the orbit started at (0, pi + offset); see the docstring."""
    orb = fastpath.orbit(0.0, math.pi + offset, eps, collisions)
    dphi = (orb.phi + math.pi) % TWO_PI - math.pi
    x = np.vstack([dphi, orb.v - math.pi])
    a, b = x[:, :-1], x[:, 1:]
    m = b @ a.T @ np.linalg.inv(a @ a.T)
    return float(np.trace(m) / 2), float(np.linalg.det(m))


def rotation_checks():
    rows = []
    for eps in ROTATION_EPS:
        c1, det = rotation_angle(eps)
        c2, _ = rotation_angle(eps, 2 * ROTATION_OFFSET)
        err = abs(c1 - c2) + UNIT_ROUNDOFF / ROTATION_OFFSET
        expected = 1 - 2 * eps
        theta = math.degrees(math.acos(max(-1.0, min(1.0, c1))))
        rows.append(Check(f"cos(theta) at (0, pi), eps = {eps:g}", c1, err, expected,
                          f"fit x_(k+1) = M x_k to {ROTATION_COLLISIONS} collisions started "
                          f"{ROTATION_OFFSET:g} above the fixed point; cos = tr(M)/2, theta = "
                          f"{theta:.4f} deg, det M - 1 = {det - 1:.1e}; +- = change at "
                          f"offset {2 * ROTATION_OFFSET:g}",
                          agree(c1, err, expected), digits=10))
    return rows
