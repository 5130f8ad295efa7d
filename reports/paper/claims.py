"""The seed's claims as data: one ``Claim`` per statement, with a verdict and the rule behind it.

A verdict is ``confirmed``, ``refuted`` or ``inconclusive`` (the data cannot decide under the
stated rule). ``statistical`` and ``systematic`` hold the uncertainties of the quantities the
verdict rests on (95% intervals from the likelihood, and half-ranges over the window family of
``reports.stats.analysis``); ``run`` names the run directory the numbers come from.

``report.json`` holds ``{"claims": [...]}`` and the markdown of the claims is rendered from that
same list (``claims_markdown``), so the two cannot disagree.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field

from reports.runs import rundir

CONFIRMED, REFUTED, INCONCLUSIVE = "confirmed", "refuted", "inconclusive"
VERDICTS = (CONFIRMED, REFUTED, INCONCLUSIVE)


@dataclass
class Claim:
    """One statement of the seed checked on data."""

    id: str
    figure: str  # "1".."4" or "fermi"
    seed_says: str
    verdict: str
    evidence: str
    particles_per_curve: int | None
    statistical: dict = field(default_factory=dict)
    systematic: dict = field(default_factory=dict)
    run: str | None = None
    rule: str = ""

    def __post_init__(self):
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict must be one of {', '.join(VERDICTS)}, got {self.verdict!r}")


def _json_safe(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(v) for v in value]
    return value


def claims_json(claims) -> list[dict]:
    return [_json_safe(asdict(c)) for c in claims]


def write_report_json(path, claims, **sections):
    """``report.json``: the claims and any further sections (plain JSON values)."""
    rundir.write_atomic(path, json.dumps(_json_safe({"claims": claims_json(claims), **sections}),
                                         indent=1) + "\n")


def _cell(text) -> str:
    return str(text).replace("|", "/").replace("\n", " ")


BEYOND_THE_SEED = ("dissipation",)  # figures of claims the seed does not make (issue 16's study)


def _verdict_counts(claims):
    counts = {v: sum(c["verdict"] == v for c in claims) for v in VERDICTS}
    return (f"{counts[CONFIRMED]} confirmed, {counts[REFUTED]} refuted, "
            f"{counts[INCONCLUSIVE]} inconclusive")


def claims_markdown(claims: list[dict]) -> str:
    """A table of the claims (from their JSON form), then each claim's evidence and rule."""
    seeds = [c for c in claims if c["figure"] not in BEYOND_THE_SEED]
    beyond = [c for c in claims if c["figure"] in BEYOND_THE_SEED]
    summary = f"{len(seeds)} claims of the seed: {_verdict_counts(seeds)}."
    if beyond:
        figures = ", ".join(sorted({c["figure"] for c in beyond}))
        summary += f" {len(beyond)} beyond the seed ({figures}): {_verdict_counts(beyond)}."
    lines = [summary, "",
             "| id | figure | the seed says | verdict | particles per curve | run |",
             "|---|---|---|---|---|---|"]
    for c in claims:
        n = c["particles_per_curve"]
        lines.append(f"| {c['id']} | {c['figure']} | {_cell(c['seed_says'])} | "
                     f"**{c['verdict']}** | {f'{n:,}' if n else '-'} | {c['run'] or '-'} |")
    lines.append("")
    for c in claims:
        lines.append(f"- **{c['id']}** ({c['verdict']}): {c['evidence']} *Rule:* {c['rule']}")
    return "\n".join(lines) + "\n"
