"""``bouncer verify`` on output files that the csv module cannot read: a bare CR inside a field,
a field over csv's 131072-character limit, a count of 2**63 or more. The audit fails with a line
naming the file (exit 1: bad input gets a one-line error, never a traceback such as
``_csv.Error`` or ``OverflowError``)."""

import shutil
from pathlib import Path

import pytest
from scene_texts import SMALL_VELOCITY, TINY

from reports.cli import main
from reports.runs import driver
from reports.runs.recheck import recheck
from reports.runs.scenes import parse_scene


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("broken-csv")
    driver.run(parse_scene(TINY), base / "tiny", progress=False)
    driver.run(parse_scene(SMALL_VELOCITY), base / "velocity", progress=False)
    return base


def _bare_cr(line):
    return line.replace(",", "\r,", 1)


def _huge_field(line):
    return '"' + "1" * 200_000 + '"' + line[line.index(","):]


@pytest.mark.slow
@pytest.mark.parametrize("source, name", [("tiny", "counts.csv"), ("tiny", "survival.csv"),
                                          ("tiny", "sample.csv"),
                                          ("velocity", "velocity.csv")])
@pytest.mark.parametrize("edit", [_bare_cr, _huge_field])
def test_an_unreadable_csv_fails_the_audit_naming_the_file(runs, tmp_path, capsys, source,
                                                           name, edit):
    run = Path(shutil.copytree(runs / source, tmp_path / "run"))
    lines = (run / name).read_text().split("\n")
    lines[2] = edit(lines[2])
    (run / name).write_text("\n".join(lines))
    ok, report = recheck(run)
    assert not ok and any(line.startswith(name) or f" {name}" in line for line in report)
    assert main(["verify", str(run), "--quiet"]) == 1
    assert name in capsys.readouterr().out


def test_a_count_beyond_int64_is_not_a_row_of_the_run(runs, tmp_path):
    run = Path(shutil.copytree(runs / "tiny", tmp_path / "run"))
    lines = (run / "counts.csv").read_text().split("\n")
    fields = lines[1].split(",")
    lines[1] = ",".join(fields[:-1] + [str(2**63)])
    (run / "counts.csv").write_text("\n".join(lines))
    ok, report = recheck(run)
    assert not ok and any(line.startswith("counts.csv:2: not a row of this run") for line in report)
