"""The audit of a finished run (``reports.runs.recheck``, ``bouncer verify RUN``) on a tiny
transport run and a tiny phase-space run, each fault alone (its hash updated where the deeper check
is the one under test), with the report's wording."""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest
from scene_texts import PORTRAIT, TINY, TINY_VELOCITY
from test_integrity import edit_csv as edit_rows

from reports.runs import driver, executor, rundir
from reports.runs.counts import Tally
from reports.runs.plan import make_plan
from reports.runs.recheck import _compare, _hashes, load_run, recheck
from reports.runs.rundir import RunInterrupted
from reports.runs.scenes import parse_scene


@pytest.fixture(scope="module")
def portrait_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("portrait") / "run"
    driver.run(parse_scene(PORTRAIT), out, progress=False)
    return out


def manifest_of(run_dir):
    return json.loads((run_dir / "manifest.json").read_text())


def edit_manifest(run_dir, edit):
    manifest = manifest_of(run_dir)
    edit(manifest)
    (run_dir / "manifest.json").write_text(json.dumps(manifest))


def rehash(run_dir, name):
    """Record the edited file's hash, as a careful forger would."""
    edit_manifest(run_dir, lambda m: m["hashes"].__setitem__(
        name, rundir.sha256_file(run_dir / name)))


def problems_of(lines):
    """The discrepancy lines of a report: between the 'not audited:' line and the verdict."""
    start = next(i for i, x in enumerate(lines) if x.startswith("not audited: "))
    return lines[start + 1:-1]


# ---- a clean run and the report's form ------------------------------------------------------

def test_clean_run_report(run):
    ok, lines = recheck(run)
    manifest = manifest_of(run)
    worst = manifest["verification"]["worst_error"]
    n = manifest["verification"]["sampled"]
    assert ok is True
    assert lines == [
        f"run {run}: scene tiny, status complete",
        f"{n} sampled collisions recomputed by verify: worst error {worst:.3g} kappa*u"
        f" (recorded {worst:.3g}), 0 overstepped (tolerance 16 kappa*u)",
        "checked: content hashes, checkpoint invariants, counts.csv and survival.csv"
        " re-derived, sample.csv, the sample replayed from the seed, every field of the"
        " manifest",
        "not audited: the content of provenance.json (how and when the run was made; its"
        " hash and its schema are checked)",
        "OK"]
    assert recheck(str(run))[0] is True  # a path given as a string


def test_clean_phase_space_report(portrait_run):
    ok, lines = recheck(portrait_run)
    assert ok is True and lines[-1] == "OK"
    assert lines[2] == ("checked: content hashes, checkpoint invariants, portrait.npy"
                        " re-derived, sample.csv, the sample replayed from the seed, every"
                        " field of the manifest")


def test_phase_space_portrait_must_match_the_checkpoint(portrait_run, tmp_path):
    run_dir = Path(shutil.copytree(portrait_run, tmp_path / "run"))
    portrait = np.load(run_dir / "portrait.npy")
    portrait[0, 0] += 1
    np.save(run_dir / "portrait.npy", portrait)
    rehash(run_dir, "portrait.npy")
    ok, lines = recheck(run_dir)
    assert not ok and problems_of(lines) == [
        "portrait.npy: differs from the checkpoint's portrait (or is missing)"]
    (run_dir / "portrait.npy").unlink()
    ok, lines = recheck(run_dir)
    assert problems_of(lines) == [
        "portrait.npy: missing (the manifest records its hash)",
        "portrait.npy: differs from the checkpoint's portrait (or is missing)"]


def test_phase_space_hashes_its_portrait(portrait_run, tmp_path):
    run_dir = Path(shutil.copytree(portrait_run, tmp_path / "run"))
    edit_manifest(run_dir, lambda m: m["hashes"].pop("portrait.npy"))
    ok, lines = recheck(run_dir)
    assert not ok and problems_of(lines) == ["manifest.json: no hash recorded for portrait.npy"]


def test_the_report_shows_twenty_discrepancies_and_counts_the_rest(run):
    """k edited sample errors (the file's hash updated): 2k discrepancies, each row differing
    from the checkpoint and from verify's recomputation."""
    def edit(k):
        edit_rows(run / "sample.csv", lambda rows: [r.__setitem__(10, "0.5")
                                                   for r in rows[1:k + 1]])
        rehash(run, "sample.csv")
        return recheck(run)

    original = (run / "sample.csv").read_bytes()
    ok, lines = edit(10)
    assert not ok and len(problems_of(lines)) == 20 and lines[-1] == "FAILED: 20 discrepancies"
    (run / "sample.csv").write_bytes(original)
    ok, lines = edit(11)
    assert lines[-2] == "... and 2 more" and lines[-1] == "FAILED: 22 discrepancies"
    assert len(problems_of(lines)) == 21  # 20 shown and the count of the rest


def test_recorded_worst_error_is_reported_and_checked(run):
    worst = manifest_of(run)["verification"]["worst_error"]
    edit_manifest(run, lambda m: m["verification"].__setitem__("worst_error", 0.125))
    ok, lines = recheck(run)
    assert "(recorded 0.125)" in lines[1]
    assert problems_of(lines) == [f"manifest.json: verification.worst_error is 0.125, the"
                                  f" checkpoint and sample give {worst!r}"]
    edit_manifest(run, lambda m: m["verification"].pop("worst_error"))
    with pytest.raises(ValueError, match=r"manifest.json: field verification: 'worst_error' is"
                                         r" a required property"):
        recheck(run)
    edit_manifest(run, lambda m: m.pop("verification"))
    with pytest.raises(ValueError, match="'verification' is a required property"):
        recheck(run)


# ---- what the run directory must hold -------------------------------------------------------

@pytest.mark.parametrize("name", ["manifest.json", "scene.toml"])
def test_not_a_run_directory(run, name):
    (run / name).unlink()
    with pytest.raises(ValueError, match=r"is not a run directory \(no manifest.json and"
                                         r" scene.toml\)"):
        load_run(run)


def test_unreadable_manifest_or_scene(run):
    (run / "scene.toml").write_bytes(b"\xff")
    with pytest.raises(ValueError, match=r"run/scene.toml: not UTF-8 text"):
        load_run(run)
    (run / "manifest.json").write_text("{not json")
    with pytest.raises(ValueError, match=r"run/manifest.json: not valid JSON \(Expecting"):
        load_run(run)


def test_load_run_names_the_scene_file_in_its_errors(run):
    manifest, scene = load_run(str(run))
    assert manifest["status"] == "complete" and scene.name == "tiny"
    (run / "scene.toml").write_text(TINY.replace("widths = [1.0]", "widths = [0.0]"))
    with pytest.raises(ValueError) as err:
        load_run(run)
    assert str(err.value).startswith(f"{run / 'scene.toml'}")


def test_a_partial_run_without_a_sample_cannot_be_verified_yet(run):
    edit_manifest(run, lambda m: m.__setitem__("status", "partial"))
    ok, lines = recheck(run)  # it has a sample: audited, and fails for being partial
    assert not ok and problems_of(lines) == [
        "manifest.json: the run is not complete (status partial)"]
    (run / "sample.csv").unlink()
    with pytest.raises(ValueError, match=r"has no sample.csv \(status partial\): nothing to"
                                         r" verify yet"):
        recheck(run)
    edit_manifest(run, lambda m: m.__setitem__("status", "complete"))
    ok, lines = recheck(run)  # complete without a sample: audited, and fails
    assert not ok and "sample.csv: missing (the manifest records its hash)" in lines
    assert "sample.csv is missing or not UTF-8 text" in lines


def test_an_interrupted_run_is_reported_with_its_finished_chunks(tmp_path, monkeypatch):
    real, calls = executor.run_chunk, []

    def stop_after_three(*args):
        calls.append(args)
        if len(calls) > 3:
            raise KeyboardInterrupt
        return real(*args)

    monkeypatch.setattr(executor, "run_chunk", stop_after_three)
    with pytest.raises(RunInterrupted):
        driver.run(parse_scene(TINY), tmp_path / "cut", progress=False, threads=1)
    monkeypatch.setattr(executor, "run_chunk", real)
    manifest = manifest_of(tmp_path / "cut")
    cut = tmp_path / "cut"
    assert not (cut / "sample.csv").is_file()
    with pytest.raises(ValueError, match="nothing to verify yet"):
        recheck(cut)
    plan = make_plan(parse_scene(TINY))
    (cut / "sample.csv").write_text(
        driver.result_files(plan, Tally.load(cut / "checkpoint.npz"))["sample.csv"])
    ok, lines = recheck(tmp_path / "cut")
    done = manifest["chunks_done"]
    assert not ok and 0 < done < 8
    assert f"checkpoint.npz: {done} of 8 chunks finished" in lines
    assert f"manifest.json: the run is not complete (status {manifest['status']})" in lines


# ---- hashes ---------------------------------------------------------------------------------

def test_hashes(run):
    manifest = manifest_of(run)
    expected = ["scene.toml", "sample.csv", "checkpoint.npz", "provenance.json", "survival.csv",
                "counts.csv"]
    assert _hashes(run, manifest, expected) == []
    assert _hashes(run, {"hashes": {}}, expected[:2]) == [
        "manifest.json: no hash recorded for scene.toml",
        "manifest.json: no hash recorded for sample.csv"]
    del manifest["hashes"]["counts.csv"]
    assert _hashes(run, manifest, expected) == ["manifest.json: no hash recorded for counts.csv"]
    manifest["hashes"]["portrait.npy"] = "0" * 64
    (run / "sample.csv").write_text("edited\n")
    assert _hashes(run, manifest, expected) == [
        "manifest.json: no hash recorded for counts.csv",
        "manifest.json: a hash recorded for portrait.npy, which this run does not write",
        "sample.csv: SHA-256 differs from the manifest's (edited or corrupted)",
        "portrait.npy: missing (the manifest records its hash)"]


def test_a_run_without_hashes_is_refused_or_fails_for_each_file(run):
    edit_manifest(run, lambda m: m["hashes"].clear())
    ok, lines = recheck(run)
    assert not ok and problems_of(lines) == [
        f"manifest.json: no hash recorded for {name}" for name in
        ("scene.toml", "sample.csv", "checkpoint.npz", "provenance.json", "survival.csv",
         "counts.csv")]
    edit_manifest(run, lambda m: m.pop("hashes"))
    with pytest.raises(ValueError, match="'hashes' is a required property"):
        recheck(run)


@pytest.mark.parametrize("name", ["../outside.csv", "/etc/passwd", ".bouncer.lock"])
def test_a_hash_for_a_file_outside_the_run_is_refused(run, name):
    """The audit reads only the files a run writes: a hash recorded under another name (a path
    out of the run directory) fails the manifest's schema before anything is opened."""
    edit_manifest(run, lambda m: m["hashes"].__setitem__(name, "0" * 64))
    with pytest.raises(ValueError, match="field hashes: .* is not one of"):
        recheck(run)


# ---- line comparisons ------------------------------------------------------------------------

def test_compare_names_lines_from_one_and_counts_them():
    assert _compare("f.csv", "a\nb\nc\n", "a\nb\nc\n", "w") == []
    assert _compare("f.csv", "a\nb\nc\n", "a\nB\nc\n", "w") == ["f.csv:2: w has 'b', the file 'B'"]
    assert _compare("f.csv", "a\nb\n", "a\nb\nc\n", "w") == ["f.csv: 3 lines, w has 2"]
    assert _compare("f.csv", "a\nb\nc\n", "x\nb\n", "w") == [
        "f.csv:1: w has 'a', the file 'x'", "f.csv: 2 lines, w has 3"]


def test_worst_error_nan_is_not_equal(run):
    """A manifest field compared by type and value: a NaN worst error is a discrepancy."""
    edit_manifest(run, lambda m: m["verification"].__setitem__("worst_error", math.nan))
    assert not recheck(run)[0]


# ---- the manifest's figures ------------------------------------------------------------------

FIGURES = [("collisions",), ("chunks_done",), ("chunks",), ("particles_total",),
           ("verification", "sampled"), ("verification", "uncertain_settled"),
           ("curves", "from hole 1", "censored"), ("curves", "from hole 2", "stuck"),
           ("curves", "from hole 1", "escaped", "P12"), ("curves", "from hole 2", "escaped", "P21")]


def _at(manifest, path):
    for key in path[:-1]:
        manifest = manifest[key]
    return manifest, path[-1]


@pytest.mark.parametrize("path", FIGURES, ids=".".join)
def test_each_manifest_figure_is_checked(run, path):
    key = ".".join(path)
    value = _at(manifest_of(run), path)[0][path[-1]]
    edit_manifest(run, lambda m: _at(m, path)[0].__setitem__(path[-1], value + 1))
    ok, lines = recheck(run)
    source = "the plan gives" if path[0] in ("chunks", "particles_total") else \
        "the checkpoint and sample give"
    assert not ok and problems_of(lines) == [
        f"manifest.json: {key} is {value + 1!r}, {source} {value!r}"]


def test_a_curve_missing_from_the_manifest_is_a_discrepancy(run):
    curve = manifest_of(run)["curves"]["from hole 2"]
    edit_manifest(run, lambda m: m["curves"].pop("from hole 2"))
    assert problems_of(recheck(run)[1]) == [
        f"manifest.json: curves.from hole 2 is None, the checkpoint and sample give {curve!r}"]


@pytest.mark.parametrize("path", [("verification",), ("curves",),
                                  ("curves", "from hole 2", "escaped")], ids=".".join)
def test_missing_manifest_sections_are_refused_by_the_schema(run, path):
    edit_manifest(run, lambda m: _at(m, path)[0].pop(path[-1]))
    with pytest.raises(ValueError) as err:
        recheck(run)
    assert str(err.value).startswith(f"{run / 'manifest.json'}: ")
    assert "\n" not in str(err.value)


ESCAPE = """
name = "one-clock"
kind = "escape"
eps = 0.6
particles = 150
seed = 4
chunk_size = 64
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.5]
[horizon]
collisions = 40
time = 8.0
[record]
verify_samples = 6
[physics]
restitution = 0.5
"""


@pytest.mark.parametrize("clock", ["collisions", "time"])
def test_a_one_clock_run_passes_and_its_figures_are_that_clocks(tmp_path, clock):
    """The manifest's escaped / censored / stuck figures come from the first recorded clock; a
    run that records only one clock has nothing on the other (restitution 0.5: some stick)."""
    scene = parse_scene(ESCAPE.replace("[record]", f'[record]\nclocks = ["{clock}"]'))
    driver.run(scene, tmp_path / "run", progress=False)
    curve = manifest_of(tmp_path / "run")["curves"]["phi_c=2"]
    assert curve["censored"] > 0 and curve["escaped"]["phi_c=2"] > 0 and curve["stuck"] > 0
    ok, lines = recheck(tmp_path / "run")
    assert ok is True, lines
    for key in ("censored", "stuck"):
        edit_manifest(tmp_path / "run", lambda m, k=key: m["curves"]["phi_c=2"].__setitem__(k, 0))
        assert problems_of(recheck(tmp_path / "run")[1]) == [
            f"manifest.json: curves.phi_c=2.{key} is 0, the checkpoint and sample give"
            f" {curve[key]}"]
        edit_manifest(tmp_path / "run",
                      lambda m, k=key: m["curves"]["phi_c=2"].__setitem__(k, curve[k]))


# ---- the output files ------------------------------------------------------------------------

def test_edited_counts_with_its_hash_updated(run):
    edit_rows(run / "counts.csv", lambda rows: rows[3].__setitem__(4, str(int(rows[3][4]) + 1)))
    rehash(run, "counts.csv")
    line = (run / "counts.csv").read_text().splitlines()[3]
    ok, lines = recheck(run)
    found = problems_of(lines)
    assert not ok and found[0].startswith("counts.csv:4: the checkpoint has '")
    assert found[0].endswith(f"the file '{line}'")
    assert found[1] == ("counts.csv:2: curve 'from hole 1', clock collisions: 200 escaped + 1"
                        " censored + 0 stuck = 201, but 200 particles were run")
    assert all(x.startswith("survival.csv:") for x in found[2:]) and len(found) > 2


def test_forged_counts_and_survival_without_checkpoint(run):
    """A forger who edits counts.csv, writes survival.csv from it with the run's own writer,
    deletes the checkpoint and records the new hashes: the invariant and the range of the
    survival curve still fail, by line."""
    from reports.runs.driver import survival_rows
    from reports.runs.integrity import parse_counts

    edit_rows(run / "counts.csv", lambda rows: rows[1].__setitem__(4, str(int(rows[1][4]) + 50)))
    plan = make_plan(parse_scene(TINY))
    counts = parse_counts(plan, (run / "counts.csv").read_text())[0]
    with np.errstate(invalid="ignore"):
        text = rundir.csv_text(["curve", "clock", "x", "p", "p_lo", "p_hi"],
                               survival_rows(plan, counts))
    (run / "survival.csv").write_text(text)
    (run / "checkpoint.npz").unlink()
    for name in ("counts.csv", "survival.csv"):
        rehash(run, name)
    edit_manifest(run, lambda m: m["hashes"].pop("checkpoint.npz"))
    ok, lines = recheck(run)
    found = problems_of(lines)
    assert not ok and found[0] == "manifest.json: no hash recorded for checkpoint.npz"
    assert found[1].startswith("checkpoint ") and "is unreadable" in found[1]
    assert found[2] == ("counts.csv:2: curve 'from hole 1', clock collisions: 249 escaped + 1"
                        " censored + 0 stuck = 250, but 200 particles were run")
    assert found[3] == ("survival.csv:2: P11 (collisions): p 1.15 with band [nan, nan] is not"
                        " 0 <= p_lo <= p <= p_hi <= 1")  # the time clock's rows are unchanged
    assert not any("the checkpoint has" in x for x in found)  # nothing to compare with


@pytest.mark.parametrize("name", ["counts.csv", "survival.csv", "sample.csv"])
def test_output_that_is_not_utf8(run, name):
    (run / name).write_bytes(b"\xff\xfe not text\n")
    rehash(run, name)
    ok, lines = recheck(run)
    message = ("sample.csv is missing or not UTF-8 text" if name == "sample.csv"
               else "counts.csv or survival.csv is missing or not UTF-8 text")
    assert not ok and message in problems_of(lines)


def test_a_sample_that_is_not_utf8_fails_the_audit_naming_the_file(run, capsys):
    """Not an error exit without the file's name (exit 2, 'codec can't decode'): a failed
    audit (exit 1) that names sample.csv."""
    from reports.cli import main

    (run / "sample.csv").write_bytes(b"\xff\xfe not text\n")
    assert main(["verify", str(run), "--quiet"]) == 1
    out = capsys.readouterr().out
    assert "sample.csv is missing or not UTF-8 text" in out and "FAILED" in out


def test_edited_sample_row_with_its_hash_updated(run):
    edit_rows(run / "sample.csv", lambda rows: rows[3].__setitem__(10, "0.5"))
    rehash(run, "sample.csv")
    line = (run / "sample.csv").read_text().splitlines()[3]
    found = problems_of(recheck(run)[1])
    assert found[0].startswith("sample.csv:4: the checkpoint has '")
    assert found[0].endswith(f"the file '{line}'") and len(found) == 2
    assert found[1].startswith("sample.csv:4: verify gives tau_ref ")


@pytest.fixture(scope="module")
def velocity_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("velocity") / "run"
    driver.run(parse_scene(TINY_VELOCITY), out, progress=False)
    return out


def test_velocity_run_report_and_missing_file(velocity_run, tmp_path):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    ok, lines = recheck(run_dir)
    assert ok is True and lines[2] == ("checked: content hashes, checkpoint invariants,"
                                       " velocity.csv re-derived, sample.csv, the sample"
                                       " replayed from the seed, every field of the manifest")
    (run_dir / "velocity.csv").write_bytes(b"\xff")
    rehash(run_dir, "velocity.csv")
    assert problems_of(recheck(run_dir)[1]) == ["velocity.csv is missing or not UTF-8 text"]


def test_velocity_file_is_compared_and_checked(velocity_run, tmp_path):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    rows = (run_dir / "velocity.csv").read_text().splitlines()
    cells = rows[3].split(",")
    cells[2] = str(int(cells[2]) - 1)  # one particle lost at a grid point
    rows[3] = ",".join(cells)
    (run_dir / "velocity.csv").write_text("\n".join(rows) + "\n")
    rehash(run_dir, "velocity.csv")
    found = problems_of(recheck(run_dir)[1])
    assert found[0].startswith("velocity.csv:4: the checkpoint has '")
    assert any("moving" in x and ":4:" in x for x in found[1:])


@pytest.mark.parametrize("key", ["moving", "stuck", "mean_v_at_horizon"])
def test_velocity_manifest_figures(velocity_run, tmp_path, key):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    value = manifest_of(run_dir)["curves"]["r=0.9"][key]
    edit_manifest(run_dir, lambda m: m["curves"]["r=0.9"].__setitem__(key, value + 1))
    assert problems_of(recheck(run_dir)[1]) == [
        f"manifest.json: curves.r=0.9.{key} is {value + 1!r}, the checkpoint and sample give"
        f" {value!r}"]
    edit_manifest(run_dir, lambda m: m["curves"]["r=0.9"].__setitem__("particles_done", 7))
    assert ("manifest.json: curves.r=0.9.particles_done is 7, the checkpoint and sample give 100"
            in problems_of(recheck(run_dir)[1]))


# ---- the recomputed sample -------------------------------------------------------------------

def edit_sample(run_dir, edits):
    """edits: {line: {column: value}} (lines numbered from the header, 1)."""
    def edit(rows):
        header = rows[0]
        for line, cells in edits.items():
            for col, value in cells.items():
                rows[line - 1][header.index(col)] = value
    edit_rows(run_dir / "sample.csv", edit)
    rehash(run_dir, "sample.csv")


def sample_problems(run_dir):
    """The discrepancies of step 5 (the recomputed sample): not the comparison with the
    checkpoint, nor the replay from the seed (an edited state fails that too)."""
    return [x for x in problems_of(recheck(run_dir)[1])
            if x.startswith("sample.csv:") and "the checkpoint has" not in x
            and "drawn from seed" not in x]


def test_a_sample_row_verify_refuses_fails_the_audit_by_line(run, capsys):
    """v = -1 is no departure: fastpath and verify both refuse it. Without the guard verify's
    ValueError ended the audit (exit 2, no file or line named)."""
    from reports.cli import main

    edit_sample(run, {3: {"v": "-1.0"}})
    found = sample_problems(run)
    assert found[0].startswith("sample.csv:3: fastpath.step refuses the row: not a departure")
    assert found[1].startswith("sample.csv:3: verify refuses the row: no departure")
    assert len(found) == 2
    assert main(["verify", str(run), "--quiet"]) == 1
    assert "sample.csv:3: verify refuses the row" in capsys.readouterr().out


def test_unparsable_sample_rows_are_named_and_the_rest_checked(run):
    edit_sample(run, {2: {"phi": "x"}, 3: {"experiment": "x"}, 4: {"experiment": "x"},
                       5: {"tau_ref": ""}, 6: {"error": "0.5"}})
    found = sample_problems(run)
    assert found[:4] == [
        "sample.csv:2: not a sample row",
        "sample.csv:3: not a sample row (experiment)",
        "sample.csv:4: not a sample row (experiment)",
        "sample.csv:5: not a sample row"]
    assert found[4].startswith("sample.csv:6: verify gives tau_ref ") and len(found) == 5


def test_a_velocity_sample_row_of_no_curve(velocity_run, tmp_path):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    edit_sample(run_dir, {2: {"experiment": "9"}})
    assert sample_problems(run_dir) == ["sample.csv:2: not a sample row (experiment)"]


def test_a_fast_result_not_reproduced_bit_for_bit(run):
    rows = (run / "sample.csv").read_text().splitlines()
    phi1 = float(rows[3].split(",")[6])
    edit_sample(run, {4: {"phi1": repr(float(np.nextafter(phi1, 10.0)))}})
    found = sample_problems(run)
    assert len(found) == 1 and found[0].startswith("sample.csv:4: fastpath.step gives (")
    assert found[0].endswith(f", the file ({float(np.nextafter(phi1, 10.0))!r}, "
                             f"{float(rows[3].split(',')[7])!r}, "
                             f"{float(rows[3].split(',')[8])!r}) (not reproduced bit for bit)")


def test_an_overstep_is_counted_in_the_report(run):
    rows = (run / "sample.csv").read_text().splitlines()
    tau = float(rows[1].split(",")[8])
    edit_sample(run, {2: {"tau": repr(tau * (1 + 1e-9))}})
    ok, lines = recheck(run)
    assert not ok and ", 1 overstepped (tolerance 16 kappa*u)" in lines[1]
    assert ("sample.csv:2: OVERSTEP: tau exceeds verify's first root by more than"
            " 16*kappa*u") in lines


def test_progress_bar_counts_the_recomputed_collisions(run, capsys):
    n = manifest_of(run)["verification"]["sampled"]
    assert recheck(run, progress=True)[0] is True
    err = capsys.readouterr().err
    assert "verify sample" in err and f"{n}/{n}" in err and "collision/s" in err
    assert recheck(run, progress=False)[0] is True
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize(("key", "value"), [("censored", 5), ("stuck", 1)])
def test_a_forged_phase_space_curve_figure_fails(portrait_run, tmp_path, key, value):
    """The driver writes curves.portrait (zeros: a portrait records no escapes); the audit checks
    those figures for phase-space runs too, and fails a forged one."""
    run_dir = Path(shutil.copytree(portrait_run, tmp_path / "run"))
    edit_manifest(run_dir, lambda m: m["curves"]["portrait"].__setitem__(key, value))
    ok, lines = recheck(run_dir)
    assert not ok and problems_of(lines) == [
        f"manifest.json: curves.portrait.{key} is {value}, the checkpoint and sample give 0"]


def test_velocity_manifest_without_its_curves(velocity_run, tmp_path):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    curve = manifest_of(run_dir)["curves"]["r=0.9"]
    edit_manifest(run_dir, lambda m: m["curves"].pop("r=0.9"))
    assert problems_of(recheck(run_dir)[1]) == [
        f"manifest.json: curves.r=0.9 is None, the checkpoint and sample give {curve!r}"]
    edit_manifest(run_dir, lambda m: m.pop("curves"))
    with pytest.raises(ValueError, match="'curves' is a required property"):
        recheck(run_dir)


def test_velocity_run_totals_are_checked_too(velocity_run, tmp_path):
    run_dir = Path(shutil.copytree(velocity_run, tmp_path / "run"))
    value = manifest_of(run_dir)["collisions"]
    edit_manifest(run_dir, lambda m: m.__setitem__("collisions", value + 1))
    assert problems_of(recheck(run_dir)[1]) == [
        f"manifest.json: collisions is {value + 1}, the checkpoint and sample give {value}"]


def test_no_progress_bar_unless_asked(run, capsys):
    assert recheck(run)[0] is True
    assert capsys.readouterr().err == ""


def test_the_plan_is_the_manifests_seed_and_particles(run, capsys):
    """The audit plans the run from the manifest's particles and seed (not the scene's): a
    seed make_plan refuses is an error (exit 2, one line), never a passed audit."""
    from reports.cli import main

    edit_manifest(run, lambda m: m.__setitem__("seed", -1))
    assert main(["verify", str(run), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bouncer: ") and "seed" in err and err.count("\n") == 1


def test_a_forged_checkpoint_that_breaks_the_invariants(run):
    """Its own digest recomputed and its hash recorded: the invariants name the fault, and the
    outputs are then checked from counts.csv alone (the checkpoint is not used)."""
    path = run / "checkpoint.npz"
    tally = Tally.load(path)
    tally.cens_n[0, 3] += 40
    tally.save(path)
    rehash(run, "checkpoint.npz")
    ok, lines = recheck(run)
    assert not ok and problems_of(lines) == [
        "checkpoint.npz: curve 'from hole 1', clock collisions: 199 escaped + 41 censored + 0"
        " stuck = 240, but 200 particles were run"]
