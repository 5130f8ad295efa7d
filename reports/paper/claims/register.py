"""The register of the paper's checkable claims, as data, written before any verdict.

One entry per claim: id, figure, our one-line reading (``statement``), the paper's words
verbatim (``quote``; whitespace may differ, "..." elides, LaTeX as in the text), the
``observable``, the ``regime`` it speaks of, the ``family`` of analyses its words allow (windows
inside the regime, metrics, levels, curves; ``reports.paper.claims.family``), the ``rule`` that
decides it and the ``tolerance`` of its qualitative words (constants of
``reports.paper.claims.rules``), and its ``source``. Claims made for
several holes or widths have one entry each. The evaluators (``escape_claims``,
``transport_claims``, ``start_claims``, ``geometry_claims``, ``fermi_claims``, ...) compute the
members of each family and the evidence; ``make_claim`` joins them to the entry into a ``Claim``
whose verdict is their agreement.

``quote_found(quote, text)`` is how a quote is checked against the paper's text (the test
``tests/reports/paper/test_register.py`` runs it when ``BOUNCER_PAPER_TEXT`` names the file).
"""

from __future__ import annotations

from reports.paper.claims import rules as R
from reports.paper.claims.claim import Claim, agreement
from reports.paper.claims.family import analyses_json
from reports.paper.claims.register_entry import AGREE, entry_of
from reports.paper.claims.register_section2 import section2_entries
from reports.paper.claims.window_family import LATE_MEMBERS
from reports.paper.studies.escape_regimes import (
    HAZARD_FAST,
    HAZARD_TENTH,
    ONSET_TOLERANCE,
    SURVIVORS_MIN,
)
from reports.paper.studies.followed_samples import ISLAND_COLLISIONS

ISLAND_HOLES = ("0", "0.5", "1", "1.5")  # the paper's Fig. 2 caption
SEA_HOLES = ("2", "2.5")
WIDTHS = ("0.1", "0.4", "1", "2.2")
TRAPPING_WIDTHS = ("0.4", "1")  # "a very strong P_11(t) for hole sizes h = 0.4 and h = 1"

Q_HOLES = ("Holes with $\\phi_c=0,0.5,1,1.5$ are located over or near the large elliptic islands,"
           " while holes with $\\phi_c=2,2.5$ are almost entirely in the chaotic sea.")
Q_DISCRETE = ("The two plots on the left are for discrete time, showing primarily exponential "
              "decay in the former case, and algebraic in the latter.")
Q_INTERMEDIATE_N = ("We now focus on the intermediate behaviour in the case where the hole largely"
                    " blocks orbits near the elliptic islands. When measured in discrete time, "
                    "this is exponential as expected for strongly chaotic systems.")
Q_INTERMEDIATE_T = ("When escape is measured in continuous time (right plots), the rapid decay is "
                    "instead close to a stretched exponential, with $\\sqrt{t}$ in the exponent.")
Q_STAGES = ("For a hole placed over part of the elliptic islands, decay is initially slower, as it"
            " takes some time for the dynamics to ``find'' regions close to the elliptic islands, "
            "faster at intermediate times, as the hole covers sticky orbits which would slow "
            "decay")
Q_TAIL = ("and eventually a slow power law, as islands not covered by the hole become "
          "significant.")
Q_SEA_SLOWED = ("Where the hole is in the chaotic sea, decay is generally slowed by the available"
                " large elliptic islands.")
Q_SAME_POWER_CAPTION = "The algebraic decay has the same power as for discrete time."
Q_SAME_POWER_TEXT = ("The algebraic decays in continuous time are, however, the same as in "
                     "discrete time")
Q_BOUNDED = ("this is because it is dominated by orbits near the elliptic island, which do not "
             "accelerate, and in fact have tightly bounded velocity.")
Q_VELOCITY = ("This orbit diffuses in velocity, with a typical velocity proportional to "
              "$\\sqrt{n}$")
Q_TIME = "and hence time $t_0\\approx n\\sqrt{n}$ on average."
Q_N_SQRT_T = ("the largest contribution from $n\\approx(3c_1n_0t^2)^{1/4}$, corresponding to a "
              "probability $e^{-c_2\\sqrt{t}}$")
Q_PLATEAU = ("So, if the initial conditions include an elliptic region not connected with the "
             "hole, the survival probability will tend to a constant as $t\\to\\infty$, giving the"
             " probability of choosing such an initial condition.")
Q_DESTROY_ALL = ("Note that a hole partially covering an island may in fact destroy all orbits "
                 "surrounding that island")
Q_EFFECTIVE = ("here we see effective destruction of islands using holes quite a lot smaller than "
               "the islands concerned.")
Q_OTHER_SET = ("any other reasonably large set in the chaotic region ... would give the same "
               "results, at least at long times.")
Q_OTHER_DENSITY = ("any other reasonably large set in the chaotic region and any other smooth "
                   "density would give the same results, at least at long times.")
Q_UNIVERSAL = ("We do not observe a universal law, perhaps due to the small number of prominent "
               "islands considered in our system")
Q_HOLES_4 = ("Holes near $\\phi=0$ will cover both elliptic islands and chaotic sea, while holes "
             "near $\\phi=\\pi$ will cover mostly chaotic sea.")
Q_HOLE_2 = ("The second hole is centred at $\\pi$; this covers some of the smaller islands, and is"
            " far from the large islands around $\\phi=0$, so for practical purposes it is in the "
            "strongly chaotic region.")
Q_EVENTUAL = ("If the particle always eventually escapes (as would follow from Poincar\\'e's "
              "recurrence theorem if the phase space were of finite invariant measure, and is "
              "probably still true here), we have ... \\sum_j P_{ij}(0)=1")
Q_STRONG = ("This figure shows very clearly the effect we are seeking, namely a very strong "
            "$P_{11}(t)$ for hole sizes $h=0.4$ and $h=1$.")
Q_TRAP = ("For these parameter values (and many not shown), the hole in the elliptic region "
          "effectively traps the long-lived orbits near the smaller islands while reducing the "
          "lifetime of orbits near the large island. In other words, orbits near these small "
          "islands cannot reach other parts of phase space without passing through this hole.")
Q_SMALL = ("On the other hand, a hole that is too small ($h=0.1$) does not effectively trap these"
           " orbits")
Q_LARGE = "one that is too large ($h=2.2$) allows all orbits to escape within a finite time."
Q_FIG4_T = ("Another feature we can see, particularly in the plot for hole size $1$, is that the "
            "long lived orbits are well approximated by a stretched exponential, "
            "$ae^{b\\sqrt{t}}$.")
Q_FIG4_N = ("hole size $h=1$, compared for discrete time (left) and continuous time (right), and"
            " fits to the stretched exponential behaviour in both cases.")
Q_FEWER = ("Here we see a difference in the transporting orbits, which decay with many fewer "
           "collisions")
Q_LARGE_V = "these can reach large velocities."
Q_OTHER_H = ("The discrete time plots for the other values of $h$ are even more similar to those "
             "of continuous time given in Fig.~\\ref{f:hs}, and are not shown.")
Q_GAUSSIAN = ("The tail of the distribution of time as a function of $n$ follows a typical "
              "diffusion process, decaying as $e^{-c_1(t/t_0)^2}$")
Q_C2 = ("corresponding to a probability $e^{-c_2\\sqrt{t}}$ with $c_2$ determined from the other "
        "constants.")
Q_FINITE = ("What we can say about the system considered here is that clear stretched exponential "
            "decay is observed, at least for finite times and in some situations")
Q_CAPTION_T = ("Those on the right are for continuous time, showing stretched exponential decay; "
               "note the $t^{1/2}$ on the axis.")
Q_REDUCING = ("the hole in the elliptic region effectively traps the long-lived orbits near the "
              "smaller islands while reducing the lifetime of orbits near the large island.")
Q_MANY = ("For these parameter values (and many not shown), the hole in the elliptic region "
          "effectively traps the long-lived orbits near the smaller islands")
Q_CONCLUSION = ("Here we note that generic mixed phase space allows the asymmetric transport "
                "similar to that observed in the stadium, but with a different functional form, "
                "specifically a stretched exponential for the slowly escaping dynamics.")

BETA_TOL = ("a form word holds if beta's 95% interval widened by its systematic lies nearer "
            "that form than the paper's other two: cells power law [0, 1/4), sqrt(x) "
            "[1/4, 3/4), exponential [3/4, 5/4]; refuted if wholly outside the cell")
CLOSE_TOL = (f"'close to' a form: beta's widened interval within {R.BAND} of it: [0.4, 0.6] for "
             "the sqrt law; refuted if wholly outside")
INTERMEDIATE = ("intermediate, the same orbits in both clocks: from t_D, where <v(t)> reaches "
                f"its diffusive law t^(1/3) (local exponent within {R.pct(ONSET_TOLERANCE)}, "
                "Fermi ensemble from the same start box), and the n where P(n) falls to P(t_D), "
                "to where the discrete-time hazard first falls below "
                f"{HAZARD_FAST} of its plateau (the chaotic population still holds 90% of the "
                "escapes) and the t where P(t) falls to that level; at least "
                f"{R.MIN_ESCAPES_INTERMEDIATE} escapes")
TAIL = ("late tail: from where the discrete-time hazard has fallen to "
        f"{HAZARD_TENTH} of its plateau (the slow population holds 90% of the escapes) to the"
        " last escape before the horizon;"
        f" at least {R.MIN_ESCAPES_TAIL} escapes")
FAM_INSIDE = ("windows inside the intermediate regime, each fitted on its own: the regime's "
              "window, its start a quarter decade later, its end a quarter decade earlier, and "
              f"both; those with at least {R.MIN_ESCAPES_INTERMEDIATE} escapes")
FAM_TAIL = ("the tail's late windows: starts moving later from the tail's start by quarter "
            "decades (never back into the intermediate regime), each to the end of the data, "
            f"every one holding at least {R.MIN_ESCAPES_TAIL} escapes up to the latest, each "
            "fitted on its own")
FAM_LIMIT = ("'eventually', a limit: the tail's late windows (starts moving later from the "
             "tail's start by quarter decades, each to the end of the data) read as a trend: "
             f"the latest {LATE_MEMBERS} holding at least {R.MIN_ESCAPES_TAIL} escapes (the "
             "latest window with enough escapes, and the starts a quarter and a half decade "
             "before it), each fitted on its own")
FAM_FERMI = ("windows inside the diffusive regime: the regime's window, its start a quarter "
             "decade later, its end a quarter decade earlier, and both; each slope with its own "
             "bootstrap interval")
FAM_LONG_TIMES = ("every hole and clock; 'at long times', a limit: the late tail's windows "
                  "(starts moving later by quarter decades from the reference's tail level, "
                  "each to the last bin with 10 particles at risk in both) read as a trend: the "
                  f"latest {LATE_MEMBERS} with enough escapes to decide (a log-rank interval "
                  "narrow enough to fit inside the holds band; its width does not depend on the "
                  "ratio measured); the hazard ratio of each")
FAM_ISLAND_SURVIVAL = ("the share still inside at the study's horizon and at half of it (the "
                       "plateau it tends to)")
FAM_LONG_LIVED = ("long-lived times: the long-lived time and later times a quarter decade "
                  f"apart, every one at which at least {R.fewest_to_reach(R.TRAP_SHARE)} "
                  "entrants of hole 1 remain (with fewer, none leaving by hole 2 cannot show "
                  f"a share at or below {R.pct(R.TRAP_SHARE)}: the bound is out of reach)")
FAM_WELL = ("the long-lived regime's late windows: starts moving later by quarter decades "
            f"from the long-lived time, every one with at least {R.MIN_ESCAPES_TAIL} escapes; "
            "three members each: the model selection, the residual excess and Pearson's "
            "chi-squared")
WELL_RULE = ("'well approximated': each window three members: the three-way comparison "
             "(confirmed if it picks the stretched law, refuted if it picks another, "
             "inconclusive if it cannot choose), the residual excess (confirmed if the law "
             f"stays within {R.RESIDUAL_LEVEL:g} in log S of the data beyond its 95% band where "
             f"at least 100 particles remain, refuted if it strays by at least "
             f"{R.RESIDUAL_FAILS:g}) and the absolute goodness of fit (confirmed if Pearson's "
             f"chi-squared p >= {R.GOF_HOLDS:g}, refuted if p <= {R.GOF_FAILS:g}); {AGREE}")
WELL_TOL = (f"'well approximated': the stretched law wins; excess in log S: "
            f"{R.bounds_text(R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS, '{:g}'.format)}; goodness of "
            f"fit p: {R.bounds_text(R.GOF_HOLDS, R.GOF_FAILS, '{:g}'.format)}; the power in the "
            "exponent is left open by the paper and only reported")
FAM_GEOMETRY = ("the hole's strip in two velocity periods of the nearly periodic phase space: "
                "pi/2 < v < 3 pi/2 (around the island (0, pi)) and 3 pi/2 < v < 5 pi/2 (around "
                "(0, 2 pi)), 2000 random starts each")
LONG_LIVED = (f"long-lived: after the entrants of hole 1 still inside fall to "
              f"{R.LONG_LIVED_LEVEL:g} (P_11 + P_12 <= {R.LONG_LIVED_LEVEL:g}), to the last "
              "escape")


def _bounds(holds, fails, fmt=R.pct):
    return R.bounds_text(holds, fails, fmt)


SAME_TOL = (f"'the same': equal within {R.pct(R.SAME)} (relative), different beyond "
            f"{R.pct(R.SAME_FAILS)}")


_entry = entry_of


def _escape_entries():
    out = []
    for h in ISLAND_HOLES + SEA_HOLES:
        island = h in ISLAND_HOLES
        out.append(_entry(
            f"fig2-hole-phi_c={h}", "2",
            f"the hole of width 0.3 at phi_c = {h} lies "
            + ("over or near the large elliptic islands" if island else
               "almost entirely in the chaotic sea"),
            Q_HOLES,
            ("share of the strip widened by one hole width (phi_c +- 0.45) on the large island "
             "around (0, pi)" if island else "share of the strip phi_c +- 0.15 on any island")
            + ", from 2000 random starts per velocity period classified by their orbits "
              "(reports/paper/studies/islands.py)",
            "phase space at eps = 0.6 (no holes)",
            ("each member: confirmed if the Wilson interval of the share lies at or above "
             f"{R.pct(R.OVER_OR_NEAR)}, refuted if it lies at or below "
             f"{R.pct(R.OVER_OR_NEAR_FAILS)} (a trace: the hole far from the island), "
             f"inconclusive otherwise; {AGREE}" if island else
             f"each member: confirmed if the Wilson interval lies at or below "
             f"{R.pct(R.ALMOST_ENTIRELY)}, refuted if it lies at or above "
             f"{R.pct(R.ALMOST_ENTIRELY_FAILS)} (mostly islands), inconclusive otherwise; "
             f"{AGREE}"),
            ("'over or near', share of the strip widened by one hole width on the island: "
             + _bounds(R.OVER_OR_NEAR, R.OVER_OR_NEAR_FAILS) if island else
             "'almost entirely in the sea', share on islands: "
             + _bounds(R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS)), family=FAM_GEOMETRY))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-n-phi_c={h}", "2",
            f"discrete-time escape through the hole at phi_c = {h} is exponential in its "
            "intermediate regime", Q_INTERMEDIATE_N,
            "stretched exponent beta of the maximum-likelihood fit of P(n) (binned, censored "
            "counts) in the intermediate window", INTERMEDIATE,
            f"form 'exponential' on each member's beta: cell [3/4, 5/4]; {AGREE}", BETA_TOL,
            family=FAM_INSIDE))
    for h in SEA_HOLES:
        out.append(_entry(
            f"fig2-n-phi_c={h}", "2",
            f"discrete-time escape through the hole at phi_c = {h} (chaotic sea) is algebraic",
            Q_DISCRETE,
            "stretched exponent beta of the fit of P(n) in the late tail window", TAIL,
            f"form 'algebraic' (power law) on each member's beta: cell [0, 1/4); {AGREE}",
            BETA_TOL, family=FAM_TAIL))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-n-tail-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} eventually follows a slow power law in "
            "discrete time", Q_TAIL,
            "stretched exponent beta of the fit of P(n) in the late tail window, on the run of "
            f"this hole alone (scene escape-tail-phi_c={h}, 10^9 starts) where one is given, "
            "else on the paper-scale run", TAIL,
            f"form 'power law' on each member's beta: cell [0, 1/4); {AGREE}", BETA_TOL,
            family=FAM_LIMIT))
        out.append(_entry(
            f"fig2-t-phi_c={h}", "2",
            f"continuous-time escape through the hole at phi_c = {h} is close to exp(-c sqrt(t))"
            " in its intermediate regime", Q_INTERMEDIATE_T,
            "stretched exponent beta of the fit of P(t) in the intermediate window",
            INTERMEDIATE, f"'close to' sqrt(t) on each member's beta: band [0.4, 0.6]; {AGREE}",
            CLOSE_TOL, family=FAM_INSIDE))
    for h in ISLAND_HOLES + SEA_HOLES:
        island = h in ISLAND_HOLES
        out.append(_entry(
            f"fig2-same-power-phi_c={h}", "2",
            f"the algebraic decay through the hole at phi_c = {h} has the same power law "
            "exponent in continuous as in discrete time",
            Q_SAME_POWER_TEXT if island else Q_SAME_POWER_CAPTION,
            "the powers of P(n) and P(t) over the same survival levels: power-law exponents "
            "alpha_n and alpha_t (maximum likelihood), and the slope of log t_q on log n_q at "
            "matched levels q (equal powers: slope 1)",
            "matched survival levels: from the first level at or below the late tail's start "
            "level where the continuous-time curve is the non-accelerating population (the "
            "intermediate stretched law, extrapolated, explains at most "
            f"{R.pct(R.CHAOTIC_GONE)} of its survivors), down to {SURVIVORS_MIN}/N",
            "'the same' rule on each member, a +- U_a against b +- U_b (U the 95% half-width): "
            f"confirmed if |a - b| + U <= {R.SAME} x their mean, refuted if |a - b| - U >= "
            f"{R.SAME_FAILS} x their mean, inconclusive otherwise; the slope against 1 with "
            f"U = 0 for 1; {AGREE}",
            SAME_TOL,
            family=("level windows whose start level moves down (later) by quarter decades from "
                    f"the regime's start, every one with at least {R.MIN_ESCAPES_TAIL} escapes "
                    "in each clock; two metrics each: alpha_n against alpha_t, and the "
                    "matched-quantile slope against 1")))
        out.append(_entry(
            f"fig2-bounded-velocity-phi_c={h}", "2",
            f"the orbits of the slow decay through the hole at phi_c = {h} do not accelerate: "
            "their velocity stays bounded", Q_BOUNDED,
            "time per collision t/n (twice the mean velocity) of each escape after n_half, from "
            "joint (n, t) data (the run's joint record where it has one, else a sampled study, "
            "reports/paper/studies/joint_sample.py): slope of log (statistic of t/n) against log "
            "n over quarter decades of n (the variable the escapes are selected on); "
            "Poisson-bootstrap interval",
            "the slow decay: escapes after n_half, where the slow population holds half the "
            f"escapes; at least {R.MIN_ESCAPES_TAIL} escapes",
            f"each member: confirmed if the slope's interval lies within [{R.BOUNDED[0]}, "
            f"{R.BOUNDED[1]}] (bounded velocity), refuted if it lies wholly outside "
            f"[{R.BOUNDED_FAILS[0]}, {R.BOUNDED_FAILS[1]}] (nearer velocity diffusion's 1/2 "
            f"than 0), inconclusive otherwise; {AGREE}",
            f"'tightly bounded velocity': t/n ~ n^s, holds at |s| <= {R.BOUNDED[1]}, fails at "
            f"|s| >= {R.BOUNDED_FAILS[1]}",
            family=("the slow decay's late windows: starts moving later from n_half by quarter "
                    f"decades, each to the last escape, every one with at least "
                    f"{R.MIN_ESCAPES_TAIL} escapes and a slope; two statistics of t/n per "
                    "quarter decade of n: the median and the mean")))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-stages-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} is slower at first and faster at "
            "intermediate times than through the holes in the chaotic sea", Q_STAGES,
            "this hole against the holes at phi_c = 2 and 2.5: the escape rate per collision (the"
            " hazard over a quarter decade of n; their ratio with Poisson intervals) and the "
            "survival P(n) where the stage ends (the ratio with the 95% Wilson bands)",
            "early: where this hole's P falls to 3/4 and to 1/2; intermediate: the middle and "
            "the end of its intermediate window",
            "two parts, 'slower at first' (a lower rate, P above the sea hole's) and 'faster at "
            "intermediate times' (a higher rate, P below it); each member: confirmed if the "
            "ratio's interval lies at or beyond 1 in the stated direction, refuted if it lies "
            "beyond 1 in the other, inconclusive otherwise; a part is the agreement of its "
            "members; the claim is confirmed if both parts are, refuted if one is",
            "none beyond the 95% intervals (an ordering)",
            family=("each part against both sea holes: the escape rate at its two points "
                    "(early: P = 3/4 and P = 1/2; intermediate: the window's middle and end) "
                    "and the survival where the stage ends")))
    for h in SEA_HOLES:
        out.append(_entry(
            f"fig2-sea-slowed-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} is slowed by the large islands: its late "
            "survivors stick to the large island around (0, pi m) and it decays more slowly "
            "than through the island holes", Q_SEA_SLOWED,
            "share of the survivors after n collisions (sampled study, "
            "reports/paper/studies/follow.py) whose next 200 collisions are locked to a period-1 "
            "resonance of the large islands (mean flight time 2 pi m within 1%, velocity within "
            "a band of 5); P(n) against the island holes' P(n) there",
            "late tail: survivors at n_tail, where the slow population holds 90% of the "
            "escapes, and half a decade later",
            "two parts: 'late survivors on the large islands', each member confirmed if the "
            f"Wilson interval of the locked share lies at or above {R.pct(1 - R.MOSTLY)}, "
            f"refuted if at or below {R.pct(1 - R.MOSTLY_FAILS)}; 'slower than through the "
            "island holes', each member confirmed if P(n) lies above the island hole's beyond "
            "the 95% bands, refuted if below; a part is the agreement of its members; the claim "
            "is confirmed if both parts are, refuted if one is",
            "'slowed by the large islands': most of the late survivors there, "
            + _bounds(1 - R.MOSTLY, 1 - R.MOSTLY_FAILS),
            family=("both parts at n_tail and half a decade later; the ordering against each "
                    "island hole")))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"sec3-n-sqrt-t-phi_c={h}", "sec3",
            f"the orbits escaping through the hole at phi_c = {h} at time t in the intermediate "
            "regime made n ~ t^(1/2) collisions", Q_N_SQRT_T,
            "slope of log (statistic of n of the escapes at time t) against log t over quarter "
            "decades of t, from joint (n, t) data (the run's joint record where it has one, "
            "else a sampled study, reports/paper/studies/joint_sample.py); Poisson-bootstrap "
            "interval",
            INTERMEDIATE + " (continuous time); the saddle-point argument is a large-t "
            "statement",
            "band rule on each member's slope: confirmed if its interval lies in [0.4, 0.6], "
            "refuted if wholly outside (the closed system's typical orbit has n ~ t^(2/3)); "
            + AGREE,
            "'n ~ t^(1/2)': slope within 0.1 of 1/2",
            family=("large t: windows whose start moves later by quarter decades from the "
                    "intermediate window's start, each to its end, the latest "
                    f"{LATE_MEMBERS} with at least {R.MIN_ESCAPES_TAIL} escapes and a slope; "
                    "two statistics of n per quarter decade of t: the median and the mean")))
    out += [
        _entry("fermi-n", "fermi", "a chaotic orbit's typical velocity grows as n^(1/2)",
               Q_VELOCITY, "slope of log<v_n> against log n, eps = 0.6, starts in the paper's "
               "escape box, no holes; bootstrap over particle blocks",
               "diffusive: n from 1000 to the end of the ensemble",
               "'the same' exponent, each member: confirmed if the slope's interval (1.96 "
               f"sigma) lies within {R.pct(R.SAME)} of 1/2, [0.45, 0.55]; refuted if it lies "
               f"wholly beyond {R.pct(R.SAME_FAILS)} of it, outside [0.375, 0.625]; "
               f"inconclusive otherwise; {AGREE}",
               f"'proportional to sqrt(n)': exponent within {R.pct(R.SAME)} of 1/2; not beyond "
               f"{R.pct(R.SAME_FAILS)}", family=FAM_FERMI),
        _entry("fermi-t", "fermi", "time grows as n^(3/2), i.e. <v(t)> grows as t^(1/3)",
               Q_TIME, "slope of log<v(t)> against log t, as fermi-n",
               "diffusive: t from 10^4 to the last time all particles reach",
               f"as fermi-n: confirmed within {R.pct(R.SAME)} of 1/3, [0.30, 0.367]; refuted "
               f"wholly beyond {R.pct(R.SAME_FAILS)} of it, outside [0.25, 0.417]; {AGREE}",
               f"'t_0 ~ n sqrt(n)': exponent of <v(t)> within {R.pct(R.SAME)} of 1/3; not beyond"
               f" {R.pct(R.SAME_FAILS)}", family=FAM_FERMI),
        _entry("sec3-other-box", "sec3",
               "a second start box in the chaotic sea gives the same escape at long times",
               Q_OTHER_SET,
               "hazard ratio (log-rank, binned) of the run from the box 3.85 < phi < 4.15, "
               "4.5 < v < 6.5 (scene escape-second-box, 10^7 per hole) against the paper-scale "
               "run, every hole and clock",
               "long times: the late tail, from where the paper-scale curve falls to its tail "
               "level P(n_tail) (the slow population holds 90% of the escapes), in both clocks,"
               " to the last bin with 10 particles at risk in both runs",
               "each member: confirmed if the hazard ratio's 95% interval lies within "
               f"[1/{1 + R.SAME:g}, {1 + R.SAME:g}], refuted if it lies wholly outside "
               f"[1/{1 + R.SAME_FAILS:g}, {1 + R.SAME_FAILS:g}], inconclusive otherwise; one part "
               "per hole and clock, each the agreement of its members; the claim is confirmed if "
               "every part is, refuted if one is",
               f"'the same results': hazards equal within {R.pct(R.SAME)}, different beyond "
               f"{R.pct(R.SAME_FAILS)}", family=FAM_LONG_TIMES),
        _entry("sec3-other-density", "sec3",
               "a second smooth density on the paper's start box gives the same escape at long "
               "times", Q_OTHER_DENSITY,
               "hazard ratio as sec3-other-box, for starts with density proportional to "
               "sin(pi (phi - 3.85)/0.3) sin(pi (v - 2)/2) on the paper's box: a run of the "
               "built-in scene escape-other-density where one is given, else a sampled study "
               "(reports/paper/studies/follow.py)",
               "long times, as sec3-other-box", "as sec3-other-box",
               f"'the same results': hazards equal within {R.pct(R.SAME)}, different beyond "
               f"{R.pct(R.SAME_FAILS)}", family=FAM_LONG_TIMES),
        _entry("sec3-island-start", "sec3",
               "starts touching an island not connected with the hole give a survival that "
               "tends to a constant, the share of starts on the island", Q_PLATEAU,
               "survival P(t) of the scene escape-island-start (hole at pi) over the last two "
               "decades before the horizon t = 10^5; the share of the start box on regular "
               "orbits (reports/paper/studies/islands.py, 4000 random starts)",
               "t -> infinity: the trend of the last two spans before the horizon",
               "two parts: 'tends to a constant', each member confirmed if the fall decelerates "
               "(the last span holds significantly fewer than half of the two spans' escapes), "
               "refuted if it significantly accelerates; 'giving the probability', each member "
               "confirmed if the limit, between P(T) and P(T) minus the geometric continuation of "
               "the falls, equals the regular share under 'the same', refuted if it differs "
               "beyond the uncertainties; a part is the agreement of its members; the claim is "
               "confirmed if both parts are, refuted if one is",
               f"'tends to a constant': a decelerating fall; 'giving the probability': equal "
               f"within {R.pct(R.SAME)}, different beyond {R.pct(R.SAME_FAILS)}",
               family=("the last two decades before the horizon and the last two half decades "
                       "(spans of the trend), each for both parts")),
        _entry("sec3-destroy-all", "sec3",
               "a hole over part of the large island destroys all the orbits surrounding it",
               Q_DESTROY_ALL,
               "share of the starts of the escape-island-start box on the large island (orbits "
               "locked around (0, pi)) that are still inside after n collisions with the hole "
               "of width 0.3 at phi_c = 0 (sampled study)", "t -> infinity (the study's "
               f"horizon, {ISLAND_COLLISIONS} collisions, and the plateau before it)",
               "'all' is an exact word, read at the measurement's floor (one threshold, as "
               f"'eventually escapes'): each member confirmed if at most {R.pct(R.DESTROYED)} "
               "of them remain (Wilson upper bound), refuted if the Wilson lower bound lies at "
               f"or above it; {AGREE}",
               f"'destroy all', share left: at most {R.pct(R.DESTROYED)} (the floor)",
               family=FAM_ISLAND_SURVIVAL),
        _entry("sec3-effective-destruction", "sec3",
               "here the hole of width 0.3 at phi_c = 0, quite a lot smaller than the large "
               "island, effectively destroys its orbits: they escape as if the island were "
               "chaotic sea", Q_EFFECTIVE,
               "two parts: the escape problem's survival through the hole over the island "
               "(phi_c = 0) against the holes in the sea (phi_c = 2, 2.5), P_0(n)/P_sea(n) with "
               "Wilson intervals (the islands' sticky orbits slow the sea holes' decay), and "
               "the island's phase width in hole widths (the escape-island-start box classified)",
               "the sea holes' late tail: n_tail and half a decade later",
               "'effective destruction': each member confirmed if the survival through the hole "
               f"over the island is at most {R.pct(R.DESTROYED)} of the survival through the "
               f"sea hole, refuted if at least {R.pct(R.DESTROYED_FAILS)} of it; 'quite a lot "
               f"smaller', each member confirmed if the island spans at least "
               f"{R.MUCH_SMALLER:g} hole widths, refuted if at most {R.MUCH_SMALLER_FAILS:g}; "
               "a part is the agreement of its members; the claim is confirmed if both parts "
               "are, refuted if one is",
               f"'effective destruction', survival ratio: "
               f"{_bounds(R.DESTROYED, R.DESTROYED_FAILS)}; 'quite a lot smaller', island width "
               f"in hole widths: {_bounds(R.MUCH_SMALLER, R.MUCH_SMALLER_FAILS, '{:g}'.format)}",
               family=("the survival ratio against each sea hole at its n_tail and half a "
                       "decade later; the island's phase width from the 5th-95th and from the "
                       "1st-99th percentiles of its orbits' phases")),
        _entry("intro-universal", "sec3", "the late power-law exponents differ between holes",
               Q_UNIVERSAL,
               "power-law exponent alpha_n of the late tail windows of each escape hole",
               TAIL,
               "'the same' rule on every pair of holes; each member (one rank of window): "
               f"confirmed if some pair is at least {R.pct(R.SAME_FAILS)} apart beyond their "
               f"uncertainties, refuted if every pair is the same within {R.pct(R.SAME)}, "
               f"inconclusive otherwise; {AGREE}",
               f"'universal': all equal within {R.pct(R.SAME)}; differing: at least "
               f"{R.pct(R.SAME_FAILS)} apart",
               family=("the tail's late windows of every hole (starts moving later from each "
                       "tail's start by quarter decades), compared rank by rank: the windows "
                       "from the tail's start together, those a quarter decade later together, "
                       "... while every hole's window holds at least "
                       f"{R.MIN_ESCAPES_TAIL} escapes")),
    ]
    for h in SEA_HOLES:
        out.append(_entry(
            f"fig2-t-phi_c={h}", "2",
            f"continuous-time escape through the hole at phi_c = {h} (chaotic sea) is a "
            "stretched exponential in its intermediate regime", Q_CAPTION_T,
            "stretched exponent beta of the fit of P(t) in the intermediate window",
            INTERMEDIATE, "form 'stretched exponential' on each member's beta: the cell of the "
            f"sqrt law [1/4, 3/4), nearer it than the exponential or the power law; {AGREE}",
            BETA_TOL, family=FAM_INSIDE))
    out.append(_entry(
        "intro-finite-times", "intro", "clear stretched exponential decay is seen over finite "
        "times: the continuous-time escape through the holes over the islands in their "
        "intermediate regime", Q_FINITE,
        "the continuous-time intermediate windows of the holes over the islands: the law the "
        "model selection picks and the stretched exponent beta", INTERMEDIATE,
        "one part per hole, two members per window: the model selection (confirmed if it "
        "picks the stretched exponential, refuted if another law) and beta (confirmed in the "
        "sqrt cell [1/4, 3/4), neither exponential nor power law, refuted wholly outside); a "
        "part is the agreement of its members; the claim is confirmed if every part is, "
        "refuted if one is", BETA_TOL, family=FAM_INSIDE))
    out.append(_entry(
        "sec3-gaussian-tail", "sec3", "in the closed system, the time t_n of an orbit of n "
        "collisions has a Gaussian upper tail in t/t_0, t_0 its average", Q_GAUSSIAN,
        "the exponent kappa of log S(x) = a - c x^kappa, x = t_n/<t_n>, fitted on the upper "
        "tail of the closed system's orbits (eps = 0.6, the paper's start box, no hole; "
        "reports/paper/claims/saddle_claims.py); intervals by resampling orbits",
        "n = 50, 100, 200 collisions: the n the intermediate regime's orbits make",
        f"'the same' exponent as 2 for each member: confirmed within {R.pct(R.SAME)}, refuted "
        f"beyond {R.pct(R.SAME_FAILS)}; {AGREE}", SAME_TOL,
        family="each n of 50, 100, 200; the tail levels S from 10^-1 to 10^-2 and from "
               "10^-2 to 10^-3"))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"sec3-c2-phi_c={h}", "sec3", f"for the hole at phi_c = {h}, c_2 predicted from "
            "c_1 (the closed system's Gaussian tail), t_0 and n_0 (the discrete escape rate) "
            "equals the c_2 fitted to P(t)", Q_C2,
            "c_2 = (4/3)(3 c_1/a_0^2)^(1/4) n_0^(-3/4) (the saddle point; t_0 = a_0 n^(3/2) "
            "the average time of n collisions, n_0 = 1/gamma of the exponential fitted on the "
            "discrete intermediate window) against c of exp(-c t^(1/2)) fitted with beta = 1/2 "
            "fixed on the continuous intermediate window",
            INTERMEDIATE, f"'the same' rule on each member: confirmed within {R.pct(R.SAME)}, "
            f"refuted beyond {R.pct(R.SAME_FAILS)}, the intervals of c_1 (resampled orbits), "
            f"n_0 and the fit included; {AGREE}", SAME_TOL,
            family="c_1 and a_0 from n = 50, 100, 200 collisions, each against the fit on "
                   "every window inside the continuous intermediate regime (as fig2-t)"))
    return out


def _transport_entries():
    width_parts = "one part per width and assertion, each the agreement of its members"
    out = [
        _entry("sec4-holes", "3", "the hole at 0 covers both islands and chaotic sea, the hole at"
               " pi mostly chaotic sea (every width)", Q_HOLES_4,
               "shares of the strips 0 +- h/2 and pi +- h/2 on islands "
               "(reports/paper/studies/islands.py)",
               "phase space at eps = 0.6",
               f"{width_parts} (hole 1 islands, hole 1 sea, hole 2 mostly sea): a member is "
               f"confirmed if the Wilson interval shows at least {R.pct(R.BOTH)} islands (sea) "
               f"in the hole-1 strip, or at most {R.pct(R.MOSTLY)} islands in the hole-2 strip;"
               f" refuted if islands (sea) hold at most {R.pct(R.BOTH_FAILS)} of the hole-1 "
               f"strip, or islands at least {R.pct(R.MOSTLY_FAILS)} of the hole-2 strip; the "
               "claim is confirmed if every part is, refuted if one is",
               f"'both', share of each: {_bounds(R.BOTH, R.BOTH_FAILS)}; 'mostly sea', share "
               f"on islands: {_bounds(R.MOSTLY, R.MOSTLY_FAILS)}", family=FAM_GEOMETRY),
        _entry("sec4-hole-2", "3", "the hole at pi covers some smaller islands, none of the large"
               " ones, and is in the strongly chaotic region (every width)", Q_HOLE_2,
               "shares of the strip pi +- h/2 on small islands, on the large island, and on "
               "islands altogether", "phase space at eps = 0.6",
               f"{width_parts} (some small islands, far from the large island, strongly "
               "chaotic): a member is confirmed if some small-island starts are found (Wilson "
               f"lower bound > 0), the large-island share is at most {R.pct(R.FAR)}, all "
               f"islands hold at most {R.pct(R.ALMOST_ENTIRELY)}; refuted if the large island "
               f"holds at least {R.pct(R.FAR_FAILS)} or all islands at least "
               f"{R.pct(R.ALMOST_ENTIRELY_FAILS)} (Wilson intervals); the claim is confirmed if "
               "every part is, refuted if one is",
               f"'far from the large islands', share on them: {_bounds(R.FAR, R.FAR_FAILS)}; "
               "'strongly chaotic for practical purposes', share on islands: "
               f"{_bounds(R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS)}", family=FAM_GEOMETRY),
    ]
    for h in WIDTHS:
        out.append(_entry(
            f"sec4-eventual-h={h}", "3",
            f"for h = {h} every particle eventually escapes: sum_j P_ij(0) = 1", Q_EVENTUAL,
            "share of the entrants of each hole still inside at the horizon (n = 10^5 or "
            "t = 10^7)", "the horizon",
            f"one part per entry hole (both must hold), each member: confirmed if the Wilson "
            f"interval of that share lies at or below {R.ESCAPED_TO:g}, refuted if above; a "
            "part is the agreement of its members",
            f"sum_j P_ij(0) = 1 to within {R.ESCAPED_TO:g}",
            family="both entry holes (parts), each read in both clocks' records of the "
                   "particles still inside at the horizon"))
    for h in TRAPPING_WIDTHS:
        out.append(_entry(
            f"fig3-h={h}", "3", f"for h = {h} P_11 is very strong: it outlives P_12, P_21 and "
            "P_22 by at least a decade", Q_STRONG,
            "at the same level: times t_ij at which P_ij(t) falls to a level q, t_11 against "
            "the largest other; at the same time: P_11(t) against the largest other P_ij(t) at "
            "the time the last other falls to q",
            f"late times (levels q = max(10^-6, 100/N) and 10 q, at most "
            f"{R.LONG_LIVED_LEVEL:g}: N >= 10^6)",
            f"each member: confirmed if the ratio >= {R.DECADE:g} with a margin of one bin "
            f"(10^(1/20)) for the grid's resolution, refuted if <= {R.STRONG_FAILS:g} by that "
            f"margin, inconclusive in between; {AGREE}",
            f"'very strong', P_11 against max(others) in time or in probability: "
            f"{_bounds(R.DECADE, R.STRONG_FAILS, '{:g}'.format)} (about as long-lived)",
            family="two metrics (the same level, the same time) at two levels (q and 10 q)"))
        out.append(_entry(
            f"fig3-trap-h={h}", "3", f"for h = {h} the hole at 0 traps the long-lived orbits: "
            "almost none of them leave through the hole at pi", Q_TRAP,
            "share of the entrants of hole 1 still inside at a long-lived time t that leave "
            "through hole 2: P_12(t)/(P_11(t) + P_12(t)), with its 95% Wilson interval",
            LONG_LIVED,
            f"each member: confirmed if the interval lies at or below {R.pct(R.TRAP_SHARE)}, "
            f"refuted if it lies at or above {R.pct(R.TRAP_SHARE_FAILS)}, inconclusive "
            f"otherwise; {AGREE}",
            "'effectively traps', share out through the other hole: "
            + _bounds(R.TRAP_SHARE, R.TRAP_SHARE_FAILS), family=FAM_LONG_LIVED))
    out += [
        _entry("fig3-h=0.1", "3", "for h = 0.1 the hole at 0 does not trap the long-lived orbits:"
               " a share of them still leaves through the hole at pi", Q_SMALL,
               "as fig3-trap-h=0.4: P_12/(P_11 + P_12) at long-lived times", LONG_LIVED,
               f"each member: confirmed if the interval lies at or above "
               f"{R.pct(R.TRAP_SHARE_FAILS)}, refuted if it lies at or below "
               f"{R.pct(R.TRAP_SHARE)}, inconclusive otherwise; {AGREE}",
               "'does not effectively trap', share out through the other hole: "
               + _bounds(R.TRAP_SHARE_FAILS, R.TRAP_SHARE), family=FAM_LONG_LIVED),
        _entry("fig3-h=2.2", "3", "for h = 2.2 every orbit escapes within a finite time", Q_LARGE,
               "escape times of all entrants (both exits, continuous time): particles left at "
               "the horizon; survivors beyond the last escape predicted by each of the three "
               "laws fitted to the last part of the decay",
               "finite time: from where the survival falls to a level (10^-1 or 10^-2 of the "
               "entrants), or 5 bins before the last escape if that is earlier, to the last "
               "escape",
               "each member: confirmed if nobody is left at the horizon and every law predicts "
               "at least 3 survivors beyond the observed last escape (the decay ends more "
               "sharply than any of them allows: P < e^-3 = 0.05 of seeing none); refuted if "
               "particles are left at the horizon; inconclusive otherwise; one part per entry "
               "hole, each the agreement of its members; the claim is confirmed if both are, "
               "refuted if one is",
               "'within a finite time': a sharper end than any exponential, stretched or "
               "power-law tail at the 5% level",
               family="both entry holes; the last part of the decay from 10^-1 and from 10^-2"),
        _entry("fig4-P11-time", "4", "for h = 1 the long-lived reflected orbits (P_11) are well "
               "approximated by a stretched exponential in continuous time", Q_FIG4_T,
               "P_11(t), maximum-likelihood fits of the three laws (the other exit's escapes "
               "censor)", LONG_LIVED, WELL_RULE, WELL_TOL, family=FAM_WELL),
        _entry("fig4-P11-collisions", "4", "for h = 1 the long-lived reflected orbits (P_11) are "
               "well approximated by a stretched exponential in discrete time", Q_FIG4_N,
               "P_11(n), as fig4-P11-time", LONG_LIVED.replace("P_11 + P_12", "P_11 + P_12 (n)"),
               WELL_RULE, WELL_TOL, family=FAM_WELL),
    ]
    for ij, reflected in (("P12", "P11"), ("P21", "P11")):
        out.append(_entry(
            f"fig4-fewer-collisions-{ij}", "4", f"for h = 1 the transporting orbits of {ij} "
            f"decay with many fewer collisions than the reflected orbits of hole 1 ({reflected}) "
            "for the same time", Q_FEWER,
            f"collisions per unit time of {ij} against {reflected}: at the same survival level "
            "q (relative to each curve's P(0)), (n_q/t_q) of the one over the other's, from the "
            "run; at the same escape time, the ratio of their median collision counts, from "
            "joint (n, t) data (reports/paper/studies/joint_sample.py)",
            "the top decades and the tail of the curves; the escape times holding most of "
            f"{ij}'s escapes and its latest with at least 100 escapes of each",
            f"each member: confirmed if the ratio's interval lies at or below {R.FEWER}, "
            f"refuted if at or above {R.FEWER_FAILS}, inconclusive otherwise; {AGREE}",
            f"'many fewer', ratio: {_bounds(R.FEWER, R.FEWER_FAILS, '{:g}'.format)} (about "
            "as many)",
            family=("the same level: the top decades (levels P(0)/10 to P(0)/10^3) and the "
                    "tail (the last two decades above 100/N); the same time, in the decay: the "
                    "latest two quarter decades of t with at least 100 escapes of each")))
    for ij, entry_hole in (("P12", 1), ("P21", 2)):
        out.append(_entry(
            f"fig4-large-velocities-{ij}", "4", f"for h = 1 the transporting orbits of {ij} can "
            "reach large velocities", Q_LARGE_V,
            f"the largest velocity of each {ij} orbit before it escapes (sampled study of entry "
            f"hole {entry_hole}, and an independent replica of it)",
            f"all {ij} escapes",
            f"each member: confirmed if some orbit exceeds {R.LARGE_VELOCITY:g} times the "
            "largest start velocity (Wilson lower bound of that share > 0), refuted if none "
            f"exceeds {R.LARGE_VELOCITY_FAILS:g} times it (Wilson upper bound of that share "
            f"below {R.NONE_SHARE:g}), inconclusive otherwise; a bound the sample cannot reach "
            "(its own tail, extrapolated, expects fewer than one orbit beyond it) is said so; "
            + AGREE,
            f"'large': above {R.LARGE_VELOCITY:g} times the start box's largest velocity "
            f"(v = 4); not large: none above {R.LARGE_VELOCITY_FAILS:g} times it (they stay "
            "at the start velocities)",
            family="the sampled study and an independent replica of it (its own starts)"))
    out += [
        _entry("conclusion-asymmetry", "3", "transport is asymmetric as in the stadium, with a "
               "stretched exponential for the slowly escaping dynamics", Q_CONCLUSION,
               "the asymmetry of fig3-h=W and the functional form of P_11's long-lived regime in "
               "continuous time (the law the model selection picks among exponential, "
               "stretched exponential and the stadium's power law, and the stretched law's "
               "absolute goodness of fit), for W = 0.4 and 1",
               LONG_LIVED, "four parts (the asymmetry and the form, for W = 0.4 and 1), each "
               "the agreement of its members: the asymmetry as fig3-h=W; the form, each window "
               "confirmed if the selection picks the stretched exponential and Pearson's "
               f"chi-squared does not reject it (p >= {R.GOF_HOLDS:g}), refuted if it picks the "
               f"power law or the exponential or chi-squared rejects it beyond doubt (p <= "
               f"{R.GOF_FAILS:g}); the claim is confirmed if every part is, refuted if one is",
               "as fig3-h=W; the form: the likelihood-ratio tests of the model selection at "
               "their level, and the absolute goodness of fit beside them",
               family=("as fig3-h=W for the asymmetry; the form on the long-lived regime's "
                       "late windows (as fig4-P11-time), each by the selection and by "
                       "chi-squared")),
    ]
    for h in ("0.1", "0.4", "2.2"):
        out.append(_entry(
            f"fig4-other-h={h}", "4", f"for h = {h} the discrete-time P_ij look more like the "
            "continuous-time ones than they do for h = 1",
            Q_OTHER_H,
            "D = spread (max - min) over the four P_ij of log(t_q/n_q), t_q and n_q the times "
            "and collision counts at which P_ij reaches the same level q: over the top decades"
            " its median over levels from P_ij(0)/10 down to max(P_ij(0) 10^-4, 100/N); in "
            "the tail at the levels 100/N and 1000/N; curves that differ between the clocks "
            "only by a common time per collision have D = 0",
            "matched survival levels of every P_ij: the top decades and the tail",
            "each member: confirmed if D(h) + r < D(1), refuted if D(h) - r > D(1), "
            "inconclusive otherwise (or when a P_ij does not reach the levels), r = "
            f"log(10)/20 the bins' resolution; {AGREE}",
            "'even more similar': a smaller spread than for h = 1 by more than one bin",
            family=("the difference between the clocks wherever it is read: the top decades "
                    "(the median over levels) and the tail (each of the levels 100/N and "
                    "1000/N)")))
    for h in TRAPPING_WIDTHS:
        out.append(_entry(
            f"fig3-reducing-lifetime-h={h}", "3", f"for h = {h} the hole in the elliptic region "
            "cuts short the lives of the orbits on the large island", Q_REDUCING,
            "share of starts on the large island (orbits locked to its resonance) still inside "
            "at the long-lived time of the transport run (the entrants of hole 1 fall to "
            f"{R.LONG_LIVED_LEVEL:g}), with holes of width h at 0 and pi (sampled study, "
            "reports/paper/claims/lifetime_claims.py); without a hole they never leave",
            "the long-lived time of the transport run",
            f"each member: confirmed if the Wilson interval lies at or below "
            f"{R.pct(R.DESTROYED)}, refuted if at or above {R.pct(R.DESTROYED_FAILS)}; {AGREE}",
            "'reducing the lifetime', share left: " + _bounds(R.DESTROYED, R.DESTROYED_FAILS),
            family="the island of (0, pi) (the box of scene escape-island-start) and of "
                   "(0, 2 pi) (the same box a period pi higher)"))
    out.append(_entry(
        "fig3-many-not-shown", "3", "for many hole sizes besides 0.4 and 1 the hole at 0 also "
        "traps the long-lived orbits (and P_11 is very strong)", Q_MANY,
        "the share of the widths of a sweep (transport runs of widths not shown in Fig. 3) "
        "for which the trapping claim (as fig3-trap-h) is confirmed; the same for 'very "
        "strong P_11' (as fig3-h)",
        "widths 0.2, 0.3, 0.6, 0.8, 1.4, 1.8 between the paper's 0.1 and 2.2; the long-lived "
        "regime of each",
        "each member: confirmed if at least half of the widths give the effect, refuted if at "
        f"most one in six does; {AGREE}",
        "'many': at least half of the widths not shown; not many: at most one in six",
        family="two readings of 'the effect': effective trapping (as fig3-trap-h) and a very "
               "strong P_11 (as fig3-h), each over the sweep"))
    return out


def entries():
    """Every register entry, in report order (dicts with the register's fields)."""
    return section2_entries() + _escape_entries() + _transport_entries()


_BY_ID = None


def entry(claim_id):
    global _BY_ID
    if _BY_ID is None:
        _BY_ID = {e["id"]: e for e in entries()}
    return _BY_ID[claim_id]


def make_claim(claim_id, evidence, *, analyses=(), particles_per_curve=None, statistical=None,
               systematic=None, run=None):
    """The ``Claim`` of register entry ``claim_id``: its verdict (and the kind of an
    inconclusive one) is the agreement of its ``analyses`` (``reports.paper.claims.family.Analysis``
    members; none: inconclusive for want of data)."""
    e = entry(claim_id)
    members = analyses_json(analyses)
    verdict, kind = agreement(members)
    return Claim(id=e["id"], figure=e["figure"], statement=e["statement"], quote=e["quote"],
                 observable=e["observable"], regime=e["regime"], family=e["family"],
                 rule=e["rule"], tolerance=e["tolerance"], source=e["source"], verdict=verdict,
                 inconclusive=kind, evidence=evidence, analyses=members,
                 particles_per_curve=particles_per_curve,
                 statistical=dict(statistical or {}), systematic=dict(systematic or {}),
                 run=run)


def normalised(text):
    return " ".join(text.split())


def quote_found(quote, text):
    """True if ``quote`` occurs in ``text`` with whitespace normalised, each "..." standing for
    any (possibly empty) stretch of text, the pieces in order."""
    text = normalised(text)
    at = 0
    for piece in (normalised(p) for p in quote.split("...")):
        if not piece:
            continue
        found = text.find(piece, at)
        if found < 0:
            return False
        at = found + len(piece)
    return True
