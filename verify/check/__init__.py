"""Check any bouncer integrator against the certified reference: ``check_integrator``.

``check_integrator(flight_time, step=None)`` runs hypothesis property suites against a user's
callables ``flight_time(phi, v, eps) -> float`` and ``step(phi, v, eps) -> (phi1, v1, tau)``
and returns a :class:`CheckReport`. The properties (``u = 2**-53``, ``kappa``
= :func:`verify.condition_number`, ``k`` the allowed multiple, 16 by default as for ``fastpath``):

``no_overstep``
    tau never lies beyond the certified first root by more than ``k*kappa*u*tau``: random
    departures with eps in ``[0, 10]``, and near-grazing departures for eps > 1 (close root
    pairs, which a fixed-step scan jumps over, and near misses).
``accuracy``
    ``|tau - tau_ref| / tau_ref <= k*kappa*u`` on random departures, the hard cases (tiny
    departure speed, huge v, unreduced phases, tiny and huge eps) and near the fixed points; the
    worst observed ``k`` is reported.
``fixed_points``
    ``(0, pi*m) -> tau = 2*pi*m``; with ``step``: the state maps to itself, and the Jacobian
    of ``step`` by central differences is ``[[1, 2], [-2*eps, 1 - 4*eps]]`` within a tolerance
    derived from the difference step (see :func:`_jacobian_tolerance`).
``energy`` (needs ``step``)
    ``E = v**2/2 + eps*cos(phi)``: ``E1 - E0 = 2*u*(u - v_in)`` with the plate velocity (here
    ``u``) ``-eps*sin(phi1)`` and ``v_in = v - tau`` (conservation in flight plus the impact).
``holmes_limit``
    ``|tau - 2*v| <= 4*eps/tau`` for large v (exact for every root of the gap).
``reversibility``
    from ``(-(phi + tau), tau - v)`` the flight time is again ``tau`` (the user's own tau, so
    this needs no reference: an error ``e`` in tau shows up as ``~e*|d'(tau)|/w0``). Departure
    speeds ``w0 >= 1e-3`` only: the reversed flight arrives at speed ``w0``, and a slower
    arrival at eps > 1 is a near-graze that a float64 method may rightly refuse to decide.

A callable that raises, returns NaN/inf, a non-positive time or the wrong shape fails the
property that called it; the checker does not crash. The callables run in a worker process
(:mod:`.worker`), so a call that hangs past ``call_timeout`` or kills the process (exit,
segfault) is such a failure too; the whole check runs under ``budget`` seconds, and a property
the budget cut short is INCONCLUSIVE with the count reached. Inputs where ``verify`` itself cannot
decide the first root (:class:`verify.UndecidableCollision`) are discarded; a property left with
no checked input is INCONCLUSIVE too. A check passes only when every property of its suite ran
and held. A ``MODULE:FUNCTION`` spec is imported in the worker process only: a module that
raises, calls ``sys.exit()`` or crashes while importing is a ``ValueError`` (nothing of it was
checked), and never ends the caller's process.

Each property draws its inputs in parts (e.g. random / close root pairs / near misses), each
part its own hypothesis search with its share of ``max_examples``, so every kind of input is
reached. A first pass counts the failing inputs; if there is one, a second pass stops at the
first failure and hypothesis shrinks it to the smallest failing input it can find: that input
is what the report shows.

Never imports ``fastpath`` (the independence rule). Hypothesis is imported only when a check
runs, so ``import verify`` does not need it.

The package, one job per module: ``loading`` (the user's callable from ``MODULE:FUNCTION``),
``calling`` (calling it and vetting its output), ``tolerance`` (the tolerance model),
``properties`` (the property bodies), ``driver`` (hypothesis: parts, survey, shrink),
``report`` (the results), ``suites`` (names and sizes), ``worker`` (the worker process),
``budget`` (the overall deadline), ``api`` (``check_integrator``).
"""

from .api import assert_integrator, check_integrator
from .loading import load_callable
from .report import CheckReport, Failure, PropertyResult
from .suites import PROPERTIES, SUITES

__all__ = [
    "PROPERTIES",
    "SUITES",
    "CheckReport",
    "Failure",
    "PropertyResult",
    "assert_integrator",
    "check_integrator",
    "load_callable",
]
