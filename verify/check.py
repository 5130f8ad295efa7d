"""Check any bouncer integrator against the certified reference: ``check_integrator``.

``check_integrator(flight_time, step=None)`` runs hypothesis property suites against a user's
callables ``flight_time(phi, v, eps) -> float`` and ``step(phi, v, eps) -> (phi1, v1, tau)``
and returns a :class:`CheckReport`. The properties (DESIGN.md Section 2; ``u = 2**-53``, ``kappa``
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
property that called it; the checker does not crash. Inputs where ``verify`` itself cannot
decide the first root (:class:`verify.UndecidableCollision`) are discarded.

Each property draws its inputs in parts (e.g. random / close root pairs / near misses), each
part its own hypothesis search with its share of ``max_examples``, so every kind of input is
reached. A first pass counts the failing inputs; if there is one, a second pass stops at the
first failure and hypothesis shrinks it to the smallest failing input it can find: that input
is what the report shows.

Never imports ``fastpath`` (the independence rule). Hypothesis is imported only when a check
runs, so ``import verify`` does not need it.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import math
import numbers
import os
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

from mpmath import mp

from .certify import certify_flight
from .conditioning import condition_number
from .errors import UndecidableCollision
from .gap import mp_gap, mp_gap_prime

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

PROPERTIES = (
    "no_overstep", "accuracy", "fixed_points", "energy", "holmes_limit", "reversibility",
)
SUITES = ("all", "fast", *PROPERTIES)
NEEDS_STEP = ("energy",)
DEFAULT_EXAMPLES = {"all": 100, "fast": 20}  # per property; a single property runs as "all"

U = 2.0**-53  # unit roundoff of float64
_REF_DPS = 30  # digits of the certified reference (float64 needs 17)
_WORK_DPS = 60  # digits of the checker's own arithmetic on exact float inputs
TWO_PI = 2.0 * math.pi


# --------------------------------------------------------------------------- results


@dataclass(frozen=True)
class Failure:
    """One falsified property: its name, the input, what was expected and what came back.

    ``expected`` and ``obtained`` are floats (a flight time), tuples (a step's output or a
    Jacobian) or a string (an exception the callable raised). ``call`` names the callable that
    produced ``obtained`` (``"flight_time"`` or ``"step"``); ``(phi, v, eps)`` is its input
    (the input the property started from, for Jacobians and reversibility).
    """

    property: str
    phi: float
    v: float
    eps: float
    expected: object
    obtained: object
    message: str
    call: str = "flight_time"

    @property
    def input(self) -> tuple[float, float, float]:
        return (self.phi, self.v, self.eps)

    def __str__(self) -> str:
        return (
            f"{self.property}: {self.call}(phi={self.phi!r}, v={self.v!r}, eps={self.eps!r})\n"
            f"    expected {_show(self.expected)}\n"
            f"    obtained {_show(self.obtained)}\n"
            f"    {self.message}"
        )


@dataclass(frozen=True)
class PropertyResult:
    """Outcome of one property: ``status`` is "PASS", "FAIL" or "SKIP"."""

    name: str
    status: str
    inputs: int
    note: str = ""
    failure: Failure | None = None
    seconds: float = 0.0
    failed: int = 0


@dataclass(frozen=True)
class CheckReport:
    """What :func:`check_integrator` found. ``ok``: no property failed (skips are not failures)."""

    target: str
    step_target: str | None
    suite: str
    k: float
    seed: int | None
    max_examples: int
    results: tuple[PropertyResult, ...]
    worst_accuracy_k: float | None
    worst_accuracy_input: tuple[float, float, float] | None = None
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        return all(r.status != "FAIL" for r in self.results)

    @property
    def failures(self) -> list[Failure]:
        return [r.failure for r in self.results if r.failure is not None]

    def result(self, name: str) -> PropertyResult:
        for r in self.results:
            if r.name == name:
                return r
        raise KeyError(f"property {name!r} was not run (suite {self.suite!r})")

    def __str__(self) -> str:
        step = self.step_target or "none"
        lines = [
            f"check of flight_time={self.target}, step={step}",
            f"suite {self.suite!r}, k = {self.k:g}, seed {self.seed}, up to {self.max_examples}"
            f" inputs per property, {self.seconds:.1f} s",
        ]
        width = max(len(p) for p in PROPERTIES)
        for r in self.results:
            note = f"  ({r.note})" if r.note else ""
            if r.status == "FAIL":
                what = f"{r.failed} of {r.inputs} inputs fail"
            elif r.status == "SKIP":
                what = "skipped"
            else:
                what = f"{r.inputs} inputs"
            lines.append(f"  {r.status}  {r.name:<{width}}  {what}{note}")
        fails = self.failures
        if fails:
            lines.append(
                f"{len(fails)} of {len(self.results)} properties failed; smallest failing "
                "input found (hypothesis-shrunk):"
            )
            for f in fails:
                lines.extend("  " + line for line in str(f).splitlines())
        else:
            lines.append("all properties hold")
        return "\n".join(lines)


# --------------------------------------------------------------------------- loading


def load_callable(spec: str, *, search_cwd: bool = True) -> Callable:
    """``"MODULE:FUNCTION"`` -> the callable it names.

    MODULE is a dotted module name (``mypkg.solvers``) or a path to a ``.py`` file
    (``solvers/mine.py``); FUNCTION may be dotted (``Solver.flight_time``). With ``search_cwd``
    the current directory is put on ``sys.path`` first, so users can name their own files.
    Raises ``ValueError`` with a one-line message when the spec is malformed, the module
    cannot be imported, the attribute is missing or is not callable.
    """
    if not isinstance(spec, str):
        raise ValueError(f"expected MODULE:FUNCTION, got {spec!r}")
    module_name, sep, attr = spec.rpartition(":")
    if not sep or not module_name.strip() or not attr.strip():
        raise ValueError(f"expected MODULE:FUNCTION (e.g. mymodule:flight_time), got {spec!r}")
    module_name, attr = module_name.strip(), attr.strip()
    if search_cwd:
        cwd = os.getcwd()
        if cwd not in sys.path and "" not in sys.path:
            sys.path.insert(0, cwd)
    module = _import(module_name)
    obj = module
    for part in attr.split("."):
        try:
            obj = getattr(obj, part)
        except AttributeError:
            raise ValueError(f"module {module_name!r} has no attribute {attr!r}") from None
    if not callable(obj):
        raise ValueError(f"{spec!r} is not callable (it is a {type(obj).__name__})")
    return obj


def _import(module_name: str):
    is_path = module_name.endswith(".py") or "/" in module_name or os.sep in module_name
    try:
        if not is_path:
            return importlib.import_module(module_name)
        path = os.path.abspath(module_name)
        if not os.path.isfile(path):
            raise ValueError(f"cannot import module {module_name!r}: no such file")
        name = "_bouncer_user_" + os.path.splitext(os.path.basename(path))[0]
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:
            raise ValueError(f"cannot import module {module_name!r}: not a Python file")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            sys.modules.pop(name, None)
            raise
        return module
    except ValueError:
        raise
    except ModuleNotFoundError as err:
        raise ValueError(f"cannot import module {module_name!r}: {err}") from None
    except Exception as err:  # the user's module raised while importing
        msg = str(err).splitlines()[0] if str(err) else ""
        raise ValueError(
            f"importing module {module_name!r} failed: {type(err).__name__}: {msg}"
        ) from None


# --------------------------------------------------------------------------- calling


class _Bad(Exception):
    """The user's callable misbehaved; ``text`` describes what came back."""

    def __init__(self, text: str, message: str) -> None:
        super().__init__(message)
        self.text = text
        self.message = message


def _one_line(err: BaseException) -> str:
    text = str(err).splitlines()[0] if str(err) else ""
    return f"{type(err).__name__}: {text}" if text else type(err).__name__


def _as_float(x, what: str) -> float:
    try:
        if hasattr(x, "shape") and getattr(x, "shape", ()) not in ((), (1,)):
            raise TypeError(f"shape {x.shape}")
        val = float(x[0] if getattr(x, "shape", ()) == (1,) else x)
    except (TypeError, ValueError, IndexError) as err:
        raise _Bad(repr(x), f"{what} is not a real number ({_one_line(err)})") from None
    if not math.isfinite(val):
        raise _Bad(repr(val), f"{what} is not finite")
    return val


def _call_flight(fn, phi, v, eps) -> float:
    try:
        out = fn(phi, v, eps)
    except Exception as err:  # the user's code: any exception is a failure of the property
        raise _Bad(f"exception {_one_line(err)}", "flight_time raised on a valid departure") \
            from None
    tau = _as_float(out, "the flight time")
    if not tau > 0:
        raise _Bad(repr(tau), "the flight time is not positive")
    return tau


def _call_step(fn, phi, v, eps) -> tuple[float, float, float]:
    try:
        out = fn(phi, v, eps)
    except Exception as err:
        raise _Bad(f"exception {_one_line(err)}", "step raised on a valid departure") from None
    try:
        phi1, v1, tau = out
    except (TypeError, ValueError):
        raise _Bad(repr(out), "step must return (phi1, v1, tau)") from None
    phi1 = _as_float(phi1, "phi1")
    v1 = _as_float(v1, "v1")
    tau = _as_float(tau, "tau")
    if not tau > 0:
        raise _Bad(repr((phi1, v1, tau)), "the flight time tau of step is not positive")
    return phi1, v1, tau


def _show(x) -> str:
    if isinstance(x, float):
        return repr(x)
    if isinstance(x, tuple):
        return "(" + ", ".join(_show(y) for y in x) + ")"
    return str(x)


def _name(fn) -> str:
    mod = getattr(fn, "__module__", None)
    qual = getattr(fn, "__qualname__", None) or getattr(fn, "__name__", None) or repr(fn)
    return f"{mod}:{qual}" if mod else str(qual)


# --------------------------------------------------------------------------- tolerances


def _mpf(x):
    return mp.mpf(x)


def _num(phi, v, eps, tau):
    """Numerator of kappa: the rounding scale of d divided by tau (verify.condition_number)."""
    return abs(_mpf(v)) + tau + abs(_mpf(eps)) * (1 + abs(_mpf(phi)) + tau)


def _phase_rounding(k, phi, tau) -> float:
    """Rounding of a float phase (phi + tau) mod 2*pi beside the tau error: k/2 ulps of
    |phi| + tau + 2*pi (a sum and up to two reductions, each a few ulps; 8 ulps at k = 16)."""
    return k / 2 * math.ulp(abs(float(phi)) + abs(float(tau)) + TWO_PI)


def _map_tolerances(k, phi, v, eps, tau, kappa):
    """(tau, phi1, v1) tolerances of a float64 step (the fastpath suite's derivation, with k):
    phi1 carries the tau error and the phase rounding; v1 = tau - v - 2*eps*sin(phi1) carries
    the tau error with weight 1 + 2|eps|, the phase rounding with weight 2|eps| and k/4 ulps of
    its terms."""
    tau_tol = float(k * kappa * U * tau) if mp.isfinite(kappa) else math.inf
    phase = _phase_rounding(k, phi, tau)
    e2 = 2.0 * abs(float(eps))
    phi1_tol = tau_tol + phase
    v1_tol = (1.0 + e2) * tau_tol + e2 * phase + k / 4 * math.ulp(
        abs(float(tau)) + abs(float(v)) + e2
    )
    return tau_tol, phi1_tol, v1_tol


def _phase_distance(a, b):
    """|a - b| mod 2*pi folded into [0, pi] (mpf)."""
    two_pi = 2 * mp.pi
    d = (_mpf(a) - _mpf(b)) % two_pi
    return min(d, two_pi - d)


def _jacobian_tolerance(eps: float, step_tol: float) -> tuple[float, float]:
    """(h, tolerance) of the central-difference Jacobian at a fixed point.

    Central differences make an error ``<= step_tol/h`` from the step's own errors (at most
    ``step_tol`` at each of the two points) plus the truncation ``C*h**2`` with ``C`` a bound on
    a third derivative of the map over 6: ``C = (1 + |eps|)**3``, since each derivative of
    ``-2*eps*sin(phi + tau)`` brings a factor of order ``1 + |eps|`` (checked against verify's
    40-digit map for m = 1..10, eps = 0.1..10: the ratio is at most 0.55). ``h`` minimises
    ``step_tol/h + C*h**2``; the tolerance is twice that sum.
    """
    c = (1.0 + abs(eps)) ** 3
    h = (step_tol / (2.0 * c)) ** (1.0 / 3.0)
    return h, 2.0 * (step_tol / h + c * h * h)


# --------------------------------------------------------------------------- properties


_DISCARD = object()


class _Checker:
    """The property bodies; each takes one drawn case and returns None, a Failure or _DISCARD."""

    def __init__(self, flight_time, step, k):
        self.fn = flight_time
        self.step = step
        self.k = float(k)
        self.worst_k: float | None = None
        self.worst_input: tuple[float, float, float] | None = None
        self.reference = functools.lru_cache(maxsize=4096)(self._reference)

    def _reference(self, phi, v, eps):
        """(tau_ref, kappa) at _REF_DPS digits, or None where verify cannot decide."""
        try:
            cert = certify_flight(phi, v, eps, _REF_DPS)
        except UndecidableCollision:
            return None
        with mp.workdps(_WORK_DPS):
            kappa = condition_number(phi, v, eps, cert.tau)
        if not mp.isfinite(kappa):
            return None
        return cert.tau, kappa

    def _fail(self, prop, case, expected, obtained, message, call="flight_time"):
        phi, v, eps = case[:3]
        return Failure(prop, phi, v, eps, expected, obtained, message, call)

    def _against_reference(self, prop, case):
        """(tau_ref, kappa, tau) for the user's flight time at ``case``; _DISCARD where verify
        cannot decide, a Failure where the callable raises or returns a non-time."""
        phi, v, eps = case
        ref = self.reference(phi, v, eps)
        if ref is None:
            return _DISCARD
        tau_ref, kappa = ref
        try:
            tau = _call_flight(self.fn, phi, v, eps)
        except _Bad as bad:
            return self._fail(prop, case, float(tau_ref), bad.text, bad.message)
        return tau_ref, kappa, tau

    # -- no_overstep
    def no_overstep(self, case):
        phi, v, eps = case
        got = self._against_reference("no_overstep", case)
        if not isinstance(got, tuple):
            return got  # discarded or failed
        tau_ref, kappa, tau = got
        with mp.workdps(_WORK_DPS):
            tol = self.k * kappa * U * tau_ref
            excess = _mpf(tau) - tau_ref
            if excess <= tol:
                return None
            P, V, E = _mpf(phi), _mpf(v), _mpf(eps)
            linear = mp_gap_prime(P, V, E, tau_ref) * excess  # d(tau) if on the first root's line
            d_tau = mp_gap(P, V, E, _mpf(tau))
            if linear < 0 and linear / 2 >= d_tau >= 2 * linear:
                what = "tau is the first root computed too late"
            else:
                what = "the first collision was skipped"
            return self._fail(
                "no_overstep", case, float(tau_ref), tau,
                f"tau is {mp.nstr(excess, 3)} beyond the certified first root (allowed "
                f"k*kappa*u*tau = {mp.nstr(tol, 3)}, kappa = {mp.nstr(kappa, 3)}): {what}",
            )

    # -- accuracy
    def accuracy(self, case):
        phi, v, eps = case
        got = self._against_reference("accuracy", case)
        if not isinstance(got, tuple):
            return got  # discarded or failed
        tau_ref, kappa, tau = got
        with mp.workdps(_WORK_DPS):
            rel = abs(_mpf(tau) - tau_ref) / tau_ref
            k_obs = float(rel / (kappa * U))
        if self.worst_k is None or k_obs > self.worst_k:
            self.worst_k, self.worst_input = k_obs, (phi, v, eps)
        if k_obs <= self.k:
            return None
        return self._fail(
            "accuracy", case, float(tau_ref), tau,
            f"relative error {float(rel):.3g} = {k_obs:.3g} x kappa*u "
            f"(kappa = {float(kappa):.3g}); allowed {self.k:g} x kappa*u",
        )

    # -- fixed_points
    def fixed_points(self, case):
        phi, v, eps = case
        m = round(v / math.pi)
        with mp.workdps(_WORK_DPS):
            tau_exact = 2 * _mpf(v)  # exact root of the float input up to ~eps*(v-pi*m)**2/v
            kappa = condition_number(phi, v, eps, tau_exact)
            tau_tol, phi1_tol, v1_tol = _map_tolerances(self.k, phi, v, eps, tau_exact, kappa)
            phi1_exact = tau_exact % (2 * mp.pi)
            v1_exact = tau_exact - _mpf(v) - 2 * _mpf(eps) * mp.sin(tau_exact)
        where = f"fixed point (0, pi*{m})"
        try:
            tau = _call_flight(self.fn, phi, v, eps)
        except _Bad as bad:
            return self._fail("fixed_points", case, float(tau_exact), bad.text,
                              f"{where}: {bad.message}")
        with mp.workdps(_WORK_DPS):
            if abs(_mpf(tau) - tau_exact) > tau_tol:
                return self._fail(
                    "fixed_points", case, float(tau_exact), tau,
                    f"{where}: tau must be 2*pi*{m} (= 2*v); off by "
                    f"{float(abs(_mpf(tau) - tau_exact)):.3g} > tolerance {tau_tol:.3g}",
                )
        if self.step is None:
            return None
        try:
            phi1, v1, tau_s = _call_step(self.step, phi, v, eps)
        except _Bad as bad:
            return self._fail("fixed_points", case, (float(phi1_exact), float(v1_exact),
                              float(tau_exact)), bad.text, f"{where}: {bad.message}", "step")
        with mp.workdps(_WORK_DPS):
            off = (
                float(_phase_distance(phi1, phi1_exact)) > phi1_tol
                or abs(_mpf(v1) - v1_exact) > v1_tol
                or abs(_mpf(tau_s) - tau_exact) > tau_tol
            )
        expected = (float(phi1_exact), float(v1_exact), float(tau_exact))
        if off:
            return self._fail(
                "fixed_points", case, expected, (phi1, v1, tau_s),
                f"{where} must map to itself: tolerances phi1 {phi1_tol:.3g} (mod 2*pi), "
                f"v1 {v1_tol:.3g}, tau {tau_tol:.3g}", "step",
            )
        return self._jacobian(case, m, max(phi1_tol, v1_tol))

    def _jacobian(self, case, m, step_tol):
        phi, v, eps = case
        h, tol = _jacobian_tolerance(eps, step_tol)
        exact = ((1.0, 2.0), (-2.0 * eps, 1.0 - 4.0 * eps))
        columns = []
        for dphi, dv in ((h, 0.0), (0.0, h)):
            try:
                plus = _call_step(self.step, phi + dphi, v + dv, eps)
                minus = _call_step(self.step, phi - dphi, v - dv, eps)
            except _Bad as bad:
                return self._fail("fixed_points", case, exact, bad.text,
                                  f"step near the fixed point (0, pi*{m}), h = {h:.3g}: "
                                  f"{bad.message}", "step")
            dphi1 = math.remainder(plus[0] - minus[0], TWO_PI)  # phases wrap at 0 = 2*pi
            columns.append((dphi1 / (2 * h), (plus[1] - minus[1]) / (2 * h)))
        fd = ((columns[0][0], columns[1][0]), (columns[0][1], columns[1][1]))
        worst = max(abs(fd[i][j] - exact[i][j]) for i in range(2) for j in range(2))
        if worst <= tol:
            return None
        return self._fail(
            "fixed_points", case, exact, fd,
            f"Jacobian of step at (0, pi*{m}) by central differences (h = {h:.3g}) is off by "
            f"{worst:.3g} > tolerance {tol:.3g}", "step",
        )

    # -- energy
    def energy(self, case):
        phi, v, eps = case
        try:
            phi1, v1, tau = _call_step(self.step, phi, v, eps)
        except _Bad as bad:
            return self._fail("energy", case, "E1 - E0 = 2*u*(u - v_in)", bad.text, bad.message,
                              "step")
        with mp.workdps(_WORK_DPS):
            P, V, E, P1, V1, T = (_mpf(x) for x in (phi, v, eps, phi1, v1, tau))
            kappa = condition_number(phi, v, eps, tau)
            if not mp.isfinite(kappa):
                return _DISCARD
            tau_tol, phi1_tol, v1_tol = _map_tolerances(self.k, phi, v, eps, T, kappa)
            u = -E * mp.sin(P1)
            v_in = V - T
            e0 = V * V / 2 + E * mp.cos(P)
            e1 = V1 * V1 / 2 + E * mp.cos(P1)
            lhs, rhs = e1 - e0, 2 * u * (u - v_in)
            # |residual| <= |v1|*dv1 + 2|u|*dtau + (|u| + 2|eps*v1|)*dphi1 to first order
            tol = (abs(V1) * v1_tol + 2 * abs(u) * tau_tol
                   + (abs(u) + 2 * abs(E * V1)) * phi1_tol)
            if abs(lhs - rhs) <= tol:
                return None
            return self._fail(
                "energy", case, f"E1 - E0 = 2*u*(u - v_in) = {mp.nstr(rhs, 12)}",
                (phi1, v1, tau),
                f"E1 - E0 = {mp.nstr(lhs, 12)}: energy bookkeeping off by "
                f"{mp.nstr(abs(lhs - rhs), 3)} > tolerance {mp.nstr(tol, 3)}", "step",
            )

    # -- holmes_limit
    def holmes_limit(self, case):
        phi, v, eps = case
        try:
            tau = _call_flight(self.fn, phi, v, eps)
        except _Bad as bad:
            return self._fail("holmes_limit", case, f"tau ~ 2*v = {2 * v!r}", bad.text,
                              bad.message)
        with mp.workdps(_WORK_DPS):
            T = _mpf(tau)
            kappa = condition_number(phi, v, eps, tau)
            slack = self.k * kappa * U * T if mp.isfinite(kappa) else mp.inf
            bound = 4 * abs(_mpf(eps)) / T
            dev = abs(T - 2 * _mpf(v))
            if dev <= bound + slack:
                return None
            return self._fail(
                "holmes_limit", case, f"|tau - 2*v| <= 4*eps/tau = {mp.nstr(bound, 3)}", tau,
                f"|tau - 2*v| = {mp.nstr(dev, 3)} exceeds 4*eps/tau + k*kappa*u*tau = "
                f"{mp.nstr(bound + slack, 3)}",
            )

    # -- reversibility
    def reversibility(self, case):
        phi, v, eps = case
        try:
            tau = _call_flight(self.fn, phi, v, eps)
        except _Bad as bad:
            return self._fail("reversibility", case, "a flight time", bad.text, bad.message)
        phi_r, v_r = -(phi + tau), tau - v
        with mp.workdps(_WORK_DPS):
            P, V, E, T = (_mpf(x) for x in (phi, v, eps, tau))
            w0 = V + E * mp.sin(P)
            w0_r = _mpf(v_r) + E * mp.sin(_mpf(phi_r))  # = -d'(tau): the impact speed
            scale = self.k * U * _num(phi, v, eps, T)
            if w0_r <= 0:
                if w0_r > -scale:  # a graze within rounding: nothing to reverse
                    return _DISCARD
                return self._fail(
                    "reversibility", case, "d'(tau) < 0 (the particle falls onto the plate)",
                    tau, f"d'(tau) = {mp.nstr(-w0_r, 3)} > 0 at the returned tau: the particle "
                    "moves away from the plate there, so tau is no first collision",
                )
            # tau2 - tau ~ (|d'(tau)|/w0)*(error of tau) + (error of tau2): both within
            # k*u*tau times num/w0 (kappa's numerator over the speed that divides it)
            tol = self.k * U * T * (_num(phi, v, eps, T) + _num(phi_r, v_r, eps, T)) / w0
        try:
            tau2 = _call_flight(self.fn, phi_r, v_r, eps)
        except _Bad as bad:
            return self._fail("reversibility", (phi_r, v_r, eps), tau, bad.text,
                              f"reversed flight from (-(phi + tau), tau - v) of the departure "
                              f"(phi={phi!r}, v={v!r}): {bad.message}")
        with mp.workdps(_WORK_DPS):
            dev = abs(_mpf(tau2) - T)
            if dev <= tol:
                return None
            return self._fail(
                "reversibility", (phi_r, v_r, eps), tau, tau2,
                f"reversed flight from (-(phi + tau), tau - v) of the departure "
                f"(phi={phi!r}, v={v!r}, tau={tau!r}) takes a different time: off by "
                f"{mp.nstr(dev, 3)} > tolerance {mp.nstr(tol, 3)}",
            )


def _strategies():
    """Per property: (label, strategy, share of the inputs). Each part runs as its own
    hypothesis search, so every kind of input gets its share (``one_of`` would not promise it).
    """
    from . import strategies as vs

    random = vs.departures(eps=(0.0, 10.0))
    return {
        "no_overstep": (
            ("random", random, 0.4),
            ("close root pairs", vs.near_grazing(clearance=vs.clearances(-1)), 0.4),
            ("near misses", vs.near_grazing(clearance=vs.clearances(+1)), 0.2),
        ),
        "accuracy": (
            ("random", random, 0.4), ("hard", vs.hard_cases(), 0.4),
            ("near fixed points", vs.near_fixed_point(), 0.2),
        ),
        "fixed_points": (("fixed points", vs.fixed_points(), 1.0),),
        "energy": (("random", random, 0.6), ("hard", vs.hard_cases(), 0.4)),
        "holmes_limit": (("large v", vs.large_velocities(), 1.0),),
        # the reversed flight ARRIVES with the forward departure speed w0: for w0 -> 0 and
        # eps > 1 that arrival is a near-graze a float64 method may rightly refuse to decide
        "reversibility": (
            ("random", vs.departures(eps=(0.0, 10.0), w0=(1e-3, 30.0)), 0.8),
            ("near fixed points", vs.near_fixed_point(), 0.2),
        ),
    }


# --------------------------------------------------------------------------- driver


class _Falsified(Exception):
    def __init__(self, failure: Failure) -> None:
        super().__init__(str(failure))
        self.failure = failure


def _find_falsified(err: BaseException) -> _Falsified | None:
    """The _Falsified inside err (hypothesis may wrap it, e.g. as a FlakyFailure group)."""
    seen = set()
    stack = [err]
    while stack:
        e = stack.pop()
        if e is None or id(e) in seen:
            continue
        seen.add(id(e))
        if isinstance(e, _Falsified):
            return e
        stack.extend(getattr(e, "exceptions", ()))
        stack.extend((e.__cause__, e.__context__))
    return None


def _hypothesis_run(test, strategy, max_examples: int, seed: int | None, shrink: bool):
    """Run ``test`` on ``max_examples`` drawn cases under quiet, database-free settings."""
    from hypothesis import HealthCheck, Phase, Verbosity, given, settings
    from hypothesis import seed as hypothesis_seed

    phases = (Phase.explicit, Phase.generate) + ((Phase.shrink,) if shrink else ())
    run = settings(
        database=None, max_examples=max_examples, deadline=None, derandomize=False,
        suppress_health_check=list(HealthCheck), report_multiple_bugs=False,
        verbosity=Verbosity.quiet, print_blob=False, phases=phases,
    )(given(strategy)(test))
    if seed is not None:
        run = hypothesis_seed(seed)(run)
    run()


@dataclass
class _Outcome:
    inputs: int = 0
    failed: int = 0
    failure: Failure | None = None
    note: str = ""


def _survey(body, count, first, strategy):
    from hypothesis import reject

    def survey(case):
        result = body(case)
        if result is _DISCARD:
            reject()
        count["inputs"] += 1
        if result is not None:
            count["failed"] += 1
            if not first:
                first.append((strategy, result))

    return survey


def _run_property(body, parts, max_examples: int, seed: int | None) -> _Outcome:
    """Each part: a survey of its share of ``max_examples`` inputs that counts the failing ones.
    Then, for the first part with a failure, a second run that stops at the first failure and
    lets hypothesis shrink it to the smallest failing input."""
    from hypothesis import reject
    from hypothesis.errors import Unsatisfiable

    out = _Outcome()
    first: list[tuple[object, Failure]] = []
    per_part = []

    def falsify(case):
        result = body(case)
        if result is _DISCARD:
            reject()
        if result is not None:
            raise _Falsified(result)

    for label, strategy, share in parts:
        count = {"inputs": 0, "failed": 0}
        survey = _survey(body, count, first, strategy)
        n = max(1, round(max_examples * share))
        try:
            _hypothesis_run(survey, strategy, n, seed, shrink=False)
        except Unsatisfiable:
            out.note = f"too few valid {label} inputs could be drawn"
        out.inputs += count["inputs"]
        out.failed += count["failed"]
        if len(parts) > 1:
            per_part.append(f"{label} {count['failed']}/{count['inputs']}")
    if not first:
        return out
    if len(parts) > 1:
        out.note = "failing: " + ", ".join(per_part)
    strategy, failure = first[0]
    try:
        _hypothesis_run(falsify, strategy, max_examples, seed, shrink=True)
    except Exception as err:  # noqa: BLE001 - look for our own failure inside hypothesis' wrap
        found = _find_falsified(err)
        if found is None:
            raise
        out.failure = found.failure
        if found is not err:
            out.note += "; flaky: the callable gave different results for the same input"
        return out
    out.failure = failure
    out.note += "; not reproduced on a second run (flaky callable?): first failure, unshrunk"
    return out


def _properties_of(suite: str) -> tuple[str, ...]:
    if suite in ("all", "fast"):
        return PROPERTIES
    return (suite,)


def _check_suite(suite) -> str:
    if suite not in SUITES:
        raise ValueError(f"suite must be one of {', '.join(SUITES)}; got {suite!r}")
    return suite


def check_integrator(
    flight_time: Callable,
    *,
    step: Callable | None = None,
    suite: str = "all",
    max_examples: int | None = None,
    seed: int | None = 0,
    k: float = 16,
) -> CheckReport:
    """Run the property suite (module docstring) against ``flight_time`` (and ``step``).

    suite: "all", "fast" (20 inputs per property instead of 100) or one property name.
    max_examples: inputs per property (overrides the suite's count). seed: hypothesis seed
    (an int gives the same inputs every run; None draws fresh ones). k: allowed multiple of
    ``kappa*u``. Properties that need ``step`` are skipped without it (asking for one of them
    alone raises ``ValueError``). Returns a :class:`CheckReport`; never raises for a
    misbehaving callable.
    """
    suite = _check_suite(suite)
    if not callable(flight_time):
        raise ValueError(f"flight_time must be callable, got {flight_time!r}")
    if step is not None and not callable(step):
        raise ValueError(f"step must be callable or None, got {step!r}")
    if suite in NEEDS_STEP and step is None:
        raise ValueError(f"suite {suite!r} needs a step callable (step=... / --step)")
    if isinstance(k, bool) or not isinstance(k, numbers.Real) or not (0 < k < math.inf):
        raise ValueError(f"k must be a positive finite number, got k={k!r}")
    if max_examples is None:
        max_examples = DEFAULT_EXAMPLES["fast" if suite == "fast" else "all"]
    if isinstance(max_examples, bool) or not isinstance(max_examples, numbers.Integral) \
            or max_examples < 1:
        raise ValueError(f"max_examples must be an integer >= 1, got {max_examples!r}")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, numbers.Integral)):
        raise ValueError(f"seed must be an integer or None, got seed={seed!r}")

    checker = _Checker(flight_time, step, k)
    strategies = _strategies()
    results = []
    start = time.perf_counter()
    for name in _properties_of(suite):
        t0 = time.perf_counter()
        if name in NEEDS_STEP and step is None:
            results.append(PropertyResult(name, "SKIP", 0, "needs a step callable"))
            continue
        got = _run_property(getattr(checker, name), strategies[name], int(max_examples), seed)
        notes = [got.note] if got.note else []
        if name == "accuracy" and checker.worst_k is not None:
            phi, v, eps = checker.worst_input
            notes.insert(0, f"worst k = {checker.worst_k:.3g} at phi={phi!r}, v={v!r}, "
                            f"eps={eps!r}; allowed {k:g}")
        if name == "fixed_points" and step is None:
            notes.append("flight time only: no step given")
        status = "FAIL" if got.failure is not None else "PASS" if got.inputs else "SKIP"
        results.append(PropertyResult(name, status, got.inputs, "; ".join(notes), got.failure,
                                      time.perf_counter() - t0, got.failed))
    return CheckReport(
        target=_name(flight_time),
        step_target=None if step is None else _name(step),
        suite=suite,
        k=float(k),
        seed=seed,
        max_examples=int(max_examples),
        results=tuple(results),
        worst_accuracy_k=checker.worst_k,
        worst_accuracy_input=checker.worst_input,
        seconds=time.perf_counter() - start,
    )


def assert_integrator(flight_time: Callable, **kwargs) -> CheckReport:
    """:func:`check_integrator`, raising ``AssertionError`` with the report's text on failure.

    For a user's pytest suite::

        import verify
        from mysolver import flight_time, step

        def test_my_integrator():
            verify.assert_integrator(flight_time, step=step)
    """
    report = check_integrator(flight_time, **kwargs)
    if not report.ok:
        raise AssertionError(str(report))
    return report
