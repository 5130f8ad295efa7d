"""Building blocks of the reference: mpmath precision and intervals, exact inputs, exact phase
reduction, and the candidate-and-proof search for the first root of a gap.

Nothing here knows the bouncer's physics beyond "a gap ``d(t)`` that starts positive":
:mod:`verify.elastic` and :mod:`verify.dissipative` supply the gaps.
"""
