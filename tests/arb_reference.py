"""A second reference for the first collision, in python-flint's ``arb`` balls (not a test module).

It shares no code with ``verify`` (nor ``fastpath``): its own phase reduction, its own closed
forms of the drag flights and its own proof, a lower-bound scan:

* ``d(t) = 2*eps*sin(r + t/2)*sin(t/2) + Y(t)`` with ``r = phi - 2*pi*m`` reduced in ``arb`` at
  a precision raised by the exponent of ``phi`` (``m`` any integer: the ball of ``2*pi*m`` is
  exact enough), ``Y(t) = t*(v - t/2)`` without drag, the textbook closed forms with drag;
  ``d'(t) = V(t) + eps*sin(r + t)``, ``d''(t) = -1 - eta(V(t)) + eps*cos(r + t)``.
* The scan starts at ``t = w0/A`` (``d(t) >= w0*t - A*t**2/2 > 0`` before, ``A`` a bound of
  ``-d''``) and steps by the larger root ``s`` of ``g + p*s - a*s**2/2`` with ``g``, ``p`` the
  lower ends of the balls of ``d(t)``, ``d'(t)`` and ``a`` the upper end of the ball of
  ``-d''`` over the window ``[t, t + L]`` (the step kept inside the window): by Taylor's
  theorem ``d > 0`` on ``[t, t + s)``. Every step is a proof; there is no concavity shortcut.
* When the steps stall (``d(t)`` within its rounding of 0), a point ``t2`` just ahead with
  ``d(t2) < 0`` proved encloses the first root in ``(t, t2)``; otherwise the precision is
  doubled (up to ``MAX_PREC`` bits) and the scan redone.

The enclosure is returned as exact ``fractions.Fraction`` ends, so a caller compares it with
any other number exactly.
"""

from __future__ import annotations

from fractions import Fraction

import flint
from flint import arb

START_PREC = 128
MAX_PREC = 4096
MAX_STEPS = 200_000


class NoDeparture(ValueError):
    """``w0 = v + eps*sin(phi) < 0``: no flight."""


def _exact(x: float) -> arb:
    return arb(Fraction(x).numerator) / arb(Fraction(x).denominator)


def _fraction(x: arb) -> Fraction:
    """The exact value of an exact arb (a ball of radius 0)."""
    man, exp = x.mid().man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def _point(q: Fraction) -> arb:
    return arb(q.numerator) / arb(q.denominator)


def reduced_phase(phi: float) -> arb:
    """``phi - 2*pi*m`` as a ball at the current precision, computed at ``prec + exponent``."""
    prec = flint.ctx.prec
    exponent = max(0, abs(Fraction(phi)).numerator.bit_length()
                   - abs(Fraction(phi)).denominator.bit_length())
    flint.ctx.prec = prec + exponent + 32
    try:
        two_pi = 2 * arb.pi()
        m = (_exact(phi) / two_pi).mid().floor()
        r = _exact(phi) - two_pi * m
    finally:
        flint.ctx.prec = prec
    return +r


class _Flight:
    """The particle's motion ``(Y(t), V(t))`` for an exact time ``t`` (ball), its force
    ``eta`` and the velocity's range over a window (``V`` is monotone during a flight)."""

    def __init__(self, v: float, k: float, law: str):
        self.v, self.k, self.law = _exact(v), _exact(k), law
        self.drag = k > 0
        if self.drag and law == "quadratic":
            self.s = self.k.sqrt()

    def eta(self, vel: arb) -> arb:
        """``eta`` over the ball ``vel`` (``eta`` is increasing: from the ball's ends)."""
        if not self.drag:
            return arb(0)
        if self.law == "linear":
            return self.k * vel
        low, high = vel.lower(), vel.upper()
        return (self.k * low * abs(low)).union(self.k * high * abs(high))

    def motion(self, t: arb) -> tuple[arb, arb]:
        v, k = self.v, self.k
        if not self.drag:
            return t * (v - t / 2), v - t
        if self.law == "linear":
            z = (-k * t).exp()
            return (v + 1 / k) * (1 - z) / k - t / k, v * z - (1 - z) / k
        return self._quadratic(t)

    def _quadratic(self, t: arb) -> tuple[arb, arb]:
        v, k, s = self.v, self.k, self.s
        if v > 0:
            a = (s * v).atan()
            top = a / s
            rising = ((a - s * t).cos() / a.cos()).log() / k, (a - s * t).tan() / s
            after = t - top
            falling = (1 / a.cos()).log() / k - (s * after).cosh().log() / k, \
                -(s * after).tanh() / s
            if t < top:
                return rising
            if t > top:
                return falling
            return rising[0].union(falling[0]), rising[1].union(falling[1])
        x = -s * v  # >= 0
        branches = []
        if not x >= 1:
            a = x.atanh()
            branches.append((-((a + s * t).cosh() / a.cosh()).log() / k, -(a + s * t).tanh() / s))
        if not x <= 1:
            a = (1 / x).atanh()  # acoth(x)
            branches.append((-((a + s * t).sinh() / a.sinh()).log() / k, -(a + s * t).coth() / s))
        if x.contains(1):
            branches.append((v * t, v + 0 * t))
        y, vel = branches[0]
        for other in branches[1:]:
            y, vel = y.union(other[0]), vel.union(other[1])
        return y, vel

    def velocity_range(self, t: arb, end: arb) -> arb:
        return self.motion(t)[1].union(self.motion(end)[1])


class _Gap:
    def __init__(self, phi, v, eps, k, law):
        self.r = reduced_phase(phi)
        self.eps = _exact(eps)
        self.flight = _Flight(v, k, law)

    def value_and_slope(self, t: arb) -> tuple[arb, arb]:
        y, vel = self.flight.motion(t)
        plate = 2 * self.eps * (self.r + t / 2).sin() * (t / 2).sin()
        return y + plate, vel + self.eps * (self.r + t).sin()

    def minus_curvature(self, t: arb, end: arb) -> arb:
        window = t.union(end)
        vel = self.flight.velocity_range(t, end)
        return 1 + self.flight.eta(vel) - self.eps * (self.r + window).cos()


def _step(g: arb, p: arb, a: arb) -> arb | None:
    """Lower end of the larger root of ``g + p*s - a*s**2/2`` (``g > 0``), or None for no root."""
    if a <= 0:
        return None if p >= 0 else g / -p
    disc = (p * p + 2 * a * g).sqrt()
    return (p + disc) / a if p >= 0 else 2 * g / (disc - p)


def _scan(phi, v, eps, k, law):
    gap = _Gap(phi, v, eps, k, law)
    _, w0 = gap.value_and_slope(arb(0))
    if w0 < 0:
        raise NoDeparture(f"w0 < 0 for phi={phi}, v={v}, eps={eps}")
    if not w0 > 0:
        return None
    big_a = (1 + gap.flight.eta(gap.flight.v)).upper()
    big_a = (big_a if big_a > 0 else arb(0)) + abs(gap.eps)
    t = (w0.lower() / big_a).lower()  # d >= w0*t - A*t**2/2 > 0 on (0, 2*w0/A)
    shrink = 1 - arb(2) ** -30
    for _ in range(MAX_STEPS):
        d, p = gap.value_and_slope(t)
        g, slope = d.lower(), p.lower()
        if g > 0:
            length = _step(g, slope, big_a)
            length = 4 * t if length is None else length
            s = None
            for _ in range(60):  # windows of growing length while the step spans them
                end = (t + length).upper()
                step = _step(g, slope, gap.minus_curvature(t, end).upper())
                if step is None or step >= length:  # d > 0 on the whole window
                    s, length = length, 4 * length
                    continue
                if s is None or step > s:  # the root of the bound is inside the window
                    s = step
                break
            new_t = (t + (s * shrink).lower()).lower()
            if new_t > t + t * arb(2) ** (20 - flint.ctx.prec):
                t = new_t
                continue
        # stalled: d(t) is within its rounding of 0 (d > 0 is proved on (0, t])
        for scale in (2, 16, 256):
            width = abs(d.mid()) + d.rad() + t * arb(2) ** (8 - flint.ctx.prec)
            ahead = (t + scale * width / (abs(p.mid()) + p.rad())).upper()
            if gap.value_and_slope(ahead)[0] < 0:
                return t, ahead
        return None
    return None


def first_root(phi: float, v: float, eps: float, k: float = 0.0, law: str = "linear"):
    """``(lo, hi)`` exact ``Fraction``s with the first root of the gap in ``(lo, hi)``, ``d > 0``
    proved on ``(0, lo]``; None when it stays undecided at ``MAX_PREC`` bits.
    :class:`NoDeparture` for ``w0 < 0``."""
    old = flint.ctx.prec
    prec = START_PREC
    try:
        while prec <= MAX_PREC:
            flint.ctx.prec = prec
            found = _scan(phi, v, eps, k, law)
            if found is not None:
                return _fraction(found[0]), _fraction(found[1])
            prec *= 2
        return None
    finally:
        flint.ctx.prec = old
