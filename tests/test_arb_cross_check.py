"""verify and fastpath held to a second, independent reference: python-flint's ``arb`` balls.

The reference (tests/arb_reference.py) certifies the first root of the gap by its own lower-bound
scan, its own phase reduction and its own closed forms of the drag flights, sharing no code with
verify or fastpath. On every flight below (random departures of every kind, the hard-case table,
huge phases, linear and quadratic drag, quadratic drag below its terminal velocity):

* verify's certificate encloses the same root: its enclosure and the reference's intersect (two
  proofs of "the first root is in here"), and ``verify.certify_flight(...).tau`` is within
  ``1.2*10**-dps`` of the reference's root, relatively;
* fastpath (``fastpath.flight`` and ``fastpath.step``, public API), where it says CONVERGED, is
  held to what its error analysis gives for the rounding that actually happens, not to the
  bound of its stopping rule. ``kappa`` is computed here from the reference (the reduced phase,
  as fastpath reduces it): ``(|v| + tau + |eps|*(1 + |phi_r| + tau))/|d'(tau)|``.

  tau: within ``K_TAU*kappa*u`` (K_TAU = 4). The solvers stop where the computed gap is within
  its bound E of zero and then take one Newton step (``fastpath.elastic.concave``,
  ``lower_bound``): the root is then off by the gap's actual rounding over |d'(tau)|. E carries
  a factor 4 over the roundings it bounds, and E/(|d'|*tau) <= 12*kappa*u
  (tests/fastpath/fastpath_tolerances.py), so the actual rounding is <= 3*kappa*u*tau; the
  returned float adds half an ulp, <= u*tau <= kappa*u*tau: 4 in all. (16, the bound of the
  stopping rule without the Newton step, is what the property suites allow.)
  phi1 (``step``): within ``K_TAU*kappa*u*tau + PHASE_ULPS*ulp(2*pi)``: the tau error and the
  landing phase's exact reduction, a few ulps of 2*pi (PHASE_ULPS = 4, docs/fastpath.md).
  v1 (``step``, elastic flights, v1 = tau - v - 2*eps*sin(phi1)): the tau error with weight
  1 + 2|eps|, the phase error with weight 2|eps|, and four roundings of the formula and the
  sine, 4u*(tau + |v| + 2|eps|).

The default suite runs 520 flights (a few seconds); ``-m slow`` runs 5,320 more.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction

import flint
import numpy as np
import pytest
from flint import arb

import fastpath
import verify
from tests import arb_reference as reference
from verify.hard_cases import DISSIPATIVE_CASES, HARD_CASES

U = 2.0**-53
K_TAU = 4.0  # module docstring: the actual rounding at the Newton step's stop, plus the last ulp
PHASE_ULPS = 4.0  # the landing phase's reduction, in ulps of 2*pi
ULP_TWO_PI = math.ulp(2 * math.pi)
DPS = 30
LAWS = ("linear", "quadratic")


def _random_elastic(rng: random.Random):
    """A departure: eps in [0, 1] or [1, 10] or [-3, 0], the phase reduced or up to 1e6 or
    huge (1e12 .. 1e300), w0 log-uniform in [1e-10, 30] (v from it)."""
    kind = rng.random()
    eps = rng.uniform(0.0, 1.0) if kind < 0.4 else rng.uniform(1.0, 10.0) if kind < 0.8 \
        else -rng.uniform(0.0, 3.0)
    which = rng.random()
    if which < 0.6:
        phi = rng.uniform(0.0, 2 * math.pi)
    elif which < 0.85:
        phi = rng.uniform(-1e3, 1e6)
    else:
        phi = rng.choice((-1.0, 1.0)) * rng.uniform(1.0, 10.0) * 10.0 ** rng.randint(12, 300)
    w0 = 10.0 ** rng.uniform(-10.0, 1.5)
    return phi, w0 - eps * math.sin(phi), eps, 0.0, "linear"


def _random_drag(rng: random.Random):
    """A departure with drag 1e-6 .. 3 (either law), eps in [-2, 2], w0 in [1e-6, 10]; one in
    five quadratic-drag departures below the terminal velocity (v < -1/sqrt(k))."""
    law = rng.choice(LAWS)
    k = 10.0 ** rng.uniform(-6.0, 0.5)
    if law == "quadratic" and rng.random() < 0.2:
        v = -rng.uniform(1.05, 3.0) / math.sqrt(k)
        eps = (abs(v) + rng.uniform(0.1, 2.0)) * rng.choice((-1.0, 1.0))
        phi = math.asin(min(1.0, (rng.uniform(0.01, 0.5) - v) / abs(eps))) * np.sign(eps)
        phi = float(phi)
    else:
        eps = rng.uniform(-2.0, 2.0)
        phi = rng.uniform(0.0, 2 * math.pi)
        v = 10.0 ** rng.uniform(-6.0, 1.0) - eps * math.sin(phi)
    return phi, v, eps, k, law


def _flights(n_elastic: int, n_drag: int, seed: int):
    rng = random.Random(seed)
    out = [(c.phi, c.v, c.eps, 0.0, "linear") for c in HARD_CASES]
    out += [(c.phi, c.v, c.eps, c.drag, c.drag_law) for c in DISSIPATIVE_CASES
            if c.drag > 0 and c.kind != "w0=0 departure"]
    out += [_random_elastic(rng) for _ in range(n_elastic)]
    out += [_random_drag(rng) for _ in range(n_drag)]
    return out


def _certified(flights):
    """(flight, enclosure) for each departure the reference certifies (w0 > 0 proved)."""
    out = []
    for flight in flights:
        try:
            found = reference.first_root(*flight)
        except reference.NoDeparture:
            continue
        assert found is not None, f"the reference did not decide {flight}"
        out.append((flight, found))
    return out


def _exact(x) -> Fraction:
    """An mpf or float as the exact fraction it is."""
    if hasattr(x, "_mpf_"):
        man, exp = x.man_exp
        return Fraction(int(man)) * Fraction(2) ** int(exp)
    return Fraction(x)


def _kappa(flight, root) -> float:
    """The condition number of the reference's root (the reduced phase, as fastpath sees it)."""
    phi, v, eps, k, law = flight
    gap = reference._Gap(phi, v, eps, k, law)
    t = reference._point(root)
    _, slope = gap.value_and_slope(t)
    phase = abs(phi) if abs(phi) < 8 else float(gap.r)
    num = abs(v) + float(root) + abs(eps) * (1 + phase + float(root))
    return math.inf if slope.contains(0) else num / float(abs(slope).lower())


def _hold_verify(certified, drag_every=1):
    """verify's certificates against the reference (drag flights: every ``drag_every``-th)."""
    count = 0
    for j, ((phi, v, eps, k, law), (lo, hi)) in enumerate(certified):
        if k > 0 and j % drag_every:
            continue
        cert = verify.certify_flight(phi, v, eps, dps=DPS, drag=k, drag_law=law)
        v_lo, v_hi = (_exact(x) for x in cert.enclosure)
        assert v_lo < hi and lo < v_hi, ((phi, v, eps, k, law), "a different root")
        tau = _exact(cert.tau)
        tol = Fraction(12, 10**(DPS + 1)) * tau
        assert lo - tol <= tau <= hi + tol, (phi, v, eps, k, law)
        count += 1
    return count


def _landing(flight, root):
    """(phi1, v1) of the reference: (phi_r + root) mod 2*pi and, without drag,
    root - v - 2*eps*sin(phi1), as arb balls at 200 bits."""
    phi, v, eps, k, law = flight
    old = flint.ctx.prec
    flint.ctx.prec = 200
    try:
        gap = reference._Gap(phi, v, eps, k, law)
        arrival = gap.r + reference._point(root)
        turn = 2 * arb.pi()
        phi1 = arrival - turn * (arrival / turn).mid().floor()
        v1 = reference._point(root) - reference._exact(v) - 2 * gap.eps * arrival.sin()
        return phi1, v1
    finally:
        flint.ctx.prec = old


def _phase_distance(a: float, ball) -> float:
    d = abs(float(ball - reference._exact(a)))
    return min(d, 2 * math.pi - d)


def _hold_fastpath(certified):
    """fastpath's converged flights and steps against the reference: the worst of tau (units of
    kappa*u), phi1 and v1 (units of their bounds, module docstring), and the count."""
    worst = {"tau": 0.0, "phi1": 0.0, "v1": 0.0}
    converged = 0
    for flight, (lo, hi) in certified:
        phi, v, eps, k, law = flight
        drag = {"drag": k, "drag_law": law} if k > 0 else {}
        result = fastpath.flight(phi, v, eps, **drag)
        if int(result.status) != int(fastpath.FlightStatus.CONVERGED):
            continue
        root = (lo + hi) / 2
        error = abs(Fraction(float(result.tau)) - root) / root
        kappa = _kappa(flight, root)
        units = float(error) / (kappa * U)
        assert units <= K_TAU, (flight, float(result.tau), float(root), units)
        worst["tau"] = max(worst["tau"], units)
        converged += 1
        phi1, v1, tau = fastpath.step(phi, v, eps, **drag)
        assert tau == result.tau
        ref_phi1, ref_v1 = _landing(flight, root)
        tau_error = K_TAU * kappa * U * float(root)
        phase_bound = tau_error + PHASE_ULPS * ULP_TWO_PI
        phase_units = _phase_distance(phi1, ref_phi1) / phase_bound
        assert phase_units <= 1.0, (flight, phi1, float(ref_phi1))
        worst["phi1"] = max(worst["phi1"], phase_units)
        if k == 0:
            v_bound = (tau_error * (1 + 2 * abs(eps)) + 2 * abs(eps) * PHASE_ULPS * ULP_TWO_PI
                       + 4 * U * (float(root) + abs(v) + 2 * abs(eps)))
            v_units = abs(float(ref_v1 - reference._exact(v1))) / v_bound
            assert v_units <= 1.0, (flight, v1, float(ref_v1))
            worst["v1"] = max(worst["v1"], v_units)
    return worst, converged


def test_reference_agrees_with_itself_on_known_flights():
    """The reference finds 2*v for eps = 0 and the fixed point's 2*pi*m, and encloses them."""
    lo, hi = reference.first_root(0.0, 3.0, 0.0)
    assert lo < 6 < hi and hi - lo < Fraction(1, 10**30)
    lo, hi = reference.first_root(0.0, math.pi, 0.6)
    # next to the fixed point (0, pi): d(2v) = eps*(1 - cos(2v)) ~ 1e-32 with v = fl(pi)
    assert abs((lo + hi) / 2 - 2 * Fraction(math.pi)) < Fraction(1, 10**30)


def test_verify_and_fastpath_agree_with_the_arb_reference():
    """520 flights: the hard-case table (94), the dissipative table's drag flights (26), 330
    random elastic departures and 70 random drag departures (at least 500 depart);
    verify checked on every elastic flight and every fifth drag flight (its drag certificates
    take ~0.1 s each), fastpath on all."""
    certified = _certified(_flights(330, 70, seed=2024))
    assert len(certified) >= 500
    assert sum(1 for (flight, _) in certified if flight[3] > 0) >= 90
    assert _hold_verify(certified, drag_every=5) >= 400
    worst, converged = _hold_fastpath(certified)
    assert converged >= 450
    print(f"arb cross-check: {len(certified)} flights, fastpath worst: tau {worst['tau']:.2f} "
          f"kappa*u, phi1 {worst['phi1']:.2f} and v1 {worst['v1']:.2f} of their bounds")


@pytest.mark.slow
def test_verify_and_fastpath_agree_with_the_arb_reference_on_many_flights():
    """5,320 flights: the two tables (120) and 5,200 random departures (seeds apart from the
    default test's; at least 5,000 depart), verify on all of them."""
    certified = _certified(_flights(4200, 1000, seed=7))
    assert len(certified) >= 5000
    assert _hold_verify(certified) >= 5000
    worst, converged = _hold_fastpath(certified)
    assert converged >= 4500
    print(f"arb cross-check: {len(certified)} flights, fastpath worst: tau {worst['tau']:.2f} "
          f"kappa*u, phi1 {worst['phi1']:.2f} and v1 {worst['v1']:.2f} of their bounds")


def test_reference_certifies_what_the_old_phase_of_verify_got_wrong():
    """The arb reference and verify.step agree on the landing phase at v = 1e15 (the flight
    time certified relatively only would leave it unknown)."""
    lo, hi = reference.first_root(1.0, 1e15, 3.0)
    phi1 = verify.step(1.0, 1e15, 3.0, dps=15)[0]
    old = flint.ctx.prec
    flint.ctx.prec = 200
    try:
        arrival = reference._exact(1.0) + reference._point(lo)
        turn = 2 * arb.pi()
        landing = arrival - turn * (arrival / turn).mid().floor()
        assert abs(float(landing) - float(phi1)) < 1e-14
    finally:
        flint.ctx.prec = old
    assert float(hi - lo) < 1e-20
