"""The repository's text talks about the code and the paper, not about how it was written.

Every tracked text file (code, docs, data, configuration) is read line by line. Forbidden:

* process talk: a numbered work session or issue, "previous/earlier/this/last release";
* "seed" for the paper (Dettmann & Leonel, "Asymmetric transport in the bouncer model"): the
  word means a random seed only, so "the seed of the run" is fine and "the seed's Fig. 2" is not;
* references to files outside the repository (``../shared``, the design notes ``DESIGN.md``:
  the project's own pages are docs/design.md and docs/model.md).

CHANGELOG.md (a record of changes by nature) and docs/report/ (generated output) are not read.
This file is not read either: its examples below must contain the forbidden phrases.
"""

import os
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SUFFIXES = {".py", ".md", ".toml", ".sh", ".txt", ".cfg", ".ipynb"}
EXCLUDED_FILES = {"CHANGELOG.md", "tests/test_repository_text.py"}
EXCLUDED_DIRS = ("docs/report/",)
# directories the fallback walk never enters (not part of the repository's text)
UNTRACKED_DIRS = {".git", ".venv", "venv", "__pycache__", ".hypothesis", ".pytest_cache",
                  ".ruff_cache", "build", "dist"}

# \s+ between words: a phrase broken across two lines is found too
PROCESS = re.compile(r"(?i)\b(session|issue)s?\s+[0-9]")
RELEASE = re.compile(r"(?i)\b(previous|earlier|this|last)\s+release\b")
OUTSIDE = re.compile(r"\.\./shared|DESIGN\.md|\bDESIGN\s+(sections?|facts?)\b")
_PAPER_WORD = (r"(paper|fig(ure)?s?\b|fig\.|sections?\b|sec\.|eq(uation)?s?\b|eq\.|tables?\b"
               r"|text\b|authors?\b|abstract\b|escape\b|lower-bound\b|steps?\b|own\b|claims?\b"
               r"|words\b|units\b|notation\b|conclusions?\b|(start\s+)?box\b)")
SEED_AS_PAPER = re.compile(
    rf"(?i)\bseed('s)?\s+{_PAPER_WORD}"
    r"|\bas\s+(stated\s+|written\s+)?in\s+the\s+seed\b"
    r"|\bthe\s+seed\s+(says|states|writes|shows|reports|claims|calls|finds|proposes)\b"
    r"|\b(claims?|words|text|authors?|fig(ure)?s?|eq(uation)?s?|sections?|sec|tables?)\.?"
    r"(\s+\(?[0-9][0-9a-z().-]*)?\s+(of|in)\s+the\s+seed\b")

RULES = {
    "a numbered session or issue": PROCESS,
    "a release named by its age": RELEASE,
    "a file outside the repository": OUTSIDE,
    "'seed' used for the paper": SEED_AS_PAPER,
}


def _excluded(path: str) -> bool:
    return path in EXCLUDED_FILES or path.startswith(EXCLUDED_DIRS)


def _walked_files():
    """Text files under ROOT when git cannot list them (an unpacked source archive)."""
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in UNTRACKED_DIRS and not d.endswith(".egg-info")]
        for name in files:
            yield Path(folder, name).relative_to(ROOT).as_posix()


def repository_files():
    """Relative paths of the text files to read: ``git ls-files``, else a walk of the tree."""
    try:
        listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True,
                                check=True, timeout=60).stdout.decode().split("\0")
    except (OSError, subprocess.SubprocessError):
        listed = list(_walked_files())
    return sorted(p for p in listed if p and Path(p).suffix in SUFFIXES and not _excluded(p)
                  and (ROOT / p).is_file())


def hits(pattern, paths):
    """``file:line: text`` for every match of ``pattern`` in ``paths`` (line of its start)."""
    found = []
    for path in paths:
        text = (ROOT / path).read_text(encoding="utf-8", errors="replace")
        lines = text.splitlines()
        for match in pattern.finditer(text):
            number = text.count("\n", 0, match.start()) + 1
            found.append(f"{path}:{number}: {lines[number - 1].strip()[:160]}")
    return found


@pytest.fixture(scope="module")
def files():
    return repository_files()


def test_the_file_list_covers_code_docs_and_tests(files):
    assert {"pyproject.toml", "fastpath/__init__.py", "verify/__init__.py", "reports/__init__.py",
            "docs/model.md", "tests/conftest.py"} <= set(files)
    assert not any(_excluded(p) for p in files)


@pytest.mark.parametrize("rule", RULES)
def test_no_line_breaks_the_rule(rule, files):
    found = hits(RULES[rule], files)
    assert not found, f"{len(found)} line(s) with {rule}:\n" + "\n".join(found)


@pytest.mark.parametrize("line", [
    # numbered by concatenation, so that a plain grep of the repository for process talk finds
    # none in this file either
    "Fermi acceleration as in session " + "12 of the work",
    "see issue " + "4", "(issues " + "3 and 5)", "fixed in Session " + "6",
    "as of session\n    " + "12",
    "unlike the previous release", "an earlier release made it", "new in this release",
])
def test_process_talk_is_caught(line):
    assert PROCESS.search(line) or RELEASE.search(line)


@pytest.mark.parametrize("line", [
    "the manifest's session fields differ", "the issue is the cancellation at small t",
    "release the lock when the process dies", "a session of 3 workers",
])
def test_technical_words_pass(line):
    assert not (PROCESS.search(line) or RELEASE.search(line))


@pytest.mark.parametrize("line", [
    "The seed's Fig. 2 shows the survival", "as in the seed paper", "the seed's lower-bound steps",
    "a quarter from the seed's box eps = 0.6", "the seed's Section 3", "the seed says 'mostly'",
    "as in the seed", "Eq. (3) of the seed", "the seed's escape scene", "the seed figure",
    "quoted from the seed's text", "every claim of the seed", "escape survival, seed Fig. 2",
    "use the seed's\n    lower-bound steps", "by the seed's steps", "one module per seed figure",
])
def test_seed_for_the_paper_is_caught(line):
    assert SEED_AS_PAPER.search(line)


@pytest.mark.parametrize("line", [
    "the seed of the run", "replayed from the start drawn from the seed",
    "every row is a pick drawn from the manifest's seed", "the same seed draws the same inputs",
    "random seed (default: the scene's)", "an edited seed fails the first row",
    "the seed's spawn key (e, k)", "a change in the seed changes every start",
    "the paper's Fig. 2 with seed 7", "hypothesis seed: the same seed draws the same inputs",
    "the seed alone decides the picks", "--seed S overrides the scene's seed",
    "The seed's check in bouncer verify", "the value of the seed", "the seed\n    of the run",
    "an edited seed results in another sample",
])
def test_random_seeds_pass(line):
    assert not SEED_AS_PAPER.search(line)


@pytest.mark.parametrize("line", ["python ../shared/tools/import_cycles.py",
                                  "(DESIGN.md, Section 2)", "the gap (DESIGN fact 11)"])
def test_outside_references_are_caught(line):
    assert OUTSIDE.search(line)


def test_the_project_pages_pass():
    assert not OUTSIDE.search("see docs/design.md and docs/model.md (the design of the code)")
