"""Orbits with drag (restitution 1) against the 60-digit reference of ``drag_reference``.

Each collision k of a fast orbit is recomputed from the orbit's own float departure state
(phi_k, v_k): the reference's FIRST root tau (no overstep), the incoming velocity V(tau), the
impact v1 = 2*u - V(tau), u = -eps*sin(phi_k + tau). Tolerances (u = 2**-53):

- tau: ``drag_reference.tau_tolerance`` (the solver stops where its computed gap is within its
  bound E of zero: the root within 2E/|d'| plus two ulps); the orbit's phase adds the rounding
  of (phi + tau) mod 2*pi (``fastpath_tolerances.phase_rounding``).
- v1 = 2*u(phi + tau) - V(tau): a tau error dt moves it by at most (2*|eps| + |1 + eta(V)|)*dt
  (|u'| <= |eps|, |V'| = |1 + eta(V)|); the phase rounding moves u by |eps| times it; V's own
  rounding is ``fastpath.dissipative.drag.particle``'s bound (held to the 60-digit forms in
  test_drag_reference); the impact formula rounds <= 4u*(2|u| + |V|) with room.

Also: the orbit is the chain of ``fastpath.step`` calls (the same kernel), bit for bit; the
elastic defaults are untouched; drag with restitution < 1 is refused.
"""

import math

import drag_reference as ref
import numpy as np
import pytest
from fastpath_figures import record
from fastpath_tolerances import phase_rounding
from mpmath import mp

import fastpath
from fastpath.arithmetic.phase import centre_phase
from fastpath.dissipative.drag import gap_state, particle
from fastpath.physics import LAWS

U = 2.0**-53
# (phi0, v0, eps, drag, law): eps below and above 1, both laws, weak to strong drag
ORBITS = [
    (4.0, 3.0, 0.6, 0.01, "linear"),
    (1.0, 2.0, 0.9, 0.3, "linear"),
    (2.5, 5.0, 1.5, 0.05, "linear"),
    (4.0, 3.0, 0.6, 0.02, "quadratic"),
    (0.3, 4.0, 1.3, 0.1, "quadratic"),
    (2.0, 1.5, 2.5, 1.0, "quadratic"),
]
N = 25


def _distance(a, b):
    d = (a - b) % (2 * mp.pi)
    return min(d, 2 * mp.pi - d)


@pytest.mark.slow
@pytest.mark.parametrize("phi0, v0, eps, k, law", ORBITS)
def test_orbit_with_drag_against_60_digits(phi0, v0, eps, k, law):
    orb = fastpath.orbit(phi0, v0, eps, N, drag=k, drag_law=law, on_uncertain="stop")
    assert orb.stopped == "collisions" and orb.sticking.shape == (0, 2)
    code = LAWS[law]
    done = len(orb.phi) - 1
    assert done >= N // 2, f"stopped after {done} collisions ({orb.status.name})"
    worst_phi, worst_v = 0.0, 0.0
    for j in range(done):
        phi, v = float(orb.phi[j]), float(orb.v[j])
        tau = float(orb.t[j + 1] - orb.t[j])  # tau up to the rounding of t (in the tolerance)
        d_error = gap_state(centre_phase(phi), v, eps, k, code, tau)[3]
        root, _ = ref.first_root(phi, v, eps, k, code, tau * (1 + 1e-9) + 1e-9)
        assert root is not None, f"collision {j}: no root up to {tau!r}"
        with mp.workdps(ref.DPS):
            tau_tol = ref.tau_tolerance(d_error, phi, v, eps, k, code, root) + 2 * math.ulp(
                float(orb.t[j + 1]))
            theta = mp.mpf(phi) + root
            _, v_in = ref.particle(v, k, code, root)
            v1_ref = -2 * mp.mpf(eps) * mp.sin(theta) - v_in
            phi_err = float(_distance(mp.mpf(float(orb.phi[j + 1])), theta))
            phi_tol = tau_tol + phase_rounding(phi, float(root))
            v_err_bound = particle(v, k, code, float(root))[3]
            slope = 2 * abs(eps) + abs(1 + float(ref.eta(v_in, mp.mpf(k), code)))
            v1_tol = (slope * tau_tol + 2 * abs(eps) * phase_rounding(phi, float(root))
                      + v_err_bound + 4 * U * (2 * abs(eps) + abs(float(v_in))))
            v1_err = float(abs(mp.mpf(float(orb.v[j + 1])) - v1_ref))
            kappa = float(ref.kappa(phi, v, eps, k, code, root))
        assert phi_err <= phi_tol, f"collision {j}: phase error {phi_err:.3g} > {phi_tol:.3g}"
        assert v1_err <= v1_tol, f"collision {j}: v1 error {v1_err:.3g} > {v1_tol:.3g}"
        worst_phi = max(worst_phi, phi_err / (kappa * U * float(root)))
        worst_v = max(worst_v, v1_err / v1_tol)
    record(f"drag orbit eps={eps} k={k} {law}: worst phase error (kappa*u*tau)",
           f"{worst_phi:.3g}, worst v1 error/tol {worst_v:.3g}, {done} collisions")


@pytest.mark.parametrize("phi0, v0, eps, k, law", ORBITS[:4])
def test_orbit_with_drag_is_the_chain_of_steps(phi0, v0, eps, k, law):
    orb = fastpath.orbit(phi0, v0, eps, 40, drag=k, drag_law=law, on_uncertain="stop")
    phi, v, t = orb.phi[0], orb.v[0], 0.0
    for j in range(len(orb.phi) - 1):
        phi, v, tau = fastpath.step(phi, v, eps, drag=k, drag_law=law)
        t += tau
        assert (phi, v, t) == (orb.phi[j + 1], orb.v[j + 1], orb.t[j + 1])


def test_drag_loses_energy_on_average_at_small_eps():
    """With eps = 0.1 the plate gives little; drag 0.05 brings v down from 5 (a sanity check
    that drag is actually applied in the orbit: without it v stays near 5)."""
    with_drag = fastpath.orbit(4.0, 5.0, 0.1, 200, drag=0.05)
    without = fastpath.orbit(4.0, 5.0, 0.1, 200)
    assert np.mean(with_drag.v[-50:]) < 0.8 * np.mean(without.v[-50:])


def test_drag_with_restitution_below_one_runs_exact_model_only():
    orb = fastpath.orbit(4.0, 3.0, 0.6, 10, drag=0.1, restitution=0.9)
    assert len(orb.phi) == 11 and orb.stopped == "collisions"
    with pytest.raises(ValueError, match="model='exact'"):
        fastpath.orbit(4.0, 3.0, 0.6, 10, model="holmes", drag=0.1)


def test_zero_drag_keyword_gives_the_elastic_orbit():
    a = fastpath.orbit(4.0, 3.0, 0.6, 100)
    b = fastpath.orbit(4.0, 3.0, 0.6, 100, drag=0.0, drag_law="quadratic", restitution=1.0)
    assert np.array_equal(a.phi, b.phi) and np.array_equal(a.v, b.v) and np.array_equal(a.t, b.t)
