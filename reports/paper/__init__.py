"""The paper's figures and claims (one module per figure, the register of claims, their rules
and evaluators) and the physics checks against published results."""
