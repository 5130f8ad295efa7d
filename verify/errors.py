"""Errors raised by the reference integrator."""

from __future__ import annotations


class UndecidableCollision(ArithmeticError):
    """The first collision could not be decided even at the largest precision allowed.

    Raised instead of guessing when an interval comparison stays ambiguous at ``max_dps``
    digits: a near-tangency (``d`` has a local minimum indistinguishable from 0: graze or not),
    a departure velocity ``w0`` indistinguishable from 0, or a root that cannot be separated.
    The message names the state, the precision reached and what stayed undecided.
    """

    def __init__(self, phi, v, eps, dps_reached: int, what: str) -> None:
        self.phi, self.v, self.eps = phi, v, eps
        self.dps_reached = dps_reached
        self.what = what
        super().__init__(
            f"flight from phi={_short(phi)}, v={_short(v)}, eps={_short(eps)} is undecidable "
            f"at {dps_reached} digits: {what}"
        )


def _short(x) -> str:
    s = str(x)
    return s if len(s) <= 40 else s[:40] + "..."


class ChatteringDetected(ArithmeticError):
    """Impacts accumulate (restitution < 1): the orbit would need infinitely many collisions.

    Raised by :func:`verify.orbit` after collision ``n`` (at time ``t``, state ``phi``, ``v``)
    when the velocity relative to the plate, ``w = v + eps*sin(phi)``, fell below the threshold
    ``w_min`` while the gap's curvature ``d''(0)`` is negative (the plate pulls the particle
    back), with drag > 0: verify computes the accumulation and sticking only without drag
    (:mod:`verify.sticking`).
    """

    def __init__(self, n: int, t, phi, v, w, w_min) -> None:
        self.n, self.t, self.phi, self.v, self.w, self.w_min = n, t, phi, v, w, w_min
        super().__init__(
            f"chattering: after collision {n} (t={_short(t)}, phi={_short(phi)}, v={_short(v)}) "
            f"the velocity relative to the plate is w={_short(w)} < {_short(w_min)} and falling: "
            "impacts accumulate; verify.orbit computes sticking phases only without drag"
        )
