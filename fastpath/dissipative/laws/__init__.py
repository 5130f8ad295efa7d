"""The drag laws: one module per law, and the one place that maps a law code to its module.

A law module (``none``, ``linear``, ``quadratic``) holds every formula of fastpath that depends
on the drag law eta(V), under the same names and signatures (``QUANTITIES``), with the
equations in its docstring:

``eta(v, k)``                      the deceleration eta(v)
``motion(v, k, t)``                (Y, V, Y_scale, V_scale): the closed-form flight and the
                                   scales of its rounding errors (``fastpath.dissipative.drag``)
``offset(v, k, t)``                (Y - v*t, V - v) of a short flight
                                   (``fastpath.dissipative.short_flight``)
``window_drift(v, k, h, p)``       the drift rate D of the particle's acceleration over a short
                                   window (``short_flight``)
``landing_drop(v, k)``             3 times the first-order shortening of the landing time 2*v
                                   (the concave solver's first guess, ``drag_flight``)
``jerk_rate(vel, v_err, k, p)``    a bound on |p'| after t, p = -1 - eta(V) (``drag_flight``)
``acceleration_sup(p, p_err, k)``  the supremum of p after t (``drag_flight``'s graze test)
``tight_particle_errors``,         optional tighter rounding bounds of the particle and the gap
``tight_gap_errors``               (the given ones where the law has none, ``drag_flight``)
``detach_discriminant(e, k)``      (g, its rounding bound): riding ends (detaches) iff g > 0
                                   (``fastpath.dissipative.sticking``)
``detachment_frame(e, k)``         (theta'*, t_c) of a detaching ride in the eps > 0 frame
``tail_terms(eps, k, u)``          (c, |A''| bound, |eta''|) of the accumulation tail

Dispatch. The law is the int field ``drag_law`` of the description (``fastpath.physics``): one
compiled loop per model class takes every law. So the choice is made at run time, here and only
here: one function per quantity that branches on the code and calls the law's function, with
the law's arguments unchanged (the results are those of the law's formulas, bit for bit). The
branch is one integer comparison, predicted the same way for a whole orbit, and numba's LLVM
inlines these small functions into the solvers. A compile-time dispatch (``typed_overload`` on
a class per law) would compile every loop once per law and change the description's type; it
buys nothing measurable here.

A new law: a module here with every name of ``QUANTITIES`` (and its tests), a code and public
name in ``fastpath.physics`` (``LAWS``), its entry in ``LAW_MODULES`` and one branch in each
function below; ``tests/fastpath/test_drag_laws.py`` checks that each function reaches the
module of each code.
"""

from fastpath.arithmetic.jit import jit
from fastpath.dissipative.laws import linear, none, quadratic
from fastpath.physics import LINEAR, NONE, QUADRATIC

LAW_MODULES = {NONE: none, LINEAR: linear, QUADRATIC: quadratic}
QUANTITIES = ("eta", "motion", "offset", "window_drift", "landing_drop", "jerk_rate",
              "acceleration_sup", "tight_particle_errors", "tight_gap_errors",
              "detach_discriminant", "detachment_frame", "tail_terms")


@jit
def eta(v, k, law):
    if law == LINEAR:
        return linear.eta(v, k)
    if law == QUADRATIC:
        return quadratic.eta(v, k)
    return none.eta(v, k)


@jit
def motion(v, k, law, t):
    if law == LINEAR:
        return linear.motion(v, k, t)
    if law == QUADRATIC:
        return quadratic.motion(v, k, t)
    return none.motion(v, k, t)


@jit
def offset(v, k, law, t):
    if law == LINEAR:
        return linear.offset(v, k, t)
    if law == QUADRATIC:
        return quadratic.offset(v, k, t)
    return none.offset(v, k, t)


@jit
def window_drift(v, k, law, h, p):
    if law == LINEAR:
        return linear.window_drift(v, k, h, p)
    if law == QUADRATIC:
        return quadratic.window_drift(v, k, h, p)
    return none.window_drift(v, k, h, p)


@jit
def landing_drop(v, k, law):
    if law == LINEAR:
        return linear.landing_drop(v, k)
    if law == QUADRATIC:
        return quadratic.landing_drop(v, k)
    return none.landing_drop(v, k)


@jit
def jerk_rate(vel, v_err, k, law, p_size):
    if law == LINEAR:
        return linear.jerk_rate(vel, v_err, k, p_size)
    if law == QUADRATIC:
        return quadratic.jerk_rate(vel, v_err, k, p_size)
    return none.jerk_rate(vel, v_err, k, p_size)


@jit
def acceleration_sup(p, p_err, k, law):
    if law == LINEAR:
        return linear.acceleration_sup(p, p_err, k)
    if law == QUADRATIC:
        return quadratic.acceleration_sup(p, p_err, k)
    return none.acceleration_sup(p, p_err, k)


@jit
def tight_particle_errors(v, k, law, t, vel, y_err, v_err):
    if law == LINEAR:
        return linear.tight_particle_errors(v, k, t, vel, y_err, v_err)
    if law == QUADRATIC:
        return quadratic.tight_particle_errors(v, k, t, vel, y_err, v_err)
    return none.tight_particle_errors(v, k, t, vel, y_err, v_err)


@jit
def tight_gap_errors(phi, v, eps, k, law, t, d, d1, vel, d_err, d1_err, v_err):
    if law == LINEAR:
        return linear.tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err)
    if law == QUADRATIC:
        return quadratic.tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err)
    return none.tight_gap_errors(phi, v, eps, k, t, d, d1, vel, d_err, d1_err, v_err)


@jit
def detach_discriminant(e, k, law):
    if law == LINEAR:
        return linear.detach_discriminant(e, k)
    if law == QUADRATIC:
        return quadratic.detach_discriminant(e, k)
    return none.detach_discriminant(e, k)


@jit
def detachment_frame(e, k, law):
    if law == LINEAR:
        return linear.detachment_frame(e, k)
    if law == QUADRATIC:
        return quadratic.detachment_frame(e, k)
    return none.detachment_frame(e, k)


@jit
def tail_terms(eps, k, law, u):
    if law == LINEAR:
        return linear.tail_terms(eps, k, u)
    if law == QUADRATIC:
        return quadratic.tail_terms(eps, k, u)
    return none.tail_terms(eps, k, u)
