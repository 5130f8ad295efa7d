"""One place for the numba options every kernel uses.

``fastmath`` stays off: the rigour of the lower-bound step and the error bounds of the gap
assume IEEE round-to-nearest arithmetic, which reassociation would break.
"""

import numba

jit = numba.njit(cache=True, nogil=True, error_model="numpy")
parallel_jit = numba.njit(cache=True, nogil=True, error_model="numpy", parallel=True)
