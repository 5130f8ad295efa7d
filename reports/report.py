"""``bouncer report``: one Markdown report of how fast and how accurate each way of simulating
the bouncer is, and the paper's results reproduced from verified runs.

Sections, each computed in this run (nothing is copied in by hand):

1. speed: ``fastpath.orbit`` exact against the Holmes map, ns per collision
   (``reports.precision.bench``);
2. work-precision: every method's error against ``verify`` and its time per collision, with the
   missed collisions on close root pairs (``reports.precision.work_precision``), and the
   hard-case table from the same evaluation (``reports.precision.hard_case_table``), with the
   dissipative hard cases (drag, departures at rest, chattering grazes: fastpath and verify
   only) in a sub-table of their own;
3. the paper's figures from trusted ensemble runs, with every claim of the paper decided
   (``reports.paper.sections.paper_figures_section``; the sections that contribute claims are
   listed in ``claim_sections``);
4. physics checks against published results (``reports.paper.sections.physics_checks_section``);
5. optionally, finished runs given with ``--include-run`` (e.g. the paper-scale escape run).

Figures are written as PNG and PDF next to ``report.md``, the claims with their verdicts to
``report.json`` (the claims of ``report.md`` are rendered from it); files are replaced
atomically. ``build_report(..., paper_only=True)`` rebuilds only the paper's sections (claims,
figures, physics checks) from the runs, and splices them into an existing ``report.md``,
keeping its speed and work-precision sections.
"""

from __future__ import annotations

import datetime
import json
import math
import os
import platform
import subprocess
import sys
import threading
import time
from contextlib import contextmanager
from pathlib import Path

from reports.paper.checks.diffusion import begin_ensembles
from reports.paper.claims.claim import claims_markdown, write_report_json
from reports.paper.figures.specification import specification_markdown
from reports.paper.sections.dynamics_section import dynamics_section
from reports.paper.sections.paper_figures_section import paper_figures_section
from reports.paper.sections.physics_checks_section import physics_checks_section
from reports.paper.studies.background import Worker
from reports.precision.bench import (
    ensemble_table,
    headline_ratios,
    orbit_table,
    time_ensembles,
    time_orbits,
)
from reports.precision.hard_case_table import dissipative_case_section, hard_case_markdown
from reports.precision.methods import default_methods
from reports.precision.work_precision import (
    plot_work_precision,
    run_work_precision,
    work_precision_markdown,
)
from reports.runs import rundir
from reports.runs.manifest import load_provenance
from reports.runs.provenance import versions
from reports.runs.recheck import load_run
from reports.stats.plot import plot_run

DEFAULT_OUT = "bouncer-report"


def _header(particles, quick):
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True, timeout=5, cwd=Path(__file__).parent).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        commit = ""
    packages = ", ".join(f"{k} {v}" for k, v in versions().items())
    size = "quick (smoke-test sizes)" if quick else (
        f"{particles:,} particles per curve" if particles else "default sizes")
    return "\n".join([
        "# bouncer-verify report",
        "",
        f"Built {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC on {platform.node()}"
        f" ({platform.machine()}, {os.cpu_count()} cores), {size}; "
        f"{packages}" + (f"; git {commit}" if commit else "") + ".",
        "",
        "Errors of flight times are given in units of kappa*u: kappa is the condition number "
        "of the flight time (`verify.condition_number`) and u = 2^-53 the unit roundoff, so a "
        "float64 method that is as accurate as its input allows scores O(1).",
        "",
    ])


# the speed section's sizes: (particles per curve, turns) of the paper-escape ensembles and
# (collisions, rounds) of the orbits; ``bouncer bench`` takes larger ones (docs/performance.md)
SPEED_ENSEMBLES = (500_000, 2)
SPEED_ORBITS = (3_000_000, 3)


def _speed_section(quick, echo):
    particles, turns = (20_000, 1) if quick else SPEED_ENSEMBLES
    echo(f"speed: paper-escape ensembles of {particles:,} particles per curve, exact and Holmes,"
         f" {turns} turns")
    ensembles = time_ensembles(particles, repeats=turns)
    ratio, kernel = headline_ratios(ensembles)
    collisions, repeats = (200_000, 2) if quick else SPEED_ORBITS
    echo(f"speed: orbits of {collisions:,} collisions, exact and Holmes, {repeats} rounds")
    best = time_orbits(0.6, collisions, repeats)
    return "\n".join([
        "## Speed: exact map against the Holmes map", "",
        f"Headline: the paper's escape ensemble takes **{ratio:.2f} x** the time of the bare"
        f" Holmes-map loop on the same starts end to end (verification sample, histograms,"
        f" checkpoints), **{kernel:.2f} x** kernel against loop (`bouncer bench`).", "",
        ensemble_table(ensembles), "",
        orbit_table(best, collisions, 0.6, repeats), ""])


def _precision_sections(out_dir, quick, compare, echo):
    methods = default_methods() + list(compare)
    result = run_work_precision(quick=quick, methods=methods, echo=echo)
    plot_work_precision(result, out_dir / "work_precision")
    hard = [i for i, c in enumerate(result.cases) if c.group == "hard"]
    errors = {m.name: [result.errors[m.name][i] for i in hard] for m in methods}
    echo("hard cases with drag and chattering: fastpath against verify")
    dissipative = dissipative_case_section()
    return "\n".join([
        work_precision_markdown(result, "work_precision.png"), "",
        hard_case_markdown([result.cases[i] for i in hard], [result.references[i] for i in hard],
                           errors, methods), "",
        dissipative, "",
    ])


def _threads_text(threads):
    """provenance.json's ``threads`` in words: None is numba's default (every CPU)."""
    return "numba's default threads" if threads is None else f"{threads} threads"


def _included_run(out_dir, run_dir, echo):
    manifest, scene = load_run(run_dir)
    record = load_provenance(run_dir)
    name = Path(run_dir).name
    image = f"included-{name}.png"
    echo(f"included run {run_dir}: plotting")
    plot_run(run_dir, out_dir / image)
    v = manifest["verification"]
    compute = record.get("compute_s") or math.nan
    return "\n".join([
        f"## Included run: {scene.name}, {manifest['particles']:,} particles per curve", "",
        f"Run directory `{name}` (status {manifest['status']}, seed {manifest['seed']}, "
        f"{manifest['collisions']:,} collisions, started {record.get('started', '?')}, "
        f"finished {record.get('finished') or '?'}, {_threads_text(record.get('threads'))}: "
        f"{compute:.0f} s of computation, "
        f"{record.get('collisions_per_s') or math.nan:.3g} collisions/s, "
        f"{compute / len(manifest['curves']):.0f} s per curve on average). Verification: "
        f"{v['sampled']} sampled "
        f"collisions recomputed by verify, worst error {v['worst_error']:.3g} kappa*u, "
        f"{v['uncertain_settled']} uncertain collisions settled by verify, {v['overstepped']} "
        "overstepped.", "",
        f"![{scene.name} survival]({image})", "",
    ])


# What each stage of a report took at the default size on 2 cores, kernels compiled afresh
# (docs/performance.md, "Where the default report's time goes"): the weights of the overall
# progress line. A stage not named here (an included run) weighs INCLUDED_RUN_S.
STAGE_S = {
    "paper's figures and claims": 445.0,
    "dynamics: periodic orbits, Lyapunov exponents, Fermi acceleration": 12.0,
    "physics checks": 38.0,
    "speed": 50.0,
    "work-precision and hard cases": 57.0,
}
INCLUDED_RUN_S = 2.0


class ReportProgress:
    """One progress line on stderr for the whole report: the fraction done and the time left,
    refreshed every second by a background thread (the runs inside a stage add their own bars).

    The stages report no fraction of their own, so each weighs what it took in the committed
    report (``STAGE_S``); within a stage the fraction grows with its elapsed time, up to 95% of
    its weight until it ends. The pace, the time the finished stages took over their weights
    (1 before any has finished), scales the weights of the rest: the time left is the weight
    left times the pace, and it adapts to a slower machine, a larger ``--particles`` or
    ``--quick`` as the stages finish.
    """

    def __init__(self, labels, enabled=True):
        self.weights = [STAGE_S.get(label, INCLUDED_RUN_S) for label in labels]
        self.labels = list(labels)
        self.done_weight = self.done_seconds = 0.0
        self.stage = -1
        self.running = False  # a stage has begun and not yet ended
        self.start = self.stage_start = time.perf_counter()
        self.bar = None
        if enabled:
            from tqdm import tqdm

            self.bar = tqdm(bar_format="{desc}", file=sys.stderr, leave=True)

    def pace(self):
        return self.done_seconds / self.done_weight if self.done_weight > 0 else 1.0

    def fraction_and_left(self, now=None):
        """(fraction of the report done, estimated seconds left). The time left is the weight
        left times the pace counted with the running stage (its elapsed time over the weight it
        is credited with): equal to ``pace()`` while the stage keeps to time, and growing while it
        overruns, so that a stage far behind its weight never shows a constant time left."""
        now = time.perf_counter() if now is None else now
        done, seconds = self.done_weight, self.done_seconds
        if self.running:
            elapsed = now - self.stage_start
            done += min(elapsed / self.pace(), 0.95 * self.weights[self.stage])
            seconds += elapsed
        pace = seconds / done if done > 0 else self.pace()
        total = sum(self.weights)
        return (done / total if total else 1.0), (total - done) * pace

    def line(self, now=None):
        now = time.perf_counter() if now is None else now
        fraction, left = self.fraction_and_left(now)
        stage = (f"stage {self.stage + 1} of {len(self.labels)}: {self.labels[self.stage]}"
                 if 0 <= self.stage < len(self.labels) else "done")
        return (f"report: {100 * fraction:.0f}% ({stage}), {_minutes(now - self.start)}"
                f" elapsed, about {_minutes(left)} left")

    @contextmanager
    def stage_of(self, label):
        """The stage ``label`` (the next of ``labels``) while the block runs."""
        self.stage = self.labels.index(label, self.stage + 1)
        self.stage_start = time.perf_counter()
        self.running = True
        stop = threading.Event()
        ticker = None
        if self.bar is not None:
            self.bar.set_description_str(self.line())

            def tick():
                while not stop.wait(1.0):
                    self.bar.set_description_str(self.line())

            ticker = threading.Thread(target=tick, daemon=True)
            ticker.start()
        try:
            yield
        finally:
            stop.set()
            if ticker is not None:
                ticker.join()
            self.running = False
            self.done_weight += self.weights[self.stage]
            self.done_seconds += time.perf_counter() - self.stage_start
            if self.bar is not None:
                self.bar.set_description_str(self.line())

    def close(self):
        if self.bar is not None:
            self.stage = len(self.labels)
            self.bar.set_description_str(self.line())
            self.bar.close()


def _minutes(seconds):
    seconds = max(0, round(seconds))
    return f"{seconds // 60}:{seconds % 60:02d}"


CLAIMS_HEADING = "## The paper's claims: verdicts"
FIGURES_HEADING = "## The paper's figures from trusted runs"
PHYSICS_HEADING = "## Physics checks against published results"


def claim_sections(out_dir, particles, quick, echo, include_runs, worker=None):
    """(label, make) of every section that contributes claims; make() -> (markdown, claims),
    the claims as ``Claim``s or as dicts with the keys of ``reports.paper.claims.claim.FIELDS``. A
    section of more claims is one more entry here. ``worker`` (a ``background.Worker``): where
    the paper's claims come to run on one core, the dissipation study and the physics checks'
    diffusion ensembles begin on it."""
    ahead = None if worker is None else (lambda: begin_ensembles(quick, worker.submit))
    return [
        ("paper's figures and claims", lambda: paper_figures_section(
            out_dir, particles=particles, quick=quick, echo=echo, runs_dir=out_dir / "runs",
            include_runs=include_runs, worker=worker, on_one_core=ahead)),
        ("dynamics: periodic orbits, Lyapunov exponents, Fermi acceleration",
         lambda: dynamics_section(out_dir, quick=quick, echo=echo)),
    ]


def claims_heading_text(stored, families=""):
    """The claims section: the claims rendered from ``report.json`` and the specification
    plots of the contested ones (``families``, ``specification_markdown``)."""
    return (f"{CLAIMS_HEADING}\n\nRendered from `report.json` (every claim with its quote, "
            "reading, family of analyses, rule, tolerance, evidence, uncertainties and run). A "
            "verdict is the agreement of the claim's family: confirmed or refuted only where "
            "every analysis its words allow gives it; an inconclusive one says why: too few "
            "data (`data`), precise but between the word's two bounds (`between-bounds`), or "
            "analyses that disagree (`analysis`). Rules and tolerances: "
            "`reports/paper/claims/rules.py`; the register: `reports/paper/claims/register.py`.\n\n"
            + claims_markdown(stored) + ("\n" + families if families else ""))


def splice(old_md, sections):
    """``old_md`` with each section (heading -> new text, up to the next "## " heading)
    replaced; a section not found is inserted after the first paragraph block."""
    lines = old_md.splitlines()
    out, i, done = [], 0, set()
    while i < len(lines):
        line = lines[i]
        hit = next((h for h in sections if line.strip() == h), None)
        if hit is None:
            out.append(line)
            i += 1
            continue
        out.extend(sections[hit].rstrip("\n").splitlines())
        out.append("")
        done.add(hit)
        i += 1
        while i < len(lines) and not lines[i].startswith("## "):
            i += 1
    missing = [text for h, text in sections.items() if h not in done]
    if missing:
        first = next((k for k, line in enumerate(out) if line.startswith("## ")), len(out))
        out[first:first] = [t.rstrip("\n") + "\n" for t in missing]
    return "\n".join(out) + "\n"


REBUILD_NOTE = "Paper sections (claims, figures, physics checks) rebuilt"


def with_rebuild_note(md, note):
    """``md`` with ``note`` after its "Built ..." line, replacing an earlier rebuild note."""
    lines = [line for line in md.splitlines() if not line.startswith(REBUILD_NOTE)]
    text = "\n".join(lines)
    while "\n\n\n" in text:
        text = text.replace("\n\n\n", "\n\n")
    lines = text.splitlines()
    at = next((i + 1 for i, line in enumerate(lines) if line.startswith("Built ")), 1)
    return "\n".join(lines[:at] + ["", note] + lines[at:]) + "\n"


def build_report(out_dir=DEFAULT_OUT, particles=None, quick=False, compare=(), include_runs=(),
                 echo=print, progress=True, paper_only=False):
    """Compute every section and write ``out_dir/report.md``; returns its path. ``progress``:
    one progress line for the whole report on stderr (``ReportProgress``). ``paper_only``: only
    the claims, the paper's figures and the physics checks, spliced into an existing
    ``report.md`` (written whole if none)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    timings = []
    sections = claim_sections(out_dir, particles, quick, echo, include_runs, Worker())
    labels = [label for label, _ in sections] + ["physics checks"]
    if not (paper_only and (out_dir / "report.md").is_file()):
        if not paper_only:
            labels += ["speed", "work-precision and hard cases"]
        labels += [f"included run {run_dir}" for run_dir in include_runs]
    overall = ReportProgress(labels, progress)

    def timed(label, make):
        t0 = time.perf_counter()
        with overall.stage_of(label):
            result = make()
        timings.append((label, time.perf_counter() - t0))
        return result

    try:
        return _build(out_dir, particles, quick, compare, include_runs, echo, paper_only,
                      sections, timed, timings, start)
    finally:
        overall.close()


def _build(out_dir, particles, quick, compare, include_runs, echo, paper_only, sections, timed,
           timings, start):
    """``build_report``'s sections, each through ``timed`` (its progress and time)."""
    claims, claim_md = [], []
    for label, make in sections:
        md, section_claims = timed(label, make)
        claim_md.append(md)
        claims += list(section_claims)
    physics = timed("physics checks", lambda: physics_checks_section(out_dir, quick=quick,
                                                                     echo=echo))
    write_report_json(out_dir / "report.json", claims, built=_now_utc(),
                      particles_per_curve=particles, quick=quick)
    stored = json.loads((out_dir / "report.json").read_text(encoding="utf-8"))["claims"]
    families = specification_markdown(stored, out_dir)
    path = out_dir / "report.md"
    if paper_only and path.is_file():
        old = path.read_text(encoding="utf-8")
        note = (f"{REBUILD_NOTE} {_now_utc()} from the runs in {out_dir}; the speed and "
                "work-precision sections are from the build named above.")
        sections = {CLAIMS_HEADING: claims_heading_text(stored, families),
                    PHYSICS_HEADING: physics}
        for md in claim_md:  # each section under its own heading (its first line)
            sections[md.splitlines()[0].strip()] = md
        new = splice(old, sections)
        rundir.write_atomic(path, with_rebuild_note(new, note))
        echo(f"paper sections of {path} rebuilt in {time.perf_counter() - start:.0f} s")
        return path
    parts = [_header(particles, quick)]
    if not paper_only:
        parts.append(timed("speed", lambda: _speed_section(quick, echo)))
        parts.append(timed("work-precision and hard cases",
                           lambda: _precision_sections(out_dir, quick, compare, echo)))
    parts += claim_md
    parts.append(physics)
    for run_dir in include_runs:
        parts.append(timed(f"included run {run_dir}",
                           lambda r=run_dir: _included_run(out_dir, r, echo)))
    total = time.perf_counter() - start
    rows = "\n".join(f"| {label} | {seconds:.0f} |" for label, seconds in timings)
    parts.append("## How long this report took\n\n| section | seconds |\n|---|---|\n"
                 f"{rows}\n| total | {total:.0f} |\n")
    parts.insert(1, claims_heading_text(stored, families))
    rundir.write_atomic(path, "\n".join(parts))
    echo(f"report written to {path} in {total:.0f} s")
    return path


def _now_utc():
    return f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC"
