"""Which properties exist, the suites that group them, and how many inputs each draws."""

PROPERTIES = (
    "no_overstep", "accuracy", "fixed_points", "energy", "holmes_limit", "reversibility",
)
SUITES = ("all", "fast", *PROPERTIES)
NEEDS_STEP = ("energy",)
DEFAULT_EXAMPLES = {"all": 100, "fast": 20}  # per property; a single property runs as "all"


def properties_of(suite: str) -> tuple[str, ...]:
    if suite in ("all", "fast"):
        return PROPERTIES
    return (suite,)


def check_suite(suite) -> str:
    if suite not in SUITES:
        raise ValueError(f"suite must be one of {', '.join(SUITES)}; got {suite!r}")
    return suite
