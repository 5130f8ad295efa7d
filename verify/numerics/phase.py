"""Exact reduction of a phase modulo 2*pi, with a precision that grows with the phase.

A float phase ``phi`` is an exact binary number; the reduced phase is ``r = phi - 2*pi*k`` with
the integer ``k = floor(phi/(2*pi))``. Computing ``2*pi*k`` at ``p`` bits leaves an absolute
error ``~|phi|*2**-p``, so to know ``r`` to ``prec`` bits the work needs
``p = prec + exponent(phi) + guard`` bits: this module raises the precision by the binary
exponent of ``phi`` (``|phi| = 1e300`` adds ~997 bits). ``k`` only needs to be some integer:
a ``k`` off by one near a multiple of 2*pi still gives an exact congruent phase (just outside
``[0, 2*pi)`` by a rounding), so the enclosure is rigorous whatever ``k`` is.

Phases with ``|phi| < 8`` are not reduced: their sine is computed directly, and a reduction
would only add an absolute rounding error to a small phase.
"""

from __future__ import annotations

from typing import NamedTuple

import mpmath

from .precision import hi, iv, lo, mp, working_prec

_GUARD_BITS = 20
_NO_REDUCTION_BELOW = 8


class ReducedPhase(NamedTuple):
    """``value``: an ``mpf`` congruent to ``phi`` mod 2*pi up to ``2**-prec``;
    ``enclosure``: an ``iv`` interval (current ``iv`` precision) that contains the exact
    ``phi - 2*pi*k``; ``k``: the integer used; ``work_bits``: the precision of the reduction."""

    value: mpmath.mpf
    enclosure: object
    k: int
    work_bits: int


def reduction_bits(phi, prec: int) -> int:
    """Bits needed to reduce ``phi`` to ``prec`` bits: ``prec + exponent(phi) + guard``."""
    return prec + max(0, int(mp.mag(phi))) + _GUARD_BITS


def reduce_phase(phi: mpmath.mpf, prec: int) -> ReducedPhase:
    """Reduce the exact ``phi`` modulo 2*pi (see the module docstring)."""
    if abs(phi) < _NO_REDUCTION_BELOW:
        return ReducedPhase(phi, iv.mpf(phi), 0, prec)
    bits = reduction_bits(phi, prec)
    with working_prec(bits):
        k = int(mp.floor(phi / (2 * mp.pi)))
        r = iv.mpf(phi) - 2 * iv.pi * k
        r_lo, r_hi = lo(r), hi(r)
    enclosure = iv.mpf([r_lo, r_hi])  # outward rounding to the caller's precision
    return ReducedPhase(+((r_lo + r_hi) / 2), enclosure, k, bits)


def time_until(target, phase):
    """The time from ``phase`` to the next phase congruent to ``target``: ``(target - phase)
    mod 2*pi`` in ``(0, 2*pi]`` (a whole period when they coincide), at the current precision."""
    two_pi = 2 * mp.pi
    d = target - phase
    d -= two_pi * mp.floor(d / two_pi)
    return d if d > 0 else two_pi
