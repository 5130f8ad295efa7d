"""The report reuses a stored run only when ``bouncer verify`` passes on it with this code."""

from reports.paper.studies.paper_runs import ensure_run
from reports.runs.recheck import recheck


def test_a_run_this_code_does_not_reproduce_is_run_again(tmp_path):
    said = []
    out = ensure_run("paper-phase-space", tmp_path, 40, said.append)
    assert recheck(out)[0]
    assert ensure_run("paper-phase-space", tmp_path, 40, said.append) == out
    assert "reusing" in said[-1]
    sample = out / "sample.csv"
    rows = sample.read_text().splitlines()
    fields = rows[1].split(",")
    fields[-3] = repr(float(fields[-3]) * (1 + 2.0**-52))  # tau one ulp off: another solver
    sample.write_text("\n".join([rows[0], ",".join(fields), *rows[2:]]) + "\n")
    assert not recheck(out)[0]
    before = len(said)
    assert ensure_run("paper-phase-space", tmp_path, 40, said.append) == out
    assert any("running it again" in line for line in said[before:])
    assert recheck(out)[0]
