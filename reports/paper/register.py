"""The register of the paper's checkable claims, as data, written before any verdict.

One entry per claim: id, figure, our one-line reading (``statement``), the paper's words
verbatim (``quote``; whitespace may differ, "..." elides, LaTeX as in the text), the
``observable``, the ``regime`` it speaks of, the ``rule`` that decides it and the ``tolerance`` of
its qualitative words (constants of ``reports.paper.rules``), and its ``source``. Claims made for
several holes or widths have one entry each. The evaluators (``escape_claims``,
``transport_claims``, ``start_claims``, ``geometry_claims``, ``fermi``) compute verdicts and
evidence; ``make_claim`` joins them to the entry into a ``Claim``, by keyword.

``quote_found(quote, text)`` is how a quote is checked against the paper's text (the test
``tests/reports/paper/test_register.py`` runs it when ``BOUNCER_PAPER_TEXT`` names the file).
"""

from __future__ import annotations

from reports.paper import rules as R
from reports.paper.claims import PAPER, Claim

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
Q_DESTRUCTION = ("Note that a hole partially covering an island may in fact destroy all orbits "
                 "surrounding that island; here we see effective destruction of islands using "
                 "holes quite a lot smaller than the islands concerned.")
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
Q_CONCLUSION = ("Here we note that generic mixed phase space allows the asymmetric transport "
                "similar to that observed in the stadium, but with a different functional form, "
                "specifically a stretched exponential for the slowly escaping dynamics.")

BETA_TOL = ("a form word holds if beta's 95% interval widened by its systematic lies nearer "
            "that form than the paper's other two: cells power law [0, 1/4), sqrt(x) "
            "[1/4, 3/4), exponential [3/4, 5/4]; refuted if wholly outside the cell")
CLOSE_TOL = (f"'close to' a form: beta's widened interval within {R.BAND} of it: [0.4, 0.6] for "
             "the sqrt law; refuted if wholly outside")
INTERMEDIATE = ("intermediate, the same orbits in both clocks: from t_D, where <v(t)> reaches "
                f"its diffusive law t^(1/3) (local exponent within {R.pct(R.ONSET_TOLERANCE)}, "
                "Fermi ensemble from the same start box), and the n where P(n) falls to P(t_D), "
                "to where the discrete-time hazard first falls below "
                f"{R.HAZARD_FAST} of its plateau (the chaotic population still holds 90% of the "
                "escapes) and the t where P(t) falls to that level; at least "
                f"{R.MIN_ESCAPES_INTERMEDIATE} escapes")
TAIL = ("late tail: from where the discrete-time hazard has fallen to "
        f"{R.HAZARD_TENTH} of its plateau (the slow population holds 90% of the escapes) to the"
        " last escape before the horizon;"
        f" at least {R.MIN_ESCAPES_TAIL} escapes")
FAMILY = "systematic: half-range over the window family (start x 10^(+-1/4), end x 10^(-1/4))"
LONG_LIVED = (f"long-lived: after the entrants of hole 1 still inside fall to "
              f"{R.LONG_LIVED_LEVEL:g} (P_11 + P_12 <= {R.LONG_LIVED_LEVEL:g}), to the last "
              "escape")


def _bounds(holds, fails, fmt=R.pct):
    return R.bounds_text(holds, fails, fmt)


SAME_TOL = (f"'the same': equal within {R.pct(R.SAME)} (relative), different beyond "
            f"{R.pct(R.SAME_FAILS)}")


def _entry(id, figure, statement, quote, observable, regime, rule, tolerance, source=PAPER):
    return {"id": id, "figure": figure, "statement": statement, "quote": quote,
            "observable": observable, "regime": regime, "rule": rule, "tolerance": tolerance,
            "source": source}


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
            + ", pi/2 < v < 3 pi/2, from 2000 random starts classified by their orbits "
              "(reports/paper/islands.py)",
            "phase space at eps = 0.6 (no holes)",
            ("confirmed if the Wilson interval of the share lies at or above "
             f"{R.pct(R.OVER_OR_NEAR)}, refuted if it lies at or below "
             f"{R.pct(R.OVER_OR_NEAR_FAILS)} (a trace: the hole far from the island), "
             "inconclusive otherwise" if island else
             f"confirmed if the Wilson interval lies at or below {R.pct(R.ALMOST_ENTIRELY)}, "
             f"refuted if it lies at or above {R.pct(R.ALMOST_ENTIRELY_FAILS)} (mostly islands), "
             "inconclusive otherwise"),
            ("'over or near', share of the strip widened by one hole width on the island: "
             + _bounds(R.OVER_OR_NEAR, R.OVER_OR_NEAR_FAILS) if island else
             "'almost entirely in the sea', share on islands: "
             + _bounds(R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS))))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-n-phi_c={h}", "2",
            f"discrete-time escape through the hole at phi_c = {h} is exponential in its "
            "intermediate regime", Q_INTERMEDIATE_N,
            "stretched exponent beta of the maximum-likelihood fit of P(n) (binned, censored "
            "counts) in the intermediate window", INTERMEDIATE,
            f"form 'exponential': beta cell [3/4, 5/4]; {FAMILY}", BETA_TOL))
    for h in SEA_HOLES:
        out.append(_entry(
            f"fig2-n-phi_c={h}", "2",
            f"discrete-time escape through the hole at phi_c = {h} (chaotic sea) is algebraic",
            Q_DISCRETE,
            "stretched exponent beta of the fit of P(n) in the late tail window", TAIL,
            f"form 'algebraic' (power law): beta cell [0, 1/4); {FAMILY}", BETA_TOL))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-n-tail-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} eventually follows a slow power law in "
            "discrete time", Q_TAIL,
            "stretched exponent beta of the fit of P(n) in the late tail window", TAIL,
            f"form 'power law': beta cell [0, 1/4); {FAMILY}", BETA_TOL))
        out.append(_entry(
            f"fig2-t-phi_c={h}", "2",
            f"continuous-time escape through the hole at phi_c = {h} is close to exp(-c sqrt(t))"
            " in its intermediate regime", Q_INTERMEDIATE_T,
            "stretched exponent beta of the fit of P(t) in the intermediate window",
            INTERMEDIATE, f"'close to' sqrt(t): beta band [0.4, 0.6]; {FAMILY}", CLOSE_TOL))
    for h in ISLAND_HOLES + SEA_HOLES:
        island = h in ISLAND_HOLES
        out.append(_entry(
            f"fig2-same-power-phi_c={h}", "2",
            f"the algebraic decay through the hole at phi_c = {h} has the same power law "
            "exponent in continuous as in discrete time",
            Q_SAME_POWER_TEXT if island else Q_SAME_POWER_CAPTION,
            "power-law exponents alpha_n and alpha_t (maximum likelihood) of P(n) and P(t) over "
            "the same survival levels",
            "matched survival levels: from the late tail's start level down to "
            f"{R.SURVIVORS_MIN}/N; at least {R.MIN_ESCAPES_TAIL} escapes in each clock",
            f"'the same' rule on alpha_n and alpha_t with U = 95% interval half-width + {FAMILY}:"
            f" confirmed if |alpha_n - alpha_t| + U <= {R.SAME} x their mean, refuted if "
            f"|alpha_n - alpha_t| - U >= {R.SAME_FAILS} x their mean, inconclusive otherwise;"
            " compared only where the continuous-time curve is the non-accelerating population: "
            "the intermediate stretched law, extrapolated, explains at most "
            f"{R.pct(R.CHAOTIC_GONE)} of the survivors at the window's start (else "
            "inconclusive)",
            SAME_TOL))
        out.append(_entry(
            f"fig2-bounded-velocity-phi_c={h}", "2",
            f"the orbits of the slow decay through the hole at phi_c = {h} do not accelerate: "
            "their velocity stays bounded", Q_BOUNDED,
            "mean time per collision t/n (twice the mean velocity) of each escape after n_half, "
            "from a sampled study recording n and t of each particle (reports/paper/follow.py):"
            " slope of log median(t/n) against log n over quarter-decades of n (the variable "
            "the escapes are selected on); bootstrap interval over particles",
            "the slow decay: escapes after n_half, where the slow population holds half the "
            f"escapes; at least {R.MIN_ESCAPES_TAIL} escapes",
            f"confirmed if the slope's interval lies within [{R.BOUNDED[0]}, {R.BOUNDED[1]}] "
            f"(bounded velocity), refuted if it lies wholly outside [{R.BOUNDED_FAILS[0]}, "
            f"{R.BOUNDED_FAILS[1]}] (nearer velocity diffusion's 1/2 than 0), inconclusive "
            "otherwise",
            f"'tightly bounded velocity': t/n ~ n^s, holds at |s| <= {R.BOUNDED[1]}, fails at "
            f"|s| >= {R.BOUNDED_FAILS[1]}"))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"fig2-stages-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} is slower at first and faster at "
            "intermediate times than through the holes in the chaotic sea", Q_STAGES,
            "P(n) of this hole against P(n) of the holes at phi_c = 2 and 2.5 (95% Wilson bands)",
            "early: at this hole's median escape (P = 1/2); intermediate: at the end of its "
            "intermediate window",
            "confirmed if P is above both sea-hole curves early and below both at the end of the"
            " intermediate window, each with disjoint 95% bands; refuted if either order is "
            "reversed with disjoint bands; inconclusive otherwise",
            "none beyond the 95% bands (an ordering)"))
    for h in SEA_HOLES:
        out.append(_entry(
            f"fig2-sea-slowed-phi_c={h}", "2",
            f"escape through the hole at phi_c = {h} is slowed by the large islands: its late "
            "survivors stick to the large island around (0, pi m) and it decays more slowly "
            "than through the island holes", Q_SEA_SLOWED,
            "share of the survivors at n_tail (sampled study, "
            "reports/paper/follow.py) whose next 200 collisions are locked to a period-1 "
            "resonance of the large islands (mean flight time 2 pi m within 1%, velocity within "
            "a band of 5); P(n) against the island holes' P(n) there",
            "late tail: survivors at n_tail, where the slow population holds 90% of the "
            "escapes",
            f"confirmed if the Wilson interval of that share lies at or above "
            f"{R.pct(1 - R.MOSTLY)} and P(n) lies above every island-hole curve there; refuted "
            f"if the interval lies at or below {R.pct(1 - R.MOSTLY_FAILS)} or P(n) lies below "
            "an island-hole curve; inconclusive otherwise",
            "'slowed by the large islands': most of the late survivors there, "
            + _bounds(1 - R.MOSTLY, 1 - R.MOSTLY_FAILS)))
    for h in ISLAND_HOLES:
        out.append(_entry(
            f"sec3-n-sqrt-t-phi_c={h}", "sec3",
            f"the orbits escaping through the hole at phi_c = {h} at time t in the intermediate "
            "regime made n ~ t^(1/2) collisions", Q_N_SQRT_T,
            "slope of log(median n of the escapes at time t) against log t, from a sampled "
            "study recording n and t of each particle (reports/paper/follow.py); bootstrap "
            "interval over particles", INTERMEDIATE + " (continuous time)",
            "band rule on the slope: confirmed if its interval widened by the window family's "
            "half-range lies in [0.4, 0.6], refuted if wholly outside (the closed system's "
            "typical orbit has n ~ t^(2/3))",
            "'n ~ t^(1/2)': slope within 0.1 of 1/2"))
    out += [
        _entry("fermi-n", "fermi", "a chaotic orbit's typical velocity grows as n^(1/2)",
               Q_VELOCITY, "slope of log<v_n> against log n, eps = 0.6, starts in the paper's "
               "escape box, no holes; bootstrap over particle blocks",
               "diffusive: n from 1000 to the end of the ensemble",
               "'the same' exponent: confirmed if the slope's interval (1.96 sigma + "
               f"window-family half-range) lies within {R.pct(R.SAME)} of 1/2, [0.45, 0.55]; "
               f"refuted if it lies wholly beyond {R.pct(R.SAME_FAILS)} of it, outside "
               "[0.375, 0.625]; inconclusive otherwise",
               f"'proportional to sqrt(n)': exponent within {R.pct(R.SAME)} of 1/2; not beyond "
               f"{R.pct(R.SAME_FAILS)}"),
        _entry("fermi-t", "fermi", "time grows as n^(3/2), i.e. <v(t)> grows as t^(1/3)",
               Q_TIME, "slope of log<v(t)> against log t, as fermi-n",
               "diffusive: t from 10^4 to the last time all particles reach",
               f"as fermi-n: confirmed within {R.pct(R.SAME)} of 1/3, [0.30, 0.367]; refuted "
               f"wholly beyond {R.pct(R.SAME_FAILS)} of it, outside [0.25, 0.417]",
               f"'t_0 ~ n sqrt(n)': exponent of <v(t)> within {R.pct(R.SAME)} of 1/3; not beyond"
               f" {R.pct(R.SAME_FAILS)}"),
        _entry("sec3-other-box", "sec3",
               "a second start box in the chaotic sea gives the same escape at long times",
               Q_OTHER_SET,
               "hazard ratio (log-rank, binned) of the run from the box 3.85 < phi < 4.15, "
               "4.5 < v < 6.5 (scene escape-second-box, 10^7 per hole) against the paper-scale "
               "run, every hole and clock, over the earlier and the later half of the long-time "
               "window",
               "long times: the late tail, from where the paper-scale curve falls to its tail "
               "level P(n_tail) (the slow population holds 90% of the escapes), in both clocks,"
               " to the last bin with 10 particles at risk in both runs",
               "confirmed if every hazard ratio's 95% interval lies within "
               f"[1/{1 + R.SAME:g}, {1 + R.SAME:g}], refuted if one lies wholly outside "
               f"[1/{1 + R.SAME_FAILS:g}, {1 + R.SAME_FAILS:g}], inconclusive otherwise",
               f"'the same results': hazards equal within {R.pct(R.SAME)}, different beyond "
               f"{R.pct(R.SAME_FAILS)}"),
        _entry("sec3-other-density", "sec3",
               "a second smooth density on the paper's start box gives the same escape at long "
               "times", Q_OTHER_DENSITY,
               "hazard ratio as sec3-other-box, for starts with density proportional to "
               "sin(pi (phi - 3.85)/0.3) sin(pi (v - 2)/2) on the paper's box (sampled study, "
               "reports/paper/follow.py)",
               "long times, as sec3-other-box", "as sec3-other-box",
               f"'the same results': hazards equal within {R.pct(R.SAME)}, different beyond "
               f"{R.pct(R.SAME_FAILS)}"),
        _entry("sec3-island-start", "sec3",
               "starts touching an island not connected with the hole give a survival that "
               "tends to a constant, the share of starts on the island", Q_PLATEAU,
               "survival P(t) of the scene escape-island-start (hole at pi) over the last two "
               "decades before the horizon t = 10^5; the share of the start box on regular "
               "orbits (reports/paper/islands.py, 4000 random starts)",
               "t -> infinity: the trend of the last two decades before the horizon",
               "confirmed if the fall decelerates (the last decade holds significantly fewer "
               "than half of the two decades' escapes) and the limit, between P(10^5) and P(10^5)"
               " minus the geometric continuation of the falls, equals the regular share under "
               "'the same'; refuted if the fall accelerates or the limit differs beyond the "
               "uncertainties; inconclusive otherwise",
               f"'tends to a constant': a decelerating fall; 'giving the probability': equal "
               f"within {R.pct(R.SAME)}, different beyond {R.pct(R.SAME_FAILS)}"),
        _entry("sec3-destruction", "sec3",
               "a hole over part of the large island, much smaller than the island, destroys "
               "the orbits surrounding it", Q_DESTRUCTION,
               "share of the starts of the escape-island-start box on the large island (orbits "
               "locked around (0, pi)) that are still inside after 3000 collisions with the "
               "hole of width 0.3 at phi_c = 0 (sampled study); the phase width of those orbits",
               "t -> infinity (3000 collisions: 19,000 time units)",
               f"confirmed if at most {R.pct(R.DESTROYED)} of them survive (Wilson upper bound)"
               f" and the island's phase width is at least {R.MUCH_SMALLER:g} hole widths; "
               f"refuted if at least {R.pct(R.DESTROYED_FAILS)} survive (Wilson lower bound) or"
               f" the island is at most {R.MUCH_SMALLER_FAILS:g} hole widths wide; inconclusive "
               "otherwise",
               f"'destroy all', share left: {_bounds(R.DESTROYED, R.DESTROYED_FAILS)}; 'quite a "
               f"lot smaller', island width in hole widths: "
               f"{_bounds(R.MUCH_SMALLER, R.MUCH_SMALLER_FAILS, '{:g}'.format)}"),
        _entry("intro-universal", "sec3", "the late power-law exponents differ between holes",
               Q_UNIVERSAL,
               "power-law exponent alpha_n of the late tail window of each escape hole",
               TAIL,
               "'the same' rule on every pair of holes: confirmed if some pair is refuted as the "
               f"same (exponents at least {R.pct(R.SAME_FAILS)} apart beyond their "
               f"uncertainties), refuted if every pair is confirmed the same (within "
               f"{R.pct(R.SAME)}), inconclusive otherwise",
               f"'universal': all equal within {R.pct(R.SAME)}; differing: at least "
               f"{R.pct(R.SAME_FAILS)} apart"),
    ]
    return out


def _transport_entries():
    out = [
        _entry("sec4-holes", "3", "the hole at 0 covers both islands and chaotic sea, the hole at"
               " pi mostly chaotic sea (every width)", Q_HOLES_4,
               "shares of the strips 0 +- h/2 and pi +- h/2 on islands (pi/2 < v < 3 pi/2; "
               "reports/paper/islands.py)", "phase space at eps = 0.6",
               f"confirmed if, for every width, the hole-1 strip holds at least {R.pct(R.BOTH)} "
               f"islands and {R.pct(R.BOTH)} sea and the hole-2 strip at most "
               f"{R.pct(R.MOSTLY)} islands (Wilson intervals); refuted if, for some width, "
               f"islands or sea hold at most {R.pct(R.BOTH_FAILS)} of the hole-1 strip or "
               f"islands at least {R.pct(R.MOSTLY_FAILS)} of the hole-2 strip; inconclusive "
               "otherwise",
               f"'both', share of each: {_bounds(R.BOTH, R.BOTH_FAILS)}; 'mostly sea', share "
               f"on islands: {_bounds(R.MOSTLY, R.MOSTLY_FAILS)}"),
        _entry("sec4-hole-2", "3", "the hole at pi covers some smaller islands, none of the large"
               " ones, and is in the strongly chaotic region (every width)", Q_HOLE_2,
               "shares of the strip pi +- h/2 on small islands, on the large island, and on "
               "islands altogether", "phase space at eps = 0.6",
               "confirmed if, for every width, some small-island starts are found (Wilson lower "
               f"bound > 0), the large-island share is at most {R.pct(R.FAR)} and all "
               f"islands hold at most {R.pct(R.ALMOST_ENTIRELY)}; refuted if, for some width, "
               f"the large island holds at least {R.pct(R.FAR_FAILS)} or all islands at least "
               f"{R.pct(R.ALMOST_ENTIRELY_FAILS)} (Wilson intervals); inconclusive otherwise",
               f"'far from the large islands', share on them: {_bounds(R.FAR, R.FAR_FAILS)}; "
               "'strongly chaotic for practical purposes', share on islands: "
               f"{_bounds(R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS)}"),
    ]
    for h in WIDTHS:
        out.append(_entry(
            f"sec4-eventual-h={h}", "3",
            f"for h = {h} every particle eventually escapes: sum_j P_ij(0) = 1", Q_EVENTUAL,
            "share of the entrants of each hole still inside at the horizon (n = 10^5 or "
            "t = 10^7)", "the horizon",
            f"confirmed if for both entry holes the Wilson interval of that share lies at or "
            f"below {R.ESCAPED_TO:g}, refuted if above", f"sum_j P_ij(0) = 1 to within "
            f"{R.ESCAPED_TO:g}"))
    for h in TRAPPING_WIDTHS:
        out.append(_entry(
            f"fig3-h={h}", "3", f"for h = {h} P_11 is very strong: it outlives P_12, P_21 and "
            "P_22 by at least a decade", Q_STRONG,
            "times t_ij at which P_ij(t) (continuous time) falls to q = max(10^-6, 100/N)",
            f"late times (the level q, at most {R.LONG_LIVED_LEVEL:g}: N >= 10^6)",
            f"confirmed if t_11 >= {R.DECADE:g} max(t_12, t_21, t_22) with a margin of one bin "
            "(10^(1/20)) for the grid's resolution, refuted if t_11 <= "
            f"{R.STRONG_FAILS:g} max(t_12, t_21, t_22) by that margin, inconclusive in between",
            f"'very strong', t_11 / max(others): "
            f"{_bounds(R.DECADE, R.STRONG_FAILS, '{:g}'.format)} (about as long-lived)"))
        out.append(_entry(
            f"fig3-trap-h={h}", "3", f"for h = {h} the hole at 0 traps the long-lived orbits: "
            "almost none of them leave through the hole at pi", Q_TRAP,
            "share of the entrants of hole 1 still inside at the long-lived time that leave "
            "through hole 2: P_12/(P_11 + P_12), with its 95% Wilson interval", LONG_LIVED,
            f"confirmed if the interval lies at or below {R.pct(R.TRAP_SHARE)}, refuted if it "
            f"lies at or above {R.pct(R.TRAP_SHARE_FAILS)}, inconclusive otherwise",
            "'effectively traps', share out through the other hole: "
            + _bounds(R.TRAP_SHARE, R.TRAP_SHARE_FAILS)))
    out += [
        _entry("fig3-h=0.1", "3", "for h = 0.1 the hole at 0 does not trap the long-lived orbits:"
               " a share of them still leaves through the hole at pi", Q_SMALL,
               "as fig3-trap-h=0.4: P_12/(P_11 + P_12) at the long-lived time", LONG_LIVED,
               f"confirmed if the interval lies at or above {R.pct(R.TRAP_SHARE_FAILS)}, refuted "
               f"if it lies at or below {R.pct(R.TRAP_SHARE)}, inconclusive otherwise",
               "'does not effectively trap', share out through the other hole: "
               + _bounds(R.TRAP_SHARE_FAILS, R.TRAP_SHARE)),
        _entry("fig3-h=2.2", "3", "for h = 2.2 every orbit escapes within a finite time", Q_LARGE,
               "escape times of all entrants (both exits, continuous time): particles left at "
               "the horizon; survivors beyond the last escape predicted by each of the three "
               "laws fitted to the last part of the decay",
               "finite time: from where the survival falls to 10^-1 (the last 10% of the "
               "entrants), or 5 bins before the last escape if that is earlier, to the last "
               "escape",
               "confirmed if nobody is left at the horizon and every law predicts at least 3 "
               "survivors beyond the observed last escape (the decay ends more sharply than any "
               "of them allows: P < e^-3 = 0.05 of seeing none); refuted if particles are left "
               "at the horizon; inconclusive otherwise",
               "'within a finite time': a sharper end than any exponential, stretched or "
               "power-law tail at the 5% level"),
        _entry("fig4-P11-time", "4", "for h = 1 the long-lived reflected orbits (P_11) are well "
               "approximated by a stretched exponential in continuous time", Q_FIG4_T,
               "P_11(t), maximum-likelihood fits of the three laws (the other exit's escapes "
               "censor)", LONG_LIVED,
               "'well approximated' rule: confirmed if the stretched law wins the three-way "
               f"comparison and stays within {R.RESIDUAL_LEVEL:g} in log S of the data beyond "
               "its 95% band (where at least 100 particles remain); refuted if another law wins"
               f" or it strays by at least {R.RESIDUAL_FAILS:g}; inconclusive otherwise; "
               f"at least {R.MIN_ESCAPES_TAIL} escapes",
               f"'well approximated', excess in log S: "
               f"{_bounds(R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS, '{:g}'.format)}; the power in "
               "the exponent is left open by the paper and only reported"),
        _entry("fig4-P11-collisions", "4", "for h = 1 the long-lived reflected orbits (P_11) are "
               "well approximated by a stretched exponential in discrete time", Q_FIG4_N,
               "P_11(n), as fig4-P11-time", LONG_LIVED.replace("P_11 + P_12", "P_11 + P_12 (n)"),
               "as fig4-P11-time", "'well approximated', excess in log S: "
               + _bounds(R.RESIDUAL_LEVEL, R.RESIDUAL_FAILS, "{:g}".format)),
        _entry("fig4-fewer-collisions", "4", "for h = 1 the transporting orbits escape after many"
               " fewer collisions than the reflected ones that leave at the same time", Q_FEWER,
               "median collision count n of the transporting (P_12, P_21) and of the reflected "
               "(P_11, P_22) escapes per quarter-decade of escape time t, sampled study recording "
               "n and t of each particle (reports/paper/follow.py); bootstrap intervals",
               "every quarter-decade of t with at least 100 escapes of each kind",
               f"confirmed if in every such bin the ratio of medians is at most {R.FEWER} "
               f"(bootstrap upper bound), refuted if it is at least {R.FEWER_FAILS} (bootstrap "
               "lower bound) in every bin, inconclusive otherwise",
               f"'many fewer', ratio: {_bounds(R.FEWER, R.FEWER_FAILS, '{:g}'.format)} (about "
               "as many)"),
        _entry("fig4-large-velocities", "4", "for h = 1 transporting orbits can reach large "
               "velocities", Q_LARGE_V,
               "largest velocity of each transporting orbit before it escapes (sampled study)",
               "all transporting escapes",
               f"confirmed if some transporting orbit exceeds {R.LARGE_VELOCITY:g} times the "
               "largest start velocity (Wilson lower bound of that share > 0), refuted if none "
               f"exceeds {R.LARGE_VELOCITY_FAILS:g} times it (Wilson upper bound of that share "
               f"below {R.NONE_SHARE:g}), inconclusive otherwise",
               f"'large': above {R.LARGE_VELOCITY:g} times the start box's largest velocity "
               f"(v = 4); not large: none above {R.LARGE_VELOCITY_FAILS:g} times it (they stay "
               "at the start velocities)"),
        _entry("conclusion-asymmetry", "3", "transport is asymmetric as in the stadium, with a "
               "stretched exponential for the slowly escaping dynamics", Q_CONCLUSION,
               "the verdicts of fig3-h=W (asymmetry) and the functional form of P_11's "
               "long-lived regime in continuous time (the law the model selection picks among "
               "exponential, stretched exponential and the stadium's power law), for W = 0.4 "
               "and 1",
               LONG_LIVED, "confirmed if all four are (the form: the selection picks the "
               "stretched exponential), refuted if one is refuted (the form: it picks the power"
               " law or the exponential), inconclusive otherwise",
               "as fig3-h=W; the form: the likelihood-ratio tests of the model selection at "
               "their level"),
    ]
    for h in ("0.1", "0.4", "2.2"):
        out.append(_entry(
            f"fig4-other-h={h}", "4", f"for h = {h} the discrete-time P_ij look more like the "
            "continuous-time ones than they do for h = 1",
            Q_OTHER_H,
            "D(h) = spread (max - min) over the four P_ij of the median of log(t_q/n_q), t_q and"
            " n_q the times and collision counts at which P_ij reaches the same levels q (4 per "
            "decade, from P_ij(0)/10 down to max(P_ij(0) 10^-4, 100/N)): curves that differ "
            "between the clocks only by a common time per collision have D = 0",
            "matched survival levels of every P_ij",
            "confirmed if D(h) + r < D(1), refuted if D(h) - r > D(1), inconclusive otherwise "
            "(or when a P_ij spans less than two decades of levels above 100/N), r = "
            "log(10)/20 the bins' resolution",
            "'even more similar': a smaller spread than for h = 1 by more than one bin"))
    return out


def entries():
    """Every register entry, in report order (dicts with the register's fields)."""
    return _escape_entries() + _transport_entries()


_BY_ID = None


def entry(claim_id):
    global _BY_ID
    if _BY_ID is None:
        _BY_ID = {e["id"]: e for e in entries()}
    return _BY_ID[claim_id]


def make_claim(claim_id, verdict, evidence, particles_per_curve=None, statistical=None,
               systematic=None, run=None):
    """The ``Claim`` of register entry ``claim_id`` with its verdict and evidence."""
    e = entry(claim_id)
    return Claim(id=e["id"], figure=e["figure"], statement=e["statement"], quote=e["quote"],
                 observable=e["observable"], regime=e["regime"], rule=e["rule"],
                 tolerance=e["tolerance"], source=e["source"], verdict=verdict,
                 evidence=evidence, particles_per_curve=particles_per_curve,
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
