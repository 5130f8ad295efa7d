"""Statistics on run outputs: fits of survival laws and the survival figure of a run."""
