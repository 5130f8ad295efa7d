"""The seed's figures, one module per figure, and the physics checks against published results."""
