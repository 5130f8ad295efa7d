"""One row of the physics-check table: quantity, measured +- uncertainty, expected, agrees?
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from reports.paper.studies.sampling import fmt


@dataclass
class Check:
    """One row of the table."""

    quantity: str
    measured: float
    error: float
    expected: float
    method: str
    agrees: bool | None
    note: str = ""
    digits: int = 3


def agree(measured, err, expected, k=3.0, extra=0.0):
    if not (math.isfinite(measured) and math.isfinite(err)):
        return None
    return bool(abs(measured - expected) <= k * err + extra)


def _row(c: Check) -> str:
    agree = {True: "yes", False: "**no**", None: "n/a"}[c.agrees]
    exp = f"{c.expected:.{c.digits}g}" if c.digits > 3 else f"{c.expected:.4g}"
    return (f"| {c.quantity} | {fmt(c.measured, c.error)} | {exp} | {c.method} | "
            f"{agree} |")


def physics_table(rows) -> str:
    lines = ["| quantity | measured | expected | method | agrees? |", "|---|---|---|---|---|"]
    lines += [_row(c) for c in rows]
    return "\n".join(lines)
