"""The audit's recomputed sample (step 5 of ``bouncer verify RUN``) and its re-derived output
files (steps 3 and 4), on the tiny runs of ``test_recheck.py`` (each fault alone, its hash
updated where the deeper check is the one under test)."""

import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from scene_texts import TINY
from test_recheck import (
    edit_rows,
    edit_sample,
    manifest_of,
    problems_of,
    rehash,
    sample_problems,
)

from reports.cli import main
from reports.runs import driver
from reports.runs.recheck import _sample, recheck
from reports.runs.scenes import parse_scene

# ---- the recomputed sample (_sample) --------------------------------------------------------


def test_progress_bar_is_labelled_verify_sample(run, capsys):
    """``bouncer verify``
    without --quiet shows a progress bar on stderr (reports/cli/verify.py: --quiet is "no progress
    bar"); every refresh of it reads "verify sample: ", counts the sampled collisions of the
    manifest (n/n) in collisions per second, and nothing else is written to stderr."""
    n = manifest_of(run)["verification"]["sampled"]
    assert main(["verify", str(run)]) == 0
    captured = capsys.readouterr()
    refreshes = [x.rstrip("\n") for x in captured.err.replace("\n", "\r").split("\r") if x]
    ours = [x for x in refreshes if x.startswith("verify sample: ")]
    replay = [x for x in refreshes if x.startswith("replay from the seed: ")]
    assert ours and replay and len(ours) + len(replay) == len(refreshes)
    assert refreshes.index(ours[-1]) < refreshes.index(replay[0])  # the sample first
    assert ours[0].startswith("verify sample:   0%|") and f" 0/{n} " in ours[0]
    assert ours[-1].startswith("verify sample: 100%|") and f" {n}/{n} " in ours[-1]
    assert ours[-1].endswith("collision/s]") and captured.out.endswith("OK\n")
    assert replay[-1].startswith("replay from the seed: 100%|") and f" {n}/{n} " in replay[-1]


def test_a_sample_with_cr_line_ends_is_still_checked_by_line(run, capsys):
    """A sample.csv with CR line ends (its hash updated) differs from the checkpoint's byte for
    byte (one discrepancy for the line ends); it is read as csv's own files are, and an edited
    row is reported by file and line (exit 1), by the comparison with the checkpoint and by
    verify's recomputation, never a csv traceback."""
    edit_sample(run, {4: {"tau_ref": "1.5"}})
    text = (run / "sample.csv").read_text()
    (run / "sample.csv").write_bytes(text.replace("\n", "\r").encode())
    rehash(run, "sample.csv")
    assert main(["verify", str(run), "--quiet"]) == 1
    out = capsys.readouterr().out.splitlines()
    found = [x for x in out if x.startswith("sample.csv:")]
    assert found[0] == ("sample.csv: its lines end in CR, the checkpoint's in LF (the comparison"
                        " is byte for byte)")
    assert found[1].startswith("sample.csv:4: the checkpoint has ")
    assert found[2].startswith("sample.csv:4: verify gives tau_ref ")
    assert found[2].endswith("; the file 1.5, " + repr(float(text.splitlines()[3].split(",")[10])))
    assert len(found) == 3 and out[-1] == "FAILED: 3 discrepancies"


def test_rows_after_a_refused_row_are_still_recomputed(run):
    """Step 5 covers
    *every* row of sample.csv; a row verify refuses (v = -1, no departure) is reported by line and
    the rows after it are still recomputed: an edited error two rows on is reported too."""
    edit_sample(run, {2: {"v": "-1.0"}, 4: {"error": "0.5"}})
    found = sample_problems(run)
    assert found[0].startswith("sample.csv:2: fastpath.step refuses the row: not a departure")
    assert found[1].startswith("sample.csv:2: verify refuses the row: no departure")
    assert found[2].startswith("sample.csv:4: verify gives tau_ref ")
    assert found[2].endswith(", 0.5") and len(found) == 3


def test_sample_returns_the_overstepped_lines(run):
    """``_sample`` returns (rows, worst
    recomputed error, overstepped *lines*, discrepancies) (its docstring): the line numbers of
    sample.csv (header = 1) whose tau oversteps, not only how many. (Through ``bouncer verify`` only
    their count is shown; the line is in the OVERSTEP message.)"""
    rows = (run / "sample.csv").read_text().splitlines()
    tau = float(rows[2].split(",")[8])
    edit_sample(run, {3: {"tau": repr(tau * (1 + 1e-9))}})
    scene = parse_scene((run / "scene.toml").read_text())
    got_rows, worst, overstepped, out, parsed = _sample(run, scene, False)
    assert [r.line for r in parsed] == list(range(2, len(rows) + 1))
    assert overstepped == [3] and len(got_rows) == len(rows) - 1
    assert worst > 16 and out[-1] == ("sample.csv:3: OVERSTEP: tau exceeds verify's first root"
                                      " by more than 16*kappa*u")


@pytest.fixture(scope="module")
def drag_run(tmp_path_factory):
    """A transport run with drag and restitution 1: not elastic, and not a carried step."""
    out = tmp_path_factory.mktemp("drag") / "run"
    scene = parse_scene(TINY + "[physics]\ndrag = 0.05\n")
    assert scene.physics() == {"drag": 0.05, "drag_law": "linear", "restitution": 1.0}
    assert not scene.carries
    driver.run(scene, out, progress=False)
    return out


@pytest.mark.slow
def test_a_drag_run_with_restitution_1_is_repeated_with_its_drag(drag_run, tmp_path):
    """Step 5 repeats each row with ``fastpath.step(phi, v, eps)`` *of the
    run's physics*; a drag run with r = 1 passes the audit (the drag-free step would give other
    results on every row), and an edited phi1 is still named as fastpath.step's."""
    run_dir = Path(shutil.copytree(drag_run, tmp_path / "run"))
    ok, lines = recheck(run_dir)
    assert ok is True, lines
    phi1 = float((run_dir / "sample.csv").read_text().splitlines()[1].split(",")[6])
    edit_sample(run_dir, {2: {"phi1": repr(phi1 + 1e-6)}})
    found = sample_problems(run_dir)
    assert len(found) == 1 and found[0].startswith("sample.csv:2: fastpath.step gives (")
    assert found[0].endswith("(not reproduced bit for bit)")


# ---- the output files (_outputs) ------------------------------------------------------------


def test_a_curve_with_no_rows_in_counts_is_named_without_a_line(run):
    """Per curve and clock escapes + censored + stuck =
    particles; a curve and clock with no row left in counts.csv (its rows deleted, the hash
    updated) is reported as counts.csv:?, the file named and no line to name."""
    edit_rows(run / "counts.csv", lambda rows: rows.__setitem__(
        slice(None), [r for r in rows if r[:2] != ["from hole 2", "time"]]))
    rehash(run, "counts.csv")
    found = problems_of(recheck(run)[1])
    assert ("counts.csv:?: curve 'from hole 2', clock time: 0 escaped + 0 censored + 0 stuck = 0,"
            " but 200 particles were run") in found
    assert not any(x.startswith(("counts.csv:None", "counts.csv:XX")) for x in found)


def test_stuck_counts_are_summed_exactly(run):
    """Escapes + censored + stuck = particles holds in integers (stuck taken from parse_counts'
    exact dict, not summed from counts.csv's int64 arrays): four forged stuck rows of 2**62 sum to
    2**64, which an int64 sum wraps to 0, and the invariant still names the curve with its true
    total."""
    edit_rows(run / "counts.csv", lambda rows: rows.extend(
        ["from hole 1", "collisions", "stuck", edge, str(2**62)]
        for edge in ("1.0", "2.0", "3.0", "5.0")))
    rehash(run, "counts.csv")
    with np.errstate(over="ignore"):
        found = problems_of(recheck(run)[1])
    assert any(x.startswith("counts.csv:2: curve 'from hole 1', clock collisions: ")
               and x.endswith(f" + {2**64} stuck = {2**64 + 200}, but 200 particles were run")
               for x in found)


def test_inconsistent_counts_give_no_numpy_warning(run):
    """Counts that break the invariant give
    p > 1 and an invalid band when survival.csv is re-derived; that is reported as a discrepancy
    by file and line, not as a numpy RuntimeWarning on stderr."""
    edit_rows(run / "counts.csv", lambda rows: rows[1].__setitem__(4, str(int(rows[1][4]) + 50)))
    rehash(run, "counts.csv")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ok, lines = recheck(run)
    assert not ok and [str(w.message) for w in caught] == []
    assert ("counts.csv:2: curve 'from hole 1', clock collisions: 249 escaped + 1 censored + 0"
            " stuck = 250, but 200 particles were run") in problems_of(lines)
