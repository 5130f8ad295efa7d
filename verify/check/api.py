"""``check_integrator`` and ``assert_integrator``: validate the arguments, run each property of
the suite through the driver, and assemble the :class:`CheckReport`."""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Callable

from .driver import property_parts, run_property
from .properties import Checker
from .report import CheckReport, PropertyResult, callable_name
from .suites import DEFAULT_EXAMPLES, NEEDS_STEP, check_suite, properties_of


def check_integrator(
    flight_time: Callable,
    *,
    step: Callable | None = None,
    suite: str = "all",
    max_examples: int | None = None,
    seed: int | None = 0,
    k: float = 16,
) -> CheckReport:
    """Run the property suite (module docstring) against ``flight_time`` (and ``step``).

    suite: "all", "fast" (20 inputs per property instead of 100) or one property name.
    max_examples: inputs per property (overrides the suite's count). seed: hypothesis seed
    (an int gives the same inputs every run; None draws fresh ones). k: allowed multiple of
    ``kappa*u``. Properties that need ``step`` are skipped without it (asking for one of them
    alone raises ``ValueError``). Returns a :class:`CheckReport`; never raises for a
    misbehaving callable.
    """
    suite = check_suite(suite)
    if not callable(flight_time):
        raise ValueError(f"flight_time must be callable, got {flight_time!r}")
    if step is not None and not callable(step):
        raise ValueError(f"step must be callable or None, got {step!r}")
    if suite in NEEDS_STEP and step is None:
        raise ValueError(f"suite {suite!r} needs a step callable (step=... / --step)")
    if isinstance(k, bool) or not isinstance(k, numbers.Real) or not (0 < k < math.inf):
        raise ValueError(f"k must be a positive finite number, got k={k!r}")
    if max_examples is None:
        max_examples = DEFAULT_EXAMPLES["fast" if suite == "fast" else "all"]
    if isinstance(max_examples, bool) or not isinstance(max_examples, numbers.Integral) \
            or max_examples < 1:
        raise ValueError(f"max_examples must be an integer >= 1, got {max_examples!r}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)):
        raise ValueError(f"seed must be an integer or None, got seed={seed!r}")

    checker = Checker(flight_time, step, k)
    strategies = property_parts()
    results = []
    start = time.perf_counter()
    for name in properties_of(suite):
        t0 = time.perf_counter()
        if name in NEEDS_STEP and step is None:
            results.append(PropertyResult(name, "SKIP", 0, "needs a step callable"))
            continue
        got = run_property(getattr(checker, name), strategies[name], int(max_examples), seed)
        notes = [got.note] if got.note else []
        if name == "accuracy" and checker.worst_k is not None:
            phi, v, eps = checker.worst_input
            notes.insert(0, f"worst k = {checker.worst_k:.3g} at phi={phi!r}, v={v!r}, "
                            f"eps={eps!r}; allowed {k:g}")
        if name == "fixed_points" and step is None:
            notes.append("flight time only: no step given")
        status = "FAIL" if got.failure is not None else "PASS" if got.inputs else "SKIP"
        results.append(PropertyResult(name, status, got.inputs, "; ".join(notes), got.failure,
                                      time.perf_counter() - t0, got.failed))
    return CheckReport(
        target=callable_name(flight_time),
        step_target=None if step is None else callable_name(step),
        suite=suite,
        k=float(k),
        seed=seed,
        max_examples=int(max_examples),
        results=tuple(results),
        worst_accuracy_k=checker.worst_k,
        worst_accuracy_input=checker.worst_input,
        seconds=time.perf_counter() - start,
    )


def assert_integrator(flight_time: Callable, **kwargs) -> CheckReport:
    """:func:`check_integrator`, raising ``AssertionError`` with the report's text on failure.

    For a user's pytest suite::

        import verify
        from mysolver import flight_time, step

        def test_my_integrator():
            verify.assert_integrator(flight_time, step=step)
    """
    report = check_integrator(flight_time, **kwargs)
    if not report.ok:
        raise AssertionError(str(report))
    return report
