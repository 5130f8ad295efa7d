"""Claims as data: one ``Claim`` per checkable statement, with its verdict and the rule behind it.

A claim's fields (``report.json`` holds exactly these keys, in this order):

    id, figure        where it belongs ("2", "3", "4", "sec3", ...)
    statement         our one-line reading of what is asserted
    quote             the paper's own words, verbatim (whitespace may differ, "..." elides);
                      empty for claims that are not the paper's
    observable        what is measured
    regime            the part of the data the statement speaks of (bulk, intermediate, late
                      tail, finite time, matched survival levels, ...)
    family            the family of analyses its words allow (windows inside the regime,
                      metrics, levels, curves), declared before the verdict
    rule              how the verdict follows from the measurement
    tolerance         the stated tolerance of a qualitative word ("close to", "the same", ...)
    source            "paper", a cited publication, or "this project" (our own estimate)
    verdict           confirmed | refuted | inconclusive (the data cannot decide under the rule)
    inconclusive      for an inconclusive verdict its kind: "data" (too few data), "between-bounds"
                      (precise, between the word's two bounds) or "analysis" (the family
                      disagrees); None for a decided one
    evidence          the numbers that decided it
    analyses          the members of the family: {"variant", "verdict", "figure", "bounds",
                      "note"} (``reports.paper.claims.family.analyses_json``)
    particles_per_curve, statistical, systematic, run

A verdict is the agreement of its family (``agreement``; how members are made:
``reports.paper.claims.family``). A claim that asserts several things at once (a conjunction:
"slower at first, faster at intermediate times") has one family per ``part``: a part is confirmed
(refuted) only if it has at least ``MIN_MEMBERS`` members and every one of them is confirmed
(refuted); the claim is confirmed if every part is, refuted if a part is, inconclusive
otherwise, of one kind:

* "data": too few data: a part with fewer than ``MIN_MEMBERS`` members, or whose undecided
  members are all imprecise (their intervals straddle a bound, their windows hold too few
  escapes), so that more data could decide;
* "between-bounds": in a part no member decides and one at least lies precisely between the
  word's two bounds, where the word itself is fuzzy;
* "analysis": a part's family disagrees: members decide differently, or one decides while
  another lies precisely between the bounds.

A part of kind "analysis" makes the claim's kind "analysis", else one of kind "between-bounds"
makes it "between-bounds", else it is "data". A ``Claim`` whose verdict or kind is not the
agreement of its analyses is refused.

``statistical`` and ``systematic`` hold the uncertainties the verdict rests on (95% intervals,
half-ranges over a stated window family); ``run`` names the run directory of the numbers.
The register of the paper's claims (``reports.paper.claims.register``) fixes id, figure, statement,
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
DATA, BETWEEN_BOUNDS, ANALYSIS = "data", "between-bounds", "analysis"
KINDS = (DATA, BETWEEN_BOUNDS, ANALYSIS)
MIN_MEMBERS = 2
BETWEEN = "between the word's bounds"  # the note of a member precisely between the bounds
PAPER = "paper"
THIS_PROJECT = "this project"
FIELDS = ("id", "figure", "statement", "quote", "observable", "regime", "family", "rule",
          "tolerance", "source", "verdict", "inconclusive", "evidence", "analyses",
          "particles_per_curve", "statistical", "systematic", "run")


@dataclass
class Claim:
    """One statement checked on data (module docstring). Build it by keyword."""

    id: str
    figure: str
    statement: str
    quote: str
    observable: str
    regime: str
    family: str
    rule: str
    tolerance: str
    source: str
    verdict: str
    inconclusive: str | None
    evidence: str
    analyses: list = field(default_factory=list)
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
        check_family(self.id, self.verdict, self.inconclusive, self.analyses)


def _part_agreement(members):
    verdicts = {a["verdict"] for a in members}
    if len(members) >= MIN_MEMBERS and verdicts in ({CONFIRMED}, {REFUTED}):
        return verdicts.pop(), None
    if len(members) < MIN_MEMBERS:
        return INCONCLUSIVE, DATA
    decided = verdicts - {INCONCLUSIVE}
    between = any(a.get("note") == BETWEEN for a in members)
    if len(decided) == 2 or (decided and between):
        return INCONCLUSIVE, ANALYSIS
    return INCONCLUSIVE, (BETWEEN_BOUNDS if between else DATA)


def agreement(analyses):
    """(verdict, kind) of a family given as JSON dicts with "verdict", "note" and "part" (module
    docstring); kind is None when the claim is decided. No analyses: inconclusive, "data"."""
    parts = {}
    for a in analyses:
        if a["verdict"] not in VERDICTS:
            raise ValueError(f"an analysis has no valid verdict: {a['verdict']!r}")
        parts.setdefault(a.get("part", ""), []).append(a)
    if not parts:
        return INCONCLUSIVE, DATA
    results = [_part_agreement(m) for m in parts.values()]
    verdicts = [v for v, _ in results]
    if all(v == CONFIRMED for v in verdicts):
        return CONFIRMED, None
    if any(v == REFUTED for v in verdicts):
        return REFUTED, None
    kinds = {k for _, k in results}
    for kind in (ANALYSIS, BETWEEN_BOUNDS):
        if kind in kinds:
            return INCONCLUSIVE, kind
    return INCONCLUSIVE, DATA


def check_family(claim_id, verdict, kind, analyses):
    """ValueError unless (verdict, kind) is the agreement of the analyses (``agreement``)."""
    if (verdict, kind) != agreement(analyses):
        raise ValueError(f"claim {claim_id!r}: {verdict} ({kind}) is not the agreement of its "
                         f"analyses, {agreement(analyses)}: "
                         f"{[(a.get('part', ''), a['verdict']) for a in analyses]}")


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
    order; a dict with other keys, or whose verdict is not the agreement of its analyses, is
    refused."""
    out = []
    for c in claims:
        d = asdict(c) if isinstance(c, Claim) else dict(c)
        if set(d) != set(FIELDS):
            raise ValueError(f"claim {d.get('id')!r}: keys must be exactly {', '.join(FIELDS)};"
                             f" got {', '.join(sorted(d))}")
        check_family(d["id"], d["verdict"], d["inconclusive"], d["analyses"])
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


def _number(x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        return str(x)
    return f"{x:.4g}"


def analyses_markdown(analyses) -> str:
    """The members of a family (JSON form), one clause each: variant: figure [interval] ->
    verdict (note)."""
    parts = []
    for a in analyses:
        f = a["figure"]
        lo, hi = f["interval"]
        parts.append(f"{a['variant']}: {f['quantity']} = {_number(f['value'])} "
                     f"[{_number(lo)}, {_number(hi)}] -> {a['verdict']}"
                     + (f" ({a['note']})" if a.get("note") else ""))
    return "; ".join(parts)


def verdict_text(c) -> str:
    """'confirmed', 'refuted' or 'inconclusive (kind)' of a claim (JSON form)."""
    return c["verdict"] + (f" ({c['inconclusive']})" if c["verdict"] == INCONCLUSIVE else "")


def claims_markdown(claims: list[dict]) -> str:
    """A table of the claims (from their JSON form), then every claim with its quote, reading,
    family, rule, tolerance, the evidence and the analyses that decided it; refuted and
    inconclusive claims first."""
    lines = [claims_summary(claims), "",
             "| id | figure | verdict | our reading | source | particles per curve | run |",
             "|---|---|---|---|---|---|---|"]
    for c in claims:
        n = c["particles_per_curve"]
        lines.append(f"| {c['id']} | {c['figure']} | **{verdict_text(c)}** | "
                     f"{_cell(c['statement'])} | {_cell(c['source'])} | "
                     f"{f'{n:,}' if n else '-'} | {c['run'] or '-'} |")
    lines.append("")
    order = {REFUTED: 0, INCONCLUSIVE: 1, CONFIRMED: 2}
    for c in sorted(claims, key=lambda c: order[c["verdict"]]):
        said = (f"The paper: \"{_quoted(c['quote'])}\"" if c["source"] == PAPER else
                f"Source: {c['source']}" + (f": \"{_quoted(c['quote'])}\"" if c["quote"] else "."))
        members = (f" *Analyses ({len(c['analyses'])}):* {analyses_markdown(c['analyses'])}."
                   if c["analyses"] else "")
        lines.append(
            f"- **{c['id']}** ({verdict_text(c)}). {said} *Reading:* {c['statement']}. "
            f"*Observable:* {c['observable']}. *Regime:* {c['regime']}. *Family:* "
            f"{c['family']}. *Rule:* {c['rule']}. *Tolerance:* {c['tolerance']}. *Evidence:* "
            f"{c['evidence']}{members}")
    return "\n".join(lines) + "\n"
