"""No evaluator in the package's source, except where the text is the package's own.

A static guard to go with the audit-hook tests of ``test_untrusted_input.py``: every call
of ``eval``, ``exec``, ``compile``, ``sympify``, ``parse_expr`` or ``S`` in
``src/quadric_contact`` is listed here with the reason it never sees user text.  A new
call fails this test until someone has checked it and added it with its reason.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "quadric_contact"
EVALUATORS = {"eval", "exec", "compile", "sympify", "parse_expr", "S", "__import__"}

# (module file name, function name) -> why its argument is not user text.
ALLOWED = {
    ("family_numeric.py", "exec"): "runs a program generated from integer coefficients and "
    "checked by _checked (straight-line code of the generator's grammar)",
    ("family_numeric.py", "compile"): "compiles the same generated, checked program",
    ("algebraic.py", "sympify"): "strict sympify of a sympy expression; text is refused just "
    "before it with EquationError",
    ("native.py", "exec"): "codegen/native.py, at build time: the C wrapper of a kernel, generated "
    "from the numba types of its arguments (names and numbers of its own making)",
    ("native.py", "compile"): "compiles the same generated wrapper",
}


def _calls(path: Path) -> list[tuple[str, int]]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else None
            if name in EVALUATORS:
                # re.compile and the like are not evaluators of Python text.
                if name == "compile" and isinstance(f, ast.Attribute):
                    continue
                found.append((name, node.lineno))
    return found


def _all_calls() -> list[tuple[str, str, int]]:
    return [(path.name, name, line) for path in sorted(SRC.rglob("*.py")) for name, line in _calls(path)]


def test_every_evaluator_call_is_known():
    unknown = [c for c in _all_calls() if (c[0], c[1]) not in ALLOWED]
    assert not unknown, f"evaluator calls not reviewed for user text: {unknown}"


@pytest.mark.parametrize("key", sorted(ALLOWED))
def test_the_allowed_calls_still_exist(key):
    # A stale entry would let a new call in the same place pass unreviewed.
    assert any((c[0], c[1]) == key for c in _all_calls()), key


def test_the_scan_finds_an_evaluator(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("import sympy\nsympy.sympify(text)\neval(x)\nre.compile('a')\n")
    assert [name for name, _ in _calls(bad)] == ["sympify", "eval"]
