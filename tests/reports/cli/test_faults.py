"""Bad input and faults, through the ``bouncer`` command: each case gives the exit status
documented in docs/runs.md, one line on stderr (``bouncer...: error: ...``, no traceback), and
leaves no file behind that was not there before (no temporary files, no half-made run, and
the run directory it reads unchanged). Audits that find a discrepancy (exit 1) print their
report on stdout and end with the FAILED line.

Most cases run ``reports.cli.main`` in this process on copies of one tiny run; the faults are
injected by replacing a function (a full disk: an OSError ENOSPC from the write of one file).
"""

import errno
import hashlib
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


MAX_LINE = 600  # characters of an error line: the values it echoes are clipped


def one_line(capsys):
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("bouncer") and ": error: " in lines[0], lines[0]
    assert "Traceback" not in captured.err + captured.out
    assert len(lines[0]) <= MAX_LINE, lines[0]
    assert "np.float" not in lines[0] and "[Errno" not in lines[0], lines[0]  # plain words
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


def _rehashed(name, change):
    """Rewrite run/NAME with ``change(bytes)`` and record its new SHA-256 in the manifest: a
    forger who knows the format (the hash check alone cannot tell)."""
    def setup(folder):
        path = folder / "run" / name
        path.write_bytes(change(path.read_bytes()))
        manifest_path = folder / "run" / "manifest.json"
        manifest = json.loads(manifest_path.read_text())
        manifest["hashes"][name] = hashlib.sha256(path.read_bytes()).hexdigest()
        manifest_path.write_text(json.dumps(manifest))
    return setup


def _manifest_text(old, new):
    def setup(folder):
        path = folder / "run" / "manifest.json"
        text = json.dumps(json.loads(path.read_text()), indent=1)
        assert old in text
        path.write_text(text.replace(old, new))
    return setup


LONG = "7" * 5000  # an integer of more digits than Python converts (4300)
DEEP_TOML = 'name = "x"\nkind = "escape"\na = ' + "[" * 100_000 + "]" * 100_000 + "\n"


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
    ("scene nested 100000 deep", ["run", "deep.toml", "--out", "o"],
     _write("deep.toml", DEEP_TOML), 2, "deep.toml: not valid TOML: nested too deeply"),
    ("scene 5000-digit integer", ["run", "bad.toml", "--out", "o"],
     _scene("particles = 200", f"particles = {LONG}"), 2,
     "bad.toml: line 5 (particles): an integer of 5000 digits"),
    ("scene a megabyte long", ["run", "big.toml", "--out", "o"],
     _write("big.toml", TINY + "# " + "x" * (1 << 20) + "\n"), 2,
     "scene file big.toml: 1048", ),
    ("scene a directory", ["run", "adir", "--out", "o"], _write("adir/x", "x"), 2,
     "scene file adir: a directory, not a regular file"),
    ("scene long text value", ["run", "bad.toml", "--out", "o"],
     _scene('eps = 0.6', 'eps = "' + "y" * 100_000 + '"'), 2, "eps must be a number, got"),
    ("scene widths twice", ["run", "bad.toml", "--out", "o"],
     _scene("widths = [1.0]", "widths = [1.0, 1.0]"), 2,
     "bad.toml: holes.widths lists 1.0 twice (the experiments are holes.centres x"
     " holes.widths"),
    ("scene widths print alike", ["run", "bad.toml", "--out", "o"],
     _scene("widths = [1.0]", "widths = [1.0, 1.00001]"), 2,
     "holes.widths 1.0 and 1.00001 both show as 1 in curve names"),
    ("scene quadratic drag 1e300", ["run", "bad.toml", "--out", "o"],
     _write("bad.toml", TINY + '[physics]\ndrag = 1e300\ndrag_law = "quadratic"\n'), 2,
     "bad.toml: physics.drag = 1e+300 (quadratic) stops a particle of speed 5.2"),
    ("scene linear drag 1e20", ["run", "bad.toml", "--out", "o"],
     _write("bad.toml", TINY + "[physics]\ndrag = 1e20\n"), 2,
     "float64 cannot run these flights; drag must be <= 2.81e+14 here"),
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
    ("verify manifest 5000-digit integer", ["verify", "run"],
     _manifest_text('"particles": 200', f'"particles": {LONG}'), 2,
     "run/manifest.json: field particles: an integer of 5000 digits"),
    ("verify manifest a directory", ["verify", "run"],
     lambda w: ((w / "run/manifest.json").unlink(), (w / "run/manifest.json").mkdir()), 2,
     "run/manifest.json: a directory, not a regular file"),
    ("verify scene.toml nested deep", ["verify", "run"], _write("run/scene.toml", DEEP_TOML),
     2, "run/scene.toml: not valid TOML: nested too deeply"),
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
    ("fit manifest 5000-digit integer", ["fit", "run", "--json"],
     _manifest_text('"particles_done": 200', f'"particles_done": {LONG}'), 2,
     "run/manifest.json: field curves.from hole 2: {'particles_done': an integer of 5000"
     " digits"),
    ("fit count 5000 digits", ["fit", "h.csv", "--json"],
     _write("h.csv", f"lower,upper,count\n0,1,{LONG}\n1,2,5\n"), 2,
     " characters) ...777"),
    ("fit field over csv's limit", ["fit", "h.csv", "--json"],
     _write("h.csv", "lower,upper,count\n0,1,\"" + "8" * 200_000 + "\"\n"), 2,
     "h.csv: not readable as CSV (field larger than field limit"),
    ("fit counts.csv a directory", ["fit", "run", "--json"],
     lambda w: ((w / "run/counts.csv").unlink(), (w / "run/counts.csv").mkdir()), 2,
     "run/counts.csv: a directory, not a regular file"),
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
    ("survival.csv CRLF, rehashed", _rehashed("survival.csv", lambda b: b.replace(b"\n", b"\r\n")),
     "survival.csv: its lines end in CRLF, the curve from counts.csv's in LF (the comparison is"
     " byte for byte)"),
    ("counts.csv CRLF, rehashed", _rehashed("counts.csv", lambda b: b.replace(b"\n", b"\r\n")),
     "counts.csv: its lines end in CRLF, the checkpoint's in LF"),
    ("survival.csv with a byte-order mark, rehashed",
     _rehashed("survival.csv", lambda b: b"\xef\xbb\xbf" + b),
     "survival.csv:1: the curve from counts.csv has 'curve,clock,x,p,p_lo,p_hi', the file"),
    ("provenance random bytes, rehashed", _rehashed("provenance.json", lambda b: os.urandom(600)),
     "provenance.json: not"),
    ("provenance of another shape, rehashed", _rehashed("provenance.json", lambda b: b"[1, 2]"),
     "provenance.json: [1, 2] is not of type 'object'"),
    ("provenance without a field, rehashed",
     _rehashed("provenance.json", lambda b: json.dumps(
         {k: v for k, v in json.loads(b).items() if k != "versions"}).encode()),
     "provenance.json: 'versions' is a required property"),
    ("survival.csv a directory", lambda w: ((w / "run/survival.csv").unlink(),
                                            (w / "run/survival.csv").mkdir()),
     "survival.csv: a directory, not a regular file"),
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


# ---- files that are not regular files, read-only folders, exports ---------------------------

def bouncer_process(argv, cwd, timeout=120):
    """``bouncer ARGV`` in a fresh process (a reader that blocks would hang this one)."""
    return subprocess.run([sys.executable, "-m", "reports.cli", *map(str, argv)], cwd=cwd,
                          capture_output=True, text=True, timeout=timeout,
                          env=dict(os.environ, PYTHONPATH=str(ROOT)))


@pytest.mark.slow
@pytest.mark.parametrize(("argv", "fifo", "status", "text"), [
    (["verify", "run", "--quiet"], "run/survival.csv", 1,
     "survival.csv: a FIFO (named pipe), not a regular file"),
    (["verify", "run", "--quiet"], "run/checkpoint.npz", 1,
     "checkpoint.npz: a FIFO (named pipe), not a regular file"),
    (["verify", "run"], "run/manifest.json", 2,
     "run/manifest.json: a FIFO (named pipe), not a regular file"),
    (["run", "tiny.toml", "--out", "run", "--resume"], "run/scene.toml", 2,
     "run/scene.toml: a FIFO (named pipe), not a regular file"),
    (["run", "pipe.toml", "--out", "o"], "pipe.toml", 2,
     "scene file pipe.toml: a FIFO (named pipe), not a regular file"),
    (["fit", "pipe.csv", "--json"], "pipe.csv", 2, "pipe.csv: a FIFO (named pipe), not a"
     " regular file"),
    (["fit", "run", "--json"], "run/counts.csv", 2, "run/counts.csv: a FIFO (named pipe)"),
    (["plot", "run", "--out", "p.png"], "run/survival.csv", 2,
     "run/survival.csv: a FIFO (named pipe)"),
])
def test_a_fifo_in_place_of_a_file_is_refused_without_waiting(argv, fifo, status, text, work):
    """Every file the command reads is opened without blocking and must be a regular file: a
    FIFO nobody writes to would otherwise hang the reader for good."""
    path = work / fifo
    path.unlink(missing_ok=True)
    os.mkfifo(path)
    before = tree(work)
    proc = bouncer_process(argv, work)
    assert proc.returncode == status, proc.stdout + proc.stderr
    assert "Traceback" not in proc.stderr
    assert text in (proc.stderr if status == 2 else proc.stdout), proc.stdout + proc.stderr
    if status == 2:
        assert len(proc.stderr.strip().splitlines()) == 1
    assert tree(work) == before


def test_fit_into_a_read_only_folder_is_one_line_and_leaves_nothing(work, monkeypatch, capsys):
    """The figures are written once every curve is analysed; one that cannot be written (a
    read-only file system) takes back those written before it and the folders made for them."""
    from reports.cli import fit

    real, calls = fit.write_atomic, []

    def read_only(path, data):
        calls.append(path)
        if len(calls) == 2:
            raise OSError(errno.EROFS, os.strerror(errno.EROFS), str(path))
        return real(path, data)

    monkeypatch.setattr(fit, "write_atomic", read_only)
    before = tree(work)
    assert bouncer(["fit", "run", "--clock", "collisions", "--jobs", "1", "--out",
                    "figs/deep"]) == 2
    line = one_line(capsys)
    assert line == f"bouncer fit: error: {calls[1]}: Read-only file system"
    assert tree(work) == before and not (work / "figs").exists()


def test_a_histogram_exported_with_a_byte_order_mark_is_read(work, capsys):
    """A spreadsheet's UTF-8 export starts with a byte-order mark: the header is still read."""
    rows = "lower,upper,count\n1,2,50\n2,4,30\n4,8,15\n8,inf,5\n"
    (work / "plain.csv").write_text(rows)
    (work / "marked.csv").write_bytes(b"\xef\xbb\xbf" + rows.encode())
    assert bouncer(["fit", "plain.csv", "--json", "--clock", "collisions"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert bouncer(["fit", "marked.csv", "--json", "--clock", "collisions"]) == 0
    marked = json.loads(capsys.readouterr().out)
    for result in plain + marked:
        result.pop("source")
        result.pop("curve")
    assert marked == plain


def test_a_scene_with_a_byte_order_mark_runs(work, capsys):
    (work / "marked.toml").write_bytes(b"\xef\xbb\xbf" + TINY.encode())
    assert bouncer(["run", "marked.toml", "--out", "m", "--quiet"]) == 0
    assert (work / "m" / "scene.toml").read_text() == TINY  # the scene as parsed
    assert bouncer(["verify", "m", "--quiet"]) == 0
