"""``bouncer verify`` on a restitution run: the sample is re-derived bit for bit from the
recorded departure and its carried state (``fastpath.carried_step``), and tampering with a
sample value, the carried state, a count or the stuck column fails the audit (exit 1)."""

import csv
import json
import shutil
from pathlib import Path

import pytest

from reports.cli import main
from reports.runs.rundir import CARRIED_COLUMNS, SAMPLE_COLUMNS

# eps = 0.6, r = 0.8: chattering runs (short flights carried from a base, s > 0) that end
# stuck for good, and ordinary flights between them
CHATTER = """
name = "chatter"
kind = "escape"
eps = 0.6
particles = 600
seed = 8
chunk_size = 300
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [0.0, 2.0]
widths = [0.3]
[horizon]
collisions = 5000
time = 1e5
[record]
verify_samples = 120
[physics]
restitution = 0.8
"""


@pytest.fixture(scope="module")
def clean_run(tmp_path_factory):
    base = tmp_path_factory.mktemp("chatter")
    (base / "chatter.toml").write_text(CHATTER)
    assert main(["run", str(base / "chatter.toml"), "--out", str(base / "run"), "--quiet"]) == 0
    return base / "run"


@pytest.fixture
def run_dir(clean_run, tmp_path):
    return Path(shutil.copytree(clean_run, tmp_path / "run"))


def audit(path, capsys):
    code = main(["verify", str(path), "--quiet"])
    return code, capsys.readouterr().out


def rows_of(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def edit_csv(path, edit):
    rows = rows_of(path)
    edit(rows)
    with open(path, "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows)


def chattering_line(rows):
    """Index of a sample row departing inside a run of short flights (s > 0)."""
    s = rows[0].index("s")
    return next(i for i, r in enumerate(rows) if i > 0 and float(r[s]) != 0.0)


def test_restitution_run_passes_the_audit(clean_run, capsys):
    rows = rows_of(clean_run / "sample.csv")
    assert tuple(rows[0]) == SAMPLE_COLUMNS + CARRIED_COLUMNS
    assert len(rows) - 1 >= 100
    chattering_line(rows)  # the sample holds steps that (phi, v) alone do not determine
    code, out = audit(clean_run, capsys)
    assert code == 0 and out.rstrip().endswith("OK"), out
    assert f"{len(rows) - 1} sampled collisions recomputed by verify" in out


def test_edited_fast_result_is_not_reproduced(run_dir, capsys):
    rows = rows_of(run_dir / "sample.csv")
    i, col = chattering_line(rows), rows[0].index("phi1")
    phi1 = float(rows[i][col])
    edit_csv(run_dir / "sample.csv",
             lambda r: r[i].__setitem__(col, repr(float.__add__(phi1, 2.0**-50))))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "sample.csv: SHA-256 differs" in out
    assert f"sample.csv:{i + 1}: fastpath.carried_step gives" in out


@pytest.mark.parametrize(("column", "message"), [("w", "carried w="),
                                                 ("s", "carried base_phase=")])
def test_edited_carried_state_is_refused(run_dir, capsys, column, message):
    rows = rows_of(run_dir / "sample.csv")
    i, col = chattering_line(rows), rows[0].index(column)
    edit_csv(run_dir / "sample.csv",
             lambda r: r[i].__setitem__(col, repr(2.0 * float(r[i][col]))))
    code, out = audit(run_dir, capsys)
    assert code == 1 and f"sample.csv:{i + 1}: fastpath.carried_step refuses the row" in out
    assert message in out


def test_edited_count_fails_the_audit(run_dir, capsys):
    header = rows_of(run_dir / "counts.csv")[0]
    assert header[2] == "outcome" and header[4] == "count", header

    def bump(rows):
        k = next(i for i, r in enumerate(rows)
                 if i > 0 and r[2] not in ("stuck", "censored") and int(r[4]) > 0)
        rows[k][4] = str(int(rows[k][4]) + 1)

    edit_csv(run_dir / "counts.csv", bump)
    code, out = audit(run_dir, capsys)
    assert code == 1 and "counts.csv: SHA-256 differs" in out
    assert "but 600 particles were run" in out


def test_edited_stuck_column_fails_the_audit(run_dir, capsys):
    manifest = json.loads((run_dir / "manifest.json").read_text())
    curve = manifest["curves"]["phi_c=0"]
    assert curve["stuck"] > 0  # eps <= 1, r < 1: some particles stick for good
    curve["stuck"] -= 1
    (run_dir / "manifest.json").write_text(json.dumps(manifest))
    code, out = audit(run_dir, capsys)
    assert code == 1 and "manifest.json: curves.phi_c=0.stuck" in out

    def unstick(rows):
        k = next(i for i, r in enumerate(rows) if i > 0 and r[2] == "stuck" and int(r[4]) > 0)
        rows[k][4] = str(int(rows[k][4]) - 1)

    edit_csv(run_dir / "counts.csv", unstick)
    code, out = audit(run_dir, capsys)
    assert code == 1 and "counts.csv: SHA-256 differs" in out
    assert "but 600 particles were run" in out


@pytest.mark.slow
@pytest.mark.parametrize("law", ["linear", "quadratic"])
def test_drag_and_restitution_run_passes_the_audit(tmp_path, capsys, law):
    """drag with r < 1: the run's samples, chattering ones included, are
    repeated by ``fastpath.carried_step`` with the drag and recomputed by verify."""
    physics = f'restitution = 0.8\ndrag = 0.2\ndrag_law = "{law}"'
    text = CHATTER.replace("restitution = 0.8", physics)
    text = text.replace("particles = 600", "particles = 200").replace("chunk_size = 300",
                                                                      "chunk_size = 100")
    (tmp_path / "chatter.toml").write_text(text)
    assert main(["run", str(tmp_path / "chatter.toml"), "--out", str(tmp_path / "run"),
                 "--quiet"]) == 0
    rows = rows_of(tmp_path / "run" / "sample.csv")
    chattering_line(rows)
    code, out = audit(tmp_path / "run", capsys)
    assert code == 0 and out.rstrip().endswith("OK"), out
