"""Claims as data: the schema, report.json round trips, the markdown rendered from it."""

import json
import math

import pytest

from reports.paper.claims import family as F
from reports.paper.claims.claim import (
    FIELDS,
    Claim,
    agreement,
    claims_json,
    claims_markdown,
    write_report_json,
)


def members(verdict):
    note = "" if verdict != "inconclusive" else F.STRADDLES
    return F.analyses_json([F.Analysis(f"window {i}", verdict, "beta", 0.56, 0.55, 0.57,
                                       (0.4, 0.6), (), note) for i in (1, 2)])


def claim(verdict="confirmed", **kw):
    analyses = kw.pop("analyses", members(verdict if verdict in ("confirmed", "refuted",
                                                                 "inconclusive") else
                                          "confirmed"))
    base = dict(id="fig2-t-phi_c=1", figure="2", statement="close to exp(-c sqrt(t))",
                quote="the rapid decay is instead close to a stretched exponential",
                observable="beta", regime="intermediate", family="two windows", rule="band",
                tolerance="0.1", source="paper", verdict=verdict,
                inconclusive=agreement(analyses)[1], evidence="beta = 0.56 [0.55, 0.57].",
                analyses=analyses, particles_per_curve=10**8, statistical={"beta": 0.56},
                systematic={"beta": math.inf}, run="paper-escape-1e8")
    base.update(kw)
    return Claim(**base)


def test_an_unknown_verdict_is_refused():
    with pytest.raises(ValueError, match="verdict must be one of"):
        claim("partly confirmed")


def test_a_claim_of_the_paper_needs_its_quote():
    with pytest.raises(ValueError, match="needs its quote"):
        claim(quote=" ")
    assert claim(quote="", source="this project").quote == ""


def test_report_json_round_trips_with_exactly_the_schema_and_the_markdown_follows_it(tmp_path):
    claims = [claim(), claim("refuted", id="fig3-h=1"), claim("inconclusive", id="fermi-t")]
    write_report_json(tmp_path / "report.json", claims, quick=True)
    stored = json.loads((tmp_path / "report.json").read_text())
    assert [list(c) for c in stored["claims"]] == [list(FIELDS)] * 3
    assert stored["claims"][0]["systematic"]["beta"] == "inf"  # JSON has no infinity
    assert stored["claims"] == claims_json(claims)
    md = claims_markdown(stored["claims"])
    assert md.startswith("3 claims of the paper: 1 confirmed, 1 refuted, 1 inconclusive.")
    assert "| fig3-h=1 | 2 | **refuted** |" in md
    assert "| fermi-t | 2 | **inconclusive (data)** |" in md
    assert stored["claims"][0]["analyses"][0]["figure"] == {
        "quantity": "beta", "value": 0.56, "interval": [0.55, 0.57]}
    assert "*Analyses (2):* window 1: beta = 0.56 [0.55, 0.57] -> confirmed" in md
    # every verdict with its quote; refuted and inconclusive ones first, with their evidence
    assert md.count("The paper: \"the rapid decay is instead close to a stretched") == 3
    assert md.index("**fig3-h=1** (refuted)") < md.index("**fermi-t** (inconclusive (data))") < \
        md.index("**fig2-t-phi_c=1** (confirmed)")
    assert "*Evidence:* beta = 0.56" in md


def test_claims_from_another_section_come_as_dicts_with_the_same_keys():
    other = dict(zip(FIELDS, ["sec2-fixed-points", "sec2", "elliptic for 0 < eps < 1", "q", "o",
                              "r", "f", "rule", "t", "paper", "confirmed", None, "e",
                              members("confirmed"), None, {}, {}, None], strict=True))
    assert claims_json([claim(), other])[1]["id"] == "sec2-fixed-points"
    with pytest.raises(ValueError, match="keys must be exactly"):
        claims_json([{**other, "seed_says": "x"}])
    with pytest.raises(ValueError, match="not the agreement"):
        claims_json([{**other, "analyses": members("confirmed")[:1]}])


def test_claims_not_of_the_paper_are_counted_apart():
    md = claims_markdown(claims_json([claim(), claim("refuted", id="dissipation-exponent",
                                                     figure="dissipation", quote="",
                                                     source="this project")]))
    assert md.startswith("1 claims of the paper: 1 confirmed, 0 refuted, 0 inconclusive. 1 "
                         "claims from other publications or this project")
    assert "Source: this project" in md
