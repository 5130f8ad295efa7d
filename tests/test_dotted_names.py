"""Every dotted name of this project written in the docs and in the sources' prose resolves.

A *dotted name* is a match of ``DOTTED``: one of the three packages, ``fastpath``, ``verify`` or
``reports``, followed by one or more ``.identifier`` parts (``fastpath.step``,
``reports.runs.scenes.KINDS``, ``fastpath.FlightStatus.CONVERGED``), not preceded by a letter,
digit, ``_``, ``.``, ``/`` or ``-`` (so ``docs/fastpath.md`` and ``rd.verify.x`` are not names)
and not ending in a file suffix (``fastpath.md`` is a page). It is looked for

* in README.md and docs/*.md: inside code spans (single or double backticks) and fenced blocks;
* in CHANGELOG.md, section [Unreleased] only (the released sections are a record of their time):
  likewise, except that a name in a sentence that tells of its removal or renaming
  (``HISTORY``: "renamed", "removed", "formerly", ...) is history and need not resolve;
* in the Python sources of fastpath/, verify/ and reports/: anywhere in a docstring (a string
  standing alone as a statement: module, class, function and attribute docstrings) or a comment,
  backticks or not.

A name *resolves* when its longest importable prefix is a module and every further part is an
attribute (``getattr``) of what came before. A part after a class resolves through the class:
an attribute, a method, an enum member, a dataclass or NamedTuple field, or an annotated field.

Every unresolved name is printed with its ``file:line`` and the part that failed.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import io
import re
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("fastpath", "verify", "reports")
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
CHANGELOG = ROOT / "CHANGELOG.md"

DOTTED = re.compile(r"(?<![\w./-])(?:fastpath|verify|reports)(?:\.[A-Za-z_]\w*)+")
FILE_SUFFIXES = {"py", "md", "json", "jsonl", "txt", "toml", "csv", "png", "pdf", "svg", "npz",
                 "npy", "log", "yaml", "yml", "html", "gz"}
CODE_SPAN = re.compile(r"(`+)(.+?)(?<!`)\1(?!`)", re.DOTALL)
FENCE = re.compile(r"^\s*(```|~~~)")
HISTORY = re.compile(r"(?i)\b(renamed|removed|formerly|retired|dropped|no longer|replaces|"
                     r"replaced|used to be|was called)\b")
SENTENCE_END = re.compile(r"[.;:!?](?=\s)|\n\s*\n|\n\s*[-*]\s")


def dotted_names(text: str):
    """``(offset, name)`` of every dotted name in ``text``."""
    for match in DOTTED.finditer(text):
        if match.group().rsplit(".", 1)[1] not in FILE_SUFFIXES:
            yield match.start(), match.group()


def _line_of(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def markdown_names(text: str, first_line: int = 1):
    """``(line, name, sentence)`` of the dotted names in the code of a Markdown text."""
    lines = text.split("\n")
    prose, fenced, in_fence = [], [], False
    for number, line in enumerate(lines):
        if FENCE.match(line):
            in_fence = not in_fence
            prose.append("")
            continue
        prose.append("" if in_fence else line)
        if in_fence:
            fenced.extend((number, offset, name) for offset, name in dotted_names(line))
    for number, _, name in fenced:
        yield first_line + number, name, lines[number]
    prose_text = "\n".join(prose)
    for span in CODE_SPAN.finditer(prose_text):
        for offset, name in dotted_names(span.group(2)):
            at = span.start(2) + offset
            yield (first_line - 1 + _line_of(prose_text, at), name,
                   _sentence_around(prose_text, at))


def _sentence_around(text: str, offset: int) -> str:
    starts = [m.end() for m in SENTENCE_END.finditer(text, 0, offset)]
    start = starts[-1] if starts else 0
    end = SENTENCE_END.search(text, offset)
    return text[start:end.start() if end else len(text)]


def unreleased_section() -> tuple[str, int]:
    """The text of CHANGELOG.md's [Unreleased] section and the line it starts on."""
    lines = CHANGELOG.read_text(encoding="utf-8").split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("## [Unreleased]")) + 1
    end = next((i for i in range(start, len(lines)) if lines[i].startswith("## ")), len(lines))
    return "\n".join(lines[start:end]), start + 1


def source_prose(path: Path):
    """``(line, text)`` of every docstring and comment of a Python file."""
    source = path.read_text(encoding="utf-8")
    for node in ast.walk(ast.parse(source)):
        if (isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
                and isinstance(node.value.value, str)):
            yield node.lineno, node.value.value
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type == tokenize.COMMENT:
            yield token.start[0], token.string


def source_names(path: Path):
    """``(line, name)`` of the dotted names in a Python file's docstrings and comments.

    A docstring's line is where its statement starts; the name's own line is counted from there
    (exact unless the string holds escaped newlines).
    """
    for line, text in source_prose(path):
        for offset, name in dotted_names(text):
            yield line + text.count("\n", 0, offset), name


def source_files():
    for package in PACKAGES:
        yield from sorted((ROOT / package).rglob("*.py"))


def _class_has(cls: type, name: str) -> bool:
    if hasattr(cls, name):
        return True
    if dataclasses.is_dataclass(cls) and name in {f.name for f in dataclasses.fields(cls)}:
        return True
    return any(name in getattr(base, "__annotations__", {}) for base in cls.__mro__)


def resolves(name: str) -> str | None:
    """None when ``name`` resolves, else why not."""
    parts = name.split(".")
    for cut in range(len(parts), 0, -1):
        module_name = ".".join(parts[:cut])
        try:
            target = importlib.import_module(module_name)
        except ModuleNotFoundError as error:
            if error.name is not None and not module_name.startswith(error.name):
                return f"importing {module_name} fails: {error}"
            continue
        break
    for depth, part in enumerate(parts[cut:], start=cut):
        if isinstance(target, type) and _class_has(target, part):
            target = getattr(target, part, None)
            if target is None:  # a field without a class-level value: nothing further to follow
                return None if depth == len(parts) - 1 else f"{part} is a field, not a namespace"
            continue
        try:
            target = getattr(target, part)
        except AttributeError:
            return f"{'.'.join(parts[:depth])} has no attribute {part}"
    return None


def all_names():
    """``(where, name, sentence)`` for every dotted name this test checks."""
    for page in PAGES:
        for line, name, sentence in markdown_names(page.read_text(encoding="utf-8")):
            yield f"{page.relative_to(ROOT)}:{line}", name, sentence
    text, first_line = unreleased_section()
    for line, name, sentence in markdown_names(text, first_line):
        yield f"CHANGELOG.md:{line}", name, sentence
    for path in source_files():
        for line, name in source_names(path):
            yield f"{path.relative_to(ROOT)}:{line}", name, ""


def unresolved_names() -> list[tuple[str, str, str]]:
    """``(where, name, why)`` of the names that do not resolve and are not history."""
    found, cache = [], {}
    for where, name, sentence in all_names():
        if name not in cache:
            cache[name] = resolves(name)
        if cache[name] is None:
            continue
        if where.startswith("CHANGELOG.md:") and HISTORY.search(sentence):
            continue
        found.append((where, name, cache[name]))
    return found


def test_dotted_names_in_docs_docstrings_and_comments_resolve():
    broken = [f"{where}: {name} ({why})" for where, name, why in unresolved_names()]
    print("\n".join(broken))
    assert not broken, "dotted names that do not resolve:\n" + "\n".join(broken)


def test_the_scanner_finds_names_in_code_spans_fences_and_docstrings():
    page = "A `fastpath.step` and ``verify.flight_time(phi, v)``; docs/fastpath.md is a page.\n" \
           "```python\nimport reports.runs.scenes\n```\nplain fastpath.orbit is prose\n"
    assert [(line, name) for line, name, _ in markdown_names(page)] == [
        (3, "reports.runs.scenes"), (1, "fastpath.step"), (1, "verify.flight_time")]
    assert [name for _, name in dotted_names("see docs/verify.md, fastpath.md, x.fastpath.y")] == []


def test_resolution_goes_through_modules_classes_and_fields():
    assert resolves("fastpath.step") is None
    assert resolves("fastpath.dynamics.kernels") is None
    assert resolves("fastpath.FlightStatus.CONVERGED") is None
    assert resolves("fastpath.physics.Dissipative.restitution") is None
    assert resolves("fastpath.no_such_name") is not None
    assert resolves("verify.flight_time.no_such_part") is not None
    assert resolves("reports.runs.no_such_module.x") is not None


def test_a_changelog_sentence_that_tells_of_a_rename_is_history():
    text = "- `fastpath.advance` was renamed `fastpath.step`.\n- `fastpath.gone` keeps going.\n"
    sentences = {name: sentence for _, name, sentence in markdown_names(text)}
    assert HISTORY.search(sentences["fastpath.advance"])
    assert not HISTORY.search(sentences["fastpath.gone"])
