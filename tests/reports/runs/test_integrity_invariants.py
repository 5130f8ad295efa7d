"""The invariants of a run's checkpoint and outputs (``reports.runs.integrity``) that
``bouncer verify`` and a resume check, each fault on its own so that a weakened check cannot hide
behind another one."""

from fractions import Fraction

import numpy as np
import pytest
from scene_texts import PORTRAIT, SMALL_VELOCITY, TINY

from reports.runs.counts import Tally
from reports.runs.integrity import (
    curve_problems,
    parse_counts,
    survival_problems,
    tally_problems,
    velocity_shape_problems,
)
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene


@pytest.fixture(scope="module")
def vplan():
    return make_plan(parse_scene(SMALL_VELOCITY))


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


# ---- the checkpoint's tally ------------------------------------------------------------------

ARRAYS = ("esc_n", "esc_t", "cens_n", "cens_t", "portrait", "stuck_n", "stuck_t")


def _consistent(plan, chunks):
    """An empty tally with ``chunks`` finished and every started particle censored on both
    clocks (in the first bin): all invariants hold."""
    tally = Tally.empty(plan)
    for key in chunks:
        tally.finished.add(key)
    for e in range(len(plan.experiments)):
        done = tally.finished.particles_done(plan, e)
        tally.cens_n[e, 0] = tally.cens_t[e, 0] = done
    return tally


def test_a_consistent_tally_passes(tplan):
    assert tally_problems(tplan, _consistent(tplan, [(0, 0), (1, 3), (1, 1)])) == []
    assert tally_problems(tplan, _consistent(tplan, tplan.chunks)) == []


@pytest.mark.parametrize("name", ARRAYS)
def test_misshapen_array_is_named_and_stops_the_checks(tplan, name):
    tally = _consistent(tplan, [(0, 0)])
    good = getattr(tally, name).shape
    setattr(tally, name, np.zeros((3, *good[1:]), np.int64))
    tally.finished.add((0, 1))  # 64 particles unaccounted for: not reported, shapes first
    assert tally_problems(tplan, tally) == [
        f"{name} has shape {(3, *good[1:])}, the plan needs {good}"]


@pytest.mark.parametrize("name", ARRAYS)
def test_negative_count_is_named(tplan, name):
    plan = tplan
    tally = _consistent(plan, [(0, 0)])
    a = getattr(tally, name)
    if a.size == 0:  # the portrait of a scene that draws none: a phase-space plan's
        plan = make_plan(parse_scene(PORTRAIT))
        tally = Tally.empty(plan)
        a = tally.portrait
    a.flat[a.size - 1] = -1
    assert tally_problems(plan, tally) == [f"{name} has negative counts"]


@pytest.mark.parametrize(("collisions", "settled"), [(-1, 0), (0, -1)])
def test_negative_totals_are_named(tplan, collisions, settled):
    tally = _consistent(tplan, [(0, 0)])
    tally.collisions, tally.settled = collisions, settled
    assert tally_problems(tplan, tally) == [
        f"negative totals: collisions {collisions}, settled {settled}"]


@pytest.mark.parametrize("prefix", [[1], [1, 0, 0], [5, 0], [0, -1]])
def test_finished_prefixes_that_do_not_fit_the_plan(tplan, prefix):
    tally = Tally.empty(tplan)
    tally.finished.prefix = prefix
    assert tally_problems(tplan, tally) == [
        f"finished-chunk prefixes {prefix} do not fit 2 curves x 4 chunks"]


@pytest.mark.parametrize("extra", [{(2, 1)}, {(-1, 1)}, {(0, 1)}, {(0, 0)}, {(0, 4)}])
def test_finished_chunks_outside_the_plan(tplan, extra):
    """prefix [1, 0]: chunk (0, 0) is in the prefix, (0, 1) and (0, 4) ... are not extras."""
    tally = _consistent(tplan, [(0, 0)])
    tally.finished.extra = set(extra)
    assert tally_problems(tplan, tally) == [
        f"finished chunks outside the plan: {sorted(extra)}"]


def test_a_full_prefix_and_an_extra_at_the_edge_fit(tplan):
    tally = _consistent(tplan, [(0, 0), (0, 1), (0, 2), (0, 3), (1, 3)])
    assert tally.finished.prefix == [4, 0] and tally.finished.extra == {(1, 3)}
    assert tally_problems(tplan, tally) == []


@pytest.mark.parametrize("clock", ["collisions", "time"])
def test_every_curve_and_clock_must_add_up(tplan, clock):
    tally = _consistent(tplan, [(0, 0), (1, 0), (1, 1)])
    cens = tally.cens_n if clock == "collisions" else tally.cens_t
    cens[1, 0] -= 1
    assert tally_problems(tplan, tally) == [
        f"curve 'from hole 2', clock {clock}: 0 escaped + 127 censored + 0 stuck = 127, but 128"
        " particles were run"]
    esc = tally.esc_n if clock == "collisions" else tally.esc_t
    esc[1, 1, 3] = 1  # an escape through the second hole completes it
    stuck = tally.stuck_n if clock == "collisions" else tally.stuck_t
    stuck[0, 2] = 2
    assert tally_problems(tplan, tally) == [
        f"curve 'from hole 1', clock {clock}: 0 escaped + 64 censored + 2 stuck = 66, but 64"
        " particles were run"]


def test_curve_problems_take_stuck_from_the_dict_when_given(tplan):
    tally = _consistent(tplan, [(0, 0)])
    tally.stuck_n[0, 0] = 5  # ignored: the dict is given
    assert curve_problems(tplan, tally, [64, 0], {}) == []
    assert curve_problems(tplan, tally, [64, 0], {(0, "time"): 1}) == [
        (0, "time", "curve 'from hole 1', clock time: 0 escaped + 64 censored + 1 stuck = 65,"
         " but 64 particles were run")]
    assert curve_problems(tplan, tally, [64, 0]) == [
        (0, "collisions", "curve 'from hole 1', clock collisions: 0 escaped + 64 censored + 5"
         " stuck = 69, but 64 particles were run")]


def test_phase_space_has_no_curves_but_its_visits_are_bounded():
    plan = make_plan(parse_scene(PORTRAIT))
    tally = Tally.empty(plan)
    tally.finished.add((0, 0))
    assert curve_problems(plan, tally, [100]) == []  # nothing escapes or is censored
    tally.portrait[1, 2] = 7
    tally.collisions = 7
    assert tally_problems(plan, tally) == []
    tally.collisions = 6
    assert tally_problems(plan, tally) == ["7 portrait visits but only 6 collisions"]


def _row(e, k):
    return [e, k] + [0.0] * 8


def test_sample_rows_must_belong_to_finished_sampled_chunks(tplan):
    tally = _consistent(tplan, [(0, 0), (1, 0)])
    tally.samples = [_row(0, 0)] * 5 + [_row(1, 0)] * 5
    assert tally_problems(tplan, tally) == []
    for e, k in [(0, 1), (2, 0), (-1, 0)]:
        tally.samples = [_row(0, 0), _row(e, k), _row(e, k)]
        assert tally_problems(tplan, tally) == [
            f"sample rows of chunk ({e}, {k}), which is not a finished sampled chunk"]
    tally.samples = [_row(0, 0)] * 6 + [_row(1, 0)] * 7
    assert tally_problems(tplan, tally) == [
        "6 sample rows in chunk (0, 0), at most 5 are drawn"]


def test_rows_of_an_unsampled_chunk_are_refused():
    plan = make_plan(parse_scene(TINY))
    plan.sample_stride = 2  # chunks (0, 1), (0, 3), (1, 1), (1, 3) carry no picks
    tally = _consistent(plan, [(0, 0), (0, 1)])
    tally.samples = [_row(0, 0)]
    assert tally_problems(plan, tally) == []
    tally.samples = [_row(0, 1)]
    assert tally_problems(plan, tally) == [
        "sample rows of chunk (0, 1), which is not a finished sampled chunk"]


def test_velocity_tallies_are_checked_for_shape_and_sums(vplan):
    tally = Tally.empty(vplan)
    tally.moving = None
    assert tally_problems(vplan, tally) == [
        f"moving has shape None, the plan needs {Tally.empty(vplan).moving.shape}"]
    tally = Tally.empty(vplan)
    tally.finished.add((0, 0))  # 64 particles run, none recorded moving or stuck
    assert tally_problems(vplan, tally) != []


def test_a_bin_written_twice_counts_twice(tplan):
    """counts.csv holds one row a bin; a second row of the same bin (an edit) adds to it, so
    that the invariant sees every particle the file claims."""
    text = (COUNTS_HEADER + "from hole 1,collisions,P12,3.0,4\n"
            "from hole 1,collisions,censored,5.0,2\nfrom hole 1,collisions,P12,3.0,1\n"
            "from hole 1,collisions,censored,5.0,3\n")
    counts, _, problems, _ = parse_counts(tplan, text)
    assert problems == []
    assert counts.esc_n[0, 1, 2] == 5 and counts.esc_n.sum() == 5
    assert counts.cens_n[0, 4] == 5 and counts.cens_n.sum() == 5


def test_an_extra_chunk_of_the_first_curve_fits(tplan):
    tally = _consistent(tplan, [(0, 2)])
    assert tally.finished.prefix == [0, 0] and tally.finished.extra == {(0, 2)}
    assert tally_problems(tplan, tally) == []


def test_chunks_outside_the_plan_are_shown_three_at_most(tplan):
    tally = _consistent(tplan, [(0, 0)])
    tally.finished.extra = {(0, 4), (0, 5), (0, 6), (0, 7)}
    assert tally_problems(tplan, tally) == [
        "finished chunks outside the plan: [(0, 4), (0, 5), (0, 6)]"]


def test_velocity_shape_problems_come_with_the_others(vplan):
    tally = Tally.empty(vplan)
    tally.collisions = -2
    tally.stuck_at = None
    assert tally_problems(vplan, tally) == [
        "negative totals: collisions -2, settled 0",
        f"stuck_at has shape None, the plan needs {tally.moving.shape}"]
