"""The hard cases of the bouncer flight problem: ONE named table, shared by the tests and reports.

Each ``HardCase`` holds float64 inputs (the exact values every integrator sees), an id and a
one-line reason why the case is hard. Small-w0 entries are built as v = w0 - eps*sin(phi) in
float64, so the actual w0 of the float inputs differs from the nominal one in its last digits.
The near-grazing entries were made with ``verify.grazing_contact(eps, psi, T0, clearance)`` at
50 digits and rounded to float64, which moves the clearance by ~T*1e-16: the "0" entries are
graze-or-miss at a clearance of order 1e-16, which float64 cannot decide (``contact`` is the
time of the tangency, ``clearance`` the nominal minimum gap).

Every entry is labelled with its class ``kind`` (see ``KINDS``) and what a solver must do,
``expect``: ``"flight"`` (return the certified flight time) or ``"ValueError"`` (float64 cannot
hold the flight: ``tau``, ``v**2`` or ``tau*v`` overflow, so a float64 integrator must raise a
``ValueError`` saying so; verify, whose mpmath exponents are unbounded, certifies these flights).
``HARD_CASES`` holds the ``"flight"`` entries, ``OVERFLOW_CASES`` the ``"ValueError"`` ones,
``ALL_CASES`` both.

Further classes: ``eps->1`` (eps = 1 -+ 1e-12, 1 -+ 1e-6 and 1 exactly: concavity
degenerates at 1), ``near-triple-root`` (``phi = -x, v = x``: for ``|eps| <= 1`` the exact
flight time is ``2x``, and ``d'(2x) = eps*sin(x) - x ~ -x**3/6`` at eps = 1: a near-triple root),
``huge-phase`` (``|phi|`` = 1e12 .. 1e300: reduction modulo 2*pi needs ~|phi|/2**53 more bits
than the phase holds), ``overflow``.

The dissipative classes (``DISSIPATIVE_CASES``, with ``drag``, ``drag_law`` and the
certified ``tau``): ``drag-graze``, ``w0=0 departure`` and ``chattering-graze`` (near-grazes of a
chattering departure with small w0 just before the phase where the plate's acceleration falls
through -1; elastic rows have ``drag = 0.0`` and stay out of ``HARD_CASES``, so that the elastic
table's counted figures do not move; see the table).
"""

import math
from typing import NamedTuple

from .numerics.float64 import TWO_PI


class HardCase(NamedTuple):
    id: str
    phi: float
    v: float
    eps: float
    reason: str
    contact: float | None = None
    clearance: float | None = None
    kind: str = ""
    expect: str = "flight"
    drag: float = 0.0
    drag_law: str = "linear"
    restitution: float = 1.0
    tau: float | None = None  # the certified flight time rounded to float64, where stored


PI = math.pi


def _w0(w0, phi, eps, tag, kind="small-w0"):
    v = w0 - eps * math.sin(phi)  # libm's sin reduces huge phases exactly (to < 1 ulp)
    return HardCase(
        f"w0={w0:g}-eps={eps:g}{tag}",
        phi,
        v,
        eps,
        f"tiny departure speed w0 ~ {w0:g} (kappa ~ v/w0): cancellation in d",
        kind=kind,
    )


def _graze(phi, v, eps, psi, t_contact, clearance):
    return HardCase(
        f"graze-eps={eps:g}-c={clearance}",
        phi,
        v,
        eps,
        f"near-tangency at T={t_contact:.6g}, plate phase psi={psi}, clearance {clearance}"
        " (verify.grazing_contact)",
        contact=t_contact,
        clearance=float(clearance),
        kind="graze",
    )


def _case(phi, v, eps, reason, case_id, kind, expect="flight"):
    return HardCase(case_id, phi, v, eps, reason, kind=kind, expect=expect)


def _triple(x, eps, tag):
    return _case(-x, x, eps, f"phi = -x, v = x, x = {x:g}: flight 2x, d'(2x) = eps*sin(x) - x "
                 f"(near-triple root at eps = {tag})", f"triple-x={x:g}-eps={tag}",
                 "near-triple-root")


_EPS_NEAR_ONE = ((1.0 - 1e-12, "1-1e-12"), (1.0 - 1e-6, "1-1e-6"), (1.0, "1"),
                 (1.0 + 1e-6, "1+1e-6"), (1.0 + 1e-12, "1+1e-12"))


HARD_CASES = (
    # departure speed w0 from 1e-3 down to 1e-12
    *[_w0(w0, 4.0, 0.6, "") for w0 in (1e-3, 1e-6, 1e-9, 1e-12)],
    *[_w0(w0, 4.0, 3.0, "") for w0 in (1e-3, 1e-6, 1e-9, 1e-12)],
    _w0(1e-6, 4.0, 0.999999, "", kind="eps->1"),
    _w0(1e-9, 4.0, 1e-8, ""),
    _w0(1e-6, 5.0, 100.0, ""),
    # large velocities: tau ~ 2v, the Holmes limit, t*(v - t/2) cancels near the root
    _case(1.0, 1e3, 0.6, "v = 1e3: tau ~ 2e3, cancellation in t*(v - t/2)", "v=1e3-eps=0.6",
          "large-v"),
    _case(1.0, 1e6, 0.6, "v = 1e6: tau ~ 2e6, gap_error ~ 1e-3 in absolute terms", "v=1e6-eps=0.6",
          "large-v"),
    _case(4.0, 1e6, 100.0, "v = 1e6 at eps = 100: large plate term", "v=1e6-eps=100", "large-v"),
    _case(0.5, 1e5, 3.0, "v = 1e5 at eps = 3", "v=1e5-eps=3", "large-v"),
    # the eps range, at one generic state
    *[
        _case(4.0, 3.0, eps, f"eps = {eps!r}: {why}", f"eps={eps!r}",
              "eps->1" if 0.99 < eps < 1.01 else "eps-range")
        for eps, why in (
            (1e-8, "plate almost still: tau ~ 2v"),
            (0.2429, "the paper: last spanning invariant curves break (K = 4*eps ~ 0.971)"),
            (0.6, "the paper's standard eps"),
            (0.999999, "concave bound 2*w0/(1-eps) almost useless"),
            (1.0, "d'' <= 0 only: the concavity degenerates"),
            (1.000001, "just convex: crawling near tangencies is possible"),
            (3.0, "several roots possible"),
        )
    ],
    _case(1.0, 3.0, 100.0, "eps = 100: plate amplitude >> flight height", "eps=100", "eps-range"),
    _case(4.0, 80.0, 100.0, "eps = 100, departure on the falling plate", "eps=100-phi=4",
          "eps-range"),
    _case(4.0, 3.0, -0.6, "negative eps (the pi-shifted model)", "eps=-0.6", "eps-range"),
    # phases at and next to 0 and pi (and the top end of [0, 2*pi))
    *[
        _case(phi, 3.0, eps, f"phase {name} at eps = {eps}", f"phi={name}-eps={eps:g}",
              "special-phase")
        for eps in (0.6, 3.0)
        for phi, name in (
            (0.0, "0"),
            (math.nextafter(0.0, 1.0), "0+"),
            (math.nextafter(0.0, -1.0), "0-"),
            (math.nextafter(TWO_PI, 0.0), "2pi-"),
            (TWO_PI, "float(2pi)"),
            (PI, "pi"),
            (math.nextafter(PI, 0.0), "pi-"),
            (math.nextafter(PI, 4.0), "pi+"),
        )
    ],
    # unreduced phases
    *[
        _case(phi, 3.0, eps, f"unreduced phase {phi!r} at eps = {eps}",
              f"phi={phi!r}-eps={eps:g}", "unreduced-phase")
        for eps in (0.6, 3.0)
        for phi in (1e6 + 0.3, -50.0)
    ],
    # a small negative phase is reduced to ~2*pi - 0.34 inside fastpath, so its gap error bound
    # grows with 5.94 instead of 0.34 on a short flight
    _case(
        -0.34274032340288646,
        0.3529882181733127,
        1.05,
        "small negative phase, short flight past a near-graze (clearance -1e-6, eps = 1.05)",
        "negative-phase-short-graze",
        "graze",
    ),
    # near-grazing pairs for eps > 1 (generated by verify.grazing_contact, see the docstring)
    _graze(-2.4762056588386616, 2.3329253488466524, 1.5, 0.3, 2.776205658838662, "1e-2"),
    _graze(-2.4690589104382212, 2.325778600446212, 1.5, 0.3, 2.769058910438221, "1e-6"),
    _graze(-2.469058191769642, 2.3257778817776327, 1.5, 0.3, 2.7690581917696417, "1e-10"),
    _graze(-2.469058191697768, 2.3257778817057586, 1.5, 0.3, 2.7690581916977677, "0"),
    _graze(-2.469058191625894, 2.3257778816338845, 1.5, 0.3, 2.7690581916258936, "-1e-10"),
    _graze(-2.4690574729565076, 2.3257771629644983, 1.5, 0.3, 2.7690574729565074, "-1e-6"),
    _graze(-3.892051019375766, 3.305490399391747, 3.0, 0.3, 4.192051019375766, "1e-2"),
    _graze(-3.8901814972737423, 3.3036208772897235, 3.0, 0.3, 4.190181497273742, "1e-6"),
    _graze(-3.8901813102170144, 3.3036206902329956, 3.0, 0.3, 4.190181310217015, "1e-10"),
    _graze(-3.8901813101983067, 3.3036206902142884, 3.0, 0.3, 4.190181310198307, "0"),
    _graze(-3.8901813101795994, 3.3036206901955807, 3.0, 0.3, 4.190181310179599, "-1e-10"),
    _graze(-3.8901811231228502, 3.303620503138832, 3.0, 0.3, 4.1901811231228505, "-1e-6"),
    _graze(-3.433135364898757, 7.727390750940787, 10.0, -0.5, 2.933135364898757, "1e-2"),
    _graze(-3.4321917693774617, 7.726447155419492, 10.0, -0.5, 2.9321917693774617, "1e-6"),
    _graze(-3.4321916749734367, 7.726447061015467, 10.0, -0.5, 2.9321916749734367, "1e-10"),
    _graze(-3.4321916749639954, 7.726447061006025, 10.0, -0.5, 2.9321916749639954, "0"),
    _graze(-3.432191674954554, 7.726447060996584, 10.0, -0.5, 2.932191674954554, "-1e-10"),
    _graze(-3.4321915805505196, 7.726446966592549, 10.0, -0.5, 2.9321915805505196, "-1e-6"),
    _graze(-0.9879746258602482, 1.0065108897348156, 1.1, -0.2, 0.7879746258602481, "1e-2"),
    _graze(-0.8181916350180554, 0.8367278988926227, 1.1, -0.2, 0.6181916350180553, "1e-6"),
    _graze(-0.818162071602777, 0.8366983354773443, 1.1, -0.2, 0.6181620716027769, "1e-10"),
    _graze(-0.8181620686458191, 0.8366983325203865, 1.1, -0.2, 0.6181620686458191, "0"),
    _graze(-0.8181620656888612, 0.8366983295634286, 1.1, -0.2, 0.6181620656888612, "-1e-10"),
    _graze(-0.8181324958596152, 0.8366687597341825, 1.1, -0.2, 0.6181324958596152, "-1e-6"),
    # eps -> 1 from both sides: at a generic state and on a short flight (-0.01, 0.01)
    *[_case(4.0, 3.0, eps, f"eps = {tag} at a generic state", f"eps={tag}", "eps->1")
      for eps, tag in _EPS_NEAR_ONE if tag in ("1-1e-12", "1+1e-12")],
    *[_case(-0.01, 0.01, eps, f"eps = {tag}, short flight phi = -0.01, v = 0.01 (w0 ~ 1.7e-7)",
            f"short-eps={tag}", "eps->1") for eps, tag in _EPS_NEAR_ONE],
    # near-triple roots: phi = -x, v = x (exact flight 2x for |eps| <= 1)
    *[_triple(x, eps, tag) for x in (1e-6, 1e-4, 1e-2, 1.0)
      for eps, tag in ((1.0, "1"), (1.0 - 1e-6, "1-1e-6"))],
    # huge phases: reduction modulo 2*pi with precision growing with the exponent of phi
    *[_case(phi, 3.0, eps, f"huge phase {phi:g} at eps = {eps}", f"phi={phi:g}-eps={eps:g}",
            "huge-phase") for eps in (0.6, 3.0) for phi in (1e12, 1e17, 1e300, -1e300)],
    _w0(1e-8, 1e12, 0.6, "-phi=1e12", kind="huge-phase"),
)

# float64 overflow: tau ~ 2e308 > DBL_MAX, v**2 = inf, eps*... terms near DBL_MAX
OVERFLOW_CASES = (
    _case(1.0, 1e308, 0.6, "v = 1e308: tau ~ 2e308 overflows float64", "v=1e308", "overflow",
          "ValueError"),
    _case(0.5, 3.0, 1e300, "eps = 1e300: eps*sin and v1 ~ 1e300, d'' ~ 1e300", "eps=1e300",
          "overflow", "ValueError"),
    _case(1.0, 1e308, 1e300, "v = 1e308 and eps = 1e300", "v=1e308-eps=1e300", "overflow",
          "ValueError"),
    _case(1.0, 1e200, 0.6, "v = 1e200: v**2 and tau*v overflow float64", "v=1e200", "overflow",
          "ValueError"),
)

def _dissipative(case_id, phi, v, eps, law, k, tau, kind, reason):
    return HardCase(case_id, phi, v, eps, reason, kind=kind, drag=k, drag_law=law, tau=tau)


# Flights with drag (not in HARD_CASES, whose users call the elastic model). ``tau`` is
# verify.certify_flight(..., drag=k, drag_law=law).tau at 50 digits rounded to float64.
# "drag-graze": the elastic near-grazes above (clearance 1e-2, +-1e-6) under drag 1e-8, which
# moves the clearance by ~1e-8: still a pass above (landing later) or a close root pair.
# "w0=0 departure": phi = 0, v = 0 (w0 = 0 exactly): d''(0) = eps - 1 > 0, or d''(0) = 0 with
# d'''(0) = k > 0 (eps = 1, linear drag): the gap opens by its curvature.
_DRAG_GRAZES = (
    (-2.4762056588386616, 2.3329253488466524, 1.5, "1e-2",
     4.2633070636679635, 4.263306931899682),
    (-2.4690589104382212, 2.325778600446212, 1.5, "1e-6", 4.233979529806101, 4.23397939194823),
    (-2.4690574729565076, 2.3257771629644983, 1.5, "-1e-6",
     2.766852168072916, 2.7668128824794938),
    (-3.8901814972737423, 3.3036208772897235, 3.0, "1e-6",
     6.8232924430174675, 6.823292321128432),
    (-3.8901811231228502, 3.303620503138832, 3.0, "-1e-6", 4.189062665767766, 4.188954674819296),
)
# "chattering-graze": a chattering particle (restitution r < 1) leaves each
# impact with a small relative speed w = w0. Just before theta* = 2*pi - arccos(1/eps), where the
# plate's acceleration -eps*cos falls through -1, the relative acceleration d'' = -1 - eta(V) +
# eps*cos(phi + t) is slightly negative at the departure and turns positive a moment later, so
# with a = sqrt(eps**2 - 1) and phi = theta* - delta the gap is d(t) ~ (a/6)*t*(t**2 - 3*delta*t +
# 6*w/a): a hump of height ~a*delta**3/12, then a dip at t_m ~ 3*delta/2 that is tangent to the
# plate when w = 3*a*delta**2/8. Below the tangency the particle comes back in the dip nearly
# tangentially (two roots ~sqrt(8*|c|/(a*delta)) apart, slope ~sqrt(a*delta*|c|), kappa up to
# ~1e12); above it, it leaves and lands an O(1) time later. As delta -> 0 the hump, the dip and
# the departure merge into a triple root at t = 0 (d''(0) = -a*delta ~ 0): w = 1e-3, 1e-5, 1e-8,
# 1e-9 take delta = 0.049, 0.0049, 1.5e-4, 4.9e-5 and the hump height from 1e-5 down to 1e-14,
# so a float64 solver must resolve a clearance c against a gap whose whole dip is tiny, and
# crawl past a positive one (fastpath's lower-bound steps, built on the global curvature bound
# 1 + |eps| while the dip's own d'' is ~a*delta/2, take 54 of their 60 iterations for c = 1e-15
# at w = 1e-9 and run out at c = 1e-16: MAX_ITERATIONS before the first root, not a wrong
# answer). v was tuned at 60 digits so that the dip's minimum is c (scripts/chattering_grazes.py
# prints these rows); "0+" / "0-" are the two float64 neighbours of the exact tangency's v
# (actual clearance of the float inputs ~1e-17..1e-21, either side of 0: float64 cannot decide
# them, verify can).
# Elastic rows (drag 0.0: the flight is the elastic gap, restitution acts only at impacts) and
# linear/quadratic drag 1e-8. Row: (eps, law, drag, nominal w, nominal clearance, phi, v, t_m =
# contact (the dip), actual clearance of the float64 inputs (60 digits), certified tau).
_CHATTER_GRAZES = (
    (1.5, "linear", 0.0, 0.001, "1e-6", 5.3932787499251935, 1.1665492131141069,
     0.07295019910426484, 9.999999999982523e-07, 3.614432949989247),
    (1.5, "linear", 0.0, 0.001, "1e-10", 5.3932787499251935, 1.1665355541279248,
     0.07345717177717401, 9.999999529061691e-11, 3.6144061223269106),
    (1.5, "linear", 0.0, 0.001, "1e-14", 5.3932787499251935, 1.166535552766724,
     0.07345722178564051, 1.0007045674577471e-14, 3.6144061196533452),
    (1.5, "linear", 0.0, 0.001, "0+", 5.3932787499251935, 1.166535552766588,
     0.07345722179064111, 8.537662793698133e-18, 3.614406119653078),
    (1.5, "linear", 0.0, 0.001, "0-", 5.3932787499251935, 1.1665355527665877,
     0.07345722179064927, -7.77311699769608e-18, 0.07345719789201204),
    (1.5, "linear", 0.0, 0.001, "-1e-14", 5.3932787499251935, 1.1665355527664516,
     0.07345722179564987, -1.0006281129463226e-14, 0.07345636433478465),
    (1.5, "linear", 0.0, 0.001, "-1e-10", 5.3932787499251935, 1.1665355514052518,
     0.07345727180398329, -9.999999736802458e-11, 0.0733715039634635),
    (1.5, "linear", 0.0, 0.001, "-1e-6", 5.3932787499251935, 1.1665219851311428,
     0.07395078522084327, -1.0000000000031789e-06, 0.06490805250722828),
    (1.5, "linear", 0.0, 1e-05, "1e-10", 5.43723284794301, 1.1229144547076721,
     0.007322676525025341, 1.0000000017432696e-10, 3.5710940935705504),
    (1.5, "linear", 0.0, 1e-05, "1e-14", 5.43723284794301, 1.1229144410574967,
     0.007327682869693701, 1.0000551695597456e-14, 3.5710940670983193),
    (1.5, "linear", 0.0, 1e-05, "0+", 5.43723284794301, 1.122914441056132,
     0.00732768336969448, 5.640901417423175e-19, 3.571094067095673),
    (1.5, "linear", 0.0, 1e-05, "0-", 5.43723284794301, 1.1229144410561318,
     0.007327683369775834, -1.0629824171062476e-18, 0.007327655460549899),
    (1.5, "linear", 0.0, 1e-05, "-1e-14", 5.43723284794301, 1.1229144410547673,
     0.007327683869695157, -9.999424197658036e-15, 0.007324976475516603),
    (1.5, "linear", 0.0, 1e-05, "-1e-10", 5.43723284794301, 1.1229144274139038,
     0.007332676584127262, -9.999999926505817e-11, 0.007057040390453982),
    (1.5, "linear", 0.0, 1e-08, "1e-14", 5.441962197653618, 1.1181884244177172,
     0.00023115826202051924, 1.0000006812475817e-14, 3.5663711695140856),
    (1.5, "linear", 0.0, 1e-08, "0+", 5.441962197653618, 1.1181884243745037,
     0.00023166043693698569, 2.6340441241780395e-21, 3.566371169430392),
    (1.5, "linear", 0.0, 1e-08, "0-", 5.441962197653618, 1.1181884243745035,
     0.00023166043950893317, -4.880490635779861e-20, 0.00023162681242620134),
    (1.5, "linear", 0.0, 1e-08, "-1e-14", 5.441962197653618, 1.1181884243313835,
     0.0002321582940384019, -9.999981077038845e-15, 0.0002164482615086749),
    (1.5, "linear", 0.0, 1e-09, "1e-15", 5.4420677987249695, 1.1180828263169431,
     7.275003333360665e-05, 1.0000068555873058e-15, 3.566265574195673),
    (1.5, "linear", 0.0, 1e-09, "1e-16", 5.4420677987249695, 1.1180828263046108,
     7.32069610832164e-05, 1.0000106053707047e-16, 3.566265574171789),
    (1.5, "linear", 0.0, 1e-09, "0+", 5.4420677987249695, 1.1180828263032454,
     7.325702323961822e-05, 1.3581697185772918e-20, 3.5662655741691447),
    (1.5, "linear", 0.0, 1e-09, "0-", 5.4420677987249695, 1.1180828263032452,
     7.325703137278327e-05, -2.684630500414706e-21, 7.324300619166333e-05),
    (1.5, "linear", 0.0, 1e-09, "-1e-15", 5.4420677987249695, 1.1180828262896405,
     7.375036698235996e-05, -1.0000076585292634e-15, 6.471239473825638e-05),
    (3.0, "linear", 0.0, 1e-06, "1e-10", 5.051254906295397, 2.8293978448588004,
     0.0014025889029493498, 9.99999998208056e-11, 5.968578735272975),
    (3.0, "linear", 0.0, 1e-06, "0+", 5.051254906295397, 2.829397774932447,
     0.0014565065604678976, 5.485290224179635e-19, 5.968578667280034),
    (3.0, "linear", 0.0, 1e-06, "0-", 5.051254906295397, 2.8293977749324464,
     0.001456506560791307, -9.828982523346894e-20, 0.0014564945958023734),
    (3.0, "linear", 0.0, 1e-06, "-1e-10", 5.051254906295397, 2.8293977073799828,
     0.0015034342067905952, -9.99999996985261e-11, 0.0010779543498931309),
    (1.5, "linear", 1e-08, 0.001, "1e-6", 5.3932787499251935, 1.1665492135307374,
     0.07295021439620368, 1.0000000000005035e-06, 3.614432952165656),
    (1.5, "linear", 1e-08, 0.001, "1e-10", 5.3932787499251935, 1.1665355545473837,
     0.07345718685706958, 1.0000000389170322e-10, 3.614406124509075),
    (1.5, "linear", 1e-08, 0.001, "0+", 5.3932787499251935, 1.166535553186047,
     0.07345723687051828, 1.29574507151866e-17, 3.6144061218352426),
    (1.5, "linear", 1e-08, 0.001, "0-", 5.3932787499251935, 1.1665355531860468,
     0.07345723687052644, -3.3533324186222542e-18, 0.07345722117363082),
    (1.5, "linear", 1e-08, 0.001, "-1e-10", 5.3932787499251935, 1.1665355518247111,
     0.07345728688384207, -9.999999712948881e-11, 0.07337151905218814),
    (1.5, "linear", 1e-08, 0.001, "-1e-6", 5.3932787499251935, 1.1665219855533544,
     0.07395080010249726, -1.0000000000028411e-06, 0.06490806844947103),
    (1.5, "linear", 1e-08, 1e-08, "0+", 5.441962197653618, 1.118188424375799,
     0.00023167543680672743, 1.0419022280591453e-20, 3.566371171871206),
    (1.5, "linear", 1e-08, 1e-08, "0-", 5.441962197653618, 1.1181884243757987,
     0.00023167543937850838, -4.102325884145785e-20, 0.00023164461063352642),
    (1.5, "quadratic", 1e-08, 0.001, "1e-6", 5.3932787499251935, 1.1665492135901037,
     0.07295021620340598, 1.0000000000048566e-06, 3.6144329576288663),
    (1.5, "quadratic", 1e-08, 0.001, "1e-10", 5.3932787499251935, 1.1665355546070777,
     0.07345718863397419, 9.999999427251888e-11, 3.6144061299729824),
    (1.5, "quadratic", 1e-08, 0.001, "0+", 5.3932787499251935, 1.166535553245741,
     0.07345723864742115, 9.664654649657128e-19, 3.61440612729915),
    (1.5, "quadratic", 1e-08, 0.001, "0-", 5.3932787499251935, 1.1665355532457409,
     0.07345723864742931, -1.534431805570215e-17, 0.07345720506985591),
    (1.5, "quadratic", 1e-08, 0.001, "-1e-10", 5.3932787499251935, 1.1665355518844054,
     0.07345728866073503, -9.999999518147674e-11, 0.07337152083137613),
    (1.5, "quadratic", 1e-08, 0.001, "-1e-6", 5.3932787499251935, 1.1665219856133666,
     0.07395080185099367, -1.0000000000036865e-06, 0.06490807037015349),
    (1.5, "quadratic", 1e-08, 1e-08, "0+", 5.441962197653618, 1.118188424375952,
     0.00023167720721755807, 1.3006693971871711e-20, 3.566371177371703),
    (1.5, "quadratic", 1e-08, 1e-08, "0-", 5.441962197653618, 1.1181884243759517,
     0.00023167720978931936, -3.843598026027518e-20, 0.00023164736921622),
)


def _chatter(eps, law, k, w, c, phi, v, t_m, clearance, tau):
    model = "elastic" if k == 0.0 else f"{law}-drag={k:g}"
    where = "lands in the dip" if tau < 2 * t_m else "passes over it and lands later"
    return HardCase(
        f"chatter-graze-{model}-eps={eps:g}-w={w:g}-c={c}", phi, v, eps,
        f"chattering departure (w0 ~ {w:g}) just before theta* = 2*pi - arccos(1/eps): dip at "
        f"t = {t_m:.3g}, clearance {clearance:.3g} (nominal {c}), {where}",
        contact=t_m, clearance=clearance, kind="chattering-graze", drag=k, drag_law=law, tau=tau)


CHATTERING_GRAZES = tuple(_chatter(*row) for row in _CHATTER_GRAZES)


DISSIPATIVE_CASES = (
    *[_dissipative(f"drag-graze-{law}-eps={eps:g}-c={c}", phi, v, eps, law, 1e-8, tau,
                   "drag-graze", f"near-graze (clearance {c}) at eps = {eps} under {law} drag 1e-8")
      for phi, v, eps, c, tau_lin, tau_quad in _DRAG_GRAZES
      for law, tau in (("linear", tau_lin), ("quadratic", tau_quad))],
    _dissipative("w0=0-eps=1.5-linear", 0.0, 0.0, 1.5, "linear", 0.1, 2.347056382201692,
                 "w0=0 departure", "departure at rest, d''(0) = 0.5 > 0"),
    _dissipative("w0=0-eps=1.5-quadratic", 0.0, 0.0, 1.5, "quadratic", 0.1, 2.365794430471219,
                 "w0=0 departure", "departure at rest, d''(0) = 0.5 > 0"),
    _dissipative("w0=0-eps=1-linear", 0.0, 0.0, 1.0, "linear", 0.1, 0.39814790798759475,
                 "w0=0 departure", "departure at rest, d''(0) = 0 exactly, d'''(0) = k > 0"),
    *CHATTERING_GRAZES,
)

ALL_CASES = HARD_CASES + OVERFLOW_CASES + DISSIPATIVE_CASES

KINDS = tuple(sorted({case.kind for case in ALL_CASES}))
