"""The exact collision map (phi, v) -> (phi1, v1) of the paper's equations (1)-(2).

After the flight time tau (``solve_flight``), with plate velocity u = -eps*sin(phi + tau) and
incoming velocity v_in = v - tau, the elastic impact gives

    phi1 = (phi + tau) mod 2*pi,      v1 = 2*u - v_in = tau - v - 2*eps*sin(phi + tau).

phi1 is reduced from the exact sum phi + tau (+ the remainder of a long flight's root,
``fastpath.elastic.landing``): a few ulps of 2*pi at any speed.
"""


from fastpath.arithmetic.jit import jit
from fastpath.arithmetic.phase import centre_phase
from fastpath.arithmetic.rounding import UNIT_ROUNDOFF
from fastpath.arithmetic.sincos import sin_cos
from fastpath.elastic.flight import AUTO, departure_phase, flight_from, phase_error_of
from fastpath.elastic.landing import landing_phase

CARRIED_SINE_ERROR = 8.0 * UNIT_ROUNDOFF  # sine carried across collisions (rotation, Newton)


@jit
def collide(phi, v, eps, method=AUTO):
    """Return (phi1, v1, tau, iterations, status) for one flight and impact.

    The sine and cosine are computed here from the centred phase by ``fastpath.arithmetic.sincos``
    (the ensembles' lanes do the same): its error beyond libm's and the centring's are added.
    """
    centred, phase_error = departure_phase(phi)
    sin_phi, cos_phi = sin_cos(centred)
    phi1, _, _, v1, tau, iterations, status = collide_from(
        centred, sin_phi, cos_phi, v, eps, method, phase_error
    )
    return phi1, v1, tau, iterations, status


@jit
def collide_from(phi, sin_phi, cos_phi, v, eps, method=AUTO, sine_error=CARRIED_SINE_ERROR):
    """(phi1, sin(phi1), cos(phi1), v1, tau, iterations, status) for phi in [-pi, 2*pi).

    Takes and returns the sine and cosine of the phase, so that a chain of collisions calls
    libm's sine and cosine once per collision; ``sine_error`` bounds the absolute error of the
    given sine (a few u when carried, ``CARRIED_SINE_ERROR``).
    """
    centred = centre_phase(phi)
    phase_error = phase_error_of(phi, centred) + sine_error
    tau, tau_lo, sin1, cos1, iterations, status = flight_from(
        centred, sin_phi, cos_phi, v, eps, method, phase_error
    )
    phi1 = landing_phase(phi, tau, tau_lo)
    v1 = tau - v - 2.0 * eps * sin1
    return phi1, sin1, cos1, v1, tau, iterations, status
