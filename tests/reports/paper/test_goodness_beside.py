"""Pearson's chi-squared stands beside every model comparison and every form read on beta."""

import re

import numpy as np

from reports.paper.claims.well_approximated_claims import selection_member
from reports.paper.claims.window_members import beta_member
from reports.stats.calibration import draw
from reports.stats.goodness import pearson
from reports.stats.likelihood import fit_law, window_of


def test_the_selection_and_the_form_say_each_laws_chi_squared_and_p():
    curve = draw("stretched_exponential", 100_000, np.random.default_rng(3))
    window = (20, 60)
    chosen = selection_member(curve, window, "n")
    for law in ("exponential", "power law", "stretched exponential"):
        assert re.search(law + r" chi\^2/dof = [0-9.e+]+/\d+, p = ", chosen.variant), law
    form = beta_member(curve, window, "sqrt", "n")
    g = pearson(fit_law("stretched_exponential", window_of(curve, *window)))
    assert f"chi^2/dof = {g.chi2:.4g}/{g.dof}, p = {g.p:.2g}" in form.variant
