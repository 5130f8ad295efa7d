"""The paper's figures from trusted runs, with the paper's claims decided on them.

``paper_figures_section(out_dir, particles=None, quick=False, echo=None, runs_dir=None,
include_runs=())`` runs (or reuses complete run directories in ``runs_dir``, default
``out_dir/runs``) the built-in scenes paper-phase-space, paper-escape, paper-transport,
escape-second-box and escape-island-start through ``reports.runs.driver.run`` (a complete run of
paper-escape, paper-transport or escape-second-box among ``include_runs`` with more particles
replaces the default-scale one: the paper-scale runs; escape-second-box is made at the size of
paper-escape, at most its scene's 10^7), runs the sampled studies
(``reports.paper.studies.followed_samples``), decides every claim of the register
(``reports.paper.claims.register``) and draws

    paper_fig1_phase_space   phase space at eps = 0.6, centred, holes as strips    (Fig. 1)
    paper_fig2_escape        discrete left, continuous right, regime laws            (Fig. 2)
    paper_fig3_transport     all P_ij(t) for h = 0.1, 0.4, 1, 2.2                     (Fig. 3)
    paper_fig4_h1            h = 1, discrete left, continuous right                  (Fig. 4)
    paper_survivors          late survivors: where they are, n against t, t/n
    paper_fermi              <v> against n and t at eps = 0.6, log-log
    paper_dissipation        <v_n> with restitution r < 1 and drag at eps = 2

as PNG and PDF in ``out_dir``. Returns (Markdown, claims): the claims as ``Claim``s, in register
order, then the claims from other publications and this project (dissipation).
"""

from __future__ import annotations

import time
from pathlib import Path

from reports.paper.claims.dissipation_claims import dissipation_claims
from reports.paper.claims.escape_claims import escape_analysis, escape_claims
from reports.paper.claims.fermi_claims import fermi_claims
from reports.paper.claims.geometry_claims import escape_hole_claims, transport_hole_claims
from reports.paper.claims.lifetime_claims import (
    SWEEP_PARTICLES,
    many_not_shown_claim,
    reducing_lifetime_claim,
    sweep_scene,
)
from reports.paper.claims.method_claims import method_claims
from reports.paper.claims.ordering_claims import snapshot_times
from reports.paper.claims.periodicity_claims import periodicity_claims
from reports.paper.claims.phase_space_claims import coexist_claim, large_eps_claim
from reports.paper.claims.register import ISLAND_HOLES, SEA_HOLES, TRAPPING_WIDTHS, entries
from reports.paper.claims.saddle_claims import c2_claim, gaussian_tail_claim
from reports.paper.claims.start_claims import (
    destroy_all_claim,
    effective_destruction_claim,
    island_start_claim,
    other_box_claim,
    other_density_claim,
)
from reports.paper.claims.transport_claims import transport_analysis, transport_claims
from reports.paper.figures.paper_dissipation import dissipation_markdown, figure_dissipation
from reports.paper.figures.paper_fermi import fermi_markdown, figure_fermi
from reports.paper.figures.paper_fig1_phase_space import figure_phase_space, phase_space_markdown
from reports.paper.figures.paper_fig2_escape import escape_markdown, figure_escape
from reports.paper.figures.paper_fig3_transport import figure_transport, transport_markdown
from reports.paper.figures.paper_fig4_h1 import figure_h1, h1_markdown
from reports.paper.figures.paper_survivors import figure_survivors
from reports.paper.studies.background import begin
from reports.paper.studies.dissipation_study import start_dissipation_study
from reports.paper.studies.escape_regimes import diffusive_onset
from reports.paper.studies.fermi_ensemble import fermi_ensemble
from reports.paper.studies.followed_samples import (
    escape_sample,
    island_box_sample,
    transport_sample,
)
from reports.paper.studies.joint_sample import from_followed, run_joint
from reports.paper.studies.paper_runs import (
    DEFAULT_PARTICLES,
    PHASE_SPACE_QUICK,
    QUICK_PARTICLES,
    ensure_run,
    largest_run,
    read_manifest,
    run_summary,
    say_nothing,
)
from reports.runs.scenes import load_scene

EXTRA_QUICK = {"escape-second-box": 2000, "escape-island-start": 500}
# compared curve by curve with paper-escape: made at the report's size (at most the scene's),
# a larger complete run among ``include_runs`` used instead
AT_REPORT_SIZE = ("escape-second-box",)
TAIL_SCENES = {hole: f"escape-tail-phi_c={hole}" for hole in ("0", "1")}
T_DIFFUSIVE = 1 / 3  # <v(t)> ~ t^(1/3)


def _runs(out_dir, runs_dir, particles, quick, include_runs, echo):
    n = int(particles) if particles else (QUICK_PARTICLES if quick else DEFAULT_PARTICLES)
    ps = PHASE_SPACE_QUICK if quick else load_scene("paper-phase-space").particles
    runs = {"paper-phase-space": ensure_run("paper-phase-space", runs_dir, ps, echo)}
    for scene in ("paper-escape", "paper-transport"):
        runs[scene] = ensure_run(scene, runs_dir, n, echo)
        bigger = largest_run(scene, [runs[scene], *include_runs])
        if bigger is not None and bigger != runs[scene]:
            echo(f"paper figures: {scene} verdicts from the included run {bigger}")
            runs[scene] = bigger
    for scene, q in EXTRA_QUICK.items():
        size = q if quick else load_scene(scene).particles
        if scene in AT_REPORT_SIZE:
            size = min(size, n)
        runs[scene] = ensure_run(scene, runs_dir, size, echo)
        bigger = largest_run(scene, [runs[scene], *include_runs])
        if bigger is not None and bigger != runs[scene]:
            echo(f"paper figures: {scene} verdicts from the included run {bigger}")
            runs[scene] = bigger
    # runs used where one is given or committed, never made here: the other start density, and
    # the island holes alone with 10^9 starts for their discrete-time tails
    for scene in ("escape-other-density", *TAIL_SCENES.values()):
        runs[scene] = largest_run(scene, [*include_runs, *sorted(runs_dir.glob(f"{scene}-*"))])
    runs["transport-width-sweep"] = ensure_run(
        "transport-width-sweep", runs_dir, QUICK_PARTICLES if quick else SWEEP_PARTICLES, echo,
        scene_text=sweep_scene())
    return runs


def _hole_centre(hole):
    return float(hole)


def decide(out_dir, runs, quick, echo, on_one_core=None):
    """Every claim, with what the figures need: (claims, context dict). ``on_one_core()`` is
    called where the rest of the claims run mostly on one core (Python, numpy, mpmath): work
    begun there in the background has the other core."""
    echo("paper figures: Fermi acceleration ensemble (diffusive onset, fermi claims)")
    fermi = fermi_ensemble(bool(quick))
    t_d = diffusive_onset(fermi.t, fermi.mean_v_t, T_DIFFUSIVE)
    echo(f"paper figures: escape windows and fits (t_D = {t_d:.3g})")
    esc = escape_analysis(runs["paper-escape"], t_d)
    follow, snapshot, smooth = {}, {}, {}
    for hole in ISLAND_HOLES + SEA_HOLES:
        if hole not in esc:
            continue
        tail = esc[hole]["windows"].n_at.get("tail")
        snapshot[hole] = snapshot_times(tail) if tail is not None else ()
        echo(f"paper figures: sampled escape study, phi_c = {hole}")
        follow[hole] = escape_sample(_hole_centre(hole), bool(quick), "uniform",
                                     snapshot[hole])
        if runs.get("escape-other-density") is None:
            smooth[f"phi_c={hole}"] = escape_sample(_hole_centre(hole), bool(quick),
                                                    "smooth")
    joint = joint_samples(runs["paper-escape"], follow)
    echo("paper figures: transport analysis and the sampled study of h = 1")
    tr = transport_analysis(runs["paper-transport"])
    samples = {entry: transport_sample(1.0, entry, bool(quick)) for entry in (1, 2)}
    replicas = {entry: transport_sample(1.0, entry, bool(quick), replica=1)
                for entry in (1, 2)}
    echo("paper figures: island geometry and the island-start studies")
    claims = escape_hole_claims(quick)
    tails = {}
    for hole, scene in TAIL_SCENES.items():
        if runs.get(scene) is not None:
            echo(f"paper figures: the discrete-time tail of phi_c = {hole} from {runs[scene]}")
            tails[hole] = (escape_analysis(runs[scene], t_d)[hole], runs[scene])
    claims += escape_claims(esc, runs["paper-escape"], {"joint": joint, "follow": follow,
                                                        "snapshot": snapshot}, tails)
    claims += fermi_claims(fermi)
    levels = {f"phi_c={h}": a["windows"].level_tail for h, a in esc.items()}
    claims.append(other_box_claim(runs["paper-escape"], runs["escape-second-box"], levels))
    claims.append(other_density_claim(runs["paper-escape"], smooth, levels,
                                      runs.get("escape-other-density")))
    island = island_box_sample(0.0, bool(quick))
    box_regular = (int(island[2].regular.sum()), len(island[0]))
    claims.append(island_start_claim(runs["escape-island-start"], box_regular))
    claims.append(destroy_all_claim(island))
    if "0" in esc:
        claims.append(effective_destruction_claim(esc, island))
    claims += transport_hole_claims(quick)
    claims += transport_claims(tr, runs["paper-transport"], samples,
                               joint=run_joint(runs["paper-transport"], width="1") or None,
                               replicas=replicas)
    if on_one_core is not None:  # the rest: mpmath, numpy fits and bootstraps, few kernels
        on_one_core()
    echo("paper figures: the method, the near periodicity, the phase space, the saddle point")
    claims += method_claims(quick) + periodicity_claims(quick)
    claims += [large_eps_claim(quick), coexist_claim(fermi, quick), gaussian_tail_claim(quick)]
    claims += [c2_claim(h, esc[h], quick) for h in ISLAND_HOLES if h in esc]
    echo("paper figures: island lifetimes and the sweep of hole sizes")
    claims += [reducing_lifetime_claim(h, tr[h], quick) for h in TRAPPING_WIDTHS if h in tr]
    claims.append(many_not_shown_claim(transport_analysis(runs["transport-width-sweep"]),
                                       Path(runs["transport-width-sweep"]).name))
    order = {e["id"]: i for i, e in enumerate(entries())}
    claims.sort(key=lambda c: order.get(c.id, len(order)))
    return claims, {"fermi": fermi, "escape": esc, "transport": tr, "follow": follow,
                    "snapshot": {h: (s[0] if s else None) for h, s in snapshot.items()},
                    "t_d": t_d}


def joint_samples(run_dir, follow):
    """{hole: JointSample}: the run's joint (n, t) record where it has one
    (``reports.paper.studies.joint_sample.run_joint``), else the sampled study's."""
    recorded = run_joint(run_dir)
    fallback = f"run {Path(run_dir).name} records no joint (n, t) histogram: sampled study"
    return {hole: recorded.get(hole) or from_followed(fol, fallback)
            for hole, fol in follow.items()}


def paper_figures_section(out_dir, particles=None, quick=False, echo=None,
                          runs_dir=None, include_runs=(), worker=None, on_one_core=None):
    """Run or reuse the runs, decide the claims, write the figures; returns (Markdown with
    image links relative to ``out_dir``, the claims). Where the claims come to run on one
    core, the dissipation study begins on ``worker`` (a ``background.Worker``; default: a
    thread of its own), then ``on_one_core()`` is called (more work for the worker)."""
    echo = echo or say_nothing
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    runs_dir = Path(runs_dir) if runs_dir is not None else out_dir / "runs"
    runs_dir.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    runs = _runs(out_dir, runs_dir, particles, quick, include_runs, echo)
    dissipation_done = []

    def begin_dissipation():  # its moments (or their re-check) beside the one-core claims
        echo("paper figures: dissipation (restitution and drag at eps = 2) begun in the "
             "background")
        dissipation_done.append(start_dissipation_study(
            bool(quick), echo, start=begin if worker is None else worker.submit))
        if on_one_core is not None:
            on_one_core()

    claims, ctx = decide(out_dir, runs, quick, echo, on_one_core=begin_dissipation)
    echo("paper figures: dissipation (restitution and drag at eps = 2)")
    if not dissipation_done:
        begin_dissipation()
    dissipation = dissipation_done[0]()
    claims += dissipation_claims(dissipation)
    echo("paper figures: drawing")
    figure_phase_space(runs["paper-phase-space"], out_dir)
    figure_escape(runs["paper-escape"], out_dir, ctx["escape"])
    figure_transport(runs["paper-transport"], out_dir, ctx["transport"])
    figure_h1(runs["paper-transport"], out_dir, ctx["transport"])
    figure_survivors(runs["paper-phase-space"], out_dir, ctx["escape"], ctx["follow"],
                     ctx["snapshot"])
    figure_fermi(ctx["fermi"], out_dir)
    figure_dissipation(dissipation, out_dir)
    seconds = time.perf_counter() - t0
    esc_n = read_manifest(runs["paper-escape"])["particles"]
    tr_n = read_manifest(runs["paper-transport"])["particles"]
    md = [
        "## The paper's figures from trusted runs", "",
        "Every curve comes from a `bouncer run` of a built-in scene, with its verification "
        f"summary. The paper used 10^8 starts per curve; Fig. 2 uses {esc_n:,} "
        f"(`{Path(runs['paper-escape']).name}`), Figs. 3-4 {tr_n:,} "
        f"(`{Path(runs['paper-transport']).name}`). The claims they decide are listed, with "
        "their quotes, rules and evidence, in the verdicts section above and in "
        "`report.json`.", "",
        phase_space_markdown(runs["paper-phase-space"], "paper_fig1_phase_space.png"),
        escape_markdown(runs["paper-escape"], "paper_fig2_escape.png", ctx["escape"]),
        transport_markdown(runs["paper-transport"], "paper_fig3_transport.png"),
        h1_markdown("paper_fig4_h1.png"),
        "### Late survivors: the mechanism", "",
        "![Late survivors](paper_survivors.png)", "",
        "Sampled studies (`reports/paper/studies/followed_samples.py`) record each particle's "
        "collisions n and time t together and the states of the survivors (claims sec3-n-sqrt-t-*, "
        "fig2-bounded-velocity-*, fig2-sea-slowed-*).", "",
        "### The other start sets", "",
        f"Second start box: {run_summary(runs['escape-second-box'])}. Island start box: "
        f"{run_summary(runs['escape-island-start'])}.", "",
        fermi_markdown(ctx["fermi"], "paper_fermi.png"),
        dissipation_markdown(dissipation, "paper_dissipation.png"),
        f"(paper figures: {seconds:.0f} s)", ""]
    return "\n".join(md), claims
