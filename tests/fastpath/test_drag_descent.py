"""Long descents with drag: flights that sink slowly near the terminal velocity converge.

With linear drag k and a fast departure the particle rises to ~v/k and sinks at ~1/k per unit
of time: thousands of time units during which the lower-bound steps, bounded by the plate's
curvature |eps|, used to crawl and run out of their 60 evaluations. The jump over the descent
(``fastpath.dissipative.drag_flight.descent_jump``) certifies that no collision happens while the
particle is above the plate's reach, from the particle's concave height alone. Each flight is
held to verify's certified root within the solver's own error bound (``drag_reference``).
"""

import math

import pytest
from drag_reference import first_root, tau_tolerance

import fastpath
import verify
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state
from fastpath.physics import LAWS

CASES = [
    ((1.0, 1000.0, 0.6), 3.0, "linear"),
    ((1.0, 1000.0, 0.6), 100.0, "linear"),
    ((1.0, 1e4, 0.6), 0.5, "linear"),
    ((1.0, 1000.0, 0.0), 1e8, "linear"),
    ((1.0, 1000.0, 2.0), 3.0, "linear"),
    ((1.0, 1e6, 0.6), 0.01, "linear"),
    ((2.5, 300.0, -0.9), 1.0, "linear"),
    ((1.0, 1000.0, 0.6), 3.0, "quadratic"),
]


@pytest.mark.slow
@pytest.mark.parametrize(("state", "k", "law"), CASES,
                         ids=[f"{s}-k={k}-{law}" for s, k, law in CASES])
def test_a_long_descent_converges_to_the_certified_root(state, k, law):
    """CONVERGED within 30 evaluations, and within the solver's error bound of verify's root
    (these used to end MAX_ITERATIONS after 60)."""
    phi, v, eps = state
    res = fastpath.flight(phi, v, eps, drag=k, drag_law=law)
    assert res.status == fastpath.FlightStatus.CONVERGED and res.iterations <= 30, res
    ref = verify.flight_time(phi, v, eps, dps=30, drag=k, drag_law=law)
    d_err = gap_state(centre_phase(phi), v, eps, k, LAWS[law], float(ref))[3]
    assert abs(res.tau - float(ref)) <= tau_tolerance(d_err, phi, v, eps, k, LAWS[law], ref)


def test_a_flight_out_of_evaluations_says_so():
    """A flight that runs out of its 60 evaluations is reported as such (the budget named), not
    as a flight float64 cannot decide: the chattering graze with clearance 1e-16, where the
    lower-bound steps run out past a shallow dip."""
    phi, v, eps = 5.4420677987249695, 1.1180828263046108, 1.5
    assert fastpath.flight(phi, v, eps).status == fastpath.FlightStatus.MAX_ITERATIONS
    with pytest.raises(fastpath.UncertainCollision, match="budget of 60 gap evaluations"):
        fastpath.flight_time(phi, v, eps)


BELOW_TERMINAL = [
    (1.5707963267948966, -2.9, 3.0, 1.0, "quadratic"),
    (1.2, -5.0, 6.0, 0.5, "quadratic"),
    (2.0, -40.0, 45.0, 0.01, "quadratic"),
    (1.2, -5.0, 6.0, 0.5, "linear"),
    (1.2, -3.0, 3.5, 1.0, "linear"),
]


@pytest.mark.parametrize("case", BELOW_TERMINAL, ids=[f"{c[4]}-v={c[1]}" for c in BELOW_TERMINAL])
def test_departures_faster_than_terminal_are_accepted_and_right(case):
    """fastpath takes every departure with w0 = v + eps*sin(phi) > 0, also one falling faster
    than the terminal velocity (v < -1/sqrt(k) quadratic, v < -1/k linear; the plate moving
    down faster still): CONVERGED within the solver's error bound of a 60-digit first root
    found by sampling the gap (``drag_reference.first_root``, independent of the solver)."""
    phi, v, eps, k, law = case
    assert v + eps * math.sin(phi) > 0
    res = fastpath.flight(phi, v, eps, drag=k, drag_law=law)
    assert res.status == fastpath.FlightStatus.CONVERGED, res
    ref, _ = first_root(phi, v, eps, k, LAWS[law], 2.0 * res.tau)
    d_err = gap_state(centre_phase(phi), v, eps, k, LAWS[law], float(ref))[3]
    assert abs(res.tau - float(ref)) <= tau_tolerance(d_err, phi, v, eps, k, LAWS[law], ref)


STRONG = [(phi, v, eps, k) for phi in (0.5, 2.5) for eps in (0.6, -0.9)
          for k in (10.0, 1000.0) for v in (1e5, 1e6, 1e8) if k * v >= 1e6]


@pytest.mark.parametrize(("phi", "v", "eps", "k"), STRONG)
def test_linear_drag_descents_with_k_v_up_to_1e11_converge(phi, v, eps, k):
    """At k*v >= 1e8 the flight's rounding bound on d' (charged with |V'| at the departure,
    1 + k*v) exceeded |d'| at the root and the steps crept towards it; with the local bound
    (``fastpath.dissipative.laws.linear.tight_gap_errors``) they converge, within the solver's
    bound of verify's root."""
    res = fastpath.flight(phi, v, eps, drag=k)
    assert res.status == fastpath.FlightStatus.CONVERGED, res
    ref = verify.flight_time(phi, v, eps, dps=30, drag=k)
    d_err = gap_state(centre_phase(phi), v, eps, k, LAWS["linear"], float(ref))[3]
    assert abs(res.tau - float(ref)) <= tau_tolerance(d_err, phi, v, eps, k, LAWS["linear"], ref)
