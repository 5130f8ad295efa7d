"""The loops over many collisions and many particles, each taking the physics description
(``fastpath.physics``) and compiled once per description class.

``particle``   one particle of any description: begin, advance by one collision, depart.
``orbit``      the orbit loop of ``fastpath.orbit``.
``escape``     escape and transport ensembles, recording histograms only.
``moments``    velocity moments of many particles (``moments``).
``portrait``   the phase-space portrait, a histogram of the collision states.
``histogram``  histogram bins and the holes of the escape kernels.
``records``    what a kernel records of one particle besides its counts (flags, samples).
``arrays``     the named groups of arrays the kernels take and fill.
``threads``    groups of blocks of particles, one Python thread each.

Nothing is imported here: a module compiles its kernels when they are first called.
"""
