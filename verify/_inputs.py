"""Validation of inputs; every real is taken as the exact binary value it holds."""

from __future__ import annotations

import numbers

import mpmath
from mpmath import mp
from mpmath.ctx_mp_python import _mpf as _mpf_base


def exact_real(name: str, x) -> mpmath.mpf:
    """``x`` as an ``mpf`` without rounding; ``ValueError`` for NaN, inf or non-reals."""
    if type(x) is mpmath.mpf:
        val = x
    elif isinstance(x, _mpf_base):  # a lazy constant such as mp.pi: freeze it at caller precision
        val = mp.mpf(x)
    elif isinstance(x, bool) or not isinstance(x, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {x!r}")
    elif isinstance(x, numbers.Integral):
        n = int(x)
        with mp.workprec(max(53, n.bit_length() + 2)):
            val = mp.mpf(n)
    else:
        with mp.workprec(64):  # a float64 (or narrower) converts exactly at >= 53 bits
            val = mp.mpf(float(x))
    if mp.isnan(val) or mp.isinf(val):
        raise ValueError(f"{name} must be finite, got {name}={x!r}")
    return val


def check_dps(dps, name: str = "dps") -> int:
    """Return ``dps`` as an int >= 15, else raise ``ValueError`` naming it."""
    if isinstance(dps, bool) or not isinstance(dps, numbers.Integral):
        raise ValueError(f"{name} must be an integer >= 15, got {name}={dps!r}")
    if dps < 15:
        raise ValueError(f"{name} must be >= 15, got {name}={dps!r}")
    return int(dps)
