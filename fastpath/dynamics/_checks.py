"""Input checks of the dynamics functions: a clear ValueError naming the bad value."""

import math
import numbers

import numpy as np

from fastpath.dynamics.kernels import MODELS


def integer(name, value, minimum=None):
    """An integer (not a bool) >= minimum, as an int."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral,)):
        raise ValueError(f"{name} must be an integer, got {name}={value!r}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {name}={value}")
    return int(value)


def model_code(model):
    """The kernel code of a model name ("exact" or "holmes")."""
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model must be one of {sorted(MODELS)}, got model={model!r}")
    return MODELS[model]


def departing(phi, v, eps, what="the start"):
    """ValueError unless w0 = v + eps*sin(phi) > 0 (the particle leaves the plate)."""
    w0 = v + eps * math.sin(phi)
    if not w0 > 0.0:
        raise ValueError(f"{what} does not depart: w0 = v + eps*sin(phi) = {w0!r} <= 0 at "
                         f"phi={phi!r}, v={v!r}, eps={eps!r}")
