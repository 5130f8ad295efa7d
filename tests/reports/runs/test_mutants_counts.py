"""Tests that kill mutants of ``reports/runs/counts.py`` (scripts/mutation.sh runs)."""

from reports.runs.counts import Finished


def test_legacy_empty_finished_list_is_one_curve_with_nothing_done():
    """Checkpoints of earlier versions hold the finished chunks as a list of (e, k); an empty
    list means one curve (curves = 1 + max e, with max e = 0 by default) and no chunk done."""
    f = Finished.from_json([])
    assert f.prefix == [0] and f.extra == set() and len(f) == 0


def test_legacy_finished_list_is_compacted():
    f = Finished.from_json([[1, 0], [0, 1], [0, 0]])
    assert f.prefix == [2, 1] and f.extra == set()
    assert f.to_json() == {"prefix": [2, 1], "extra": []}
