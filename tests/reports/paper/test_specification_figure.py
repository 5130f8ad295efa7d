"""Specification plots: every contested claim drawn with its family, nothing else."""

from reports.paper.claims import family as F
from reports.paper.claims.claim import agreement
from reports.paper.figures.specification import contested, specification_markdown


def claim(cid, verdicts):
    analyses = F.analyses_json([
        F.Analysis(f"window {i}", v, "beta", 0.3 + 0.1 * i, 0.25 + 0.1 * i, 0.35 + 0.1 * i,
                   (0.25, 0.75), ((-1e9, 0.25), (0.75, 1e9)),
                   "" if v != "inconclusive" else F.STRADDLES) for i, v in enumerate(verdicts)])
    verdict, kind = agreement(analyses)
    return {"id": cid, "verdict": verdict, "inconclusive": kind, "analyses": analyses}


def test_only_claims_not_confirmed_by_every_member_are_contested():
    assert not contested(claim("a", ["confirmed", "confirmed"]))
    assert contested(claim("b", ["confirmed", "refuted"]))
    assert contested(claim("c", ["refuted", "refuted"]))
    assert contested(claim("d", ["confirmed", "inconclusive"]))


def test_a_figure_per_contested_claim_and_markdown_that_shows_each(tmp_path):
    claims = [claim("fig2-n-phi_c=2", ["refuted", "confirmed", "confirmed"]),
              claim("fig2-t-phi_c=1", ["confirmed", "confirmed"])]
    md = specification_markdown(claims, tmp_path)
    files = sorted(p.name for p in (tmp_path / "specification").iterdir())
    assert files == ["spec_fig2-n-phi_c_2.pdf", "spec_fig2-n-phi_c_2.png"]
    assert "![family of fig2-n-phi_c=2](specification/spec_fig2-n-phi_c_2.png)" in md
    assert "inconclusive (analysis), 3 analyses" in md and "fig2-t-phi_c=1" not in md
    assert specification_markdown(claims[1:], tmp_path) == ""
