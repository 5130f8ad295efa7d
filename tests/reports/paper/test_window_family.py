"""The windows a claim's words allow: inside a bounded regime, later starts in a tail."""

import numpy as np

from reports.paper.claims.window_family import (
    LATE_MEMBERS,
    inside_windows,
    late_windows,
    limit_windows,
)
from reports.stats.histogram import Curve, bin_means, survival_boundaries

EDGES = np.concatenate([[0.0], np.geomspace(0.1, 1e7, 161)])  # 20 bins per decade


def curve(escapes_per_bin=1000):
    x = survival_boundaries(EDGES, "time")
    esc = np.full(len(EDGES), escapes_per_bin, np.int64)
    esc[-1] = 0
    zero = np.zeros(len(EDGES), np.int64)
    return Curve("synthetic", "e", "c", "time", x, esc, zero, zero, bin_means(EDGES, "time"),
                 int(esc.sum()))


def at(c, value):
    return int(np.argmin(np.abs(np.log(c.x[1:-1] / value)))) + 1


def test_windows_inside_a_regime_never_leave_it():
    c = curve()
    a, b = at(c, 100.0), at(c, 1e4)
    ws = inside_windows(c, a, b, 1000)
    assert ws[0] == (a, b) and len(ws) == 4
    assert all(a <= w0 < w1 <= b for w0, w1 in ws)
    assert {round(c.x[w0]) for w0, _ in ws} == {100, 178}        # a quarter decade later
    assert {round(c.x[w1]) for _, w1 in ws} == {10000, 5623}     # a quarter decade earlier


def test_tail_windows_start_only_later_and_end_where_the_data_do():
    c = curve()
    a, b = at(c, 100.0), at(c, 1e4)
    ws = late_windows(c, a, b, 1000)
    starts = [c.x[w0] for w0, _ in ws]
    assert starts[0] == c.x[a] and all(w1 == b for _, w1 in ws)
    assert np.allclose(np.diff(np.log10(starts)), 0.25)
    assert min(starts) >= c.x[a]


def test_a_limit_reads_the_latest_windows_with_enough_escapes():
    c = curve(10)
    a, b = at(c, 100.0), at(c, 1e4)
    every = late_windows(c, a, b, 100)     # a window needs 10 bins of 10 escapes
    latest = limit_windows(c, a, b, 100)
    assert latest == every[-LATE_MEMBERS:] and len(every) > LATE_MEMBERS
    assert all(c.escapes[w0:w1].sum() >= 100 for w0, w1 in latest)
    assert late_windows(c, a, b, 10**6) == []
