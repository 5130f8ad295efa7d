"""The unit roundoff and error-free transformations of float64 arithmetic.

With round-to-nearest, fl(x op y) = (x op y)*(1 + delta), |delta| <= UNIT_ROUNDOFF = 2**-53, for
results in the normal range; a subnormal result is off by at most SUBNORMAL/2 = 2**-1075.
``two_sum`` and ``two_product`` return a rounded result together with its exact rounding error,
so that x + y or x*y can be carried as an unevaluated sum of two floats (Knuth's TwoSum; Dekker's
product with Veltkamp's splitting).
"""

from fastpath.arithmetic.jit import inline_jit, jit

UNIT_ROUNDOFF = 2.0**-53
# The smallest subnormal. Below 2**-1022 rounding is absolute: a result there is off by at most
# half of it, whatever its size (the relative bound u no longer holds).
SUBNORMAL = 2.0**-1074
_ROOT_SUBNORMAL = 2.0**-537  # its square is SUBNORMAL
_SPLIT = 134217729.0  # 2**27 + 1, Veltkamp's splitter for Dekker's exact product


@inline_jit
def plus_underflow(bound, weight):
    """bound + SUBNORMAL*weight for bound, weight >= 0 (the same float): an error bound with an
    allowance for the absolute rounding of ``weight`` subnormal results.

    Arithmetic on subnormal numbers is slow, and SUBNORMAL*weight is subnormal for every
    ordinary weight (computed in the gap's bounds it took 18% of an elastic orbit's time on the
    AMD EPYC of docs/performance.md). Where
    bound >= 2**-900 and weight < 2**100 the allowance (< 2**-973) is below half an ulp of bound
    (>= 2**-953) and the sum is bound: the weight is then multiplied by 0 before any scaling
    (a product with a select of the constants 1 and 0: a branch or a select on the product
    itself is turned by the compiler into computing the subnormal product anyway).
    Otherwise the allowance is (weight*2**-537)*2**-537, an exact product rounded once, as
    SUBNORMAL*weight is.
    """
    needed = (bound < 2.0**-900) | (weight >= 2.0**100)  # no branch: the lanes vectorise it
    return bound + ((weight * select(needed, 1.0, 0.0)) * _ROOT_SUBNORMAL) * _ROOT_SUBNORMAL


@jit
def two_sum(x, y):
    """(s, e) with s = fl(x + y) and x + y = s + e exactly (Knuth)."""
    s = x + y
    y_virtual = s - x
    return s, (x - (s - y_virtual)) + (y - y_virtual)


@jit
def two_product(a, b):
    """(p, e) with p = fl(a*b) and a*b = p + e exactly (Dekker, Veltkamp splitting; |a*b| below
    ~1e300 so that the splitting does not overflow)."""
    p = a * b
    a_big = _SPLIT * a
    a_hi = a_big - (a_big - a)
    a_lo = a - a_hi
    b_big = _SPLIT * b
    b_hi = b_big - (b_big - b)
    b_lo = b - b_hi
    return p, ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo


@inline_jit
def select(condition, a, b):
    """a if condition else b, as a select (no branch: it keeps a loop vectorisable)."""
    return a if condition else b
