"""Hypothesis strategies for bouncer departures: use them in your own property tests.

Every strategy draws tuples ``(phi, v, eps)`` of Python floats that are valid departures *as
floats*: ``w0 = v + eps*sin(phi) > 0`` holds for the exact binary values (checked in mpmath), not
only for the formula evaluated in float64. The departure speed ``w0`` is drawn first and
``v = w0 - eps*sin(phi)`` derived from it, so small ``w0`` (short, ill-conditioned flights) is
reached as often as large.

Range arguments (``eps``, ``w0``, ``phi``, ``clearance``, ...) take a number (that value), a
``(lo, hi)`` pair (floats in that range, both ends included, except a lower bound 0 for a
speed, which must be positive) or any hypothesis strategy of floats.

    from hypothesis import given
    from verify.strategies import departures, hard_cases

    @given(departures(eps=(0.0, 1.0)))
    def test_my_integrator(case):
        phi, v, eps = case
        ...

Hypothesis is needed (``pip install bouncer-verify[test]``); ``import verify`` alone is not.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

from .elastic.grazing import grazing_contact
from .numerics.float64 import TWO_PI
from .numerics.precision import mp, to_user, working_dps

__all__ = [
    "clearances",
    "departures",
    "exact_w0",
    "fixed_points",
    "hard_cases",
    "huge_phases",
    "large_velocities",
    "near_fixed_point",
    "near_grazing",
    "near_triple_root",
]

_W0_DPS = 50  # exact w0 of float inputs: phases up to ~1e6 and w0 down to ~1e-300 fit easily
_LINEAR_W0_FLOOR = 1e-3  # below this, w0 is drawn log-uniformly


def exact_w0(phi: float, v: float, eps: float):
    """``v + eps*sin(phi)`` of the float inputs, at 50 digits (an ``mpf``)."""
    with working_dps(_W0_DPS):
        return to_user(mp.mpf(v) + mp.mpf(eps) * mp.sin(mp.mpf(phi)))


def _is_departure(phi: float, v: float, eps: float) -> bool:
    if not all(math.isfinite(x) for x in (phi, v, eps)):
        return False
    return exact_w0(phi, v, eps) > 0


def _floats(spec, name: str, *, positive: bool = False) -> st.SearchStrategy:
    """A number, a (lo, hi) pair or a strategy -> a strategy of floats (see module docstring)."""
    if isinstance(spec, st.SearchStrategy):
        return spec
    if isinstance(spec, int | float) and not isinstance(spec, bool):
        if not math.isfinite(spec) or (positive and spec <= 0):
            raise ValueError(f"{name} must be a finite{' positive' if positive else ''} number, "
                             f"got {name}={spec!r}")
        return st.just(float(spec))
    try:
        lo, hi = (float(x) for x in spec)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} must be a number, a (lo, hi) pair or a hypothesis strategy, got {spec!r}"
        ) from None
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo > hi:
        raise ValueError(f"{name} range must be finite with lo <= hi, got {name}={spec!r}")
    if positive and hi <= 0:
        raise ValueError(f"{name} range must contain positive values, got {name}={spec!r}")
    if positive and lo <= 0:
        return st.floats(0.0, hi, exclude_min=True, allow_subnormal=False)
    if lo == hi:
        return st.just(lo)
    return st.floats(lo, hi, allow_subnormal=False)


def _log_uniform(lo: float, hi: float) -> st.SearchStrategy:
    """Floats spread over the decades between lo > 0 and hi: a decade, then a mantissa in
    [1, 10) (hypothesis' floats over an exponent range crowd its ends; integers do not)."""
    a, b = math.floor(math.log10(lo)), math.floor(math.log10(hi))
    return st.tuples(st.integers(a, b), st.floats(1.0, 10.0, exclude_max=True)).map(
        lambda p: min(max(p[1] * 10.0 ** p[0], lo), hi)
    )


def _speeds(spec) -> st.SearchStrategy:
    """w0: a (lo, hi) range is drawn half uniformly (above 1e-3), half log-uniformly."""
    if isinstance(spec, st.SearchStrategy) or isinstance(spec, int | float):
        return _floats(spec, "w0", positive=True)
    lo, hi = (float(x) for x in spec)
    if not (0 < lo <= hi and math.isfinite(hi)):
        raise ValueError(f"w0 range must satisfy 0 < lo <= hi < inf, got w0={spec!r}")
    parts = []
    if hi > _LINEAR_W0_FLOOR:
        parts.append(st.floats(max(lo, _LINEAR_W0_FLOOR), hi))
    if lo < hi:
        parts.append(_log_uniform(lo, hi))
    return st.one_of(parts) if parts else st.just(lo)


def _phases(unreduced: bool) -> st.SearchStrategy:
    reduced = st.floats(0.0, TWO_PI, exclude_max=True)
    if not unreduced:
        return reduced
    return st.one_of(reduced, st.floats(-1e3, 1e6))


@st.composite
def _departure(draw, eps_s, w0_s, phi_s):
    eps = draw(eps_s)
    phi = draw(phi_s)
    w0 = draw(w0_s)
    v = w0 - eps * math.sin(phi)
    if not _is_departure(phi, v, eps):  # rounding of v can push w0 to <= 0: redraw
        return None
    return (phi, v, eps)


def departures(eps=(0.0, 10.0), *, w0=(1e-12, 30.0), phi=None, unreduced=True):
    """Valid departures ``(phi, v, eps)``.

    eps: range of the amplitude (default ``[0, 10]``); w0: range of the departure speed
    ``v + eps*sin(phi)`` (default ``[1e-12, 30]``; half of the draws log-uniform, so tiny
    speeds are frequent); phi: range of the phase, default ``[0, 2*pi)`` or, with ``unreduced``,
    also unreduced phases in ``[-1e3, 1e6]``.
    """
    eps_s = _floats(eps, "eps")
    phi_s = _phases(unreduced) if phi is None else _floats(phi, "phi")
    w0_s = _speeds(w0)
    return _departure(eps_s, w0_s, phi_s).filter(lambda case: case is not None)


_SPECIAL_PHASES = (
    0.0,
    math.nextafter(0.0, 1.0),
    -math.nextafter(0.0, 1.0),
    math.pi,
    math.nextafter(math.pi, 0.0),
    math.nextafter(math.pi, 4.0),
    math.nextafter(TWO_PI, 0.0),
    TWO_PI,
)


@st.composite
def _hard_case(draw, eps_max):
    kind = draw(st.sampled_from(
        ("small_w0", "huge_v", "unreduced_phase", "tiny_eps", "huge_eps", "special_phase")
    ))
    reduced = st.floats(0.0, TWO_PI, exclude_max=True)
    moderate_w0 = st.floats(1e-3, 30.0)
    eps_s = st.floats(0.0, min(10.0, eps_max), allow_subnormal=False)
    if kind == "small_w0":
        eps, phi, w0 = draw(eps_s), draw(reduced), draw(_log_uniform(1e-12, 1e-3))
    elif kind == "huge_v":
        eps = draw(st.floats(0.0, eps_max, allow_subnormal=False))
        phi = draw(st.one_of(reduced, st.floats(-1e3, 1e6)))
        v = draw(_log_uniform(1e3, 1e6))
        return (phi, v, eps) if _is_departure(phi, v, eps) else None
    elif kind == "unreduced_phase":
        phi = draw(st.one_of(st.floats(1e3, 1e6), st.floats(-1e6, -1e3)))
        eps, w0 = draw(eps_s), draw(moderate_w0)
    elif kind == "tiny_eps":
        eps, phi, w0 = draw(_log_uniform(1e-12, 1e-6)), draw(reduced), draw(moderate_w0)
    elif kind == "huge_eps":
        eps = draw(st.floats(10.0, max(10.0, eps_max)))
        phi, w0 = draw(reduced), draw(moderate_w0)
    else:
        phi, eps, w0 = draw(st.sampled_from(_SPECIAL_PHASES)), draw(eps_s), draw(moderate_w0)
    v = w0 - eps * math.sin(phi)
    return (phi, v, eps) if _is_departure(phi, v, eps) else None


def hard_cases(eps_max: float = 100.0):
    """Departures that break careless solvers, one kind per draw:

    small departure speed ``w0`` in ``[1e-12, 1e-3]`` (log-uniform; kappa ~ v/w0); huge ``v`` in
    ``[1e3, 1e6]`` (tau ~ 2v, cancellation in ``tau*(v - tau/2)``, eps up to ``eps_max``);
    unreduced phases ``1e3 <= |phi| <= 1e6``; tiny eps in ``[1e-12, 1e-6]``; huge eps in
    ``[10, eps_max]``; phases at and next to ``0``, ``pi`` and ``2*pi``.
    """
    if not (math.isfinite(eps_max) and eps_max > 0):
        raise ValueError(f"eps_max must be a finite positive number, got eps_max={eps_max!r}")
    return _hard_case(float(eps_max)).filter(lambda case: case is not None)


def clearances(sign: int = 0, smallest: float = 1e-9, largest: float = 1e-2):
    """Clearances of a near-graze: magnitudes spread over the decades ``[smallest, largest]``;
    ``sign`` -1 (close root pairs), +1 (near misses) or 0 (both)."""
    if sign not in (-1, 0, 1):
        raise ValueError(f"sign must be -1, 0 or 1, got sign={sign!r}")
    if not 0 < smallest <= largest < math.inf:
        raise ValueError(f"need 0 < smallest <= largest, got {smallest!r}, {largest!r}")
    magnitude = _log_uniform(smallest, largest)
    signs = st.sampled_from((-1.0, 1.0)) if sign == 0 else st.just(float(sign))
    return st.tuples(signs, magnitude).map(lambda p: p[0] * p[1])


@st.composite
def _grazing(draw, eps_s, clearance_s, dps, first):
    eps = draw(eps_s)
    # eps*cos(psi) = 1 + fraction*(eps - 1) > 1: the contact is a dip of d (a graze from above)
    fraction = draw(st.floats(0.1, 1.0))
    sign = draw(st.sampled_from((1.0, -1.0)))
    t_guess = draw(st.floats(0.5, 8.0))
    clearance = draw(clearance_s)
    psi = sign * math.acos((1.0 + fraction * (eps - 1.0)) / eps)
    try:
        contact = grazing_contact(eps, psi, t_guess, clearance, dps=dps)
    except ValueError:  # no departure leads to a contact near this guess
        return None
    phi, v = float(contact.phi), float(contact.v)
    if first:
        # below the plate (for clearance < 0) within ~sqrt(2*|clearance|/d''(T)) of T
        curvature = eps * math.cos(psi) - 1.0
        half_width = math.sqrt(2.0 * max(-clearance, 0.0) / curvature)
        if not _clear_before(phi, v, eps, min(0.98 * float(contact.T),
                                                float(contact.T) - 2.0 * half_width)):
            return None
    return (phi, v, eps) if _is_departure(phi, v, eps) else None


_GRID = 512


def _clear_before(phi, v, eps, t_end) -> bool:
    """Float64 grid heuristic (not a proof): the gap is positive on (0, t_end], so the dip
    after t_end is the first place the particle comes near the plate."""
    if not t_end > 0.0:
        return False
    for i in range(1, _GRID + 1):
        t = t_end * i / _GRID
        if 2.0 * eps * math.sin(phi + t / 2) * math.sin(t / 2) + t * (v - t / 2) <= 0.0:
            return False
    return True


def near_grazing(eps=(1.05, 10.0), *, clearance=None, first: bool = True, dps: int = 30):
    """Departures for ``eps > 1`` whose gap dips to ``clearance`` (a near-tangency).

    Built by :func:`verify.grazing_contact` from a plate phase with ``eps*cos(psi) > 1``: the
    gap has a local minimum of ``clearance`` (positive: the particle passes just above the
    plate; negative: two close roots, which a solver stepping in fixed increments jumps over).
    Default clearance: :func:`clearances` (``+-10**[-9, -2]``, log-uniform); below ~1e-12
    float64 inputs cannot tell a graze from a miss (their rounding moves the clearance by
    ~1e-16*T). With ``first`` (default) only departures whose gap stays positive before the
    dip are drawn (a float64 grid check, not a proof: ``verify.certify_flight`` decides the
    actual first root); otherwise the particle may land before it reaches the dip.
    """
    eps_s = _floats(eps, "eps")
    clearance_s = clearances() if clearance is None else _floats(clearance, "clearance")
    return _grazing(eps_s, clearance_s, dps, bool(first)).filter(lambda case: case is not None)


def _ints(spec, name):
    if isinstance(spec, st.SearchStrategy):
        return spec
    if isinstance(spec, int) and not isinstance(spec, bool):
        if spec < 1:
            raise ValueError(f"{name} must be >= 1, got {name}={spec!r}")
        return st.just(spec)
    try:
        lo, hi = (int(x) for x in spec)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an int, a (lo, hi) pair or a strategy, got {spec!r}") \
            from None
    if not 1 <= lo <= hi:
        raise ValueError(f"{name} range must satisfy 1 <= lo <= hi, got {name}={spec!r}")
    return st.integers(lo, hi)


def fixed_points(m=(1, 20), *, eps=(0.0, 10.0)):
    """Fixed points ``(0.0, m*pi, eps)`` of the collision map (``m = round(v/pi)``).

    ``v`` is the float nearest ``pi*m`` (up to one rounding), so the exact flight time of the
    float input is ``2*v`` to within ``~eps*(v - pi*m)**2/v``: for ``phi = 0`` exactly the gap
    ``eps*(1 - cos(t)) + t*(v - t/2)`` is positive on ``(0, 2*v)`` for every ``eps >= 0``.
    """
    return st.tuples(_ints(m, "m"), _floats(eps, "eps")).map(
        lambda p: (0.0, p[0] * math.pi, p[1])
    )


@st.composite
def _near_fixed(draw, m_s, eps_s, radius):
    m, eps = draw(m_s), draw(eps_s)
    dphi = draw(st.floats(-radius, radius))
    dv = draw(st.floats(-radius, radius))
    phi, v = dphi, m * math.pi + dv
    return (phi, v, eps) if _is_departure(phi, v, eps) else None


def near_fixed_point(m=(1, 10), *, eps=(0.0, 10.0), radius: float = 1e-3):
    """Departures within ``radius`` (in phi and in v) of a fixed point ``(0, pi*m)``.

    The fixed points of the exact map: ``tau = 2*pi*m``, linearisation
    ``[[1, 2], [-2*eps, 1 - 4*eps]]``, elliptic for ``0 < eps < 1``, hyperbolic for ``eps > 1``.
    """
    if not (math.isfinite(radius) and radius >= 0):
        raise ValueError(f"radius must be a finite number >= 0, got radius={radius!r}")
    return _near_fixed(_ints(m, "m"), _floats(eps, "eps"), float(radius)).filter(
        lambda case: case is not None
    )


def large_velocities(v=(30.0, 1e6), eps=(0.0, 10.0)):
    """Departures with large ``v`` (log-uniform), any phase: the Holmes regime ``tau ~ 2v``."""
    v_s = _log_uniform(*v) if isinstance(v, tuple) else _floats(v, "v", positive=True)

    @st.composite
    def _case(draw):
        eps_ = draw(_floats(eps, "eps"))
        phi = draw(_phases(True))
        v_ = draw(v_s)
        return (phi, v_, eps_) if _is_departure(phi, v_, eps_) else None

    return _case().filter(lambda case: case is not None)


@st.composite
def _triple(draw, eps_s, x_s):
    eps, x = draw(eps_s), draw(x_s)
    return (-x, x, eps) if _is_departure(-x, x, eps) else None


def near_triple_root(eps=(1.0 - 1e-6, 1.0), *, x=(1e-8, 10.0)):
    """Departures ``(-x, x, eps)``: the near-triple roots, the hardest well-posed flights.

    ``d(2x) = eps*(cos(x) - cos(x)) + 2x*(x - x) = 0`` holds exactly for the float inputs, so
    for ``|eps| <= 1`` (d concave, one positive root) the exact flight time is ``2*x``. With
    ``d'(2x) = eps*sin(x) - x`` (``~ -x**3/6`` at eps = 1) the root is a near-triple root for
    small ``x`` and eps near 1 (kappa ~ 6/x**2). ``x`` is drawn log-uniformly from the ``x``
    range (default ``[1e-8, 10]``), eps from the ``eps`` range (default ``[1 - 1e-6, 1]``).
    For eps > 1 only draws with ``w0 = x - eps*sin(x) > 0`` are kept, and ``2x`` is a root
    but not necessarily the first.
    """
    if isinstance(x, tuple):
        lo, hi = (float(b) for b in x)
        if not (0 < lo <= hi and math.isfinite(hi)):
            raise ValueError(f"x range must satisfy 0 < lo <= hi < inf, got x={x!r}")
        x_s = _log_uniform(lo, hi)
    else:
        x_s = _floats(x, "x", positive=True)
    return _triple(_floats(eps, "eps"), x_s).filter(lambda case: case is not None)


@st.composite
def _huge_phase(draw, eps_s, exponents, w0_s):
    sign = draw(st.sampled_from((-1.0, 1.0)))
    exponent = draw(st.integers(*exponents))
    phi = sign * draw(st.floats(1.0, 10.0, exclude_max=True)) * 10.0 ** exponent
    eps, w0 = draw(eps_s), draw(w0_s)
    with working_dps(_W0_DPS):  # mpmath reduces huge phases exactly (libm does too)
        v = float(w0 - mp.mpf(eps) * mp.sin(mp.mpf(phi)))
    return (phi, v, eps) if _is_departure(phi, v, eps) else None


def huge_phases(eps=(0.0, 10.0), *, exponent=(12, 307), w0=(1e-3, 30.0)):
    """Departures with huge unreduced phases ``|phi| = m*10**k``, ``k`` in ``exponent``
    (default 12..307, both signs): reducing them modulo 2*pi needs about ``k*log2(10)`` more
    bits than the phase holds. ``v`` is set from the exact ``sin(phi)`` so that ``w0`` lies in
    the ``w0`` range (up to the rounding of ``v``)."""
    lo, hi = exponent
    if not (isinstance(lo, int) and isinstance(hi, int) and 0 <= lo <= hi <= 307):
        raise ValueError(f"exponent must be a pair of ints 0 <= lo <= hi <= 307, "
                         f"got exponent={exponent!r}")
    return _huge_phase(_floats(eps, "eps"), (lo, hi), _speeds(w0)).filter(
        lambda case: case is not None
    )
