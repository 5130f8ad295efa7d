"""One particle of any description: its flight, its collision, and its state from one to the next.

The loops of ``fastpath.kernels`` (orbits, ensembles, moments) move particles with three calls:
``begin`` fills a particle's state array (the layout of ``fastpath.dissipative.carried``),
``advance`` moves it on by one collision, ``departure_point`` says where its next flight starts.
The description (``fastpath.physics``) picks the map; its class is a compile-time constant, so
each loop is compiled once per model and the elastic one carries no dissipative code:

``Elastic``      the paper's collision (``fastpath.elastic.collision``). With ``as_step`` each
                 collision is ``fastpath.step``'s, a function of the departure (phi, v) alone,
                 bit for bit: what the ensembles do, whose samples are audited by ``step``. The
                 first departure is then the phase as given, not its reduction (as ``step``).
                 Without, the sine and cosine are carried from collision to collision and the
                 solver skips the straight-line flight (``GENERAL``): what ``fastpath.orbit`` and
                 the velocity moments do (faster, the same to rounding, not ``step``'s bits).
``Holmes``       the Holmes map (flight time 2*v).
``Dissipative``  drag and restitution, sticking and detachment (``fastpath.dissipative.carried``;
                 with r < 1 a collision reads the carried state, ``fastpath.carried_step``).

``flight`` and ``step`` are the single flight and collision of ``fastpath.flight`` and
``fastpath.step`` for a description.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.dissipative import carried
from fastpath.dissipative.carried import COS, NO_STICKING, PHI, SIN, T, V
from fastpath.dissipative.drag_flight import solve_drag_flight
from fastpath.dissipative.impact import dissipative_collide
from fastpath.elastic.collision import collide, collide_from
from fastpath.elastic.flight import AUTO, GENERAL, solve_flight
from fastpath.elastic.holmes import holmes_collide
from fastpath.physics import DISSIPATIVE, ELASTIC, HOLMES, model_of
from fastpath.status import CONVERGED


@jit
def flight(physics, phi, v, method=AUTO):
    """(tau, iterations, status) of the flight from (phi, v), phi any real: the elastic flight,
    or the flight with the description's drag (restitution does not change a flight)."""
    if model_of(physics) == DISSIPATIVE and physics.drag != 0.0:
        return solve_drag_flight(physics, phi, v, method)
    return solve_flight(phi, v, physics.eps, method)


@jit
def step(physics, phi, v):
    """(phi1, v1, tau, iterations, status): one collision from (phi, v), phi any real, phi1 in
    [0, 2*pi); the collision of ``fastpath.step`` (Elastic or Dissipative)."""
    if model_of(physics) == DISSIPATIVE:
        return dissipative_collide(physics, phi, v)
    return collide(phi, v, physics.eps)


@jit
def begin(physics, state, phi0, v0, t0, as_step):
    """Fill ``state`` for a departure from (phi0, v0) at time t0; return a FlightStatus code
    (not CONVERGED only for a dissipative departure that is not certain, r < 1)."""
    status = carried.begin(physics, state, phi0, v0, t0)
    if model_of(physics) == ELASTIC and as_step:
        state[PHI] = phi0  # a step starts from the phase as given (module docstring)
    return status


@jit
def advance(physics, state, method, as_step, detach, hole_lo):
    """Move ``state`` on by one collision: (status, iterations, tau, sticking, t_start, t_end)
    as ``fastpath.dissipative.carried.advance`` (sticking NO_STICKING without dissipation; the
    state is unchanged where status is not CONVERGED). method: AUTO or LOWER_BOUND (a
    ``fastpath.elastic.flight`` code); detach: ``fastpath.dissipative.sticking.detachment``;
    hole_lo: the holes' lower edges, for the dissipative tail (``carried``)."""
    model = model_of(physics)
    if model == HOLMES:
        tau = 2.0 * state[V]
        state[PHI], state[V] = holmes_collide(state[PHI], state[V], physics.eps)
        state[T] = state[T] + tau
        return CONVERGED, 0, tau, NO_STICKING, math.nan, math.nan
    if model == ELASTIC:
        if as_step:
            phi1, v1, tau, its, status = collide(state[PHI], state[V], physics.eps, method)
            sin1, cos1 = state[SIN], state[COS]
        else:
            phi1, sin1, cos1, v1, tau, its, status = collide_from(
                state[PHI], state[SIN], state[COS], state[V], physics.eps,
                GENERAL if method == AUTO else method)
        if status != CONVERGED:
            return status, its, tau, NO_STICKING, math.nan, math.nan
        state[PHI], state[V], state[T] = phi1, v1, state[T] + tau
        state[SIN], state[COS] = sin1, cos1
        return CONVERGED, its, tau, NO_STICKING, math.nan, math.nan
    return carried.advance(physics, state, method, detach, hole_lo)


@jit
def departure_point(state):
    """(phi, v, t) of the next flight's departure (``fastpath.dissipative.carried``)."""
    return carried.departure_point(state)

