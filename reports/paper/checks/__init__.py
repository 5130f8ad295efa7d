"""Physics checks against published results: Fermi acceleration, the rotation angle at the
elliptic fixed point, velocity diffusion against Rechester and White; one row each in the
physics-check table."""
