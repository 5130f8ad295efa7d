"""Seed Fig. 4: h = 1, discrete against continuous time, stretched fits.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from reports.paper.fig3_transport import TAIL_DECADE, transport_curve, transport_dominance
from reports.paper.runs import read_manifest, run_summary
from reports.paper.sampling import fmt
from reports.paper.style import band, caption, chi2_dof, pyplot, save_figure
from reports.runs.survival import read_survival
from reports.stats.least_squares import fit_survival

TAIL_SURVIVORS = 20  # Fig. 4 follows P_11's tail down to 20 survivors (Wilson-weighted)


def _fig4_windows(data, h, clock, n):
    """Fit windows for P_11's tail: from x_q (where P_11 + P_12 has fallen to q, the late time
    of Fig. 3) and from 10 x_q, to the last point with >= TAIL_SURVIVORS survivors."""
    c = transport_curve(data, f"h={h}/P11", clock)
    dom = transport_dominance(data, h, n, clock)
    if c is None or dom is None:
        return []
    x, p = c[0], c[1]
    ok = (x > 0) & (p >= TAIL_SURVIVORS / n)
    if not ok.any():
        return []
    end = float(x[ok][-1])
    out = []
    for start in (dom["t_q"], TAIL_DECADE * dom["t_q"]):
        if ((x >= start) & (x <= end) & ok).sum() >= 5:
            out.append((max(start, float(x[x > 0][0])), end))
    return out


def _tail_fits(c, window):
    st = fit_survival(*c, "stretched", window)
    pw = fit_survival(*c, "power", window)
    return st, chi2_dof(st, *c), pw, chi2_dof(pw, *c)


def figure_h1(run_dir, out_dir, h="1"):
    plt = pyplot()
    man = read_manifest(run_dir)
    n = man["particles"]
    data = read_survival(Path(run_dir) / "survival.csv")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    fits = {}
    for ax, clock in zip(axes, ("collisions", "time"), strict=True):
        for ij in ("P11", "P12", "P21", "P22"):
            c = transport_curve(data, f"h={h}/{ij}", clock)
            if c is not None:
                band(ax, *c, ij)
        c = transport_curve(data, f"h={h}/P11", clock)
        for k, window in enumerate(_fig4_windows(data, h, clock, n)):
            try:
                fits[clock, k] = _tail_fits(c, window)
            except (ValueError, RuntimeError):
                continue
            if k == 0:
                st, _, pw, _ = fits[clock, k]
                xf = np.geomspace(*window, 100)
                ax.plot(xf, st(xf), "k--", lw=1.2,
                        label=f"P11 fit a exp(b sqrt x): b = {fmt(st.b, st.b_err)}")
                ax.plot(xf, pw(xf), ":", color="grey", lw=1.2,
                        label=f"P11 power fit: b = {fmt(pw.b, pw.b_err)}")
                ax.axvline(window[0], color="grey", ls=":", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(0.3 / n, 1.5)
        ax.set_xlabel("n (collisions)" if clock == "collisions" else "t")
        ax.set_ylabel("P_ij")
        ax.set_title(("discrete" if clock == "collisions" else "continuous") + " time",
                     fontsize=10)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle(f"Fig. 4: transport for h = {h}, discrete vs continuous time, stretched-"
                 "exponential fits to P_11", fontsize=11)
    caption(fig, run_summary(run_dir) + " (per entry hole)")
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    return save_figure(fig, out_dir, "paper_fig4_h1"), fits


def h1_markdown(fits, image):
    lines = [
        "### Fig. 4: h = 1, discrete against continuous time",
        "",
        f"![Fig. 4: h = 1]({image})",
        "",
        "Seed's claim: the long-lived reflected orbits (P_11) are well approximated by a "
        "stretched exponential a exp(b sqrt(x)) in both discrete and continuous time; the "
        "transmitted orbits (P_12) decay within many fewer collisions.",
        "",
        "Computed: both models fitted to P_11 from x_q (where P_11 + P_12 has fallen to q, as "
        "in Fig. 3: the reflected tail alone) and from 10 x_q, to the last point with >= "
        f"{TAIL_SURVIVORS} survivors; chi^2/dof compared (the survival points are correlated: "
        "read chi^2 as a comparison).",
        "",
        "| clock | window | a exp(b sqrt x): b | chi2/dof | a x^b: b | chi2/dof | better |",
        "|---|---|---|---|---|---|---|",
    ]
    better = []
    for (clock, _k), (st, cs, pw, cp) in fits.items():
        b = "stretched" if cs < cp else "power law"
        better.append(b == "stretched")
        lines.append(f"| {clock} | {st.window[0]:.3g} - {st.window[1]:.3g} | "
                     f"{fmt(st.b, st.b_err)} | {cs:.3g} | {fmt(pw.b, pw.b_err)} | {cp:.3g} |"
                     f" {b} |")
    verdict = ("**confirmed**" if better and all(better) else "**not confirmed**"
               if better and not any(better) else "**partly confirmed**" if better
               else "**undecided** (too few particles)")
    lines += ["", f"Stretched exponential better than a power law for P_11: {verdict} "
                  f"({sum(better)} of {len(better)} windows).", ""]
    return "\n".join(lines)
