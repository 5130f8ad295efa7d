"""Tests that kill mutants of ``reports/runs/integrity.py`` (scripts/mutation.sh integrity): the
invariants that ``bouncer verify`` and a resume check, each fault on its own so that a weakened
check cannot hide behind another one."""

from fractions import Fraction

import pytest

from reports.runs.counts import Tally
from reports.runs.integrity import (
    parse_counts,
    survival_problems,
    tally_problems,
    velocity_shape_problems,
)
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene

VELOCITY = """
name = "small-velocity"
kind = "velocity"
eps = 2.0
particles = 300
seed = 3
chunk_size = 64
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 300
[record]
bins_per_decade = 5
verify_samples = 30
[physics]
restitution = [1.0, 0.9]
"""


@pytest.fixture(scope="module")
def vplan():
    return make_plan(parse_scene(VELOCITY))


def test_velocity_arrays_of_an_empty_tally_pass(vplan):
    assert velocity_shape_problems(vplan, Tally.empty(vplan)) == []


@pytest.mark.parametrize("name", ["moving", "stuck_at", "sum_v", "sum_v2"])
def test_missing_velocity_array_is_named(vplan, name):
    tally = Tally.empty(vplan)
    shape = getattr(tally, name).shape
    setattr(tally, name, None)
    assert velocity_shape_problems(vplan, tally) == [
        f"{name} has shape None, the plan needs {shape}"]


@pytest.mark.parametrize("name", ["moving", "stuck_at", "sum_v", "sum_v2"])
def test_misshapen_velocity_array_is_named(vplan, name):
    tally = Tally.empty(vplan)
    shape = getattr(tally, name).shape
    setattr(tally, name, getattr(tally, name)[:, :-1])
    assert velocity_shape_problems(vplan, tally) == [
        f"{name} has shape {(shape[0], shape[1] - 1)}, the plan needs {shape}"]
    assert tally_problems(vplan, tally) == [
        f"{name} has shape {(shape[0], shape[1] - 1)}, the plan needs {shape}"]


@pytest.mark.parametrize("name", ["moving", "stuck_at"])
def test_negative_velocity_count_is_named(vplan, name):
    tally = Tally.empty(vplan)
    getattr(tally, name)[1, 2] = -1
    assert velocity_shape_problems(vplan, tally) == [f"{name} has negative counts"]


@pytest.mark.parametrize("name", ["sum_v", "sum_v2"])
def test_inexact_velocity_sum_is_named(vplan, name):
    tally = Tally.empty(vplan)
    a = getattr(tally, name)
    a[0, 1] = 0.5  # a float where an exact Fraction belongs
    assert velocity_shape_problems(vplan, tally) == [
        f"{name} holds values that are not exact sums"]
    a[0, 1] = Fraction(1, 2)
    assert velocity_shape_problems(vplan, tally) == []


def test_negative_sums_are_not_counts(vplan):
    """Only moving and stuck_at are counts: a negative exact sum is not a sign problem here."""
    tally = Tally.empty(vplan)
    tally.sum_v[0, 0] = Fraction(-1)
    assert velocity_shape_problems(vplan, tally) == []


# ---- survival.csv ----------------------------------------------------------------------------

HEADER = "curve,clock,x,p,p_lo,p_hi\n"


def test_survival_rows_in_range_and_falling_pass():
    text = HEADER + "a,collisions,1,1.0,0.9,1.0\na,collisions,2,0.5,0.4,0.6\n"
    assert survival_problems(text) == []


def test_survival_row_out_of_range_is_named_by_file_and_line():
    text = HEADER + "a,collisions,1,1.0,0.9,1.0\na,collisions,2,0.5,0.6,0.7\n"
    assert survival_problems(text) == [
        "survival.csv:3: a (collisions): p 0.5 with band [0.6, 0.7] is not"
        " 0 <= p_lo <= p <= p_hi <= 1"]
    assert survival_problems(text, "s.csv")[0].startswith("s.csv:3: ")


def test_rising_survival_is_named_by_file_and_line():
    text = (HEADER + "a,collisions,1,0.5,0.4,0.6\nb,collisions,1,0.9,0.8,1.0\n"
            "a,time,1,0.9,0.8,1.0\na,collisions,2,0.6,0.5,0.7\n")
    assert survival_problems(text) == [
        "survival.csv:5: a (collisions): p rises from 0.5 to 0.6"]


def test_unparsable_survival_row_is_named_by_line():
    text = HEADER + "a,collisions,1,1.0,0.9,1.0\na,collisions,2,half,0.4,0.6\n"
    assert survival_problems(text) == ["survival.csv:3: not a survival row"]
    assert survival_problems(HEADER + "a,collisions,1\n") == ["survival.csv:2: not a survival row"]


def test_checks_go_on_after_an_unparsable_row():
    text = HEADER + "a,collisions,1,x,0.9,1.0\na,collisions,2,1.0,0.9,1.5\n"
    assert survival_problems(text) == [
        "survival.csv:2: not a survival row",
        "survival.csv:3: a (collisions): p 1.0 with band [0.9, 1.5] is not"
        " 0 <= p_lo <= p <= p_hi <= 1"]


# ---- counts.csv ------------------------------------------------------------------------------

TINY = """
name = "tiny"
kind = "transport"
eps = 0.6
particles = 200
seed = 3
chunk_size = 64
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [1.0]
[horizon]
collisions = 200
"""

COUNTS_HEADER = "experiment,clock,outcome,lower_edge,count\n"


@pytest.fixture(scope="module")
def tplan():
    return make_plan(parse_scene(TINY))


def test_empty_or_foreign_counts_csv_is_refused_at_the_header(tplan):
    for text, header in [("", None), ("a,b\n1,2\n", ["a", "b"])]:
        counts, stuck, problems, first = parse_counts(tplan, text)
        assert problems == [f"counts.csv:1: header {header} is not the counts.csv header"]
        assert counts.esc_n.sum() == counts.cens_n.sum() == 0 and stuck == {} and first == {}
    assert parse_counts(tplan, "", "c2.csv")[2] == ["c2.csv:1: header None is not the"
                                                   " counts.csv header"]


def test_rows_that_are_not_of_this_run_are_named_by_line(tplan):
    rows = ["from hole 1,collisions,P11,1.0,5",     # 2: fine
            "from hole 1,collisions,P11,2.0,0",     # 3: a zero count is never written
            "from hole 1,collisions,P11,2.0,-4",    # 4: negative
            "from hole 9,collisions,P11,2.0,1",     # 5: no such experiment
            "from hole 1,collisions,P11,2.5,1",     # 6: no such edge
            "from hole 1,sideways,P11,2.0,1",       # 7: no such clock
            "from hole 1,collisions,P11,2.0",       # 8: a field short
            "from hole 1,collisions,P31,2.0,1",     # 9: no such outcome
            "from hole 2,time,censored,0.1,3"]      # 10: fine
    counts, stuck, problems, first = parse_counts(tplan, COUNTS_HEADER + "\n".join(rows) + "\n")
    assert problems == [f"counts.csv:{i}: not a row of this run: {rows[i - 2]}"
                        for i in range(3, 9)] + ["counts.csv:9: unknown outcome 'P31'"]
    assert first == {(0, "collisions"): 2, (1, "time"): 10}
    assert counts.esc_n[0, 0, 0] == 5 and counts.esc_n.sum() == 5
    assert counts.cens_t[1, 1] == 3 and counts.cens_t.sum() == 3


def test_a_clock_the_scene_does_not_record_is_not_a_row_of_this_run(tplan):
    plan = make_plan(parse_scene(TINY.replace("[horizon]", '[record]\nclocks = ["collisions"]'
                                              "\n[horizon]")))
    assert plan.scene.clocks == ("collisions",)
    text = COUNTS_HEADER + "from hole 1,time,P11,0.1,5\nfrom hole 1,collisions,P11,1.0,5\n"
    counts, _, problems, first = parse_counts(plan, text)
    assert problems == ["counts.csv:2: not a row of this run: from hole 1,time,P11,0.1,5"]
    assert counts.esc_t.sum() == 0 and first == {(0, "collisions"): 3}


def test_stuck_rows_count_under_their_clock(tplan):
    text = (COUNTS_HEADER + "from hole 2,collisions,stuck,3.0,4\nfrom hole 2,time,stuck,0.1,2\n"
            "from hole 2,collisions,stuck,3.0,1\n")
    counts, stuck, problems, _ = parse_counts(tplan, text)
    assert problems == [] and stuck == {(1, "collisions"): 5, (1, "time"): 2}
    assert counts.stuck_n[1, 2] == 5 and counts.stuck_n.sum() == 5
    assert counts.stuck_t[1, 1] == 2 and counts.stuck_t.sum() == 2
