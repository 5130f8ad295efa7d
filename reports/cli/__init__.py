"""Subcommands of the ``bouncer`` command line."""
