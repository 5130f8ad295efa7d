"""A verdict is the agreement of its family: members built here with known verdicts."""

import math

import pytest

from reports.paper.claims import family as F
from reports.paper.claims import rules as R
from reports.paper.claims.claim import (
    ANALYSIS,
    BETWEEN_BOUNDS,
    CONFIRMED,
    DATA,
    INCONCLUSIVE,
    REFUTED,
    Claim,
    agreement,
)


def member(verdict, note="", part=""):
    return F.Analysis("v", verdict, "q", 0.5, 0.4, 0.6, (0, 1), (), note, part)


def test_every_member_confirming_confirms_and_every_one_refuting_refutes():
    assert F.family_verdict([member(CONFIRMED)] * 3) == (CONFIRMED, None)
    assert F.family_verdict([member(REFUTED)] * 2) == (REFUTED, None)


def test_one_member_is_not_a_family():
    assert F.family_verdict([member(CONFIRMED)]) == (INCONCLUSIVE, DATA)
    assert F.family_verdict([]) == (INCONCLUSIVE, DATA)


@pytest.mark.parametrize(("members", "kind"), [
    ([CONFIRMED, REFUTED], ANALYSIS),                        # they decide differently
    ([CONFIRMED, (INCONCLUSIVE, R.BETWEEN)], ANALYSIS),      # one decides, one lies between
    ([CONFIRMED, (INCONCLUSIVE, F.STRADDLES)], DATA),        # more data could decide
    ([(INCONCLUSIVE, R.BETWEEN), (INCONCLUSIVE, F.STRADDLES)], BETWEEN_BOUNDS),
    ([(INCONCLUSIVE, F.TOO_FEW), (INCONCLUSIVE, F.STRADDLES)], DATA),
])
def test_an_undecided_family_says_which_kind_it_is(members, kind):
    built = [member(m) if isinstance(m, str) else member(*m) for m in members]
    assert F.family_verdict(built) == (INCONCLUSIVE, kind)


def test_a_conjunction_is_refuted_by_one_refuted_part_and_confirmed_only_by_all():
    confirmed = [member(CONFIRMED, part="a")] * 2
    refuted = [member(REFUTED, part="b")] * 2
    undecided = [member(CONFIRMED, part="b"), member(INCONCLUSIVE, F.STRADDLES, part="b")]
    assert F.family_verdict(confirmed + refuted) == (REFUTED, None)
    assert F.family_verdict(confirmed + undecided) == (INCONCLUSIVE, DATA)
    assert F.family_verdict(confirmed + [member(CONFIRMED, part="b")] * 2) == (CONFIRMED, None)


def test_a_member_says_why_exactly_when_it_does_not_decide():
    with pytest.raises(ValueError, match="says why"):
        member(INCONCLUSIVE)
    with pytest.raises(ValueError, match="says why"):
        member(CONFIRMED, F.STRADDLES)


def claim(verdict, kind, analyses):
    return Claim(id="x", figure="2", statement="s", quote="q", observable="o", regime="r",
                 family="f", rule="r", tolerance="t", source="paper", verdict=verdict,
                 inconclusive=kind, evidence="e", analyses=F.analyses_json(analyses))


def test_a_claim_whose_verdict_is_not_its_familys_agreement_is_refused():
    assert claim(CONFIRMED, None, [member(CONFIRMED)] * 2).verdict == CONFIRMED
    with pytest.raises(ValueError, match="not the agreement"):
        claim(CONFIRMED, None, [member(CONFIRMED)])          # one member
    with pytest.raises(ValueError, match="not the agreement"):
        claim(REFUTED, None, [member(REFUTED), member(CONFIRMED)])
    with pytest.raises(ValueError, match="not the agreement"):
        claim(INCONCLUSIVE, DATA, [member(REFUTED), member(CONFIRMED)])  # it is "analysis"
    assert claim(INCONCLUSIVE, DATA, []).inconclusive == DATA


def test_the_json_form_holds_variant_verdict_figure_and_bounds():
    a = F.word_member("window 1", "share", 0.05, 0.02, 0.08, 0.1, 0.5)
    (j,) = F.analyses_json([a])
    assert j["variant"] == "window 1" and j["verdict"] == CONFIRMED
    assert j["figure"] == {"quantity": "share", "value": 0.05, "interval": [0.02, 0.08]}
    assert j["bounds"] == {"holds": [-math.inf, 0.1], "fails": [[0.5, math.inf]]}
    assert agreement([j, j]) == (CONFIRMED, None)


@pytest.mark.parametrize(("lo", "hi", "verdict", "note"), [
    (0.30, 0.40, CONFIRMED, ""), (0.05, 0.20, REFUTED, ""),
    (0.20, 0.30, INCONCLUSIVE, F.STRADDLES), (math.nan, 0.3, INCONCLUSIVE, F.TOO_FEW)])
def test_the_form_rule_on_a_members_beta(lo, hi, verdict, note):
    a = F.form_member("w", 0.3, lo, hi, "sqrt")
    assert (a.verdict, a.note) == (verdict, note)


def test_the_same_rule_reads_the_relative_difference():
    a = F.same_member("w", "alpha", 2.0, 0.05, 2.1, 0.05)   # 5% apart, +- 5%
    assert a.verdict == CONFIRMED and a.value == pytest.approx(0.1 / 2.05)
    b = F.same_member("w", "alpha", 1.2, 0.02, 1.0, 0.0)    # 18% apart, precise
    assert b.verdict == INCONCLUSIVE and b.note == R.BETWEEN
    assert F.same_member("w", "alpha", 3.0, 0.1, 2.0, 0.1).verdict == REFUTED


def test_an_ordering_has_one_threshold():
    assert F.threshold_member("w", "r", 2.0, 1.5, 2.5, 1.0, False).verdict == CONFIRMED
    assert F.threshold_member("w", "r", 0.5, 0.4, 0.6, 1.0, False).verdict == REFUTED
    assert F.threshold_member("w", "r", 1.0, 0.9, 1.1, 1.0, False).note == F.STRADDLES
    assert F.threshold_member("w", "r", 0.2, 0.1, 0.3, 0.5, True).verdict == CONFIRMED
