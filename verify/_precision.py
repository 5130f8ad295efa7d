"""Local precision for the point (``mp``) and interval (``iv``) contexts.

Both contexts are raised together and restored in ``finally``: the global precision a caller
set is never changed permanently.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from mpmath import iv, mp
from mpmath.libmp import dps_to_prec


@contextmanager
def working_dps(dps: int) -> Iterator[int]:
    """Set ``mp`` and ``iv`` to ``dps`` decimal digits for the block; yield the bit precision."""
    prec = dps_to_prec(dps)
    old_mp, old_iv = mp.prec, iv.prec
    try:
        mp.prec = prec
        iv.prec = prec
        yield prec
    finally:
        mp.prec = old_mp
        iv.prec = old_iv


def lo(x) -> mp.mpf:
    """Lower end of an ``iv`` interval as an exact ``mpf``."""
    return mp.make_mpf(x._mpi_[0])


def hi(x) -> mp.mpf:
    """Upper end of an ``iv`` interval as an exact ``mpf``."""
    return mp.make_mpf(x._mpi_[1])


def mid(x) -> mp.mpf:
    """Midpoint of an ``iv`` interval, at the current ``mp`` precision."""
    return (lo(x) + hi(x)) / 2
