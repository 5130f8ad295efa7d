"""Load the user's callable from ``"MODULE:FUNCTION"`` or ``"path/to/file.py:FUNCTION"``."""

from __future__ import annotations

import importlib
import importlib.util
import os
import sys
from collections.abc import Callable


def load_callable(spec: str, *, search_cwd: bool = True) -> Callable:
    """``"MODULE:FUNCTION"`` -> the callable it names.

    MODULE is a dotted module name (``mypkg.solvers``) or a path to a ``.py`` file
    (``solvers/mine.py``); FUNCTION may be dotted (``Solver.flight_time``). With ``search_cwd``
    the current directory is put on ``sys.path`` first, so users can name their own files.
    Raises ``ValueError`` with a one-line message when the spec is malformed, the module
    cannot be imported (it raises, or calls ``sys.exit()``, while importing), the attribute is
    missing or is not callable.
    """
    module_name, attr = parse_spec(spec)
    if search_cwd:
        cwd = os.getcwd()
        if cwd not in sys.path and "" not in sys.path:
            sys.path.insert(0, cwd)
    module = _import(module_name)
    obj = module
    for part in attr.split("."):
        try:
            obj = getattr(obj, part)
        except AttributeError:
            raise ValueError(f"module {module_name!r} has no attribute {attr!r}") from None
    if not callable(obj):
        raise ValueError(f"{spec!r} is not callable (it is a {type(obj).__name__})")
    return obj


def parse_spec(spec: str) -> tuple[str, str]:
    """``"MODULE:FUNCTION"`` -> (MODULE, FUNCTION), without importing anything; ``ValueError``
    when the spec is malformed."""
    if not isinstance(spec, str):
        raise ValueError(f"expected MODULE:FUNCTION, got {spec!r}")
    module_name, sep, attr = spec.rpartition(":")
    if not sep or not module_name.strip() or not attr.strip():
        raise ValueError(f"expected MODULE:FUNCTION (e.g. mymodule:flight_time), got {spec!r}")
    return module_name.strip(), attr.strip()


def _import(module_name: str):
    is_path = module_name.endswith(".py") or "/" in module_name or os.sep in module_name
    try:
        if not is_path:
            return importlib.import_module(module_name)
        path = os.path.abspath(module_name)
        if not os.path.isfile(path):
            raise ValueError(f"cannot import module {module_name!r}: no such file")
        name = "_bouncer_user_" + os.path.splitext(os.path.basename(path))[0]
        spec = importlib.util.spec_from_file_location(name, path)
        if spec is None or spec.loader is None:
            raise ValueError(f"cannot import module {module_name!r}: not a Python file")
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        except BaseException:
            sys.modules.pop(name, None)
            raise
        return module
    except ValueError:
        raise
    except ModuleNotFoundError as err:
        raise ValueError(f"cannot import module {module_name!r}: {err}") from None
    except KeyboardInterrupt:
        raise
    except SystemExit as err:  # a script's sys.exit(): nothing of it was checked
        raise ValueError(
            f"importing module {module_name!r} called sys.exit({err.code!r}); a module to"
            " check must not exit when imported (put the script part under"
            " if __name__ == '__main__':)"
        ) from None
    except BaseException as err:  # the user's module raised while importing
        msg = str(err).splitlines()[0] if str(err) else ""
        raise ValueError(
            f"importing module {module_name!r} failed: {type(err).__name__}: {msg}"
        ) from None
