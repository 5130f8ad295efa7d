"""docs/claims.md states the verdicts of the committed report as they are in its report.json."""

import json
import re
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
PAGE = ROOT / "docs" / "claims.md"
REPORT = ROOT / "docs" / "report" / "report.json"
ROW = re.compile(r"^\| (\S+) \| \*\*(confirmed|refuted|inconclusive)\*\* \|", re.MULTILINE)


def committed_claims():
    return {c["id"]: c for c in json.loads(REPORT.read_text(encoding="utf-8"))["claims"]}


def test_every_verdict_on_the_page_is_the_committed_one():
    claims = committed_claims()
    rows = ROW.findall(PAGE.read_text(encoding="utf-8"))
    assert rows, "no verdict table in docs/claims.md"
    wrong = [(cid, verdict, claims.get(cid, {}).get("verdict")) for cid, verdict in rows
             if claims.get(cid, {}).get("verdict") != verdict]
    assert not wrong, wrong
    paper = {cid for cid, c in claims.items() if c["source"] == "paper"}
    assert paper <= {cid for cid, _ in rows}, sorted(paper - {cid for cid, _ in rows})


def test_the_page_counts_the_committed_verdicts():
    paper = [c for c in committed_claims().values() if c["source"] == "paper"]
    counts = Counter(c["verdict"] for c in paper)
    text = " ".join(PAGE.read_text(encoding="utf-8").split())
    expected = (f"{len(paper)} claims of the paper, {counts['confirmed']} confirmed, "
                f"{counts['refuted']} refuted, {counts['inconclusive']} inconclusive")
    assert expected in text, expected
