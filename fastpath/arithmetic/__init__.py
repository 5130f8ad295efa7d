"""float64 building blocks: the numba options, exact sums and products, phase reduction, sines.

``jit``        the numba decorators every kernel uses (cached, no fastmath).
``rounding``   the unit roundoff u = 2**-53, error-free sums and products (TwoSum, Dekker),
               ``select`` (a branch-free choice).
``phase``      reduction of any float to [0, 2*pi) or [-pi, pi) (Cody-Waite, Payne-Hanek).
``sincos``     sine and cosine in straight-line code (vectorisable), 4u.
``rotation``   sines moved along by angle addition; the sine of an exact sum of two floats.

Nothing here knows the bouncer: these are the tools the solvers are built from.
"""
