"""The package's folders are its layers: each imports only from the layers below it.

Every module's imports are read from its source (module level and inside
functions).  A module in layer ``k`` may import the package's modules of layers
``<= k`` only; ``codegen`` (development time) is imported by nothing at run time.
Function-level imports of the package's own modules are listed: each one must
be for a heavy optional dependency's sake, never to dodge a cycle.
"""

from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src" / "quadric_contact"
ORDER = [
    "_generated",
    "exact",
    "model",
    "theory",
    "modes",
    "families",
    "scenes",
    "paper",
    "testing",
    "interfaces",
]
APART = {"codegen"}
# top-level modules and the layer they count as
TOP = {"__init__": "interfaces", "__main__": "interfaces"}
# (importer, imported) pairs allowed although they go up a layer (each with its reason); empty is the goal
ALLOWED_UPWARD: set[tuple[str, str]] = set()


def layer_of(module: str) -> str:
    parts = module.split(".")
    assert parts[0] == "quadric_contact", module
    if len(parts) == 1:
        return "interfaces"
    head = parts[1]
    if head in ORDER or head in APART:
        return head
    return TOP.get(head, head)


def module_name(path: Path) -> str:
    rel = path.relative_to(SRC.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def imports(path: Path) -> list[tuple[int, str, bool]]:
    """(line, imported module, inside a function) for the package's own imports."""
    tree = ast.parse(path.read_text())
    me = module_name(path).split(".")
    is_pkg = path.name == "__init__.py"
    out = []

    def visit(node: ast.AST, in_function: bool) -> None:
        for child in ast.iter_child_nodes(node):
            inner = in_function or isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            if isinstance(child, ast.ImportFrom):
                if child.level:
                    base = me if is_pkg else me[:-1]
                    base = base[: len(base) - (child.level - 1)] if child.level > 1 else base
                    target = ".".join(base + ([child.module] if child.module else []))
                else:
                    target = child.module or ""
                if target.split(".")[0] == "quadric_contact":
                    for alias in child.names:
                        full = f"{target}.{alias.name}"
                        candidate = SRC.parent / (full.replace(".", "/") + ".py")
                        package = SRC.parent / full.replace(".", "/") / "__init__.py"
                        known = candidate.exists() or package.exists()
                        out.append((child.lineno, full if known else target, inner))
            elif isinstance(child, ast.Import):
                for alias in child.names:
                    if alias.name.split(".")[0] == "quadric_contact":
                        out.append((child.lineno, alias.name, inner))
            visit(child, inner)

    visit(tree, False)
    return out


MODULES = sorted(p for p in SRC.rglob("*.py") if "_generated" not in p.parts or p.name != "__init__.py")


def violations() -> tuple[list[str], list[str]]:
    upward, function_level = [], []
    for path in MODULES:
        me = module_name(path)
        mine = layer_of(me)
        for line, target, inner in imports(path):
            theirs = layer_of(target)
            where = f"{path.relative_to(SRC.parent)}:{line} imports {target}"
            if inner and layer_of(target) != "interfaces":
                function_level.append(where)
            if theirs in APART and mine not in APART and mine != "interfaces":
                upward.append(f"{where} (the code generator at run time)")
                continue
            if mine in APART or theirs in APART:
                continue
            if ORDER.index(theirs) > ORDER.index(mine) and (me, target) not in ALLOWED_UPWARD:
                upward.append(f"{where} ({mine} -> {theirs})")
    return upward, function_level


def test_every_module_has_a_layer():
    for path in MODULES:
        layer = layer_of(module_name(path))
        assert layer in ORDER or layer in APART, f"{path}: no layer"


def test_each_layer_imports_only_from_the_layers_below():
    upward, _ = violations()
    assert not upward, "imports that go up a layer:\n" + "\n".join(upward)


def test_the_formulas_import_nothing_of_the_package():
    for path in (SRC / "_generated").glob("*.py"):
        assert not imports(path), path
