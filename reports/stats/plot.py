"""``bouncer plot RUN_DIR``: the survival curves of a run as in the paper's figures.

Escape (Fig. 2): P(n) against n (log-log) and P(t) against sqrt(t) (log P). Transport
(Figs. 3-4): P_ij against t and against n (log-log), one row per hole width. Phase space
(Fig. 1): log(1 + counts) of the (phi, v) histogram. Velocity: <v_n> against n (log-log), one
line per curve, +- one standard error shaded. Wilson bands are shaded.

With ``fit`` the curves of ``clock`` get the maximum-likelihood fits of ``bouncer fit``
(``reports.stats``, binned censored counts): ``fit="regimes"`` draws the law of every regime
``bouncer fit`` finds; a law name (exponential, stretched, power) fits that law over the bins
of ``window`` (its ends moved to the nearest bin boundaries). Each fitted law is drawn in its
curve's colour (dashed; the regimes of one curve in dash patterns of their own), anchored at
the data's survival at its window start, with a legend entry naming the curve, the law and the
window. Interval ends the data do not bound are printed in words
(``reports.stats.analysis.interval_text``). The image is written atomically.
"""

from __future__ import annotations

import io
from collections import defaultdict
from pathlib import Path

import numpy as np

from fastpath.arithmetic.phase import TWO_PI
from reports.runs import rundir
from reports.runs.recheck import load_run
from reports.runs.survival import read_survival
from reports.stats.analysis import analyse, best_law_text, interval_text
from reports.stats.hazard import boundary_index, curve_probability
from reports.stats.histogram import read_run
from reports.stats.likelihood import fit_law, window_of

FIT_LAWS = {"exponential": "exponential", "stretched": "stretched_exponential",
            "power": "power_law"}
FIT_CHOICES = ("regimes", *FIT_LAWS)


def plot_run(run_dir, out=None, fit=None, window=None, clock="time", curve=None):
    """Draw the run's figure; returns report lines (file written, fits)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    run_dir = Path(run_dir)
    manifest, scene = load_run(run_dir)
    if fit and fit not in FIT_CHOICES:
        raise ValueError(f"--fit must be one of {', '.join(FIT_CHOICES)}, got {fit!r}")
    if fit in FIT_LAWS and not window:
        raise ValueError(f"--fit {fit} needs --window LO HI (--fit regimes needs none)")
    lines = []
    if scene.kind == "velocity":
        if fit:
            raise ValueError("--fit fits survival curves; a velocity run has none")
        fig = _velocity_figure(plt, run_dir, scene, manifest)
    elif scene.kind == "phase-space":
        rundir.check_input(run_dir / "portrait.npy")
        counts = np.load(run_dir / "portrait.npy")
        fig, ax = plt.subplots(figsize=(7, 5))
        ax.imshow(np.log1p(counts.T), origin="lower", aspect="auto", cmap="Greys",
                  extent=(0, TWO_PI, *scene.v_range))
        ax.set_xlabel("phi")
        ax.set_ylabel("v")
        ax.set_title(f"{scene.name}: eps = {scene.eps:g}")
    else:
        data = read_survival(run_dir / "survival.csv")
        curves = ({(c.curve, c.clock): c for c in read_run(run_dir, clocks=(clock,))}
                  if fit else {})
        groups = _groups(scene, data)
        clocks = list(scene.clocks)
        fig, axes = plt.subplots(len(groups), len(clocks), squeeze=False,
                                 figsize=(6 * len(clocks), 4 * len(groups)))
        for r, (title, names) in enumerate(groups):
            for c, ck in enumerate(clocks):
                ax = axes[r, c]
                for name in names:
                    if (name, ck) not in data:
                        continue
                    x, p, lo, hi = data[name, ck]
                    xs = np.sqrt(x) if scene.kind == "escape" and ck == "time" else x
                    pos = p > 0
                    line, = ax.plot(xs[pos], p[pos], label=name, lw=1)
                    ax.fill_between(xs[pos], lo[pos], hi[pos], color=line.get_color(),
                                    alpha=0.2, lw=0)
                    if fit and ck == clock and (curve is None or curve == name) and (
                            name, ck) in curves:
                        lines += _fit_lines(ax, curves[name, ck], fit, window, scene,
                                            line.get_color())
                _axes(ax, scene, ck, title, manifest)
        fig.tight_layout()
    default = {"phase-space": "portrait.png", "velocity": "velocity.png"}.get(scene.kind,
                                                                            "survival.png")
    out = Path(out) if out else run_dir / default
    image = io.BytesIO()
    fig.savefig(image, dpi=120, format="png")
    plt.close(fig)
    rundir.write_atomic(out, image.getvalue())  # never a half-written image
    lines.insert(0, f"wrote {out}")
    return lines


def _velocity_figure(plt, run_dir, scene, manifest):
    """<v_n> against n >= 1 on log-log axes, one line per curve, shaded +- one standard error."""
    rows = rundir.read_csv(run_dir / "velocity.csv")
    fig, ax = plt.subplots(figsize=(7, 5))
    for exp in scene.experiments():
        mine = [r for r in rows if r["curve"] == exp.name and int(r["n"]) >= 1 and r["mean_v"]]
        n = np.array([int(r["n"]) for r in mine])
        mean = np.array([float(r["mean_v"]) for r in mine])
        se = np.array([float(r["se_v"]) if r["se_v"] else 0.0 for r in mine])
        line, = ax.plot(n, mean, label=exp.name, lw=1)
        ax.fill_between(n, mean - se, mean + se, color=line.get_color(), alpha=0.2, lw=0)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("n (collisions)")
    ax.set_ylabel("<v_n> (particles still moving)")
    ax.set_title(f"{scene.name}: eps = {scene.eps:g} ({manifest['particles']} per curve)",
                 fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def _groups(scene, data):
    names = list(dict.fromkeys(name for name, _ in data))  # in file order
    if scene.kind == "escape":
        return [(scene.name, names)]
    by_width = defaultdict(list)
    for name in names:
        by_width[name.rpartition("/")[0]].append(name)
    return [(f"{scene.name} {w}".strip(), ns) for w, ns in by_width.items()]


FIT_STYLES = ("--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))  # one per regime, cycled


def _draw(ax, curve, fit, scene, label, colour, style="--"):
    """The fitted law, dashed in the curve's colour, anchored at the data's survival at its
    window start; its legend entry names the curve, the law and its window."""
    a = boundary_index(curve, fit.window.start)
    x = np.geomspace(fit.window.start, fit.window.end, 200)
    p = curve_probability(curve)[a] * np.exp(fit.log_survival(x))
    xs = np.sqrt(x) if scene.kind == "escape" and curve.clock == "time" else x
    ax.plot(xs, p, color=colour, ls=style, lw=1.2, label=f"{curve.curve}: {label}")


def _fit_lines(ax, curve, fit, window, scene, colour):
    """Draw the maximum-likelihood fits of one curve; returns the report lines."""
    name = f"{curve.curve} ({curve.clock})"
    try:
        if fit == "regimes":
            result = analyse(curve)
            out = []
            for i, (law, regime) in enumerate(zip(result["_regime_fits"], result["regimes"],
                                                  strict=True)):
                _draw(ax, curve, law, scene, f"{regime['law'].replace('_', ' ')} on"
                      f" [{regime['from']:g}, {regime['to']:g}]", colour,
                      FIT_STYLES[i % len(FIT_STYLES)])
                out.append(f"{name}: {regime['law'].replace('_', ' ')} for x in "
                           f"[{regime['from']:g}, {regime['to']:g}]")
            out.append(f"{name}: late regime, best {best_law_text(result)}")
            return out
        a, b = (boundary_index(curve, w) for w in window)
        law = fit_law(FIT_LAWS[fit], window_of(curve, min(a, b), max(a, b)))
    except ValueError as err:
        return [f"{name}: no fit: {err}"]
    _draw(ax, curve, law, scene, f"{law.law.replace('_', ' ')} on [{law.window.start:g},"
          f" {law.window.end:g}]", colour)
    model = {**law.params, **{f"{k}_ci95": ci for k, ci in law.ci95.items()}}
    params = ", ".join(f"{k} = {v:.4g} {interval_text(model, k)}"
                       for k, v in law.params.items())
    return [f"{name}: {law.law.replace('_', ' ')} ({params}) by maximum likelihood on "
            f"[{law.window.start:g}, {law.window.end:g}]"]


def _axes(ax, scene, clock, title, manifest):
    ax.set_yscale("log")
    ax.set_ylim(0.3 / manifest["particles"], 1.5)
    if scene.kind == "escape" and clock == "time":
        ax.set_xlabel("sqrt(t)")
    else:
        ax.set_xscale("log")
        ax.set_xlabel("n (collisions)" if clock == "collisions" else "t")
    ax.set_ylabel("P")
    ax.set_title(f"{title} ({manifest['particles']} per curve)", fontsize=9)
    ax.legend(fontsize=7)
