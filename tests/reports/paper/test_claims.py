"""Claims as data: verdicts checked, report.json round-trips, the markdown rendered from it."""

import json
import math

import pytest

from reports.paper.claims import Claim, claims_json, claims_markdown, write_report_json


def claim(verdict="confirmed", **kw):
    base = dict(id="fig2-n-phi_c=0", figure="2", seed_says="exponential", verdict=verdict,
                evidence="Vuong Z = 3.", particles_per_curve=10**8,
                statistical={"beta": 0.97, "beta_ci95": [0.96, 0.98]},
                systematic={"beta": math.inf}, run="paper-escape-1e8", rule="Vuong at 0.05")
    base.update(kw)
    return Claim(**base)


def test_an_unknown_verdict_is_refused():
    with pytest.raises(ValueError, match="verdict must be one of"):
        claim("partly confirmed")


def test_report_json_round_trips_and_the_markdown_follows_it(tmp_path):
    claims = [claim(), claim("refuted", id="fig3-h=1"), claim("inconclusive", id="fermi-t")]
    write_report_json(tmp_path / "report.json", claims, quick=True)
    stored = json.loads((tmp_path / "report.json").read_text())
    assert stored["quick"] is True
    assert [c["id"] for c in stored["claims"]] == ["fig2-n-phi_c=0", "fig3-h=1", "fermi-t"]
    assert stored["claims"][0]["systematic"]["beta"] == "inf"  # JSON has no infinity
    assert stored["claims"] == claims_json(claims)
    md = claims_markdown(stored["claims"])
    assert "3 claims of the seed: 1 confirmed, 1 refuted, 1 inconclusive." in md
    assert "| fig3-h=1 | 2 | exponential | **refuted** | 100,000,000 | paper-escape-1e8 |" in md


def test_claims_beyond_the_seed_are_counted_apart():
    claims = [claim(), claim("refuted", id="dissipation-exponent", figure="dissipation")]
    md = claims_markdown(claims_json(claims))
    assert md.startswith("1 claims of the seed: 1 confirmed, 0 refuted, 0 inconclusive. 1 beyond"
                         " the seed (dissipation): 0 confirmed, 1 refuted, 0 inconclusive.")
