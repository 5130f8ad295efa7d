"""No overstepped collision: the fast flight time is the FIRST root, as verify certifies it.

Random valid departures (eps in (0, 10], reduced and unreduced phases, w0 drawn and v derived)
and, for eps > 1, departures built by ``verify.grazing_contact`` to graze or nearly graze. Each
fast answer is judged by ``fastpath_reference.flight_outcome``: CONVERGED must agree with
verify's certified first root within K*kappa*u; UNCERTAIN/MAX_ITERATIONS is allowed only where
the dip of the exact gap is within a few gap_error of zero; a CONVERGED wrong root never is.
"""

import math

import pytest
from fastpath_figures import FIGURES, bump
from fastpath_reference import assert_flight_ok
from fastpath_tolerances import exact_w0
from hypothesis import assume, example, given
from hypothesis import strategies as st

TWO_PI = 2.0 * math.pi
CLEARANCES = (1e-2, 1e-6, 1e-10, 0.0, -1e-10, -1e-6)

eps_values = st.floats(min_value=0.0, max_value=10.0, exclude_min=True, allow_subnormal=False)
phases = st.one_of(
    st.floats(min_value=0.0, max_value=TWO_PI, exclude_max=True),
    st.floats(min_value=-1e3, max_value=1e6),  # unreduced
)
departure_speeds = st.one_of(
    st.floats(min_value=1e-3, max_value=30.0), st.floats(min_value=1e-10, max_value=1e-3)
)


@given(phi=phases, w0=departure_speeds, eps=eps_values)
@example(phi=4.0, w0=3.0 + 0.6 * math.sin(4.0), eps=0.6)
@example(phi=1e6 + 0.3, w0=1e-9, eps=3.0)
def test_random_departures_agree_with_verify(phi, w0, eps):
    v = w0 - eps * math.sin(phi)
    assume(exact_w0(phi, v, eps) > 0)  # the float v may round w0 to <= 0
    out = assert_flight_ok(phi, v, eps)
    bump("random departures: flights judged")
    if out.status != "CONVERGED":
        bump("random departures: UNCERTAIN/MAX_ITERATIONS (justified)")


@pytest.mark.slow
@given(
    eps=st.floats(min_value=1.05, max_value=10.0),
    fraction=st.floats(min_value=0.1, max_value=1.0),
    sign=st.sampled_from([1.0, -1.0]),
    t_guess=st.floats(min_value=0.5, max_value=8.0),
)
@example(eps=3.0, fraction=1.0, sign=1.0, t_guess=5.0)
# phi = -0.3427 is reduced to 5.94 inside fastpath: a gap_error scaled with 5.94 instead of 0.34
# would put tau off by 19 kappa*u (kappa at the caller's phi). Also in hard_cases.HARD_CASES as
# "negative-phase-short-graze".
@example(eps=1.05, fraction=0.125, sign=-1.0, t_guess=1.0)
# A dip at float resolution (minimum -1.4e-17) whose computed discriminant is -1.6e-19: read as
# "no root" it would jump to tau = 4.93 over the first root 0.4453. The lower models take d, d' and
# d'' at their rounding bounds.
@example(eps=2.0, fraction=0.25, sign=-1.0, t_guess=1.0)
def test_grazing_departures_never_converge_to_a_wrong_root(eps, fraction, sign, t_guess):
    """eps*cos(psi) = 1 + fraction*(eps - 1) > 1: the contact is a dip (a graze from above)."""
    import verify

    psi = sign * math.acos((1.0 + fraction * (eps - 1.0)) / eps)
    for clearance in CLEARANCES:
        try:
            contact = verify.grazing_contact(eps, psi, t_guess, clearance)
        except ValueError:  # no departure leads to a contact near this guess
            assume(False)
        phi, v = float(contact.phi), float(contact.v)
        assume(exact_w0(phi, v, eps) > 0)
        out = assert_flight_ok(phi, v, eps)
        bump(f"grazing (hypothesis): flights at clearance {clearance:g}")
        if out.status != "CONVERGED":
            bump(f"grazing (hypothesis): UNCERTAIN/MAX_ITERATIONS at clearance {clearance:g}")


@pytest.mark.parametrize("clearance", CLEARANCES)
@pytest.mark.parametrize(
    "eps, psi, t_guess", [(1.5, 0.3, 4.0), (3.0, -0.3, 2.0), (10.0, -0.5, 3.0)]
)
def test_grazing_grid(eps, psi, t_guess, clearance):
    """A fixed grid of grazing departures (reproducible UNCERTAIN counts)."""
    import verify

    contact = verify.grazing_contact(eps, psi, t_guess, clearance)
    phi, v = float(contact.phi), float(contact.v)
    out = assert_flight_ok(phi, v, eps)
    bump("grazing grid: flights")
    if out.status != "CONVERGED":
        bump("grazing grid: UNCERTAIN/MAX_ITERATIONS")
        FIGURES.setdefault("grazing grid: uncertain cases", []).append(
            f"eps={eps} psi={psi} clearance={clearance:g}"
        )
