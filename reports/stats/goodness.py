"""Absolute goodness of fit of a survival law on its window: Pearson's chi-squared.

A likelihood ratio says which of two laws fits better, not whether either fits. Beside every
model comparison the report gives this test of the fitted law alone.

In bin j of the window the particles at risk at its start, less half the competing escapes of
the bin (the actuarial convention of ``life_table``), r_j, face the law's conditional escape
probability q_j = 1 - S(x_{j+1})/S(x_j). Given the past, the escapes O_j are binomial(r_j, q_j):
expected E_j = r_j q_j, variance V_j = r_j q_j (1 - q_j), and the O_j - E_j are uncorrelated (a
martingale), so over groups g of bins

    X^2 = sum_g (O_g - E_g)^2 / V_g,   O_g = sum_{j in g} O_j, ...,   dof = groups - parameters

is chi-squared with dof degrees of freedom when the law is right. Groups are quarter decades of
the clock (``hazard.HAZARD_PER_DECADE``; bins below x = 1 one by one), merged with the next until
E_g >= ``MIN_EXPECTED`` (the chi-squared approximation), the last one into the one before it.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from scipy.stats import chi2

from reports.stats.hazard import HAZARD_PER_DECADE

MIN_EXPECTED = 5.0


class GoodnessOfFit(NamedTuple):
    """Pearson's X^2 of a fit, its degrees of freedom and p-value (NaN without a degree of
    freedom), and the number of groups."""

    chi2: float
    dof: int
    p: float
    groups: int

    @property
    def per_dof(self):
        return self.chi2 / self.dof if self.dof > 0 else math.nan

    def text(self):
        return (f"chi^2 = {self.chi2:.4g} on {self.dof} dof (chi^2/dof = {self.per_dof:.3g}), "
                f"p = {self.p:.2g}")


def _groups(x, per_decade=HAZARD_PER_DECADE):
    """Bin index groups [(a, b)] of about 1/per_decade decade over boundaries x."""
    groups, a, m = [], 0, len(x) - 1
    while a < m:
        if x[a] < 1.0:
            b = a + 1
        else:
            b = int(np.searchsorted(x, x[a] * 10.0 ** (1.0 / per_decade) * (1 - 1e-12)))
            b = min(max(b, a + 1), m)
        groups.append((a, b))
        a = b
    return groups


def pearson(fit):
    """``GoodnessOfFit`` of a ``likelihood.LawFit`` on its window (module docstring)."""
    w = fit.window
    x = w.x
    log_s = fit.log_survival(x)
    q = -np.expm1(np.diff(log_s))
    q = np.clip(q, 0.0, 1.0)
    competing_in_bin = np.zeros(len(w.escapes))
    inside = w.points < x[-1]
    k = np.searchsorted(x, w.points[inside], side="right") - 1
    np.add.at(competing_in_bin, np.clip(k, 0, len(w.escapes) - 1), w.weights[inside])
    gone = w.escapes + competing_in_bin
    risk_start = w.at_risk - np.concatenate([[0.0], np.cumsum(gone)[:-1]])
    r = risk_start - 0.5 * competing_in_bin
    e, v = r * q, r * q * (1 - q)
    o_g, e_g, v_g = [], [], []
    for a, b in _groups(x):
        if e_g and e_g[-1] < MIN_EXPECTED:
            o_g[-1] += w.escapes[a:b].sum()
            e_g[-1] += e[a:b].sum()
            v_g[-1] += v[a:b].sum()
        else:
            o_g.append(w.escapes[a:b].sum())
            e_g.append(e[a:b].sum())
            v_g.append(v[a:b].sum())
    if len(e_g) > 1 and e_g[-1] < MIN_EXPECTED:
        o_g[-2] += o_g.pop()
        e_g[-2] += e_g.pop()
        v_g[-2] += v_g.pop()
    o_g, e_g, v_g = map(np.asarray, (o_g, e_g, v_g))
    use = v_g > 0
    stat = float(np.sum((o_g[use] - e_g[use]) ** 2 / v_g[use]))
    dof = int(use.sum()) - fit.k
    p = float(chi2.sf(stat, dof)) if dof > 0 else math.nan
    return GoodnessOfFit(stat, dof, p, int(use.sum()))
