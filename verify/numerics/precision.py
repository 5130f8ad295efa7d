"""Working precision of the point (``mp``) and interval (``iv``) contexts; the one escalation rule.

Every certificate in :mod:`verify` is an *attempt* at some working precision that either
succeeds or raises :class:`NotDecided` (an interval comparison stayed ambiguous); the attempt is
then repeated at a higher precision by :func:`escalate`, up to a limit, after which the caller's
public error (:class:`verify.UndecidableCollision`) is raised. No other precision loop exists.

Both contexts are raised together by :func:`working_dps` and restored in ``finally``: the global
precision a caller set is never changed permanently.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TypeVar

from mpmath import iv, mp
from mpmath.libmp import dps_to_prec

GUARD_DPS = 10  # digits worked beyond those promised (a first attempt at dps + GUARD_DPS)

T = TypeVar("T")


def default_max_dps(dps: int) -> int:
    """The largest working precision an escalation reaches unless told: ``max(4*dps, 400)``."""
    return max(4 * dps, 400)


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


class NotDecided(ArithmeticError):
    """An attempt could not decide at its working precision (retry higher).

    ``what`` says what stayed undecided; ``needed`` is a hint in digits (0: none), e.g. from
    the condition number of the root being enclosed.
    """

    def __init__(self, what: str, needed: int = 0) -> None:
        super().__init__(what)
        self.what = what
        self.needed = needed


def escalate(attempt: Callable[[int], T], dps: int, max_dps: int,
             undecidable: Callable[[int, NotDecided], Exception]) -> T:
    """Run ``attempt(wdps)`` inside ``working_dps(wdps)`` from ``wdps = min(dps + GUARD_DPS,
    max_dps)``; on :class:`NotDecided` retry at ``min(max_dps, max(2*wdps, needed))``. At
    ``max_dps`` the exception ``undecidable(wdps, why)`` is raised instead (called outside the
    working precision)."""
    wdps = min(dps + GUARD_DPS, max_dps)
    while True:
        try:
            with working_dps(wdps):
                return attempt(wdps)
        except NotDecided as und:
            if wdps >= max_dps:
                raise undecidable(wdps, und) from None
            wdps = min(max_dps, max(2 * wdps, und.needed))
