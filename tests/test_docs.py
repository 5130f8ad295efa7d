"""Every fenced code block of README.md and docs/*.md runs as printed.

The conventions (also in docs/testing.md, "Examples that run"):

* A ```python block is a self-contained script (imports included): it runs in a fresh
  interpreter, in an empty temporary directory that holds a link to the repository's
  ``examples/`` folder, and passes when it exits without an exception. Its assertions are the
  page's checkable claims.
* A ```console (or ```shell) block is a terminal session. A line ``$ bouncer ...`` is a command,
  run by bash in a temporary directory shared by the block's commands (with the same link to
  ``examples/``); a line ending in ``\\`` continues on the next. The lines after a command, up to
  the next ``$`` line, are its expected output, compared line by line with what it prints
  (stdout and stderr together, trailing spaces ignored): ``...`` within a line matches any text,
  a line that is ``...`` alone matches any number of lines. A command followed by no lines has
  its output ignored. The exit status must be 0, or N where the expected output ends with the
  line ``[exit status N]``. Only ``bouncer`` commands run: install and test commands belong in
  ```bash blocks.
* A ```sh block is a script of commands, one a line (a ``#`` after a space starts a comment):
  each runs by bash in a temporary directory shared by the block's commands, as a console
  block's do, and must exit 0; its output is not compared. Only ``bouncer`` commands.
* A ```bash block is shown, not run (install and test commands); one made only of ``bouncer``
  commands must be a ```sh or console block, or say with a skip marker why it cannot run.
* An HTML comment on the line before a block marks it: ``<!-- docs-test: slow -->`` gives it
  SLOW_LIMIT_S seconds instead of QUICK_LIMIT_S, ``<!-- docs-test: skip (REASON) -->`` does not
  run it, and pytest reports the skip with its reason.
* Blocks with any other language (```toml, ```text, none) are shown, not run.

The blocks run in the full suite (``pytest``, or ``pytest tests/test_docs.py``), not in the quick
loop ``pytest -m "not slow"``: each starts a fresh interpreter (a second or more per block), so
their tests are marked ``slow``. The quick loop keeps this runner's own tests.
"""

from __future__ import annotations

import functools
import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
RUN_LANGUAGES = ("python", "console", "shell", "sh")
SHELL_LANGUAGES = ("bash", "sh", "shell", "console", "zsh", "shell-session")
QUICK_LIMIT_S = 120
SLOW_LIMIT_S = 600
MARKER = re.compile(r"<!--\s*docs-test:\s*(.*?)\s*-->")
EXIT_LINE = re.compile(r"\[exit status (\d+)\]")


@dataclass(frozen=True)
class Block:
    """One fenced code block: where it is, its language, its text and its marker."""

    page: str
    line: int
    language: str
    text: str
    marker: str

    @property
    def name(self) -> str:
        return f"{self.page}:{self.line}"


def fenced_blocks(markdown: str, page: str) -> list[Block]:
    """The fenced code blocks of a markdown text, with the docs-test marker before each."""
    blocks = []
    lines = markdown.splitlines()
    i = 0
    while i < len(lines):
        opening = re.match(r"^(\s*)(`{3,})\s*([\w+-]*)", lines[i])
        if not opening:
            i += 1
            continue
        indent, fence, language = opening.groups()
        start = i
        i += 1
        body = []
        while i < len(lines) and not lines[i].strip().startswith(fence):
            line = lines[i]
            body.append(line[len(indent):] if line.startswith(indent) else line.lstrip())
            i += 1
        i += 1  # the closing fence
        before = start - 1
        while before >= 0 and not lines[before].strip():
            before -= 1
        marker = MARKER.fullmatch(lines[before].strip()) if before >= 0 else None
        blocks.append(Block(page, start + 1, language.lower(), "\n".join(body) + "\n",
                            marker.group(1) if marker else ""))
    return blocks


def block_param(block: Block):
    """The test parameter of a block: marked slow (module docstring), and skipped if its marker
    says so."""
    marks = [pytest.mark.slow]
    if block.marker.startswith("skip"):
        reason = block.marker[len("skip"):].strip(" ()") or "no reason given"
        marks.append(pytest.mark.skip(reason=f"{block.name}: {reason}"))
    return pytest.param(block, marks=marks, id=block.name)


def _collect() -> list:
    params = []
    for path in PAGES:
        page = str(path.relative_to(ROOT))
        for block in fenced_blocks(path.read_text(encoding="utf-8"), page):
            if block.language in RUN_LANGUAGES:
                params.append(block_param(block))
    return params


def line_matches(expected: str, actual: str) -> bool:
    """One expected line against one printed line; ``...`` matches any text."""
    pattern = ".*".join(re.escape(part) for part in expected.rstrip().split("..."))
    return re.fullmatch(pattern, actual.rstrip()) is not None


def output_matches(expected: list[str], actual: list[str]) -> bool:
    """Expected lines against printed lines; a line ``...`` alone matches any number of lines."""
    expected = [e.rstrip() for e in expected]
    actual = [a.rstrip() for a in actual]
    while actual and not actual[-1]:
        actual.pop()

    @functools.cache
    def match(i: int, j: int) -> bool:
        if i == len(expected):
            return j == len(actual)
        if expected[i].strip() == "...":
            return any(match(i + 1, k) for k in range(j, len(actual) + 1))
        return j < len(actual) and line_matches(expected[i], actual[j]) and match(i + 1, j + 1)

    return match(0, 0)


@dataclass(frozen=True)
class Command:
    """A ``$`` line of a console block, its expected output and exit status."""

    command: str
    expected: list[str]
    status: int


def session_commands(text: str) -> list[Command]:
    """The commands of a console block with the output quoted after each."""
    commands: list[Command] = []
    lines = text.splitlines()
    i = 0
    while i < len(lines):
        if not lines[i].startswith("$ "):
            if lines[i].strip():
                raise ValueError(f"output before the first command: {lines[i]!r}")
            i += 1
            continue
        command = lines[i][2:]
        while command.endswith("\\") and i + 1 < len(lines):
            i += 1
            command = command[:-1] + " " + lines[i].strip()
        i += 1
        expected = []
        while i < len(lines) and not lines[i].startswith("$ "):
            expected.append(lines[i])
            i += 1
        while expected and not expected[-1].strip():
            expected.pop()
        status = 0
        if expected and EXIT_LINE.fullmatch(expected[-1].strip()):
            status = int(EXIT_LINE.fullmatch(expected[-1].strip()).group(1))
            expected.pop()
        commands.append(Command(command.strip(), expected, status))
    return commands


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    env["PYTHONUNBUFFERED"] = "1"  # stdout and stderr reach the one pipe in the order written
    env["MPLBACKEND"] = "Agg"
    env["COLUMNS"] = "80"  # argparse wraps --help to the terminal's width
    env.pop("PYTHONPATH", None)  # a reader's shell has no repository on the path
    return env


def _workdir(tmp_path: Path) -> Path:
    tmp_path.mkdir(parents=True, exist_ok=True)
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    return tmp_path


def _limit(block: Block) -> int:
    return SLOW_LIMIT_S if block.marker == "slow" else QUICK_LIMIT_S


def _run(args, block: Block, cwd: Path, what: str) -> subprocess.CompletedProcess:
    limit = _limit(block)
    try:
        return subprocess.run(args, cwd=cwd, env=_environment(), stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=limit)
    except subprocess.TimeoutExpired:
        advice = "" if block.marker == "slow" else " (mark the block <!-- docs-test: slow -->)"
        pytest.fail(f"{block.name}: {what} did not finish within {limit} s{advice}")


def _tail(text: str, lines: int = 60) -> str:
    return "\n".join(text.splitlines()[-lines:])


def run_python(block: Block, cwd: Path) -> None:
    script = cwd / "docs_block.py"
    script.write_text(block.text, encoding="utf-8")
    done = _run([sys.executable, str(script)], block, cwd, "the python block")
    assert done.returncode == 0, (
        f"{block.name}: the python block failed (exit {done.returncode}):\n{_tail(done.stdout)}")


def script_commands(text: str) -> list[str]:
    """The commands of a ```sh block: its lines without comments, blank ones dropped."""
    commands = []
    for line in text.splitlines():
        command = re.split(r"(?:^|\s)#", line, maxsplit=1)[0].strip()
        if command:
            commands.append(command)
    return commands


def run_script(block: Block, cwd: Path) -> None:
    commands = script_commands(block.text)
    assert commands, f"{block.name}: an sh block with no command"
    for command in commands:
        assert command.split()[0] == "bouncer", (
            f"{block.name}: only bouncer commands run in an sh block; show {command!r} in a"
            " ```bash block")
        done = _run(["bash", "-c", command], block, cwd, repr(command))
        assert done.returncode == 0, (
            f"{block.name}: {command!r} exited {done.returncode}:\n{_tail(done.stdout)}")


def run_session(block: Block, cwd: Path) -> None:
    commands = session_commands(block.text)
    assert commands, f"{block.name}: a {block.language} block with no '$ ' command"
    for c in commands:
        assert c.command.split()[0] == "bouncer", (
            f"{block.name}: only bouncer commands run in a {block.language} block; "
            f"show {c.command!r} in a ```bash block")
        done = _run(["bash", "-c", c.command], block, cwd, repr(c.command))
        assert done.returncode == c.status, (
            f"{block.name}: {c.command!r} exited {done.returncode}, expected {c.status}:\n"
            f"{_tail(done.stdout)}")
        if c.expected:
            assert output_matches(c.expected, done.stdout.splitlines()), (
                f"{block.name}: {c.command!r} printed\n{_tail(done.stdout)}\n"
                f"--- expected ---\n" + "\n".join(c.expected))


@pytest.mark.parametrize("block", _collect())
def test_code_block_runs_as_printed(block, tmp_path):
    assert block.marker in ("", "slow") or block.marker.startswith("skip"), (
        f"{block.name}: unknown docs-test marker {block.marker!r} (slow, skip (REASON))")
    cwd = _workdir(tmp_path)
    if block.language == "python":
        run_python(block, cwd)
    elif block.language == "sh":
        run_script(block, cwd)
    else:
        run_session(block, cwd)


def _all_blocks() -> list[Block]:
    return [block for path in PAGES
            for block in fenced_blocks(path.read_text(encoding="utf-8"),
                                       str(path.relative_to(ROOT)))]


def test_a_block_of_bouncer_commands_is_run_or_says_why_not():
    """A ```bash block is shown, not run: one whose every command is ``bouncer ...`` would be
    a promise nobody checks. It must be a ```sh (or console) block, run by this file, or carry
    a skip marker with its reason."""
    def bouncer_only(block):
        commands = [c.removeprefix("$ ") for c in script_commands(block.text)
                    if block.language != "console" or c.startswith("$ ")]
        return commands and all(c.split()[0] == "bouncer" for c in commands)

    unchecked = [b.name for b in _all_blocks() if b.language in SHELL_LANGUAGES
                 and b.language not in RUN_LANGUAGES and not b.marker.startswith("skip")
                 and bouncer_only(b)]
    assert unchecked == []
    skipped = [b for b in _all_blocks() if b.marker.startswith("skip")]
    assert all(b.marker.strip("skip ()") for b in skipped)  # every skip gives its reason


def test_sh_blocks_split_into_commands_without_comments():
    text = "bouncer scenes            # the built-in scenes\n\n# a comment line\n" \
           "bouncer run x --seed 3  #seed\nbouncer fit 'a#b'\n"
    assert script_commands(text) == ["bouncer scenes", "bouncer run x --seed 3",
                                     "bouncer fit 'a#b'"]


def test_output_convention_matches_text_lines_and_wildcards():
    assert output_matches(["complete: 4 points in ... s"], ["complete: 4 points in 0.7 s"])
    assert not output_matches(["complete: 4 points"], ["complete: 5 points"])
    assert output_matches(["first", "...", "last"], ["first", "a", "b", "last"])
    assert output_matches(["first", "...", "last"], ["first", "last"])
    assert not output_matches(["first", "last"], ["first", "extra", "last"])
    assert not output_matches(["first"], ["first", "extra"])  # unquoted extra output fails
    assert output_matches(["a  "], ["a", ""])  # trailing spaces and blank lines are ignored
    assert not output_matches(["(1.0)"], ["11.0"])  # the rest is literal, not a regex


def test_console_blocks_split_into_commands_outputs_and_exit_status():
    text = ("$ bouncer run x \\\n    --quiet\nline 1\n...\n"
            "$ bouncer verify x\n[exit status 2]\n$ bouncer scenes\n")
    commands = session_commands(text)
    assert [c.command for c in commands] == [
        "bouncer run x  --quiet", "bouncer verify x", "bouncer scenes"]
    assert [c.expected for c in commands] == [["line 1", "..."], [], []]
    assert [c.status for c in commands] == [0, 2, 0]
    with pytest.raises(ValueError, match="before the first command"):
        session_commands("output\n$ bouncer scenes\n")


@pytest.mark.slow
def test_a_session_fails_on_other_output_or_exit_status(tmp_path):
    def session(text):
        return Block("page.md", 1, "console", text, "")

    run_session(session("$ bouncer run no-such-scene\nbouncer: error: no scene ...\n"
                        "[exit status 2]\n"), _workdir(tmp_path / "a"))
    with pytest.raises(AssertionError, match="exited 2, expected 0"):
        run_session(session("$ bouncer run no-such-scene\n"), _workdir(tmp_path / "b"))
    with pytest.raises(AssertionError, match="printed"):
        run_session(session("$ bouncer run no-such-scene\nbouncer: error: no file\n"
                            "[exit status 2]\n"), _workdir(tmp_path / "c"))
    with pytest.raises(AssertionError, match="only bouncer commands"):
        run_session(session("$ pip install .\n"), _workdir(tmp_path / "d"))


@pytest.mark.slow
def test_a_script_fails_on_a_command_that_fails(tmp_path):
    def script(text):
        return Block("page.md", 1, "sh", text, "")

    run_script(script("bouncer scenes  # lists them\n"), _workdir(tmp_path / "a"))
    with pytest.raises(AssertionError, match="'bouncer run no-such-scene' exited 2"):
        run_script(script("bouncer scenes\nbouncer run no-such-scene\n"),
                   _workdir(tmp_path / "b"))
    with pytest.raises(AssertionError, match="only bouncer commands"):
        run_script(script("pip install .\n"), _workdir(tmp_path / "c"))


def test_a_python_block_fails_on_an_exception(tmp_path):
    run_python(Block("page.md", 1, "python", "assert 1 + 1 == 2\n", ""), _workdir(tmp_path))
    with pytest.raises(AssertionError, match="the python block failed"):
        run_python(Block("page.md", 1, "python", "assert 1 + 1 == 3\n", ""), tmp_path)


def test_markers_are_read_from_the_line_before_a_block():
    page = ("text\n<!-- docs-test: slow -->\n```python\nx = 1\n```\n\n"
            "<!-- docs-test: skip (takes an hour) -->\n\n```console\n$ bouncer demo\n```\n"
            "```toml\na = 1\n```\n")
    blocks = fenced_blocks(page, "page.md")
    assert [(b.line, b.language, b.marker) for b in blocks] == [
        (3, "python", "slow"), (9, "console", "skip (takes an hour)"), (12, "toml", "")]
    assert blocks[0].text == "x = 1\n"
    slow, skipped, plain = (block_param(b).marks for b in blocks)
    assert [m.name for m in slow] == [m.name for m in plain] == ["slow"]  # full suite only
    assert [(m.name, m.kwargs.get("reason")) for m in skipped] == [
        ("slow", None), ("skip", "page.md:9: takes an hour")]
    assert _limit(blocks[0]) == SLOW_LIMIT_S and _limit(blocks[2]) == QUICK_LIMIT_S
