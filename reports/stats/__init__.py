"""Survival-law inference on binned, censored escape counts (likelihood fits, model choice)."""
