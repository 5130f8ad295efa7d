"""How many bootstrap replicates the paper's studies and claims draw, each count defined here
once. Their random streams are the seeds of ``reports.paper.studies.seeds``.

The percentile intervals below are the 2.5% and 97.5% percentiles of the replicates; a
resampling whose statistic is not a number for half the replicates or more gives no interval.
"""

# the standard deviation of a statistic over resampled particle blocks
# (``sampling.bootstrap_blocks``): a standard deviation from B replicates has a relative error of
# about 1/sqrt(2 B), 3.5% at 400, below the two digits its error bars print
BLOCK_SD_REPLICATES = 400

# the 95% percentile intervals of the claims and of the joint (n, t) samples: 200 replicates put
# five whole replicates beyond each end of the interval
INTERVAL_REPLICATES = 200

# the 95% percentile intervals of the closed system's tail fits (the saddle-point claims): each
# replicate redraws and refits a whole sample of up to 100,000 orbit times, so these intervals
# are read from half as many replicates (2.5 beyond each end)
TAIL_FIT_REPLICATES = 100
