"""Trusted ensemble runs: the driver around ``fastpath.kernels.escape`` with ``verify`` checks.

The run is a fixed sequence of chunks (experiment e, chunk k) of at most ``scene.chunk_size``
starts.
Chunk (e, k) draws its starts, its verification picks and their collision indices from
``numpy.random.SeedSequence(seed, spawn_key=(e, k))`` only, so a result depends on
(scene, seed, particles) and not on threads, chunk order or interruptions; counts are integers,
summed exactly. After each chunk:

1. flagged particles (a flight float64 cannot decide) are settled by ``verify.step`` and resume
   in ``fastpath`` until they escape or reach the horizon;
2. the chunk's sampled collisions are recomputed by ``verify.step`` from the same float64 state;
   the error of the fast flight time is measured in units of kappa*u (kappa from
   ``verify.condition_number``, u = 2**-53):  err = |tau_fast - tau_ref| / (tau_ref*kappa*u).
   tau_fast - tau_ref > 16*kappa*u*tau_ref means the fast path jumped past the first collision
   (an overstep): the run stops with status ``failed``;
3. the chunk is merged; after the first chunk and then at most every ``CHECKPOINT_INTERVAL_S``
   seconds (and on Ctrl-C or a failure) the merged counts and the finished chunks are
   checkpointed atomically, with the manifest (status ``partial``, the SHA-256 of the
   checkpoint), SIGINT held back until both are written. A run killed outright loses at most
   the chunks of the last interval (rewriting the checkpoint, whose verification sample grows
   with the run, after every chunk cost ~15% of a run's time at 10^6 particles per curve).
   ``resume`` skips finished chunks, after checking the checkpoint's digest and invariants
   (``reports.runs.integrity``); the end result is identical.

One process writes a run directory (``reports.runs.lock``). The complete manifest records the
SHA-256 of every output; ``bouncer verify`` (``reports.runs.recheck``) audits them.

Steps 1 and 2 are ``run_chunk(scene, seed, curve, chunk, particles)``, a pure function of its
arguments returning a ``ChunkResult`` (counts, the verified sample rows, overstepped rows, or a
failure as data), so it runs the same in this process or as a task on a Dask worker
(``reports.runs.cluster``, ``run(..., scheduler=...)``). The merge (``Tally.merge``) is keyed by the
chunk index (curve, chunk): a chunk already merged is ignored, counts are integer sums, and the
sample rows and the list of finished chunks are kept sorted by index, so the merged state is a
function of the *set* of finished chunks only, whatever order they finish in.
"""

from __future__ import annotations

import io
import json
import sys
import time
from contextlib import closing
from dataclasses import replace
from pathlib import Path

import numba.core.event as numba_event
import numpy as np

from fastpath.arithmetic.jit import CACHE_ROOT
from reports.runs import cluster, manifest, rundir
from reports.runs.chunk import OVERSTEP_TOLERANCE, check_result, run_chunk
from reports.runs.counts import CheckpointError, Tally
from reports.runs.executor import Executor
from reports.runs.integrity import tally_problems
from reports.runs.joint_file import JOINT_FILE, joint_text
from reports.runs.lock import RunLock
from reports.runs.plan import check_size, make_plan
from reports.runs.provenance import dirty_text, git, now, versions
from reports.runs.rundir import CHECKPOINT, PROVENANCE, RunFailed, RunInterrupted
from reports.runs.scenes import parse_scene
from reports.runs.signals import deferred_interrupt
from reports.runs.survival import survival_curve, wilson
from reports.runs.velocity import velocity_text

summary = manifest.verification_summary  # the manifest's verification summary of a tally


def run(scene, out, particles=None, seed=None, resume=False, force=False, progress=True,
        threads=None, scheduler=None, require_clean=False):
    """Run (or resume) ``scene`` into the directory ``out``; returns the final manifest.

    ``scheduler``: None runs the chunks here, one after another (numba threads inside each);
    a Dask scheduler address (``"tcp://host:8786"``) or a ``distributed.Client`` sends them as
    tasks to that cluster (``reports.runs.cluster``). The result is bit-identical either way, and a
    run started one way resumes the other way without recomputing finished chunks.

    Before the directory is created, the cluster is connected to (or, here, the kernels are
    compiled: ``compile_kernels``), so a run refused or stopped before its first chunk leaves
    nothing behind: a new run that fails (or is interrupted) before its first chunk is
    checkpointed removes what it wrote, and the directory if it made it.

    provenance.json records the git commit of the sources, and whether the work tree had
    uncommitted changes outside ``out`` (``provenance.git``): a dirty tree is said on stderr
    (with ``progress``, at a terminal), and refused (ValueError, before anything is written)
    with ``require_clean``.

    Raises ValueError for bad input or a filesystem fault (exit 2; ``RunBusy`` when another
    process holds the directory's lock, ``CheckpointError`` for a checkpoint that fails its hash
    or invariants), RunFailed when a check fails (exit 1) and RunInterrupted on Ctrl-C (the
    checkpoint is consistent: resume it; KeyboardInterrupt if nothing was kept).
    """
    plan = make_plan(scene, particles, seed)
    check_size(plan)
    out = Path(out)
    if scheduler is not None:
        cluster.check_available()
    rundir.check_out(out, resume, force)  # refuse before creating anything
    source = clean_source(out, require_clean, progress)
    new_dirs = rundir.missing_folders(out)
    ctx = {"threads": threads, "hashes": {}, "provenance": {"versions": versions(), "git": source},
           "session": {"scheduler": None, "workers": None, "worker_threads": None,
                       "chunks_computed": 0},
           "compile_s": None, "kept": resume}
    try:
        with Executor(scheduler, ctx["session"]) as execute, RunLock(out):
            # (RunBusy above: another process's run, not ours to clean up)
            try:
                if scheduler is None:
                    ctx["compile_s"] = compile_kernels(plan, threads, progress)
                return _run_locked(plan, out, resume, force, progress, execute, ctx)
            except BaseException as err:
                if ctx["kept"]:
                    raise
                left = rundir.remove_run_files(out)  # nothing to keep: leave no trace of it
                if not isinstance(err, OSError):
                    raise
                what = (f"could not remove {', '.join(left)} from {out}" if left
                        else "it left nothing behind")
                raise ValueError(f"{rundir.os_error_text(err)}; the run stopped before its"
                                 f" first chunk was saved and {what}") from None
    except BaseException:
        if not ctx["kept"]:
            rundir.remove_new_folders(out, new_dirs)
        raise


def clean_source(out, require_clean, progress):
    """The git record of the sources for provenance.json (``provenance.git``, the run's own
    directory ``out`` left out); a dirty or unknown tree is refused (ValueError) with
    ``require_clean``, else said on stderr with ``progress`` at a terminal (``bouncer run``
    says it in its summary too, on stdout)."""
    record = git(exclude=out)
    problem = dirty_text(record)
    if problem and require_clean:
        raise ValueError(f"--require-clean: {problem}")
    if problem and progress and _interactive():
        print(f"bouncer run: warning: {problem}", file=sys.stderr, flush=True)
    return record


def _interactive():
    """Whether stderr is a terminal (a warning there is read, not parsed)."""
    return sys.stderr.isatty()


def compile_kernels(plan, threads, progress):
    """Compile (or load from numba's cache) the kernels of ``plan``'s scene by running a
    one-particle chunk, so that compilation is neither charged to the run's rate nor shown
    as a stalled progress bar; returns the seconds it took.

    Loading cached kernels takes about a second and is not mentioned. When numba starts to
    compile (its ``numba:compile`` event: a kernel the cache does not hold), that is said at
    once on stderr with the time it is expected to take (``expected_compile_text``), and the
    time it took is printed when it ends and recorded for the next estimate
    (``COMPILE_TIMES``).
    """
    start = time.perf_counter()
    key = _compile_key(plan.scene)
    notice = _CompileNotice(None if not progress else lambda: print(
        f"{plan.scene.name}: compiling the numba kernels ({key}: {expected_compile_text(key)};"
        " later runs load them from numba's cache) ...", end="", file=sys.stderr, flush=True))
    # a short horizon: the same kernels (argument types do not change), a particle's worth
    # of work (a velocity scene runs every particle to its horizon)
    short = replace(plan.scene, max_collisions=min(plan.scene.max_collisions or WARM_UP_N,
                                                   WARM_UP_N))
    with numba_event.install_listener("numba:compile", notice):
        try:
            run_chunk(short, plan.seed, 0, 0, 1, threads)  # a failure there is the run's to meet
        finally:
            seconds = time.perf_counter() - start
            if notice.compiled and progress:
                print(f" {seconds:.1f} s", file=sys.stderr, flush=True)
    if notice.compiled:
        _record_compile_time(key, seconds)
    return round(seconds, 3)


WARM_UP_N = 10  # collisions of the one particle that compiles the kernels
# compile times of this machine, by ``_compile_key``: the last one measured (the expected one)
COMPILE_TIMES = Path(CACHE_ROOT) / "compile_times.json"
# the same, measured with an empty numba cache on the 2-core machine of docs/performance.md
# (AMD EPYC, 2026-11-28: paper-escape, paper-phase-space, dissipation-saturation): what a
# first compile is expected to take where this machine has none recorded
REFERENCE_COMPILE_S = {"escape kernel, elastic model": 15.0,
                       "portrait kernel, elastic model": 11.0,
                       "moments kernel, dissipative model": 15.0}


class _CompileNotice(numba_event.Listener):
    """Calls ``say`` (once) when numba starts to compile a kernel."""

    def __init__(self, say=None):
        self.say, self.compiled = say, False

    def on_start(self, event):
        if not self.compiled and self.say is not None:
            self.say()
        self.compiled = True

    def on_end(self, event):
        pass


def _compile_key(scene):
    """Which kernels a scene compiles: its kernel and model ("escape kernel, elastic model",
    ...; transport scenes run the escape kernel)."""
    kernel = KERNEL_OF_KIND.get(scene.kind, scene.kind)
    return f"{kernel} kernel, {'elastic' if scene.elastic else 'dissipative'} model"


KERNEL_OF_KIND = {"escape": "escape", "transport": "escape", "phase-space": "portrait",
                  "velocity": "moments"}


def expected_compile_text(key):
    """How long compiling the kernels of ``key`` is expected to take, and from what
    measurement: the last compile on this machine, else the 2-core reference."""
    try:
        seconds = json.loads(COMPILE_TIMES.read_text(encoding="utf-8"))[key]
        return f"about {seconds:.0f} s, as the last time on this machine"
    except (OSError, ValueError, KeyError, TypeError):
        pass
    if key in REFERENCE_COMPILE_S:
        return f"about {REFERENCE_COMPILE_S[key]:.0f} s on 2 cores (docs/performance.md)"
    return "a first run"


def _record_compile_time(key, seconds):
    """Keep ``seconds`` in ``COMPILE_TIMES`` for the next estimate (best effort: a cache folder
    that cannot be written only loses the estimate)."""
    try:
        times = json.loads(COMPILE_TIMES.read_text(encoding="utf-8"))
        times = times if isinstance(times, dict) else {}
    except (OSError, ValueError):
        times = {}
    times[key] = round(seconds, 1)
    try:
        COMPILE_TIMES.parent.mkdir(parents=True, exist_ok=True)
        rundir.write_atomic(COMPILE_TIMES, json.dumps(times, indent=1, sort_keys=True) + "\n")
    except OSError:
        pass


def _resume_tally(plan, out, old):
    """The checkpoint of a partial run, refused (CheckpointError) if it fails its content hash
    or its invariants."""
    ckpt = out / CHECKPOINT
    advice = "; it cannot be resumed: start the run again with --force"
    if not ckpt.exists():
        if old.get("chunks_done"):
            raise CheckpointError(f"checkpoint {ckpt} is missing but the manifest records"
                                  f" {old['chunks_done']} finished chunks{advice}")
        return Tally.empty(plan)
    try:
        rundir.check_input(ckpt)
        tally = Tally.load(ckpt)
    except (CheckpointError, rundir.InputError) as err:
        raise CheckpointError(f"{err}{advice}") from None
    problems = tally_problems(plan, tally)
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        raise CheckpointError(f"checkpoint {ckpt} fails its invariants: {problems[0]}{more}"
                              f"{advice}")
    return tally


def _run_locked(plan, out, resume, force, progress, execute, ctx):
    scene = plan.scene
    resuming = rundir.prepare(out, resume, force)
    ckpt = out / CHECKPOINT
    if resuming:
        old = manifest.load_manifest(out / rundir.MANIFEST)
        text = rundir.read_input_text(out / "scene.toml", rundir.MAX_SCENE_BYTES)
        stored = parse_scene(text, str(out / "scene.toml"))
        if stored != scene or old["particles"] != plan.particles or old["seed"] != plan.seed:
            raise ValueError(f"--resume: {out} holds a run of scene {old['scene']['name']!r} with "
                             f"{old['particles']} particles and seed {old['seed']}; give the"
                             " same scene, --particles and --seed")
        if old["status"] == "complete":
            return old
        tally = _resume_tally(plan, out, old)
    else:
        rundir.write_atomic(out / "scene.toml", scene.source)
        tally = Tally.empty(plan)
    ctx["hashes"]["scene.toml"] = rundir.sha256_file(out / "scene.toml")
    session = ctx["session"]
    if ckpt.is_file():
        ctx["hashes"][CHECKPOINT] = rundir.sha256_file(ckpt)
    _manifest(out, plan, tally, "partial", ctx)
    done = sum(tally.finished.particles_done(plan, e) for e in range(len(plan.experiments)))
    bar = _progress(plan, done, plan.particles_total, progress)
    jobs = (((e, k), (scene, plan.seed, e, k, plan.particles, ctx["threads"]))
            for e, k in plan.chunks if (e, k) not in tally.finished)
    saved, unsaved = None, False  # when the checkpoint was last written; chunks merged since
    try:
        with closing(execute(jobs)) as results:
            last = time.perf_counter()
            for _, result in results:
                with deferred_interrupt():  # merge, checkpoint and manifest: all or nothing
                    check_result(result)
                    if result.bad and unsaved:  # the checkpoint: every chunk before this one
                        _checkpoint(out, plan, tally, ctx)
                        unsaved = False
                    if not tally.merge(result, scene.kind):
                        continue
                    session["chunks_computed"] += 1
                    now = time.perf_counter()
                    tally.elapsed += now - last
                    last = now
                    if result.bad:
                        _fail(out, plan, tally, ctx, result.bad)
                    unsaved = True
                    if saved is None or now - saved >= CHECKPOINT_INTERVAL_S:
                        _checkpoint(out, plan, tally, ctx)
                        saved, unsaved = now, False
                if bar is not None:
                    bar.update(plan.chunk_particles(result.chunk))
                    bar.set_postfix_str(f"{tally.collisions / max(tally.elapsed, 1e-9):.3g}"
                                        " coll/s", refresh=False)
        if len(tally.finished) != plan.n_chunks:  # only if an executor drops a task
            raise RunFailed(f"{plan.n_chunks - len(tally.finished)} chunk(s) never came back")
        with deferred_interrupt():
            if unsaved:
                ctx["hashes"][CHECKPOINT] = tally.save(ckpt)
            ctx["hashes"].update(write_results(out, plan, tally))
            return _manifest(out, plan, tally, "complete", ctx)
    except RunFailed as err:
        if not getattr(err, "recorded", False):
            with deferred_interrupt():
                if unsaved:
                    ctx["hashes"][CHECKPOINT] = tally.save(ckpt)
                _manifest(out, plan, tally, "failed", ctx, failure=str(err))
                ctx["kept"] = True
        raise
    except KeyboardInterrupt:
        if unsaved:  # the chunks merged since the last checkpoint
            with deferred_interrupt():
                _checkpoint(out, plan, tally, ctx)
        if not ctx["kept"]:
            raise  # before the first chunk: nothing to resume, the run leaves nothing
        raise RunInterrupted(out, len(tally.finished), plan.n_chunks) from None
    except OSError as err:
        if not ctx["kept"]:
            raise  # run() removes what it wrote and says so
        raise ValueError(f"{rundir.os_error_text(err)}; the checkpoint holds the chunks finished"
                         " before: fix this and continue with --resume") from None
    finally:
        if bar is not None:
            bar.close()


def _checkpoint(out, plan, tally, ctx):
    """The merged tally to the checkpoint, then the manifest (status partial) with its hash."""
    ctx["hashes"][CHECKPOINT] = tally.save(out / CHECKPOINT)
    ctx["kept"] = True  # --resume continues from it (the partial manifest is there already)
    _manifest(out, plan, tally, "partial", ctx)


def _fail(out, plan, tally, ctx, bad):
    row = dict(zip(rundir.sample_columns(plan.scene), bad[0], strict=True))
    msg = (f"OVERSTEP: {len(bad)} sampled collision(s) where the fast flight time exceeds"
           f" verify's first root by more than {OVERSTEP_TOLERANCE:g}*kappa*u, first: {row}")
    ver = summary(tally, plan.scene)
    ver["overstepped"] = len(bad)
    ctx["hashes"].update(write_results(out, plan, tally))
    _manifest(out, plan, tally, "failed", ctx, failure=msg, verification=ver)
    ctx["kept"] = True
    err = RunFailed(msg)
    err.recorded = True
    raise err


CHECKPOINT_INTERVAL_S = 5.0


def _progress(plan, initial, total, enabled):
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, unit="particle", unit_scale=True,
                desc=plan.scene.name, file=sys.stderr, smoothing=0.1)



def _manifest(out, plan, tally, status, ctx, failure=None, verification=None):
    """Write provenance.json, then the manifest with its hash; returns the manifest. ``ctx``:
    threads, session, provenance, compile time and the SHA-256 of the files written so far
    (``hashes``)."""
    compute = round(tally.elapsed, 3)
    record = {**ctx["provenance"], "threads": ctx["threads"], "session": ctx["session"],
              "started": tally.started, "updated": now(),
              "finished": now() if status == "complete" else None,
              "compile_s": ctx["compile_s"], "compute_s": compute,
              "collisions_per_s": round(tally.collisions / compute) if compute else None}
    ctx["hashes"][PROVENANCE] = rundir.write_json(out / PROVENANCE, record)
    out_manifest = manifest.build(plan, tally, status, ctx["hashes"], verification, failure)
    rundir.write_json(out / rundir.MANIFEST, out_manifest)
    return out_manifest


COUNTS_COLUMNS = ("experiment", "clock", "outcome", "lower_edge", "count")


def survival_rows(plan, tally):
    """Rows curve,clock,x,p,p_lo,p_hi of survival.csv (module docstring of statistics)."""
    rows = []
    for e, exp in enumerate(plan.experiments):
        for clock in plan.scene.clocks:
            if clock == "collisions":
                edges, esc, cens = plan.n_edges, tally.esc_n[e], tally.cens_n[e]
                stuck = tally.stuck_n[e]
            else:
                edges, esc, cens = plan.t_edges, tally.esc_t[e], tally.cens_t[e]
                stuck = tally.stuck_t[e]
            for j, curve in enumerate(exp.curves):
                x, surv, p = survival_curve(esc[j], cens, edges, plan.particles, clock,
                                            add_censored=plan.scene.kind == "escape",
                                            stuck=stuck)
                lo, hi = wilson(surv, plan.particles)
                for xi, pi, li, hi_ in zip(x, p, lo, hi, strict=True):
                    xs = str(int(xi)) if clock == "collisions" else repr(float(xi))
                    rows.append([curve, clock, xs, repr(float(pi)), repr(float(li)),
                                 repr(float(hi_))])
    return rows


def result_files(plan, tally):
    """{name: text or bytes} of survival.csv, counts.csv (or portrait.npy, or velocity.csv),
    joint.csv (scenes that record it) and sample.csv."""
    sc = plan.scene
    files = {}
    if sc.kind == "phase-space":
        buf = io.BytesIO()
        np.save(buf, tally.portrait)
        files["portrait.npy"] = buf.getvalue()
    elif sc.kind == "velocity":
        files["velocity.csv"] = velocity_text(plan, tally)
    else:
        files["survival.csv"] = rundir.csv_text(["curve", "clock", "x", "p", "p_lo", "p_hi"],
                                                survival_rows(plan, tally))
        files["counts.csv"] = rundir.csv_text(COUNTS_COLUMNS, counts_rows(plan, tally))
    if sc.joint:
        files[JOINT_FILE] = joint_text(plan, tally.joint)
    samples = sorted(tally.samples, key=lambda r: (r[0], r[1], r[2]))
    files["sample.csv"] = rundir.csv_text(
        rundir.sample_columns(sc),
        [[*map(int, r[:4]), *map(repr, map(float, r[4:]))] for r in samples])
    return files


def counts_rows(plan, tally):
    """Rows experiment,clock,outcome,lower_edge,count of counts.csv: the non-zero bins."""
    rows = []
    for e, exp in enumerate(plan.experiments):
        for clock in plan.scene.clocks:
            edges = plan.n_edges if clock == "collisions" else plan.t_edges
            esc = tally.esc_n[e] if clock == "collisions" else tally.esc_t[e]
            cens = tally.cens_n[e] if clock == "collisions" else tally.cens_t[e]
            stuck = tally.stuck_n[e] if clock == "collisions" else tally.stuck_t[e]
            outcomes = [(c, esc[j]) for j, c in enumerate(exp.curves)] + [("censored", cens)]
            outcomes.append(("stuck", stuck))  # only non-zero bins: none in elastic runs
            for name, counts in outcomes:
                for b in np.flatnonzero(counts):
                    rows.append([exp.name, clock, name, repr(float(edges[b])), int(counts[b])])
    return rows


def write_results(out, plan, tally):
    """Write ``result_files`` atomically; returns {name: SHA-256}."""
    return {name: rundir.write_atomic(out / name, data)
            for name, data in result_files(plan, tally).items()}
