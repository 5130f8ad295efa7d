"""One method on one case, judged against ``verify``: the error of tau in units of kappa*u, and
whether the method stepped past the first collision.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import mpmath
import numpy as np
from mpmath import mp

import verify
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from reports.precision.methods import Method, Outcome

REFERENCE_DPS = 60


@dataclass(frozen=True)
class Case:
    """A departure (float64 phi, v, eps) with a label; ``contact`` is the graze time T of a
    near-grazing departure (the bottom of the dip between its two close roots), else None."""

    phi: float
    v: float
    eps: float
    label: str
    group: str  # "random", "hard" or "grazing"
    contact: float | None = None
    clearance: float | None = None


@dataclass(frozen=True)
class Reference:
    """verify at REFERENCE_DPS: tau with its enclosure, (phi1, v1) and kappa."""

    tau: mpmath.mpf
    upper: mpmath.mpf
    phi1: mpmath.mpf
    v1: mpmath.mpf
    kappa: mpmath.mpf


@dataclass(frozen=True)
class Error:
    """One method on one case. NaN errors where the method failed."""

    tau_rel: float
    tau_units: float  # tau_rel / (kappa*u)
    phi1_abs: float
    v1_rel: float
    iterations: int | None
    status: str  # "ok", "uncertain", "missed" or "error: ..."


COSTS: dict[str, float] = {}  # wall seconds spent per method (evaluation and timing), diagnostics
_REFERENCES: dict[tuple[float, float, float], Reference | None] = {}


def reference(case: Case) -> Reference | None:
    """verify.step at REFERENCE_DPS with its enclosure and kappa (cached); None if undecidable."""
    key = (case.phi, case.v, case.eps)
    if key not in _REFERENCES:
        try:
            cert = verify.certify_flight(case.phi, case.v, case.eps, dps=REFERENCE_DPS)
            phi1, v1, tau = verify.step(case.phi, case.v, case.eps, dps=REFERENCE_DPS)
            with mp.workdps(REFERENCE_DPS):
                kappa = verify.condition_number(case.phi, case.v, case.eps, tau)
            _REFERENCES[key] = Reference(tau, cert.enclosure[1], phi1, v1, kappa)
        except verify.UndecidableCollision:
            _REFERENCES[key] = None
    return _REFERENCES[key]


def _reduced_phase(phi: float) -> mpmath.mpf:
    """phi mod 2*pi to 40 digits, with the working precision raised by phi's decimal exponent
    (a phase of 1e300 needs 300 more digits of pi to be reduced right)."""
    extra = max(0, math.frexp(phi)[1]) * 30 // 100 + 1
    with mp.workdps(40 + extra):
        r = mp.mpf(phi) % (2 * mp.pi)
    with mp.workdps(40):
        return +r


def _gap_rate(case: Case, t) -> mpmath.mpf:
    phi = _reduced_phase(case.phi)
    with mp.workdps(40):
        t = mp.mpf(t)
        return mp.mpf(case.v) - t + mp.mpf(case.eps) * mp.sin(phi + t)


def overstepped(case: Case, ref: Reference, tau) -> bool:
    """True if ``tau`` lies past a later root: past the first root, with the gap rising at tau or
    positive somewhere between the first root and tau (a fine float64 grid, step <= 0.005)."""
    if not tau > ref.upper:
        return False
    if _gap_rate(case, tau) > 0:
        return True
    lo, hi = float(ref.upper), float(tau)
    phi = float(_reduced_phase(case.phi))
    n = int(min(200_000, max(64, (hi - lo) / 0.005)))
    s = np.linspace(lo, hi, n)
    eps, v = case.eps, case.v
    d = 2.0 * eps * np.sin(phi + 0.5 * s) * np.sin(0.5 * s) + s * (v - 0.5 * s)
    err = 4.0 * UNIT_ROUNDOFF * (abs(eps) * np.minimum(s, 2.0) * (phi + s + 3.0) + s * (abs(v) + s))
    return bool(np.any(d > 8.0 * err))


def _mp(x):
    return mp.mpf(x) if not isinstance(x, mpmath.mpf) else x


def compare(method: Method, case: Case, ref: Reference, out: Outcome) -> Error:
    """Errors of one outcome against the reference (Holmes: against the exact map)."""
    bad = out.status.startswith("error") or out.status.startswith("uncertain")
    try:
        finite = mp.isfinite(_mp(out.tau))
    except (TypeError, ValueError):
        finite = False
    if bad or not finite:
        status = out.status if bad else "error: no flight time (NaN)"
        return Error(math.nan, math.nan, math.nan, math.nan, out.iterations, status)
    with mp.workdps(REFERENCE_DPS):
        tau = _mp(out.tau)
        rel = abs(tau - ref.tau) / ref.tau
        units = rel / (ref.kappa * UNIT_ROUNDOFF)
        dphi = (_mp(out.phi1) - ref.phi1 + mp.pi) % (2 * mp.pi) - mp.pi
        dv = abs(_mp(out.v1) - ref.v1) / max(1, abs(ref.v1))
    status = "ok"
    if method.model == "exact" and overstepped(case, ref, tau):
        status = "missed"
    return Error(float(rel), float(units), float(abs(dphi)), float(dv), out.iterations, status)


def evaluate(methods: list[Method], cases: list[Case]):
    """(references, {method name: [Error per case]}); cases without a reference get None."""
    start = time.perf_counter()
    refs = [reference(c) for c in cases]
    COSTS["reference"] = COSTS.get("reference", 0.0) + time.perf_counter() - start
    errors: dict[str, list[Error]] = {m.name: [] for m in methods}
    for case, ref in zip(cases, refs, strict=True):
        for m in methods:
            if ref is None:
                errors[m.name].append(Error(math.nan, math.nan, math.nan, math.nan, None,
                                            "no reference (undecidable)"))
                continue
            start = time.perf_counter()
            out = m.safe_solve(case.phi, case.v, case.eps)
            COSTS[m.name] = COSTS.get(m.name, 0.0) + time.perf_counter() - start
            errors[m.name].append(compare(m, case, ref, out))
    return refs, errors
