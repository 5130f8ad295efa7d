"""The elastic bouncer of the paper: the gap of one flight (:mod:`.gap`, the paper's flight
equation), the certificate of its first root (:mod:`.certificate`), the condition number of the
flight time (:mod:`.conditioning`) and departures built to graze the plate (:mod:`.grazing`).
The map itself, equations (1)-(2), is :func:`verify.step` (:mod:`verify.collision`)."""
