"""Validation of inputs: ONE validator for every public verify function.

Every real is taken as the exact binary value it holds (a float64 converts to ``mpf`` without
rounding). The rules, each failure a ``ValueError`` that names the bad value:

* ``phi``, ``v``, ``eps`` (and ``tau``, ``clearance``, ...): finite real numbers; ``bool`` and
  ``str`` are rejected, not converted;
* a departure needs ``w0 = d'(0) = v + eps*sin(phi) > 0`` (the particle leaves the plate),
  rejected when ``w0 <= 0`` is proved in interval arithmetic; a ``w0`` too close to 0 to decide
  here passes and is decided (or reported undecidable) by the certificate;
* a time ``tau`` passed with a state must be ``> 0``;
* ``dps`` (digits) is an int ``>= 15`` (a bool is not an int here).

The physics keywords (drag, drag law, restitution) are validated with the physics description,
:func:`verify.dissipative.physics.check_physics`.
"""

from __future__ import annotations

import numbers
from typing import NamedTuple

import mpmath
from mpmath.libmp import from_int, from_man_exp

from .phase import reduce_phase
from .precision import hi, iv, lo, mp, working_dps

MIN_DPS = 15
_W0_CHECK_DPS = 30  # w0 is checked at this many digits (after an exact phase reduction)


class State(NamedTuple):
    """Validated inputs as exact ``mpf`` (``tau`` is None where none was passed)."""

    phi: mpmath.mpf
    v: mpmath.mpf
    eps: mpmath.mpf
    tau: mpmath.mpf | None
    dps: int | None


def exact_real(name: str, x) -> mpmath.mpf:
    """``x`` as an ``mpf`` of this thread's context without rounding.

    Every real is taken as the exact binary number it holds: an ``int``, a ``float`` or numpy
    float of any width (``np.float32``, ``np.longdouble``), an mpmath ``mpf`` (a lazy constant
    such as ``mpmath.mp.pi`` is taken at its own context's precision), or a rational such as
    ``fractions.Fraction`` whose denominator is a power of two. ``ValueError`` for NaN, inf,
    non-reals (``bool``, ``str``, complex), and reals that are not binary numbers
    (``Fraction(1, 3)``), which would need a rounding verify does not choose for the caller.
    """
    if hasattr(x, "_mpf_"):
        val = mp.make_mpf(x._mpf_)
    elif isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {name}={x!r}")
    elif isinstance(x, numbers.Integral):
        val = mp.make_mpf(from_int(int(x)))
    else:
        num, den = _integer_ratio(name, x)
        if den & (den - 1):
            raise ValueError(
                f"{name} must be a binary number (a float, an mpf, or a fraction with a power-of-2 "
                f"denominator), got {name}={x!r}: round it to the precision you mean first"
            )
        val = mp.make_mpf(from_man_exp(num, 1 - den.bit_length()))
    if mp.isnan(val) or mp.isinf(val):
        raise ValueError(f"{name} must be finite, got {name}={x!r}")
    return val


def _integer_ratio(name: str, x) -> tuple[int, int]:
    """``(numerator, denominator)`` of the real ``x`` exactly (``ValueError`` if not finite)."""
    if isinstance(x, numbers.Rational):
        return int(x.numerator), int(x.denominator)
    try:
        num, den = x.as_integer_ratio()
    except (OverflowError, ValueError):
        raise ValueError(f"{name} must be finite, got {name}={x!r}") from None
    except AttributeError:
        raise ValueError(f"{name} must be a real number with an exact binary value, "
                         f"got {name}={x!r}") from None
    return int(num), int(den)


def check_dps(dps, name: str = "dps") -> int:
    """Return ``dps`` as an int >= 15, else raise ``ValueError`` naming it."""
    if isinstance(dps, bool) or not isinstance(dps, numbers.Integral):
        raise ValueError(f"{name} must be an integer >= {MIN_DPS}, got {name}={dps!r}")
    if dps < MIN_DPS:
        raise ValueError(f"{name} must be >= {MIN_DPS}, got {name}={dps!r}")
    return int(dps)


_NO_TAU = object()


def check_state(phi, v, eps, *, tau=_NO_TAU, dps=None, names=("phi", "v", "eps"),
                w0_zero_ok=False) -> State:
    """Validate a departure ``(phi, v, eps)``, optionally a time ``tau`` and digits ``dps``.

    ``names`` are the argument names used in the messages (``("phi0", "v0", "eps")`` for
    :func:`verify.orbit`). See the module docstring for the rules. ``w0_zero_ok``: a ``w0``
    proved to be exactly 0 passes (a departure at rest relative to the plate, which
    :func:`verify.certify_flight` accepts only when the gap is proved to open, see
    :mod:`verify.dissipative.drag_gap`).
    """
    phi_, v_, eps_ = (exact_real(n, x) for n, x in zip(names, (phi, v, eps), strict=True))
    dps_ = None if dps is None else check_dps(dps)
    w0_lo, w0_hi = _w0_enclosure(phi_, v_, eps_)
    if w0_hi < 0 or (w0_hi == 0 and not (w0_zero_ok and w0_lo == 0)):
        raise ValueError(
            f"no departure: w0 = v + eps*sin(phi) = {mp.nstr(w0_hi, 8)} <= 0 "
            f"({names[0]}={phi!r}, {names[1]}={v!r}, {names[2]}={eps!r})"
        )
    tau_ = None
    if tau is not _NO_TAU:
        tau_ = exact_real("tau", tau)
        if tau_ <= 0:
            raise ValueError(f"tau must be > 0, got tau={tau!r}")
    return State(phi_, v_, eps_, tau_, dps_)


def w0_is_zero(phi, v, eps) -> bool:
    """``w0 = v + eps*sin(phi)`` is exactly 0 (its interval enclosure is the point 0)."""
    return _w0_enclosure(phi, v, eps) == (0, 0)


def _w0_enclosure(phi, v, eps) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Ends of an interval enclosure of ``w0 = v + eps*sin(phi)``."""
    with working_dps(_W0_CHECK_DPS) as prec:
        w0 = iv.mpf(v) + iv.mpf(eps) * iv.sin(reduce_phase(phi, prec).enclosure)
        return lo(w0), hi(w0)
