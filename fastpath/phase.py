"""Reduction of a phase (a time) to [0, 2*pi).

A three-part Cody-Waite reduction: 2*pi = TWO_PI_HI + TWO_PI_MID + TWO_PI_LO, where the first two
parts carry 31 significant bits each, so that k*TWO_PI_HI and k*TWO_PI_MID are exact for
|k| < 2**21. The reduced phase is then accurate to a few ulps of 2*pi for |x| < ~1e7, where a plain
``x % (2*pi)`` carries the representation error of 2*pi times k (about 1e-10 at x = 1e6).
"""

import math

from fastpath._jit import jit

PI = math.pi
TWO_PI = 2.0 * math.pi
# 2*pi = HI + MID + LO to ~1e-35 (HI and MID have 31 significant bits; checked in the tests).
TWO_PI_HI = 6.2831853069365025
TWO_PI_MID = 2.430840201437384e-10
TWO_PI_LO = 1.1650928224373424e-19
_MAX_EXACT_TURNS = 2.0**21


@jit
def reduce_phase(x):
    """Return x mod 2*pi in [0, 2*pi)."""
    if 0.0 <= x < TWO_PI:
        return x
    k = math.floor(x / TWO_PI)
    if abs(k) < _MAX_EXACT_TURNS:
        r = ((x - k * TWO_PI_HI) - k * TWO_PI_MID) - k * TWO_PI_LO
    else:
        r = x - k * TWO_PI  # beyond ~1e7 the phase itself holds fewer digits than this loses
    # k from the float quotient can be off by one at the boundaries.
    if r < 0.0:
        r += TWO_PI
    elif r >= TWO_PI:
        r -= TWO_PI
    if r >= TWO_PI:  # r was -tiny and r + 2*pi rounded up to 2*pi
        r = 0.0
    return r


@jit
def centre_phase(x):
    """Return x mod 2*pi in [-pi, pi); a phase already in that range is returned unchanged.

    The flight kernels take centred phases: the rounding error of sin(phi + t/2) grows with
    |phi|, and a departure given as -0.3 must not be moved to 2*pi - 0.3 (which also costs the
    representation error of 2*pi).
    """
    if -PI <= x < PI:
        return x
    r = reduce_phase(x)
    if r >= PI:
        r -= TWO_PI
    return r
