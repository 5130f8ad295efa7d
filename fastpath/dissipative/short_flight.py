"""A short flight from a small relative velocity, in relative coordinates (chattering impacts),
without or with drag.

The elastic solvers take the absolute velocity v and form w0 = v + eps*sin(phi) themselves, with
an absolute error ~u*(|v| + |eps|): harmless for an ordinary flight, but a chattering impact has
w0 ~ 1e-10 and would keep only six digits. Here the relative velocity w (particle minus plate) is
the state, carried from impact to impact (``fastpath.dissipative.sticking.inelastic_impact``), and
the gap is written so that every term is proportional to w*t or smaller:

    d(t)  = w*t + A*t**2/2 + eps*(cos(phi)*C4(t) - sin(phi)*S3(t)),     A = -1 + eps*cos(phi),
    d'(t) = w + A*t - eps*(cos(phi)*S3(t) + sin(phi)*V2(t)),

with S3(t) = t - sin(t), C4(t) = 1 - cos(t) - t**2/2 and V2(t) = 1 - cos(t) = 2*sin(t/2)**2
(the first two by their Taylor series for t <= 1: no cancellation). This is the gap of docs/model.md
with cos(phi) - cos(phi + t) expanded by angle addition.

When it applies (``elastic_short_window``): A < 0 at departure and, with m = a/2 (a = -A, lowered by
its rounding bound) and h = 4*w/a, the plate's acceleration over [0, h] keeps d'' <= -m:

    d''(s) <= A + |J|*s + |eps|*s**2/2,    J = -eps*sin(phi)  (d''' = -eps*sin, |d''''| <= |eps|),

so m_h := a - |J|*h - |eps|*h**2/2 >= a/2 is required, and h <= 1. Then d is strictly concave on
[0, h] with d(0) = 0, d'(0) = w > 0, and d(t) <= w*t - m_h*t**2/2 < 0 for t > 2*w/m_h: exactly
one positive root in (0, 2*w/m_h], no earlier collision possible. Newton's method started at
that upper bound moves monotonically down onto the root (a concave function's tangent at a point
beyond its root crosses zero between the root and that point), and stops when it no longer
decreases or the computed gap is not negative: the root to within rounding, an error of a few
u*tau (every term of d is relative to w*t).

The incoming relative velocity d'(tau) ~ -w keeps a relative error of a few u as well.

With drag: the same with the particle's drag: the state is the relative velocity w (carried
across impacts), the absolute one v = u + w only enters through the drag, and every term of the
gap is proportional to w*t or smaller (no v*t formed and subtracted):

    d(t)  = w*t + (Y(t) - v*t) + eps*(cos(phi)*2*sin(t/2)**2 - sin(phi)*S3(t)),
    d'(t) = w + (V(t) - v) + eps*(cos(phi)*sin(t) - sin(phi)*2*sin(t/2)**2),

with the particle's offsets Y - v*t and V - v from uniform motion: the closed forms of the law,
rewritten so that no v*t is formed (``offset`` of its module in ``fastpath.dissipative.laws``).

When it applies (``drag_short_window``): with a = 1 + eta(v) - eps*cos(phi) (lowered by its rounding
bound), h = 4w/a, the curvature d''(s) = p(V(s)) + eps*cos(phi + s), p = -1 - eta, satisfies d''(s)
<= -a + (|J| + D)*s + |eps|*s**2/2 with J = -eps*sin(phi) and the drift of the particle's
acceleration |p(V(s)) - p(v)| <= D*s: V moves monotonically towards terminal, so |V(s) - v| <=
s*|p(v)|, and D the law's ``window_drift`` (k*|p(v)| linear, 2k*(|v| + h*|p(v)|)*|p(v)| quadratic:
eta' = 2k|V|). The test m_h = a - (|J| + D)*h - |eps|*h**2/2 >= a/2, h <= 1, sqrt(k)*h <= 1/2 makes
d strictly concave on [0, h]: one root in (0, 2w/m_h], Newton from there moves monotonically onto it
(as without drag).

``short_window`` and ``short_flight`` take the physics description: drag == 0 runs the formulas
without drag (bit for bit those of a drag-free orbit), drag > 0 those with it.
"""

import math

from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.dissipative.laws import eta, offset, window_drift
from fastpath.dissipative.special import SERIES_LIMIT, s3
from fastpath.status import ITERATION_LIMIT


@jit
def c4(t):
    """1 - cos(t) - t**2/2 = -t**4/24 + t**6/720 - ... (series for t <= 1, cancellation-free)."""
    if t > SERIES_LIMIT:
        return 2.0 * math.sin(0.5 * t) ** 2 - 0.5 * t * t
    x = t * t
    s = 1.0 - x / 380.0
    for k in (306.0, 240.0, 182.0, 132.0, 90.0, 56.0, 30.0):
        s = 1.0 - x / k * s
    return -x * x / 24.0 * s


@jit
def relative_gap(sin_phi, cos_phi, w, eps, accel, t):
    """d(t) = w*t + A*t**2/2 + eps*(cos(phi)*C4(t) - sin(phi)*S3(t)), A = accel."""
    return w * t + 0.5 * accel * t * t + eps * (cos_phi * c4(t) - sin_phi * s3(t))


@jit
def relative_rate(sin_phi, cos_phi, w, eps, accel, t):
    """d'(t) = w + A*t - eps*(cos(phi)*S3(t) + sin(phi)*2*sin(t/2)**2), A = accel."""
    v2 = 2.0 * math.sin(0.5 * t) ** 2
    return w + accel * t - eps * (cos_phi * s3(t) + sin_phi * v2)


@jit
def departure_deceleration(cos_phi, eps):
    """a = 1 - eps*cos(phi) (minus the gap's d''(0)) lowered by its rounding bound.

    cos_phi is libm's cosine of a phase in [0, 4*pi): an error of a few ulps of 4*pi in the
    argument and one of the cosine, 8u*|eps|*(1 + 4*pi) with room.
    """
    return (1.0 - eps * cos_phi) - 8.0 * UNIT_ROUNDOFF * (1.0 + abs(eps) * 14.0)


@jit
def elastic_short_window(sin_phi, cos_phi, w, eps):
    """Upper bound 2*w/m_h on the flight time if the module docstring's test passes, else 0."""
    a = departure_deceleration(cos_phi, eps)
    if not (a > 0.0 and w > 0.0):
        return 0.0
    h = 4.0 * w / a
    m_h = a - abs(eps * sin_phi) * h - 0.5 * abs(eps) * h * h
    if not (h <= SERIES_LIMIT and m_h >= 0.5 * a):
        return 0.0
    return 2.0 * w / m_h * (1.0 + 4.0 * UNIT_ROUNDOFF)


@jit
def drag_relative_gap(sin_phi, cos_phi, w, v, eps, k, law, t):
    """(d(t), d'(t)) in relative coordinates (module docstring)."""
    dy, dv = offset(v, k, law, t)
    v2 = 2.0 * math.sin(0.5 * t) ** 2
    d = w * t + dy + eps * (cos_phi * v2 - sin_phi * s3(t))
    d1 = w + dv + eps * (cos_phi * math.sin(t) - sin_phi * v2)
    return d, d1


@jit
def drag_short_window(sin_phi, cos_phi, w, v, eps, k, law):
    """Upper bound 2w/m_h on the flight time if the module docstring's test passes, else 0."""
    e_v = eta(v, k, law)
    a = (1.0 + e_v - eps * cos_phi) - 8.0 * UNIT_ROUNDOFF * (1.0 + abs(eps) * 14.0 + abs(e_v))
    if not (a > 0.0 and w > 0.0):
        return 0.0
    h = 4.0 * w / a
    p = abs(1.0 + e_v)
    drift = window_drift(v, k, law, h, p)
    m_h = a - (abs(eps * sin_phi) + drift) * h - 0.5 * abs(eps) * h * h
    if not (h <= SERIES_LIMIT and math.sqrt(k) * h <= 0.5 and m_h >= 0.5 * a):
        return 0.0
    return 2.0 * w / m_h * (1.0 + 4.0 * UNIT_ROUNDOFF)


@jit
def short_window(sin_phi, cos_phi, w, v, physics):
    """Upper bound on a short flight from relative velocity w (absolute v) where the module
    docstring's test certifies one, else 0: ``elastic_short_window`` or ``drag_short_window``."""
    if physics.drag != 0.0:
        return drag_short_window(sin_phi, cos_phi, w, v, physics.eps, physics.drag,
                                 physics.drag_law)
    return elastic_short_window(sin_phi, cos_phi, w, physics.eps)


@jit
def relative_gap_and_rate(sin_phi, cos_phi, w, v, physics, t):
    """(d(t), d'(t)) in relative coordinates, without drag (``relative_gap``,
    ``relative_rate``) or with it (``drag_relative_gap``)."""
    eps = physics.eps
    if physics.drag != 0.0:
        return drag_relative_gap(sin_phi, cos_phi, w, v, eps, physics.drag, physics.drag_law, t)
    accel = -1.0 + eps * cos_phi
    return (relative_gap(sin_phi, cos_phi, w, eps, accel, t),
            relative_rate(sin_phi, cos_phi, w, eps, accel, t))


@jit
def short_flight(sin_phi, cos_phi, w, v, physics, upper):
    """(tau, d'(tau), iterations): Newton from the certified upper bound ``short_window``.

    Returns the first root of the gap from a departure with relative velocity w > 0 (absolute
    velocity v) and the incoming relative velocity d'(tau) < 0 there.
    """
    t = upper
    for k in range(1, ITERATION_LIMIT + 1):
        d, r = relative_gap_and_rate(sin_phi, cos_phi, w, v, physics, t)
        if not d < 0.0:  # within rounding of the root (d <= 0 at or beyond it)
            return t, r, k
        t_next = t - d / r
        if not t_next < t:
            return t, r, k
        t = t_next
    return t, incoming_rate(sin_phi, cos_phi, w, v, physics, t), ITERATION_LIMIT


@jit
def incoming_rate(sin_phi, cos_phi, w, v, physics, t):
    """d'(t) alone (``relative_gap_and_rate``)."""
    if physics.drag != 0.0:
        return drag_relative_gap(sin_phi, cos_phi, w, v, physics.eps, physics.drag,
                                 physics.drag_law, t)[1]
    return relative_rate(sin_phi, cos_phi, w, physics.eps, -1.0 + physics.eps * cos_phi, t)
