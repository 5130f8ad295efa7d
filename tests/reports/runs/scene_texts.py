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

# a transport scene small enough for any audit test (two exits, one width)
TINY = """
name = "tiny"
kind = "transport"
eps = 0.6
particles = 200
seed = 3
chunk_size = 64
[start]
v = [2.0, 4.0]
[holes]
centres = [0.0, 3.141592653589793]
widths = [1.0]
[horizon]
collisions = 200
"""

# a velocity scene with r = 1 and r = 0.9
SMALL_VELOCITY = """
name = "small-velocity"
kind = "velocity"
eps = 2.0
particles = 300
seed = 3
chunk_size = 64
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 300
[record]
bins_per_decade = 5
verify_samples = 30
[physics]
restitution = [1.0, 0.9]
"""

# an escape scene where most particles stick for good (restitution 0.5)
STICK = """
name = "stick"
kind = "escape"
eps = 0.6
particles = 400
seed = 5
chunk_size = 200
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.3]
[horizon]
collisions = 2000
time = 1e5
[record]
verify_samples = 20
[physics]
restitution = 0.5
"""

# a velocity scene of 100 particles with r = 1 and r = 0.9
TINY_VELOCITY = """
name = "tiny-velocity"
kind = "velocity"
eps = 2.0
particles = 100
seed = 3
chunk_size = 50
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[horizon]
collisions = 100
[record]
bins_per_decade = 5
verify_samples = 6
[physics]
restitution = [1.0, 0.9]
"""

# a phase-space scene of 300 particles over 12 collisions, on a 36 x 24 grid
PORTRAIT_300 = """
name = "portrait-settle"
kind = "phase-space"
eps = 0.6
particles = 300
seed = 5
[start]
phi = [0.0, 6.283185307179586]
v = [1.0, 6.0]
[horizon]
collisions = 12
[record]
phi_bins = 36
v_bins = 24
v_range = [0.0, 8.0]
"""

# an escape scene of 300 particles in chunks of 128, with both horizons
ESCAPE_300 = """
name = "plan-small"
kind = "escape"
eps = 0.6
particles = 300
seed = 5
chunk_size = 128
[start]
phi = [3.85, 4.15]
v = [2.0, 4.0]
[holes]
centres = [2.0]
widths = [0.3]
[horizon]
collisions = 40
time = 60.0
[record]
verify_samples = 20
"""

# the scene STICK with 200 particles (one chunk)
STICK_200 = STICK.replace("particles = 400", "particles = 200")
