"""The register's entries for the paper's Section 2: its numerical method, the map's near
periodicity in v, and the phase space as eps varies (``reports.paper.claims.register`` joins them to
the others; evaluators ``method_claims``, ``periodicity_claims``, ``phase_space_claims``)."""

from __future__ import annotations

from reports.paper.claims import rules as R
from reports.paper.claims.register_entry import AGREE, entry_of

Q_OVERSTEP = ("The time step is chosen using a rigorous lower bound for the actual time step, thus "
              "the first collision is never overstepped, modulo round-off error.")
Q_QUADRATIC = ("Thus the algorithm typically converges quadratically, similar to Newton's method, "
               "for example.")
Q_FIVE = ("In practice, the approach to the collision to a tolerance close to machine precision "
          "takes around five steps")
Q_PERIOD = ("Recall the family of periodic orbits at $\\phi=0$ and $v=\\pi m$; clearly both these "
            "and their stability is periodic in $v$ with period $\\pi$.")
Q_LESS = ("The map as a whole is not periodic, as can be seen for free flights starting and "
          "ending at different $y$ values, but this becomes less significant at large $v$")
Q_LARGE_EPS = "for large $\\epsilon$ the motion is almost entirely chaotic."
Q_COEXIST = ("The parameter $\\epsilon=0.6$ of Fig.~\\ref{f:phase} shows clear elliptic islands "
             "around the fixed points, coexisting with Fermi acceleration of the chaotic orbits")
Q_FIXED_ELLIPTIC = ("the matrix has complex eigenvalues corresponding to an elliptic fixed point "
                    "in the region $0<\\epsilon<1$")
Q_FIXED_HYPERBOLIC = "For $\\epsilon<0$ or $\\epsilon>1$ the orbit is hyperbolic."
Q_PERIOD_TWO = ("For $\\epsilon>1$ the fixed points studied above become unstable (initially "
                "bifurcating into elliptic period 2 orbits)")
Q_SMALL_EPS = "For small $\\epsilon$ the velocity is bounded due to invariant curves."
Q_TRANSITION = ("Near $\\epsilon\\approx0.24$ (corresponding to $K=0.971\\ldots$) invariant "
                "spanning curves at all but the lowest velocities are disrupted, leading to "
                "unbounded velocity (Fermi acceleration) of some orbits.")
Q_ACCELERATOR = ("At some parameter values $K>2\\pi$, the standard map also has ``accelerator "
                 "modes'', which are orbits in which velocity increases linearly with discrete "
                 "time")
Q_ANOMALOUS = ("these can be stable and surrounded by elliptical islands, so yielding anomolous "
               "diffusion of velocity for the chaotic component")
Q_NORMAL = ("this $\\epsilon$ is below the lowest accelerator modes, so diffusion of velocity in "
            "discrete time is expected to be normal to a good approximation.")
Q_LYAPUNOV = ("The largest Lyapunov exponent as calculated for typical points in this component "
              "are likely to be positive for the discrete dynamics but zero in the continuous "
              "dynamics, as the chaos-inducing collisions are rare when the particle has high "
              "velocity.")
STUDY = ("the dynamics study (reports/paper/studies/dynamics_study.py, "
         "docs/report/dynamics/study.json)")
PROOF = "none: interval proofs"
SAMPLES = ("two samples at eps = 0.6: the departures along orbits from the paper's escape box "
           "(the flights of its simulations) and uniform departures over the first two velocity "
           "periods of Fig. 1")


def dynamics_entries():
    NEAR, LOWEST_MARGIN, SIGMAS = R.NEAR, R.LOWEST_MARGIN, R.SIGMAS  # noqa: N806
    parts = "a part is the agreement of its members; the claim is confirmed if every part is"
    return [
        entry_of(
            "sec2-fixed-elliptic", "sec2", "The fixed points (0, pi m) are elliptic for "
            "0 < eps < 1", Q_FIXED_ELLIPTIC, "certified enclosure of tr DF at the fixed point "
            f"and its residue R = (2 - tr)/4 (Krawczyk's operator on the exact map), {STUDY}",
            "the study's fixed points with 0 < eps < 1",
            "each member (a certified fixed point): confirmed if proved elliptic with a trace "
            "enclosure holding 2 - 4 eps, refuted if proved hyperbolic or the enclosure misses "
            f"it, inconclusive if undecided; {AGREE}", PROOF,
            family="every certified fixed point (0, pi m) of the study in the range"),
        entry_of(
            "sec2-fixed-hyperbolic", "sec2", "The fixed points (0, pi m) are hyperbolic for "
            "eps < 0 or eps > 1", Q_FIXED_HYPERBOLIC, "as sec2-fixed-elliptic",
            "the study's fixed points with eps < 0 or eps > 1",
            "as sec2-fixed-elliptic, the kind hyperbolic", PROOF,
            family="every certified fixed point (0, pi m) of the study in the range"),
        entry_of(
            "sec2-period-two", "sec2", "Above eps = 1 the fixed points are hyperbolic and "
            "period-2 orbits born there are elliptic", Q_PERIOD_TWO,
            "certified residues of the fixed points (eps > 1) and of the period-2 orbits "
            f"(s, pi m - s), (-s, pi m + s), eps sin s = s, {STUDY}",
            "eps from 1 to the period-2 orbits' first loss of stability",
            "two parts: every certified fixed point above 1 (confirmed if proved hyperbolic, "
            "refuted if elliptic) and every certified period-2 orbit below its first loss of "
            f"stability (confirmed if proved elliptic, refuted if hyperbolic); {parts}, refuted "
            "if one is", PROOF,
            family="every certified orbit of the study in the range, in two parts"),
        entry_of(
            "sec2-fermi-transition", "sec2", "Invariant spanning curves break near eps = 0.24 at "
            "all velocities but the lowest; beyond, velocity is unbounded for some orbits",
            Q_TRANSITION,
            "Greene's eps_c (residues of symmetric approximants crossing the critical residue "
            "R_c = 0.2500888, Aitken-extrapolated) of noble curves per velocity band j "
            "(v ~ pi (j + omega)); the high-velocity fit a + b/v + c/v^2; "
            f"direct simulation across each band, {STUDY}",
            "every velocity band computed, and the limit v -> infinity",
            f"three parts: 'near 0.24 at all but the lowest': each band j >= 1 confirmed within "
            f"{NEAR:.0%} of K_c/4, refuted beyond; band 0 confirmed beyond "
            f"{1 + LOWEST_MARGIN:g} K_c/4, refuted below; the limit a confirmed within 3 "
            "standard errors of K_c/4; 'unbounded velocity above eps_c': each simulation at "
            "1.10 eps_c confirmed if an orbit crosses its band; 'no crossing below eps_c': "
            "each simulation at 0.95 eps_c confirmed if none does and refuted if one does; "
            f"{parts}, refuted if one is",
            f"'near 0.24' = within {NEAR:.0%} of K_c/4; 'lowest velocities' = band 0 (v < pi) "
            f"beyond {1 + LOWEST_MARGIN:g} K_c/4",
            family="every band, the limit, and every simulation of the study"),
        entry_of(
            "sec2-small-eps-bounded", "sec2", "For eps below the first break-up every band "
            "keeps an invariant spanning curve, so velocities stay bounded", Q_SMALL_EPS,
            "the largest Greene eps_c found in each band, and the high-velocity limit",
            "every band computed and the limit v -> infinity",
            f"each band confirmed if its eps_c is at least (1 - {NEAR:g}) K_c/4, refuted if "
            f"below; the limit confirmed within 3 standard errors of K_c/4; {AGREE}",
            f"{NEAR:.0%} of K_c/4", family="every band and the limit"),
        entry_of(
            "sec2-accelerator-modes", "sec2", "Accelerator modes (v growing linearly in n) "
            "exist for K = 4 eps > 2 pi; in the exact map the period-1 ones are exact, from "
            "eps = pi/2 on", Q_ACCELERATOR,
            "certified period-1 blocks F(x) = x + (2 pi m, pi) of the exact map; Newton search "
            f"for period-1 blocks on an eps grid, {STUDY}", "the study's eps grid",
            "each certified block confirmed if proved elliptic (it exists and is stable); the "
            "search confirmed if the first period-1 block lies within one grid step of pi/2, "
            f"refuted if farther; {AGREE}", "one grid step in eps",
            family="every certified block and the search"),
        entry_of(
            "sec2-normal-diffusion", "sec2", "eps = 0.6 lies below the lowest elliptic "
            "(island-bearing) accelerator modes, and velocity diffusion in discrete time is "
            "normal (<(v_n - v_0)^2> ~ n^mu, mu = 1)", Q_NORMAL,
            "the slope mu of log <(v_n - v_0)^2> against log n from the paper's start box; the "
            f"Newton search for accelerator blocks by period, {STUDY}",
            "eps = 0.6, the study's windows of n past the transient (starting at n0 >= its "
            "family_from); the periods searched",
            "two parts: 'below the lowest accelerator modes', each period searched confirmed "
            "if its first elliptic block lies above eps = 0.6, refuted at or below; 'normal to "
            f"a good approximation', each window's mu (1.96 standard errors) confirmed within "
            f"{R.pct(R.SAME)} of 1, refuted wholly beyond {R.pct(R.SAME_FAILS)}; {parts}, "
            "refuted if one is",
            f"'normal to a good approximation': mu within {R.pct(R.SAME)} of 1, not beyond "
            f"{R.pct(R.SAME_FAILS)}",
            family="every period searched; every window of mu past the transient"),
        entry_of(
            "sec2-anomalous-diffusion", "sec2", "where accelerator modes are stable and "
            "surrounded by islands, the chaotic component's velocity diffuses anomalously",
            Q_ANOMALOUS,
            "the certified accelerator blocks' stability; mu of the diffusion runs at the eps "
            f"of the certified elliptic blocks, {STUDY}",
            "the eps of the certified elliptic blocks (K > 2 pi)",
            "two parts: 'stable, surrounded by islands', each certified block confirmed if "
            "proved elliptic; 'anomalous diffusion', each window's |mu - 1| (1.96 standard "
            f"errors) confirmed at or beyond {R.pct(R.SAME_FAILS)}, refuted within "
            f"{R.pct(R.SAME)} (normal); {parts}, refuted if one is",
            f"'anomalous': mu at least {R.pct(R.SAME_FAILS)} from 1; normal: within "
            f"{R.pct(R.SAME)}",
            family="every certified block; every window of mu at their eps past the transient"),
        entry_of(
            "intro-lyapunov", "intro", "The largest Lyapunov exponent is positive per "
            "collision and tends to zero per unit time", Q_LYAPUNOV,
            "lambda_n = S_n/n and lambda_t = S_n/t_n from the tangent map (exact Jacobian, "
            f"renormalised every collision), mean over orbits, {STUDY}",
            "eps = 0.6, orbits from the paper's start box",
            f"two parts: 'positive per collision', lambda_n at the last checkpoint and a decade "
            f"before it, each confirmed if above 0 by {SIGMAS:g} standard errors, refuted if "
            f"below by as many; 'zero per unit time', each window's alpha of lambda_t ~ "
            f"t^alpha confirmed if below 0 by {SIGMAS:g} standard errors, refuted if above; "
            f"{parts}, refuted if one is", f"signs at {SIGMAS:g} standard errors",
            family="two checkpoints of lambda_n; every fitted window of alpha"),
    ]


def section2_entries():
    same2 = R.relative_band(2.0, R.SAME)
    fails2 = R.relative_band(2.0, R.SAME_FAILS)
    return dynamics_entries() + [
        entry_of(
            "sec2-never-overstepped", "sec2", "the paper's lower-bound time step never steps "
            "past the first collision, up to round-off", Q_OVERSTEP,
            "flights of fastpath.flight(method='lower_bound') (the paper's steps) that end past "
            "a later root, judged against verify (reports/precision/evaluate.overstepped: past "
            "the first root with the gap rising, or positive between: the rounding of the last "
            "step does not count)", "every flight",
            "'never' is exact: each member confirmed if none of its flights oversteps, refuted "
            f"if one does; {AGREE}", "none (modulo round-off, as judged)",
            family=f"{SAMPLES}; the close root pairs and the hard cases of the precision "
                   "comparison, where a step past the first root is possible at all"),
        entry_of(
            "sec2-quadratic", "sec2", "the lower-bound iteration converges quadratically: "
            "e_{k+1} ~ C e_k^2", Q_QUADRATIC,
            "the order p of the iterates' distance to the root, e_{k+1} ~ C e_k^p, from the "
            "iterates at 80 digits (the median over a flight's steps, then over flights; "
            "bootstrap interval over flights)", "typical flights (the paper's 'typically')",
            f"'the same' order as 2, each member: confirmed if the interval lies in "
            f"[{same2[0]:g}, {same2[1]:g}], refuted if wholly outside [{fails2[0]:g}, "
            f"{fails2[1]:g}]; {AGREE}",
            f"'quadratically': order within {R.pct(R.SAME)} of 2, not beyond "
            f"{R.pct(R.SAME_FAILS)}", family=SAMPLES),
        entry_of(
            "sec2-five-steps", "sec2", "in practice the lower-bound iteration reaches machine "
            "precision in about five steps", Q_FIVE,
            "the mean number of steps of fastpath.flight(method='lower_bound') (its stopping "
            "rule: the step below the float64 resolution of the flight time) with its bootstrap "
            "interval", "the flights of the paper's simulations ('in practice')",
            "each member: confirmed if the mean's interval lies in [4, 6], refuted if it lies "
            f"wholly outside [2.5, 10]; {AGREE}",
            "'around five': within one step of five; not: a factor two off", family=SAMPLES),
        entry_of(
            "sec2-stability-period-pi", "sec2", "the fixed points (0, pi m) have the same "
            "stability for every m: periodic in v with period pi", Q_PERIOD,
            "verify.periodic_orbit at (0, pi m), m = 1..4: the certified kind (elliptic, "
            "hyperbolic) and the enclosure of the trace of the linearisation",
            "the fixed points of the first four velocity periods",
            "each member: confirmed if every m gives the same certified kind and a trace "
            "enclosure holding 2 - 4 eps, refuted if one differs, inconclusive if one is not "
            f"certified; {AGREE}", "none: certified enclosures",
            family="eps = 0.3 and 0.6 (elliptic) and 1.5 (hyperbolic)"),
        entry_of(
            "sec2-less-significant", "sec2", "the map's departure from periodicity in v falls "
            "as v grows", Q_LESS,
            "the exact map from (phi, v + pi) against the one from (phi, v) shifted by pi: the "
            "median over random phases of |delta phi_1| and |delta v_1| at v = pi (m + 1/2), "
            "m = 1, 2, 4, ..., 64, eps = 0.6; the slope of log median on log v with its "
            "bootstrap interval", "v from 4.7 to 203",
            "each member: confirmed if the slope's interval lies below 0 (the departure "
            f"falls), refuted if above; {AGREE}", "a sign: 'less significant' is a fall",
            family="the two departures, in phase and in velocity"),
        entry_of(
            "sec2-large-eps-chaotic", "sec2", "for large eps nearly all of phase space is "
            "chaotic sea", Q_LARGE_EPS,
            "share of random starts on islands (regular: velocity within a band of 5 for 2000 "
            "collisions; reports/paper/studies/islands.py)",
            "eps = 2 and 4 (the fixed points are hyperbolic beyond eps = 1)",
            f"each member: confirmed if the Wilson interval lies at or below "
            f"{R.pct(R.ALMOST_ENTIRELY)}, refuted if at or above "
            f"{R.pct(R.ALMOST_ENTIRELY_FAILS)}; {AGREE}",
            "'almost entirely chaotic', share on islands: "
            + R.bounds_text(R.ALMOST_ENTIRELY, R.ALMOST_ENTIRELY_FAILS),
            family="eps = 2 and 4, each in two velocity bands of one period well above the "
                   "plate's speed (10 < v < 10 + pi, 20 < v < 20 + pi)"),
        entry_of(
            "sec2-islands-coexist", "sec2", "at eps = 0.6 clear elliptic islands surround the "
            "fixed points while the chaotic orbits accelerate", Q_COEXIST,
            "two parts: the share of the box |phi| < 1 around (0, pi m) on the island of "
            "(0, pi m); the slope of log<v_n> on log n of the Fermi ensemble (no holes, the "
            "paper's start box)", "eps = 0.6; the Fermi ensemble's diffusive regime",
            f"'clear islands', each member confirmed if the share's Wilson interval lies at or "
            f"above {R.pct(R.BOTH)}, refuted if at or below {R.pct(R.BOTH_FAILS)} (a trace); "
            "'Fermi acceleration', each member confirmed if the slope's 95% interval lies "
            "above 0, refuted if below; a part is the agreement of its members; the claim is "
            "confirmed if both parts are, refuted if one is",
            f"'clear': {R.bounds_text(R.BOTH, R.BOTH_FAILS)} of the box; 'acceleration': a "
            "growing <v_n> (a sign)",
            family="the islands of (0, pi) and (0, 2 pi); the windows inside the diffusive "
                   "regime (as fermi-n)"),
    ]
