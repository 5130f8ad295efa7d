"""Statistics on run outputs: survival-law inference on binned, censored escape counts
(likelihood fits, model choice, regimes, calibration), least-squares fits kept for
``bouncer plot --fit``, and the survival figure of a run."""
