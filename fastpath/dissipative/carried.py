"""One particle, one collision: the carried state of a dissipative orbit and its step.

Orbits and ensemble kernels with drag or restitution r < 1 share this step. A particle's state
lives in a small float64 array (indices below) that ``begin`` fills and ``advance`` moves on by
one impact: the flight (with drag, ``fastpath.impact``; without drag and r < 1 the short
relative-coordinate flight of a chattering run, ``fastpath.short_flight``, or the ordinary one),
the impact v1 = (1 + r)*u - r*v_in, and, when r < 1 and the impacts from there accumulate
(``fastpath.sticking.accumulation_tail``), the summed tail and the sticking episode: the
particle rides the plate from t_acc and leaves at the detachment phase (|eps| > 1) or is stuck
for good (|eps| <= 1).

Physics covered. drag == 0: any r in (0, 1] (r = 1 is the elastic map, bit for bit). drag > 0
and r = 1: a chain of drag flights and elastic impacts (with r = 1 impacts never accumulate in
finite time). drag > 0 and r < 1 (``_drag_inelastic_advance``): the same carried relative
velocity and run bases as without drag, with the short relative-coordinate flights of
``fastpath.drag_short_flight``, certified drag flights (``fastpath.drag_flight``) otherwise, the
tail ``fastpath.drag_sticking.drag_accumulation_tail`` and the drag's sticking condition and
detachment phase (``fastpath.drag_sticking``); an accumulation where the decision "ever
detaches" is within rounding (``detach_kind`` UNDECIDED) is UNCERTAIN (state unchanged).

Without drag and r < 1 the arithmetic is that of the former loop of ``inelastic_orbit``
(the same operations in the same order): phases and times of a run of short flights are summed
from the run's start (the base) so that their roundings do not pile up, and the relative velocity
w is carried across impacts.

Holes (ensembles). The impacts of a summed tail are not computed one by one; they land at
phases between the last computed impact theta_k and the accumulation phase theta_k + T. If a
hole's lower edge lies in that arc (within T plus a rounding margin), the tail is NOT summed and
the impacts go on one by one, each tested against the holes by the caller; a run whose next
flight no longer moves the clock (the edge within rounding of the accumulation point) is
UNCERTAIN.

The carried departure. Without drag and r < 1 a step depends on more than the departure point
(phi, v) = ``departure_point(state)``: on the run's base phase and the time s since it (the
phase of the impact is base + (s + tau), not phi + tau), on the sine and cosine carried from
the last impact and on the carried relative velocity w (v + eps*sin(phi) recomputed would lose
the digits of a chattering w), and on whether the departure is a detachment. ``CARRIED`` names
these state entries; ``carried_state`` rebuilds a state from (phi, v) and them, from which
``advance`` repeats the step bit for bit (the audit of a run's sample, ``fastpath.carried_step``).
"""

import math

import numpy as np

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import TWO_PI, centre_phase, reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.drag import particle
from fastpath.dissipative.drag_flight import solve_drag_flight
from fastpath.dissipative.drag_short_flight import drag_short_flight, drag_short_window
from fastpath.dissipative.drag_sticking import (
    DETACHES,
    NEVER,
    drag_accumulation_tail,
    drag_detachment,
)
from fastpath.dissipative.impact import dissipative_collide
from fastpath.dissipative.short_flight import short_flight, short_window
from fastpath.dissipative.sticking import (
    accumulation_tail,
    can_detach,
    detachment_flight,
    detachment_phase,
    detachment_velocity,
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


def new_state():
    """An empty state array (``begin`` fills it)."""
    return np.zeros(STATE_SIZE)


@jit
def begin(state, phi0, v0, t0, eps, drag, restitution):
    """Fill ``state`` for a departure from (phi0, v0) at time t0; return a FlightStatus code.

    With r < 1 the departure is checked here (w0 = v0 + eps*sin(phi0) beyond its
    rounding bound, as ``inelastic_orbit`` always did); otherwise the first flight checks it.
    """
    base = reduce_phase(phi0)
    state[PHI], state[V], state[T] = base, v0, t0
    state[BASE_PHASE], state[BASE_TIME], state[S] = base, t0, 0.0
    sin_th, cos_th = math.sin(base), math.cos(base)
    state[SIN], state[COS], state[VK], state[DETACHED] = sin_th, cos_th, v0, 0.0
    state[W] = v0 + eps * sin_th
    if restitution == 1.0:
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
def store_carried(samples, slot, carried):
    """``carried`` into the columns after the six sample fields of ``samples[slot]``."""
    for j in range(len(carried)):
        samples[slot, 6 + j] = carried[j]


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
def detachment(eps, drag, law, restitution):
    """(tau, iterations, status, theta*, u(theta*), kind) of the flight from detachment, the same
    after every episode: computed once per physics. Without drag (``fastpath.sticking``) theta*
    and u are NaN (``_inelastic_advance`` takes them from ``fastpath.sticking``); with drag
    ``fastpath.drag_sticking.drag_detachment``. (NaN, 0, UNCERTAIN, ...) where there is none."""
    if restitution != 1.0 and drag != 0.0:
        return drag_detachment(eps, drag, law)
    kind = DETACHES if can_detach(eps) else NEVER
    if restitution == 1.0 or not can_detach(eps):
        return math.nan, 0, UNCERTAIN, math.nan, math.nan, kind
    tau, _, _, iterations, status = detachment_flight(eps)
    return tau, iterations, status, math.nan, math.nan, kind


@jit
def _long_flight(theta, v, eps, method):
    """(tau, iterations, status) of an ordinary flight from the absolute state (theta, v)."""
    centred = centre_phase(theta)
    tau, _, _, iterations, status = flight_from(
        centred, math.sin(centred), math.cos(centred), v, eps, method,
        phase_error_of(theta, centred),
    )
    return tau, iterations, status


@jit
def edge_within(theta, span, hole_lo):
    """Whether a hole's lower edge lies in the arc (theta, theta + span + margin] mod 2*pi."""
    for j in range(len(hole_lo)):
        d = (hole_lo[j] - theta) % TWO_PI
        if d <= span + _TAIL_MARGIN or d >= TWO_PI - _TAIL_MARGIN:
            return True
    return False


@jit
def advance(state, eps, drag, law, restitution, method, detach, hole_lo):
    """Move ``state`` on by one impact; return (status, iterations, tau, sticking, t_start, t_end).

    status: CONVERGED, or the FlightStatus of a flight that could not be decided (the state is
    then unchanged: ``departure_point`` gives the departure to settle). tau: the flight time
    from the departure. sticking: NO_STICKING, EPISODE (t_start, t_end) = (t_acc, t_detach)
    after the impact, or STUCK (t_acc, inf). detach: ``detachment(eps, ...)``. hole_lo: lower
    edges of the holes whose crossing forbids summing a tail (empty for a plain orbit).
    """
    if restitution == 1.0:
        phi1, v1, tau, its, status = dissipative_collide(
            state[PHI], state[V], eps, drag, law, restitution
        )
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        state[PHI], state[V], state[T] = phi1, v1, state[T] + tau
        return CONVERGED, its, tau, NO_STICKING, math.nan, math.nan
    if drag != 0.0:
        return _drag_inelastic_advance(state, eps, drag, law, restitution, method, detach,
                                       hole_lo)
    return _inelastic_advance(state, eps, restitution, method, detach, hole_lo)


@jit
def _inelastic_advance(state, eps, r, method, detach, hole_lo):
    """``advance`` without drag and r < 1 (the module docstring; former ``inelastic_orbit``)."""
    base_phase, base_time, s = state[BASE_PHASE], state[BASE_TIME], state[S]
    sin_th, cos_th, w, vk = state[SIN], state[COS], state[W], state[VK]
    w_in = 0.0
    if state[DETACHED] != 0.0:
        tau, its, status = detach[0], detach[1], detach[2]
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        long = True
    else:
        upper = short_window(sin_th, cos_th, w, eps)
        long = not upper > 0.0
        if long:
            tau, its, status = _long_flight(base_phase + s, vk, eps, method)
            if status != CONVERGED:
                return status, its, tau, NO_STICKING, math.nan, math.nan
        else:
            tau, w_in, its = short_flight(sin_th, cos_th, w, eps, upper)
            if s + tau == s:  # the clock no longer moves: a hole edge within rounding
                return UNCERTAIN, its, tau, NO_STICKING, math.nan, math.nan
    state[DETACHED] = 0.0
    s += tau
    theta = base_phase + s
    sin_th, cos_th = math.sin(theta), math.cos(theta)
    if long:
        w_in = (vk - tau) + eps * sin_th
    vk, w = inelastic_impact(-eps * sin_th, w_in, r)
    state[PHI], state[V], state[T] = reduce_phase(theta), vk, base_time + s
    if long or s > _REBASE:
        base_phase, base_time, s = reduce_phase(theta), base_time + s, 0.0
    sticking, t_start, t_end = NO_STICKING, math.nan, math.nan
    tail = accumulation_tail(sin_th, cos_th, w, eps, r)
    if tail == tail and not edge_within(state[PHI], tail, hole_lo):
        t_start = base_time + (s + tail)
        if not can_detach(eps):
            sticking, t_end = STUCK, math.inf
        else:
            theta_star = detachment_phase(eps)
            stay = s + tail + reduce_phase(theta_star - (base_phase + (s + tail)))
            sticking, t_end = EPISODE, base_time + stay
            base_phase, base_time, s = theta_star, base_time + stay, 0.0
            vk, w = detachment_velocity(eps), 0.0
            state[DETACHED] = 1.0
    state[BASE_PHASE], state[BASE_TIME], state[S] = base_phase, base_time, s
    state[SIN], state[COS], state[W], state[VK] = sin_th, cos_th, w, vk
    return CONVERGED, its, tau, sticking, t_start, t_end


@jit
def _drag_inelastic_advance(state, eps, k, law, r, method, detach, hole_lo):
    """``advance`` with drag and r < 1: ``_inelastic_advance`` with the drag's short flights,
    flights, tail and detachment (module docstring)."""
    base_phase, base_time, s = state[BASE_PHASE], state[BASE_TIME], state[S]
    sin_th, cos_th, w, vk = state[SIN], state[COS], state[W], state[VK]
    w_in = 0.0
    if state[DETACHED] != 0.0:
        tau, its, status = detach[0], detach[1], detach[2]
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        long = True
    else:
        upper = drag_short_window(sin_th, cos_th, w, vk, eps, k, law)
        long = not upper > 0.0
        if long:
            tau, its, status = solve_drag_flight(base_phase + s, vk, eps, k, law, method)
            if status != CONVERGED:
                return status, its, tau, NO_STICKING, math.nan, math.nan
        else:
            tau, w_in, its = drag_short_flight(sin_th, cos_th, w, vk, eps, k, law, upper)
            if s + tau == s:
                return UNCERTAIN, its, tau, NO_STICKING, math.nan, math.nan
    s_new = s + tau
    theta = base_phase + s_new
    sin_new, cos_new = math.sin(theta), math.cos(theta)
    if long:
        w_in = particle(vk, k, law, tau)[1] + eps * sin_new
    vk_new, w_new = inelastic_impact(-eps * sin_new, w_in, r)
    tail = drag_accumulation_tail(sin_new, cos_new, w_new, eps, k, law, r)
    summed = tail == tail and not edge_within(reduce_phase(theta), tail, hole_lo)
    if summed and detach[5] != DETACHES and detach[5] != NEVER:
        return UNCERTAIN, its, tau, NO_STICKING, math.nan, math.nan  # ever detaches: undecided
    s, sin_th, cos_th, vk, w = s_new, sin_new, cos_new, vk_new, w_new
    state[DETACHED] = 0.0
    state[PHI], state[V], state[T] = reduce_phase(theta), vk, base_time + s
    if long or s > _REBASE:
        base_phase, base_time, s = reduce_phase(theta), base_time + s, 0.0
    sticking, t_start, t_end = NO_STICKING, math.nan, math.nan
    if summed:
        t_start = base_time + (s + tail)
        if detach[5] == NEVER:
            sticking, t_end = STUCK, math.inf
        else:
            theta_star = detach[3]
            stay = s + tail + reduce_phase(theta_star - (base_phase + (s + tail)))
            sticking, t_end = EPISODE, base_time + stay
            base_phase, base_time, s = theta_star, base_time + stay, 0.0
            vk, w = detach[4], 0.0
            state[DETACHED] = 1.0
    state[BASE_PHASE], state[BASE_TIME], state[S] = base_phase, base_time, s
    state[SIN], state[COS], state[W], state[VK] = sin_th, cos_th, w, vk
    return CONVERGED, its, tau, sticking, t_start, t_end


@jit
def carried_collide(phi, v, eps, drag, law, restitution, carried):
    """(phi1, v1, tau, status) of one ``advance`` (r < 1, any drag) from the departure (phi, v)
    with the ``CARRIED`` entries ``carried``: the step an ensemble kernel made from that state."""
    state = carried_state(phi, v, carried)
    detach = detachment(eps, drag, law, restitution)
    status, _, tau, _, _, _ = advance(
        state, eps, drag, law, restitution, AUTO, detach, np.empty(0)
    )
    return state[PHI], state[V], tau, status
