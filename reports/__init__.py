"""Application layer: composes ``fastpath`` and ``verify`` into checked runs, the CLI, reports."""
