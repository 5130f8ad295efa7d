"""Accelerator modes of the exact map: which velocity-shifted relations are orbits, and proofs.

A block of p collisions with velocity shift l != 0 is a relation

    F^p(phi, v) = (phi + 2*pi*w, v + pi*l)                                   (phase unreduced)

at one state. It describes an orbit (an accelerator mode: v grows by pi*l every p collisions
for ever) only if the next block, from (phi, v + pi*l), is the same block shifted by pi*l in v,
and so on. The Holmes map in its standard-map form commutes with v -> v + pi, so there every
block repeats; the exact map does not, and a block is in general a one-off (the zero of two
equations at one state, with nothing to make them hold again one block later).

Lemma 1 (one flight). Let a flight from (phi, v) have first root tau and let k != 0 be an
integer. The flight from (phi, v + pi*k) ends at the same phase mod 2*pi with velocity
v1 + pi*k if and only if (eps != 0)

    tau = 2*v   and   cos(phi + tau) = cos(phi)                                         (*)

(and the root tau + 2*pi*k of the shifted gap is its first). Proof: equal landing phases give
equal plate velocities, so v1' - v1 = tau' - tau - pi*k, which is pi*k iff tau' = tau + 2*pi*k.
With d(tau) = 0, the shifted gap at tau' is eps*(cos(phi) - cos(phi + tau)) +
(tau + 2*pi*k)*(v - tau/2) = 2*pi*k*(v - tau/2), zero iff tau = 2*v; then d(tau) = 0 leaves
eps*(cos(phi) - cos(phi + tau)) = 0.

Lemma 2 (chains). (*) holds in two ways: (A) tau = 2*pi*n, so v = pi*n and the particle lands at
its own phase z with v1 = v - 2*eps*sin(z); or (B) phi + tau = -phi (mod 2*pi), v = -phi
(mod pi), landing at -z with v1 = v + 2*eps*sin(z). A block of such flights visits the phases
+y and -y only; write kappa_z = 2*eps*sin(z) (sin(y) != 0, else nothing changes v). After an
A flight at z, v = -kappa_z (mod pi): the next is A again iff kappa_z = 0 (mod pi), B iff
kappa_z = z (mod pi) (both would need z = 0 mod pi). In the second case the flights are forced
to run A(z), B, A(-z), B, ..., whose kicks cancel; without A flights the B flights alternate
+y, -y and their kicks cancel too. So a block of flights (*) with a net shift is n repetitions of
one A flight: the period-1 mode

    (phi*, pi*m) -> (phi*, pi*(m + l)),   -2*eps*sin(phi*) = pi*l,   tau = 2*pi*m,

which needs |eps| >= pi*|l|/2 (K = 4*eps >= 2*pi). Hence the shifted relations that repeat, block
after block shifted by pi*l, are exactly the period-1 modes, and only while their flights stay
first roots; every other shifted block is refused (its next block is not its shifted copy).

Lemma 3 (the mode goes on). Every period-1 zero of G is such a mode: tau = 2*pi*m exactly, so
d(tau) = 0 gives v = pi*m and v1 - v = pi*l gives the sine. From (phi*, V), V = pi*M, the gap
g(t) = eps*(cos(phi*) - cos(phi* + t)) + t*(V - t/2) has the root 2*V, and since
|eps*(cos(phi*) - cos(phi* + t))| <= |eps|*min(t, 2*V - t) (Lipschitz from both ends, 2*V a
multiple of 2*pi) and t*(V - t/2) >= min(t, 2*V - t)*V/2,

    g(t) >= min(t, 2*V - t)*(V/2 - |eps|) > 0   on (0, 2*V)   when V > 2*|eps|,

so 2*V is then the first root (and w0 = V - pi*l/2 > 0). For l > 0 the velocities pi*(m + k*l)
grow: those <= 2*|eps| (finitely many) are certified flight by flight (``continuation``); the
rest hold by the bound. For l < 0 they fall to 0 after finitely many blocks: the relation is not
invariant forward in time and is refused (its time reverse, at phase -phi*, is the mode with
shift -l).

Stability of a mode. The mode's Jacobians differ from block to block: at velocity V
(a = 0, w0 = V - pi*l/2, w1 = V + pi*l/2)

    DF_V = [[1, b], [-c, -1 + b - c*b]],   b = 2*V/w1,   c = 2*eps*cos(phi*),   det = b - 1,

so tr/sqrt(det) = (1 - c)*f(b), f(b) = b/sqrt(b - 1) >= 2, decreasing on (1, 2); for l > 0, b
rises to 2 as V grows, and the limit V -> infinity is the standard map's accelerator mode,
residue R_inf = c/2 = eps*cos(phi*). The normalised residue (2 - tr/sqrt(det))/4 of every block
lies between that of the first block and R_inf, so: "elliptic" if the first block's is proved in
(0, 1) (then every block's is), "hyperbolic" if R_inf is proved outside [0, 1] (then every
block's is), "undecided" otherwise (including blocks of both kinds).
"""

from __future__ import annotations

from verify.dynamics.box_flight import Undecided, box_flight
from verify.dynamics.errors import NotCertified
from verify.dynamics.numbers import Enclosure, hi, lo

MAX_SLOW_BLOCKS = 1_000  # flights certified one by one below V = 2*|eps| (beyond: refused)
_RETRIES, _WIDEN = 4, 16  # brackets around 2*V tried, each this much wider


def continuation(ctx, eps, phase, m, shift) -> int:
    """Prove that the period-1 mode (phi*, pi*m), phi* in ``phase``, shift l > 0, goes on for
    ever (Lemma 3): every velocity pi*(m + k*l) <= 2*|eps|, k >= 1, has the first root
    2*pi*(m + k*l), certified by :func:`verify.dynamics.box_flight.box_flight` on a bracket
    around it. Returns the number of flights certified; raises NotCertified."""
    iv = ctx.iv
    eps_iv = iv.mpf(eps)
    bound = 2 * abs(eps_iv)
    done = 0
    level = m + shift
    while not lo(iv.pi * level) > hi(bound):
        if done == MAX_SLOW_BLOCKS:
            raise NotCertified(f"the accelerator mode has more than {MAX_SLOW_BLOCKS} blocks "
                               f"below v = 2*|eps| to certify one by one")
        speed = iv.pi * level
        tau = 2 * speed
        # |d'| >= V there: a bracket a few times the gap's spread over the phase box is enough
        mp = ctx.mp  # the ends are computed at the working precision (lo/hi are exact)
        ends = mp.make_mpf(tau._mpi_[0]), mp.make_mpf(tau._mpi_[1])
        width = mp.make_mpf(phase.delta._mpi_[1]) * 4 * (1 + abs(eps)) + mp.mpf(2) ** (
            -mp.prec // 2) * (1 + level)
        for attempt in range(_RETRIES + 1):
            try:
                box_flight(ctx, phase, speed, eps, ends[0] - width, ends[1] + width)
                break
            except Undecided as und:
                if attempt == _RETRIES:
                    raise NotCertified(f"the accelerator mode is not proved to go on: the "
                                       f"flight from v = pi*{level} is not proved to end at "
                                       f"2*pi*{level} ({und.what})") from None
                width *= _WIDEN
        done += 1
        level += shift
    return done


def limit_residue(ctx, eps, phase) -> Enclosure:
    """R_inf = eps*cos(phi*), the residue of the mode's linearisation as v -> infinity."""
    iv = ctx.iv
    return Enclosure.of(iv.mpf(eps) * iv.cos(phase))
