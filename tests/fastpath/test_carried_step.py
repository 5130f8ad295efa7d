"""``fastpath.carried_step``: one step of a chattering orbit (r < 1) from its carried state.

Ensemble kernels move particles with ``fastpath.dissipative.carried.advance``, whose step reads
more than the departure (phi, v): the run's base phase and time since it, the carried sine, cosine
and relative velocity w, and whether the departure is a detachment. ``carried_step`` must repeat
every such step bit for bit from (phi, v) and those entries (that is what ``bouncer verify``
relies on), and refuse a carried state that is not a departure from (phi, v).
"""

import math

import numpy as np
import pytest

import fastpath
from fastpath.dissipative.carried import (
    CARRIED,
    DETACHED,
    PHI,
    STATE_SIZE,
    STUCK,
    S,
    V,
    W,
    advance,
    begin,
    departure_point,
)
from fastpath.dissipative.sticking import detachment
from fastpath.elastic.flight import AUTO
from fastpath.physics import LAWS, NONE, dissipative
from fastpath.status import CONVERGED


def steps_of(phi0, v0, eps, r, n, k=0.0, law=NONE):
    """[(phi, v, carried, (phi1, v1, tau))] of up to n advance steps from (phi0, v0)."""
    state = np.zeros(STATE_SIZE)
    physics = dissipative(eps, k, law, r)
    assert begin(state, phi0, v0, 0.0, physics) == CONVERGED
    detach, no_holes = detachment(physics), np.empty(0)
    out = []
    for _ in range(n):
        phi, v, _ = departure_point(state)
        carried = tuple(float(state[j]) for j in CARRIED)
        status, _, tau, kind, _, _ = advance(state, physics, AUTO, detach, no_holes)
        assert status == CONVERGED
        out.append((phi, v, carried, (state[PHI], state[V], tau)))
        if kind == STUCK:
            break
    return out


@pytest.mark.parametrize(("phi0", "v0", "eps", "r", "n"), [
    (4.0, 3.0, 0.6, 0.8, 3000),   # chattering runs ending stuck for good (|eps| <= 1)
    (4.0, 3.0, 1.5, 0.8, 3000),   # sticking episodes and departures from detachment
    (1.0, 2.0, -1.5, 0.5, 3000),
    (3.9, 2.5, 0.95, 0.3, 3000),
])
def test_carried_step_repeats_every_step_of_the_kernel(phi0, v0, eps, r, n):
    steps = steps_of(phi0, v0, eps, r, n)
    run, detached = 0, 0
    for phi, v, carried, kernel in steps:
        assert fastpath.carried_step(phi, v, eps, carried, restitution=r) == kernel
        run += carried[CARRIED.index(S)] != 0.0
        detached += carried[CARRIED.index(DETACHED)] != 0.0
    # the cases that (phi, v) alone cannot reproduce were exercised
    assert run > 0
    if abs(eps) > 1.0:
        assert detached > 0


@pytest.mark.parametrize(("phi0", "v0", "eps", "r", "k", "law"), [
    (4.0, 3.0, 0.6, 0.8, 0.1, "linear"),  # stuck for good (0.6*sqrt(1.01) < 1)
    (4.0, 3.0, 1.5, 0.8, 0.1, "linear"),  # episodes and departures from the drag's theta*
    (4.0, 3.0, 1.5, 0.8, 0.1, "quadratic"),
    (4.0, 3.0, 0.9, 0.8, 0.6, "linear"),  # |eps| < 1 detaching through drag
])
def test_carried_step_repeats_every_step_with_drag(phi0, v0, eps, r, k, law):
    steps = steps_of(phi0, v0, eps, r, 3000, k, LAWS[law])
    run, detached = 0, 0
    for phi, v, carried, kernel in steps:
        got = fastpath.carried_step(phi, v, eps, carried, restitution=r, drag=k, drag_law=law)
        assert got == kernel
        run += carried[CARRIED.index(S)] != 0.0
        detached += carried[CARRIED.index(DETACHED)] != 0.0
    assert run > 0
    if abs(eps) * (1.0 + k) > 1.05:
        assert detached > 0


def one_step(eps=0.6, r=0.8, k=50):
    """A departure inside a run of short flights (s > 0) of the eps, r orbit from (4, 3)."""
    for phi, v, carried, kernel in steps_of(4.0, 3.0, eps, r, 3000)[k:]:
        if carried[CARRIED.index(S)] != 0.0:
            return phi, v, list(carried), kernel
    raise AssertionError("no run of short flights")


def changed(carried, entry, value):
    out = list(carried)
    out[CARRIED.index(entry)] = value
    return out


def test_a_carried_state_that_is_not_the_departure_is_refused():
    phi, v, carried, _ = one_step()
    w = carried[CARRIED.index(W)]
    with pytest.raises(ValueError, match="carried w="):
        fastpath.carried_step(phi, v, 0.6, changed(carried, W, 2.0 * w), restitution=0.8)
    s = carried[CARRIED.index(S)]
    with pytest.raises(ValueError, match="carried base_phase="):
        fastpath.carried_step(phi, v, 0.6, changed(carried, S, s + 1e-9), restitution=0.8)
    with pytest.raises(ValueError, match="detached=0.5"):
        fastpath.carried_step(phi, v, 0.6, changed(carried, DETACHED, 0.5), restitution=0.8)
    with pytest.raises(ValueError, match="is not the detachment"):
        fastpath.carried_step(phi, v, 0.6, changed(carried, DETACHED, 1.0), restitution=0.8)


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"restitution": 1.0}, "restitution=1.0"),
    ({"restitution": 1.5}, "restitution=1.5"),
])
def test_physics_without_a_carried_state_is_refused(kwargs, name):
    phi, v, carried, _ = one_step()
    with pytest.raises(ValueError, match=name):
        fastpath.carried_step(phi, v, 0.6, carried, **kwargs)


@pytest.mark.parametrize(("carried", "name"), [
    ([4.0, 0.0, 0.1, 0.9, 1.0], "6 numbers"),
    ([math.nan, 0.0, 0.1, 0.9, 1.0, 0.0], "base_phase"),
    ([4.0, 0.0, 0.1, 0.9, math.inf, 0.0], "w"),
])
def test_bad_carried_names_the_value(carried, name):
    with pytest.raises(ValueError, match=name):
        fastpath.carried_step(4.0, 3.0, 0.6, carried, restitution=0.8)
