"""The code blocks of docs/fastpath.md run as printed."""

import re
from pathlib import Path

PAGE = Path(__file__).resolve().parents[2] / "docs" / "fastpath.md"


def test_every_python_block_of_the_fastpath_page_runs(capsys):
    blocks = re.findall(r"```python\n(.*?)```", PAGE.read_text(), re.S)
    assert len(blocks) >= 2
    for i, block in enumerate(blocks):
        exec(compile(block, f"{PAGE.name}[block {i}]", "exec"), {})
    assert capsys.readouterr().out.strip().endswith("1000")
