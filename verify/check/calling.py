"""Call the user's code and vet what comes back: a finite real flight time > 0, or a step's
``(phi1, v1, tau)``. Anything else (an exception, NaN, a wrong shape) becomes :class:`Bad`,
which the property that called turns into a failure."""

from __future__ import annotations

import math
import numbers


class Bad(Exception):
    """The user's callable misbehaved; ``text`` describes what came back. ``fault`` is
    "timeout" or "crash" when the call did not return at all (see :mod:`.worker`)."""

    def __init__(self, text: str, message: str, fault: str | None = None) -> None:
        super().__init__(message)
        self.text = text
        self.message = message
        self.fault = fault


def one_line(err: BaseException) -> str:
    text = str(err).splitlines()[0] if str(err) else ""
    return f"{type(err).__name__}: {text}" if text else type(err).__name__


def as_float(x, what: str) -> float:
    """``x`` as a float if it is a real number: a Python or numpy real (not a bool), or a numpy
    array of one real element. Anything else (a string such as "1.0", None, a complex number, a
    bool) is :class:`Bad` naming its type: a time given as text is not a time, even where
    ``float()`` would read it."""
    if hasattr(x, "shape") and hasattr(x, "dtype"):  # numpy arrays and scalars
        if x.shape not in ((), (1,)):
            raise Bad(_shown(x), f"{what} is not a real number (an array of shape {x.shape})")
        if x.dtype.kind not in "fiu":
            raise Bad(_shown(x), f"{what} is not a real number (an array of {x.dtype})")
        x = x.reshape(()).item()
    if isinstance(x, bool) or not isinstance(x, numbers.Real):
        kind = getattr(type(x), "description", None) or f"a {type(x).__name__}"
        raise Bad(_shown(x), f"{what} is not a real number ({kind})")
    try:
        val = float(x)
    except (TypeError, ValueError, OverflowError) as err:
        raise Bad(_shown(x), f"{what} is not a real number ({one_line(err)})") from None
    if not math.isfinite(val):
        raise Bad(repr(val), f"{what} is not finite")
    return val


def _shown(x, limit: int = 80) -> str:
    """The repr of what came back, clipped for the report."""
    try:
        text = repr(x)
    except Exception as err:  # noqa: BLE001 - a user's object whose repr fails
        text = f"<{type(x).__name__} whose repr raised {one_line(err)}>"
    return text if len(text) <= limit else text[:limit - 3] + "..."


def call_flight(fn, phi, v, eps) -> float:
    try:
        out = fn(phi, v, eps)
    except Bad:  # a worker's timeout or crash, already described
        raise
    except (Exception, SystemExit) as err:  # the user's code: any exception, or an exit,
        # is a failure of the property (in-process, an exit must not end the caller)
        raise Bad(f"exception {one_line(err)}", "flight_time raised on a valid departure") \
            from None
    tau = as_float(out, "the flight time")
    if not tau > 0:
        raise Bad(repr(tau), "the flight time is not positive")
    return tau


def call_step(fn, phi, v, eps) -> tuple[float, float, float]:
    try:
        out = fn(phi, v, eps)
    except Bad:
        raise
    except (Exception, SystemExit) as err:
        raise Bad(f"exception {one_line(err)}", "step raised on a valid departure") from None
    if isinstance(out, str | bytes):
        raise Bad(_shown(out), "step must return (phi1, v1, tau), not a string")
    try:
        phi1, v1, tau = out
    except Exception:  # noqa: BLE001 - whatever the user's object does when unpacked
        raise Bad(_shown(out), "step must return (phi1, v1, tau)") from None
    phi1 = as_float(phi1, "phi1")
    v1 = as_float(v1, "v1")
    tau = as_float(tau, "tau")
    if not tau > 0:
        raise Bad(repr((phi1, v1, tau)), "the flight time tau of step is not positive")
    return phi1, v1, tau
