"""Bad input and faults, through the ``bouncer`` command: each case gives the exit status
documented in docs/runs.md, one line on stderr (``bouncer...: error: ...``, no traceback), and
leaves no file behind that was not there before (no temporary files, no half-made run, and
the run directory it reads unchanged). Audits that find a discrepancy (exit 1) print their
report on stdout and end with the FAILED line.

Most cases run ``reports.cli.main`` in this process on copies of one tiny run; the faults are
injected by replacing a function (a full disk: an OSError ENOSPC from the write of one file).
"""

import errno
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from reports.cli import main
from reports.runs import cluster, driver, executor, rundir
from tests.reports.runs.scene_texts import TINY

ROOT = Path(__file__).resolve().parents[3]


def bouncer(argv):
    """``main(argv)``'s exit status (argparse's errors exit through SystemExit)."""
    try:
        return main([str(a) for a in argv])
    except SystemExit as stop:
        return stop.code


def tree(folder):
    """{relative path: bytes} of every file under ``folder``."""
    return {str(p.relative_to(folder)): p.read_bytes()
            for p in sorted(Path(folder).rglob("*")) if p.is_file()}


def one_line(capsys):
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("bouncer") and ": error: " in lines[0], lines[0]
    assert "Traceback" not in captured.err + captured.out
    return lines[0]


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("tiny") / "run"
    driver.run(driver.parse_scene(TINY), out, progress=False)
    return out


@pytest.fixture
def work(tiny_run, tmp_path, monkeypatch):
    """A folder holding tiny.toml and a copy of the tiny run (``run``), the current folder."""
    shutil.copytree(tiny_run, tmp_path / "run")
    (tmp_path / "tiny.toml").write_text(TINY)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _edit_manifest(edit):
    def setup(folder):
        path = folder / "run" / "manifest.json"
        manifest = json.loads(path.read_text())
        path.write_text(json.dumps(edit(manifest) or manifest))
    return setup


def _write(name, text):
    def setup(folder):
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(text.encode() if isinstance(text, str) else text)
    return setup


def _scene(old, new, name="bad.toml"):
    return _write(name, TINY.replace(old, new))


def _set(key, value):
    return _edit_manifest(lambda m: m.__setitem__(key, value))


# (id, argv, setup, exit status, text in the error line); the cases run in the folder ``work``
BAD_INPUT = [
    # bouncer run: options
    ("run unknown scene", ["run", "no-such-scene"], None, 2, "no scene 'no-such-scene'"),
    ("run particles 0", ["run", "tiny.toml", "--particles", "0", "--out", "o"], None, 2,
     "--particles must be >= 1"),
    ("run particles -5", ["run", "tiny.toml", "--particles", "-5", "--out", "o"], None, 2,
     "--particles must be >= 1"),
    ("run particles 1.5", ["run", "tiny.toml", "--particles", "1.5"], None, 2,
     "argument --particles: need an integer"),
    ("run particles abc", ["run", "tiny.toml", "--particles", "abc"], None, 2,
     "argument --particles: need an integer"),
    ("run particles 1e30", ["run", "tiny.toml", "--particles", "1e30", "--out", "o"], None, 2,
     "years here"),
    ("run seed -1", ["run", "tiny.toml", "--seed", "-1", "--out", "o"], None, 2,
     "--seed must be >= 0"),
    ("run threads 0", ["run", "tiny.toml", "--threads", "0", "--out", "o"], None, 2,
     "--threads must be between 1 and"),
    ("run threads 9999", ["run", "tiny.toml", "--threads", "9999", "--out", "o"], None, 2,
     "--threads must be between 1 and"),
    ("run unknown option", ["run", "tiny.toml", "--colour", "5"], None, 2,
     "unrecognized arguments"),
    ("no subcommand", [], None, 2, "the following arguments are required: COMMAND"),
    ("unknown subcommand", ["runn"], None, 2, "invalid choice: 'runn'"),
    # bouncer run: the run directory
    ("run resume without run", ["run", "tiny.toml", "--resume", "--out", "o"], None, 2,
     "holds no run"),
    ("run out is a file", ["run", "tiny.toml", "--out", "tiny.toml"], None, 2,
     "is a file, not a directory"),
    ("run out under a file", ["run", "tiny.toml", "--out", "tiny.toml/r"], None, 2,
     "tiny.toml"),
    ("run existing run", ["run", "tiny.toml", "--out", "run"], None, 2,
     "use --resume to continue it or --force"),
    ("run force on a folder", ["run", "tiny.toml", "--out", "other", "--force"],
     _write("other/notes.txt", "mine"), 2, "is not a run directory; not deleting it"),
    # bouncer run: scene files
    ("scene not utf-8", ["run", "bin.toml", "--out", "o"], _write("bin.toml", bytes(range(256))),
     2, "bin.toml is not UTF-8 text"),
    ("scene not toml", ["run", "bad.toml", "--out", "o"], _write("bad.toml", "name = [\n"), 2,
     "bad.toml: not valid TOML"),
    ("scene name escapes", ["run", "bad.toml"], _scene('name = "tiny"', 'name = "../../etc/evil"'),
     2, "name must be a plain file name"),
    ("scene name hidden", ["run", "bad.toml"], _scene('name = "tiny"', 'name = ".tiny"'), 2,
     "name must be a plain file name"),
    ("scene name empty", ["run", "bad.toml"], _scene('name = "tiny"', 'name = ""'), 2,
     "name must be a non-empty string"),
    ("scene name absolute", ["run", "bad.toml"], _scene('name = "tiny"', 'name = "/tmp/x"'), 2,
     "name must be a plain file name"),
    ("scene unknown key", ["run", "bad.toml", "--out", "o"],
     _scene("seed = 3", "seed = 3\nsed = 4"), 2, "unknown key(s) in scene: sed"),
    ("scene eps text", ["run", "bad.toml", "--out", "o"], _scene("eps = 0.6", 'eps = "0.6"'), 2,
     "eps must be a number"),
    ("scene width 0", ["run", "bad.toml", "--out", "o"], _scene("widths = [1.0]", "widths = [0.0]"),
     2, "hole width must be in (0, 2*pi)"),
    ("scene particles -5", ["run", "bad.toml", "--out", "o"],
     _scene("particles = 200", "particles = -5"), 2, "bad.toml: particles must be >= 1"),
    ("scene no departure", ["run", "bad.toml", "--out", "o"],
     _scene("v = [2.0, 4.0]", "v = [0.1, 4.0]"), 2, "include non-departures"),
    # bouncer run --resume of a damaged run
    ("resume truncated manifest", ["run", "tiny.toml", "--out", "run", "--resume"],
     _write("run/manifest.json", '{"status": "partial", "scene"'), 2,
     "run/manifest.json: not valid JSON"),
    ("resume manifest list", ["run", "tiny.toml", "--out", "run", "--resume"],
     _write("run/manifest.json", "[1, 2, 3]"), 2, "run/manifest.json: [1, 2, 3] is not of type"),
    ("resume particles text", ["run", "tiny.toml", "--out", "run", "--resume"],
     _set("particles", "200"), 2, "field particles: '200' is not of type 'integer'"),
    ("resume particles -5", ["run", "tiny.toml", "--out", "run", "--resume"],
     _set("particles", -5), 2, "field particles: -5 is less than the minimum of 1"),
    ("resume other seed", ["run", "tiny.toml", "--out", "run", "--resume", "--seed", "4"], None, 2,
     "give the same scene, --particles and --seed"),
    ("resume scene not utf-8", ["run", "tiny.toml", "--out", "run", "--resume"],
     _write("run/scene.toml", b"\xff\xfe"), 2, "run/scene.toml: not UTF-8 text"),
    # bouncer verify: not auditable (exit 2)
    ("verify not a run", ["verify", "."], None, 2, "is not a run directory"),
    ("verify manifest list", ["verify", "run"], _write("run/manifest.json", "[1, 2, 3]"), 2,
     "[1, 2, 3] is not of type 'object'"),
    ("verify manifest 42", ["verify", "run"], _write("run/manifest.json", "42"), 2,
     "42 is not of type 'object'"),
    ("verify manifest deep", ["verify", "run"], _write("run/manifest.json", "[" * 100000), 2,
     "not valid JSON"),
    ("verify worst_error null", ["verify", "run"],
     _edit_manifest(lambda m: m["verification"].__setitem__("worst_error", None)), 2,
     "field verification.worst_error: None is not of type 'number'"),
    ("verify verification list", ["verify", "run"], _set("verification", []), 2,
     "field verification: [] is not of type 'object'"),
    ("verify hashes list", ["verify", "run"], _set("hashes", []), 2,
     "field hashes: [] is not of type 'object'"),
    ("verify particles text", ["verify", "run"], _set("particles", "300000"), 2,
     "field particles: '300000' is not of type 'integer'"),
    ("verify particles float", ["verify", "run"], _set("particles", 200.0), 2,
     "field particles: 200.0 is not of type 'integer'"),
    ("verify hash of a path", ["verify", "run"],
     _edit_manifest(lambda m: m["hashes"].__setitem__("../../x", "0" * 64)), 2,
     "field hashes: '../../x' is not one of"),
    ("verify provenance in manifest", ["verify", "run"], _set("git", {"commit": "abc"}), 2,
     "'git' was unexpected"),
    ("verify truncated manifest", ["verify", "run"], _write("run/manifest.json", "{"), 2,
     "run/manifest.json: not valid JSON"),
    # bouncer plot and fit of damaged runs and histograms
    ("plot not a run", ["plot", "."], None, 2, "is not a run directory"),
    ("plot manifest list", ["plot", "run"], _write("run/manifest.json", "[1, 2, 3]"), 2,
     "is not of type 'object'"),
    ("plot fit without window", ["plot", "run", "--fit", "exponential"], None, 2,
     "--fit exponential needs --window"),
    ("fit manifest list", ["fit", "run", "--json"], _write("run/manifest.json", "[1, 2, 3]"), 2,
     "is not of type 'object'"),
    ("fit no such path", ["fit", "nothing.csv"], None, 2, "nothing.csv: no such file"),
    ("fit jobs 0", ["fit", "run", "--jobs", "0"], None, 2, "--jobs must be >= 1"),
    ("fit count 1e300", ["fit", "h.csv", "--json"],
     _write("h.csv", "lower,upper,count\n0,1,1e300\n"), 2, "count 1e300 is above 2**53"),
    ("fit count 2**63-1", ["fit", "h.csv", "--json"],
     _write("h.csv", f"lower,upper,count\n0,1,{2**63 - 1}\n1,2,5\n"), 2, "is above 2**53"),
    ("fit edges 1e300", ["fit", "h.csv", "--json"],
     _write("h.csv", "lower,upper,count\n1e300,1.5e300,10\n1.5e300,1.7e300,5\n"), 2,
     "outside [0, 2**53]"),
    ("fit header", ["fit", "h.csv"], _write("h.csv", "a,b\n1,2\n"), 2, "header must be"),
    # bouncer check
    ("check spec", ["check", "fastpath"], None, 2, "expected MODULE:FUNCTION"),
    ("check suite", ["check", "fastpath:flight_time", "--suite", "bogus"], None, 2,
     "unknown suite 'bogus'"),
    ("check budget 0", ["check", "fastpath:flight_time", "--budget", "0"], None, 2, "--budget"),
    ("check module exits", ["check", "script_style:flight_time", "--no-progress"],
     _write("script_style.py",
            "import sys\ndef flight_time(p, v, e):\n    return 2*v\nsys.exit(0)\n"),
     2, "called sys.exit(0)"),
    # bouncer demo, bench, report, sweep
    ("demo collisions 0", ["demo", "--collisions", "0"], None, 2, "--collisions must be >= 1"),
    ("demo sample 0", ["demo", "--sample", "0"], None, 2, "--sample must be >= 1"),
    ("demo eps nan", ["demo", "--eps", "nan"], None, 2, "--eps must be a finite number"),
    ("bench repeats 0", ["bench", "--repeats", "0"], None, 2, "--repeats must be >= 1"),
    ("bench threads 0", ["bench", "--threads", "0"], None, 2, "--threads must be between 1"),
    ("report particles 0", ["report", "--particles", "0"], None, 2, "--particles must be >= 1"),
    ("report particles 2.5", ["report", "--particles", "2.5"], None, 2,
     "argument --particles: need an integer"),
    ("report include no run", ["report", "--include-run", "nothing"], None, 2,
     "--include-run nothing: not a run directory"),
    ("report include bad run", ["report", "--include-run", "run"], _set("seed", "3"), 2,
     "field seed: '3' is not of type 'integer'"),
    ("sweep eps range", ["sweep", "--eps", "1", "0", "3", "--out", "o"], None, 2,
     "--eps: need LO < HI"),
    ("sweep phase-space", ["sweep", "paper-phase-space", "--out", "o"], None, 2,
     "sweep needs an escape scene"),
    ("sweep particles 0", ["sweep", "--particles", "0", "--out", "o"], None, 2,
     "--particles must be >= 1"),
]

TAMPERED = [  # the audit runs and fails: exit 1, the report on stdout
    ("seed", _edit_manifest(lambda m: m.__setitem__("seed", m["seed"] + 1)),
     "is not a verification pick drawn from seed 4"),
    ("scene eps", _edit_manifest(lambda m: m["scene"].__setitem__("eps", 0.9)),
     "manifest.json: scene.eps is 0.9, scene.toml gives 0.6"),
    ("scene horizon", _edit_manifest(lambda m: m["scene"]["horizon"].__setitem__("collisions", 7)),
     "manifest.json: scene.horizon.collisions is 7, scene.toml gives 200"),
    ("bins", _edit_manifest(lambda m: m["bins"]["collisions"].__setitem__("per_decade", 10)),
     "manifest.json: bins.collisions.per_decade is 10, the histograms' bins are 20"),
    ("survival band", _set("survival_band", "99% Clopper-Pearson"),
     "manifest.json: survival_band is '99% Clopper-Pearson', survival.csv's band is"),
    ("chunk size", _set("chunk_size", 128),
     "manifest.json: chunk_size is 128, scene.toml gives 64"),
    ("particles", _set("particles", 300), "but 300 particles were run"),
    ("status", _set("status", "partial"), "the run is not complete (status partial)"),
    ("provenance git", _write("run/provenance.json", "{}"),
     "provenance.json: SHA-256 differs from the manifest's"),
]


@pytest.mark.parametrize("case", BAD_INPUT, ids=[c[0] for c in BAD_INPUT])
def test_bad_input_is_one_line_and_leaves_nothing(case, work, capsys):
    _, argv, setup, status, text = case
    if setup is not None:
        setup(work)
    before = tree(work)
    assert bouncer(argv) == status
    line = one_line(capsys)
    assert text in line
    assert tree(work) == before


@pytest.mark.parametrize("case", TAMPERED, ids=[c[0] for c in TAMPERED])
def test_a_tampered_run_fails_its_audit(case, work, capsys):
    _, setup, text = case
    setup(work)
    before = tree(work)
    assert bouncer(["verify", "run", "--quiet"]) == 1
    captured = capsys.readouterr()
    assert captured.err == ""
    assert any(text in line for line in captured.out.splitlines()), captured.out
    assert captured.out.splitlines()[-1].startswith("FAILED: ")
    assert tree(work) == before


# ---- faults while a run writes ----------------------------------------------------------------

def _full_disk_at(monkeypatch, name, nth=1):
    """From the nth write of ``name`` through ``rundir.write_atomic`` on, every one fails as on
    a full disk (after its temporary file was opened and partly written); ``_space_again``
    ends it."""
    real_open, seen = open, []

    class Full:
        def __init__(self, f):
            self.f = f

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            self.f.close()
            return False

        def write(self, data):
            self.f.write(data[: len(data) // 2])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    def opening(path, *args, **kwargs):
        f = real_open(path, *args, **kwargs)
        if Path(path).name.startswith(f".{name}.tmp"):
            seen.append(path)
            if len(seen) >= nth:
                return Full(f)
        return f

    monkeypatch.setattr(rundir, "open", opening, raising=False)


def _space_again(monkeypatch):
    monkeypatch.delattr(rundir, "open")


def temporaries(folder):
    return [p for p in Path(folder).rglob(".*.tmp*")]


def test_a_full_disk_at_the_first_checkpoint_leaves_nothing(work, monkeypatch, capsys):
    _full_disk_at(monkeypatch, "checkpoint.npz")
    before = tree(work)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 2
    line = one_line(capsys)
    assert "new/checkpoint.npz: No space left on device" in line
    assert "before its first chunk was saved and it left nothing behind" in line
    assert tree(work) == before and not (work / "new").exists()


def test_a_full_disk_mid_run_keeps_the_checkpoint_and_resumes(work, monkeypatch, capsys):
    """The manifest after the first checkpoint cannot be written: the temporary file goes, the
    message names the file and says how to continue; with space again --resume completes the
    run as if nothing happened."""
    _full_disk_at(monkeypatch, "manifest.json", nth=2)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 2
    line = one_line(capsys)
    assert "new/manifest.json: No space left on device" in line
    assert "continue with --resume" in line
    assert temporaries(work) == []
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet", "--resume"]) == 2  # still full
    assert "No space left on device" in one_line(capsys) and temporaries(work) == []
    _space_again(monkeypatch)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet", "--resume"]) == 0
    for name in ("counts.csv", "survival.csv", "sample.csv", "scene.toml"):
        assert (work / "new" / name).read_bytes() == (work / "run" / name).read_bytes(), name
    resumed, whole = (json.loads((work / d / "manifest.json").read_text()) for d in ("new", "run"))
    for manifest in (resumed, whole):  # the files that hold times (elapsed, dates)
        del manifest["hashes"]["checkpoint.npz"], manifest["hashes"]["provenance.json"]
    assert resumed == whole
    assert bouncer(["verify", "new", "--quiet"]) == 0


def test_a_full_disk_writing_the_results_resumes_to_the_same_run(work, monkeypatch, capsys):
    _full_disk_at(monkeypatch, "survival.csv")
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 2
    assert "new/survival.csv: No space left on device" in one_line(capsys)
    assert temporaries(work) == [] and not (work / "new" / "survival.csv").exists()
    _space_again(monkeypatch)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet", "--resume"]) == 0
    new, old = work / "new" / "survival.csv", work / "run" / "survival.csv"
    assert new.read_bytes() == old.read_bytes()


def test_ctrl_c_before_the_first_chunk_leaves_nothing(work, monkeypatch, capsys):
    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(executor, "run_chunk", interrupted)
    before = tree(work)
    assert bouncer(["run", "tiny.toml", "--out", "a/b/new", "--quiet"]) == 130
    assert capsys.readouterr().err == "bouncer: interrupted\n"
    assert tree(work) == before and not (work / "a").exists()


def test_ctrl_c_after_a_chunk_keeps_the_checkpoint(work, monkeypatch, capsys):
    real, calls = executor.run_chunk, []

    def second_interrupted(*args):
        calls.append(args)
        if len(calls) == 3:  # two chunks in flight: the first is merged and saved
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(executor, "run_chunk", second_interrupted)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 130
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "continue with: bouncer run tiny.toml --out new --resume" in err
    assert temporaries(work) == []
    monkeypatch.setattr(executor, "run_chunk", real)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet", "--resume"]) == 0


def test_a_run_that_cannot_write_its_folder_leaves_nothing(work, monkeypatch, capsys):
    """The first write of the run (scene.toml) fails: the folders it made go again."""
    _full_disk_at(monkeypatch, "scene.toml")
    assert bouncer(["run", "tiny.toml", "--out", "a/b/new", "--quiet"]) == 2
    assert "No space left on device" in one_line(capsys)
    assert not (work / "a").exists()


@pytest.mark.slow
@pytest.mark.parametrize("command", [["run", "tiny.toml", "--out", "new"],
                                     ["sweep", "tiny-escape.toml", "--out", "new"]])
def test_an_unreachable_scheduler_leaves_nothing(work, monkeypatch, capsys, command):
    """Nothing listens on port 1: the connection is refused within the connect timeout, before
    the run directory exists; the same command then works without --resume or --force."""
    pytest.importorskip("distributed")
    monkeypatch.setattr(cluster, "CONNECT_TIMEOUT", "2s")
    (work / "tiny-escape.toml").write_text(ESCAPE)
    before = tree(work)
    assert bouncer([*command, "--quiet", "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert "cannot connect to the Dask scheduler at tcp://127.0.0.1:1" in one_line(capsys)
    assert tree(work) == before and not (work / "new").exists()


ESCAPE = TINY.replace('kind = "transport"', 'kind = "escape"').replace(
    "[start]\n", "[start]\nphi = [3.85, 4.15]\n").replace(
    "centres = [0.0, 3.141592653589793]", "centres = [1.0]")


def test_ctrl_c_while_the_command_imports_is_one_line(tmp_path):
    """Ctrl-C in the first second (the imports of numba, scipy, ...) is one line, exit 130:
    here the import of numba is interrupted."""
    script = ("import sys\n"
              "class Stop:\n"
              "    def find_spec(self, name, path=None, target=None):\n"
              "        if name == 'numba':\n"
              "            raise KeyboardInterrupt\n"
              "sys.meta_path.insert(0, Stop())\n"
              "from reports.cli import main\n"
              "sys.exit(main(['scenes']))\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert proc.returncode == 130
    assert proc.stderr == "bouncer: interrupted\n" and proc.stdout == ""


def test_a_full_disk_taking_the_lock_leaves_nothing(work, monkeypatch, capsys):
    """Writing the lock's holder fails: the lock is released, the folder made goes again."""
    from reports.runs import lock

    real = Path.write_text

    def full(self, *args, **kwargs):
        if self.name == lock.HOLDER_NAME:
            real(self, "{", encoding="utf-8")
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", full)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 2
    assert "new/.bouncer.lock.json: No space left on device" in one_line(capsys)
    assert not (work / "new").exists()
    monkeypatch.setattr(Path, "write_text", real)
    assert bouncer(["run", "tiny.toml", "--out", "new", "--quiet"]) == 0
