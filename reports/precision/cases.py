"""The test cases of the precision comparison: random departures, close root pairs (grazing
pairs) and the shared hard-case table of ``verify.hard_cases``.
"""

from __future__ import annotations

import math

import numpy as np

import verify
from fastpath.arithmetic.phase import TWO_PI
from reports.precision.evaluate import Case, reference
from verify.hard_cases import HARD_CASES

SEED = 20240604




def random_states(n: int, seed: int = SEED) -> list[Case]:
    """n seeded departures: a quarter from the paper's box (eps = 0.6, 3.85 < phi < 4.15,
    2 < v < 4); the rest with eps uniform in (0, 10] or log-uniform in [1e-3, 10] (half each),
    phi uniform, v log-uniform in [0.1, 1e4], resampled until w0 = v + eps*sin(phi) > 0."""
    rng = np.random.default_rng(seed)
    cases = []
    n_box = n // 4
    for _ in range(n_box):
        cases.append(Case(float(rng.uniform(3.85, 4.15)), float(rng.uniform(2.0, 4.0)), 0.6,
                          "paper box", "random"))
    for i in range(n - n_box):
        eps = float(10.0 - rng.uniform(0.0, 10.0)) if i % 2 else float(10 ** rng.uniform(-3, 1))
        phi = float(rng.uniform(0.0, TWO_PI))
        while True:
            v = float(10 ** rng.uniform(-1, 4))
            if v + eps * math.sin(phi) > 0.0:
                break
        cases.append(Case(phi, v, eps, "random", "random"))
    order = rng.permutation(len(cases))
    return [cases[i] for i in order]


def grazing_case(eps, psi, t_guess, clearance, label="grazing pair") -> Case | None:
    """A near-grazing departure (float64) from ``verify.grazing_contact``, or None."""
    try:
        g = verify.grazing_contact(eps, psi, t_guess, clearance)
    except ValueError:
        return None
    phi, v = float(g.phi), float(g.v)
    if not v + eps * math.sin(phi) > 0.0:
        return None
    return Case(phi, v, float(eps), label, "grazing", float(g.T), float(clearance))


def grazing_cases(n: int, seed: int = SEED + 1) -> list[Case]:
    """n departures of eps > 1 whose first two roots form a close pair: clearance -1e-2..-1e-8
    (log-uniform) at a contact time T, with no earlier collision (checked with ``verify``)."""
    rng = np.random.default_rng(seed)
    cases: list[Case] = []
    tries = 0
    while len(cases) < n and tries < 40 * n:
        tries += 1
        eps = float(rng.choice([1.5, 3.0, 10.0]))
        half = 0.8 * math.acos(1.0 / eps)
        psi, t_guess = float(rng.uniform(-half, half)), float(rng.uniform(2.0, 12.0))
        clearance = -float(10 ** rng.uniform(-8, -2))
        case = grazing_case(eps, psi, t_guess, clearance)
        if case is None:
            continue
        ref = reference(case)
        if ref is None:
            continue
        curvature = eps * math.cos(psi) - 1.0
        separation = 2.0 * math.sqrt(2.0 * -clearance / curvature)
        if not case.contact - 1.5 * separation < float(ref.tau) < case.contact:
            continue  # an earlier collision: not a close-pair test
        cases.append(case)
    return cases


QUICK_STRIDE = 6  # every 6th case in quick mode


def hard_cases(quick: bool = False) -> list[Case]:
    """The shared hard-case table as report cases (every QUICK_STRIDE-th with ``quick``)."""
    table = HARD_CASES[::QUICK_STRIDE] if quick else HARD_CASES
    return [Case(c.phi, c.v, c.eps, c.id, "hard", c.contact, c.clearance) for c in table]
