"""pytest plugin for the ``NUMBA_DISABLE_JIT=1`` mutation runs (scripts/mutation/ensemble.py).

Compiled, ``math.floor`` of NaN or inf gives some integer and the arithmetic around it gives NaN
(``sin_cos``, ``reduce_moderate``, ``centre_moderate``); as plain Python it raises. The lockstep
lanes compute an unanswered lane's NaN on purpose (the select discards it), so the ``fastpath``
modules get a ``math`` whose ``floor`` returns a non-finite argument unchanged (NaN in, NaN out,
as compiled) and is ``math.floor`` otherwise.

It also registers the hypothesis profile ``mutation`` (the solver group sets
HYPOTHESIS_PROFILE=mutation; tests/conftest.py loads the profile that names): the default
profile's 60 examples, derandomized and without the example database. With the database, one
failing example is replayed in every later run of the scratch copy, and an example that fails
only as plain Python (2*w0/(1 - eps*cos_phi) at eps = cos_phi = 1 raises ZeroDivisionError;
compiled it is inf) then "kills" every later mutant; derandomized, every mutant meets the same
examples as the unmutated run, which passes.
"""

import math
import sys
import types

from hypothesis import HealthCheck, settings

import fastpath.elastic.lockstep  # noqa: F401
import fastpath.kernels.escape  # noqa: F401  (every kernel module imported before the swap)


def _floor(x):
    return math.floor(x) if abs(x) < math.inf else x


_math = types.SimpleNamespace(**{k: getattr(math, k) for k in dir(math) if not k.startswith("__")})
_math.floor = _floor

for _name, _module in list(sys.modules.items()):
    if _name.startswith("fastpath") and getattr(_module, "math", None) is math:
        _module.math = _math

settings.register_profile(
    "mutation", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow],
    database=None, derandomize=True,
)
