"""reports/paper is laid out by what each module holds: every module in one of its subpackages,
a figure module named after the file it writes, claims decided only in ``*_claims`` modules, and
the subpackages import one another in one direction only.

Read from the sources (no module is run): a figure module's stems are the string literals it
passes to ``save_figure``; a claim is decided where ``make_claim`` or ``Claim`` is called.
"""

import ast
from pathlib import Path

import pytest

PAPER = Path(__file__).resolve().parents[3] / "reports" / "paper"
SUBPACKAGES = {"claims", "studies", "checks", "figures", "sections"}
FIGURE_HELPERS = {"style"}  # the drawing helpers the figures share; writes no file
PER_CLAIM_FOLDER = {"specification"}  # one plot per contested claim, in the folder of that name


def modules(folder):
    return sorted(p for p in folder.glob("*.py") if p.name != "__init__.py")


def calls(path, name):
    """The calls of ``name`` (a plain name or an attribute) in the module at ``path``."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            func = node.func
            if getattr(func, "id", None) == name or getattr(func, "attr", None) == name:
                yield node


def module_constant(path, name):
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == name
                                                for t in node.targets):
            return ast.literal_eval(node.value)
    return None


def test_every_module_of_reports_paper_sits_in_a_subpackage_that_says_what_it_holds():
    loose = [p.name for p in modules(PAPER)]
    assert loose == [], f"modules outside the subpackages of reports/paper: {loose}"
    folders = {p.name for p in PAPER.iterdir() if p.is_dir() and p.name != "__pycache__"}
    assert folders == SUBPACKAGES
    for name in SUBPACKAGES:
        init = PAPER / name / "__init__.py"
        assert init.exists() and ast.get_docstring(ast.parse(init.read_text())), name
        assert not list((PAPER / name).glob("*/*.py")), f"{name} is nested deeper"


@pytest.mark.parametrize("path", modules(PAPER / "figures"), ids=lambda p: p.stem)
def test_a_figure_module_is_named_after_the_file_it_writes(path):
    stems = {ast.literal_eval(c.args[2]) if isinstance(c.args[2], ast.Constant) else None
             for c in calls(path, "save_figure")}
    if path.stem in FIGURE_HELPERS:
        assert stems == set(), f"{path.name} is a helper and writes {stems}"
    elif path.stem in PER_CLAIM_FOLDER:
        assert stems == set() and module_constant(path, "FOLDER") == path.stem
    else:
        assert stems == {path.stem}, f"{path.name} writes {stems}, not {path.stem}"


def test_figures_are_written_only_by_the_figure_modules():
    elsewhere = [p.relative_to(PAPER).as_posix() for sub in SUBPACKAGES - {"figures"}
                 for p in modules(PAPER / sub) if list(calls(p, "save_figure"))]
    assert elsewhere == []


def test_claims_are_decided_only_in_the_claims_modules():
    deciding = {p.relative_to(PAPER).as_posix() for sub in SUBPACKAGES for p in modules(PAPER / sub)
                if list(calls(p, "make_claim")) or list(calls(p, "Claim"))}
    allowed = {"claims/register.py"}  # make_claim itself builds the Claim of an entry
    misplaced = sorted(m for m in deciding - allowed
                       if not (m.startswith("claims/") and m.endswith("_claims.py")))
    assert misplaced == [], f"claims decided outside a claims/*_claims.py module: {misplaced}"


# What each subpackage of reports/paper may import from reports.paper, read from the package:
# studies compute, and nothing above them feeds back into a computation; checks and claims
# judge the studies; figures draw the studies and mark what a claim decided (its verdict, its
# windows); sections assemble all of them into the report.
MAY_IMPORT = {
    "studies": {"studies"},
    "checks": {"studies", "checks"},
    "claims": {"studies", "claims"},
    "figures": {"studies", "claims", "figures"},
    "sections": SUBPACKAGES,
}


def paper_imports(path):
    """The subpackages of reports.paper the module at ``path`` imports (any import statement,
    at module level or inside a function)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names = [node.module] + [f"{node.module}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        else:
            continue
        for name in names:
            parts = name.split(".")
            if parts[:2] == ["reports", "paper"] and len(parts) > 2 and parts[2] in SUBPACKAGES:
                found.add(parts[2])
    return found


def test_subpackages_import_only_downwards():
    """Besides their own subpackage, studies import none of reports/paper (in particular no
    claims: claims are built from studies, never the other way); checks and claims import only
    studies; figures studies and claims; sections any of them."""
    assert set(MAY_IMPORT) == SUBPACKAGES
    upward = sorted(f"{p.relative_to(PAPER).as_posix()} imports {sorted(extra)}"
                    for sub in SUBPACKAGES for p in modules(PAPER / sub)
                    if (extra := paper_imports(p) - MAY_IMPORT[sub]))
    assert upward == [], f"imports against the layering of reports/paper: {upward}"
