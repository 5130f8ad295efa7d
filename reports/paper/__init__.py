"""The paper's part of the report, in five subpackages: ``claims`` (the register of the paper's
claims, their rules and the modules that decide them), ``studies`` (the computations the claims
and figures read), ``checks`` (physics checks against published results), ``figures`` (one
module per figure, named after the file it writes) and ``sections`` (the report sections they
make)."""
