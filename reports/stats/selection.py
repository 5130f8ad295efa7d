"""Which law: likelihood-ratio tests for the nested pairs, Vuong's test for the non-nested one.

Nesting (``likelihood``): the stretched exponential exp(-c x**beta) is the exponential at
beta = 1, an interior point, and the power law at beta = 0, the boundary of beta >= 0. So

    exponential vs stretched   Lambda_e = 2 (l_s - l_e),  p_e = P(chi^2_1 > Lambda_e)
    power law   vs stretched   Lambda_p = 2 (l_s - l_p),  p_p = P(chibar^2 > Lambda_p)
                               = (1/2) P(chi^2_1 > Lambda_p) for Lambda_p > 0, 1 at 0

(chi-bar-squared: under the power law the estimate of beta sits on the boundary half the
time, Self & Liang 1987). Exponential vs power law are not nested: Vuong's statistic on the
per-particle log-likelihood ratios r_i = log p_exp(cell_i) - log p_pow(cell_i) (each particle's
cell: its escape bin or its censoring point),

    Z = sum_i r_i / (sqrt(n) omega),  omega^2 = mean of (r_i - rbar)^2,  p = 2 Phi(-|Z|),

Z > 0 favouring the exponential (as Clauset, Shalizi and Newman 2009 use it).

Decision at level LEVEL = 0.05 ("a law is rejected" means its test against the stretched law
has p < LEVEL):

1. neither simple law rejected: Vuong decides between them if its p < LEVEL, else
   ``inconclusive``;
2. exactly one simple law rejected: the other one;
3. both rejected: ``stretched_exponential`` (significantly better than either simple law).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2, norm

from reports.stats.likelihood import cell_log_probs

LEVEL = 0.05
INCONCLUSIVE = "inconclusive"


def lr_exponential(fits):
    """(Lambda_e, p_e): exponential (beta = 1) against the stretched law."""
    lam = max(0.0, 2.0 * (fits["stretched_exponential"].loglik - fits["exponential"].loglik))
    return lam, float(chi2.sf(lam, 1))


def lr_power_law(fits):
    """(Lambda_p, p_p): power law (boundary beta = 0) against the stretched law, chi-bar^2."""
    lam = max(0.0, 2.0 * (fits["stretched_exponential"].loglik - fits["power_law"].loglik))
    return lam, (0.5 * float(chi2.sf(lam, 1)) if lam > 0 else 1.0)


def vuong(fit_a, fit_b):
    """(Z, p) of Vuong's test, Z > 0 favouring ``fit_a``; both fits on the same window."""
    w = fit_a.window
    pa = np.concatenate(cell_log_probs(fit_a.law, fit_a.scale, fit_a.params.get("beta"), w))
    pb = np.concatenate(cell_log_probs(fit_b.law, fit_b.scale, fit_b.params.get("beta"), w))
    n = np.concatenate([w.escapes, w.weights])
    use = n > 0
    r, n = (pa - pb)[use], n[use]
    total = n.sum()
    mean = float(np.dot(n, r) / total)
    omega = math.sqrt(float(np.dot(n, (r - mean) ** 2) / total))
    if omega == 0.0:
        return 0.0, 1.0
    z = mean * math.sqrt(total) / omega
    return z, float(2.0 * norm.sf(abs(z)))


def choose(fits):
    """The decision rule of the module docstring: (best law, the tests as a dict)."""
    lam_e, p_e = lr_exponential(fits)
    lam_p, p_p = lr_power_law(fits)
    z, p_v = vuong(fits["exponential"], fits["power_law"])
    tests = {
        "lr_stretched_vs_exponential": {"statistic": lam_e, "p": p_e},
        "lr_stretched_vs_power_law": {"statistic": lam_p, "p": p_p},
        "vuong_exponential_vs_power_law": {"statistic": z, "p": p_v},
        "level": LEVEL,
    }
    exp_rejected, pow_rejected = p_e < LEVEL, p_p < LEVEL
    if exp_rejected and pow_rejected:
        best = "stretched_exponential"
    elif exp_rejected:
        best = "power_law"
    elif pow_rejected:
        best = "exponential"
    elif p_v < LEVEL:
        best = "exponential" if z > 0 else "power_law"
    else:
        best = INCONCLUSIVE
    return best, tests
