"""Bad input raises ValueError naming the value; arrays broadcast; scalars give Python floats."""

import math

import numpy as np
import pytest
from fastpath_tolerances import exact_w0

import fastpath

GOOD = {"phi": 4.0, "v": 3.0, "eps": 0.6}
BAD_VALUES = [math.nan, math.inf, -math.inf]


@pytest.mark.parametrize("bad", BAD_VALUES, ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("name", ["phi", "v", "eps"])
@pytest.mark.parametrize(
    "func", [fastpath.flight_time, fastpath.flight, fastpath.step, fastpath.holmes_step]
)
def test_non_finite_input_names_the_value(func, name, bad):
    args = {**GOOD, name: bad}
    with pytest.raises(ValueError, match=name):
        func(args["phi"], args["v"], args["eps"])
    arrays = {**GOOD, name: np.array([1.0, bad])}
    with pytest.raises(ValueError, match=name):
        func(arrays["phi"], arrays["v"], arrays["eps"])


@pytest.mark.parametrize("bad", BAD_VALUES, ids=["nan", "inf", "-inf"])
@pytest.mark.parametrize("name", ["phi0", "v0", "eps"])
def test_orbit_non_finite_input_names_the_value(name, bad):
    args = {"phi0": 4.0, "v0": 3.0, "eps": 0.6, name: bad}
    with pytest.raises(ValueError, match=name):
        fastpath.orbit(args["phi0"], args["v0"], args["eps"], 10)


@pytest.mark.parametrize(
    "phi, v",
    [(4.0, 0.0), (1.0, -1.0), (4.0, -0.6 * math.sin(4.0) - 1e-15), (1e12, 0.0)],
)
def test_not_departing_is_rejected(phi, v):
    """w0 = v + eps*sin(phi) < 0 for certain at eps = 0.6 (the third 1e-15 below 0, beyond the
    ~5e-16 rounding bound of w0), also at a huge phase."""
    eps = 0.6
    assert exact_w0(phi, v, eps) < -2e-16
    with pytest.raises(ValueError, match="w0"):
        fastpath.flight_time(phi, v, eps)
    with pytest.raises(ValueError, match="w0"):
        fastpath.step(phi, v, eps)
    with pytest.raises(ValueError, match="w0"):
        fastpath.orbit(phi, v, eps, 3)
    res = fastpath.flight(phi, v, eps)
    assert res.status == fastpath.FlightStatus.NOT_DEPARTING and math.isnan(res.tau)


def test_w0_within_rounding_of_zero_is_uncertain_not_rejected():
    """v = -fl(0.6*sin(1)): w0 computes as 0, but the exact w0 of these floats is not 0; its sign
    is below float64's resolution, so the flight is UNCERTAIN (never NOT_DEPARTING)."""
    phi, v, eps = 1.0, -0.6 * math.sin(1.0), 0.6
    assert exact_w0(phi, v, eps) != 0
    assert fastpath.flight(phi, v, eps).status == fastpath.FlightStatus.UNCERTAIN
    with pytest.raises(fastpath.UncertainCollision, match="departure or not"):
        fastpath.flight_time(phi, v, eps)


def test_message_states_the_computed_w0():
    with pytest.raises(ValueError, match=r"computed as -0\.36674.* rounding error <= "):
        fastpath.flight_time(1e12, 0.0, 0.6)


def test_valid_departure_at_huge_phase_is_accepted():
    """phi = 1e12 with w0 = +1e-8 (exact at 60 digits) is a departure: accepted, not rejected as
    'w0 = 9.99e-09 <= 0'."""
    from mpmath import mp

    with mp.workdps(60):
        v = float(1e-8 - 0.6 * mp.sin(mp.mpf(1e12)))
    assert exact_w0(1e12, v, 0.6) > 0
    assert fastpath.flight_time(1e12, v, 0.6) > 0


@pytest.mark.parametrize(
    "phi, v, eps", [(1.0, 1e308, 0.6), (1.0, 1e200, 3.0), (1.0, 3.0, 1e308), (0.5, 1e300, 1e300)]
)
def test_overflow_is_a_value_error_saying_overflow(phi, v, eps):
    for func in (fastpath.flight_time, fastpath.step):
        with pytest.raises(ValueError, match="overflow"):
            func(phi, v, eps)
        with pytest.raises(ValueError, match="overflow"):
            func(np.array([phi, 4.0]), np.array([v, 3.0]), eps)
    assert fastpath.flight(phi, v, eps).status == fastpath.FlightStatus.OVERFLOW


@pytest.mark.parametrize("call", [
    lambda: fastpath.flight([4.0], [10**400], 0.6),
    lambda: fastpath.step(np.array([4.0]), [3.0], [10**400]),
    lambda: fastpath.flight_time(4.0, 10**400, 0.6),
    lambda: fastpath.orbit(4.0, 3.0, [-(10**400)], 3),
    lambda: fastpath.flight(4.0, 3.0, 0.6, drag=10**400),
], ids=["flight-array", "step-array", "flight_time-scalar", "orbit", "drag"])
def test_an_integer_beyond_float64_is_a_value_error(call):
    """Python integers beyond float64's range are rejected like inf: ValueError, not numpy's
    OverflowError."""
    with pytest.raises(ValueError, match="must be finite"):
        call()


@pytest.mark.parametrize("bad", ["4.0", True, np.bool_(False), None, [1.0, "x"], 1 + 2j,
                                 np.array(["1.0"]), np.array([True, False])])
@pytest.mark.parametrize(
    "func", [fastpath.flight_time, fastpath.flight, fastpath.step, fastpath.holmes_step]
)
def test_strings_and_bools_are_rejected(func, bad):
    with pytest.raises(ValueError, match="phi"):
        func(bad, 3.0, 0.6)
    with pytest.raises(ValueError, match="eps"):
        func(4.0, 3.0, bad)


@pytest.mark.parametrize("phi, v", [(4.0, 0.0), (1.0, -1.0)])
def test_holmes_step_rejects_non_departures(phi, v):
    with pytest.raises(ValueError, match="w0"):
        fastpath.holmes_step(phi, v, 0.6)
    with pytest.raises(ValueError, match="w0"):
        fastpath.holmes_step(np.array([4.0, phi]), np.array([3.0, v]), 0.6)
    with pytest.raises(ValueError, match="w0"):
        fastpath.orbit(phi, v, 0.6, 3, model="holmes")


def test_exact_tangential_departure_is_rejected():
    """w0 == 0 exactly: resting on the plate at phase 0."""
    with pytest.raises(ValueError, match="w0"):
        fastpath.flight_time(0.0, 0.0, 0.6)


def test_shapes_that_do_not_broadcast():
    with pytest.raises(ValueError, match="phi"):
        fastpath.flight_time(np.zeros(3), np.ones(4), 0.5)
    with pytest.raises(ValueError, match="v"):
        fastpath.step(np.zeros(3), np.ones(4), 0.5)


@pytest.mark.parametrize("n", [10.0, 2.5, "10", None, True])
def test_orbit_non_integer_n(n):
    with pytest.raises(ValueError, match="n"):
        fastpath.orbit(4.0, 3.0, 0.6, n)


def test_orbit_negative_n_and_bad_names():
    with pytest.raises(ValueError, match="n"):
        fastpath.orbit(4.0, 3.0, 0.6, -1)
    with pytest.raises(ValueError, match="model"):
        fastpath.orbit(4.0, 3.0, 0.6, 10, model="holmez")
    with pytest.raises(ValueError, match="on_uncertain"):
        fastpath.orbit(4.0, 3.0, 0.6, 10, on_uncertain="ignore")
    with pytest.raises(ValueError, match="orbit"):
        fastpath.orbit(np.array([4.0, 1.0]), 3.0, 0.6, 10)


@pytest.mark.parametrize("dps", [14, 0, -5])
def test_verify_rejects_low_precision(dps):
    import verify

    with pytest.raises(ValueError, match="dps"):
        verify.flight_time(4.0, 3.0, 0.6, dps=dps)


def test_arrays_broadcast():
    phi = np.linspace(0.0, 6.0, 3).reshape(3, 1)
    v = np.linspace(2.0, 5.0, 4)
    tau = fastpath.flight_time(phi, v, 0.6)
    assert tau.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            assert tau[i, j] == fastpath.flight_time(float(phi[i, 0]), float(v[j]), 0.6)
    phi1, v1, tau2 = fastpath.step(phi, v, 0.6)
    assert phi1.shape == v1.shape == tau2.shape == (3, 4)
    assert np.array_equal(tau2, tau)
    res = fastpath.flight(phi, v, 0.6)
    assert res.tau.shape == res.iterations.shape == res.status.shape == (3, 4)
    h_phi1, h_v1 = fastpath.holmes_step(phi, v, 0.6)
    assert h_phi1.shape == h_v1.shape == (3, 4)


def test_scalars_give_python_floats():
    assert type(fastpath.flight_time(4.0, 3.0, 0.6)) is float
    assert all(type(x) is float for x in fastpath.step(4.0, 3.0, 0.6))
    assert all(type(x) is float for x in fastpath.holmes_step(4.0, 3.0, 0.6))
    res = fastpath.flight(4.0, 3.0, 0.6)
    assert type(res.tau) is float
    assert type(fastpath.flight_time(np.float64(4.0), 3, 0.6)) is float


def test_orbit_shapes_and_models():
    orb = fastpath.orbit(4.0, 3.0, 0.6, 100)
    assert orb.phi.shape == orb.v.shape == orb.t.shape == (101,)
    assert orb.iterations.shape == (100,)
    assert orb.status == fastpath.FlightStatus.CONVERGED
    hol = fastpath.orbit(4.0, 3.0, 0.6, 100, model="holmes")
    assert hol.phi.shape == (101,) and hol.iterations is None
    assert fastpath.orbit(4.0, 3.0, 0.6, 0).phi.shape == (1,)


@pytest.mark.parametrize("func", [fastpath.flight, fastpath.flight_time])
@pytest.mark.parametrize("drag", [0.0, 0.1])
def test_a_flight_refuses_a_restitution_it_would_not_apply(func, drag):
    """restitution acts at an impact, not on a flight: flight and flight_time take only 1 and
    say so (they used to accept any r and ignore it); step and orbit apply it."""
    with pytest.raises(ValueError, match=r"restitution=0.5 does not act on a flight"):
        func(4.0, 3.0, 0.6, drag=drag, restitution=0.5)
    assert func(4.0, 3.0, 0.6, drag=drag, restitution=1.0) == func(4.0, 3.0, 0.6, drag=drag)


def test_a_scalar_flight_status_is_a_flight_status():
    """FlightResult.status of a scalar call is a FlightStatus member (of arrays: its codes)."""
    assert fastpath.flight(4.0, 3.0, 0.6).status is fastpath.FlightStatus.CONVERGED
    assert fastpath.flight(4.0, 0.0, 0.6).status is fastpath.FlightStatus.NOT_DEPARTING
    codes = fastpath.flight(np.array([4.0, 4.0]), np.array([3.0, 0.0]), 0.6).status
    assert [fastpath.FlightStatus(c) for c in codes] == [fastpath.FlightStatus.CONVERGED,
                                                         fastpath.FlightStatus.NOT_DEPARTING]


@pytest.mark.parametrize("call", [
    lambda method: fastpath.flight(1.0, 2.0, 3.0, method=method),
    lambda method: fastpath.orbit(4.0, 3.0, 0.6, 5, method=method),
])
def test_an_unknown_method_is_refused_naming_the_valid_ones(call):
    """Only "auto" and "lower_bound" are methods; a former name such as "seed" is a ValueError
    that lists them."""
    call("lower_bound")
    with pytest.raises(ValueError, match=r"method must be one of \['auto', 'lower_bound'\],"
                                         r" got 'seed'"):
        call("seed")


def test_version_is_the_package_version():
    from importlib.metadata import version

    assert fastpath.__version__ == version("bouncer-verify")


@pytest.mark.parametrize("func", [fastpath.flight, fastpath.flight_time, fastpath.step,
                                  fastpath.holmes_step, fastpath.orbit, fastpath.carried_step])
def test_public_docstrings_name_their_parameters(func):
    """Every parameter of a public function is named in its docstring."""
    import inspect

    doc = func.__doc__
    for name in inspect.signature(func).parameters:
        assert name in doc, (func.__name__, name)


def test_a_scalar_flight_is_the_flight_solver_and_the_array_call_bit_for_bit():
    """``flight_time`` and scalar ``flight`` (which run ``step``'s compiled collision) give
    ``solve_flight``'s tau, iterations and status, and the array call's, for both methods and
    every kind of departure: concave, several roots (eps > 1), huge phases, non-departures."""
    from fastpath.elastic.flight import METHODS, solve_flight

    rng = np.random.default_rng(31)
    n = 400
    phi = np.concatenate([rng.uniform(-10.0, 10.0, n - 4), [1e12, -3e9, 4.0, 1.0]])
    v = np.concatenate([rng.uniform(0.01, 40.0, n - 4), [2.0, 5.0, 0.0, -1.0]])
    eps = np.concatenate([rng.choice([0.1, 0.6, 1.0, 1.5, 3.0, 7.0], n - 4), [0.6, 2.5, 0.6, 0.6]])
    for method, code in METHODS.items():
        arrays = fastpath.flight(phi, v, eps, method=method)
        for i in range(n):
            one = fastpath.flight(phi[i], v[i], eps[i], method=method)
            solved = solve_flight(phi[i], v[i], eps[i], code)
            got = (one.tau, one.iterations, int(one.status))
            np.testing.assert_equal(got, solved)
            np.testing.assert_equal(got, (arrays.tau[i], arrays.iterations[i], arrays.status[i]))
            if method == "auto" and one.status == fastpath.FlightStatus.CONVERGED:
                assert fastpath.flight_time(phi[i], v[i], eps[i]) == one.tau
    statuses = {fastpath.FlightStatus(s) for s in fastpath.flight(phi, v, eps).status}
    assert {fastpath.FlightStatus.CONVERGED, fastpath.FlightStatus.NOT_DEPARTING} <= statuses
