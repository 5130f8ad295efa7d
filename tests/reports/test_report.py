"""`bouncer report` and `bouncer bench` end to end, at smoke-test sizes (no timing asserted)."""

import re
import sys
from pathlib import Path

import pytest

from reports.cli import main


@pytest.mark.slow
def test_quick_report_has_every_section_and_its_figures(tmp_path, capsys):
    out = tmp_path / "report"
    assert main(["report", "--quick", "--out", str(out)]) == 0
    text = (out / "report.md").read_text(encoding="utf-8")
    for heading in ("## Speed: exact map against the Holmes map", "## Stability on hard cases",
                    "### Dissipative hard cases", "## How long this report took",
                    "## The paper's claims: verdicts", "## The paper's figures from trusted runs"):
        assert heading in text
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(images) >= 6
    for image in images:
        assert (out / image).is_file(), image
        assert (out / image).with_suffix(".pdf").is_file() or image.startswith("included-")
    assert "x Holmes" in text


def test_report_rejects_bad_input(tmp_path, capsys):
    assert main(["report", "--particles", "0", "--out", str(tmp_path / "r")]) == 2
    assert main(["report", "--include-run", str(tmp_path), "--out", str(tmp_path / "r")]) == 2
    assert main(["report", "--compare", "no_such_module:f", "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err
    assert err.count("bouncer: error:") == 3 and "Traceback" not in err


@pytest.mark.slow
def test_bench_prints_ratios_to_the_holmes_map(capsys):
    assert main(["bench", "--collisions", "20000", "--repeats", "1", "--particles", "2000",
                 "--no-cold-start"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"\| exact \(auto\) \| [\d.]+ \| [\d.]+ \|", out)
    assert re.search(r"\| Holmes map, bare loop \| [\d.]+ \| 1.00 \|", out)
    assert re.search(r"\| exact, end to end \| [\d.]+ \| [\d.e+]+ \| [\d.e+]+ \| [\d.]+ \|", out)
    assert "headline: the exact escape ensemble end to end takes" in out
    assert "collisions/s" in out and "peak memory" in out
    assert "cold s" not in out
    assert main(["bench", "--repeats", "0"]) == 2


def test_cold_start_runs_each_command_twice_first_with_an_empty_cache_of_its_own(tmp_path):
    """The first run of a command sees an empty NUMBA_CACHE_DIR, the second the cache the first
    filled; the next command starts from an empty one again. A failing command is an error."""
    from reports.precision.bench import cold_start_table, time_cold_start

    log = tmp_path / "log"
    probe = [sys.executable, "-c",
             "import os, pathlib, sys; d = pathlib.Path(os.environ['NUMBA_CACHE_DIR']);"
             " seen = (d / 'kernel').exists(); d.mkdir(parents=True, exist_ok=True);"
             " (d / 'kernel').touch(); open(sys.argv[1], 'a').write(f'{seen} ')", str(log)]
    rows = time_cold_start([("a", probe), ("b", probe)])
    assert log.read_text().split() == ["False", "True", "False", "True"]
    assert [r[0] for r in rows] == ["a", "b"] and all(r[1] > 0 and r[2] > 0 for r in rows)
    assert "| `a` |" in cold_start_table(rows)
    with pytest.raises(RuntimeError, match="exit status 3"):
        time_cold_start([("fails", [sys.executable, "-c", "import sys; sys.exit(3)"])])


def test_the_bench_times_the_quick_start_that_the_readme_shows():
    from reports.precision.bench import QUICK_START

    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    assert f"```python\n{QUICK_START}```" in readme


def test_a_paper_only_rebuild_replaces_its_sections_and_keeps_the_others():
    from reports.report import CLAIMS_HEADING, FIGURES_HEADING, PHYSICS_HEADING, splice

    old = "\n".join(["# bouncer-verify report", "", "Built then.", "",
                     "## The paper's claims: verdicts", "", "old claims", "",
                     "## Speed: exact map against the Holmes map", "", "speed table", "",
                     "## The paper's figures from trusted runs", "", "old figures", "",
                     "### Fig. 2", "old fig 2", "",
                     "## Physics checks against published results", "", "old physics", "",
                     "## How long this report took", "", "| total | 1 |"])
    new = splice(old, {CLAIMS_HEADING: f"{CLAIMS_HEADING}\n\nnew claims\n",
                       FIGURES_HEADING: f"{FIGURES_HEADING}\n\nnew figures\n",
                       PHYSICS_HEADING: f"{PHYSICS_HEADING}\n\nnew physics\n"})
    for gone in ("old claims", "old figures", "old fig 2", "old physics"):
        assert gone not in new
    for kept in ("speed table", "| total | 1 |", "new claims", "new figures", "new physics"):
        assert kept in new
    assert new.index("new claims") < new.index("speed table") < new.index("new figures")


def test_the_rebuild_note_follows_the_build_line_and_is_not_repeated():
    from reports.report import REBUILD_NOTE, with_rebuild_note

    md = "# report\n\nBuilt then.\n\nbody\n"
    once = with_rebuild_note(md, f"{REBUILD_NOTE} first.")
    twice = with_rebuild_note(once, f"{REBUILD_NOTE} second.")
    assert twice.count(REBUILD_NOTE) == 1 and "second." in twice
    assert twice.index("Built then.") < twice.index("second.") < twice.index("body")


def test_report_progress_weighs_the_stages_and_scales_the_time_left_by_the_pace():
    """The overall fraction and the time left follow the stage weights (``STAGE_S``), grow
    within a stage with its elapsed time but stop short of its end, and the time left scales
    with the pace of the finished stages and grows while a stage overruns its weight."""
    from reports.report import STAGE_S, ReportProgress

    labels = ["speed", "physics checks"]
    speed, physics = STAGE_S["speed"], STAGE_S["physics checks"]
    progress = ReportProgress(labels, enabled=False)
    assert progress.fraction_and_left(progress.start) == (0.0, speed + physics)
    progress.stage, progress.stage_start, progress.running = 0, 100.0, True
    fraction, left = progress.fraction_and_left(100.0 + speed / 2)
    assert fraction == pytest.approx(speed / 2 / (speed + physics))
    assert left == pytest.approx(speed / 2 + physics)
    fraction, late = progress.fraction_and_left(100.0 + 10 * speed)  # a stage far behind time
    assert fraction == pytest.approx(0.95 * speed / (speed + physics))
    # its pace, 10 s per 0.95 s of weight, scales what is left; later still, more is left
    assert late == pytest.approx((0.05 * speed + physics) * 10 / 0.95)
    assert progress.fraction_and_left(100.0 + 20 * speed)[1] == pytest.approx(2 * late)
    progress.done_weight, progress.done_seconds = speed, 2 * speed  # it took twice its weight
    progress.stage, progress.stage_start = 1, 500.0
    fraction, left = progress.fraction_and_left(500.0)
    assert fraction == pytest.approx(speed / (speed + physics))
    assert left == pytest.approx(2 * physics)
    assert "stage 2 of 2: physics checks" in progress.line(500.0)


def test_report_progress_counts_a_finished_stage_once():
    """Once a stage has ended (the line drawn right after it, before the next begins) its
    weight counts once: the fraction never passes 1 and is the finished weight's share."""
    from reports.report import STAGE_S, ReportProgress

    labels = ["speed", "physics checks"]
    speed, physics = STAGE_S["speed"], STAGE_S["physics checks"]
    progress = ReportProgress(labels, enabled=False)
    with progress.stage_of("speed"):
        pass
    fraction, _ = progress.fraction_and_left(progress.stage_start + speed)
    assert fraction == pytest.approx(speed / (speed + physics))
    with progress.stage_of("physics checks"):
        pass
    assert progress.fraction_and_left(progress.stage_start + 10 * physics)[0] == pytest.approx(1)


def test_included_run_says_threads_in_words():
    """A run made with numba's default threads (provenance ``threads``: null) is described as
    such, never as "None threads"."""
    from reports.report import _threads_text

    assert _threads_text(None) == "numba's default threads"
    assert _threads_text(2) == "2 threads"
