"""``check_integrator`` and ``assert_integrator``: validate the arguments, run each property of
the suite through the driver, and assemble the :class:`CheckReport`."""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Callable

from .budget import Budget, BudgetSpent
from .calling import Bad
from .driver import Run, property_parts, run_property
from .loading import load_callable, parse_spec
from .properties import Checker
from .report import NO_INPUT, CheckReport, PropertyResult, callable_name
from .suites import DEFAULT_EXAMPLES, NEEDS_STEP, check_suite, properties_of
from .worker import IMPORT_TIMEOUT, Unavailable, Worker, how_to_load

DEFAULT_CALL_TIMEOUT = 5.0  # seconds one call of the user's code may take
DEFAULT_BUDGET = 120.0  # seconds for the whole check


def _positive(name, x, allow_inf):
    if isinstance(x, bool) or not isinstance(x, numbers.Real) or not x > 0 \
            or (math.isinf(x) and not allow_inf):
        raise ValueError(f"{name} must be a positive number of seconds, got {name}={x!r}")
    return float(x)


def _target(fn, what):
    """(callable or None, spec or None) from a callable or a ``MODULE:FUNCTION`` string. A
    spec is only parsed here: the worker process imports it, so that a module that exits or
    crashes while importing cannot end the caller's process."""
    if isinstance(fn, str):
        parse_spec(fn)
        return None, fn
    if not callable(fn):
        raise ValueError(f"{what} must be callable or MODULE:FUNCTION, got {fn!r}")
    return fn, None


def _in_process(fns, specs, why):
    """The callables to call in this process (specs imported here), and the note saying so."""
    fns = {name: fn if fn is not None else load_callable(specs[name], search_cwd=True)
           for name, fn in fns.items()}
    return fns, None, (f"IN-PROCESS: {why}; no protection from hangs or crashes, the budget "
                       "is checked between inputs only (pass MODULE:FUNCTION to run it in a "
                       "worker process)")


def _callers(fns, specs, call_timeout, budget, import_timeout, workers):
    """(the callables the properties call, the worker or None, how they run); the worker is
    appended to ``workers`` before it starts, so that the caller stops it on every way out.
    ValueError when a ``MODULE:FUNCTION`` spec does not load in the worker (it raises, exits,
    crashes or hangs while importing, or names no callable)."""
    try:
        how = {name: how_to_load(fn, specs[name]) for name, fn in fns.items()}
    except Unavailable as why:  # a callable that cannot be pickled
        return _in_process(fns, specs, why)
    worker = Worker(how, call_timeout, budget, import_timeout)
    workers.append(worker)
    try:
        worker.start()
    except Unavailable as why:
        if any(specs[name] is not None for name in fns):
            raise ValueError(str(why)) from None
        return _in_process(fns, specs, why)
    except BudgetSpent:  # every property will be inconclusive with 0 inputs
        return ({name: worker.callable(name) for name in fns}, worker,
                "the budget ran out while the worker process started")
    except Bad as bad:  # the worker did not get ready; each call will try a fresh one
        return ({name: worker.callable(name) for name in fns}, worker,
                f"each call in a worker process (the first start failed: {bad.message})")
    note = "each call in a worker process"
    if worker.warm_up_note:
        note += f" ({worker.warm_up_note})"
    return {name: worker.callable(name) for name in fns}, worker, note


def check_integrator(
    flight_time: Callable | str,
    *,
    step: Callable | str | None = None,
    suite: str = "all",
    max_examples: int | None = None,
    seed: int | None = 0,
    k: float = 16,
    call_timeout: float = DEFAULT_CALL_TIMEOUT,
    budget: float = DEFAULT_BUDGET,
    progress: Callable[[str, int, int], None] | None = None,
    import_timeout: float = IMPORT_TIMEOUT,
) -> CheckReport:
    """Run the property suite (``verify.check``) against ``flight_time`` (and ``step``).

    flight_time, step: callables or ``"MODULE:FUNCTION"`` specs. They run in a worker process
    (:mod:`verify.check.worker`): a call that raises, hangs past ``call_timeout`` seconds or
    kills the process fails the property that made it, naming the input. A callable that
    cannot be pickled (a lambda, a closure) runs in-process instead, and the report says so.
    suite: "all", "fast" (20 inputs per property instead of 100) or one property name.
    max_examples: inputs per property (overrides the suite's count). seed: hypothesis seed
    (an int gives the same inputs every run; None draws fresh ones). k: allowed multiple of
    ``kappa*u``. budget: seconds for the whole check (``math.inf``: none); when it runs out
    the properties not finished are INCONCLUSIVE with the counts reached. import_timeout:
    seconds the worker may take to import a ``MODULE:FUNCTION`` spec (a module that takes
    longer, or hangs, is a ``ValueError`` naming it; within the budget). progress:
    ``progress(property, inputs so far, inputs planned)`` after each input. Properties that
    need ``step`` are skipped without it (asking for one of them alone raises
    ``ValueError``). Returns a :class:`CheckReport`; never raises for a misbehaving callable
    (an exception, ``sys.exit()``, a crash or a hang in a call is a failure of its property).
    Raises ``ValueError`` for bad arguments, including a spec whose module raises, exits,
    crashes or hangs while importing: nothing of it was checked. The worker, and whatever the
    checked code started, is stopped on every way out (:mod:`verify.check.worker`).
    """
    suite = check_suite(suite)
    flight_time, ft_spec = _target(flight_time, "flight_time")
    has_step = step is not None
    step, step_spec = (None, None) if step is None else _target(step, "step")
    if suite in NEEDS_STEP and not has_step:
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
    call_timeout = _positive("call_timeout", call_timeout, allow_inf=True)
    budget_s = _positive("budget", budget, allow_inf=True)
    import_timeout = _positive("import_timeout", import_timeout, allow_inf=True)

    start = time.perf_counter()
    clock = Budget(budget_s)
    fns = {"flight_time": flight_time, "step": step} if has_step else \
        {"flight_time": flight_time}
    specs = {"flight_time": ft_spec, "step": step_spec}
    workers: list[Worker] = []
    results = []
    try:
        calls, worker, isolation = _callers(fns, specs, call_timeout, clock, import_timeout,
                                            workers)
        run = Run(seed, clock, (lambda: worker.faults) if worker else (lambda: 0), progress)
        checker = Checker(calls["flight_time"], calls.get("step"), k)
        strategies = property_parts()
        for name in properties_of(suite):
            t0 = time.perf_counter()
            if name in NEEDS_STEP and not has_step:
                results.append(PropertyResult(name, "SKIP", 0, "needs a step callable"))
                continue
            got = run_property(name, getattr(checker, name), strategies[name],
                               int(max_examples), run)
            notes = [got.note] if got.note else []
            if name == "accuracy" and checker.worst_k is not None:
                phi, v, eps = checker.worst_input
                notes.insert(0, f"worst k = {checker.worst_k:.3g} at phi={phi!r}, v={v!r}, "
                                f"eps={eps!r}; allowed {k:g}")
            if name == "fixed_points" and not has_step:
                notes.append("flight time only: no step given")
            if got.failure is not None:
                status = "FAIL"
            elif got.cut:
                status = "INCONCLUSIVE"
            elif got.inputs:
                status = "PASS"
            else:  # it never ran: not a pass
                status = "INCONCLUSIVE"
                notes.append(NO_INPUT)
            results.append(PropertyResult(name, status, got.inputs, "; ".join(notes),
                                          got.failure, time.perf_counter() - t0, got.failed))
    finally:
        for started in workers:
            started.stop()
    if worker is not None and worker.faults:
        isolation += f"; {worker.faults} timeouts or crashes, {worker.restarts} restarts"
    return CheckReport(
        target=ft_spec or callable_name(flight_time),
        step_target=step_spec or (callable_name(step) if has_step else None),
        suite=suite,
        k=float(k),
        seed=seed,
        max_examples=int(max_examples),
        results=tuple(results),
        worst_accuracy_k=checker.worst_k,
        worst_accuracy_input=checker.worst_input,
        seconds=time.perf_counter() - start,
        budget=budget_s,
        call_timeout=call_timeout,
        isolation=isolation,
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
