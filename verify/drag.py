"""Flights with air drag in closed form: interval enclosures (``mpmath.iv``) stable as drag -> 0.

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
      falling from the start (-1/s < v <= 0; V = -tanh(atanh(-s*v) + B)/s):
             V = (v - tanh(B)/s) / (1 - k*v*tanh(B)/s)
             Y = -ln(cosh(A+B)/cosh(A))/k = -(x/k)*L(x),  x/k = (sinh(B)/s)*(tanh(B/2)/s - v)
      falling after the top (v > 0, t >= t_top): the v = 0 formulas at t - t_top, plus
             Y(t_top) = log1p(k*v**2)/(2*k) = (v**2/2)*L(k*v**2).

Every quotient by ``s`` or ``k`` is formed from ``sin(B)/s``-type factors that are computed without
cancellation (``sin``, ``tan`` to full relative precision; ``sinh`` by its series for small
arguments), so ``k -> 0`` gives ``V = v - t``, ``Y = t*(v - t/2)`` smoothly; ``k = 0`` is exactly
that. A quadratic-drag departure at or below the terminal velocity (``v <= -1/s``, possible only
after an impact with ``k*eps**2 > 1``) is rejected with ``ValueError``: its ``coth`` branch is not
implemented.

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

import mpmath
from mpmath import iv, mp

from ._inputs import check_dps, check_physics, exact_real
from ._precision import hi, lo, working_dps

_SERIES_MAX = mp.mpf(1) / 2  # series below this |argument|, closed forms above


class NotDecided(ArithmeticError):
    """An interval evaluation could not be done at this precision (raise it and retry)."""


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


class DragFlight:
    """Closed-form motion of one flight: ``V(t)``, ``Y(t)`` and ``eta`` as ``iv`` enclosures.

    Built in the current precision from exact ``v`` and ``k``; ``t`` arguments are exact ``mpf``
    (``>= 0``) or, for :meth:`velocity_box`, two ends.
    """

    def __init__(self, v: mpmath.mpf, k: mpmath.mpf, law: str) -> None:
        self.v, self.k, self.law = v, k, law
        self.iv_v, self.iv_k = iv.mpf(v), iv.mpf(k)
        self.s = iv.sqrt(self.iv_k)
        self.t_top = None
        if law == "quadratic" and k > 0:
            if v < 0 and k * v * v >= 1:  # exact: at or below the terminal velocity -1/s
                raise ValueError(
                    "quadratic drag: departure at or below the terminal velocity "
                    f"(v <= -1/sqrt(k)) is not supported, got v={mp.nstr(v, 17)}, "
                    f"drag={mp.nstr(k, 17)}"
                )
            if v > 0:
                self.t_top = iv.atan2(self.s * self.iv_v, 1) / self.s

    # --- the drag force --------------------------------------------------------------------
    def eta(self, vel):
        """``eta(V)`` over an interval ``V`` (increasing in ``V``: evaluated at both ends)."""
        if self.law == "linear":
            return self.iv_k * vel
        ends = [self.iv_k * iv.mpf(x) * abs(mp.mpf(x)) for x in (lo(vel), hi(vel))]
        return _hull(*ends)

    def eta_prime(self, vel):
        """``eta'(V)``: ``k`` or ``2*k*|V|``."""
        return self.iv_k if self.law == "linear" else 2 * self.iv_k * abs(vel)

    # --- motion ----------------------------------------------------------------------------
    def motion(self, t):
        """``(Y(t), V(t))`` as ``iv`` intervals for the exact ``t >= 0``."""
        if t == 0:
            return iv.mpf(0), self.iv_v
        it = iv.mpf(t)
        if self.k == 0:
            return it * (self.iv_v - it / 2), self.iv_v - it
        if self.law == "linear":
            return self._linear(it)
        return self._quadratic(it)

    def velocity(self, t):
        return self.motion(t)[1]

    def displacement(self, t):
        return self.motion(t)[0]

    def velocity_box(self, a, b):
        """Enclosure of ``V`` over ``[a, b]``: ``V`` is monotone in ``t``, so the hull of ends."""
        return _hull(self.velocity(a), self.velocity(b))

    def _linear(self, it):
        z = -self.iv_k * it
        p1, p2 = _phi(z, 1), _phi(z, 2)
        vel = self.iv_v * iv.exp(z) - it * p1
        disp = self.iv_v * it * p1 - it * it * p2
        return disp, vel

    def _quadratic(self, it):
        if self.t_top is None:  # v <= 0: falling from the start
            return self._falling(it, self.iv_v)
        tau = it - self.t_top
        if hi(tau) <= 0:
            return self._rising(it)
        y_top = self.iv_v * self.iv_v / 2 * _log1p_over(self.iv_k * self.iv_v * self.iv_v)
        if lo(tau) >= 0:
            disp, vel = self._falling(tau, iv.mpf(0))
            return y_top + disp, vel
        w = max(-lo(tau), hi(tau))  # t within the enclosure of t_top: the bounds at the top
        if hi(self.s * w) > 1:
            raise NotDecided("t too close to the top of the flight at this precision")
        return y_top - iv.mpf([0, 2 * w * w]), _ball(2 * w)

    def _rising(self, it):
        s, v = self.s, self.iv_v
        b = s * it
        tan_over = iv.tan(b) / s
        vel = (v - tan_over) / (1 + self.iv_k * v * tan_over)
        x_over_k = (iv.sin(b) / s) * (v - iv.tan(b / 2) / s)
        return x_over_k * _log1p_over(self.iv_k * x_over_k), vel

    def _falling(self, it, v):
        """Falling from velocity ``v`` (``-1/s < v <= 0``) for the time ``it`` (an interval)."""
        s = self.s
        b = s * it
        cosh_b = (iv.exp(b) + iv.exp(-b)) / 2
        sinh_over_s = it * _sinh_over(b)
        tanh_over_s = sinh_over_s / cosh_b
        half = b / 2
        tanh_half_over_s = (it / 2) * _sinh_over(half) / ((iv.exp(half) + iv.exp(-half)) / 2)
        vel = (v - tanh_over_s) / (1 - self.iv_k * v * tanh_over_s)
        x_over_k = sinh_over_s * (tanh_half_over_s - v)
        return -x_over_k * _log1p_over(self.iv_k * x_over_k), vel


def motion(v, t, drag, drag_law: str = "linear", dps: int = 50) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Point values ``(Y(t), V(t))`` at ``dps`` digits: midpoints of the enclosures computed at
    ``dps + 10`` digits (inputs taken as exact binary values)."""
    dps = check_dps(dps)
    phys = check_physics(drag, drag_law)
    v_, t_ = exact_real("v", v), exact_real("t", t)
    if t_ < 0:
        raise ValueError(f"t must be >= 0, got t={t!r}")
    with working_dps(dps + 10):
        disp, vel = DragFlight(v_, phys.drag, phys.drag_law).motion(t_)
        y, u = (lo(disp) + hi(disp)) / 2, (lo(vel) + hi(vel)) / 2
    with working_dps(dps):
        return +y, +u
