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

Compiling per model. numba types every branch of a function before LLVM folds the branches it
can decide, so a branch on ``model_of`` would still compile the dissipative solvers into the
elastic loops (most of their compile time). The functions here therefore choose a model's
implementation when the calling loop is typed (numba's ``overload``, by the class of the
description): only that model's code is compiled, and the loops stay one loop for every model.
"""

import math

from numba.core import types

from fastpath.arithmetic.jit import jit, typed_overload
from fastpath.dissipative import carried
from fastpath.dissipative.carried import COS, NO_STICKING, PHI, SIN, T, V
from fastpath.dissipative.drag_flight import solve_drag_flight
from fastpath.dissipative.impact import dissipative_collide
from fastpath.dissipative.sticking import (
    DETACHES,
    NEVER,
    Detachment,
    can_detach,
    detachment,
)
from fastpath.elastic.collision import CARRIED_SINE_ERROR, collide, collide_from
from fastpath.elastic.flight import AUTO, GENERAL, solve_flight
from fastpath.elastic.holmes import holmes_collide
from fastpath.physics import ELASTIC, Dissipative, Elastic, Holmes, model_of
from fastpath.status import CONVERGED, UNCERTAIN


@jit
def flight(phi, v, physics, method=AUTO):
    """(tau, iterations, status) of the flight from (phi, v), phi any real: the elastic flight,
    or the flight with the description's drag (restitution does not change a flight)."""
    return _flight(phi, v, physics, method)


def _flight(phi, v, physics, method):
    """``flight``, compiled for the description's model only (module docstring)."""


@typed_overload(_flight)
def _flight_of_model(phi, v, physics, method):
    if physics.instance_class is Dissipative:
        def dissipative_flight(phi, v, physics, method):
            if physics.drag != 0.0:
                return solve_drag_flight(phi, v, physics, method)
            return solve_flight(phi, v, physics.eps, method)
        return dissipative_flight
    return lambda phi, v, physics, method: solve_flight(phi, v, physics.eps, method)


@jit
def step(phi, v, physics):
    """(phi1, v1, tau, iterations, status): one collision from (phi, v), phi any real, phi1 in
    [0, 2*pi); the collision of ``fastpath.step`` (Elastic or Dissipative)."""
    return _step(phi, v, physics)


def _step(phi, v, physics):
    """``step``, compiled for the description's model only (module docstring)."""


@typed_overload(_step)
def _step_of_model(phi, v, physics):
    if physics.instance_class is Dissipative:
        return lambda phi, v, physics: dissipative_collide(phi, v, physics)
    return lambda phi, v, physics: collide(phi, v, physics.eps, AUTO)


@jit
def begin(state, phi0, v0, t0, physics, as_step):
    """Fill ``state`` for a departure from (phi0, v0) at time t0; return a FlightStatus code
    (not CONVERGED only for a dissipative departure that is not certain, r < 1)."""
    status = carried.begin(state, phi0, v0, t0, physics)
    if model_of(physics) == ELASTIC and as_step:
        state[PHI] = phi0  # a step starts from the phase as given (module docstring)
    return status


def advance(state, physics, method, as_step, detach, hole_lo):
    """Move ``state`` on by one collision: (status, iterations, tau, sticking, t_start, t_end)
    as ``fastpath.dissipative.carried.advance`` (sticking NO_STICKING without dissipation; the
    state is unchanged where status is not CONVERGED). method: AUTO or LOWER_BOUND (a
    ``fastpath.elastic.flight`` code); detach: ``detachment_of(physics)``; hole_lo: the holes'
    lower edges, for the dissipative tail (``carried``).

    For compiled loops only: the overload below compiles the description's model only, and
    where ``as_step`` is a constant of the loop (an escape lane: True, an orbit: False) only
    that kind of elastic collision (module docstring).
    """
    raise TypeError("advance is called from compiled code only")


@typed_overload(advance, prefer_literal=True)
def _advance_of_model(state, physics, method, as_step, detach, hole_lo):
    if physics.instance_class is Holmes:
        return lambda state, physics, method, as_step, detach, hole_lo: holmes_advance(
            state, physics.eps)
    if physics.instance_class is not Elastic:
        return lambda state, physics, method, as_step, detach, hole_lo: carried.advance(
            state, physics, method, detach, hole_lo)
    if isinstance(as_step, types.BooleanLiteral) and as_step.literal_value:
        return lambda state, physics, method, as_step, detach, hole_lo: step_advance(
            state, physics.eps, method)
    if isinstance(as_step, types.BooleanLiteral):
        return lambda state, physics, method, as_step, detach, hole_lo: orbit_advance(
            state, physics.eps, method)

    def either_advance(state, physics, method, as_step, detach, hole_lo):
        if as_step:
            return step_advance(state, physics.eps, method)
        return orbit_advance(state, physics.eps, method)
    return either_advance


@jit
def holmes_advance(state, eps):
    """``advance`` with the Holmes map (flight time 2*v)."""
    tau = 2.0 * state[V]
    state[PHI], state[V] = holmes_collide(state[PHI], state[V], eps)
    state[T] = state[T] + tau
    return CONVERGED, 0, tau, NO_STICKING, math.nan, math.nan


@jit
def step_advance(state, eps, method):
    """``advance`` with the paper's map as ``fastpath.step`` computes it (module docstring)."""
    phi1, v1, tau, its, status = collide(state[PHI], state[V], eps, method)
    return _moved(state, status, its, phi1, v1, tau, state[SIN], state[COS])


@jit
def orbit_advance(state, eps, method):
    """``advance`` with the paper's map as an orbit computes it: the sine and cosine carried
    from collision to collision, the straight-line flight skipped (module docstring)."""
    phi1, sin1, cos1, v1, tau, its, status = collide_from(
        state[PHI], state[SIN], state[COS], state[V], eps,
        GENERAL if method == AUTO else method, CARRIED_SINE_ERROR)
    return _moved(state, status, its, phi1, v1, tau, sin1, cos1)


@jit
def _moved(state, status, its, phi1, v1, tau, sin1, cos1):
    """An elastic collision into ``state`` if CONVERGED: ``advance``'s answer."""
    if status != CONVERGED:
        return status, its, tau, NO_STICKING, math.nan, math.nan
    state[PHI], state[V], state[T] = phi1, v1, state[T] + tau
    state[SIN], state[COS] = sin1, cos1
    return CONVERGED, its, tau, NO_STICKING, math.nan, math.nan


@jit
def detachment_of(physics):
    """``fastpath.dissipative.sticking.detachment`` of a dissipative description; for the elastic
    and Holmes maps, which never stick, the same record of no detachment without compiling its
    solver (module docstring)."""
    return _detachment(physics)


def _detachment(physics):
    """``detachment_of`` (its overload below chooses the model's implementation)."""


@typed_overload(_detachment)
def _detachment_of_model(physics):
    if physics.instance_class is Dissipative:
        return lambda physics: detachment(physics)
    def no_detachment(physics):  # as ``detachment`` computes it for these models
        kind = DETACHES if can_detach(physics.eps) else NEVER
        return Detachment(math.nan, 0, UNCERTAIN, math.nan, math.nan, kind)
    return no_detachment


@jit
def departure_point(state):
    """(phi, v, t) of the next flight's departure (``fastpath.dissipative.carried``)."""
    return carried.departure_point(state)

