"""Compiled kernels of the dynamics: the collision map with its Jacobian, and loops over it.

Every kernel takes the state first, then the physics description (``fastpath.physics``:
``Elastic`` for the exact map, ``Holmes`` for the Holmes map), then the rest. The description's
class is a compile-time constant: ``step_tangent`` compiles the one map of that class
(``fastpath.kernels.particle`` does the same for the loops of the flights).

The exact map (docs/model.md). After the flight tau from (phi, v), with w = v + eps*sin(phi)
the departure speed relative to the plate and w1 = v1 + eps*sin(phi1) the next one,
``d'(tau) = v - tau + eps*sin(phi1) = -w1``, and implicit differentiation of d(tau; phi, v) = 0
gives tau_phi = a, tau_v = b with

    a = eps*(sin(phi1) - sin(phi))/w1,   b = tau/w1,   c = 2*eps*cos(phi1),

    DF = [[1 + a,           b      ],
          [a - c*(1 + a),  -1 + b - c*b]],         det DF = w/w1.

(phi1 = phi + tau and v1 = tau - v - 2*eps*sin(phi1) differentiated.) At the fixed point
(0, pi*m) this is [[1, 2], [-2*eps, 1 - 4*eps]] (the paper's equation (3)). The determinant is not
1: the map preserves w dphi dv, and over a periodic orbit the factors w/w1 multiply to 1.

The Holmes map in its standard-map form: phi1 = phi + 2*v, v1 = v - 2*eps*sin(phi1), with
DF = [[1, 2], [-c, 1 - 2*c]]; a step where v - 2*eps*sin(phi1) <= 0 (where Holmes' absolute value
would act and the map is not smooth) is reported as NOT_DEPARTING. Its phase is the Holmes map's
own (``fastpath.elastic.holmes.holmes_phase``, phi + 2*v reduced exactly), so where the step
departs it is the Holmes map of the loops bit for bit.

Phases are kept reduced to [0, 2*pi) with their sines and cosines carried along; the time since
the start (the unreduced phase advance) is accumulated separately from the flight times.
"""

import math

import numpy as np
from numba import prange

from fastpath.arithmetic.jit import jit, parallel_jit, typed_overload
from fastpath.arithmetic.phase import PI, TWO_PI, reduce_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.carried import STATE_SIZE, V
from fastpath.elastic.collision import collide_from
from fastpath.elastic.flight import AUTO, GENERAL
from fastpath.elastic.holmes import holmes_phase
from fastpath.kernels.particle import advance, begin, detachment_of
from fastpath.physics import Elastic, Holmes
from fastpath.status import CONVERGED, NOT_DEPARTING

NO_HOLES = np.empty(0)  # advance's hole edges: an orbit has none
_NEAR = math.sqrt(UNIT_ROUNDOFF)  # relative step below which Newton is in its quadratic end game


@jit
def _converged(step, last, scale):
    """Newton has converged: the step is at rounding level, or it is small and stopped
    shrinking (rounding noise of an ill-conditioned G)."""
    return step <= 4.0 * UNIT_ROUNDOFF * scale or (step < _NEAR * scale and step >= 0.5 * last)


@jit
def step_tangent(phi, sin_phi, cos_phi, v, physics):
    """One collision from phi in [0, 2*pi) (with its sine and cosine) and its Jacobian, by the
    map of the description (``Elastic``: the exact map; ``Holmes``: its standard-map form).

    Returns (phi1, sin1, cos1, v1, tau, j11, j12, j21, j22, status); status is a FlightStatus
    code (the other values are meaningless unless it is CONVERGED).
    """
    return _tangent(phi, sin_phi, cos_phi, v, physics)


def _tangent(phi, sin_phi, cos_phi, v, physics):
    """``step_tangent``, compiled for the description's class only."""


@typed_overload(_tangent)
def _tangent_of_model(phi, sin_phi, cos_phi, v, physics):
    if physics.instance_class is Holmes:
        return _holmes_tangent
    if physics.instance_class is Elastic:
        return _exact_tangent
    return None  # a Dissipative description: no Jacobian here (a typing error)


def _holmes_tangent(phi, sin_phi, cos_phi, v, physics):
    eps = physics.eps
    tau = 2.0 * v
    phi1 = holmes_phase(phi, v)
    s1, c1 = math.sin(phi1), math.cos(phi1)
    v1 = v - 2.0 * eps * s1
    c = 2.0 * eps * c1
    status = CONVERGED if (v > 0.0 and v1 > 0.0) else NOT_DEPARTING
    return phi1, s1, c1, v1, tau, 1.0, 2.0, -c, 1.0 - 2.0 * c, status


def _exact_tangent(phi, sin_phi, cos_phi, v, physics):
    eps = physics.eps
    phi1, s1, c1, v1, tau, _, status = collide_from(phi, sin_phi, cos_phi, v, eps, GENERAL)
    w1 = v1 + eps * s1
    a = eps * (s1 - sin_phi) / w1
    b = tau / w1
    c = 2.0 * eps * c1
    return phi1, s1, c1, v1, tau, 1.0 + a, b, a - c * (1.0 + a), -1.0 + b - c * b, status


@jit
def orbit_monodromy(phi0, v0, physics, period, phi_out, v_out, tau_out, jac_out):
    """``period`` collisions from (phi0, v0) with the product M of their Jacobians.

    Fills phi_out, v_out (the states before each collision, phases reduced), tau_out and jac_out
    (rows j11, j12, j21, j22 of each collision). Returns (time, v_end, phi_end, m11, m12, m21,
    m22, status, done): time is the sum of the flight times (the unreduced phase advance), done
    the collisions completed (``period`` unless status is not CONVERGED).
    """
    phi = reduce_phase(phi0)
    s, c = math.sin(phi), math.cos(phi)
    v = v0
    m11, m12, m21, m22 = 1.0, 0.0, 0.0, 1.0
    time = 0.0
    for k in range(period):
        phi_out[k], v_out[k] = phi, v
        phi, s, c, v1, tau, j11, j12, j21, j22, status = step_tangent(phi, s, c, v, physics)
        if status != CONVERGED:
            return time, v, phi, m11, m12, m21, m22, status, k
        tau_out[k] = tau
        jac_out[k, 0], jac_out[k, 1], jac_out[k, 2], jac_out[k, 3] = j11, j12, j21, j22
        time += tau
        v = v1
        m11, m12, m21, m22 = (j11 * m11 + j12 * m21, j11 * m12 + j12 * m22,
                              j21 * m11 + j22 * m21, j21 * m12 + j22 * m22)
    return time, v, phi, m11, m12, m21, m22, CONVERGED, period


@jit
def product_rounding_scale(jac):
    """S = sum_k ||J_p...J_(k+1)|| * ||J_k|| * ||J_(k-1)...J_1|| (max-row-sum norms).

    To first order, an error dJ_k in one factor (its own rounding, or that of the product)
    changes M = J_p...J_1 by J_p...J_(k+1) dJ_k J_(k-1)...J_1; with |dJ_k| <= c*u*|J_k| the
    error of M is at most c*u*S. Unlike the product of the entrywise absolute values, S grows
    only as fast as the signed partial products do (polynomially along a near-critical orbit).
    """
    p = jac.shape[0]
    forward = np.empty(p)  # ||J_(k-1)...J_1||, forward[0] = 1
    f11, f12, f21, f22 = 1.0, 0.0, 0.0, 1.0
    for k in range(p):
        forward[k] = max(abs(f11) + abs(f12), abs(f21) + abs(f22))
        j11, j12, j21, j22 = jac[k, 0], jac[k, 1], jac[k, 2], jac[k, 3]
        f11, f12, f21, f22 = (j11 * f11 + j12 * f21, j11 * f12 + j12 * f22,
                              j21 * f11 + j22 * f21, j21 * f12 + j22 * f22)
    total = 0.0
    b11, b12, b21, b22 = 1.0, 0.0, 0.0, 1.0  # J_p...J_(k+1)
    for k in range(p - 1, -1, -1):
        j11, j12, j21, j22 = jac[k, 0], jac[k, 1], jac[k, 2], jac[k, 3]
        back = max(abs(b11) + abs(b12), abs(b21) + abs(b22))
        total += back * max(abs(j11) + abs(j12), abs(j21) + abs(j22)) * forward[k]
        b11, b12, b21, b22 = (b11 * j11 + b12 * j21, b11 * j12 + b12 * j22,
                              b21 * j11 + b22 * j21, b21 * j12 + b22 * j22)
    return total


@jit
def newton_block(phi0, v0, physics, period, winding, shift, max_iterations):
    """Newton's method on G(x) = F^p(x) - x - (2*pi*winding, pi*shift), x = (phi, v).

    F^p's phase is unreduced (the sum of the flight times), so G's first component is the total
    time minus 2*pi*winding. The Jacobian of G is M - I with M the exact monodromy. A step that
    does not lower |G| is halved (up to 40 times; then -1) unless the full step is already
    below sqrt(u) of the state (the end game, where |G| is rounding noise); stops when
    ``_converged`` or after ``max_iterations``.

    The phase is kept reduced to [0, 2*pi) (G does not depend on its lift).
    Returns (phi, v, g1, g2, step, iterations, status): status CONVERGED, NOT_DEPARTING or
    UNCERTAIN for a flight that failed, or -1 when Newton did not converge.
    """
    phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
    jac = np.empty((period, 4))
    phi, v = reduce_phase(phi0), v0
    target_t, target_v = TWO_PI * winding, PI * shift
    time, v_end, _, m11, m12, m21, m22, status, _ = orbit_monodromy(
        phi, v, physics, period, phi_k, v_k, tau_k, jac)
    if status != CONVERGED:
        return phi, v, math.nan, math.nan, math.nan, 0, status
    g1, g2 = time - target_t, v_end - v - target_v
    last = math.inf
    for it in range(1, max_iterations + 1):
        a11, a12, a21, a22 = m11 - 1.0, m12, m21, m22 - 1.0
        det = a11 * a22 - a12 * a21
        if det == 0.0 or not math.isfinite(det):
            return phi, v, g1, g2, math.inf, it, -1
        d_phi = -(a22 * g1 - a12 * g2) / det
        d_v = -(-a21 * g1 + a11 * g2) / det
        size = abs(g1) + abs(g2)
        near = _NEAR * max(TWO_PI, abs(v))
        end_game = max(abs(d_phi), abs(d_v)) < near  # full steps at rounding noise: no test
        scale = 1.0
        t_phi, t_v, h1, h2 = phi, v, g1, g2
        n11, n12, n21, n22 = m11, m12, m21, m22
        accepted = False
        for _ in range(40):
            t_phi, t_v = phi + scale * d_phi, v + scale * d_v
            time, v_end, _, n11, n12, n21, n22, status, _ = orbit_monodromy(
                t_phi, t_v, physics, period, phi_k, v_k, tau_k, jac)
            if status == CONVERGED:
                h1, h2 = time - target_t, v_end - t_v - target_v
                if end_game or abs(h1) + abs(h2) < size:
                    accepted = True
                    break
            scale *= 0.5
        if status != CONVERGED:
            return phi, v, g1, g2, math.inf, it, status
        if not accepted:
            return phi, v, g1, g2, math.inf, it, -1
        step = max(abs(d_phi), abs(d_v))  # the full Newton step measures convergence
        phi, v, g1, g2 = reduce_phase(t_phi), t_v, h1, h2  # G does not depend on phi's lift
        m11, m12, m21, m22 = n11, n12, n21, n22
        if scale == 1.0 and _converged(step, last, max(TWO_PI, abs(v))):
            return phi, v, g1, g2, step, it, CONVERGED
        last = step if scale == 1.0 else math.inf
    return phi, v, g1, g2, last, max_iterations, -1


@jit
def half_orbit(phase0, v, physics, steps):
    """``steps`` collisions from (phase0, v) with the tangent of the start's v direction.

    Returns (time, v_end, dtime_dv, dv_end_dv, status): time is the sum of the flight times.
    """
    phi = phase0
    s, c = math.sin(phi), math.cos(phi)
    d_phi, d_v = 0.0, 1.0
    time = 0.0
    for _ in range(steps):
        phi, s, c, v1, tau, j11, j12, j21, j22, status = step_tangent(phi, s, c, v, physics)
        if status != CONVERGED:
            return time, v, d_phi, d_v, status
        time += tau
        v = v1
        d_phi, d_v = j11 * d_phi + j12 * d_v, j21 * d_phi + j22 * d_v
    return time, v, d_phi, d_v, CONVERGED


@jit
def symmetric_newton(phase0, v0, physics, period, winding, max_iterations):
    """Newton's method for the symmetric periodic orbit through (phase0, v), phase0 = 0 or pi.

    The map is F = I1 o I0 with the involutions whose fixed sets are the lines phi = 0, pi
    (Fix I1) and phi + v = 0 mod pi (Fix I0). From a start on Fix I1, an orbit of period
    q = 2n + 1 is periodic iff after n collisions it lies on Fix I0, where the flight is
    symmetric (tau = 2v): time_n + v_n = pi*winding (the total time is 2*(time_n + v_n)). For
    q = 2n it is periodic iff after n collisions it is on Fix I1 again: time_n = pi*winding.

    Returns (v, g, step, iterations, status): status CONVERGED, a failed flight's status, or
    -1 when Newton did not converge.
    """
    n, odd = period // 2, period % 2 == 1
    target = PI * winding
    v = v0
    time, vn, dt, dvn, status = half_orbit(phase0, v, physics, n)
    if status != CONVERGED:
        return v, math.nan, math.nan, 0, status
    g, dg = (time + vn - target, dt + dvn) if odd else (time - target, dt)
    last = math.inf
    for it in range(1, max_iterations + 1):
        if dg == 0.0 or not math.isfinite(dg):
            return v, g, math.inf, it, -1
        delta = -g / dg
        end_game = abs(delta) < _NEAR * max(1.0, abs(v))
        scale = 1.0
        trial, h, dh = v, g, dg
        accepted = False
        for _ in range(40):
            trial = v + scale * delta
            time, vn, dt, dvn, status = half_orbit(phase0, trial, physics, n)
            if status == CONVERGED:
                h, dh = (time + vn - target, dt + dvn) if odd else (time - target, dt)
                if end_game or abs(h) < abs(g):
                    accepted = True
                    break
            scale *= 0.5
        if status != CONVERGED:
            return v, g, math.inf, it, status
        if not accepted:
            return v, g, math.inf, it, -1
        step = abs(delta)  # the full Newton step measures convergence
        v, g, dg = trial, h, dh
        if scale == 1.0 and _converged(step, last, max(1.0, abs(v))):
            return v, g, step, it, CONVERGED
        last = step if scale == 1.0 else math.inf
    return v, g, last, max_iterations, -1


@jit
def tangent_orbit(phi0, v0, physics, checkpoints, log_growth, times, velocities):
    """Largest Lyapunov exponent by the tangent map with renormalisation at every collision.

    A tangent vector u (start (1, 1)/sqrt(2)) is mapped by the Jacobian of each collision and
    renormalised; log|J u| is summed. At collision counts ``checkpoints`` (ascending) the sum,
    the time since the start and the velocity are stored. Returns (collisions done, status).
    """
    phi = reduce_phase(phi0)
    s, c = math.sin(phi), math.cos(phi)
    v = v0
    u1 = u2 = math.sqrt(0.5)
    total, time = 0.0, 0.0
    j = 0
    for k in range(1, checkpoints[len(checkpoints) - 1] + 1):
        phi, s, c, v1, tau, j11, j12, j21, j22, status = step_tangent(phi, s, c, v, physics)
        if status != CONVERGED:
            return k - 1, status
        v = v1
        time += tau
        x, y = j11 * u1 + j12 * u2, j21 * u1 + j22 * u2
        norm = math.hypot(x, y)
        total += math.log(norm)
        u1, u2 = x / norm, y / norm
        if k == checkpoints[j]:
            log_growth[j], times[j], velocities[j] = total, time, v
            j += 1
    return checkpoints[len(checkpoints) - 1], CONVERGED


@parallel_jit
def tangent_ensemble(phi0, v0, physics, checkpoints, log_growth, times, velocities, done,
                     status):
    """``tangent_orbit`` for each start (rows of the 2-D outputs), in parallel."""
    for i in prange(len(phi0)):
        done[i], status[i] = tangent_orbit(phi0[i], v0[i], physics, checkpoints,
                                           log_growth[i], times[i], velocities[i])


@jit
def _wrapped(x):
    """x reduced to [-pi, pi)."""
    return x - TWO_PI * math.floor(x / TWO_PI + 0.5)


@jit
def separation_exponent(phi0, v0, physics, n, d0):
    """Largest Lyapunov exponent from two nearby orbits (Benettin's renormalised separation).

    A companion starts at distance d0 along (1, 1)/sqrt(2); after each collision the separation
    d (phase difference wrapped to [-pi, pi)) is measured, log(d/d0) summed, and the companion
    moved back to distance d0 along the separation. No Jacobian is used: an independent check
    of ``tangent_orbit``. Returns (exponent per collision, collisions done, status).
    """
    phi_a = reduce_phase(phi0)
    sa, ca = math.sin(phi_a), math.cos(phi_a)  # carried as in tangent_orbit: the same orbit
    va = v0
    phi_b = reduce_phase(phi_a + d0 * math.sqrt(0.5))
    vb = v0 + d0 * math.sqrt(0.5)
    total = 0.0
    for k in range(n):
        sb, cb = math.sin(phi_b), math.cos(phi_b)
        phi_a, sa, ca, va1, _, _, _, _, _, status = step_tangent(phi_a, sa, ca, va, physics)
        if status != CONVERGED:
            return total / max(k, 1), k, status
        phi_b, _, _, vb1, _, _, _, _, _, status = step_tangent(phi_b, sb, cb, vb, physics)
        if status != CONVERGED:
            return total / max(k, 1), k, status
        va = va1
        dphi, dv = _wrapped(phi_b - phi_a), vb1 - va1
        d = math.hypot(dphi, dv)
        total += math.log(d / d0)
        phi_b = reduce_phase(phi_a + dphi * d0 / d)
        vb = va + dv * d0 / d
    return total / n, n, CONVERGED


@parallel_jit
def first_passage(phi0, v0, physics, v_top, n, passage, status):
    """Collision count at which each orbit first has v >= v_top (-1: not within n), the orbits
    of ``fastpath.orbit`` (``fastpath.kernels.particle``: its Holmes map folds, as the map
    itself does, rather than stopping)."""
    detach = detachment_of(physics)
    for i in prange(len(phi0)):
        passage[i] = -1
        status[i] = _first_passage(phi0[i], v0[i], physics, v_top, n, detach, passage, i)


@jit
def _first_passage(phi0, v0, physics, v_top, n, detach, passage, i):
    """``first_passage`` of start i (written into passage[i]); its status."""
    state = np.empty(STATE_SIZE)
    status = begin(state, phi0, v0, 0.0, physics, False)
    k = 0
    while status == CONVERGED and k < n:
        status, _, _, _, _, _ = advance(state, physics, AUTO, False, detach, NO_HOLES)
        k += 1
        if status == CONVERGED and state[V] >= v_top:
            passage[i] = k
            break
    return status


@parallel_jit
def block_search(phi0, v0, physics, period, max_iterations, out):
    """Newton's method on F^p - id - (2*pi*m, pi*l) from each start, with m and l the nearest
    integers to the start's own p collisions. Rows of ``out``: phi, v, m, l, residual, status
    (status CONVERGED, a failed flight's, or -1)."""
    for i in prange(len(phi0)):
        phi_k, v_k, tau_k = np.empty(period), np.empty(period), np.empty(period)
        jac = np.empty((period, 4))
        time, v_end, _, _, _, _, _, status, _ = orbit_monodromy(
            phi0[i], v0[i], physics, period, phi_k, v_k, tau_k, jac)
        out[i, 0], out[i, 1], out[i, 5] = phi0[i], v0[i], status
        if status != CONVERGED:
            continue
        winding = round(time / TWO_PI)
        shift = round((v_end - v0[i]) / PI)
        if winding < 1:  # shorter than pi: no block with a positive winding near this start
            out[i, 5] = -1
            continue
        phi, v, g1, g2, _, _, status = newton_block(phi0[i], v0[i], physics, period, winding, shift,
                                                    max_iterations)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = phi, v, winding, shift
        out[i, 4], out[i, 5] = max(abs(g1), abs(g2)), status


@jit
def tangent_bands(phi0, v0, physics, n, edges, sums, counts):
    """``tangent_orbit``'s log-stretches log|J u| of n collisions, summed by the velocity band
    of the state before each collision: band j holds v in [edges[j], edges[j+1]) (sums[j] and
    counts[j] accumulate). Returns (collisions done, status)."""
    phi = reduce_phase(phi0)
    s, c = math.sin(phi), math.cos(phi)
    v = v0
    u1 = u2 = math.sqrt(0.5)
    top = len(edges) - 1
    for k in range(1, n + 1):
        band = np.searchsorted(edges, v, side="right") - 1
        phi, s, c, v1, _, j11, j12, j21, j22, status = step_tangent(phi, s, c, v, physics)
        if status != CONVERGED:
            return k - 1, status
        x, y = j11 * u1 + j12 * u2, j21 * u1 + j22 * u2
        norm = math.hypot(x, y)
        if 0 <= band < top:
            sums[band] += math.log(norm)
            counts[band] += 1
        u1, u2 = x / norm, y / norm
        v = v1
    return n, CONVERGED


@parallel_jit
def tangent_band_ensemble(phi0, v0, physics, n, edges, sums, counts, done, status):
    """``tangent_bands`` for each start (rows of ``sums`` and ``counts``), in parallel."""
    for i in prange(len(phi0)):
        done[i], status[i] = tangent_bands(phi0[i], v0[i], physics, n, edges, sums[i],
                                           counts[i])
