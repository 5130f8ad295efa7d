"""The common flight in straight-line code: the same arithmetic in every lane of a batch.

The ensemble kernels spend almost all their time in flights of the concave case (|eps| <= 1)
that start at the Holmes time t = 2*v and end after three or four evaluations. Written with
early exits, each flight waits on its own branches and on libm; written as a fixed number of
evaluations whose decisions are selects, a loop over particles compiles to vector instructions
(``fastpath.kernels.escape``) and the flight costs a few nanoseconds.

``lockstep_flight`` is the method of ``fastpath.elastic.concave`` (its Holmes start, the certified
bracket, the classification of each evaluation with its error bounds, Halley steps with the
bisection guard, the clamped Newton correction at the root), with three changes that keep it
branch-free:

* sines and cosines come from ``fastpath.arithmetic.sincos.sin_cos`` (no call; error <= 4u
  instead of libm's ulp, within the gap's error bound: for t >= 1 ``gap_error`` allows
  >= 16u*|eps| for the plate term and ``rate_error`` >= 8u*|eps|), also for the rotations of
  later iterates;
* exactly ``LOCKSTEP_EVALUATIONS`` evaluations, a lane's answer frozen at its first root;
* one division per evaluation (Newton's and Halley's steps from one reciprocal) and the
  arithmetic midpoint as the bisection guard (no square roots);
* whatever it does not handle, it does not answer: ``done`` is False for a flight that is not a
  certain departure, starts short (2*w0 < 1 + |eps|), has |phi + 2v| >= 2**20, a non-finite
  value, a flat top, a bracket closed to adjacent floats, or no root within the evaluations.
  The caller then runs ``concave_flight``'s general loop. About 1 flight in 25 of the paper's
  escape ensemble (measured in the benchmark's report).

Final step: as ``concave_flight``, the Newton correction is taken at a point where |d| is within
its rounding bound, or where it is provably as good (``fastpath.elastic.concave.newton_is_final``):
one evaluation fewer in most flights.

The answer is a pure function of the inputs, so ``concave_flight`` (one flight) and the
ensemble (a batch) return the same bits for the same departure.
"""

import math

from fastpath.arithmetic.jit import inline_jit, jit
from fastpath.arithmetic.phase import MODERATE_LIMIT
from fastpath.arithmetic.rounding import select, two_sum
from fastpath.arithmetic.sincos import sin_cos
from fastpath.elastic.concave import bracket_from_root, newton_is_final
from fastpath.elastic.gap import departure, gap_error, rate_error

LOCKSTEP_EVALUATIONS = 4

# the entries of a lane's state tuple (``lane_start``, ``lane_evaluation``): the iterate t,
# t - 2v, its sine and cosine, the step h they still have to be rotated by, the bracket, the
# answer, the root point with its sine and cosine, the evaluations made, and the two flags
(T, DELTA, SIN, COS, PENDING, LO, HI, TAU, T_ROOT, SIN_ROOT, COS_ROOT, EVALUATIONS, DONE,
 FAILED) = range(14)


@inline_jit
def moderate_bracket(v, w0, w0_error, eps):
    """``fastpath.elastic.concave.bracket`` for 1e-150 < |v| < 1e150 (v**2 neither under- nor
    overflows), without the branch to hypot."""
    return bracket_from_root(v, w0, w0_error, eps, math.sqrt(v * v + 4.0 * abs(eps)))


@inline_jit
def rotate_by(s, c, h):
    """(sin, cos) of the angle moved on by h: first order below 1e-8, else angle addition."""
    sh, ch = sin_cos(h)
    tiny = abs(h) < 1e-8
    sh = select(tiny, h, sh)
    ch = select(tiny, 1.0, ch)
    return s * ch + c * sh, c * ch - s * sh


@inline_jit
def lane_evaluation(state, phi, cos_phi, v, eps, two_v, k):
    """Evaluation k of a lane that has neither answered nor given up; else unchanged.

    The iterate's sine and cosine are rotated on by the step the previous evaluation chose
    (``h``, pending: a lane that answers needs no rotation, and the last evaluation's step
    is never taken); the first evaluation starts from the Holmes start's own sine and cosine.
    At the root the answer is the Newton correction clamped into the certified bracket; its
    sine and cosine are rotated from (t_root, s_root, c_root) once, after the last evaluation.
    The branches only skip work: a vectorised loop computes both sides and selects.
    """
    t, delta, s, c, h, lo, hi, tau, t_root, s_root, c_root, evaluations, done, failed = state
    if done or failed:
        return state
    if k > 1:
        s, c = rotate_by(s, c, h)
    d = eps * (cos_phi - c) - 0.5 * t * delta
    d1 = -v - delta + eps * s
    if not (abs(d) < math.inf and abs(d1) < math.inf):
        return t, delta, s, c, 0.0, lo, hi, tau, t_root, s_root, c_root, evaluations, False, True
    d_err = gap_error(phi, v, eps, t)
    d1_err = rate_error(phi, v, eps, t)
    # one division for both steps: Newton -d/d1 and Halley -2*d*d1/(2*d1**2 - d*d2)
    halley_denominator = 2.0 * d1 * d1 - d * (-1.0 + eps * c)
    reciprocal = 1.0 / (d1 * halley_denominator)
    newton = -d * halley_denominator * reciprocal
    if d1 < -d1_err and (abs(d) <= d_err or newton_is_final(newton, d_err, d1_err, eps)):
        # at the root: the Newton correction, clamped into the certified bracket
        answer = min(max(t + newton, lo), hi)
        if d > d_err:
            lo = t
        elif d < -d_err:
            hi = t
        return t, delta, s, c, 0.0, lo, hi, answer, t, s, c, k, True, False
    if d > d_err:
        lo = t
    elif d < -d_err:
        hi = t
    else:
        if not d1 > d1_err:  # a flat top
            return (t, delta, s, c, 0.0, lo, hi, tau, t_root, s_root, c_root, evaluations, False,
                    True)
        lo = t
    t_next = t - 2.0 * d * d1 * d1 * reciprocal
    if not lo < t_next < hi:  # the bisection guard (the Holmes start is within a factor 4)
        t_next = 0.5 * (lo + hi)
    if t_next == lo or t_next == hi:  # the bracket closed to adjacent floats
        return t, delta, s, c, 0.0, lo, hi, tau, t_root, s_root, c_root, evaluations, False, True
    delta_next = t_next - two_v
    return (t_next, delta_next, s, c, delta_next - delta, lo, hi, tau, t_root, s_root, c_root,
            evaluations, False, False)


@inline_jit
def lane_start(phi, sin_phi, v, eps, w0_error):
    """The lane's state before its first evaluation (Holmes start t = 2*v), and two_v."""
    w0 = v + eps * sin_phi
    two_v = 2.0 * v
    theta0, theta0_error = two_sum(phi, two_v)
    eligible = (2.0 * w0 >= 1.0 + abs(eps) and abs(theta0) < MODERATE_LIMIT
                and 1e-150 < abs(v) < 1e150)
    lo, hi = moderate_bracket(v, w0, w0_error, eps)
    s, c = sin_cos(select(eligible, theta0, 0.0))
    s, c = s + c * theta0_error, c - s * theta0_error  # |theta0_error| <= ulp: first order
    state = (two_v, 0.0, s, c, 0.0, lo, hi, math.nan, 0.0, 0.0, 1.0, 0, False,
             not (eligible and hi < math.inf))
    return state, two_v


@inline_jit
def lane_answer(state):
    """(tau, sin(phi + tau), cos(phi + tau), evaluations, done) of a lane's final state."""
    _, _, _, _, _, _, _, tau, t_root, s_root, c_root, evaluations, done, failed = state
    s1, c1 = rotate_by(s_root, c_root, tau - t_root)
    return tau, s1, c1, evaluations, done and not failed


@inline_jit
def lockstep_flight(phi, sin_phi, cos_phi, v, eps, w0_error):
    """(tau, sin(phi + tau), cos(phi + tau), evaluations, done) for |eps| <= 1, phi in [-pi, pi).

    As ``fastpath.elastic.concave.concave_flight`` (same arguments, a certain departure
    w0 > w0_error), for the flights described in the module docstring; done False: no answer,
    use that. Straight-line code for the ensemble's loops over lanes.
    """
    state, two_v = lane_start(phi, sin_phi, v, eps, w0_error)
    state = lane_evaluation(state, phi, cos_phi, v, eps, two_v, 1)
    state = lane_evaluation(state, phi, cos_phi, v, eps, two_v, 2)
    state = lane_evaluation(state, phi, cos_phi, v, eps, two_v, 3)
    state = lane_evaluation(state, phi, cos_phi, v, eps, two_v, 4)
    return lane_answer(state)


@inline_jit
def lane_running(state):
    """The lane has neither answered nor given up."""
    return not (state[DONE] or state[FAILED])


@jit
def lockstep_flight_one(phi, sin_phi, cos_phi, v, eps, w0_error):
    """``lockstep_flight`` for one flight: the same evaluations, the same bits, but it stops
    at the first answer (or give-up) instead of running all LOCKSTEP_EVALUATIONS."""
    state, two_v = lane_start(phi, sin_phi, v, eps, w0_error)
    for k in range(1, LOCKSTEP_EVALUATIONS + 1):
        if not lane_running(state):
            break
        state = lane_evaluation(state, phi, cos_phi, v, eps, two_v, k)
    return lane_answer(state)


@inline_jit
def lockstep_collide(phi, sin_phi, cos_phi, v, eps, phase_error):
    """The departure check and ``lockstep_flight`` of ``flight_from`` for a centred phi:
    (tau, sin(phi + tau), cos(phi + tau), evaluations, done)."""
    w0, w0_error = departure(phi, sin_phi, v, eps, phase_error)
    tau, s1, c1, evaluations, done = lockstep_flight(phi, sin_phi, cos_phi, v, eps, w0_error)
    return tau, s1, c1, evaluations, done and w0 > w0_error and abs(eps) <= 1.0


__all__ = [
    "LOCKSTEP_EVALUATIONS",
    "lockstep_collide",
    "lockstep_flight",
    "lockstep_flight_one",
    "moderate_bracket",
]
