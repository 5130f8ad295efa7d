"""Impacts with restitution, and the collision map with drag.

An impact at phase theta = phi + tau with incoming particle velocity v_in and plate velocity
u = -eps*sin(theta) reverses the relative velocity and shrinks it by r (0 < r <= 1):

    v1 - u = -r*(v_in - u),   i.e.   v1 = (1 + r)*u - r*v_in,

so the kinetic energy relative to the plate, (v - u)**2/2, loses the share 1 - r**2. The flight
before it is ``fastpath.elastic.flight`` without drag and ``fastpath.dissipative.drag_flight``
with it; v_in is v - tau, resp. V(tau) of ``fastpath.dissipative.drag.particle``. With drag == 0
and r == 1 the elastic ``fastpath.elastic.collision.collide`` is called unchanged, so its results
are reproduced bit for bit.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.sincos import sin_cos
from fastpath.dissipative.drag import particle
from fastpath.dissipative.drag_flight import drag_flight
from fastpath.elastic.collision import collide
from fastpath.elastic.flight import AUTO, departure_phase, flight_from
from fastpath.elastic.gap import departure
from fastpath.elastic.landing import landing_phase
from fastpath.status import CONVERGED


@jit
def impact_velocity(v_in, u, restitution):
    """Velocity just after an impact: v1 = (1 + r)*u - r*v_in (module docstring)."""
    return (1.0 + restitution) * u - restitution * v_in


@jit
def dissipative_collide(phi, v, physics):
    """(phi1, v1, tau, iterations, status): one flight (with the drag of the description
    ``physics``, ``fastpath.dissipative.drag``) and one impact with its restitution r; phi any
    real, phi1 in [0, 2*pi) (without drag as ``fastpath.elastic.collision``: a long flight's
    root carried as an unevaluated sum, ``fastpath.elastic.landing``)."""
    eps, drag, restitution = physics.eps, physics.drag, physics.restitution
    if drag == 0.0 and restitution == 1.0:
        return collide(phi, v, eps, AUTO)
    centred, phase_error = departure_phase(phi)
    sin_phi, cos_phi = sin_cos(centred)  # as collide: the same flight when drag == 0
    if drag == 0.0:
        tau, tau_lo, sin1, _, iterations, status = flight_from(
            centred, sin_phi, cos_phi, v, eps, AUTO, phase_error
        )
        v_in = v - tau
    else:
        _, w0_error = departure(centred, sin_phi, v, eps, phase_error)
        tau, sin1, _, iterations, status = drag_flight(
            centred, sin_phi, cos_phi, v, physics, w0_error, AUTO
        )
        tau_lo = 0.0
        v_in = particle(v, drag, physics.drag_law, tau)[1] if status == CONVERGED else math.nan
    v1 = impact_velocity(v_in, -eps * sin1, restitution)
    return landing_phase(centred, tau, tau_lo), v1, tau, iterations, status
