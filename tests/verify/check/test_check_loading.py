"""verify.check.loading: MODULE:FUNCTION and path.py:FUNCTION specs; one-line ValueErrors.

Importing fastpath here is fine: only ``verify/`` itself must not import it.
"""

import pytest

import fastpath
import verify
from examples import planted_defects


def test_load_callable(tmp_path, monkeypatch):
    assert verify.check.load_callable("examples.planted_defects:holmes_flight_time") is \
        planted_defects.holmes_flight_time
    assert verify.check.load_callable("fastpath:flight_time") is fastpath.flight_time
    assert verify.check.load_callable("os.path:join.__call__")  # dotted attributes
    by_path = verify.check.load_callable("examples/planted_defects.py:holmes_flight_time")
    assert by_path(0.0, 1.5, 0.6) == 3.0
    (tmp_path / "mysolver.py").write_text("def tau(phi, v, eps):\n    return 2.0 * v\n")
    monkeypatch.chdir(tmp_path)
    assert verify.check.load_callable("mysolver:tau")(0.0, 2.0, 0.1) == 4.0
    bad = {
        "nocolon": "MODULE:FUNCTION",
        ":f": "MODULE:FUNCTION",
        "no_such_module_xyz:f": "cannot import module",
        "math:no_such_function": "has no attribute",
        "math:pi": "not callable",
        "missing_file.py:f": "no such file",
    }
    for spec, text in bad.items():
        with pytest.raises(ValueError, match=text):
            verify.check.load_callable(spec)
    (tmp_path / "broken.py").write_text("raise ImportError('needs a GPU')\n")
    with pytest.raises(ValueError, match="needs a GPU"):
        verify.check.load_callable("broken:f")
