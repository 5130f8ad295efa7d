"""The largest Lyapunov exponent from the tangent map, in both clocks.

Along an orbit, a tangent vector u_k is mapped by the exact Jacobian of each collision
(``fastpath.dynamics.kernels``) and renormalised; with S_n = sum_{k<=n} log|DF(x_k) u_k|,

    lambda_n = S_n / n   (per collision),      lambda_t = S_n / t_n   (per unit time),

t_n the time of the n-th collision. Running values are stored at ``checkpoints`` collision counts
(log-spaced, constant memory). ``separation`` is the same exponent from two nearby orbits without
the Jacobian (Benettin's renormalised separation), an independent check of the tangent map.
``by_band`` pools the same log-stretches by the velocity band where they happen: an orbit of the
chaotic component that diffuses to high velocity reads the exponent of the high-velocity
(standard-map-like) part; its early collisions give the low-velocity part.
"""

from dataclasses import dataclass

import numpy as np

from fastpath.dynamics.kernels import separation_exponent, tangent_band_ensemble, tangent_ensemble
from fastpath.inputs import departing, integer, model_physics
from fastpath.inputs import real_scalar as real
from fastpath.status import (
    CONVERGED,
    NOT_DEPARTING,
    STATUS_DTYPE,
    FlightStatus,
    UncertainCollision,
)


@dataclass(frozen=True)
class Lyapunov:
    """Largest Lyapunov exponent after n collisions, and its running values.

    ``per_collision``, ``per_time``: S_n/n and S_n/t_n (floats for one start, arrays for many);
    ``collisions``: the checkpoint counts; ``running_per_collision``, ``running_per_time``,
    ``time``, ``velocity``: values at the checkpoints (shape (k,), or (starts, k)); NaN after a
    flight that stopped an orbit of an ensemble, whose ``done`` and ``status`` say where and why.
    """

    per_collision: float | np.ndarray
    per_time: float | np.ndarray
    collisions: np.ndarray
    running_per_collision: np.ndarray
    running_per_time: np.ndarray
    time: np.ndarray
    velocity: np.ndarray
    done: int | np.ndarray
    status: int | np.ndarray
    eps: float
    model: str


def checkpoint_counts(n, count):
    """About ``count`` log-spaced collision counts from 1 to n (distinct, ascending, last n)."""
    points = np.unique(np.round(np.geomspace(1, n, max(count, 2))).astype(np.int64))
    return points if points[-1] == n else np.append(points, n)


def _starts(phi, v):
    phi_a = np.atleast_1d(np.asarray(phi, dtype=object))
    v_a = np.atleast_1d(np.asarray(v, dtype=object))
    try:
        phi_a, v_a = np.broadcast_arrays(phi_a, v_a)
    except ValueError:
        raise ValueError(f"phi and v do not broadcast: shapes {phi_a.shape}, {v_a.shape}") from None
    if phi_a.ndim != 1:
        raise ValueError(f"phi and v must be scalars or 1-D arrays, got shape {phi_a.shape}")
    return (np.array([real("phi", x) for x in phi_a]), np.array([real("v", x) for x in v_a]))


def lyapunov(phi, v, eps, n, *, model="exact", checkpoints=64):
    """Largest Lyapunov exponent of the orbit(s) from (phi, v) over n collisions.

    phi, v: a start, or 1-D arrays of starts (run in parallel); eps: the amplitude; n >= 1.
    model: "exact" or "holmes" (standard-map form). checkpoints: about how many running values to
    keep (log-spaced), or the ascending collision counts themselves (ending at n). Returns a
    :class:`Lyapunov`. Raises ValueError for bad input or a start that does not depart; for one
    start, ``fastpath.UncertainCollision`` at a flight float64 cannot decide
    (an ensemble reports it in ``status`` instead).
    """
    scalar = np.ndim(phi) == 0 and np.ndim(v) == 0
    phi_a, v_a = _starts(phi, v)
    eps = real("eps", eps)
    n = integer("n", n, minimum=1)
    physics = model_physics(model, eps)
    for p, w in zip(phi_a, v_a, strict=True):
        departing(p, w, eps)
    if np.ndim(checkpoints) == 0:
        points = checkpoint_counts(n, integer("checkpoints", checkpoints, minimum=1))
    else:
        points = np.asarray(checkpoints, dtype=np.int64)
        if (points.ndim != 1 or len(points) == 0 or points[0] < 1 or points[-1] != n
                or np.any(np.diff(points) <= 0)):
            raise ValueError("checkpoints must be a count, or ascending collision counts >= 1 "
                             f"ending at n={n}")
    rows, k = len(phi_a), len(points)
    growth, times, vel = np.full((rows, k), np.nan), np.full((rows, k), np.nan), np.full(
        (rows, k), np.nan)
    done, status = np.zeros(rows, np.int64), np.zeros(rows, STATUS_DTYPE)
    tangent_ensemble(phi_a, v_a, physics, points, growth, times, vel, done, status)
    for i in range(rows):  # checkpoints after a failed flight were never written
        after = points > done[i]
        growth[i, after] = times[i, after] = vel[i, after] = np.nan
    per_n = growth / points
    per_t = growth / times
    if scalar:
        if status[0] != CONVERGED:
            _raise(status[0], done[0], phi_a[0], v_a[0], eps)
        return Lyapunov(float(per_n[0, -1]), float(per_t[0, -1]), points, per_n[0], per_t[0],
                        times[0], vel[0], int(done[0]), int(status[0]), eps, model)
    return Lyapunov(per_n[:, -1], per_t[:, -1], points, per_n, per_t, times, vel, done, status,
                    eps, model)


def _raise(status, done, phi, v, eps):
    where = f"collision {done} of the orbit from phi={phi!r}, v={v!r}, eps={eps!r}"
    if status == NOT_DEPARTING:
        raise ValueError(f"{where}: a state that does not depart (or where the Holmes map's "
                         "absolute value acts)")
    raise UncertainCollision(f"{where}: a flight float64 cannot decide "
                             f"({FlightStatus(int(status)).name}); settle it with verify")


def separation(phi, v, eps, n, *, model="exact", distance=1e-9):
    """Largest Lyapunov exponent per collision from two orbits ``distance`` apart, renormalised
    after every collision (no Jacobian used). Returns the exponent after n collisions."""
    phi, v, eps = real("phi", phi), real("v", v), real("eps", eps)
    n = integer("n", n, minimum=1)
    physics = model_physics(model, eps)
    distance = real("distance", distance)
    if not 0.0 < distance < 1e-3:
        raise ValueError(f"distance must be in (0, 1e-3), got distance={distance!r}")
    departing(phi, v, eps)
    exponent, done, status = separation_exponent(phi, v, physics, n, distance)
    if status != CONVERGED:
        _raise(status, done, phi, v, eps)
    return float(exponent)



@dataclass(frozen=True)
class BandExponents:
    """The tangent map's log-stretch per collision by velocity band (the band of the state
    before the collision): ``edges`` (band j is [edges[j], edges[j+1])), ``per_collision`` the
    pooled sum/count per band (NaN where no collision fell), ``standard_error`` over the
    starts (of their own band means, weighted by their counts; NaN with fewer than 2 starts
    in the band), ``collisions`` per band and ``orbits`` per band (starts that visited it)."""

    edges: np.ndarray
    per_collision: np.ndarray
    standard_error: np.ndarray
    collisions: np.ndarray
    orbits: np.ndarray
    done: np.ndarray
    status: np.ndarray
    eps: float
    model: str


def by_band(phi, v, eps, n, edges, *, model="exact"):
    """The largest Lyapunov exponent's local part in each velocity band: the log-stretches
    log|DF(x_k) u_k| of n collisions from each start (the renormalised tangent vector of
    ``lyapunov``), pooled by the band of v_k. A band mean is the exponent of the chaotic
    component restricted to those velocities when the orbits have spent long enough there
    for the tangent vector to align (they start at low velocity and diffuse upwards)."""
    phi_a, v_a = _starts(phi, v)
    eps = real("eps", eps)
    n = integer("n", n, minimum=1)
    physics = model_physics(model, eps)
    edges = np.asarray(edges, dtype=float)
    if edges.ndim != 1 or len(edges) < 2 or np.any(np.diff(edges) <= 0):
        raise ValueError("edges must be at least two ascending velocities")
    for p, w in zip(phi_a, v_a, strict=True):
        departing(p, w, eps)
    rows, bands = len(phi_a), len(edges) - 1
    sums, counts = np.zeros((rows, bands)), np.zeros((rows, bands), np.int64)
    done, status = np.zeros(rows, np.int64), np.zeros(rows, STATUS_DTYPE)
    tangent_band_ensemble(phi_a, v_a, physics, n, edges, sums, counts, done, status)
    total = counts.sum(0)
    with np.errstate(invalid="ignore", divide="ignore"):
        pooled = sums.sum(0) / total
        own = sums / counts
        weights = counts / total
        visited = (counts > 0).sum(0)
        spread = np.nansum(weights**2 * (own - pooled) ** 2, axis=0)
        error = np.where(visited >= 2, np.sqrt(spread * visited / np.maximum(visited - 1, 1)),
                         np.nan)
    return BandExponents(edges, pooled, error, total, visited, done, status, eps, model)
