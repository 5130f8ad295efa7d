"""The seeds of the paper's sampled studies and bootstraps, one per study, each defined here
once so that every study is deterministic and no two studies share a random stream. The built-in
scenes carry their own seeds (20120901 to 20120904 and 20120911, in their TOML files); the
studies here continue that series.
"""

SAMPLING_SEED = 20240605  # the ensembles of the physics checks, of the Section 2 claims and of
#                           the dissipation study; block bootstraps and verify spot checks
DYNAMICS_SEED = 20240607  # the dynamics study (starts of the Lyapunov and diffusion orbits)
FOLLOWED_SEED = 20120905  # the followed-particle studies (escape, transport, island box, sweeps)
JOINT_SEED = 20120906  # bootstraps of the joint (n, t) samples
TRANSPORT_JOINT_SEED = 20120907  # bootstraps of the transporting orbits' claims (Fig. 4)
SAME_POWER_SEED = 20120908  # bootstrap of the same-power claim (Fig. 2)
