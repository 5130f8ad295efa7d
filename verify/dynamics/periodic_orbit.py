"""Certified periodic orbits of the exact collision map (Krawczyk's operator).

A periodic orbit of period p, winding m and velocity shift l is a zero of

    G(x) = F^p(x) - x - (2*pi*m, pi*l),    x = (phi, v),

with F^p's phase unreduced (so G's first component is the total time minus 2*pi*m). For a box
X = x + [-r, r]^2, an enclosure G(x) of G at the point, an enclosure J of DF^p over X and any
matrix C (here the inverse of (DF^p(x) - I) computed in the point context), Krawczyk's operator

    K(X) = x - C G(x) + (I - C (J - I)) (X - x)

satisfies: if K(X) lies in the interior of X, then G has exactly one zero in X, and it lies in
K(X) (Krawczyk 1969; Moore; the method of CAPD's and IntervalRootFinding.jl's proofs). The
enclosures come from :mod:`verify.dynamics.orbit_enclosure`, where every flight of every box is
certified: the departure, no collision before the bracket, one transversal root inside it.

Stability. With T the enclosure of tr DF^p over the final box, the residue is R = (2 - T)/4
(Greene): ``"elliptic"`` when 0 < R < 1 is proved, ``"hyperbolic"`` when R < 0 or R > 1 is
proved, ``"undecided"`` otherwise. Over a periodic orbit det DF^p = 1 (the map preserves
w dphi dv, w = v + eps*sin(phi), and the factors w_k/w_(k+1) telescope).

Minimal period. A zero of G for period p may be an orbit of a shorter period d (a divisor of p):
the fixed point (0, pi) is a zero of every F^p - id - (2*pi*p, 0). If F^d(x) = x (mod 2*pi in
phase), the next d flights repeat the first ones, so the total time of p collisions is p/d times
that of d: only divisors d with m*d/p an integer are possible. For each such d the enclosure of
the state after d collisions is compared with that of the first state shifted by 2*pi*m*d/p: if
they are disjoint (in phase or in v), F^d(x) != x is proved. Otherwise the orbit is certified
again at period d from the proved state; its proved box lies in this call's Krawczyk box X,
whose only zero of G is x, so the two are the same orbit: the result is RELABELLED to period d
(``.period`` = d, its own winding, trace and residue; recursively minimal). Where neither
proof succeeds, NotCertified names the period that could not be excluded. ``.period`` is thus
always the proved minimal period.

Velocity shifts (accelerator modes, l != 0): see :mod:`verify.dynamics.accelerator`. The exact
map is not periodic in v; the shifted relations that repeat block after block are exactly the
period-1 modes with tau = 2*pi*m (v = pi*m, -2*eps*sin(phi) = pi*l), l > 0. A block with
p >= 2 and a shift is certified only as p repetitions of such a mode (relabelled to period 1);
a decelerating shift (l < 0) and every other shifted block raise NotCertified. For a mode the
flights of later blocks are proved to be first roots too, and the stability is that of every
block (module :mod:`verify.dynamics.accelerator`), ``limit_residue`` the v -> infinity one.

Cost. Interval widths grow along the orbit like the product of the entrywise absolute
Jacobians; the working precision is chosen from that growth measured on the point orbit (about
twice its number of digits, plus guards), so long or strongly unstable orbits cost precision.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import NamedTuple

import mpmath

from verify.dynamics.accelerator import continuation, limit_residue
from verify.dynamics.box_flight import Undecided
from verify.dynamics.errors import NotCertified
from verify.dynamics.numbers import Enclosure, contexts, exact_raw, hi, lo, mat_vec
from verify.dynamics.orbit_enclosure import enclose, enclose_point, point_orbit
from verify.numerics.inputs import check_dps
from verify.numerics.precision import DEFAULT_DPS, GUARD_DPS

MAX_NEWTON = 40
ELLIPTIC, HYPERBOLIC, UNDECIDED = "elliptic", "hyperbolic", "undecided"
_RADIUS_TRIES = (0, -6, 6)  # decades around the geometric mean of the two radius limits


@dataclass(frozen=True)
class CertifiedOrbit:
    """A periodic orbit proved to exist, unique in ``box``, of proved minimal period ``period``.

    ``box``: (phi, v) enclosures of the proved zero of G near the guess (phase in the guess's
    frame); ``points``: enclosures of the p states of the orbit, phases reduced near [0, 2*pi)
    (a phase within its width of 0 keeps an enclosure around 0); ``trace``, ``determinant``:
    enclosures for DF^p over ``box``; ``residue``: (2 - trace)/4; ``stability``: "elliptic",
    "hyperbolic" or "undecided" (see the module docstring); ``period``: the minimal period
    (it may be smaller than the period asked for: the module docstring's relabelling);
    ``limit_residue``: for an accelerator mode, eps*cos(phi) (the residue as v -> infinity),
    else None; ``dps_used``: working digits; ``radius``: the half-width r of the Krawczyk box;
    ``flights``: box flights certified (every collision of every enclosure computed, attempts
    and the mode's later blocks included).
    """

    box: tuple
    points: tuple
    trace: Enclosure
    determinant: Enclosure
    residue: Enclosure
    stability: str
    eps: mpmath.mpf
    period: int
    winding: int
    velocity_shift: int
    dps_used: int
    radius: float
    flights: int
    limit_residue: Enclosure | None = None


def _integer(name, value, minimum=None):
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{name} must be an integer, got {name}={value!r}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{name} must be >= {minimum}, got {name}={value}")
    return value


def classify(residue) -> str:
    """"elliptic" if 0 < R < 1 is proved, "hyperbolic" if R < 0 or R > 1 is, else "undecided"."""
    if lo(residue) > 0 and hi(residue) < 1:
        return ELLIPTIC
    if hi(residue) < 0 or lo(residue) > 1:
        return HYPERBOLIC
    return UNDECIDED


def periodic_orbit(phi, v, eps, period, *, dps: int = DEFAULT_DPS, winding=None, velocity_shift=0,
                   tolerance=1e-3, max_dps=None) -> CertifiedOrbit:
    """Prove that a periodic orbit of the exact map exists near the guess (phi, v).

    phi, v, eps: exact real values (floats are taken as exact binary numbers); period p >= 1;
    keyword-only: dps >= 15: the digits of the arithmetic (raised where the orbit needs more, up to
    ``max_dps``, default max(4*dps, 400)); winding m (default: the guess's own p flights /
    2*pi, rounded); velocity_shift l (an accelerator mode, v_p = v + pi*l: certified only for
    the exact map's period-1 modes with l > 0, module docstring); tolerance: the orbit must lie
    within this max-norm distance of the guess.

    Returns a :class:`CertifiedOrbit` whose ``period`` is the proved minimal period (an orbit of
    a shorter period is relabelled). Raises ValueError for bad input (including a guess that
    does not depart) and :class:`verify.NotCertified` when no orbit is proved near the guess:
    the point Newton iteration fails or leaves the tolerance, DF^p - I is singular (an orbit
    that is not isolated), a flight cannot be certified, Krawczyk's test fails at ``max_dps``,
    a shorter period can be neither excluded nor proved, or a velocity shift is not an
    accelerator mode of the exact map.
    """
    raws = [exact_raw(name, x) for name, x in (("phi", phi), ("v", v), ("eps", eps))]
    period = _integer("period", period, minimum=1)
    dps = check_dps(dps)
    max_dps = max(4 * dps, 400) if max_dps is None else check_dps(max_dps, "max_dps")
    if max_dps < dps:
        raise ValueError(f"max_dps must be >= dps, got max_dps={max_dps}, dps={dps}")
    shift = _integer("velocity_shift", velocity_shift)
    if winding is not None:
        winding = _integer("winding", winding, minimum=1)
    tol = mpmath.mp.make_mpf(exact_raw("tolerance", tolerance))
    if not tol > 0:
        raise ValueError(f"tolerance must be > 0, got tolerance={tolerance!r}")
    ctx = contexts(dps + GUARD_DPS)
    guess = tuple(ctx.mp.make_mpf(r) for r in raws[:2])
    eps_mp = ctx.mp.make_mpf(raws[2])
    w0 = guess[1] + eps_mp * ctx.mp.sin(guess[0])
    if not w0 > 0:
        raise ValueError(f"the guess does not depart: w0 = v + eps*sin(phi) = "
                         f"{mpmath.nstr(w0, 8)} <= 0 at phi={phi!r}, v={v!r}, eps={eps!r}")
    where = f"near phi={phi!r}, v={v!r} (eps={eps!r})"
    if shift < 0:
        raise NotCertified(f"velocity shift {shift} < 0 {where}: v falls by pi*{-shift} per "
                           f"block and reaches 0 after finitely many: not an accelerator mode "
                           f"(its time reverse, at phase -phi, is the mode with shift {-shift})")
    if shift != 0 and period > 1:
        return _repeated_mode(guess, eps_mp, period, winding, shift, dps, tol, max_dps, where)
    state = _Problem(eps_mp, period, winding, shift, guess, tol)
    found = state.solve(ctx, dps, max_dps, where)
    if shift != 0:
        return state.mode(found)
    return _minimal(state, found, dps, max_dps)


def _repeated_mode(guess, eps, period, winding, shift, dps, tol, max_dps, where):
    """A block of p >= 2 collisions with a shift: certified only as p blocks of a period-1 mode
    (module :mod:`verify.dynamics.accelerator`, Lemma 2), relabelled to period 1."""
    refusal = (f"a block of {period} collisions with velocity shift {shift} {where} is an orbit "
               f"of the exact map only as {period} blocks of a period-1 accelerator mode")
    if shift % period:
        raise NotCertified(f"{refusal}, whose shift would be {shift}/{period}: not an integer")
    step = shift // period
    one = None
    if winding is not None:
        # p blocks of the mode (phi, pi*m1) -> (phi, pi*(m1 + l1)) take 2*pi*(p*m1 +
        # l1*p*(p - 1)/2)
        twice = 2 * winding - step * period * (period - 1)
        if twice % (2 * period):
            raise NotCertified(f"{refusal}: winding {winding} is not that of {period} blocks "
                               f"of a mode")
        one = twice // (2 * period)
        if one < 1:
            raise NotCertified(f"{refusal}: winding {winding} is too small for one")
    try:
        return periodic_orbit(guess[0], guess[1], eps, 1, dps=dps, winding=one,
                              velocity_shift=step, tolerance=tol, max_dps=max_dps)
    except NotCertified as err:
        raise NotCertified(f"{refusal}, and none was certified: {err}") from None


def _divisors(n):
    return [d for d in range(1, n) if n % d == 0]


def _minimal(state, found, dps, max_dps):
    """The orbit with its proved minimal period (module docstring: relabelled or refused)."""
    orbit = found.orbit
    p, m = orbit.period, orbit.winding
    for d in _divisors(p):
        if (m * d) % p:
            continue  # a period-d orbit repeated would take 2*pi*m*d/p per d collisions
        turns = m * d // p
        if state.distinct(found, d, turns):
            continue
        centre = (orbit.box[0].lo + orbit.box[0].hi) / 2, (orbit.box[1].lo + orbit.box[1].hi) / 2
        try:
            shorter = periodic_orbit(centre[0], centre[1], state.eps, d, dps=dps, winding=turns,
                                     tolerance=state.tolerance, max_dps=max_dps)
        except NotCertified as err:
            raise NotCertified(
                f"the orbit of period {p} may have period {d}: its state after {d} collisions "
                f"is not proved distinct from the first, and no period-{d} orbit was "
                f"certified there ({err})") from None
        if not all(found.krawczyk_box[i].lo <= shorter.box[i].lo
                   and shorter.box[i].hi <= found.krawczyk_box[i].hi for i in range(2)):
            raise NotCertified(
                f"the orbit of period {p} may have period {d}: a period-{d} orbit was certified "
                f"next to it but not inside its Krawczyk box (not proved the same orbit)")
        return shorter
    return orbit


class _Found(NamedTuple):
    """A certified zero of G: the orbit's description, the Krawczyk box X (the zero is the only
    one in X) and the enclosures B_0..B_p of its states (phases unreduced), in ``ctx``."""

    orbit: CertifiedOrbit
    krawczyk_box: tuple
    boxes: list
    ctx: object


class _Problem:
    """The zero problem G(x) = 0 of one call, in whatever context is current."""

    def __init__(self, eps, period, winding, shift, guess, tolerance):
        self.eps, self.period, self.winding, self.shift = eps, period, winding, shift
        self.guess, self.tolerance = guess, tolerance
        self.flights = 0  # box flights certified (every enclosure of every attempt)

    def solve(self, ctx, dps, max_dps, where) -> _Found:
        """Newton in the point context, then Krawczyk's test at rising precision."""
        x = self.newton(ctx)
        needed = self.digits_needed(ctx, x)
        if needed > max_dps:
            raise NotCertified(f"the orbit needs about {needed} digits (interval growth along "
                               f"{self.period} collisions), more than max_dps={max_dps}")
        work = max(dps + GUARD_DPS, needed)
        while True:
            if work > ctx.dps:
                ctx = contexts(work)
                x = self.newton(ctx, start=x)
            found = self.certify(ctx, x)
            if found is not None:
                return found
            if work >= max_dps:
                raise NotCertified(f"Krawczyk's test failed up to {work} digits for the orbit "
                                   f"of period {self.period} {where}")
            work = min(max_dps, work + work // 2)

    def distinct(self, found, d, turns) -> bool:
        """Proved: the state after d collisions differs from the first (mod 2*pi), i.e. its
        enclosure misses that of the first shifted by 2*pi*turns, in phase or in v."""
        iv = found.ctx.iv
        first, later = found.boxes[0], found.boxes[d]
        dphi = later[0] - first[0] - 2 * iv.pi * turns
        dv = later[1] - first[1]
        return not (lo(dphi) <= 0 <= hi(dphi)) or not (lo(dv) <= 0 <= hi(dv))

    def mode(self, found) -> CertifiedOrbit:
        """A period-1 accelerator mode: its later blocks proved (``accelerator.continuation``)
        and its stability over all blocks (module :mod:`verify.dynamics.accelerator`)."""
        orbit, ctx = found.orbit, found.ctx
        phase = ctx.iv.mpf([orbit.box[0].lo, orbit.box[0].hi])
        flights = continuation(ctx, self.eps, phase, orbit.winding, self.shift)
        first = (2 - ctx.iv.mpf([orbit.trace.lo, orbit.trace.hi])
                 / ctx.iv.sqrt(ctx.iv.mpf([orbit.determinant.lo, orbit.determinant.hi]))) / 4
        limit = limit_residue(ctx, self.eps, phase)
        if not orbit.determinant.lo > 0:
            stability = UNDECIDED
        elif classify(first) == ELLIPTIC:
            stability = ELLIPTIC
        elif classify(ctx.iv.mpf([limit.lo, limit.hi])) == HYPERBOLIC:
            stability = HYPERBOLIC
        else:
            stability = UNDECIDED
        return replace(orbit, stability=stability, limit_residue=limit,
                       flights=orbit.flights + flights)

    def _enclose_point(self, ctx, x, flights):
        self.flights += self.period
        return enclose_point(ctx, x[0], x[1], self.eps, flights)

    def _enclose(self, ctx, box, x, flights, points):
        self.flights += self.period
        return enclose(ctx, box, x, self.eps, flights, points)

    def _orbit(self, ctx, x):
        try:
            return point_orbit(ctx, x[0], x[1], ctx.mp.mpf(self.eps), self.period)
        except Undecided as und:
            raise NotCertified(f"the orbit from phi={mpmath.nstr(x[0], 17)}, "
                               f"v={mpmath.nstr(x[1], 17)} has a flight that cannot be "
                               f"followed: {und.what}") from None

    def _residual(self, ctx, x, flights):
        mp = ctx.mp
        total = sum((f.tau for f in flights), mp.zero)
        if self.winding is None:
            self.winding = max(1, int(mp.nint(total / (2 * mp.pi))))
        return (total - 2 * mp.pi * self.winding,
                flights[-1].v1 - x[1] - mp.pi * self.shift)

    @staticmethod
    def _monodromy(flights):
        m = (1, 0, 0, 1)
        for f in flights:
            j = f.jacobian
            m = (j[0] * m[0] + j[1] * m[2], j[0] * m[1] + j[1] * m[3],
                 j[2] * m[0] + j[3] * m[2], j[2] * m[1] + j[3] * m[3])
        return m

    def _inverse_g_prime(self, ctx, flights):
        m = self._monodromy(flights)
        a = (m[0] - 1, m[1], m[2], m[3] - 1)
        det = a[0] * a[3] - a[1] * a[2]
        scale = max(abs(e) for e in a)
        if det == 0 or abs(det) <= scale * scale * ctx.mp.mpf(2) ** (-ctx.mp.prec // 2):
            raise NotCertified("DF^p - I is singular at the orbit: it is not an isolated "
                               "periodic orbit (e.g. eps = 0, where every orbit is periodic)")
        return (a[3] / det, -a[1] / det, -a[2] / det, a[0] / det)

    def newton(self, ctx, start=None):
        """Newton's method on G in the point context from the guess (or ``start``)."""
        mp = ctx.mp
        x = self.guess if start is None else (mp.mpf(start[0]), mp.mpf(start[1]))
        size = mp.inf
        for _ in range(MAX_NEWTON):
            flights = self._orbit(ctx, x)
            g = self._residual(ctx, x, flights)
            c = self._inverse_g_prime(ctx, flights)
            step = mat_vec(c, g)
            x = (x[0] - step[0], x[1] - step[1])
            new = max(abs(step[0]), abs(step[1]))
            scale = 1 + abs(x[0]) + abs(x[1])
            if new <= mp.mpf(2) ** (-mp.prec + 12) * scale:
                break
            if new < mp.mpf(2) ** (-mp.prec // 2) * scale and new > size / 2:
                break  # at the rounding noise of G (a long orbit amplifies it): converged
            if new > size and new > self.tolerance:
                raise NotCertified("Newton's method from the guess diverges: no periodic orbit "
                                   "of this type near it")
            size = new
        else:
            raise NotCertified(f"Newton's method from the guess did not converge in "
                               f"{MAX_NEWTON} iterations")
        distance = max(abs(x[0] - self.guess[0]), abs(x[1] - self.guess[1]))
        if distance > self.tolerance:
            raise NotCertified(f"Newton's method from the guess reaches an orbit at distance "
                               f"{mpmath.nstr(distance, 3)} > tolerance "
                               f"{mpmath.nstr(self.tolerance, 3)}: no orbit of this type within "
                               f"the tolerance of the guess was found")
        return x

    def digits_needed(self, ctx, x) -> int:
        """Working digits for the proof: about twice the decades of interval growth (the
        product of the entrywise absolute Jacobians, times |C| and the largest time), plus
        guards; see the module docstring."""
        mp = ctx.mp
        flights = self._orbit(ctx, x)
        c = self._inverse_g_prime(ctx, flights)
        growth = mp.one
        a = (mp.one, mp.zero, mp.zero, mp.one)
        for f in flights:
            j = [abs(e) for e in f.jacobian]
            a = (j[0] * a[0] + j[1] * a[2], j[0] * a[1] + j[1] * a[3],
                 j[2] * a[0] + j[3] * a[2], j[2] * a[1] + j[3] * a[3])
            growth = max(growth, max(a))
        scale = growth * (1 + max(abs(e) for e in c)) * (1 + max(f.tau for f in flights))
        return int(2 * float(mp.log10(scale))) + 3 * GUARD_DPS

    def certify(self, ctx, x):
        """Krawczyk's test at this precision; the CertifiedOrbit, or None if it failed."""
        mp, iv = ctx.mp, ctx.iv
        try:
            flights = self._orbit(ctx, x)
            c = self._inverse_g_prime(ctx, flights)
            points = self._enclose_point(ctx, x, flights)
        except (Undecided, NotCertified):
            return None
        g = (points[-1][0] - iv.mpf(x[0]) - 2 * iv.pi * self.winding,
             points[-1][1] - iv.mpf(x[1]) - iv.pi * self.shift)
        c_iv = tuple(iv.mpf(e) for e in c)
        correction = mat_vec(c_iv, g)
        newton_size = max(mp.make_mpf(abs(e)._mpi_[1]) for e in correction)
        tiny = mp.mpf(2) ** (-mp.prec + 8) * (1 + abs(x[0]) + abs(x[1]))
        newton_size = max(newton_size, tiny)
        # the radius must exceed the Newton correction and stay far below 1/(|C| * growth):
        # start at sqrt(newton_size * 10**-GUARD_DPS) and try a few decades around it
        base = mp.sqrt(newton_size) * mp.mpf(10) ** (-GUARD_DPS // 2)
        for decades in _RADIUS_TRIES:
            r = base * mp.mpf(10) ** decades
            if r <= 4 * newton_size:
                continue
            box = (iv.mpf([x[0] - r, x[0] + r]), iv.mpf([x[1] - r, x[1] + r]))
            try:
                image = self._enclose(ctx, box, x, flights, points)
            except Undecided:
                continue
            kraw = _krawczyk(iv, x, box, c_iv, g, image.jacobian)
            if all(_inside(ctx, kraw[i], box[i]) for i in range(2)):
                return self._result(ctx, kraw, flights, r, box)
        return None

    def _result(self, ctx, box, flights, r, krawczyk_box) -> _Found:
        """Tighten to the Krawczyk image (which contains the orbit) and describe the orbit."""
        mp = ctx.mp
        centre = (mp.make_mpf(box[0].mid._mpi_[0]), mp.make_mpf(box[1].mid._mpi_[0]))
        try:
            flights = self._orbit(ctx, centre)
            points = self._enclose_point(ctx, centre, flights)
            image = self._enclose(ctx, box, centre, flights, points)
        except (Undecided, NotCertified) as err:
            raise NotCertified(f"the proved box could not be propagated again: {err}") from None
        j = image.jacobian
        trace = j[0] + j[3]
        det = j[0] * j[3] - j[1] * j[2]
        residue = (2 - trace) / 4
        states = tuple((_reduced(ctx, b[0]), Enclosure.of(b[1]))
                       for b in image.boxes[:-1])
        orbit = CertifiedOrbit(
            box=(Enclosure.of(box[0]), Enclosure.of(box[1])),
            points=states,
            trace=Enclosure.of(trace),
            determinant=Enclosure.of(det),
            residue=Enclosure.of(residue),
            stability=classify(residue),
            eps=mpmath.mp.make_mpf(self.eps._mpf_),
            period=self.period,
            winding=self.winding,
            velocity_shift=self.shift,
            dps_used=ctx.dps,
            radius=float(r),
            flights=self.flights,
        )
        return _Found(orbit, tuple(Enclosure.of(b) for b in krawczyk_box), image.boxes, ctx)


def _krawczyk(iv, x, box, c, g, jac):
    """K(X) = x - C G(x) + (I - C (J - I)) (X - x), componentwise intervals."""
    a = (jac[0] - 1, jac[1], jac[2], jac[3] - 1)
    ca = (c[0] * a[0] + c[1] * a[2], c[0] * a[1] + c[1] * a[3],
          c[2] * a[0] + c[3] * a[2], c[2] * a[1] + c[3] * a[3])
    contraction = (1 - ca[0], -ca[1], -ca[2], 1 - ca[3])
    offset = (box[0] - iv.mpf(x[0]), box[1] - iv.mpf(x[1]))
    cg = mat_vec(c, g)
    spread = mat_vec(contraction, offset)
    return (iv.mpf(x[0]) - cg[0] + spread[0], iv.mpf(x[1]) - cg[1] + spread[1])


def _inside(ctx, inner, outer) -> bool:
    """inner lies in the interior of outer."""
    return lo(inner) > lo(outer) and hi(inner) < hi(outer)


def _reduced(ctx, phase) -> Enclosure:
    """The phase enclosure shifted by an exact multiple of 2*pi so that its midpoint lies in
    [-w, 2*pi - w), w its width (an enclosure around 0 stays around 0)."""
    iv, mp = ctx.iv, ctx.mp
    mid = mp.make_mpf(phase.mid._mpi_[0])
    width = mp.make_mpf(phase.delta._mpi_[1])
    turns = int(mp.floor((mid + width) / (2 * mp.pi)))
    return Enclosure.of(phase - 2 * iv.pi * turns)

