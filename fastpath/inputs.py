"""Input checks shared by the public wrappers: finite float64 values of compatible shapes.

As in ``verify``: a real number (bools and strings are not), or an array of integers or floats.
"""

import math
import numbers

import numpy as np

from fastpath.physics import LAWS, MODELS, NONE, describe, holmes

_LAW_NAMES = tuple(LAWS)  # a str compares by value; a tuple test never calls array __eq__


def float_inputs(**named):
    """Convert named inputs to broadcast float64 arrays; return (arrays, all_scalar).

    Raises ValueError naming the first input that is not a finite real number (or array of them)
    and when the shapes do not broadcast.
    """
    arrays = {}
    for name, value in named.items():
        _check_kind(name, value)
        try:
            arr = np.asarray(value, dtype=np.float64)
        except OverflowError:  # an integer beyond float64's range
            raise ValueError(f"{name} must be finite in float64, got {value!r}") from None
        except (TypeError, ValueError):
            msg = f"{name} must be a real number or array of them, got {value!r}"
            raise ValueError(msg) from None
        if np.iscomplexobj(value):
            raise ValueError(f"{name} must be real, got {value!r}")
        bad = ~np.isfinite(arr)
        if bad.any():
            where = np.argwhere(bad)[0]
            at = f" at index {tuple(int(i) for i in where)}" if arr.ndim else ""
            raise ValueError(f"{name} must be finite, got {float(arr[tuple(where)])!r}{at}")
        arrays[name] = arr
    try:
        shaped = np.broadcast_arrays(*arrays.values())
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in arrays.items())
        raise ValueError(f"input shapes do not broadcast: {shapes}") from None
    all_scalar = all(a.ndim == 0 for a in arrays.values())
    return [np.ascontiguousarray(a).ravel() for a in shaped], shaped[0].shape, all_scalar


def _check_kind(name, value):
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    if isinstance(value, np.ndarray):
        if value.dtype.kind not in "iuf":
            raise ValueError(f"{name} must be an array of real numbers, got dtype {value.dtype}")
    elif not isinstance(value, numbers.Real):
        kinds = {type(x) for x in np.ravel(np.asarray(value, dtype=object))}
        if not all(issubclass(k, numbers.Real) and not issubclass(k, (bool, np.bool_))
                   for k in kinds):
            raise ValueError(f"{name} must be a real number or array of them, got {value!r}")


def scalar_inputs(**named):
    """The inputs as Python floats if every one is a real scalar, else None (use float_inputs).

    Raises ValueError naming a scalar that is not a finite real number.
    """
    out = []
    for name, value in named.items():
        kind = type(value)
        if kind is not float and (
            kind is bool or not isinstance(value, (float, int, np.floating, np.integer))
        ):
            return None  # float_inputs judges it (bools and strings raise there)
        try:
            x = float(value)
        except OverflowError:
            raise ValueError(f"{name} must be finite, got {value!r}") from None
        if not math.isfinite(x):
            raise ValueError(f"{name} must be finite, got {x!r}")
        out.append(x)
    return out


def physics_options(drag, drag_law, restitution):
    """Check the keyword-only physics options; return (drag, law code, restitution).

    drag: a finite real number >= 0; drag_law: "linear" or "quadratic" (``fastpath.physics.LAWS``);
    restitution: a finite real number in (0, 1]. ValueError naming the bad value otherwise.
    """
    if (type(drag) is float and type(restitution) is float and type(drag_law) is str
            and drag == 0.0 and restitution == 1.0 and drag_law in _LAW_NAMES):
        return 0.0, LAWS[drag_law], 1.0  # the elastic defaults, checked in ~0.1 us
    drag = real_scalar("drag", drag)
    if not drag >= 0.0:
        raise ValueError(f"drag must be >= 0, got drag={drag!r}")
    if not isinstance(drag_law, str) or drag_law not in LAWS:
        raise ValueError(f"drag_law must be one of {sorted(LAWS)}, got drag_law={drag_law!r}")
    restitution = real_scalar("restitution", restitution)
    if not 0.0 < restitution <= 1.0:
        raise ValueError(f"restitution must be in (0, 1], got restitution={restitution!r}")
    return drag, LAWS[drag_law], restitution


def real_scalar(name, value):
    """A finite real scalar as a float; bools, strings, NaN and inf are a ValueError naming
    ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, np.floating)):
        raise ValueError(f"{name} must be a real number, got {name}={value!r}")
    try:
        x = float(value)
    except OverflowError:
        raise ValueError(f"{name} must be finite, got {name}={value!r}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name} must be finite, got {name}={x!r}")
    return x


def model_physics(model, eps, drag=0.0, drag_law=NONE, restitution=1.0):
    """The physics description (``fastpath.physics``) of the public model name with the plate
    amplitude eps and the checked physics options (``physics_options``): ``Holmes`` for
    "holmes", ``Elastic`` or ``Dissipative`` (``describe``) for "exact".

    ValueError for a model that is not one of ``fastpath.physics.MODELS`` and for drag or
    restitution < 1 with the Holmes map (it has neither).
    """
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model must be one of {sorted(MODELS)}, got model={model!r}")
    if model == "holmes":
        if drag != 0.0 or restitution != 1.0:
            raise ValueError(f"drag or restitution < 1 needs model='exact', got model={model!r}")
        return holmes(eps)
    return describe(eps, drag, drag_law, restitution)


def integer(name, value, minimum=None):
    """An integer (not a bool, numpy's included) >= minimum, as an int; ValueError naming
    ``name`` otherwise."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{name} must be an integer, got {name}={value!r}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {name}={value}")
    return int(value)


def departing(phi, v, eps, what="the start"):
    """ValueError unless w0 = v + eps*sin(phi) > 0 (the particle leaves the plate)."""
    w0 = v + eps * math.sin(phi)
    if not w0 > 0.0:
        raise ValueError(f"{what} does not depart: w0 = v + eps*sin(phi) = {w0!r} <= 0 at "
                         f"phi={phi!r}, v={v!r}, eps={eps!r}")
