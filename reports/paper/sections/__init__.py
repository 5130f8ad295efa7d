"""The report's sections that come from the paper: its figures with their claims, the dynamics
section and the physics checks. Each module returns the section's Markdown (and its claims)."""
