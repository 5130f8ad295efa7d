"""One particle, one collision with dissipation: the carried state and its step.

Orbits and ensemble kernels with drag or restitution r < 1 share this step. A particle's state
lives in a small float64 array (indices below) that ``begin`` fills and ``advance`` moves on by
one impact: the flight (``fastpath.dissipative.impact`` for r = 1; for r < 1 the short
relative-coordinate flight of a chattering run, ``fastpath.dissipative.short_flight``, or an
ordinary one, with or without drag), the impact v1 = (1 + r)*u - r*v_in, and, when r < 1 and the
impacts from there accumulate (``fastpath.dissipative.sticking.accumulation_tail``), the summed
tail and the sticking episode: the particle rides the plate from t_acc and leaves at the
detachment phase or is stuck for good.

Physics covered (the description ``fastpath.physics``). r = 1: a chain of flights (with drag if
any) and elastic impacts (with r = 1 impacts never accumulate in finite time); without drag this
is the elastic map, bit for bit. r < 1: phases and times of a run of short flights are summed
from the run's start (the base) so that their roundings do not pile up, and the relative
velocity w is carried across impacts; with drag the short flights, flights, tail, sticking
condition and detachment phase are the drag's (``fastpath.dissipative.sticking``); an
accumulation where the decision "ever detaches" is within rounding (``detach_kind`` UNDECIDED) is
UNCERTAIN (state unchanged).

Holes (ensembles). The impacts of a summed tail are not computed one by one; they land at
phases between the last computed impact theta_k and the accumulation phase theta_k + T. If a
hole's lower edge lies in that arc (within T plus a rounding margin), the tail is NOT summed and
the impacts go on one by one, each tested against the holes by the caller; a run whose next
flight no longer moves the clock (the edge within rounding of the accumulation point) is
UNCERTAIN.

The carried departure. With r < 1 a step depends on more than the departure point (phi, v) =
``departure_point(state)``: on the run's base phase and the time s since it (the phase of the
impact is base + (s + tau), not phi + tau), on the sine and cosine carried from the last impact
and on the carried relative velocity w (v + eps*sin(phi) recomputed would lose the digits of a
chattering w), and on whether the departure is a detachment. ``CARRIED`` names these state
entries; ``carried_state`` rebuilds a state from (phi, v) and them, from which ``advance``
repeats the step bit for bit (the audit of a run's sample, ``fastpath.carried_step``).
"""

import math

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import TWO_PI, centre_phase, reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.drag import particle
from fastpath.dissipative.drag_flight import solve_drag_flight
from fastpath.dissipative.impact import dissipative_collide
from fastpath.dissipative.short_flight import short_flight, short_window
from fastpath.dissipative.sticking import (
    DETACHES,
    NEVER,
    accumulation_tail,
    detachment,
    inelastic_impact,
)
from fastpath.elastic.flight import AUTO, flight_from, phase_error_of
from fastpath.elastic.gap import departure
from fastpath.status import CONVERGED, NOT_DEPARTING, UNCERTAIN

# state indices
PHI, V, T = 0, 1, 2  # the last impact recorded (phase in [0, 2*pi), velocity, time)
BASE_PHASE, BASE_TIME, S = 3, 4, 5  # the run's base and the time since it (departure at base + s)
SIN, COS, W = 6, 7, 8  # sine, cosine of the departure phase; relative departure velocity
VK, DETACHED = 9, 10  # absolute departure velocity; 1.0 when departing from a detachment
STATE_SIZE = 11
CARRIED = (BASE_PHASE, S, SIN, COS, W, DETACHED)  # what a step reads beyond (phi, v)

# what follows the impact of a step
NO_STICKING = 0
EPISODE = 1  # accumulation, riding, detachment: (t_acc, t_detach)
STUCK = 2  # accumulation where the particle can never leave: (t_acc, inf)

_REBASE = 1.0  # a run of short flights is summed from its start until it lasts this long
_TAIL_MARGIN = 64.0 * UNIT_ROUNDOFF * 8.0 * math.pi  # phase rounding of theta_acc, with room


@jit
def begin(state, phi0, v0, t0, physics):
    """Fill ``state`` for a departure from (phi0, v0) at time t0; return a FlightStatus code.

    With r < 1 the departure is checked here (w0 = v0 + eps*sin(phi0) beyond its rounding
    bound); otherwise the first flight checks it. The phase is reduced to [0, 2*pi) and its
    sine and cosine are libm's (an orbit carries them from collision to collision).
    """
    eps = physics.eps
    base = reduce_phase(phi0)
    state[PHI], state[V], state[T] = base, v0, t0
    state[BASE_PHASE], state[BASE_TIME], state[S] = base, t0, 0.0
    sin_th, cos_th = math.sin(base), math.cos(base)
    state[SIN], state[COS], state[VK], state[DETACHED] = sin_th, cos_th, v0, 0.0
    state[W] = v0 + eps * sin_th
    if physics.restitution == 1.0:
        return CONVERGED
    # not centred: centring fl(pi) moves it by an ulp, and w = v0 + eps*sin would carry that
    w, w_error = departure(base, sin_th, v0, eps, phase_error_of(phi0, base))
    state[W] = w
    if not w > -w_error:
        return NOT_DEPARTING
    if not w > w_error:
        return UNCERTAIN
    return CONVERGED


@jit
def departure_point(state):
    """(phi, v, t) of the next flight's departure: the last impact, or the detachment."""
    if state[DETACHED] != 0.0:
        return reduce_phase(state[BASE_PHASE]), state[VK], state[BASE_TIME]
    return state[PHI], state[V], state[T]


@jit
def copy_carried(state, carried):
    """Copy the ``CARRIED`` entries of ``state`` into ``carried`` (a sampled departure's, kept
    until its collision is recorded)."""
    for j in range(len(CARRIED)):
        carried[j] = state[CARRIED[j]]


@jit
def carried_state(phi, v, carried):
    """A state departing from (phi, v) with the ``CARRIED`` entries ``carried`` (in that order);
    the times (absolute time, base time) are 0: a step's (phi1, v1, tau) does not read them."""
    state = np.zeros(STATE_SIZE)
    state[PHI], state[V], state[VK] = phi, v, v
    for j in range(len(CARRIED)):
        state[CARRIED[j]] = carried[j]
    return state


@jit
def long_flight(theta, v, physics, method):
    """(tau, iterations, status) of an ordinary flight from the absolute state (theta, v): with
    drag ``solve_drag_flight``; without, the elastic flight from libm's sine and cosine of the
    centred phase."""
    if physics.drag != 0.0:
        return solve_drag_flight(theta, v, physics, method)
    centred = centre_phase(theta)
    tau, _, _, _, iterations, status = flight_from(
        centred, math.sin(centred), math.cos(centred), v, physics.eps, method,
        phase_error_of(theta, centred),
    )
    return tau, iterations, status


@jit
def incoming_velocity(v, physics, tau):
    """The particle's velocity at the end of a flight of length tau from velocity v."""
    if physics.drag != 0.0:
        return particle(v, physics.drag, physics.drag_law, tau)[1]
    return v - tau


@jit
def edge_within(theta, span, hole_lo):
    """Whether a hole's lower edge lies in the arc (theta, theta + span + margin] mod 2*pi."""
    for j in range(len(hole_lo)):
        d = (hole_lo[j] - theta) % TWO_PI
        if d <= span + _TAIL_MARGIN or d >= TWO_PI - _TAIL_MARGIN:
            return True
    return False


@jit
def advance(state, physics, method, detach, hole_lo):
    """Move ``state`` on by one impact; return (status, iterations, tau, sticking, t_start, t_end).

    status: CONVERGED, or the FlightStatus of a flight that could not be decided (the state is
    then unchanged: ``departure_point`` gives the departure to settle). tau: the flight time
    from the departure. sticking: NO_STICKING, EPISODE (t_start, t_end) = (t_acc, t_detach)
    after the impact, or STUCK (t_acc, inf). detach: ``sticking.detachment(physics)``. hole_lo:
    lower edges of the holes whose crossing forbids summing a tail (empty for a plain orbit).
    """
    if physics.restitution == 1.0:
        phi1, v1, tau, its, status = dissipative_collide(state[PHI], state[V], physics)
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        state[PHI], state[V], state[T] = phi1, v1, state[T] + tau
        return CONVERGED, its, tau, NO_STICKING, math.nan, math.nan
    return inelastic_advance(state, physics, method, detach, hole_lo)


@jit
def inelastic_advance(state, physics, method, detach, hole_lo):
    """``advance`` for r < 1, with or without drag (module docstring)."""
    eps, r = physics.eps, physics.restitution
    base_phase, base_time, s = state[BASE_PHASE], state[BASE_TIME], state[S]
    sin_th, cos_th, w, vk = state[SIN], state[COS], state[W], state[VK]
    w_in = 0.0
    if state[DETACHED] != 0.0:
        tau, its, status = detach.tau, detach.iterations, detach.status
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        long = True
    else:
        upper = short_window(sin_th, cos_th, w, vk, physics)
        long = not upper > 0.0
        if long:
            tau, its, status = long_flight(base_phase + s, vk, physics, method)
            if status != CONVERGED:
                return status, its, tau, NO_STICKING, math.nan, math.nan
        else:
            tau, w_in, its = short_flight(sin_th, cos_th, w, vk, physics, upper)
            if s + tau == s:  # the clock no longer moves: a hole edge within rounding
                return UNCERTAIN, its, tau, NO_STICKING, math.nan, math.nan
    s_new = s + tau
    theta = base_phase + s_new
    sin_new, cos_new = math.sin(theta), math.cos(theta)
    if long:
        w_in = incoming_velocity(vk, physics, tau) + eps * sin_new
    vk_new, w_new = inelastic_impact(-eps * sin_new, w_in, r)
    tail = accumulation_tail(sin_new, cos_new, w_new, physics)
    summed = tail == tail and not edge_within(reduce_phase(theta), tail, hole_lo)
    if summed and detach.kind != DETACHES and detach.kind != NEVER:
        return UNCERTAIN, its, tau, NO_STICKING, math.nan, math.nan  # ever detaches: undecided
    s, sin_th, cos_th, vk, w = s_new, sin_new, cos_new, vk_new, w_new
    state[DETACHED] = 0.0
    state[PHI], state[V], state[T] = reduce_phase(theta), vk, base_time + s
    if long or s > _REBASE:
        base_phase, base_time, s = reduce_phase(theta), base_time + s, 0.0
    sticking, t_start, t_end = NO_STICKING, math.nan, math.nan
    if summed:
        t_start = base_time + (s + tail)
        if detach.kind == NEVER:
            sticking, t_end = STUCK, math.inf
        else:
            theta_star = detach.phase
            stay = s + tail + reduce_phase(theta_star - (base_phase + (s + tail)))
            sticking, t_end = EPISODE, base_time + stay
            base_phase, base_time, s = theta_star, base_time + stay, 0.0
            vk, w = detach.velocity, 0.0
            state[DETACHED] = 1.0
    state[BASE_PHASE], state[BASE_TIME], state[S] = base_phase, base_time, s
    state[SIN], state[COS], state[W], state[VK] = sin_th, cos_th, w, vk
    return CONVERGED, its, tau, sticking, t_start, t_end


@jit
def carried_collide(phi, v, physics, carried):
    """(phi1, v1, tau, status) of one ``advance`` (r < 1, any drag) from the departure (phi, v)
    with the ``CARRIED`` entries ``carried``: the step an ensemble kernel made from that state."""
    state = carried_state(phi, v, carried)
    status, _, tau, _, _, _ = advance(state, physics, AUTO, detachment(physics), np.empty(0))
    return state[PHI], state[V], tau, status
