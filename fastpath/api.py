"""Public functions of the fast path: validate, broadcast, call the kernels."""

from dataclasses import dataclass, field

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import jit, parallel_jit
from fastpath.arithmetic.phase import reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.carried import CARRIED, carried_collide
from fastpath.elastic.collision import collide
from fastpath.elastic.flight import AUTO, METHODS, departure_of
from fastpath.elastic.gap import departure_verdict
from fastpath.elastic.holmes import holmes_collide
from fastpath.inputs import float_inputs, integer, model_physics, physics_options, scalar_inputs
from fastpath.kernels.arrays import Flags, MomentGrid, MomentSums, OrbitArrays, Sample, Starts
from fastpath.kernels.moments import Moments, moments_chunk
from fastpath.kernels.orbit import orbit_loop
from fastpath.kernels.particle import flight as flight_of
from fastpath.kernels.particle import step as step_of
from fastpath.physics import Holmes, dissipative, elastic, with_eps
from fastpath.status import (
    CONVERGED,
    ITERATION_LIMIT,
    MAX_ITERATIONS,
    NOT_DEPARTING,
    OVERFLOW,
    STATUS_DTYPE,
    FlightStatus,
    UncertainCollision,
)

# The public model names (``orbit``, ``moments``) and the defaults of the physics keywords
# (the elastic bouncer of the paper); ``_elastic`` recognises the defaults by value before any
# validation, so the elastic call skips ``physics_options``.
DEFAULT_DRAG, DEFAULT_DRAG_LAW, DEFAULT_RESTITUTION = 0.0, "linear", 1.0


def _elastic(drag, drag_law, restitution):
    """True for the elastic defaults given as a float 0, the str "linear" and a float 1 (any
    other type, e.g. an array, goes through ``physics_options``)."""
    return (type(drag) is float and type(drag_law) is str and type(restitution) is float
            and drag == DEFAULT_DRAG and drag_law == DEFAULT_DRAG_LAW
            and restitution == DEFAULT_RESTITUTION)


@dataclass(frozen=True)
class FlightResult:
    """Flight times with what the solver knows about each.

    ``tau``: the flight time (NaN where there is none); ``iterations``: gap evaluations spent;
    ``status``: a ``FlightStatus`` for a scalar flight, an int8 array of ``FlightStatus`` codes
    for arrays (``FlightStatus(code)`` names one).
    """

    tau: np.ndarray | float
    iterations: np.ndarray | int
    status: np.ndarray | FlightStatus


@dataclass(frozen=True)
class Orbit:
    """Successive collisions: phases phi in [0, 2*pi), velocities v, times t since the start.

    ``iterations`` holds the lower-bound steps of each exact flight (None for the Holmes map);
    ``status`` is CONVERGED, or the status of the flight that stopped the orbit early.
    ``sticking`` (restitution < 1): rows (t_start, t_end) of the episodes where the particle
    rides the plate, from the accumulation of a chattering sequence to the detachment, t_end =
    inf when it never leaves; ``stopped``: "collisions" when the orbit ends after the n
    collisions asked for (or at a flight it could not decide, see ``status``), "stuck" when it
    ends stuck for good. phi, v, t hold the impacts computed (``fastpath.orbit``).
    """

    phi: np.ndarray
    v: np.ndarray
    t: np.ndarray
    iterations: np.ndarray | None
    status: FlightStatus
    model: str
    eps: float
    sticking: np.ndarray = field(default_factory=lambda: np.empty((0, 2)))
    stopped: str = "collisions"


@parallel_jit
def _flights(phi, v, eps, physics, method, tau, iterations, status):
    """(tau, iterations, status)[i] of the flight from (phi[i], v[i]) at eps[i]."""
    for i in prange(len(phi)):
        tau[i], iterations[i], status[i] = flight_of(phi[i], v[i], with_eps(physics, eps[i]),
                                                     method)


@parallel_jit
def _steps(phi, v, eps, physics, phi1, v1, tau, status):
    """(phi1, v1, tau, status)[i] of one collision from (phi[i], v[i]) at eps[i]."""
    for i in prange(len(phi)):
        phi1[i], v1[i], tau[i], _, status[i] = step_of(phi[i], v[i], with_eps(physics, eps[i]))


@parallel_jit
def _holmes_steps(phi, v, eps, phi1, v1, status):
    """(phi1, v1, status)[i] of the Holmes map from (phi[i], v[i]) at eps[i]."""
    for i in prange(len(phi)):
        status[i] = departure_status(phi[i], v[i], eps[i])
        phi1[i], v1[i] = holmes_collide(reduce_phase(phi[i]), v[i], eps[i])


@jit
def departure_status(phi, v, eps):
    """CONVERGED for a certain departure, NOT_DEPARTING, UNCERTAIN (w0 within rounding of 0)."""
    return departure_verdict(*departure_of(phi, v, eps))


def _shaped(shape, scalar, *arrays):
    if scalar:
        return tuple(a[0].item() for a in arrays)
    return tuple(a.reshape(shape) for a in arrays)


def _raise_on_status(status, phi, v, eps):
    """ValueError for non-departures, UncertainCollision for undecidable flights."""

    def state(i):
        return f"phi={float(phi[i])!r}, v={float(v[i])!r}, eps={float(eps[i])!r} (element {i})"

    def w0_text(i):
        w0, bound = departure_of(float(phi[i]), float(v[i]), float(eps[i]))
        return f"w0 = v + eps*sin(phi) computed as {w0!r} with rounding error <= {bound:.3g}"

    status = np.asarray(status)
    overflow = status == OVERFLOW
    if overflow.any():
        i = int(np.argmax(overflow))
        raise ValueError(f"overflow: an intermediate of the flight (v**2, t*v, ...) exceeds"
                         f" float64 at {state(i)}; inputs out of range")
    not_departing = status == NOT_DEPARTING
    if not_departing.any():
        i = int(np.argmax(not_departing))
        raise ValueError(f"not a departure: {w0_text(i)}, so w0 < 0 or w0 = 0 for certain, at"
                         f" {state(i)}; the particle does not leave the plate")
    undecided = status != CONVERGED
    if undecided.any():
        i = int(np.argmax(undecided))
        name = FlightStatus(int(status[i])).name
        w0, bound = departure_of(float(phi[i]), float(v[i]), float(eps[i]))
        why = f" ({w0_text(i)}: departure or not)" if abs(w0) <= bound else ""
        if status[i] == MAX_ITERATIONS:
            what = (f"not decided within the solver's budget of {ITERATION_LIMIT} gap"
                    f" evaluations ({name})")
        else:
            what = f"that float64 cannot decide ({name})"
        raise UncertainCollision(
            f"{int(undecided.sum())} flight(s) {what}, first at {state(i)}{why}; use"
            " fastpath.flight() to inspect the status and verify.flight_time() to settle them"
        )


def _method(method):
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    return METHODS[method]


def _flight_arrays(phi, v, eps, code, described):
    """(tau, iterations, status, inputs, shape, scalar) of the flights, elastic or with drag."""
    (phi_a, v_a, eps_a), shape, scalar = float_inputs(phi=phi, v=v, eps=eps)
    n = len(phi_a)
    out = (np.empty(n), np.empty(n, np.int64), np.empty(n, STATUS_DTYPE))
    _flights(phi_a, v_a, eps_a, described, code, *out)
    return (*out, (phi_a, v_a, eps_a), shape, scalar)


def _scalar_flight(scalars, code, described):
    if described is None:
        # the flight of ``step`` (``collide`` takes it from ``solve_flight``'s arithmetic, bit for
        # bit): a scalar flight and a scalar step share one compiled kernel
        _, _, tau, iterations, status = collide(*scalars, code)
        return tau, iterations, status
    return flight_of(scalars[0], scalars[1], with_eps(described, scalars[2]), code)


def _flight_physics(drag, drag_law, restitution):
    """The description a flight needs, None for the elastic defaults (their scalar path calls
    the elastic solver directly). A restitution other than 1 is refused: it does not act on a
    flight, and a caller who passes one expects it to."""
    if _elastic(drag, drag_law, restitution):
        return None
    drag, law, restitution = physics_options(drag, drag_law, restitution)
    if restitution != 1.0:
        raise ValueError(f"restitution={restitution!r} does not act on a flight (only at its"
                         " impact): flight and flight_time take restitution 1; step and orbit"
                         " apply it")
    return None if drag == 0.0 else dissipative(0.0, drag, law, 1.0)


def flight(phi, v, eps, *, method="auto", drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW,
           restitution=DEFAULT_RESTITUTION):
    """Flight times with their iteration counts and statuses: a ``FlightResult``; never raises
    for a status (non-departures come back as NOT_DEPARTING with tau NaN).

    Parameters (phi, v, eps broadcast; a scalar call gives scalars):
        phi: departure phase (any finite real, radians).
        v: the particle's velocity at departure.
        eps: the plate's amplitude (position eps*cos(t)).
        method: "auto" (bracketed Halley where the gap is concave, |eps| <= 1; the paper's
            lower-bound steps otherwise) or "lower_bound" (the paper's lower-bound steps
            everywhere).
        drag, drag_law: air drag eta(V) = drag*V ("linear") or drag*V*|V| ("quadratic") during
            the flight (``fastpath.dissipative.drag``).
        restitution: only 1 (the default): restitution acts at impacts, not on a flight
            (``step`` and ``orbit`` take it).
    ValueError for inputs that are not finite reals, shapes that do not broadcast, an unknown
    method, bad physics keywords.
    """
    code = _method(method)
    described = _flight_physics(drag, drag_law, restitution)
    scalars = scalar_inputs(phi=phi, v=v, eps=eps)
    if scalars is not None:
        tau, iterations, status = _scalar_flight(scalars, code, described)
        return FlightResult(tau, iterations, FlightStatus(status))
    tau, iterations, status, _, shape, scalar = _flight_arrays(
        phi, v, eps, code, elastic(0.0) if described is None else described)
    return FlightResult(*_shaped(shape, scalar, tau, iterations, status))


def flight_time(phi, v, eps, *, drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW,
                restitution=DEFAULT_RESTITUTION):
    """Smallest positive root tau of d(tau) = eps*(cos(phi) - cos(phi+tau)) + tau*(v - tau/2).

    Parameters as for ``flight`` (phi, v, eps broadcast; scalars give a float; method "auto"):
    drag and drag_law the air drag (with drag > 0 the particle's part tau*(v - tau/2) is its
    displacement under drag, ``fastpath.dissipative.drag``); restitution must be 1 (it does not
    act on a flight).
    Raises ValueError for inputs that are not finite reals, w0 = v + eps*sin(phi) <= 0 or an
    overflow, and UncertainCollision where float64 cannot decide the flight (``verify``
    settles it).
    """
    described = _flight_physics(drag, drag_law, restitution)
    scalars = scalar_inputs(phi=phi, v=v, eps=eps)
    if scalars is not None:
        tau, _, status = _scalar_flight(scalars, METHODS["auto"], described)
        if status != CONVERGED:
            _raise_on_status(np.array([status]), *([x] for x in scalars))
        return tau
    tau, _, status, inputs, shape, scalar = _flight_arrays(
        phi, v, eps, METHODS["auto"], elastic(0.0) if described is None else described)
    _raise_on_status(status, *inputs)
    return _shaped(shape, scalar, tau)[0]


def step(phi, v, eps, *, drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW,
         restitution=DEFAULT_RESTITUTION):
    """One collision of the exact map: (phi1, v1, tau), phi1 = (phi + tau) mod 2*pi in [0, 2*pi),
    v1 = tau - v - 2*eps*sin(phi + tau).

    Parameters (phi, v, eps broadcast; scalars give floats):
        phi, v, eps: the departure phase, the velocity, the plate's amplitude (as ``flight``).
        drag, drag_law: air drag during the flight (as ``flight``).
        restitution: r in (0, 1]; the impact gives v1 = (1 + r)*u - r*v_in, u = -eps*sin(phi1)
            the plate's velocity and v_in the particle's (``fastpath.dissipative.impact``).
    Errors as for ``flight_time``.
    """
    described = None
    if not _elastic(drag, drag_law, restitution):
        drag, law, restitution = physics_options(drag, drag_law, restitution)
        if drag != 0.0 or restitution != 1.0:
            described = dissipative(0.0, drag, law, restitution)
    scalars = scalar_inputs(phi=phi, v=v, eps=eps)
    if scalars is not None:
        if described is None:
            phi1, v1, tau, _, status = collide(*scalars, AUTO)
        else:
            phi1, v1, tau, _, status = step_of(*scalars[:2], with_eps(described, scalars[2]))
        if status != CONVERGED:
            _raise_on_status(np.array([status]), *([x] for x in scalars))
        return phi1, v1, tau
    (phi_a, v_a, eps_a), shape, scalar = float_inputs(phi=phi, v=v, eps=eps)
    n = len(phi_a)
    out = (np.empty(n), np.empty(n), np.empty(n), np.empty(n, STATUS_DTYPE))
    _steps(phi_a, v_a, eps_a, elastic(0.0) if described is None else described, *out)
    _raise_on_status(out[3], phi_a, v_a, eps_a)
    return _shaped(shape, scalar, *out[:3])


CARRIED_NAMES = ("base_phase", "s", "sin", "cos", "w", "detached")  # ``advance.CARRIED``


def _check_carried(phi, v, eps, carried):
    """ValueError unless ``carried`` is a departure state of (phi, v) (``carried_step``)."""
    if len(carried) != len(CARRIED):
        raise ValueError(f"carried must hold {len(CARRIED)} numbers {CARRIED_NAMES}, got"
                         f" {len(carried)}")
    values = scalar_inputs(**dict(zip(CARRIED_NAMES, carried, strict=True)))
    if values is None:
        raise ValueError(f"carried must hold real scalars, got {tuple(carried)!r}")
    base, s, sin, _, w, detached = values
    if detached not in (0.0, 1.0):
        raise ValueError(f"carried detached must be 0 or 1, got detached={detached!r}")
    if detached == 1.0:
        if not (s == 0.0 and w == 0.0 and reduce_phase(base) == phi):
            raise ValueError(f"carried s={s!r}, w={w!r}, base_phase={base!r} is not the"
                             f" detachment (s = w = 0, base_phase = phi) at phi={phi!r}")
        return
    if reduce_phase(base + s) != phi:
        raise ValueError(f"carried base_phase={base!r} + s={s!r} is not the departure phase"
                         f" phi={phi!r} (mod 2*pi)")
    # v = fl(u + w), u = fl(-eps*sin): v + eps*sin gives w back to u*(|v| + |w0|)/(1 - u);
    # twice that covers the second-order terms
    w0 = v + eps * sin
    if not abs(w - w0) <= 2.0 * UNIT_ROUNDOFF * (abs(v) + abs(w0)):
        raise ValueError(f"carried w={w!r} is not v + eps*sin = {w0!r} to rounding (v={v!r},"
                         f" sin={sin!r}, eps={eps!r})")


def carried_step(phi, v, eps, carried, *, drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW,
                 restitution=DEFAULT_RESTITUTION):
    """One collision of a chattering orbit (r < 1, any drag) from its carried state: (phi1, v1,
    tau), the step an orbit or ensemble kernel made (``fastpath.dissipative.carried``), bit for
    bit.

    Parameters: phi, v, eps (scalars) the departure and the plate's amplitude; ``carried`` the six
    carried entries below; drag, drag_law, restitution as for ``step`` (restitution < 1).

    Such a step reads more than (phi, v): ``carried`` = (base_phase, s, sin, cos, w, detached),
    the phase of the impact being base_phase + (s + tau), sin and cos those of the last impact,
    w the carried relative velocity v + eps*sin (kept to full relative precision while the
    impacts accumulate), detached 1.0 for a departure from a sticking episode (w = 0).
    ValueError for scalars that are not finite, a restitution of 1 (its steps are ``step``'s),
    and a ``carried`` that is not a departure from (phi, v): base_phase + s must
    reduce to phi, and w equal v + eps*sin to the rounding of v = u + w. Flights float64 cannot
    decide raise ``UncertainCollision`` as for ``step``.
    """
    drag, law, restitution = physics_options(drag, drag_law, restitution)
    if restitution == 1.0:
        raise ValueError(f"carried_step needs restitution < 1 (otherwise a step reads (phi, v)"
                         f" only: use step), got restitution={restitution!r}")
    scalars = scalar_inputs(phi=phi, v=v, eps=eps)
    if scalars is None:
        raise ValueError("carried_step takes scalar phi, v and eps")
    phi, v, eps = scalars
    _check_carried(phi, v, eps, tuple(carried))
    phi1, v1, tau, status = carried_collide(phi, v, dissipative(eps, drag, law, restitution),
                                            np.array(carried, dtype=float))
    if status != CONVERGED:
        _raise_on_status(np.array([status]), [phi], [v], [eps])
    return phi1, v1, tau


def holmes_step(phi, v, eps):
    """One step of the Holmes map: phi1 = (phi + 2v) mod 2*pi, v1 = |v - 2*eps*sin(phi1)|.

    Parameters: phi, v, eps as for ``step`` (broadcast; any finite phi: it is reduced to
    [0, 2*pi) first, as ``step`` does). phi + 2v is then reduced exactly: phi1 is good to a few
    ulps of 2*pi at any v. The state must be a departure (w0 = v + eps*sin(phi) > 0); errors as
    for ``flight_time``.
    """
    scalars = scalar_inputs(phi=phi, v=v, eps=eps)
    if scalars is not None:
        status = departure_status(*scalars)
        if status != CONVERGED:
            _raise_on_status(np.array([status]), *([x] for x in scalars))
        phi, v, eps = scalars
        return holmes_collide(reduce_phase(phi), v, eps)
    (phi_a, v_a, eps_a), shape, scalar = float_inputs(phi=phi, v=v, eps=eps)
    n = len(phi_a)
    out = (np.empty(n), np.empty(n), np.empty(n, STATUS_DTYPE))
    _holmes_steps(phi_a, v_a, eps_a, *out)
    _raise_on_status(out[2], phi_a, v_a, eps_a)
    return _shaped(shape, scalar, *out[:2])


def orbit(phi0, v0, eps, n, *, model="exact", on_uncertain="raise", method="auto",
          drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW, restitution=DEFAULT_RESTITUTION):
    """n collisions from (phi0, v0): an Orbit with arrays .phi .v .t of length n+1.

    Parameters (everything after n keyword-only):
        phi0, v0, eps: the start and the plate's amplitude (scalars).
        n: the number of collisions (an integer >= 0).
        model: "exact" (the transcendental map) or "holmes".
        on_uncertain: "raise" raises UncertainCollision at a flight float64 cannot decide;
            "stop" returns the orbit up to it, with its status, so the caller can settle that
            collision (e.g. with ``verify.step``) and go on.
        method: the exact flight solver, as for ``flight``.
        drag, drag_law, restitution: as for ``step``; below.

    restitution r in (0, 1]: impacts v1 - u = -r*(v_in - u). With r < 1 impacts can accumulate;
    the orbit then sticks to the plate and detaches where eps*cos(t) rises through 1, or stops
    as "stuck" for |eps| <= 1 (``Orbit.sticking``, ``Orbit.stopped``; the arrays are shorter
    than n+1 then). drag >= 0 with drag_law "linear" or "quadratic": air drag during the flights
    (``fastpath.dissipative.drag_flight``); with restitution < 1 too the particle rides the plate
    while eps*cos(t) - eta(u(t)) <= 1 and detaches where it rises through 1
    (``fastpath.dissipative.sticking``: with linear drag iff |eps|*sqrt(1 + drag**2) > 1). The
    defaults run the elastic kernel unchanged.
    """
    code = _method(method)
    physics = _model_physics(model, drag, drag_law, restitution)
    (phi_a, v_a, eps_a), _, scalar = float_inputs(phi0=phi0, v0=v0, eps=eps)
    if not scalar:
        raise ValueError("orbit takes scalar phi0, v0 and eps; use step() for arrays of states")
    n = integer("n", n, minimum=0)
    if on_uncertain not in ("raise", "stop"):
        raise ValueError(f"on_uncertain must be 'raise' or 'stop', got {on_uncertain!r}")
    phi0, v0, eps = float(phi_a[0]), float(v_a[0]), float(eps_a[0])
    physics = with_eps(physics, eps)
    holmes_map = type(physics) is Holmes
    if holmes_map:
        status = departure_status(phi0, v0, eps)
        if status != CONVERGED:
            _raise_on_status(np.array([status]), [phi0], [v0], [eps])
    out = OrbitArrays.empty(n)
    done, episodes, status, stuck = orbit_loop(phi0, v0, physics, code, out)
    _raise_for_orbit(status, done, out.phi, out.v, eps, on_uncertain)
    iterations = None if holmes_map else out.iterations[:done]
    return Orbit(out.phi[: done + 1], out.v[: done + 1], out.t[: done + 1], iterations,
                 FlightStatus(status), model, eps, out.sticking[:episodes].copy(),
                 "stuck" if stuck else "collisions")


def _model_physics(model, drag, drag_law, restitution):
    """The description of ``model`` with the checked physics keywords, at eps = 0 (the caller
    sets eps with ``with_eps`` once it is checked): the model and the physics are refused before
    the state (``fastpath.inputs.model_physics``, ``physics_options``)."""
    drag, law, restitution = physics_options(drag, drag_law, restitution)
    return model_physics(model, 0.0, drag, law, restitution)


def _raise_for_orbit(status, done, phi, v, eps, on_uncertain):
    """Raise for the flight that stopped an orbit after ``done`` collisions: always for a state
    that does not depart, for an undecided flight when on_uncertain is "raise"."""
    if status == CONVERGED or not (status == NOT_DEPARTING or on_uncertain == "raise"):
        return
    try:
        _raise_on_status(np.array([status]), np.array([phi[done]]), np.array([v[done]]),
                         np.array([eps]))
    except (ValueError, UncertainCollision) as err:
        raise type(err)(f"collision {done} of the orbit: {err}") from None


def moments(phi0, v0, eps, n_grid, *, t_grid=(), model="exact", blocks=64, max_collisions=None,
            drag=DEFAULT_DRAG, drag_law=DEFAULT_DRAG_LAW, restitution=DEFAULT_RESTITUTION):
    """Velocity moments of the orbits from (phi0[i], v0[i]) at collision indices ``n_grid`` and
    times ``t_grid``: a ``Moments`` (``fastpath.kernels.moments``: the sums and their means).

    Parameters (everything after n_grid keyword-only):
        phi0, v0: the starts (arrays of the same shape, or broadcast); eps: the plate's
            amplitude (a scalar).
        n_grid: collision indices, sorted, >= 0 (may be empty when t_grid is given).
        t_grid: times, sorted, >= 0.
        model: "exact" or "holmes", as for ``orbit``.
        blocks: the partition of the particles into blocks of consecutive indices (at most this
            many; fewer if some would be empty), each with its own row of sums; not the threads:
            any thread count gives the same numbers.
        max_collisions: caps each orbit (default: 100 * n_grid[-1] + 10**6 when a time grid is
            given, else n_grid[-1]).
        drag, drag_law, restitution: as for ``orbit`` (model "exact" only); with restitution < 1
            ``stuck_n``, ``stuck_t`` count the particles stuck for good.

    Raises ValueError for non-finite inputs, non-departing starts (v0 + eps*sin(phi0) <= 0),
    unsorted or negative grids, an unknown model, bad physics keywords.
    """
    physics = _model_physics(model, drag, drag_law, restitution)
    (phi_a, v_a), _, _ = float_inputs(phi0=phi0, v0=v0)
    (eps_a,), _, scalar = float_inputs(eps=eps)
    if not scalar:
        raise ValueError(f"eps must be a scalar, got shape {np.shape(eps)}")
    eps = float(eps_a[0])
    bad = np.flatnonzero(~(v_a + eps * np.sin(phi_a) > 0.0))
    if len(bad):
        i = int(bad[0])
        raise ValueError(f"start {i} (phi0={phi_a[i]!r}, v0={v_a[i]!r}) does not depart:"
                         f" v0 + eps*sin(phi0) <= 0 at eps={eps!r}")
    n_grid = np.asarray(n_grid, dtype=np.int64).ravel()
    t_grid = np.asarray(t_grid, dtype=np.float64).ravel()
    for name, grid in (("n_grid", n_grid), ("t_grid", t_grid)):
        if len(grid) and (np.any(np.diff(grid) < 0) or grid[0] < 0
                          or not np.all(np.isfinite(grid))):
            raise ValueError(f"{name} must be finite, >= 0 and sorted, got {grid!r}")
    if not len(n_grid) and not len(t_grid):
        raise ValueError("give n_grid and/or t_grid")
    blocks = max(1, min(integer("blocks", blocks, minimum=1), len(phi_a)))
    per_block = -(-len(phi_a) // blocks)
    blocks = -(-len(phi_a) // per_block)  # no empty block
    if max_collisions is None:
        n_last = int(n_grid[-1]) if len(n_grid) else 0
        max_collisions = 100 * n_last + 10**6 if len(t_grid) else n_last
    max_collisions = integer("max_collisions", max_collisions, minimum=0)
    m = len(phi_a)
    sums = MomentSums.zeros(blocks, len(n_grid), len(t_grid))
    flags = Flags.zeros(m)
    moments_chunk(with_eps(physics, eps),
                  Starts(phi=phi_a, v=v_a, t=np.zeros(m), n=np.zeros(m, np.int64)),
                  MomentGrid(n=n_grid, t=t_grid, max_collisions=max_collisions), False,
                  Sample.none(m), sums, flags)
    return Moments(n_grid, t_grid, sums, int(np.count_nonzero(flags.status)), model, eps)
