"""Holding one fast flight to the ``verify`` reference (shared by the suites).

``flight_outcome(phi, v, eps)`` runs ``fastpath.flight`` and judges it:

* CONVERGED: ``verify.certify_flight`` proves the gap positive on ``(0, free_until]`` and a sign
  change in ``enclosure`` (so ``tau_ref`` is the FIRST root); the fast tau must agree with it
  within ``K*kappa*u`` (``fastpath_tolerances``): since it cannot then be beyond the certified
  first root by more than rounding, it did not jump to a later root. As an independent check the
  exact gap (mpmath, 50 digits) must be positive on a grid of ``(0, tau_fast*(1 - K*kappa*u))``.
* UNCERTAIN / MAX_ITERATIONS: allowed only when the nearest dip of the exact gap has its minimum
  within a few gap_error of zero (``uncertain_justification``).
* anything else (NOT_DEPARTING for a valid departure, a CONVERGED answer verify cannot decide):
  a failure.
"""

import functools
from dataclasses import dataclass

from fastpath_tolerances import (
    DPS,
    K,
    U,
    exact_gap,
    exact_w0,
    kappa,
    tau_error_units,
    uncertain_justification,
)
from mpmath import mp

import fastpath

GRID_POINTS = 32


@dataclass(frozen=True)
class Outcome:
    phi: float
    v: float
    eps: float
    status: str  # FlightStatus name
    tau_fast: float
    iterations: int
    tau_ref: object = None  # mpf, when verify decided
    units: float | None = None  # |tau_fast - tau_ref| / (kappa*u*tau_ref)
    problem: str | None = None  # why the outcome is wrong (None: fine)

    def describe(self):
        return (
            f"phi={self.phi!r}, v={self.v!r}, eps={self.eps!r}: fast {self.status} "
            f"tau={self.tau_fast!r} ({self.iterations} iterations), verify tau={self.tau_ref}, "
            f"error {self.units} kappa*u"
        )


@functools.lru_cache(maxsize=4096)
def certificate(phi, v, eps):
    """verify.certify_flight at 50 digits (cached: hard cases are judged twice)."""
    import verify

    return verify.certify_flight(phi, v, eps, dps=DPS)


def _grid_is_free(phi, v, eps, tau_fast, tau_ref):
    """Exact gap > 0 at GRID_POINTS points of (0, tau_fast*(1 - K*kappa*u))."""
    with mp.workdps(DPS):
        end = mp.mpf(tau_fast) * (1 - K * kappa(phi, v, eps, tau_ref) * U)
        if end <= 0:
            return None
        for j in range(1, GRID_POINTS + 1):
            t = end * j / GRID_POINTS
            if not exact_gap(phi, v, eps, t) > 0:
                return f"exact gap {mp.nstr(exact_gap(phi, v, eps, t), 5)} <= 0 at t={t}"
    return None


@functools.lru_cache(maxsize=4096)
def flight_outcome(phi, v, eps):
    """Run the fast solver on float inputs and judge it against verify (module docstring)."""
    import verify

    phi, v, eps = float(phi), float(v), float(eps)
    res = fastpath.flight(phi, v, eps)
    status = fastpath.FlightStatus(res.status)
    base = {
        "phi": phi,
        "v": v,
        "eps": eps,
        "status": status.name,
        "tau_fast": res.tau,
        "iterations": res.iterations,
    }
    if not exact_w0(phi, v, eps) > 0:
        return Outcome(**base, problem="test bug: not a departure")
    if status in (fastpath.FlightStatus.UNCERTAIN, fastpath.FlightStatus.MAX_ITERATIONS):
        just = uncertain_justification(phi, v, eps, res.tau)
        if just is None:
            return Outcome(
                **base,
                problem="UNCERTAIN where no dip of the exact gap is within a few gap_error of zero",
            )
        return Outcome(**base)
    if status != fastpath.FlightStatus.CONVERGED:
        return Outcome(**base, problem=f"status {status.name} for a valid departure")
    try:
        cert = certificate(phi, v, eps)
    except verify.UndecidableCollision as err:
        return Outcome(**base, problem=f"CONVERGED but verify cannot decide: {err}")
    lo, hi = cert.enclosure
    if not (lo <= cert.tau <= hi and cert.free_until >= lo):
        return Outcome(**base, tau_ref=cert.tau, problem=f"verify certificate inconsistent: {cert}")
    units = tau_error_units(res.tau, cert.tau, phi, v, eps)
    out = {**base, "tau_ref": cert.tau, "units": units}
    if not units <= K:
        return Outcome(**out, problem=f"flight time off by {units:.3g} > K={K} kappa*u")
    grid = _grid_is_free(phi, v, eps, res.tau, cert.tau)
    if grid is not None:
        return Outcome(**out, problem=grid)
    return Outcome(**out)


def assert_flight_ok(phi, v, eps):
    """Assert the fast flight is right (see module docstring); return its Outcome."""
    out = flight_outcome(float(phi), float(v), float(eps))
    assert out.problem is None, f"{out.problem}: {out.describe()}"
    return out
