"""The register of the paper's claims: complete entries, quotes found in the paper's text."""

import os
from pathlib import Path

import pytest

from reports.paper.claims import family as F
from reports.paper.claims.claim import FIELDS, PAPER, Claim
from reports.paper.claims.register import entries, make_claim, quote_found

PAPER_TEXT = os.environ.get("BOUNCER_PAPER_TEXT")


def test_the_register_holds_at_least_40_claims_of_the_paper_each_complete():
    es = entries()
    ids = [e["id"] for e in es]
    assert len(ids) == len(set(ids))
    paper = [e for e in es if e["source"] == PAPER]
    assert len(paper) >= 40
    for e in paper:
        for key in ("quote", "statement", "observable", "regime", "family", "rule",
                    "tolerance"):
            assert e[key].strip(), (e["id"], key)


def test_make_claim_takes_every_register_field_and_its_verdict_from_the_family():
    both = [F.Analysis(f"entry hole {i}", "confirmed", "survivors", 4.0, 4.0, 4.0, (3, 9), (),
                       "") for i in (1, 2)]
    c = make_claim("fig3-h=2.2", "all gone by t = 35", analyses=both, particles_per_curve=10)
    assert isinstance(c, Claim)
    assert list(c.__dataclass_fields__) == list(FIELDS)
    assert c.quote.startswith("one that is too large") and c.source == PAPER
    assert c.verdict == "confirmed" and c.inconclusive is None and c.run is None
    assert c.family == entries()[[e["id"] for e in entries()].index("fig3-h=2.2")]["family"]
    alone = make_claim("fig3-h=2.2", "one entry hole", analyses=both[:1])
    assert (alone.verdict, alone.inconclusive) == ("inconclusive", "data")


def test_every_claim_of_the_paper_declares_its_family():
    assert all(e["family"].strip() for e in entries() if e["source"] == PAPER)


def test_quote_found_normalises_whitespace_and_reads_elisions_in_order():
    text = "Alpha  beta\n gamma delta. Epsilon zeta eta."
    assert quote_found("beta gamma", text)
    assert quote_found("Alpha beta ... Epsilon zeta", text)
    assert not quote_found("Epsilon ... Alpha", text)  # pieces out of order
    assert not quote_found("beta delta", text)  # a word left out is not an elision


@pytest.mark.skipif(not PAPER_TEXT, reason="set BOUNCER_PAPER_TEXT to the paper's text file "
                    "(Dettmann & Leonel, 'Asymmetric transport in the bouncer model'; not part "
                    "of the repository) to check every quote against it")
def test_every_quote_of_the_paper_is_found_verbatim_in_its_text():
    text = Path(PAPER_TEXT).read_text(encoding="utf-8")
    missing = [e["id"] for e in entries() if e["source"] == PAPER
               and not quote_found(e["quote"], text)]
    assert not missing
