"""The computations the claims, checks and figures read: the runs behind the figures, sampled
and followed particles, islands, escape regimes, joint (n, t) samples, the Fermi, dissipation
and dynamics studies, and the shared estimators (slopes, block bootstraps, verify spot checks)."""
