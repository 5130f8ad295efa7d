"""The property bodies (``Checker``): each takes one drawn case ``(phi, v, eps)`` and returns
None (holds), a :class:`Failure` or ``DISCARD`` (verify cannot decide the reference there).
The equations are in the docstring of :mod:`verify.check` and on each method."""

from __future__ import annotations

import functools
import math

from mpmath import mp

from ..elastic.conditioning import condition_number
from ..elastic.gap import mp_gap, mp_gap_prime
from ..errors import UndecidableCollision
from ..flight import certify_flight
from .calling import Bad, call_flight, call_step
from .report import Failure
from .tolerance import (
    TWO_PI,
    WORK_DPS,
    U,
    jacobian_tolerance,
    kappa_numerator,
    map_tolerances,
    mpf,
    phase_distance,
)

REF_DPS = 30  # digits of the certified reference (float64 needs 17)


DISCARD = object()


class Checker:
    """The property bodies; each takes one drawn case and returns None, a Failure or DISCARD."""

    def __init__(self, flight_time, step, k):
        self.fn = flight_time
        self.step = step
        self.k = float(k)
        self.worst_k: float | None = None
        self.worst_input: tuple[float, float, float] | None = None
        self.reference = functools.lru_cache(maxsize=4096)(self._reference)

    def _reference(self, phi, v, eps):
        """(tau_ref, kappa) at REF_DPS digits, or None where verify cannot decide."""
        try:
            cert = certify_flight(phi, v, eps, dps=REF_DPS)
        except UndecidableCollision:
            return None
        with mp.workdps(WORK_DPS):
            kappa = condition_number(phi, v, eps, cert.tau, reduced=False)
        if not mp.isfinite(kappa):
            return None
        return cert.tau, kappa

    def _fail(self, prop, case, expected, obtained, message, call="flight_time"):
        phi, v, eps = case[:3]
        return Failure(prop, phi, v, eps, expected, obtained, message, call)

    def _against_reference(self, prop, case):
        """(tau_ref, kappa, tau) for the user's flight time at ``case``; DISCARD where verify
        cannot decide, a Failure where the callable raises or returns a non-time."""
        phi, v, eps = case
        ref = self.reference(phi, v, eps)
        if ref is None:
            return DISCARD
        tau_ref, kappa = ref
        try:
            tau = call_flight(self.fn, phi, v, eps)
        except Bad as bad:
            return self._fail(prop, case, float(tau_ref), bad.text, bad.message)
        return tau_ref, kappa, tau

    # -- no_overstep
    def no_overstep(self, case):
        phi, v, eps = case
        got = self._against_reference("no_overstep", case)
        if not isinstance(got, tuple):
            return got  # discarded or failed
        tau_ref, kappa, tau = got
        with mp.workdps(WORK_DPS):
            tol = self.k * kappa * U * tau_ref
            excess = mpf(tau) - tau_ref
            if excess <= tol:
                return None
            P, V, E = mpf(phi), mpf(v), mpf(eps)
            linear = mp_gap_prime(P, V, E, tau_ref) * excess  # d(tau) if on the first root's line
            d_tau = mp_gap(P, V, E, mpf(tau))
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
        with mp.workdps(WORK_DPS):
            rel = abs(mpf(tau) - tau_ref) / tau_ref
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
        with mp.workdps(WORK_DPS):
            tau_exact = 2 * mpf(v)  # exact root of the float input up to ~eps*(v-pi*m)**2/v
            kappa = condition_number(phi, v, eps, tau_exact, reduced=False)
            tau_tol, phi1_tol, v1_tol = map_tolerances(self.k, phi, v, eps, tau_exact, kappa)
            phi1_exact = tau_exact % (2 * mp.pi)
            v1_exact = tau_exact - mpf(v) - 2 * mpf(eps) * mp.sin(tau_exact)
        where = f"fixed point (0, pi*{m})"
        try:
            tau = call_flight(self.fn, phi, v, eps)
        except Bad as bad:
            return self._fail("fixed_points", case, float(tau_exact), bad.text,
                              f"{where}: {bad.message}")
        with mp.workdps(WORK_DPS):
            if abs(mpf(tau) - tau_exact) > tau_tol:
                return self._fail(
                    "fixed_points", case, float(tau_exact), tau,
                    f"{where}: tau must be 2*pi*{m} (= 2*v); off by "
                    f"{float(abs(mpf(tau) - tau_exact)):.3g} > tolerance {tau_tol:.3g}",
                )
        if self.step is None:
            return None
        try:
            phi1, v1, tau_s = call_step(self.step, phi, v, eps)
        except Bad as bad:
            return self._fail("fixed_points", case, (float(phi1_exact), float(v1_exact),
                              float(tau_exact)), bad.text, f"{where}: {bad.message}", "step")
        with mp.workdps(WORK_DPS):
            off = (
                float(phase_distance(phi1, phi1_exact)) > phi1_tol
                or abs(mpf(v1) - v1_exact) > v1_tol
                or abs(mpf(tau_s) - tau_exact) > tau_tol
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
        h, tol = jacobian_tolerance(eps, step_tol)
        exact = ((1.0, 2.0), (-2.0 * eps, 1.0 - 4.0 * eps))
        columns = []
        for dphi, dv in ((h, 0.0), (0.0, h)):
            try:
                plus = call_step(self.step, phi + dphi, v + dv, eps)
                minus = call_step(self.step, phi - dphi, v - dv, eps)
            except Bad as bad:
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
            phi1, v1, tau = call_step(self.step, phi, v, eps)
        except Bad as bad:
            return self._fail("energy", case, "E1 - E0 = 2*u*(u - v_in)", bad.text, bad.message,
                              "step")
        with mp.workdps(WORK_DPS):
            P, V, E, P1, V1, T = (mpf(x) for x in (phi, v, eps, phi1, v1, tau))
            kappa = condition_number(phi, v, eps, tau, reduced=False)
            if not mp.isfinite(kappa):
                return DISCARD
            tau_tol, phi1_tol, v1_tol = map_tolerances(self.k, phi, v, eps, T, kappa)
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
            tau = call_flight(self.fn, phi, v, eps)
        except Bad as bad:
            return self._fail("holmes_limit", case, f"tau ~ 2*v = {2 * v!r}", bad.text,
                              bad.message)
        with mp.workdps(WORK_DPS):
            T = mpf(tau)
            kappa = condition_number(phi, v, eps, tau, reduced=False)
            slack = self.k * kappa * U * T if mp.isfinite(kappa) else mp.inf
            bound = 4 * abs(mpf(eps)) / T
            dev = abs(T - 2 * mpf(v))
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
            tau = call_flight(self.fn, phi, v, eps)
        except Bad as bad:
            return self._fail("reversibility", case, "a flight time", bad.text, bad.message)
        phi_r, v_r = -(phi + tau), tau - v
        with mp.workdps(WORK_DPS):
            P, V, E, T = (mpf(x) for x in (phi, v, eps, tau))
            w0 = V + E * mp.sin(P)
            w0_r = mpf(v_r) + E * mp.sin(mpf(phi_r))  # = -d'(tau): the impact speed
            scale = self.k * U * kappa_numerator(phi, v, eps, T)
            if w0_r <= 0:
                if w0_r > -scale:  # a graze within rounding: nothing to reverse
                    return DISCARD
                return self._fail(
                    "reversibility", case, "d'(tau) < 0 (the particle falls onto the plate)",
                    tau, f"d'(tau) = {mp.nstr(-w0_r, 3)} > 0 at the returned tau: the particle "
                    "moves away from the plate there, so tau is no first collision",
                )
            # tau2 - tau ~ (|d'(tau)|/w0)*(error of tau) + (error of tau2): both within
            # k*u*tau times num/w0 (kappa's numerator over the speed that divides it)
            tol = self.k * U * T * (kappa_numerator(phi, v, eps, T)
                                   + kappa_numerator(phi_r, v_r, eps, T)) / w0
        try:
            tau2 = call_flight(self.fn, phi_r, v_r, eps)
        except Bad as bad:
            return self._fail("reversibility", (phi_r, v_r, eps), tau, bad.text,
                              f"reversed flight from (-(phi + tau), tau - v) of the departure "
                              f"(phi={phi!r}, v={v!r}): {bad.message}")
        with mp.workdps(WORK_DPS):
            dev = abs(mpf(tau2) - T)
            if dev <= tol:
                return None
            return self._fail(
                "reversibility", (phi_r, v_r, eps), tau, tau2,
                f"reversed flight from (-(phi + tau), tau - v) of the departure "
                f"(phi={phi!r}, v={v!r}, tau={tau!r}) takes a different time: off by "
                f"{mp.nstr(dev, 3)} > tolerance {mp.nstr(tol, 3)}",
            )
