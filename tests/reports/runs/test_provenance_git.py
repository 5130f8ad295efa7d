"""provenance.json's git record: what makes a tree dirty (the run's own directory does not), the
changed paths it names, the warning and ``--require-clean``'s refusal."""

import subprocess
from pathlib import Path

import pytest
from scene_texts import TINY

from reports.cli import main
from reports.runs import driver, provenance
from reports.runs.manifest import load_provenance
from reports.runs.scenes import parse_scene

COMMIT = "0123456789abcdef0123456789abcdef01234567"


def fake_git(monkeypatch, root, status):
    """``provenance.git`` reads a tree at ``root`` whose ``git status -z`` is ``status``."""
    answers = {"rev-parse HEAD": COMMIT + "\n", "rev-parse --show-toplevel": f"{root}\n"}

    def answer(cwd, *args):
        return answers.get(" ".join(args), status)

    monkeypatch.setattr(provenance, "_git", answer)


def test_a_clean_tree_records_its_commit_and_nothing_else(monkeypatch, tmp_path):
    fake_git(monkeypatch, tmp_path, "")
    assert provenance.git() == {"commit": COMMIT, "dirty": False}
    assert provenance.dirty_text(provenance.git()) is None


def test_changes_make_the_tree_dirty_and_are_named(monkeypatch, tmp_path):
    fake_git(monkeypatch, tmp_path,
             " M fastpath/kernels/escape.py\0?? notes.txt\0R  new.py\0old.py\0")
    record = provenance.git()
    assert record == {"commit": COMMIT, "dirty": True,
                      "changed": ["fastpath/kernels/escape.py", "new.py", "notes.txt", "old.py"]}
    text = provenance.dirty_text(record)
    assert text.startswith(f"the git tree at {COMMIT[:12]} has uncommitted changes (first:"
                           " fastpath/kernels/escape.py, new.py, notes.txt)")
    assert '"dirty": true' in text


def test_the_runs_own_directory_does_not_make_the_tree_dirty(monkeypatch, tmp_path):
    """A run written (or resumed) inside the work tree: its own files are not the code."""
    fake_git(monkeypatch, tmp_path, "?? docs/runs/big/manifest.json\0 M docs/runs/big/counts.csv\0")
    assert provenance.git(exclude=tmp_path / "docs" / "runs" / "big")["dirty"] is False
    other = provenance.git(exclude=tmp_path / "docs" / "runs" / "other")
    assert other["dirty"] is True and len(other["changed"]) == 2


def test_at_most_twenty_changed_paths_are_listed(monkeypatch, tmp_path):
    fake_git(monkeypatch, tmp_path, "".join(f"?? f{k:02d}\0" for k in range(30)))
    assert provenance.git()["changed"] == [f"f{k:02d}" for k in range(20)]


def test_outside_a_git_tree_there_is_no_record(monkeypatch):
    def fail(cwd, *args):
        raise subprocess.CalledProcessError(128, ["git", *args])

    monkeypatch.setattr(provenance, "_git", fail)
    assert provenance.git() is None
    assert "not in a git work tree" in provenance.dirty_text(None)


def test_a_dirty_tree_is_said_at_a_terminal_and_recorded(monkeypatch, tmp_path, capsys):
    fake_git(monkeypatch, tmp_path, " M reports/runs/plan.py\0")
    monkeypatch.setattr(driver, "_interactive", lambda: True)  # stderr a terminal
    driver.run(parse_scene(TINY), tmp_path / "r", progress=True)
    err = capsys.readouterr().err
    assert ("bouncer run: warning: the git tree at 0123456789ab has uncommitted changes (first:"
            " reports/runs/plan.py)") in err
    assert load_provenance(tmp_path / "r")["git"] == {
        "commit": COMMIT, "dirty": True, "changed": ["reports/runs/plan.py"]}
    driver.run(parse_scene(TINY), tmp_path / "q", progress=False)
    assert "warning" not in capsys.readouterr().err
    monkeypatch.setattr(driver, "_interactive", lambda: False)  # a log, a pipe, a test
    driver.run(parse_scene(TINY), tmp_path / "s", progress=True)
    assert "warning" not in capsys.readouterr().err


def test_require_clean_refuses_a_dirty_tree_before_writing_anything(monkeypatch, tmp_path,
                                                                    capsys):
    fake_git(monkeypatch, tmp_path, " M reports/runs/plan.py\0")
    (tmp_path / "tiny.toml").write_text(TINY)
    out = tmp_path / "new" / "run"
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(out), "--quiet",
                 "--require-clean"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bouncer: error: --require-clean: the git tree at 0123456789ab")
    assert len(err.splitlines()) == 1 and not (tmp_path / "new").exists()
    fake_git(monkeypatch, tmp_path, "")
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(out), "--quiet",
                 "--require-clean"]) == 0
    assert load_provenance(out)["git"] == {"commit": COMMIT, "dirty": False}
    assert "provenance:" not in capsys.readouterr().out


def test_the_summary_of_a_dirty_run_says_so(monkeypatch, tmp_path, capsys):
    fake_git(monkeypatch, tmp_path, "?? scratch.py\0")
    (tmp_path / "tiny.toml").write_text(TINY)
    assert main(["run", str(tmp_path / "tiny.toml"), "--out", str(tmp_path / "r"),
                 "--quiet"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert any(x.startswith("provenance: the git tree at 0123456789ab has uncommitted changes"
                            " (first: scratch.py)") for x in out)


def test_this_repository_is_read_when_there_is_one():
    record = provenance.git()
    root = Path(provenance.__file__).resolve().parents[2]
    if not (root / ".git").exists():
        pytest.skip("not a git checkout")
    assert record is not None and len(record["commit"]) == 40
