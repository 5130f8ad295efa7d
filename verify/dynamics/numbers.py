"""Private mpmath contexts and the small interval vocabulary of the dynamics certificates.

Every certificate creates its own point context (``mpmath.MPContext``) and interval context
(``mpmath.ctx_iv.MPIntervalContext``) at its working precision, so the global ``mp``/``iv``
precision is never read or changed and calls in different threads do not interact.

Inputs are taken as exact binary values (a float64 is exactly a dyadic rational), converted
through mpmath's raw representation without rounding.
"""

from __future__ import annotations

import math
import numbers
from typing import NamedTuple

import mpmath
from mpmath import ctx_iv
from mpmath.libmp import dps_to_prec, from_float, from_int


class Contexts(NamedTuple):
    """A point context ``mp`` and an interval context ``iv`` at the same precision."""

    mp: mpmath.MPContext
    iv: ctx_iv.MPIntervalContext
    dps: int


def contexts(dps: int) -> Contexts:
    """Fresh point and interval contexts at ``dps`` decimal digits."""
    mp, iv = mpmath.MPContext(), ctx_iv.MPIntervalContext()
    mp.prec = iv.prec = dps_to_prec(dps)
    return Contexts(mp, iv, dps)


def exact_raw(name: str, x):
    """The exact raw mpf tuple of a real input; ValueError for NaN, inf or non-reals."""
    if hasattr(x, "_mpf_"):
        raw = x._mpf_
    elif isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {name}={x!r}")
    elif isinstance(x, numbers.Integral):
        raw = from_int(int(x))
    else:
        value = float(x)
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {name}={x!r}")
        raw = from_float(value)
    if raw in (mpmath.libmp.fnan, mpmath.libmp.finf, mpmath.libmp.fninf):
        raise ValueError(f"{name} must be finite, got {name}={x!r}")
    return raw


def lo(x):
    """Lower end of an interval, as an exact mpf of the global context (no rounding)."""
    return mpmath.mp.make_mpf(x._mpi_[0])


def hi(x):
    """Upper end of an interval, as an exact mpf of the global context (no rounding)."""
    return mpmath.mp.make_mpf(x._mpi_[1])


def positive(x) -> bool:
    """The interval lies in (0, inf): proved positive."""
    return lo(x) > 0


def negative(x) -> bool:
    """The interval lies in (-inf, 0): proved negative."""
    return hi(x) < 0


class Enclosure(NamedTuple):
    """A closed interval [lo, hi] of exact mpf ends that contains a quantity."""

    lo: mpmath.mpf
    hi: mpmath.mpf

    @classmethod
    def of(cls, x) -> Enclosure:
        return cls(lo(x), hi(x))

    def __contains__(self, value) -> bool:
        return self.lo <= value <= self.hi

    @property
    def mid(self) -> float:
        return float((self.lo + self.hi) / 2)

    @property
    def width(self) -> float:
        return float(self.hi - self.lo)

    def __float__(self) -> float:
        return self.mid

    def __repr__(self) -> str:
        return f"[{mpmath.nstr(self.lo, 17)}, {mpmath.nstr(self.hi, 17)}]"


# --- 2x2 interval matrices as tuples (a11, a12, a21, a22) -------------------------------------

def mat_mul(a, b):
    """Product of two 2x2 matrices given as 4-tuples (interval or point entries)."""
    return (a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3],
            a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3])


def mat_vec(a, x):
    """2x2 matrix times a 2-vector."""
    return (a[0] * x[0] + a[1] * x[1], a[2] * x[0] + a[3] * x[1])
