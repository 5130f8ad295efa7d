"""The drag laws and the flights they give, in closed form: interval enclosures (``mpmath.iv``)
stable as drag -> 0. Each law is one class (:class:`LinearDrag`, :class:`QuadraticDrag`) holding
everything law-specific that verify needs: the force ``eta`` and its slope, the closed-form
motion, the exact decision whether a particle riding the plate ever leaves it, candidates for
the phases where it leaves, and the terms of the accumulation model (:mod:`verify.dissipative.
drag_sticking`). A new drag law is a new class here, registered in :data:`LAWS`.

The particle obeys ``y'' = -1 - eta(y')`` with ``eta(V) = k*V`` ("linear") or ``k*V*|V|``
("quadratic"), ``V(0) = v``. ``Y(t) = y(t) - y(0)`` and ``V(t)`` are (``z = -k*t``)::

    linear:  V = v*exp(z) - t*phi1(z),  Y = v*t*phi1(z) - t**2*phi2(z)
             phi1(z) = expm1(z)/z = sum z**n/(n+1)!
             phi2(z) = (expm1(z) - z)/z**2 = sum z**n/(n+2)!

    quadratic, s = sqrt(k), B = s*t, L(x) = log1p(x)/x:
      rising (v > 0, t <= t_top = atan(s*v)/s; V = tan(atan(s*v) - B)/s):
             V = (v - tan(B)/s) / (1 + k*v*tan(B)/s)
             Y = ln(cos(atan(s*v) - B)/cos(atan(s*v)))/k = (x/k)*L(x),
             x/k = (sin(B)/s)*(v - tan(B/2)/s)
             [A = atan(s*v): cos(A-B)/cos(A) - 1 = sin(B)*(tan(A) - tan(B/2))]
      falling from the start (v <= 0; V = -tanh(atanh(-s*v) + B)/s above the terminal
      velocity -1/s, V = -coth(acoth(-s*v) + B)/s at or below it: the same formulas):
             V = (v - tanh(B)/s) / (1 - k*v*tanh(B)/s)
             Y = -ln(cosh(B)*(1 - s*v*tanh(B)))/k = -(x/k)*L(x),
             x/k = (sinh(B)/s)*(tanh(B/2)/s - v)
             [cosh(A+B)/cosh(A) = sinh(A'+B)/sinh(A') = cosh(B)*(1 - s*v*tanh(B)) for
              A = atanh(-s*v), A' = acoth(-s*v); 1 - s*v*tanh(B) > 0 for every v <= 0]
      falling after the top (v > 0, t >= t_top): the v = 0 formulas at t - t_top, plus
             Y(t_top) = log1p(k*v**2)/(2*k) = (v**2/2)*L(k*v**2).

Every quotient by ``s`` or ``k`` is formed from ``sin(B)/s``-type factors that are computed without
cancellation (``sin``, ``tan`` to full relative precision; ``sinh`` by its series for small
arguments), so ``k -> 0`` gives ``V = v - t``, ``Y = t*(v - t/2)`` smoothly; ``k = 0`` is exactly
that. A quadratic-drag departure at or below the terminal velocity (``v <= -1/s``, possible only
after an impact with ``k*eps**2 > 1``) decelerates towards ``-1/s``; the formulas above hold
for it unchanged (every ``v`` is accepted).

Rigour: only ``iv``'s outward-rounded primitives (``exp``, ``ln``, ``sin``, ``cos``, ``tan``,
``sqrt``, ``atan2``) and arithmetic are used; series are summed in ``iv`` and their truncation is
added as an interval ``[-R, R]`` with the bound stated at each series. ``V`` is monotone in ``t``
during a flight (``V' = -1 - eta(V)`` keeps its sign), and ``eta`` is increasing, so the velocity
over a box ``[a, b]`` is the hull of ``V(a)`` and ``V(b)``. Near the top of a quadratic flight,
where the point ``t`` cannot be placed on either side of the enclosure of ``t_top``, the bounds
``|V| <= 2*w`` and ``Y(t_top) - 2*w**2 <= Y <= Y(t_top)`` with ``w = |t - t_top|`` are used
(valid for ``s*w <= 1``: ``tan(x) <= 2*x`` there and ``|Y'| = |V|``).
"""

from __future__ import annotations

from fractions import Fraction

import mpmath

from ..numerics.inputs import check_dps, exact_real
from ..numerics.precision import (
    DEFAULT_DPS,
    GUARD_DPS,
    NotDecided,
    hi,
    iv,
    lo,
    mp,
    to_user,
    working_dps,
)

_SERIES_MAX = 0.5  # series below this |argument|, closed forms above (compared exactly)


def _hull(a, b):
    return iv.mpf([min(lo(a), lo(b)), max(hi(a), hi(b))])


def _ball(radius):
    return iv.mpf([-radius, radius])


def _tiny():
    return mp.mpf(2) ** (-iv.prec - 10)


def _phi(z, j):
    """``phi_j(z) = sum_{n>=0} z**n/(n+j)!`` for ``j`` = 1 or 2 (``z`` an ``iv`` interval).

    ``|z| <= 1/2``: partial sum to ``N`` terms plus ``[-R, R]``, ``R = 2*|z|**N/(N+j)!`` (the tail
    is dominated by a geometric series of ratio ``|z|/(N+j+1) <= 1/2``). Else the closed form
    ``(exp(z) - 1)/z`` or ``(exp(z) - 1 - z)/z**2`` at both ends (``phi_j`` is increasing).
    """
    zmax = max(abs(lo(z)), abs(hi(z)))
    if zmax <= _SERIES_MAX:
        total, term, n = iv.mpf(0), iv.mpf(1) / mp.factorial(j), 0
        tiny = _tiny()
        bound = mp.mpf(1) / mp.factorial(j)  # |z|**n/(n+j)!
        while bound > tiny:
            total += term
            n += 1
            term = term * z / (n + j)
            bound = bound * zmax / (n + j)
        return total + _ball(2 * bound)
    ends = []
    for end in (lo(z), hi(z)):
        x = iv.mpf(end)
        ends.append((iv.exp(x) - 1) / x if j == 1 else (iv.exp(x) - 1 - x) / (x * x))
    return _hull(*ends)


def _sinh_over(x):
    """``sinh(x)/x`` (``x`` a point interval, ``x != 0``): series ``sum x**(2n)/(2n+1)!`` with
    tail ``<= 2*|x|**(2N)/(2N+1)!`` for ``|x| <= 1/2``, else ``(exp(x) - exp(-x))/(2*x)``."""
    xmax = max(abs(lo(x)), abs(hi(x)))
    if xmax <= _SERIES_MAX:
        total, term, n = iv.mpf(0), iv.mpf(1), 0
        tiny = _tiny()
        bound = mp.mpf(1)
        x2 = x * x
        while bound > tiny:
            total += term
            n += 1
            term = term * x2 / ((2 * n) * (2 * n + 1))
            bound = bound * xmax**2 / ((2 * n) * (2 * n + 1))
        return total + _ball(2 * bound)
    return (iv.exp(x) - iv.exp(-x)) / (2 * x)


def _log1p_over(x):
    """``L(x) = log1p(x)/x`` (``L(0) = 1``): series ``sum (-x)**n/(n+1)`` with tail
    ``<= |x|**N/((N+1)*(1-|x|))`` for ``|x| <= 1/4``, else ``ln(1+x)/x`` (``x > -1``)."""
    xmax = max(abs(lo(x)), abs(hi(x)))
    if xmax <= _SERIES_MAX / 2:
        total, term, n = iv.mpf(0), iv.mpf(1), 0
        tiny = _tiny()
        bound = mp.mpf(1)
        while bound > tiny:
            total += term / (n + 1)
            n += 1
            term = -term * x
            bound = bound * xmax
        return total + _ball(bound / ((n + 1) * (1 - xmax)))
    if not lo(x) > -1:
        raise NotDecided("log1p of an argument not proved > -1")
    return iv.ln(1 + x) / x


class LinearDrag:
    """``eta(V) = k*V``."""

    name = "linear"

    @staticmethod
    def eta(k, vel):
        """``eta`` over the interval ``vel`` (``k`` an interval)."""
        return k * vel

    @staticmethod
    def eta_prime(k, vel):
        """``eta'(V) = k``."""
        return k

    @staticmethod
    def top_time(flight):
        """Time of the top of a rising flight where the closed form changes branch: none."""
        return None

    @staticmethod
    def motion(flight, it):
        """``(Y, V)`` at the time interval ``it``, ``z = -k*t``::

            V = v*exp(z) - t*phi1(z),  Y = v*t*phi1(z) - t**2*phi2(z)."""
        z = -flight.iv_k * it
        p1, p2 = _phi(z, 1), _phi(z, 2)
        vel = flight.iv_v * iv.exp(z) - it * p1
        disp = flight.iv_v * it * p1 - it * it * p2
        return disp, vel

    @staticmethod
    def leaves_plate(e: Fraction, k: Fraction) -> bool:
        """A particle riding the plate ever leaves it (exact, ``e = |eps|``):
        ``min a = 1 - e*sqrt(1 + k**2) < 0`` (:mod:`verify.dissipative.drag_sticking`, 2.)."""
        return e * e * (1 + k * k) > 1

    @staticmethod
    def riding_candidates(eps, k):
        """Non-rigorous ``(theta*, theta_2)`` (roots of the riding force, current precision):
        ``beta' -+ alpha``, ``beta' = atan(k)`` (``+ pi`` for ``eps < 0``),
        ``alpha = arccos(1/E) = atan(sqrt(E**2 - 1))``, ``E = |eps|*sqrt(1 + k**2)``."""
        e = abs(eps)
        shift = mp.zero if eps > 0 else mp.pi
        big_e2 = e * e * (1 + k * k)
        alpha = mp.atan(mp.sqrt(big_e2 - 1))
        beta = mp.atan(k) + shift
        return beta - alpha, beta + alpha

    @staticmethod
    def tail_terms(eps, k, u):
        """``(c, A2, p2)`` of the accumulation model: ``c = eta'(u) = k``, ``A2 = |eps|*(1 + k)``
        bounds ``|A''|``, ``p2 = |eta''| = 0``."""
        return k, abs(eps) * (1 + k), 0


class QuadraticDrag:
    """``eta(V) = k*V*|V|``."""

    name = "quadratic"

    @staticmethod
    def eta(k, vel):
        """``eta`` over the interval ``vel`` (nondecreasing: from the ends; ``k`` an interval)."""
        ends = [k * iv.mpf(x) * abs(x) for x in (lo(vel), hi(vel))]
        return _hull(*ends)

    @staticmethod
    def eta_prime(k, vel):
        """``eta'(V) = 2*k*|V|``."""
        return 2 * k * abs(vel)

    @staticmethod
    def top_time(flight):
        """``t_top = atan(s*v)/s`` for a rising flight (``v > 0``), else None."""
        if flight.v > 0:
            return iv.atan2(flight.s * flight.iv_v, 1) / flight.s
        return None

    @staticmethod
    def motion(flight, it):
        """``(Y, V)`` at the time interval ``it`` (module docstring: rising, falling from the
        start, falling after the top, and the bounds at the top)."""
        if flight.t_top is None:  # v <= 0: falling from the start
            return _falling(flight, it, flight.iv_v)
        tau = it - flight.t_top
        if hi(tau) <= 0:
            return _rising(flight, it)
        y_top = flight.iv_v * flight.iv_v / 2 * _log1p_over(flight.iv_k * flight.iv_v
                                                             * flight.iv_v)
        if lo(tau) >= 0:
            disp, vel = _falling(flight, tau, iv.mpf(0))
            return y_top + disp, vel
        w = max(-lo(tau), hi(tau))  # t within the enclosure of t_top: the bounds at the top
        if hi(flight.s * w) > 1:
            raise NotDecided("t too close to the top of the flight at this precision")
        return y_top - iv.mpf([0, 2 * w * w]), _ball(2 * w)

    @staticmethod
    def leaves_plate(e: Fraction, k: Fraction) -> bool:
        """A particle riding the plate ever leaves it (exact, ``e = |eps|``; the maximum of
        ``f = e*cos + k*e**2*sin*|sin|`` exceeds 1, :mod:`verify.dissipative.drag_sticking`,
        2.)."""
        if 2 * k * e > 1:
            return 4 * k * k * e * e - 4 * k + 1 > 0
        return e > 1

    @staticmethod
    def riding_candidates(eps, k):
        """Non-rigorous ``(theta*, theta_2)``: bisection of ``f - 1`` on the increasing and the
        decreasing branch of ``f`` (:mod:`verify.dissipative.drag_sticking`, 2.)."""
        e = abs(eps)
        shift = mp.zero if eps > 0 else mp.pi

        def f(x):
            s = mp.sin(x)
            return e * mp.cos(x) + k * e * e * s * abs(s)

        if 2 * k * e > 1:
            c = 1 / (2 * k * e)
            t_min, t_max = -mp.acos(-c), mp.acos(c)
        else:
            t_min, t_max = -mp.pi, mp.zero
        star = _bisect(f, t_min, t_max, rising=True)
        two = _bisect(f, t_max, t_min + 2 * mp.pi, rising=False)
        return star + shift, two + shift

    @staticmethod
    def tail_terms(eps, k, u):
        """``(c, A2, p2)`` of the accumulation model: ``c = eta'(u) = 2*k*|u|``,
        ``A2 = |eps| + 2*k*eps**2`` bounds ``|A''|``, ``p2 = |eta''| = 2*k``."""
        return 2 * k * abs(u), abs(eps) + 2 * k * eps**2, 2 * k


LAWS = {law.name: law for law in (LinearDrag, QuadraticDrag)}
"""The drag laws by name (the ``drag_law`` keyword of the public functions)."""


def check_drag(drag, drag_law):
    """``(k, law name)`` validated: ``drag`` finite ``>= 0`` (an exact ``mpf``), ``drag_law`` a
    name in :data:`LAWS`; ``ValueError`` naming the bad value."""
    k = exact_real("drag", drag)
    if k < 0:
        raise ValueError(f"drag must be finite and >= 0, got drag={drag!r}")
    if not isinstance(drag_law, str) or drag_law not in LAWS:
        raise ValueError(f"drag_law must be 'linear' or 'quadratic', got drag_law={drag_law!r}")
    return k, drag_law


def _bisect(f, a, b, rising):
    for _ in range(mp.prec + 20):
        m = (a + b) / 2
        if not a < m < b:
            break
        if (f(m) - 1 < 0) == rising:
            a = m
        else:
            b = m
    return (a + b) / 2


def _rising(flight, it):
    s, v = flight.s, flight.iv_v
    b = s * it
    tan_over = iv.tan(b) / s
    vel = (v - tan_over) / (1 + flight.iv_k * v * tan_over)
    x_over_k = (iv.sin(b) / s) * (v - iv.tan(b / 2) / s)
    return x_over_k * _log1p_over(flight.iv_k * x_over_k), vel


def _falling(flight, it, v):
    """Falling from velocity ``v <= 0`` (above, at or below the terminal velocity ``-1/s``) for
    the time ``it`` (an interval)."""
    s = flight.s
    b = s * it
    cosh_b = (iv.exp(b) + iv.exp(-b)) / 2
    sinh_over_s = it * _sinh_over(b)
    tanh_over_s = sinh_over_s / cosh_b
    half = b / 2
    tanh_half_over_s = (it / 2) * _sinh_over(half) / ((iv.exp(half) + iv.exp(-half)) / 2)
    vel = (v - tanh_over_s) / (1 - flight.iv_k * v * tanh_over_s)
    x_over_k = sinh_over_s * (tanh_half_over_s - v)
    return -x_over_k * _log1p_over(flight.iv_k * x_over_k), vel


class DragFlight:
    """Closed-form motion of one flight: ``V(t)``, ``Y(t)`` and ``eta`` as ``iv`` enclosures.

    Built in the current precision from the departure velocity ``v`` (an exact ``mpf``, or an
    ``iv`` interval of departure velocities whose sign is decided: every enclosure then holds
    for each velocity in it), the drag ``k`` and the law (a name in :data:`LAWS`); ``t``
    arguments are exact ``mpf`` (``>= 0``) or, for :meth:`velocity_box`, two ends.
    """

    def __init__(self, v, k: mpmath.mpf, law) -> None:
        if hasattr(v, "_mpf_"):  # an exact point
            self.v, self.iv_v = v, iv.mpf(v)
        else:
            if not (lo(v) > 0 or hi(v) < 0):
                raise NotDecided("the departure velocity is within rounding of 0")
            self.v, self.iv_v = (lo(v) + hi(v)) / 2, v
        self.k, self.law = k, LAWS[law] if isinstance(law, str) else law
        self.iv_k = iv.mpf(k)
        self.s = iv.sqrt(self.iv_k)
        self.t_top = None
        if self.law is QuadraticDrag and k > 0:
            self.t_top = self.law.top_time(self)

    # --- the drag force --------------------------------------------------------------------
    def eta(self, vel):
        """``eta(V)`` over an interval ``V`` (increasing in ``V``: evaluated at both ends)."""
        return self.law.eta(self.iv_k, vel)

    def eta_prime(self, vel):
        """``eta'(V)``."""
        return self.law.eta_prime(self.iv_k, vel)

    # --- motion ----------------------------------------------------------------------------
    def motion(self, t):
        """``(Y(t), V(t))`` as ``iv`` intervals for the exact ``t >= 0``."""
        if t == 0:
            return iv.mpf(0), self.iv_v
        it = iv.mpf(t)
        if self.k == 0:
            return it * (self.iv_v - it / 2), self.iv_v - it
        return self.law.motion(self, it)

    def velocity(self, t):
        return self.motion(t)[1]

    def displacement(self, t):
        return self.motion(t)[0]

    def velocity_box(self, a, b):
        """Enclosure of ``V`` over ``[a, b]``: ``V`` is monotone in ``t``, so the hull of ends."""
        return _hull(self.velocity(a), self.velocity(b))


def motion(v, t, drag, drag_law: str = "linear",
           dps: int = DEFAULT_DPS) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Point values ``(Y(t), V(t))`` at ``dps`` digits: midpoints of the enclosures computed at
    ``dps + 10`` digits (inputs taken as exact binary values)."""
    dps = check_dps(dps)
    k, law = check_drag(drag, drag_law)
    v_, t_ = exact_real("v", v), exact_real("t", t)
    if t_ < 0:
        raise ValueError(f"t must be >= 0, got t={t!r}")
    with working_dps(dps + GUARD_DPS):
        disp, vel = DragFlight(v_, k, law).motion(t_)
        y, u = (lo(disp) + hi(disp)) / 2, (lo(vel) + hi(vel)) / 2
    with working_dps(dps):
        return to_user((+y, +u))
