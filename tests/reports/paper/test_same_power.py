"""Where "the same power" is read: the matched survival levels of
``reports.paper.claims.same_power_claims``."""

from types import SimpleNamespace

import numpy as np

from reports.paper.claims import same_power_claims as same_power
from reports.stats.hazard import all_cause_survival
from reports.stats.histogram import Curve


def _curve(per_bin=0.3, bins=60, n=10**6):
    """A continuous-time curve losing ``per_bin`` of the survivors in every bin."""
    alive = n * (1 - per_bin) ** np.arange(bins + 1)
    escapes = np.round(-np.diff(alive)).astype(np.int64)
    escapes[-1] += n - escapes.sum()
    zeros = np.zeros(bins, dtype=np.int64)
    return Curve(source="synthetic", experiment="e", curve="c", clock="time",
                 x=np.geomspace(1.0, 1e6, bins + 1), escapes=escapes, competing=zeros,
                 censored=zeros, mid=np.geomspace(1.0, 1e6, bins), particles=n)


class _Stretched:
    """An intermediate stretched law S = exp(-c (x^beta - x_0^beta)) from the curve's start."""

    def __init__(self, beta, c=1.0):
        self.params = {"beta": beta, "c": c}

    def log_survival(self, x):
        return -self.params["c"] * (np.asarray(x) ** self.params["beta"] - 1.0)


def _analysis(beta):
    curve = _curve()
    windows = SimpleNamespace(level_tail=1e-2, level_end=1e-6)
    details = {("time", "intermediate"): {"bins": (0, 10),
                                          "fits": {"stretched_exponential": _Stretched(beta)}}}
    return {"curves": {"time": curve}, "windows": windows, "details": details}


def test_an_algebraic_intermediate_decay_has_no_accelerating_population_to_wait_out():
    """With the intermediate continuous-time law in the power-law cell (beta < 1/4: the holes
    in the chaotic sea), the matched levels start at the late tail's level P(n_tail); a stretched
    intermediate law (beta = 1/2) that still explains the survivors there holds them back."""
    algebraic = _analysis(0.05)
    assert not same_power.accelerating(algebraic)
    s = all_cause_survival(algebraic["curves"]["time"])
    start = same_power.matched_start_level(algebraic)
    assert start == s[np.flatnonzero(s <= 1e-2)[0]]
    stretched = _analysis(0.5)
    assert same_power.accelerating(stretched)
    stretched["details"][("time", "intermediate")]["fits"]["stretched_exponential"] = \
        _Stretched(0.5, c=1e-6)  # decays far slower than the curve: explains every survivor
    assert same_power.matched_start_level(stretched) is None
