"""The hard-case table (``verify.hard_cases``) as pytest parameters (phi, v, eps, reason)."""

import pytest

from verify.hard_cases import HARD_CASES as _TABLE

HARD_CASES = [pytest.param(c.phi, c.v, c.eps, c.reason, id=c.id) for c in _TABLE]
