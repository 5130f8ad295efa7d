"""``bouncer verify RUN_DIR``: audit a run directory and recompute its verification sample.

Discrepancies are reported by file and line; any one fails the audit (exit status 1). A
manifest.json that is not valid JSON of the manifest's schema (``reports.runs.manifest``) or an
invalid scene.toml is not audited at all: ValueError, exit status 2.

1. hashes: every file the run writes (outputs, scene, checkpoint, sample, provenance.json) has
   its SHA-256 in the manifest, and the file has that SHA-256;
2. the checkpoint passes its own digest and the invariants of ``reports.runs.integrity``, and
   holds every chunk of the plan;
3. counts.csv equals the counts.csv written from the checkpoint; survival.csv equals the one
   re-derived from counts.csv by the run's own writer (byte for byte), lies in [0, 1] and does not
   rise; per curve escapes + censored + stuck = particles (portrait.npy for phase-space scenes;
   velocity.csv for velocity scenes: equal to the one written from the checkpoint, moving +
   stuck = particles at every grid point, mean_v**2 <= mean_v2);
4. sample.csv equals the checkpoint's sample;
5. for every row of sample.csv (a pre-collision state (phi, v) and the fast result):
   ``fastpath.step(phi, v, eps)`` gives the stored (phi1, v1, tau) bit for bit (with
   restitution < 1 ``fastpath.carried_step`` from (phi, v) and the row's carried state, which
   it checks is a departure from (phi, v): the step the kernel made), and ``verify.step`` from
   (phi, v) gives the stored tau_ref and error again; an overstep
   tau - tau_ref > 16*kappa*u*tau_ref fails the check;
6. the seed: every row is a verification pick drawn from the manifest's seed, and its state is
   replayed from the start drawn from the seed (``reports.runs.replay``);
7. joint.csv (scenes with ``[record] joint``): equal to the one written from the checkpoint,
   every row a bin of this run, every particle in one bin, and its marginals equal to
   counts.csv's histograms (``reports.runs.joint_file``);
8. every field of the manifest equals the one the run's writer builds from scene.toml, the
   seed, the particle count, the checkpoint and the recomputed sample (``manifest.build``), and
   the status is complete.
"""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

import numpy as np

import fastpath
from reports.runs import manifest as manifests
from reports.runs import rundir
from reports.runs.chunk import OVERSTEP_TOLERANCE, check_sample
from reports.runs.counts import CheckpointError, Tally
from reports.runs.driver import result_files, survival_rows
from reports.runs.echo import clip
from reports.runs.integrity import curve_problems, parse_counts, survival_problems, tally_problems
from reports.runs.joint_file import (
    JOINT_FILE,
    joint_problems,
    joint_text,
    marginal_problems,
    parse_joint,
)
from reports.runs.plan import make_plan
from reports.runs.replay import SampleRow, replay_problems
from reports.runs.rundir import CARRIED_COLUMNS
from reports.runs.scenes import parse_scene
from reports.runs.velocity import file_problems as velocity_file_problems

SHOWN = 5  # discrepancies shown per check; the count of all of them is reported
SHOWN_LINE = 300  # characters of a line shown in a discrepancy
_SURVIVAL = "counts.csv and survival.csv"
_REDERIVED = {"phase-space": "portrait.npy", "velocity": "velocity.csv"}
_JOINT_CHECKED = "joint.csv (against the checkpoint, its marginals against counts.csv), "


def load_run(run_dir):
    """(manifest, scene) of a run directory, the manifest validated against its schema;
    ValueError (one line naming the file) if it is not a readable run directory."""
    run_dir = Path(run_dir)
    if not (run_dir / rundir.MANIFEST).exists() or not (run_dir / "scene.toml").exists():
        raise ValueError(f"{run_dir} is not a run directory (no manifest.json and scene.toml)")
    manifest = manifests.load_manifest(run_dir / rundir.MANIFEST)
    return manifest, read_scene(run_dir)


def read_scene(run_dir):
    """The scene of the run directory's scene.toml (a regular UTF-8 file of bounded size, a
    valid scene); ValueError naming the file otherwise."""
    path = Path(run_dir) / "scene.toml"
    return parse_scene(rundir.read_input_text(path, rundir.MAX_SCENE_BYTES), str(path))


def _text(path):
    """The UTF-8 text of an output file, or None (missing, not a regular file of bounded size,
    not UTF-8): the checks that need it report it."""
    try:
        return rundir.read_input_text(path)
    except (OSError, ValueError):
        return None


def _compare(name, expected, found, what):
    """Differences of two texts, byte for byte: one line if the line ends differ (CRLF or CR
    where the writer writes LF), then ["name:LINE: ..."] per line whose text differs, the line
    counts if they differ, and one line for any other difference of bytes."""
    if expected == found:
        return []
    out = []
    ends = _line_ends(found)
    if ends != _line_ends(expected):
        out.append(f"{name}: its lines end in {ends}, {what}'s in {_line_ends(expected)} (the"
                   " comparison is byte for byte)")
    exp, got = expected.splitlines(), found.splitlines()
    out += [f"{name}:{i}: {what} has {_shown(e)}, the file {_shown(g)}"
            for i, (e, g) in enumerate(zip(exp, got, strict=False), start=1) if e != g]
    if len(exp) != len(got):
        out.append(f"{name}: {len(got)} lines, {what} has {len(exp)}")
    if not out:  # the same lines and line ends, other bytes: the end of the last line
        out.append(f"{name}: the end of its last line differs from {what}'s")
    return out


def _line_ends(text):
    """How the lines of a text end: "LF", "CRLF", "CR" or a mixture of them."""
    crlf = text.count("\r\n")
    kinds = [kind for kind, count in (("LF", text.count("\n") - crlf), ("CRLF", crlf),
                                      ("CR", text.count("\r") - crlf)) if count]
    return " and ".join(kinds) or "no line end"


def _shown(line):
    return repr(clip(line, SHOWN_LINE))


def _hashes(run_dir, manifest, expected):
    recorded = manifest["hashes"]
    out = [f"manifest.json: no hash recorded for {name}" for name in expected
           if name not in recorded]
    out += [f"manifest.json: a hash recorded for {name}, which this run does not write"
            for name in recorded if name not in expected]
    for name, digest in recorded.items():
        path = run_dir / name
        try:
            if rundir.sha256_file(path) != digest:
                out.append(f"{name}: SHA-256 differs from the manifest's (edited or corrupted)")
        except FileNotFoundError:
            out.append(f"{name}: missing (the manifest records its hash)")
        except (OSError, ValueError) as err:  # a FIFO, a directory, a device, too large
            out.append(f"{name}: {_reason(err, path)}")
    return out


def _reason(err, path):
    """What is wrong with an unreadable file, without its path (the line names it)."""
    text = rundir.os_error_text(err) if isinstance(err, OSError) else str(err)
    return text.removeprefix(f"{path}: ")


def _provenance(run_dir):
    """provenance.json must be the record its schema describes (``manifest.PROVENANCE_SCHEMA``);
    its content cannot be checked beyond that (how and when the run was made)."""
    try:
        manifests.load_provenance(run_dir)
    except ValueError as err:
        return [str(err).replace(f"{Path(run_dir) / rundir.PROVENANCE}", rundir.PROVENANCE, 1)]
    return []


def _outputs(run_dir, plan, tally):
    """Steps 3 and 4 of the module docstring for the files that hold counts and the sample;
    without a usable checkpoint (``tally`` None) only what counts.csv alone allows."""
    out = []
    written = result_files(plan, tally) if tally is not None else {}
    if plan.scene.kind == "phase-space":
        try:
            data = rundir.read_input(run_dir / "portrait.npy")
        except (OSError, ValueError):
            data = None
        if tally is not None and data != written["portrait.npy"]:
            out.append("portrait.npy: differs from the checkpoint's portrait (or is missing)")
    elif plan.scene.kind == "velocity":
        text = _text(run_dir / "velocity.csv")
        if text is None:
            return out + ["velocity.csv is missing or not UTF-8 text"]
        if tally is not None:
            out += _compare("velocity.csv", written["velocity.csv"], text, "the checkpoint")
        try:
            out += velocity_file_problems(plan, text)
        except csv.Error as err:  # a bare CR, a field over csv's size limit
            out.append(f"velocity.csv: not readable as CSV ({err})")
    else:
        counts_text, survival_text = _text(run_dir / "counts.csv"), _text(run_dir / "survival.csv")
        if counts_text is None or survival_text is None:
            return out + ["counts.csv or survival.csv is missing or not UTF-8 text"]
        if tally is not None:
            out += _compare("counts.csv", written["counts.csv"], counts_text, "the checkpoint")
        try:
            counts, stuck, problems, first = parse_counts(plan, counts_text)
        except csv.Error as err:  # a bare CR, a field over csv's size limit
            out.append(f"counts.csv: not readable as CSV ({err})")
        else:
            out += problems
            done = [plan.particles] * len(plan.experiments)
            out += [f"counts.csv:{first.get((e, clock), '?')}: {msg}"
                    for e, clock, msg in curve_problems(plan, counts, done, stuck)]
            with np.errstate(invalid="ignore"):  # inconsistent counts give p > 1: reported below
                derived = rundir.csv_text(["curve", "clock", "x", "p", "p_lo", "p_hi"],
                                          survival_rows(plan, counts))
            out += _compare("survival.csv", derived, survival_text, "the curve from counts.csv")
        try:
            out += survival_problems(survival_text)
        except csv.Error as err:
            out.append(f"survival.csv: not readable as CSV ({err})")
    sample_text = _text(run_dir / "sample.csv")
    if sample_text is None:
        out.append("sample.csv is missing or not UTF-8 text")
    elif tally is not None:
        out += _compare("sample.csv", written["sample.csv"], sample_text, "the checkpoint")
    return out


def _joint_outputs(run_dir, plan, tally):
    """Step 7: joint.csv against the checkpoint, the plan and counts.csv (nothing to check for
    a scene without a joint record: the hashes step refuses a joint.csv it does not write)."""
    if not plan.scene.joint:
        return []
    text = _text(run_dir / JOINT_FILE)
    if text is None:
        return [f"{JOINT_FILE} is missing or not UTF-8 text"]
    out = []
    if tally is not None:
        out += _compare(JOINT_FILE, joint_text(plan, tally.joint), text, "the checkpoint")
    counts_text = _text(run_dir / "counts.csv")
    try:
        joint, problems = parse_joint(plan, text)
        counts, _, count_problems, _ = parse_counts(plan, counts_text or "")
    except csv.Error as err:
        return out + [f"{JOINT_FILE} or counts.csv: not readable as CSV ({err})"]
    out += problems
    out += [f"{JOINT_FILE}: {msg}" for msg in
            joint_problems(plan, joint, [plan.particles] * len(plan.experiments))]
    if not count_problems:  # (counts.csv's own problems are reported by _outputs)
        out += marginal_problems(plan, joint, counts)
    return out


_SOURCES = {"scene": "scene.toml gives", "chunk_size": "scene.toml gives",
            "seed": "the plan gives", "particles": "the plan gives",
            "particles_total": "the plan gives", "chunks": "the plan gives",
            "bins": "the histograms' bins are", "survival_band": "survival.csv's band is"}


def _manifest_fields(manifest, plan, tally, worst):
    """Step 7: every field of the manifest against the one built from what produced the
    outputs; without a usable checkpoint (``tally`` None) the fields of the plan only."""
    expected = manifests.build(plan, tally or Tally.empty(plan), "complete", manifest["hashes"])
    fields = manifests.PLAN_FIELDS + (manifests.COUNT_FIELDS if tally is not None else ())
    out = []
    for key in fields:
        source = _SOURCES.get(key, "the checkpoint and sample give")
        out += [f"manifest.json: {path} is {got!r}, {source} {want!r}"
                for path, got, want in manifests.differences(manifest[key], expected[key], key)]
    if "failure" in manifest:
        out.append(f"manifest.json: records a failure: {manifest['failure']}")
    recorded = manifest["verification"]["worst_error"]
    if recorded != worst and not any(": verification.worst_error is " in x for x in out):
        out.append(f"manifest.json: verification.worst_error is {recorded!r}, verify gives"
                   f" {worst!r} for sample.csv")
    return out


def _bar(progress, total, desc):
    if not progress:
        return None
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit="collision", file=sys.stderr)


def _sample(run_dir, scene, progress):
    """Step 5: (rows, worst recomputed error, overstepped lines, discrepancies, the rows as
    ``SampleRow`` for the replay)."""
    # a missing or non-UTF-8 sample.csv is reported by _outputs: no rows to recompute
    text = _text(run_dir / "sample.csv")
    worst, overstepped, out = 0.0, [], []
    try:
        rows = list(csv.DictReader(io.StringIO(text, newline=""))) if text is not None else []
    except csv.Error as err:  # a field over csv's size limit
        rows = []
        out.append(f"sample.csv: not readable as CSV ({err})")
    bar = _bar(progress, len(rows), "verify sample")
    parsed = []
    for line, row in enumerate(rows, start=2):
        try:
            phi, v = float(row["phi"]), float(row["v"])
            stored = (float(row["phi1"]), float(row["v1"]), float(row["tau"]))
            tau_ref, error = float(row["tau_ref"]), float(row["error"])
            carried = [float(row[c]) for c in CARRIED_COLUMNS] if scene.carries else None
        except (KeyError, TypeError, ValueError):
            out.append(f"sample.csv:{line}: not a sample row")
            continue
        try:
            physics = scene.curve_physics(int(row["experiment"]))
        except (KeyError, ValueError, IndexError):
            out.append(f"sample.csv:{line}: not a sample row (experiment)")
            continue
        try:
            parsed.append(SampleRow(line, int(row["experiment"]), int(row["chunk"]),
                                    int(row["particle"]), int(row["n"]), phi, v))
        except (KeyError, TypeError, ValueError):
            out.append(f"sample.csv:{line}: not a sample row (chunk, particle or n)")
        carries = physics.get("restitution", 1.0) < 1.0
        name = "fastpath.carried_step" if carries else "fastpath.step"
        try:
            fast = tuple(fastpath.carried_step(phi, v, scene.eps, carried, **physics)
                         if carries else fastpath.step(phi, v, scene.eps, **physics))
            if fast != stored:
                out.append(f"sample.csv:{line}: {name} gives {fast}"
                           f", the file {stored} (not reproduced bit for bit)")
        except (ValueError, fastpath.UncertainCollision) as err:
            out.append(f"sample.csv:{line}: {name} refuses the row: {err}")
        try:
            ref, err, overstep = (check_sample(phi, v, stored[2], scene.eps, physics)
                                  if physics else check_sample(phi, v, stored[2], scene.eps))
        except (ValueError, ArithmeticError) as refusal:  # verify's refusals: no departure, ...
            out.append(f"sample.csv:{line}: verify refuses the row: {refusal}")
            continue
        worst = max(worst, err)
        if (ref, err) != (tau_ref, error):
            out.append(f"sample.csv:{line}: verify gives tau_ref {ref!r}, error {err!r}; the file"
                       f" {tau_ref!r}, {error!r}")
        if overstep:
            overstepped.append(line)
            out.append(f"sample.csv:{line}: OVERSTEP: tau exceeds verify's first root by more"
                       f" than {OVERSTEP_TOLERANCE:g}*kappa*u")
        if bar is not None:
            bar.update()
    if bar is not None:
        bar.close()
    return rows, worst, overstepped, out, parsed


def recheck(run_dir, progress=False):
    """Audit the run directory (module docstring); returns (ok, report lines). ValueError for
    a directory that is not a run, or whose manifest or scene.toml is unreadable."""
    run_dir = Path(run_dir)
    manifest, scene = load_run(run_dir)
    status = manifest["status"]
    lines = [f"run {run_dir}: scene {scene.name}, status {status}"]
    if not (run_dir / "sample.csv").exists() and status != "complete":
        raise ValueError(f"{run_dir} has no sample.csv (status {status}): nothing to verify yet")
    try:
        plan = make_plan(scene, manifest["particles"], manifest["seed"])
    except ValueError as err:
        raise ValueError(f"{run_dir / 'scene.toml'}: {err}") from None
    problems = _hashes(run_dir, manifest, manifests.hashed_files(scene))
    problems += _provenance(run_dir)
    try:
        if (run_dir / rundir.CHECKPOINT).exists():  # (a missing one: Tally.load says so)
            rundir.check_input(run_dir / rundir.CHECKPOINT)
        tally = Tally.load(run_dir / rundir.CHECKPOINT)
    except (CheckpointError, OSError, ValueError) as err:
        tally = None
        problems.append(str(err) if isinstance(err, CheckpointError) else
                        f"{rundir.CHECKPOINT}: {_reason(err, run_dir / rundir.CHECKPOINT)}")
    if tally is not None:
        invariants = tally_problems(plan, tally)
        problems += [f"{rundir.CHECKPOINT}: {msg}" for msg in invariants]
        if invariants:
            tally = None
        elif len(tally.finished) != plan.n_chunks:
            problems.append(f"{rundir.CHECKPOINT}: {len(tally.finished)} of {plan.n_chunks}"
                            " chunks finished")
    problems += _outputs(run_dir, plan, tally)
    problems += _joint_outputs(run_dir, plan, tally)
    rows, worst, overstepped, sample_problems, parsed = _sample(run_dir, scene, progress)
    problems += sample_problems
    bar = _bar(progress, len(parsed), "replay from the seed")
    problems += replay_problems(plan, parsed, bar.update if bar is not None else None)
    if bar is not None:
        bar.close()
    problems += _manifest_fields(manifest, plan, tally, worst)
    if status != "complete":
        problems.append(f"manifest.json: the run is not complete (status {status})")
    recorded = manifest["verification"]["worst_error"]
    lines += [
        f"{len(rows)} sampled collisions recomputed by verify: worst error {worst:.3g} kappa*u"
        f" (recorded {recorded:.3g}), {len(overstepped)} overstepped"
        f" (tolerance {OVERSTEP_TOLERANCE:g} kappa*u)",
        f"checked: content hashes, checkpoint invariants, {_REDERIVED.get(scene.kind, _SURVIVAL)}"
        f" re-derived, {_JOINT_CHECKED if scene.joint else ''}"
        "sample.csv, the sample replayed from the seed, every field of the"
        " manifest",
        f"not audited: the content of {rundir.PROVENANCE} (how and when the run was made;"
        " its hash and its schema are checked)",
    ]
    for problem in problems[:SHOWN * 4]:
        lines.append(problem)
    if len(problems) > SHOWN * 4:
        lines.append(f"... and {len(problems) - SHOWN * 4} more")
    lines.append("OK" if not problems else f"FAILED: {len(problems)} discrepancies")
    return not problems, lines
