"""verify's public face: the names it exports, its version, and the code of docs/verify.md."""

from __future__ import annotations

import re
from pathlib import Path

import verify

DOC = Path(__file__).resolve().parents[2] / "docs" / "verify.md"


def test_public_names_and_version():
    assert "load_callable" not in verify.__all__  # it lives in verify.check
    assert callable(verify.check.load_callable)
    assert isinstance(verify.__version__, str) and verify.__version__
    for name in verify.__all__:
        assert hasattr(verify, name), name


def test_the_python_blocks_of_the_verify_page_run():
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)
    assert blocks
    for i, block in enumerate(blocks):
        exec(compile(block, f"{DOC.name}[python block {i}]", "exec"), {})
