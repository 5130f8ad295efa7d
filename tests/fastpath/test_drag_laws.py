"""The drag laws live in one module each, reached through one dispatch
(``fastpath.dissipative.laws``): no other module of fastpath branches on the law code, every law
module defines every quantity with the same parameters, and each dispatch function hands its
arguments, unchanged, to the module of the law code it is given."""

import ast
import inspect
import types
from pathlib import Path

import pytest

import fastpath
from fastpath.dissipative import laws
from fastpath.physics import LAWS, NONE

PACKAGE = Path(fastpath.__file__).resolve().parent
DISPATCH = Path(laws.__file__).resolve()
CODE_NAMES = {"NONE", "LINEAR", "QUADRATIC"}  # the law codes of fastpath.physics


def _is_law(node):
    """A value that holds a law code: a name ``law``, ``drag_law``, ``*_law``; ``x.drag_law``."""
    if isinstance(node, ast.Name):
        return node.id in ("law", "drag_law") or node.id.endswith("_law")
    return isinstance(node, ast.Attribute) and node.attr == "drag_law"


def _is_code(node):
    """A law code: LINEAR, QUADRATIC, NONE (as a name or an attribute) or an int literal."""
    if isinstance(node, ast.Name):
        return node.id in CODE_NAMES
    if isinstance(node, ast.Attribute):
        return node.attr in CODE_NAMES
    return isinstance(node, ast.Constant) and type(node.value) is int


def law_branches(source):
    """(line, text) of each comparison of a law with a law code, and of each import of the
    LINEAR or QUADRATIC code from fastpath.physics, in a module's source."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Compare):
            operands = [node.left, *node.comparators]
            if any(_is_law(x) for x in operands) and any(_is_code(x) for x in operands):
                found.append((node.lineno, ast.unparse(node)))
        elif isinstance(node, ast.ImportFrom) and node.module == "fastpath.physics":
            codes = [a.name for a in node.names if a.name in ("LINEAR", "QUADRATIC")]
            if codes:
                found.append((node.lineno, f"import {', '.join(codes)}"))
    return sorted(found)


def test_the_scan_finds_the_branches_it_is_meant_to_find():
    source = ("from fastpath.physics import LINEAR, NONE\n"
              "x = 1 if law == LINEAR else 2\n"
              "y = physics.drag_law != physics_codes.QUADRATIC\n"
              "z = drag_law == 2\n"
              "ok = drag_law == DEFAULT_DRAG_LAW or law_name in names\n")
    assert [line for line, _ in law_branches(source)] == [1, 2, 3, 4]


def test_no_module_outside_the_dispatch_branches_on_the_drag_law():
    offenders = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path.resolve() in (DISPATCH, PACKAGE / "physics.py"):
            continue
        for line, text in law_branches(path.read_text()):
            offenders.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {text}")
    assert offenders == []


def test_every_law_code_has_a_module_and_every_module_every_quantity():
    assert set(laws.LAW_MODULES) == {NONE, *LAWS.values()}
    for module in laws.LAW_MODULES.values():
        for name in laws.QUANTITIES:
            assert callable(getattr(module, name, None)), (module.__name__, name)
            law_parameters = list(inspect.signature(getattr(module, name).py_func).parameters)
            dispatch_parameters = list(inspect.signature(getattr(laws, name).py_func).parameters)
            # the dispatch takes the law's parameters in the same order, plus the code
            assert [p for p in dispatch_parameters if p != "law"] == law_parameters, name
    # every law function of a module is a registered quantity
    for module in laws.LAW_MODULES.values():
        public = {name for name, value in vars(module).items()
                  if not name.startswith("_") and hasattr(value, "py_func")
                  and value.py_func.__module__ == module.__name__}
        helpers = {"fall", "frame_force", "bisect", "extrema"}  # quadratic's own steps
        assert public - helpers <= set(laws.QUANTITIES), module.__name__


@pytest.mark.parametrize("name", laws.QUANTITIES)
def test_each_dispatch_function_hands_its_arguments_to_the_module_of_the_code(name, monkeypatch):
    """The dispatch's Python function with the law modules replaced by recorders: the call goes
    to the module of the code given, with the other arguments unchanged and in order."""
    calls = []

    def recorder(module_name):
        def record(*args):
            calls.append((module_name, args))
            return module_name
        return types.SimpleNamespace(**{q: record for q in laws.QUANTITIES})

    dispatch = getattr(laws, name).py_func
    for module in laws.LAW_MODULES.values():
        monkeypatch.setitem(dispatch.__globals__, module.__name__.rsplit(".", 1)[1],
                            recorder(module.__name__))
    parameters = list(inspect.signature(dispatch).parameters)
    for code, module in laws.LAW_MODULES.items():
        del calls[:]
        arguments = [code if p == "law" else f"<{p}>" for p in parameters]
        assert dispatch(*arguments) == module.__name__
        assert calls == [(module.__name__, tuple(a for p, a in zip(parameters, arguments,
                                                                   strict=True)
                                                 if p != "law"))]
