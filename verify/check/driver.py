"""Drive hypothesis over the properties: each property's inputs come in parts (random, close
root pairs, ...), each part its own search with its share of ``max_examples``. A survey pass
counts the failing inputs; then a second pass stops at the first failure and lets hypothesis
shrink it to the smallest failing input."""

from __future__ import annotations

from dataclasses import dataclass

from .budget import BudgetSpent
from .properties import DISCARD
from .report import Failure


def property_parts():
    """Per property: (label, strategy, share of the inputs), the hard inputs first (close root
    pairs, tiny departure speeds, ...) so that a flawed solver is caught before the budget
    goes. Each part runs as its own hypothesis search, so every kind of input gets its share
    (``one_of`` would not promise it).
    """
    from .. import strategies as vs

    random = vs.departures(eps=(0.0, 10.0))
    return {
        "no_overstep": (
            ("close root pairs", vs.near_grazing(clearance=vs.clearances(-1)), 0.4),
            ("near misses", vs.near_grazing(clearance=vs.clearances(+1)), 0.2),
            ("random", random, 0.4),
        ),
        "accuracy": (
            ("hard", vs.hard_cases(), 0.4), ("random", random, 0.4),
            ("near fixed points", vs.near_fixed_point(), 0.2),
        ),
        "fixed_points": (("fixed points", vs.fixed_points(), 1.0),),
        "energy": (("hard", vs.hard_cases(), 0.4), ("random", random, 0.6)),
        "holmes_limit": (("large v", vs.large_velocities(), 1.0),),
        # the reversed flight ARRIVES with the forward departure speed w0: for w0 -> 0 and
        # eps > 1 that arrival is a near-graze a float64 method may rightly refuse to decide
        "reversibility": (
            ("random", vs.departures(eps=(0.0, 10.0), w0=(1e-3, 30.0)), 0.8),
            ("near fixed points", vs.near_fixed_point(), 0.2),
        ),
    }


class _Falsified(Exception):
    def __init__(self, failure: Failure) -> None:
        super().__init__(str(failure))
        self.failure = failure


def _find_falsified(err: BaseException) -> _Falsified | None:
    """The _Falsified inside err (hypothesis may wrap it, e.g. as a FlakyFailure group)."""
    seen = set()
    stack = [err]
    while stack:
        e = stack.pop()
        if e is None or id(e) in seen:
            continue
        seen.add(id(e))
        if isinstance(e, _Falsified):
            return e
        stack.extend(getattr(e, "exceptions", ()))
        stack.extend((e.__cause__, e.__context__))
    return None


def _hypothesis_run(test, strategy, max_examples: int, seed: int | None, shrink: bool):
    """Run ``test`` on ``max_examples`` drawn cases under quiet, database-free settings."""
    from hypothesis import HealthCheck, Phase, Verbosity, given, settings
    from hypothesis import seed as hypothesis_seed

    phases = (Phase.explicit, Phase.generate) + ((Phase.shrink,) if shrink else ())
    run = settings(
        database=None, max_examples=max_examples, deadline=None, derandomize=False,
        suppress_health_check=list(HealthCheck), report_multiple_bugs=False,
        verbosity=Verbosity.quiet, print_blob=False, phases=phases,
    )(given(strategy)(test))
    if seed is not None:
        run = hypothesis_seed(seed)(run)
    run()


class _Stop(BaseException):  # noqa: N818 - ends a survey; BaseException: see BudgetSpent
    pass


@dataclass
class _Outcome:
    inputs: int = 0
    failed: int = 0
    failure: Failure | None = None
    note: str = ""
    cut: bool = False  # the budget ran out before the search finished


class Run:
    """What every property's search shares: the seed, the budget, a fault counter (timeouts
    and crashes of the worker; a property stops at its first) and a progress callback
    ``progress(property, inputs so far, inputs planned)``."""

    def __init__(self, seed, budget, faults=lambda: 0, progress=None) -> None:
        self.seed = seed
        self.budget = budget
        self.faults = faults
        self.progress = progress or (lambda name, done, planned: None)


def _survey(body, count, first, strategy, run, tick):
    from hypothesis import reject

    def survey(case):
        run.budget.check()
        faults = run.faults()
        result = body(case)
        if result is DISCARD:
            reject()
        count["inputs"] += 1
        tick()
        if result is not None:
            count["failed"] += 1
            if not first:
                first.append((strategy, result))
            if run.faults() != faults:
                raise _Stop  # a hang or crash: each costs a timeout or a restart

    return survey


def run_property(name, body, parts, max_examples: int, run: Run) -> _Outcome:
    """Each part: a survey of its share of ``max_examples`` inputs that counts the failing ones.
    Then, for the first part with a failure, a second run that stops at the first failure and
    lets hypothesis shrink it to the smallest failing input. A timeout or crash ends the
    property at once (unshrunk); so does the budget (``cut``)."""
    from hypothesis import reject
    from hypothesis.errors import Unsatisfiable


    out = _Outcome()
    first: list[tuple[object, Failure]] = []
    per_part = []
    planned = sum(max(1, round(max_examples * share)) for _, _, share in parts)
    stopped = ""

    def tick():
        run.progress(name, out.inputs + count["inputs"], planned)

    run.progress(name, 0, planned)
    for label, strategy, share in parts:
        count = {"inputs": 0, "failed": 0}
        survey = _survey(body, count, first, strategy, run, tick)
        n = max(1, round(max_examples * share))
        try:
            _hypothesis_run(survey, strategy, n, run.seed, shrink=False)
        except Unsatisfiable:
            out.note = f"too few valid {label} inputs could be drawn"
        except _Stop:
            stopped = "stopped at the first timeout or crash"
        except BudgetSpent:
            out.cut = True
            stopped = "the budget ran out"
        out.inputs += count["inputs"]
        out.failed += count["failed"]
        if len(parts) > 1:
            per_part.append(f"{label} {count['failed']}/{count['inputs']}")
        if stopped:
            break
    if not first:
        return out
    if len(parts) > 1:
        out.note = "failing: " + ", ".join(per_part)
    strategy, failure = first[0]
    if stopped:
        out.failure = failure
        out.note = "; ".join(filter(None, (out.note, f"{stopped}: first failure, unshrunk")))
        return out
    falsified: list[Failure] = []
    faults = run.faults()

    def falsify(case):
        if run.faults() != faults:
            raise _Stop  # shrinking a hang or crash costs a timeout or restart per try
        run.budget.check()
        result = body(case)
        if result is DISCARD:
            reject()
        if result is not None:
            falsified.append(result)
            raise _Falsified(result)

    try:
        _hypothesis_run(falsify, strategy, max_examples, run.seed, shrink=True)
    except (BudgetSpent, _Stop) as err:
        out.failure = falsified[-1] if falsified else failure
        why = "the budget ran out" if isinstance(err, BudgetSpent) else "a timeout or crash"
        out.note += f"; shrinking stopped by {why}: the last failing input tried"
        return out
    except Exception as err:  # noqa: BLE001 - look for our own failure inside hypothesis' wrap
        found = _find_falsified(err)
        if found is None:
            raise
        out.failure = found.failure
        if found is not err:
            out.note += "; flaky: the callable gave different results for the same input"
        return out
    out.failure = failure
    out.note += "; not reproduced on a second run (flaky callable?): first failure, unshrunk"
    return out
