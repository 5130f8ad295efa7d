"""The overall time budget of a check: a deadline on the monotonic clock."""

from __future__ import annotations

import math
import time


class BudgetSpent(BaseException):  # noqa: N818 - a signal, not an error
    """The budget ran out. A ``BaseException`` on purpose: hypothesis treats an ``Exception``
    raised by a test as a failing input and replays and shrinks it; this must stop the search."""


class Budget:
    """``seconds`` from now (``math.inf``: no limit)."""

    def __init__(self, seconds: float) -> None:
        self.seconds = float(seconds)
        self.start = time.monotonic()

    def elapsed(self) -> float:
        return time.monotonic() - self.start

    def remaining(self) -> float:
        if math.isinf(self.seconds):
            return math.inf
        return max(0.0, self.seconds - self.elapsed())

    def check(self) -> None:
        """Raise :class:`BudgetSpent` once the budget is used up."""
        if self.remaining() <= 0.0:
            raise BudgetSpent
