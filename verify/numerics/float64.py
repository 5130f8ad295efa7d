"""Constants of binary64 (float64) arithmetic shared by the test data (:mod:`verify.hard_cases`,
:mod:`verify.strategies`) and the tolerance model of :mod:`verify.check`."""

import math

UNIT_ROUNDOFF = 2.0**-53  # u: the relative rounding error bound of float64
TWO_PI = 2.0 * math.pi  # the float64 nearest 2*pi (a phase reduced in float64 lies below it)
