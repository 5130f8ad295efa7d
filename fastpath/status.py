"""Outcome of one flight, as the kernels report it, and the error raised for undecidable cases."""

from enum import IntEnum


class FlightStatus(IntEnum):
    """Status code returned with every flight time.

    CONVERGED      the first root of the gap is located to within rounding.
    UNCERTAIN      a near-graze (eps > 1): the gap is within its rounding error of zero where its
                   slope is too small to tell a collision from a miss; or a departure speed w0
                   within its rounding error of 0; or (|eps| <= 1) a gap and slope both within
                   rounding of zero, where float64 cannot place the root. Settle it with ``verify``.
    NOT_DEPARTING  w0 = v + eps*sin(phi) <= 0 for certain: the particle does not leave the plate.
    MAX_ITERATIONS the solver did not finish within its iteration limit (60): as UNCERTAIN.
    OVERFLOW       an intermediate (v**2, t*v, ...) overflowed float64: the input is out of range.
    """

    CONVERGED = 0
    UNCERTAIN = 1
    NOT_DEPARTING = 2
    MAX_ITERATIONS = 3
    OVERFLOW = 4


class UncertainCollision(ArithmeticError):
    """A flight whose first collision float64 cannot decide; ``verify.flight_time`` settles it."""
