"""Flights with drag against the 60-digit reference of ``drag_reference``.

For both laws and eps below and above 1: a CONVERGED flight time is within the tolerance derived
from the solver's own gap error bound (``drag_reference.tau_tolerance``) of the reference's FIRST
root (the gap sampled and its dips refined: no overstep), and the bound E itself is held to the
exact rounding error of the gap. UNCERTAIN only where the gap has a dip within a few E of zero.
The worst error in units of kappa*u and the iterations are recorded as figures.
"""

import math

import drag_reference as ref
import numpy as np
import pytest
from fastpath_figures import record
from mpmath import mp

import fastpath
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state
from fastpath.physics import LAWS

REGIMES = {"eps<1": (0.0, 0.95), "eps>1": (1.05, 3.0)}
CASES = 40


def random_flights(law, regime, seed):
    """CASES departures: phi in [-pi, pi), v in [0.02, 30] (log-uniform), drag 1e-8..3."""
    rng = np.random.default_rng(seed)
    low, high = REGIMES[regime]
    out = []
    while len(out) < CASES:
        phi = rng.uniform(-math.pi, math.pi)
        v = 10 ** rng.uniform(math.log10(0.02), math.log10(30.0))
        eps = rng.uniform(low, high) * rng.choice([-1.0, 1.0])
        k = 10 ** rng.uniform(-8, 0.5)
        if v + eps * math.sin(phi) > 1e-3:
            out.append((phi, v, eps, k))
    return out


def judge(phi, v, eps, k, law, method):
    """(status, units, iterations) of one fast flight held to the reference; asserts inside."""
    res = fastpath.flight(phi, v, eps, method=method, drag=k, drag_law=law)
    code = LAWS[law]
    if res.status == fastpath.FlightStatus.CONVERGED:
        tau = res.tau
        d_error = gap_state(centre_phase(phi), v, eps, k, code, tau)[3]
        root, lowest = ref.first_root(phi, v, eps, k, code, tau * (1 + 1e-9) + 1e-12)
        assert root is not None, f"no root up to tau={tau!r} at {(phi, v, eps, k, law)}"
        tol = ref.tau_tolerance(d_error, phi, v, eps, k, code, root)
        err = abs(mp.mpf(tau) - root)
        assert err <= tol, (
            f"tau={tau!r} vs first root {mp.nstr(root, 20)} (error {mp.nstr(err, 3)} > tol"
            f" {tol:.3g}) at phi={phi!r}, v={v!r}, eps={eps!r}, drag={k!r}, {law}"
        )
        units = float(err / (ref.kappa(phi, v, eps, k, code, root) * ref.U * root))
        return "converged", units, res.iterations
    assert res.status in (fastpath.FlightStatus.UNCERTAIN, fastpath.FlightStatus.MAX_ITERATIONS)
    # legitimate only at a dip of the exact gap within a few rounding bounds of zero
    tau = res.tau
    found = ref.local_minimum(phi, v, eps, k, code, tau)
    assert found is not None, f"{res} without a dip at {(phi, v, eps, k, law)}"
    d_error = gap_state(centre_phase(phi), v, eps, k, code, float(found[0]))[3]
    assert abs(found[1]) <= 16 * d_error, f"{res}: dip minimum {found[1]} far from 0"
    return "uncertain", None, res.iterations


@pytest.mark.slow
@pytest.mark.parametrize("method", ["auto", "lower_bound"])
@pytest.mark.parametrize("regime", sorted(REGIMES))
@pytest.mark.parametrize("law", sorted(LAWS))
def test_drag_flights_match_the_reference(law, regime, method):
    seed = 16 + 7 * sorted(LAWS).index(law) + sorted(REGIMES).index(regime)
    worst, iterations, uncertain = 0.0, [], 0
    for phi, v, eps, k in random_flights(law, regime, seed):
        status, units, its = judge(phi, v, eps, k, law, method)
        iterations.append(its)
        if status == "converged":
            worst = max(worst, units)
        else:
            uncertain += 1
    record(
        f"drag {law} {regime} {method}: worst kappa*u, mean/max iterations, uncertain",
        (round(worst, 2), round(float(np.mean(iterations)), 2), max(iterations), uncertain),
    )
    assert uncertain <= CASES // 10  # random flights: a near-graze is rare


@pytest.mark.parametrize("law", sorted(LAWS))
def test_gap_error_bound_holds(law):
    """|computed d - exact d| <= d_error and the same for d' on random flight points."""
    rng = np.random.default_rng(3 + sorted(LAWS).index(law))
    worst = 0.0
    for _ in range(300):
        phi = rng.uniform(-math.pi, math.pi)
        v = rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-2, 2)
        eps = rng.uniform(-3, 3)
        k = 10 ** rng.uniform(-10, 1)
        t = 10 ** rng.uniform(-6, 2)
        d, d1, _, d_err, d1_err, _, _ = gap_state(phi, v, eps, k, LAWS[law], t)
        with mp.workdps(ref.DPS):
            e0 = abs(mp.mpf(d) - ref.gap(phi, v, eps, k, LAWS[law], t))
            e1 = abs(mp.mpf(d1) - ref.rate(phi, v, eps, k, LAWS[law], t))
        assert e0 <= d_err, f"gap error {e0} > bound {d_err} at {(phi, v, eps, k, t)}"
        assert e1 <= d1_err, f"rate error {e1} > bound {d1_err} at {(phi, v, eps, k, t)}"
        worst = max(worst, float(e0 / d_err), float(e1 / d1_err))
    record(f"drag {law}: worst actual/bound of the gap's rounding", round(worst, 3))


def test_methods_agree_and_auto_is_not_slower_on_concave_flights():
    """Where Halley runs (|eps| < 1, moderate drag) it lands on the lower-bound steps' root
    within both tolerances, in no more evaluations on average."""
    for law in sorted(LAWS):
        auto_its, lower_its = [], []
        for phi, v, eps, k in random_flights(law, "eps<1", 99):
            k = min(k, 0.05)
            a = fastpath.flight(phi, v, eps, drag=k, drag_law=law)
            s = fastpath.flight(phi, v, eps, method="lower_bound", drag=k, drag_law=law)
            assert a.status == s.status == 0
            d_error = gap_state(centre_phase(phi), v, eps, k, LAWS[law], a.tau)[3]
            tol = ref.tau_tolerance(d_error, phi, v, eps, k, LAWS[law], a.tau)
            assert abs(a.tau - s.tau) <= 2 * tol
            auto_its.append(a.iterations)
            lower_its.append(s.iterations)
        record(f"drag {law} eps<1 drag<=0.05: mean iterations auto, lower_bound",
               (float(np.mean(auto_its)), float(np.mean(lower_its))))
        assert np.mean(auto_its) <= np.mean(lower_its)
