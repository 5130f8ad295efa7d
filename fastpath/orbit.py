"""Orbit kernels: n successive collisions from one start, exact or Holmes.

The driver fills preallocated arrays; t is the time since the start (t[0] = 0), accumulated
from the flight times (the Holmes flight time is 2*v).

``inelastic_orbit`` (restitution r < 1, no drag) also records sticking episodes
(``fastpath.sticking``): phi, v, t hold the impacts actually computed, a chattering sequence's
ones included up to the impact after which its tail is summed; the summed tail is not an entry.
An episode (t_acc, t_detach) goes into ``sticking``; the entry after it is the first impact of
the flight from the detachment state (theta*, v = u(theta*)).
"""

import math

from fastpath._jit import jit
from fastpath.collision import collide_from
from fastpath.flight import CONVERGED, NOT_DEPARTING, UNCERTAIN, flight_from, phase_error_of
from fastpath.gap import departure
from fastpath.holmes import holmes_collide
from fastpath.phase import centre_phase, reduce_phase
from fastpath.short_flight import short_flight, short_window
from fastpath.sticking import (
    accumulation_tail,
    can_detach,
    detachment_flight,
    detachment_phase,
    detachment_velocity,
    inelastic_impact,
)

_REBASE = 1.0  # a run of short flights is summed from its start until it lasts this long


@jit
def exact_orbit(phi0, v0, eps, phi, v, t, iterations, method):
    """Fill phi, v, t (length n+1) and iterations (length n); return (collisions done, status).

    method: a ``fastpath.flight`` method code (AUTO or SEED).

    Stops early at the first flight that is not CONVERGED; its status is returned.
    """
    phi[0] = reduce_phase(phi0)
    v[0] = v0
    t[0] = 0.0
    sin_phi, cos_phi = math.sin(phi[0]), math.cos(phi[0])
    for k in range(len(iterations)):
        phi1, sin_phi, cos_phi, v1, tau, its, status = collide_from(
            phi[k], sin_phi, cos_phi, v[k], eps, method
        )
        iterations[k] = its
        if status != CONVERGED:
            return k, status
        phi[k + 1] = phi1
        v[k + 1] = v1
        t[k + 1] = t[k] + tau
    return len(iterations), CONVERGED


@jit
def holmes_orbit(phi0, v0, eps, phi, v, t):
    """Fill phi, v, t (length n+1) with the Holmes map; flight time 2*v."""
    phi[0] = reduce_phase(phi0)
    v[0] = v0
    t[0] = 0.0
    for k in range(len(phi) - 1):
        phi[k + 1], v[k + 1] = holmes_collide(phi[k], v[k], eps)
        t[k + 1] = t[k] + 2.0 * v[k]


@jit
def _long_flight(theta, v, eps, method):
    """(tau, iterations, status) of an ordinary flight from the absolute state (theta, v).

    The one call site of the flight solver in ``inelastic_orbit``: a drag flight plugs in here.
    """
    centred = centre_phase(theta)
    tau, _, _, iterations, status = flight_from(
        centred, math.sin(centred), math.cos(centred), v, eps, method,
        phase_error_of(theta, centred),
    )
    return tau, iterations, status


@jit
def inelastic_orbit(phi0, v0, eps, r, phi, v, t, iterations, sticking, method):
    """Fill phi, v, t (length n+1), iterations (length n), sticking rows; restitution r < 1.

    Returns (collisions done, sticking episodes, status, stuck for good). Each flight is a
    short flight in relative coordinates where ``short_window`` certifies one (chattering), the
    flight from detachment after a sticking episode, or an ordinary flight (``_long_flight``).
    The relative velocity w is carried across impacts. Phases and times of a run of short
    flights are summed from the run's start (base) so that their roundings do not pile up.
    Stops early at a flight that is not CONVERGED, and when the particle sticks for good.
    """
    base_phase = reduce_phase(phi0)
    base_time = 0.0
    s = 0.0  # time since the base
    phi[0], v[0], t[0] = base_phase, v0, 0.0
    sin_th, cos_th = math.sin(base_phase), math.cos(base_phase)
    # not centred: centring fl(pi) moves it by an ulp, and w = v0 + eps*sin would carry that
    w, w_error = departure(base_phase, sin_th, v0, eps, phase_error_of(phi0, base_phase))
    if not w > -w_error:
        return 0, 0, NOT_DEPARTING, False
    if not w > w_error:
        return 0, 0, UNCERTAIN, False
    vk = v0
    episodes = 0
    detached = False
    tau_d, its_d, status_d = math.nan, 0, CONVERGED
    for k in range(len(iterations)):
        w_in = 0.0
        if detached:
            if not tau_d == tau_d:  # the same flight after every detachment: computed once
                tau_d, _, _, its_d, status_d = detachment_flight(eps)
            if status_d != CONVERGED:
                return k, episodes, status_d, False
            tau, its = tau_d, its_d
            detached = False
            long = True
        else:
            upper = short_window(sin_th, cos_th, w, eps)
            long = not upper > 0.0
            if long:
                tau, its, status = _long_flight(base_phase + s, vk, eps, method)
                if status != CONVERGED:
                    return k, episodes, status, False
            else:
                tau, w_in, its = short_flight(sin_th, cos_th, w, eps, upper)
        s += tau
        theta = base_phase + s
        sin_th, cos_th = math.sin(theta), math.cos(theta)
        if long:
            w_in = (vk - tau) + eps * sin_th
        vk, w = inelastic_impact(-eps * sin_th, w_in, r)
        iterations[k] = its
        phi[k + 1], v[k + 1], t[k + 1] = reduce_phase(theta), vk, base_time + s
        if long or s > _REBASE:
            base_phase, base_time, s = reduce_phase(theta), base_time + s, 0.0
        tail = accumulation_tail(sin_th, cos_th, w, eps, r)
        if not tail == tail:
            continue
        t_acc = base_time + (s + tail)
        if not can_detach(eps):
            sticking[episodes, 0], sticking[episodes, 1] = t_acc, math.inf
            return k + 1, episodes + 1, CONVERGED, True
        theta_star = detachment_phase(eps)
        stay = s + tail + reduce_phase(theta_star - (base_phase + (s + tail)))
        sticking[episodes, 0], sticking[episodes, 1] = t_acc, base_time + stay
        episodes += 1
        base_phase, base_time, s = theta_star, base_time + stay, 0.0
        vk, w, detached = detachment_velocity(eps), 0.0, True
    return len(iterations), episodes, CONVERGED, False
