"""Scene TOML texts shared by the run tests (one copy, not one per file)."""

PORTRAIT = """
name = "portrait"
kind = "phase-space"
eps = 0.6
particles = 100
seed = 3
chunk_size = 50
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 30
[record]
phi_bins = 4
v_bins = 3
v_range = [0.0, 10.0]
verify_samples = 4
"""
