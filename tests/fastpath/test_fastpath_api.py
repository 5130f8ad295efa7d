"""Bad input raises ValueError naming the value; arrays broadcast; scalars give Python floats."""

import math

import numpy as np
import pytest

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
    [(4.0, 0.0), (1.0, -1.0), (1.0, -0.6 * math.sin(1.0)), (4.0, -0.6 * math.sin(4.0) - 1e-15)],
)
def test_not_departing_is_rejected(phi, v):
    """w0 = v + eps*sin(phi) <= 0 at eps = 0.6 (the last two exactly at 0 or just below)."""
    eps = 0.6
    assert v + eps * math.sin(phi) <= 0
    with pytest.raises(ValueError, match="w0"):
        fastpath.flight_time(phi, v, eps)
    with pytest.raises(ValueError, match="w0"):
        fastpath.step(phi, v, eps)
    with pytest.raises(ValueError, match="w0"):
        fastpath.orbit(phi, v, eps, 3)
    res = fastpath.flight(phi, v, eps)
    assert res.status == fastpath.FlightStatus.NOT_DEPARTING and math.isnan(res.tau)


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
