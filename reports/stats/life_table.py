"""The life table (actuarial survival) of a binned escape curve in a fit window.

In bin j the particles at risk at x_j, less half the competing escapes of the bin,
r_j = n_j - C_j/2, face E_j escapes: q_j = E_j / r_j, and the survival since the window start is
S(x_{j+1}) = prod_{i <= j} (1 - q_i), with Greenwood's variance of log S,
sum_{i <= j} q_i / (r_i (1 - q_i)).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class LifeTable(NamedTuple):
    """x: the window's bin boundaries; survival: S at them (1 at the start); sd_log: Greenwood's
    standard deviation of log S; at_risk: r_j per bin; escapes: E_j per bin; at_risk_after: the
    particles still in the system after the window's last bin."""

    x: np.ndarray
    survival: np.ndarray
    sd_log: np.ndarray
    at_risk: np.ndarray
    escapes: np.ndarray
    at_risk_after: float


def life_table(curve, window):
    """The life table of ``curve`` (a ``reports.stats.histogram`` curve) over ``window``."""
    a = int(np.searchsorted(curve.x, window.start))
    b = a + len(window.escapes)
    later = (curve.escapes + curve.competing + curve.censored)[::-1].cumsum()[::-1]
    risk = later[a:b] - 0.5 * curve.competing[a:b]
    e = curve.escapes[a:b].astype(np.float64)
    q = np.divide(e, risk, out=np.zeros_like(e), where=risk > 0)
    s = np.concatenate([[1.0], np.cumprod(1.0 - q)])
    terms = np.divide(q, risk * (1.0 - q), out=np.zeros_like(q), where=(risk > 0) & (q < 1))
    sd_log = np.sqrt(np.concatenate([[0.0], np.cumsum(terms)]))
    after = float(later[b]) if b < len(later) else 0.0
    return LifeTable(window.x, s, sd_log, risk, e, after)
