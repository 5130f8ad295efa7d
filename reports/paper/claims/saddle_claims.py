"""The paper's saddle-point argument for exp(-c_2 sqrt(t)) (Section 3): the time of an orbit of
n collisions has a tail "decaying as e^{-c_1 (t/t_0)^2}", t_0 ~ n sqrt(n) its average; with
the discrete escape e^{-n/n_0} the largest contribution gives "a probability e^{-c_2 sqrt(t)}
with c_2 determined from the other constants".

The closed system (``closed_times``): starts uniform in the paper's escape box at eps = 0.6, no
hole, stepped with ``fastpath.step`` (flights float64 cannot decide settled by ``verify``),
each orbit's time t_n recorded at the collision counts ``N_GRID``. With x = t_n / t_0(n),
t_0(n) = <t_n> = a_0 n^(3/2):

* The Gaussian tail: the upper tail's survival S(x) fitted as log S = a - c x^kappa (least
  squares over the levels of a tail range), kappa against 2 by "the same" rule; members: each
  n of ``N_GRID`` and two tail ranges (``TAIL_RANGES``); intervals by resampling the orbits.
* c_2: with kappa = 2, c_1 from the fit log S = a - c_1 x^2; exponent -n/n_0 - (c_1/a_0^2)
  t^2/n^3 is largest at n* = (3 (c_1/a_0^2) n_0 t^2)^(1/4), so that
  c_2 = (4/3) (3 c_1/a_0^2)^(1/4) n_0^(-3/4), n_0 = 1/gamma of the discrete-time exponential
  fitted on the hole's intermediate window; against the c fitted with beta = 1/2 fixed
  (``reports.stats.likelihood.fit_stretched_fixed``) on each window inside the hole's
  continuous intermediate regime, by "the same" rule; members: each n and each window.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from reports.paper.claims import family as F
from reports.paper.claims.register import make_claim
from reports.paper.claims.window_family import inside_windows, window_label
from reports.paper.claims.window_members import window_fit
from reports.paper.studies.follow import _step_all
from reports.paper.studies.replicates import TAIL_FIT_REPLICATES
from reports.paper.studies.sampling import EPS, ESCAPE_BOX, uniform_box
from reports.paper.studies.seeds import SAMPLING_SEED
from reports.stats.likelihood import fit_stretched_fixed, window_of

N_GRID = (50, 100, 200)
TAIL_RANGES = ((1e-1, 1e-2), (1e-2, 1e-3))
C1_RANGE = (1e-1, 1e-3)
SIZES = {False: 100_000, True: 4000}
GAUSSIAN = 2.0
KAPPA_RANGE = (0.25, 8.0)


@functools.lru_cache(maxsize=2)
def closed_times(quick=False):
    """{n: t_n of every orbit} of the closed system (module docstring)."""
    m = SIZES[bool(quick)]
    rng = np.random.default_rng(SAMPLING_SEED)
    phi, v = uniform_box(rng, ESCAPE_BOX, m)
    t = np.zeros(m)
    out = {}
    for k in range(1, max(N_GRID) + 1):
        phi, v, tau, _ = _step_all(phi, v, EPS)
        t += tau
        if k in N_GRID:
            out[k] = t.copy()
    return out


def tail_points(x, level_hi, level_lo):
    """(x, S(x)) of the empirical upper-tail survival at the sorted values with S in
    [level_lo, level_hi]."""
    xs = np.sort(x)
    s = 1.0 - np.arange(1, len(xs) + 1) / len(xs)
    use = (s <= level_hi) & (s >= level_lo)
    return xs[use], s[use]


def tail_exponent(x, level_hi, level_lo):
    """kappa of the least-squares fit log S = a - c x^kappa over the tail range: the kappa
    whose straight line of log S on x^kappa leaves the least squared residual (a
    golden-section search over ``KAPPA_RANGE``; NaN on its edge)."""
    xs, s = tail_points(x, level_hi, level_lo)
    if len(xs) < 10:
        return math.nan
    y = np.log(s)

    def residual(kappa):
        z = xs ** kappa
        return float(np.sum((y - np.polyval(np.polyfit(z, y, 1), z)) ** 2))
    lo, hi = KAPPA_RANGE
    g = (math.sqrt(5) - 1) / 2
    for _ in range(60):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if residual(a) < residual(b):
            hi = b
        else:
            lo = a
    kappa = 0.5 * (lo + hi)
    # an optimum on the search's edge is no measurement: the range does not fix kappa
    edge = 1e-6 * (KAPPA_RANGE[1] - KAPPA_RANGE[0])
    return kappa if KAPPA_RANGE[0] + edge < kappa < KAPPA_RANGE[1] - edge else math.nan


def gaussian_c1(x, level_hi=C1_RANGE[0], level_lo=C1_RANGE[1]):
    """c_1 of the least-squares fit log S = a - c_1 x^2 over the tail range."""
    xs, s = tail_points(x, level_hi, level_lo)
    if len(xs) < 10:
        return math.nan
    return float(-np.polyfit(xs ** 2, np.log(s), 1)[0])


def _bootstrap(x, statistic, seed=SAMPLING_SEED):
    rng = np.random.default_rng(seed)
    got = np.array([statistic(rng.choice(x, len(x))) for _ in range(TAIL_FIT_REPLICATES)])
    got = got[np.isfinite(got)]
    if len(got) <= TAIL_FIT_REPLICATES // 2:
        return math.nan, math.nan
    return float(np.percentile(got, 2.5)), float(np.percentile(got, 97.5))


def gaussian_tail_claim(quick=False):
    times = closed_times(quick)
    members = []
    for n, t in times.items():
        x = t / t.mean()
        for hi, lo in TAIL_RANGES:
            kappa = tail_exponent(x, hi, lo)
            k_lo, k_hi = _bootstrap(x, lambda s, hi=hi, lo=lo: tail_exponent(s, hi, lo))
            if not math.isfinite(kappa):
                members.append(F.too_few(f"n = {n}, S from {hi:g} to {lo:g}: the range does "
                                         "not fix kappa", "relative difference of kappa from 2"))
                continue
            members.append(F.same_member(
                f"n = {n}, S from {hi:g} to {lo:g}: kappa = {kappa:.3f} [{k_lo:.3f}, "
                f"{k_hi:.3f}]", "relative difference of kappa from 2", kappa,
                0.5 * (k_hi - k_lo) if math.isfinite(k_hi) else math.inf, GAUSSIAN, 0.0))
    m = len(next(iter(times.values())))
    return make_claim("sec3-gaussian-tail", f"The closed system, {m:,} orbits from the paper's "
                      "box at eps = 0.6, x = t_n/<t_n>, log S(x) = a - c x^kappa on the upper "
                      f"tail: {F.family_text(members)}.", analyses=members,
                      particles_per_curve=m)


def predicted_c2(c1, a0, n0):
    """c_2 = (4/3) (3 c_1/a_0^2)^(1/4) n_0^(-3/4) (module docstring)."""
    return 4.0 / 3.0 * (3.0 * c1 / a0 ** 2) ** 0.25 * n0 ** -0.75


def c2_claim(hole, a, quick=False):
    cid = f"sec3-c2-phi_c={hole}"
    w_n = a["windows"].n.get("intermediate")
    w_t = a["windows"].t.get("intermediate")
    if w_n is None or w_t is None:
        return make_claim(cid, "No intermediate window in one of the clocks.")
    cn, ct = a["curves"]["collisions"], a["curves"]["time"]
    exp_fit = window_fit(cn, w_n, "exponential", intervals=True)
    gamma = exp_fit.params["gamma"]
    g_lo, g_hi = exp_fit.ci95["gamma"]
    fitted = []
    for w in inside_windows(ct, *w_t, 1000):
        f = fit_stretched_fixed(window_of(ct, *w), 0.5)
        fitted.append((window_label(ct, w, "t"), f.params["c"], f.ci95["c"]))
    members = []
    for n, t in closed_times(quick).items():
        a0 = t.mean() / n ** 1.5
        x = t / t.mean()
        c1 = gaussian_c1(x)
        c1_lo, c1_hi = _bootstrap(x, gaussian_c1)
        c2 = predicted_c2(c1, a0, 1 / gamma)
        # the prediction's interval: c_1's and n_0's intervals through c_2's powers 1/4, 3/4
        lo = predicted_c2(c1_lo, a0, 1 / g_lo)
        hi = predicted_c2(c1_hi, a0, 1 / g_hi)
        for label, c_fit, (f_lo, f_hi) in fitted:
            members.append(F.same_member(
                f"n = {n} (c_1 = {c1:.4g}, a_0 = {a0:.4g}) against {label}: predicted "
                f"{c2:.4f} [{min(lo, hi):.4f}, {max(lo, hi):.4f}], fitted {c_fit:.4f} "
                f"[{f_lo:.4f}, {f_hi:.4f}]", "relative difference of c_2", c2,
                0.5 * abs(hi - lo), c_fit, 0.5 * (f_hi - f_lo)))
    return make_claim(cid, f"n_0 = 1/gamma = {1 / gamma:.4g} from the discrete intermediate "
                      f"window; {F.family_text(members)}.", analyses=members,
                      particles_per_curve=cn.particles)
