"""The bookkeeping of a run (``reports.runs.counts``): ``Finished`` (which chunks are done, in
its current and its former list form), ``Counts`` (zeros of the plan's shape, sums), and the
checkpoint ``Tally`` (every field saved and loaded, unreadable or edited files refused)."""

import io
import zipfile
from types import SimpleNamespace

import numpy as np
import pytest
from scene_texts import PORTRAIT, STICK_200, TINY_VELOCITY

from reports.runs.counts import CheckpointError, Counts, Finished, Tally
from reports.runs.plan import make_plan
from reports.runs.scenes import parse_scene


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


def _saved_tally():
    """One curve with every bookkeeping field set, to save and load."""
    return Tally(np.zeros((1, 1, 3), np.int64), np.zeros((1, 1, 4), np.int64),
                 np.zeros((1, 3), np.int64), np.zeros((1, 4), np.int64),
                 np.zeros((0, 0), np.int64), collisions=5, settled=1,
                 finished=Finished([1]), samples=[[0, 0, 2, 1.0], [0, 0, 1, 2.0]],
                 elapsed=3.5, started="2026-11-23T16:00:00Z")


def test_load_keeps_every_bookkeeping_field(tmp_path):
    t = _saved_tally()
    t.samples.sort()
    t.save(tmp_path / "c.npz")
    back = Tally.load(tmp_path / "c.npz")
    assert (back.collisions, back.settled, back.elapsed, back.started) == (
        5, 1, 3.5, "2026-11-23T16:00:00Z")
    assert back.samples == [[0, 0, 1, 2.0], [0, 0, 2, 1.0]] and back.finished == Finished([1])


def test_load_messages(tmp_path):
    path = tmp_path / "c.npz"
    path.write_bytes(b"not a zip file")
    with pytest.raises(CheckpointError, match=r"is unreadable \(ValueError: "):
        Tally.load(path)
    t = _saved_tally()
    t.save(path)
    with zipfile.ZipFile(path) as z:
        members = {n: z.read(n) for n in z.namelist()}
    with zipfile.ZipFile(path, "w") as z:  # a count edited, the digest kept
        for name, data in members.items():
            if name == "esc_n.npy":
                buf = io.BytesIO()
                np.save(buf, np.ones((1, 1, 3), np.int64))
                data = buf.getvalue()
            z.writestr(name, data)
    with pytest.raises(CheckpointError,
                       match=r"fails its content hash \(edited or corrupted\)$"):
        Tally.load(path)


VELOCITY = TINY_VELOCITY.replace("verify_samples = 6\n", "")


def _int_zeros(a, shape):
    assert a.dtype == np.int64 and a.shape == shape and not a.any()


def test_zeros_are_integer_counts_of_the_plans_shape():
    """Counts are int64 (the checkpoint and counts.csv hold integers); the portrait is drawn
    only by phase-space scenes, the velocity arrays only exist for velocity scenes."""
    plan = make_plan(parse_scene(STICK_200))
    nb, tb = len(plan.n_edges), len(plan.t_edges)
    for lead in ((), (3,)):
        c = Counts.zeros(plan, 2, experiments=lead[0] if lead else None)
        _int_zeros(c.esc_n, (*lead, 2, nb))
        _int_zeros(c.esc_t, (*lead, 2, tb))
        _int_zeros(c.cens_n, (*lead, nb))
        _int_zeros(c.cens_t, (*lead, tb))
        _int_zeros(c.stuck_n, (*lead, nb))
        _int_zeros(c.stuck_t, (*lead, tb))
        _int_zeros(c.portrait, (0, 0))
        assert c.moving is None and c.sum_v is None
    plan = make_plan(parse_scene(PORTRAIT))
    _int_zeros(Counts.zeros(plan, 1).portrait, (4, 3))
    plan = make_plan(parse_scene(VELOCITY))
    for lead in ((), (2,)):
        c = Counts.zeros(plan, 1, experiments=lead[0] if lead else None)
        grid = (*lead, len(plan.n_grid))
        _int_zeros(c.moving, grid)
        _int_zeros(c.stuck_at, grid)
        _int_zeros(c.portrait, (0, 0))
        for a in (c.sum_v, c.sum_v2):
            assert a.shape == grid and all(x == 0 and type(x).__name__ == "Fraction"
                                           for x in a.flat)
