"""One argument order inside fastpath (docs/fastpath.md): the state first, then the physics
description or eps, then the rest, as in ``gap(phi, v, eps, t)``."""

import ast
from pathlib import Path

FASTPATH = Path(__file__).resolve().parents[2] / "fastpath"
# names that stand for (a part of) one particle's state
STATE = {"phi", "v", "phi0", "v0", "sin_phi", "cos_phi", "w", "theta", "sin_theta", "cos_theta",
         "phase0", "centred", "carried", "state"}
PHYSICS = {"physics", "eps"}


def _signatures():
    for path in sorted(FASTPATH.rglob("*.py")):
        tree = ast.parse(path.read_text(), str(path))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef):
                names = [a.arg for a in node.args.posonlyargs + node.args.args]
                yield f"{path.relative_to(FASTPATH.parent)}:{node.name}", names


def _out_of_order(names):
    where = [i for i, n in enumerate(names) if n in PHYSICS]
    if not where:
        return []
    first = where[0]
    return [n for n in names[first + 1:] if n in STATE and n != "carried"]


def test_state_comes_before_the_description_in_every_fastpath_function():
    wrong = {name: names for name, names in _signatures() if _out_of_order(names)}
    assert wrong == {}


def test_the_order_check_sees_a_description_first_signature():
    assert _out_of_order(["physics", "phi", "v"]) == ["phi", "v"]
    assert _out_of_order(["eps", "phi", "v", "t"]) == ["phi", "v"]
    assert _out_of_order(["phi", "v", "eps", "t"]) == []
