"""`bouncer report` and `bouncer bench` end to end, at smoke-test sizes (no timing asserted)."""

import re

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
    assert main(["bench", "--collisions", "20000", "--repeats", "1", "--particles", "2000"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"\| exact \(auto\) \| [\d.]+ \| [\d.]+ \|", out)
    assert "collisions/s" in out and "peak memory" in out
    assert main(["bench", "--repeats", "0"]) == 2


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
