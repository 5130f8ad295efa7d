"""Hypothesis profiles: ``default`` is quick, ``ci`` (HYPOTHESIS_PROFILE=ci, .ci/run) heavier.

deadline=None everywhere: the first call of a numba kernel compiles it.
"""

import os

from hypothesis import HealthCheck, settings

settings.register_profile(
    "default", max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile(
    "ci", max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow],
    print_blob=True,
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
