"""The errors of the reference: one "undecided" type.

:class:`UndecidableCollision` is raised wherever verify cannot decide at the largest precision
it allows (instead of guessing). :class:`ChatteringDetected` is the same refusal for an orbit
whose impacts pile up without a provable accumulation; it is a subclass, so
``except UndecidableCollision`` catches both. (Inside verify, an attempt that cannot decide at
its working precision raises :class:`verify.numerics.precision.NotDecided`, which
:func:`verify.numerics.precision.escalate` turns into a retry at a higher precision; it never
reaches a caller.)
"""

from __future__ import annotations

from .numerics.precision import to_user


class UndecidableCollision(ArithmeticError):
    """The first collision could not be decided even at the largest precision allowed.

    Raised instead of guessing when an interval comparison stays ambiguous at ``max_dps``
    digits: a near-tangency (``d`` has a local minimum indistinguishable from 0: graze or not),
    a departure velocity ``w0`` indistinguishable from 0, or a root that cannot be separated.
    The message names the state, the precision reached and what stayed undecided. Attributes:
    ``phi``, ``v``, ``eps`` (the state; ``phi`` and ``v`` are None where no single departure
    is concerned, e.g. the proof of where a particle riding the plate leaves it),
    ``dps_reached``, ``what``.
    """

    def __init__(self, phi, v, eps, dps_reached: int, what: str) -> None:
        self.phi, self.v, self.eps = to_user(phi), to_user(v), to_user(eps)
        self.dps_reached = dps_reached
        self.what = what
        if phi is None or v is None:  # no single departure state (the riding force's roots)
            where = f"the motion at eps={_short(eps)}"
        else:
            where = f"flight from phi={_short(phi)}, v={_short(v)}, eps={_short(eps)}"
        super().__init__(f"{where} is undecidable at {dps_reached} digits: {what}")


def _short(x) -> str:
    s = str(x)
    return s if len(s) <= 40 else s[:40] + "..."


class ChatteringDetected(UndecidableCollision):
    """Impacts accumulate (restitution < 1) but no tail could be summed.

    Raised by :func:`verify.orbit` with drag > 0 after collision ``n`` (at time ``t``, state
    ``phi``, ``v``) when the velocity relative to the plate, ``w = v + eps*sin(phi)``, fell below
    ``w_min = 10**(-dps//2)*(1 + |v| + |eps|)``, far below where
    :mod:`verify.dissipative.drag_sticking` sums the tail (``w ~ 10**(-dps/3)``), while the
    gap's curvature ``d''(0)`` is negative (the plate pulls the particle back): the
    accumulation could not be proved at this precision (e.g. a chatter that reaches the
    detachment phase), so the orbit stops instead of crawling. Attributes: those of
    :class:`UndecidableCollision` and ``n``, ``t``, ``w``, ``w_min``.
    """

    def __init__(self, n: int, t, phi, v, eps, w, w_min, dps: int) -> None:
        self.n, self.t, self.w, self.w_min = n, to_user(t), to_user(w), to_user(w_min)
        what = (f"chattering: after collision {n} (t={_short(t)}) the velocity relative to the "
                f"plate is w={_short(w)} < {_short(w_min)} and falling: impacts accumulate, but "
                "no accumulation tail could be proved")
        super().__init__(phi, v, eps, dps, what)
        self.args = (f"{what} (phi={_short(phi)}, v={_short(v)}, eps={_short(eps)}, "
                     f"{dps} digits)",)
