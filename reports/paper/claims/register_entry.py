"""One entry of the register of the paper's claims (``reports.paper.claims.register``): its fields,
written before any verdict."""

from __future__ import annotations

from reports.paper.claims.claim import PAPER

AGREE = ("the claim's verdict is the agreement of its family: confirmed (refuted) only if every "
         "member is, inconclusive otherwise")


def entry_of(id, figure, statement, quote, observable, regime, rule, tolerance, source=PAPER,
             *, family):
    """The entry's fields as a dict (``reports.paper.claims.register`` describes each)."""
    return {"id": id, "figure": figure, "statement": statement, "quote": quote,
            "observable": observable, "regime": regime, "family": family, "rule": rule,
            "tolerance": tolerance, "source": source}
