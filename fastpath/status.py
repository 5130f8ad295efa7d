"""Outcome of one flight, as the kernels report it, and the error raised for undecidable cases.

The kernels return the status as a small int (``CONVERGED`` ... ``OVERFLOW`` below, the values of
``FlightStatus``); the public functions return ``FlightStatus`` members.
"""

from enum import IntEnum

import numpy as np

ITERATION_LIMIT = 60  # gap evaluations of one flight, at most, before MAX_ITERATIONS
# The accuracy every CONVERGED flight time is held to: |tau - tau*| <= TAU_ACCURACY*kappa*u*tau*
# (kappa the flight's condition number, u = 2**-53); the tests and the runs' audit use it.
TAU_ACCURACY = 16.0


class FlightStatus(IntEnum):
    """Status code returned with every flight time.

    CONVERGED      the first root of the gap is located to within rounding.
    UNCERTAIN      a near-graze (eps > 1): the gap is within its rounding error of zero where its
                   slope is too small to tell a collision from a miss; or a departure speed w0
                   within its rounding error of 0; or (|eps| <= 1) a gap and slope both within
                   rounding of zero, where float64 cannot place the root. Settle it with ``verify``.
    NOT_DEPARTING  w0 = v + eps*sin(phi) <= 0 for certain: the particle does not leave the plate.
    MAX_ITERATIONS the solver did not finish within its iteration limit (``ITERATION_LIMIT``
                   gap evaluations): as UNCERTAIN.
    OVERFLOW       an intermediate (v**2, t*v, ...) overflowed float64: the input is out of range.
    """

    CONVERGED = 0
    UNCERTAIN = 1
    NOT_DEPARTING = 2
    MAX_ITERATIONS = 3
    OVERFLOW = 4


# the codes as plain ints, for the compiled kernels
CONVERGED = int(FlightStatus.CONVERGED)
UNCERTAIN = int(FlightStatus.UNCERTAIN)
NOT_DEPARTING = int(FlightStatus.NOT_DEPARTING)
MAX_ITERATIONS = int(FlightStatus.MAX_ITERATIONS)
OVERFLOW = int(FlightStatus.OVERFLOW)
STATUS_DTYPE = np.int8  # the dtype of every array of status codes


class UncertainCollision(ArithmeticError):
    """A flight whose first collision float64 cannot decide; ``verify.flight_time`` settles it."""
