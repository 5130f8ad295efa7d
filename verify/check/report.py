"""What a check found: :class:`Failure` (one falsified property with its input),
:class:`PropertyResult` (one property's outcome) and :class:`CheckReport` (all of them, as text
with ``str``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .suites import PROPERTIES

NO_INPUT = "no input could be checked"  # the note of a property that never ran


@dataclass(frozen=True)
class Failure:
    """One falsified property: its name, the input, what was expected and what came back.

    ``expected`` and ``obtained`` are floats (a flight time), tuples (a step's output or a
    Jacobian) or a string (an exception the callable raised). ``call`` names the callable that
    produced ``obtained`` (``"flight_time"`` or ``"step"``); ``(phi, v, eps)`` is its input
    (the input the property started from, for Jacobians and reversibility).
    """

    property: str
    phi: float
    v: float
    eps: float
    expected: object
    obtained: object
    message: str
    call: str = "flight_time"

    @property
    def input(self) -> tuple[float, float, float]:
        return (self.phi, self.v, self.eps)

    def __str__(self) -> str:
        return (
            f"{self.property}: {self.call}(phi={self.phi!r}, v={self.v!r}, eps={self.eps!r})\n"
            f"    expected {show(self.expected)}\n"
            f"    obtained {show(self.obtained)}\n"
            f"    {self.message}"
        )


@dataclass(frozen=True)
class PropertyResult:
    """Outcome of one property: ``status`` is "PASS", "FAIL", "SKIP" (it needs a step callable
    and none was given) or "INCONCLUSIVE" (the budget ran out before its search finished,
    ``inputs`` is the count reached; or no input could be checked)."""

    name: str
    status: str
    inputs: int
    note: str = ""
    failure: Failure | None = None
    seconds: float = 0.0
    failed: int = 0


@dataclass(frozen=True)
class CheckReport:
    """What :func:`check_integrator` found. ``ok``: no property failed (skips are not failures)."""

    target: str
    step_target: str | None
    suite: str
    k: float
    seed: int | None
    max_examples: int
    results: tuple[PropertyResult, ...]
    worst_accuracy_k: float | None
    worst_accuracy_input: tuple[float, float, float] | None = None
    seconds: float = 0.0
    budget: float = math.inf
    call_timeout: float = math.inf
    isolation: str = ""  # how the callables ran: a worker process, or in-process and why

    @property
    def verdict(self) -> str:
        """"failed" if a property failed, else "inconclusive" if one did not run to the end
        (the budget cut it short, or no input could be checked), else "passed": every
        property of the suite ran and held (a property that needs a step callable, when none
        was given, is skipped)."""
        if any(r.status == "FAIL" for r in self.results):
            return "failed"
        if not any(r.status == "PASS" for r in self.results) or any(
                r.status not in ("PASS", "SKIP") for r in self.results):
            return "inconclusive"
        return "passed"

    @property
    def ok(self) -> bool:
        """Every property ran and held on all its inputs (skips for want of a step callable
        aside); inconclusive is not ok."""
        return self.verdict == "passed"

    @property
    def failures(self) -> list[Failure]:
        return [r.failure for r in self.results if r.failure is not None]

    def result(self, name: str) -> PropertyResult:
        for r in self.results:
            if r.name == name:
                return r
        raise KeyError(f"property {name!r} was not run (suite {self.suite!r})")

    def __str__(self) -> str:
        step = self.step_target or "none"
        lines = [
            f"check of flight_time={self.target}, step={step}",
            f"suite {self.suite!r}, k = {self.k:g}, seed {self.seed}, up to {self.max_examples}"
            f" inputs per property, {self.seconds:.1f} s",
        ]
        if self.isolation:
            lines.append(f"budget {self.budget:g} s, call timeout {self.call_timeout:g} s, "
                         f"{self.isolation}")
        width = max(len(p) for p in PROPERTIES)
        for r in self.results:
            note = f"  ({r.note})" if r.note else ""
            if r.status == "FAIL":
                what = f"{r.failed} of {r.inputs} inputs fail"
            elif r.status == "SKIP":
                what = "skipped"
            elif r.status == "INCONCLUSIVE" and NO_INPUT in r.note:
                what = "not run"
            elif r.status == "INCONCLUSIVE":
                what = f"{r.inputs} of {self.max_examples} inputs when the budget ran out"
            else:
                what = f"{r.inputs} inputs"
            lines.append(f"  {r.status}  {r.name:<{width}}  {what}{note}")
        fails = self.failures
        if fails:
            unshrunk = any("unshrunk" in r.note for r in self.results if r.failure)
            how = "hypothesis-shrunk unless its note says unshrunk" if unshrunk \
                else "hypothesis-shrunk"
            lines.append(
                f"{len(fails)} of {len(self.results)} properties failed; smallest failing "
                f"input found ({how}):"
            )
            for f in fails:
                lines.extend("  " + line for line in str(f).splitlines())
        elif self.verdict == "inconclusive":
            if any(r.status == "INCONCLUSIVE" and NO_INPUT not in r.note for r in self.results):
                lines.append(f"inconclusive: the budget of {self.budget:g} s ran out before "
                             "every property had its inputs; no property failed on the inputs "
                             "tried")
            else:
                lines.append(f"inconclusive: a property had {NO_INPUT}; no property failed "
                             "on the inputs tried")
        else:
            lines.append("all properties hold")
        return "\n".join(lines)


def show(x) -> str:
    if isinstance(x, float):
        return repr(x)
    if isinstance(x, tuple):
        return "(" + ", ".join(show(y) for y in x) + ")"
    return str(x)


def callable_name(fn) -> str:
    mod = getattr(fn, "__module__", None)
    qual = getattr(fn, "__qualname__", None) or getattr(fn, "__name__", None) or repr(fn)
    return f"{mod}:{qual}" if mod else str(qual)
