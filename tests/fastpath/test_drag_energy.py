"""Energy bookkeeping with dissipation.

In flight E = V**2/2 + Y changes by minus the work of drag, W = integral of eta(V)*V dt >= 0;
with dt = dV/(-1 - eta(V)) it has closed forms in V alone (so it checks Y against V):

    linear:     W = -(1/k**2)*[w**2/2 - 2*w + ln(w)] from w(v) to w(V),  w = 1 + k*V
    quadratic:  rising (V > 0)  W = -(1/(2k))*[q - ln(1 + q)],   q = k*V**2, from v to min(V, 0)
                falling (V < 0) W = (1/(2k))*[-q - ln|1 - q|],  from max(v, 0) to V

At an impact the velocity relative to the plate becomes -r times itself: the kinetic energy
relative to the plate loses the share 1 - r**2.
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
from fastpath.dissipative.drag import particle
from fastpath.physics import LAWS

U = 2.0**-53


def work(v, vel, k, law):
    """W from velocity v to vel (mpf), closed forms of the module docstring."""
    with mp.workdps(ref.DPS):
        v, vel, k = mp.mpf(v), mp.mpf(vel), mp.mpf(k)
        if law == ref.LINEAR:
            def prim(w):
                return w * w / 2 - 2 * w + mp.log(w)

            return -(prim(1 + k * vel) - prim(1 + k * v)) / k**2
        total = mp.mpf(0)
        if v > 0:
            def rise(x):
                return x - mp.log(1 + x)

            total += -(rise(k * max(vel, 0) ** 2) - rise(k * v * v)) / (2 * k)
        if vel < 0:
            def fall(x):
                return -x - mp.log(abs(1 - x))

            start = min(v, 0)
            total += (fall(k * vel * vel) - fall(k * start * start)) / (2 * k)
        return total


@pytest.mark.parametrize("law", sorted(LAWS))
def test_flight_energy_drops_by_the_work_of_drag(law):
    rng = np.random.default_rng(5 + sorted(LAWS).index(law))
    worst = 0.0
    for _ in range(300):
        v = rng.choice([-1.0, 1.0]) * 10 ** rng.uniform(-2, 1.5)
        k = 10 ** rng.uniform(-6, 0.5)
        t = 10 ** rng.uniform(-3, 1.3)
        y, vel, y_err, v_err = particle(v, k, LAWS[law], t)
        with mp.workdps(ref.DPS):
            _, vel_exact = ref.particle(v, k, LAWS[law], t)
            expected = mp.mpf(v) ** 2 / 2 - work(v, vel_exact, k, LAWS[law])
            got = mp.mpf(vel) ** 2 / 2 + mp.mpf(y)
            err = abs(got - expected)
        # Y's bound, V's bound times |V| (V**2/2 moves by ~|V|*dV), rounding of the sum
        tol = y_err + (abs(vel) + v_err) * v_err + 3 * U * (vel * vel / 2 + abs(y))
        assert err <= tol, f"energy off by {err} > {tol} at v={v!r}, drag={k!r}, t={t!r}"
        worst = max(worst, float(err / tol))
    record(f"drag {law}: worst energy error / tolerance in flight", round(worst, 3))


@pytest.mark.parametrize("law", sorted(LAWS))
@pytest.mark.parametrize("restitution", [0.3, 0.8, 1.0 - 2.0**-20])
def test_impact_keeps_r_squared_of_the_relative_kinetic_energy(law, restitution):
    rng = np.random.default_rng(11)
    n = 200
    phi = rng.uniform(-math.pi, math.pi, n)
    eps = rng.uniform(-2.5, 2.5, n)
    v = np.abs(eps) + rng.uniform(0.05, 8.0, n)  # w0 > 0.05
    k = 0.07
    phi1, v1, tau = fastpath.step(phi, v, eps, drag=k, drag_law=law, restitution=restitution)
    worst = 0.0
    for i in range(n):
        v_in = particle(v[i], k, LAWS[law], tau[i])[1]
        with mp.workdps(ref.DPS):
            u = -mp.mpf(eps[i]) * mp.sin(mp.mpf(centre_phase(phi[i])) + mp.mpf(tau[i]))
            rel_out, rel_in = mp.mpf(v1[i]) - u, mp.mpf(v_in) - u
            err = abs(rel_out + restitution * rel_in)
        # v1 = (1 + r)*u - r*v_in: three roundings; u from sin(phi + tau) rounded once more
        tol = (4 * U * ((1 + restitution) * abs(float(u)) + restitution * abs(v_in) + abs(v1[i]))
               + (1 + restitution) * abs(eps[i]) * (phase_rounding(phi[i], tau[i]) + 2 * U))
        assert err <= tol, f"{err} > {tol} at phi={phi[i]!r}, v={v[i]!r}, eps={eps[i]!r}"
        with mp.workdps(ref.DPS):
            lost = 1 - rel_out**2 / rel_in**2  # the share of relative kinetic energy lost
        worst = max(worst, float(abs(lost - (1 - mp.mpf(restitution) ** 2))))
    record(f"drag {law} r={restitution}: worst |energy share lost - (1 - r**2)|", f"{worst:.2e}")
