"""The run engine: scenes, the run plan, chunks computed and verified, the driver (here or on a
Dask cluster), run directories, rechecks and sweeps. Imports only ``fastpath`` and ``verify``."""
