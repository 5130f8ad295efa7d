"""Tests that kill mutants of ``reports/runs/counts.py`` (scripts/mutation.sh runs)."""

from types import SimpleNamespace

import numpy as np

from reports.runs.counts import Counts, Finished, Tally


def test_legacy_empty_finished_list_is_one_curve_with_nothing_done():
    """Checkpoints of earlier versions hold the finished chunks as a list of (e, k); an empty
    list means one curve (curves = 1 + max e, with max e = 0 by default) and no chunk done."""
    f = Finished.from_json([])
    assert f.prefix == [0] and f.extra == set() and len(f) == 0


def test_legacy_finished_list_is_compacted():
    f = Finished.from_json([[1, 0], [0, 1], [0, 0]])
    assert f.prefix == [2, 1] and f.extra == set()
    assert f.to_json() == {"prefix": [2, 1], "extra": []}


def _counts(k, holes=2):
    """Counts with every entry k: holes x 3 N-bins, holes x 4 T-bins, a 2 x 2 portrait."""
    return Counts(np.full((holes, 3), k), np.full((holes, 4), k), np.full(3, k), np.full(4, k),
                  np.full((2, 2), k), collisions=k, settled=k)


def test_add_sums_every_histogram_and_total():
    total = _counts(1, holes=3)
    total.add(_counts(2))  # fewer holes than the total: rows 0, 1 only
    assert total.esc_n[:2].tolist() == [[3] * 3] * 2 and total.esc_n[2].tolist() == [1] * 3
    assert total.esc_t[:2].tolist() == [[3] * 4] * 2
    assert total.cens_n.tolist() == [3] * 3 and total.cens_t.tolist() == [3] * 4
    assert total.portrait.tolist() == [[3, 3], [3, 3]]
    assert (total.collisions, total.settled) == (3, 3)
    total.add(_counts(5), portrait=False)
    assert total.portrait.tolist() == [[3, 3], [3, 3]] and total.collisions == 8


def _tally():
    """Two curves, as a run's Tally (leading experiment axis)."""
    return Tally(np.zeros((2, 2, 3), np.int64), np.zeros((2, 2, 4), np.int64),
                 np.zeros((2, 3), np.int64), np.zeros((2, 4), np.int64),
                 np.zeros((2, 2), np.int64), finished=Finished.none(2))


def test_merge_adds_a_chunk_once_and_the_portrait_only_for_phase_space():
    tally = _tally()
    chunk = SimpleNamespace(curve=1, chunk=0, counts=_counts(2), rows=[])
    assert tally.merge(chunk, "escape") is True
    assert tally.merge(chunk, "escape") is False  # already merged: nothing changes
    assert tally.esc_n[1].tolist() == [[2] * 3] * 2 and tally.esc_n[0].sum() == 0
    assert tally.collisions == 2 and tally.portrait.sum() == 0
    tally.merge(SimpleNamespace(curve=1, chunk=1, counts=_counts(2), rows=[]), "phase-space")
    assert tally.portrait.tolist() == [[2, 2], [2, 2]] and tally.collisions == 4
