"""The error of the dynamics certificates."""


class NotCertified(ArithmeticError):
    """No periodic orbit could be proved near the guess (the message says which step failed).

    Raised instead of returning an orbit that is not proved: a guess with no periodic orbit of
    the given type within the tolerance, an orbit that is not isolated, a flight that cannot be
    certified, or a Krawczyk test that fails up to the largest precision allowed.
    """
