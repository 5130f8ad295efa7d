"""The README's "Results" and its summary of the committed report quote the report as it is.

The figures a user reads first (the claim counts, the speed ratios) are copied by hand from
docs/report/ when the report is rebuilt; these tests fail when a rebuilt report and the README
say different things.
"""

import json
import re
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
REPORT_MD = (ROOT / "docs" / "report" / "report.md").read_text(encoding="utf-8")
CLAIMS = json.loads((ROOT / "docs" / "report" / "report.json").read_text("utf-8"))["claims"]


def _paper_counts():
    counts = Counter(c["verdict"] for c in CLAIMS if c["source"] == "paper")
    return sum(counts.values()), counts["confirmed"], counts["refuted"], counts["inconclusive"]


def _words(text):
    return " ".join(text.split())  # the README wraps its lines


def test_readme_claim_counts_are_the_committed_reports():
    total, confirmed, refuted, inconclusive = _paper_counts()
    text = _words(README)
    summary = re.findall(r"of its (\d+) claims of the paper, (\d+) are confirmed, (\d+) refuted"
                         r" and (\d+) inconclusive", text)
    results = re.findall(r"Of (\d+) checkable claims, (\d+) are confirmed, (\d+) refuted and"
                         r" (\d+) inconclusive", text)
    assert summary and results, "the README no longer states the claim counts where it did"
    expected = (str(total), str(confirmed), str(refuted), str(inconclusive))
    assert summary == [expected] and results == [expected]


def test_readme_speed_ratios_are_the_committed_reports():
    headline = re.search(r"end to end \(verification sample, histograms, checkpoints\),"
                         r" \*\*([\d.]+) x\*\* kernel against loop", _words(REPORT_MD))
    end_to_end = re.search(r"takes \*\*([\d.]+) x\*\* the time of the bare Holmes-map loop",
                           _words(REPORT_MD))
    assert headline and end_to_end, "the report's speed headline changed its wording"
    text = _words(README)
    quoted = re.search(r"takes ([\d.]+) x the time of a bare Holmes-map ensemble on the same"
                       r" starts, end to end with verification, and ([\d.]+) x kernel against"
                       r" kernel", text)
    assert quoted, "the README no longer states the speed ratios where it did"
    assert quoted.groups() == (end_to_end.group(1), headline.group(1))
