"""Working precision of the point (``mp``) and interval (``iv``) contexts; the one escalation rule.

Thread safety. ``mp`` and ``iv`` here are not mpmath's process-wide contexts but this thread's
own ones (an ``mpmath.MPContext`` and an ``mpmath.ctx_iv.MPIntervalContext`` per thread, made on
the thread's first call and kept): every module of verify computes with them, and
:func:`working_dps` sets their precision only. So verify never reads or changes
``mpmath.mp.prec`` or ``mpmath.iv.prec``, and calls from several threads, each at its own
precision, cannot disturb each other or the caller. Values cross the public API converted:
inputs into this thread's context without rounding (:func:`verify.numerics.inputs.exact_real`),
results into ``mpmath.mp`` numbers (:func:`to_user`), which compute at the caller's precision.

Escalation. Every certificate in :mod:`verify` is an *attempt* at some working precision that
either succeeds or raises :class:`NotDecided` (an interval comparison stayed ambiguous); the
attempt is then repeated at a higher precision by :func:`escalate`, up to a limit, after which
the caller's public error (:class:`verify.UndecidableCollision`) is raised. No other precision
loop exists.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TypeVar

import mpmath
from mpmath import ctx_iv
from mpmath.libmp import dps_to_prec

DEFAULT_DPS = 50  # digits promised by a public function called without ``dps``
GUARD_DPS = 10  # digits worked beyond those promised (a first attempt at dps + GUARD_DPS)

T = TypeVar("T")


class _ThreadContexts(threading.local):
    """This thread's point and interval contexts (made on the thread's first use)."""

    def __init__(self) -> None:
        self.mp = mpmath.MPContext()
        self.iv = ctx_iv.MPIntervalContext()


_contexts = _ThreadContexts()


class _ThisThread:
    """``mp`` or ``iv`` of the calling thread: attribute access is forwarded to it. The
    precision is set by :func:`working_dps` / :func:`working_prec` only."""

    __slots__ = ("_which",)

    def __init__(self, which: str) -> None:
        object.__setattr__(self, "_which", which)

    def __getattr__(self, name):
        return getattr(getattr(_contexts, self._which), name)

    def __setattr__(self, name, value):
        raise AttributeError("verify sets the working precision with working_dps/working_prec")


mp = _ThisThread("mp")
iv = _ThisThread("iv")


def default_max_dps(dps: int) -> int:
    """The largest working precision an escalation reaches unless told: ``max(4*dps, 400)``."""
    return max(4 * dps, 400)


@contextmanager
def working_prec(bits: int) -> Iterator[int]:
    """Set this thread's ``mp`` and ``iv`` to ``bits`` bits for the block (restored after)."""
    point, interval = _contexts.mp, _contexts.iv
    old_mp, old_iv = point.prec, interval.prec
    try:
        point.prec = bits
        interval.prec = bits
        yield bits
    finally:
        point.prec = old_mp
        interval.prec = old_iv


@contextmanager
def working_dps(dps: int) -> Iterator[int]:
    """Set this thread's ``mp`` and ``iv`` to ``dps`` decimal digits; yield the bit precision."""
    with working_prec(dps_to_prec(dps)) as prec:
        yield prec


def to_user(x):
    """A result for the caller: ``mpf`` values (also inside plain tuples and lists) become
    ``mpmath.mp`` numbers with the same exact value, so that the caller's arithmetic on them
    runs at the caller's precision."""
    if hasattr(x, "_mpf_"):
        return mpmath.mp.make_mpf(x._mpf_)
    if type(x) in (tuple, list):
        return type(x)(to_user(y) for y in x)
    return x


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
