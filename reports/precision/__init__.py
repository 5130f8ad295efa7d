"""Precision comparison: the method registry, one case judged against ``verify``, work-precision,
the hard-case table and the speed benchmark."""
