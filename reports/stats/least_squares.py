"""Least-squares fits of survival curves (``bouncer plot --fit``).

Fits (``fit_survival``) over a window of x, by ``scipy.optimize.curve_fit`` on log P with the
band's width as the standard deviation, give the parameters with standard errors:

    exponential   P = a*exp(b*x)
    stretched     P = a*exp(b*sqrt(x))
    power         P = a*x**b
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import curve_fit

from reports.runs.survival import Z95

MODELS = {
    "exponential": lambda x: x,
    "stretched": np.sqrt,
    "power": np.log,
}


FORMULAS = {
    "exponential": "a*exp(b*x)",
    "stretched": "a*exp(b*sqrt(x))",
    "power": "a*x**b",
}


@dataclass(frozen=True)
class Fit:
    """Fitted parameters of P = model(x; a, b) with one-sigma standard errors."""

    model: str
    a: float
    b: float
    a_err: float
    b_err: float
    window: tuple[float, float]
    points: int

    def __str__(self):
        return (f"{FORMULAS[self.model]}: a = {self.a:.4g} +- {self.a_err:.2g}, "
                f"b = {self.b:.4g} +- {self.b_err:.2g} ({self.points} points in "
                f"[{self.window[0]:g}, {self.window[1]:g}])")

    def __call__(self, x):
        return self.a * np.exp(self.b * MODELS[self.model](np.asarray(x, dtype=np.float64)))


def fit_survival(x, p, p_lo, p_hi, model, window):
    """Fit ``model`` (exponential, stretched, power) to the points with x in ``window``.

    log P is fitted linearly in g(x) (x, sqrt(x), log x) with sigma = (log p_hi - log p_lo)/2z,
    the band in log space; absolute sigma, so the standard errors are statistical.
    Raises ValueError for an unknown model or fewer than 3 usable points.
    """
    if model not in MODELS:
        raise ValueError(f"fit model must be one of {', '.join(MODELS)}, got {model!r}")
    x, p = np.asarray(x, dtype=np.float64), np.asarray(p, dtype=np.float64)
    lo, hi = window
    use = (x >= lo) & (x <= hi) & (p > 0) & (np.asarray(p_lo) > 0)
    if model == "power":
        use &= x > 0
    if use.sum() < 3:
        raise ValueError(f"fewer than 3 points with P > 0 in the window [{lo:g}, {hi:g}]")
    g = MODELS[model](x[use])
    sigma = (np.log(np.asarray(p_hi)[use]) - np.log(np.asarray(p_lo)[use])) / (2 * Z95)
    (log_a, b), cov = curve_fit(lambda g, log_a, b: log_a + b * g, g, np.log(p[use]),
                                sigma=sigma, absolute_sigma=True)
    err = np.sqrt(np.diag(cov))
    a = float(np.exp(log_a))
    return Fit(model, a, float(b), a * float(err[0]), float(err[1]), (float(lo), float(hi)),
               int(use.sum()))
