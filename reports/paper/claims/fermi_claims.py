"""The paper's Fermi-acceleration claims ``fermi-n`` and ``fermi-t`` decided on the ensemble of
``reports.paper.studies.fermi_ensemble``, over the windows inside its diffusive regime.
"""

from __future__ import annotations

import math

from reports.paper.claims import family as F
from reports.paper.claims.register import make_claim
from reports.paper.claims.rules import SAME, SAME_FAILS, relative_band
from reports.paper.claims.window_family import STEP
from reports.paper.studies.fermi_ensemble import _window_slope
from reports.paper.studies.sampling import bootstrap_blocks, verified_text


def inside_windows(window):
    """The diffusive window (lo, hi), its start a quarter decade later, its end a quarter decade
    earlier, and both (``reports.paper.claims.window_family.STEP``)."""
    lo, hi = window
    return [(lo, hi), (lo * STEP, hi), (lo, hi / STEP), (lo * STEP, hi / STEP)]


def fermi_claims(fermi):
    """Claims ``fermi-n`` (<v_n> ~ n^(1/2)) and ``fermi-t`` (t ~ n^(3/2), i.e. <v(t)> ~
    t^(1/3)), register ``reports.paper.claims.register``.

    Family: the windows inside the diffusive regime (``inside_windows``). Each member: "the
    same" exponent (``reports.paper.claims.rules``, two bounds) on the slope's interval, 1.96 sigma
    (bootstrap over particle blocks): confirmed if it lies within ``rules.SAME`` (10%) of the
    exponent, refuted if it lies wholly beyond ``rules.SAME_FAILS`` (25%) of it, inconclusive
    otherwise.
    """
    out = []
    for key, expected, x, y, window, blocks, unit in (
            ("n", 0.5, fermi.n, fermi.mean_v_n, fermi.n_window, fermi.blocks_n, "n"),
            ("t", 1 / 3, fermi.t, fermi.mean_v_t, fermi.t_window, fermi.blocks_t, "t")):
        band = relative_band(expected, SAME)
        fails = relative_band(expected, SAME_FAILS)
        members = []
        for lo, hi in inside_windows(window):
            beta = _window_slope(x, y, lo, hi)[0]
            def slope(c, lo=lo, hi=hi, x=x):
                return _window_slope(x, c, lo, hi)[0]
            err = bootstrap_blocks(*blocks, slope) if blocks else math.nan
            variant = f"{unit} in [{lo:.4g}, {hi:.4g}]"
            if math.isfinite(beta) and math.isfinite(err):
                members.append(F.band_member(variant, f"slope of log<v> on log {unit}", beta,
                                             beta - 1.96 * err, beta + 1.96 * err, band, fails))
            else:
                members.append(F.too_few(variant, f"slope of log<v> on log {unit}", beta))
        out.append(make_claim(
            f"fermi-{key}", f"{fermi.particles} particles, bootstrap over 64 particle blocks; "
            f"the band [{band[0]:.4f}, {band[1]:.4f}], fails wholly outside [{fails[0]:.4f}, "
            f"{fails[1]:.4f}]: {F.family_text(members)}; {verified_text(fermi.verification)}.",
            analyses=members, particles_per_curve=fermi.particles,
            statistical={"beta": fermi.beta_n if key == "n" else fermi.beta_t}))
    return out
