"""Claims as data: one ``Claim`` per checkable statement, with its verdict and the rule behind it.

A claim's fields (``report.json`` holds exactly these keys, in this order):

    id, figure        where it belongs ("2", "3", "4", "sec3", ...)
    statement         our one-line reading of what is asserted
    quote             the paper's own words, verbatim (whitespace may differ, "..." elides);
                      empty for claims that are not the paper's
    observable        what is measured
    regime            the part of the data the statement speaks of (bulk, intermediate, late
                      tail, finite time, matched survival levels, ...)
    rule              how the verdict follows from the measurement
    tolerance         the stated tolerance of a qualitative word ("close to", "the same", ...)
    source            "paper", a cited publication, or "this project" (our own estimate)
    verdict           confirmed | refuted | inconclusive (the data cannot decide under the rule)
    evidence          the numbers that decided it
    particles_per_curve, statistical, systematic, run

``statistical`` and ``systematic`` hold the uncertainties the verdict rests on (95% intervals,
half-ranges over a stated window family); ``run`` names the run directory of the numbers.
The register of the paper's claims (``reports.paper.register``) fixes id, figure, statement,
quote, observable, regime, rule, tolerance and source before any verdict is computed.

``report.json`` holds ``{"claims": [...]}``; the markdown of the claims is rendered from that same
list (``claims_markdown``), so the two cannot disagree.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field

from reports.runs import rundir

CONFIRMED, REFUTED, INCONCLUSIVE = "confirmed", "refuted", "inconclusive"
VERDICTS = (CONFIRMED, REFUTED, INCONCLUSIVE)
PAPER = "paper"
THIS_PROJECT = "this project"
FIELDS = ("id", "figure", "statement", "quote", "observable", "regime", "rule", "tolerance",
          "source", "verdict", "evidence", "particles_per_curve", "statistical", "systematic",
          "run")


@dataclass
class Claim:
    """One statement checked on data (module docstring). Build it by keyword."""

    id: str
    figure: str
    statement: str
    quote: str
    observable: str
    regime: str
    rule: str
    tolerance: str
    source: str
    verdict: str
    evidence: str
    particles_per_curve: int | None = None
    statistical: dict = field(default_factory=dict)
    systematic: dict = field(default_factory=dict)
    run: str | None = None

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict must be one of {', '.join(VERDICTS)}, got {self.verdict!r}")
        if not self.source:
            raise ValueError(f"claim {self.id!r}: source must be 'paper', a cited publication or"
                             f" {THIS_PROJECT!r}")
        if self.source == PAPER and not self.quote.strip():
            raise ValueError(f"claim {self.id!r}: a claim of the paper needs its quote")


def _json_safe(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(v) for v in value]
    if hasattr(value, "item") and not isinstance(value, str):
        return _json_safe(value.item())
    return value


def claims_json(claims) -> list[dict]:
    """JSON-ready dicts of ``Claim``s or of claim dicts (another section's), keys in FIELDS
    order; a dict with other keys is refused."""
    out = []
    for c in claims:
        d = asdict(c) if isinstance(c, Claim) else dict(c)
        if set(d) != set(FIELDS):
            raise ValueError(f"claim {d.get('id')!r}: keys must be exactly {', '.join(FIELDS)};"
                             f" got {', '.join(sorted(d))}")
        out.append(_json_safe({k: d[k] for k in FIELDS}))
    return out


def write_report_json(path, claims, **sections):
    """``report.json``: the claims and any further sections (plain JSON values)."""
    rundir.write_atomic(path, json.dumps(_json_safe({"claims": claims_json(claims), **sections}),
                                         indent=1) + "\n")


def _cell(text) -> str:
    return str(text).replace("|", "/").replace("\n", " ")


def _verdict_counts(claims):
    counts = {v: sum(c["verdict"] == v for c in claims) for v in VERDICTS}
    return (f"{counts[CONFIRMED]} confirmed, {counts[REFUTED]} refuted, "
            f"{counts[INCONCLUSIVE]} inconclusive")


def _quoted(text):
    return " ".join(str(text).split())


def claims_summary(claims: list[dict]) -> str:
    """One line: the paper's claims and the others, with their verdict counts."""
    paper = [c for c in claims if c["source"] == PAPER]
    other = [c for c in claims if c["source"] != PAPER]
    line = f"{len(paper)} claims of the paper: {_verdict_counts(paper)}."
    if other:
        line += (f" {len(other)} claims from other publications or this project (not the "
                 f"paper's): {_verdict_counts(other)}.")
    return line


def claims_markdown(claims: list[dict]) -> str:
    """A table of the claims (from their JSON form), then every claim with its quote, reading,
    rule, tolerance and the evidence that decided it; refuted and inconclusive claims first."""
    lines = [claims_summary(claims), "",
             "| id | figure | verdict | our reading | source | particles per curve | run |",
             "|---|---|---|---|---|---|---|"]
    for c in claims:
        n = c["particles_per_curve"]
        lines.append(f"| {c['id']} | {c['figure']} | **{c['verdict']}** | {_cell(c['statement'])}"
                     f" | {_cell(c['source'])} | {f'{n:,}' if n else '-'} | {c['run'] or '-'} |")
    lines.append("")
    order = {REFUTED: 0, INCONCLUSIVE: 1, CONFIRMED: 2}
    for c in sorted(claims, key=lambda c: order[c["verdict"]]):
        said = (f"The paper: \"{_quoted(c['quote'])}\"" if c["source"] == PAPER else
                f"Source: {c['source']}" + (f": \"{_quoted(c['quote'])}\"" if c["quote"] else "."))
        lines.append(
            f"- **{c['id']}** ({c['verdict']}). {said} *Reading:* {c['statement']}. "
            f"*Observable:* {c['observable']}. *Regime:* {c['regime']}. *Rule:* {c['rule']}. "
            f"*Tolerance:* {c['tolerance']}. *Evidence:* {c['evidence']}")
    return "\n".join(lines) + "\n"
