"""The generated sections of docs/claims.md (``reports.paper.claims.page``)."""

import pytest

from reports.paper.claims import page as P
from reports.paper.claims.register import entries


def _claim(cid, verdict, kind=None, members=("confirmed", "confirmed")):
    return {"id": cid, "source": "paper", "verdict": verdict, "inconclusive": kind,
            "statement": f"reading of {cid}",
            "analyses": [{"verdict": v} for v in members]}


def _report():
    claims = [_claim(cid, "confirmed") for cid in P.BEFORE if cid not in P.SPLIT]
    for ids in P.SPLIT.values():
        claims += [_claim(i, "inconclusive", "data", ("inconclusive",)) for i in ids]
    claims[0] = _claim(claims[0]["id"], "inconclusive", "analysis", ("confirmed", "refuted"))
    claims.append(_claim("new-claim", "refuted", members=("refuted", "refuted")))
    return {"built": "test", "claims": claims}


def test_every_old_claim_has_its_change_recorded_and_its_id_or_split_is_registered():
    registered = {e["id"] for e in entries()}
    for cid in P.BEFORE:
        assert P.change_of(cid)
        assert set(P.SPLIT.get(cid, (cid,))) <= registered, cid
    with pytest.raises(ValueError, match="no change recorded"):
        P.change_of("a-claim-never-registered")


def test_the_sections_replace_the_old_ones_and_say_what_moved():
    report = _report()
    first = report["claims"][0]["id"]
    page = ("# Title\n\nintro\n\n" + P.VERDICTS_HEADING + "\n\nstale table\n\n## Kept\n\nkept "
            "text\n")
    text = P.rewrite(page, report)
    assert "stale table" not in text and "kept text" in text and text.startswith("# Title")
    assert text.count(P.VERDICTS_HEADING) == 1 and text.count(P.MOVED_HEADING) == 1
    paper = len(report["claims"])
    assert (f"{paper} claims of the paper, {paper - 8} confirmed, 1 refuted, 7 inconclusive"
            in " ".join(text.split()))
    assert f"| {first} | **inconclusive** | analysis | 0 of 2 |" in text
    assert f"| {first} | {P.BEFORE[first]} | inconclusive (analysis) (moved) |" in text
    assert ("| fig4-fewer-collisions | inconclusive | fig4-fewer-collisions-P12: inconclusive "
            "(data); fig4-fewer-collisions-P21: inconclusive (data) |") in text
    assert "| new-claim | **refuted** |  |" in text
    assert P.rewrite(text, report) == text  # a second run changes nothing
