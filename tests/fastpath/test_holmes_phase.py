"""One Holmes phase in fastpath: the dynamics' Holmes step (``fastpath.dynamics.kernels``, the
standard-map form with its Jacobian) lands on the phase of the Holmes map itself
(``fastpath.elastic.holmes.holmes_phase``, phi + 2*v reduced exactly), so where it departs it
is ``fastpath.holmes_step`` bit for bit, at any velocity."""

import math

import numpy as np

import fastpath
from fastpath.dynamics.kernels import step_tangent
from fastpath.physics import holmes
from fastpath.status import CONVERGED, NOT_DEPARTING

EPS = 0.6


def _tangent_steps(phi, v, eps):
    out = [step_tangent(p, math.sin(p), math.cos(p), w, holmes(eps))
           for p, w in zip(phi, v, strict=True)]
    return (np.array([o[0] for o in out]), np.array([o[3] for o in out]),
            np.array([o[9] for o in out]))


def test_the_dynamics_holmes_step_is_the_holmes_map_bit_for_bit_at_any_velocity():
    """Velocities from 3 to 1e12: phi + 2*v rounded before its reduction would miss the exact
    phase by up to ulp(2*v)/2, far beyond the few ulps of 2*pi of the exact reduction."""
    rng = np.random.default_rng(36)
    phi = rng.uniform(0.0, 2.0 * math.pi, 400)
    v = 10.0 ** rng.uniform(0.5, 12.0, 400)
    phi1, v1, status = _tangent_steps(phi, v, EPS)
    assert (status == CONVERGED).all()  # v > 2*eps: every step departs
    want_phi, want_v = fastpath.holmes_step(phi, v, EPS)
    assert np.array_equal(phi1, want_phi)
    assert np.array_equal(v1, want_v)


def test_the_dynamics_holmes_step_keeps_its_smooth_form_where_the_absolute_value_would_act():
    """Where v - 2*eps*sin(phi1) <= 0 the Holmes map folds the velocity (|.|); the standard-map
    form of the dynamics reports NOT_DEPARTING instead, and its phase is still the Holmes one."""
    rng = np.random.default_rng(37)
    phi = rng.uniform(0.0, 2.0 * math.pi, 4000)
    v = rng.uniform(0.01, 2.0 * EPS, 4000)
    phi1, v1, status = _tangent_steps(phi, v, EPS)
    folded = v - 2.0 * EPS * np.sin(phi1) <= 0.0
    assert folded.any() and (~folded).any()
    assert (status[folded] == NOT_DEPARTING).all()
    assert (status[~folded] == CONVERGED).all()
    leaves = v + EPS * np.sin(phi) > 0.0  # holmes_step takes departures only
    want_phi, want_v = fastpath.holmes_step(phi[leaves], v[leaves], EPS)
    assert np.array_equal(phi1[leaves], want_phi)
    keep = ~folded[leaves]
    assert np.array_equal(v1[leaves][keep], want_v[keep])
    assert np.array_equal(-v1[leaves][~keep], want_v[~keep])
