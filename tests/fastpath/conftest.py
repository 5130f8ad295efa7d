"""Print the figures the fastpath suite measured (see ``fastpath_figures``) after the run."""

from fastpath_figures import FIGURES


def pytest_terminal_summary(terminalreporter):
    if not FIGURES:
        return
    terminalreporter.section("fastpath figures")
    for name in sorted(FIGURES):
        terminalreporter.write_line(f"{name}: {FIGURES[name]}")
