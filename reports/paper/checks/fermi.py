"""Fermi acceleration at eps = 0.6 against the published exponents: <v_n> ~ n**(1/2) per
collision and <v(t)> ~ t**(1/3) in continuous time (rows of the physics-check table), on the
ensemble of ``reports.paper.studies.fermi_ensemble``.
"""

from __future__ import annotations

from reports.paper.checks.physics_table import Check, agree


def fermi_checks(fermi):
    common = (f"eps = 0.6, {fermi.particles} starts in the paper's escape box, no holes; "
              "+- = bootstrap over 64 particle blocks")
    return [
        Check("<v> ~ n^beta (per collision)", fermi.beta_n, fermi.beta_n_err, 0.5,
              f"slope of log<v_n> vs log n for {fermi.n_window[0]:g} <= n <= "
              f"{fermi.n_window[1]:g}; {common}", agree(fermi.beta_n, fermi.beta_n_err, 0.5)),
        Check("<v> ~ t^beta (continuous time)", fermi.beta_t, fermi.beta_t_err, 1 / 3,
              f"slope of log<v(t)> vs log t for {fermi.t_window[0]:g} <= t <= "
              f"{fermi.t_window[1]:.3g} (all particles reach it); {common}",
              agree(fermi.beta_t, fermi.beta_t_err, 1 / 3)),
    ]
