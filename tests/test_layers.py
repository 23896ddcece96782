"""The package's imports: its folders are its layers, the code generator stays development
time, and no import inside a function hides an import cycle.

An AST scan of every module of ``src/quadric_contact`` (imports at module level and
inside functions; an ``if TYPE_CHECKING:`` block is not run, so it does not count).

* A module of layer ``k`` (the folders, lowest first, in :data:`ORDER`) imports the
  package's modules of layers ``<= k`` only, and no layer below the interfaces imports
  the top package (the curated public API, which imports almost everything).
* Nothing imports :mod:`quadric_contact.codegen` but the ``codegen`` command of the
  command line (which runs the generator on request); the run-time code reads
  straight-line programs with :mod:`quadric_contact.exact.straight_line` and emits the
  families' programs with :mod:`quadric_contact.families.family_emit`.
* The graph of module-level imports has no cycle.
* An import inside a function is fine for a heavy or optional dependency (sympy,
  matplotlib, dask, numba, ...: not scanned here) or to keep a module light (the
  command line imports its commands only when they run), but never to dodge a cycle:
  for every function-level import of one of the package's modules, the imported
  module must not reach the importer through module-level imports (else the import
  could not move to the top of the file).

Edges to the top package ``quadric_contact`` (the curated public API, which imports
most modules) and from a module to its own enclosing packages are left out: Python
has already started those packages when the module runs.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = "quadric_contact"

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
"""The layers, lowest first (the README's layout table)."""
APART = {"codegen"}
"""Development time only: checked by the code generator tests below, not ordered."""

CODEGEN = f"{PACKAGE}.codegen"
CODEGEN_IMPORTERS = {f"{PACKAGE}.interfaces.cli.codegen"}
"""The only module allowed to import the generator: the ``quadric-contact codegen`` command."""


def is_codegen(module: str) -> bool:
    """The generator's package or one of its modules."""
    return module == CODEGEN or module.startswith(CODEGEN + ".")


@dataclass(frozen=True)
class Import:
    importer: str
    line: int
    target: str
    in_function: bool


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted((SRC / PACKAGE).rglob("*.py")):
        parts = list(path.relative_to(SRC).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


MODULES = _modules()


def _ancestors(module: str) -> set[str]:
    parts = module.split(".")
    return {".".join(parts[:i]) for i in range(1, len(parts))}


def _targets(node: ast.Import | ast.ImportFrom, module: str) -> Iterator[str]:
    """The package's modules an import statement runs (submodules named in a
    ``from package import name`` included)."""
    if isinstance(node, ast.Import):
        names = [a.name for a in node.names]
    else:
        if node.level:
            is_package = MODULES[module].name == "__init__.py"
            base = module.split(".")
            base = base[: len(base) - node.level + (1 if is_package else 0)]
            source = ".".join([*base, *([node.module] if node.module else [])])
        else:
            source = node.module or ""
        names = [f"{source}.{a.name}" if f"{source}.{a.name}" in MODULES else source for a in node.names]
    for name in names:
        if name == PACKAGE or not name.startswith(PACKAGE + "."):
            continue
        parts = name.split(".")
        for i in range(2, len(parts) + 1):
            prefix = ".".join(parts[:i])
            if prefix in MODULES:
                yield prefix


def _is_type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def _imports() -> list[Import]:
    found: list[Import] = []
    for module, path in MODULES.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))

        def walk(node: ast.AST, in_function: bool, module: str = module) -> None:
            for child in ast.iter_child_nodes(node):
                if _is_type_checking(child):
                    continue
                if isinstance(child, ast.Import | ast.ImportFrom):
                    for target in set(_targets(child, module)):
                        if target != module and target not in _ancestors(module):
                            found.append(Import(module, child.lineno, target, in_function))
                inner = in_function or isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda)
                walk(child, inner)

        walk(tree, False)
    return found


IMPORTS = _imports()


def _module_graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for imp in IMPORTS:
        if not imp.in_function:
            graph[imp.importer].add(imp.target)
    return graph


GRAPH = _module_graph()


def _reaches(start: str, goal: str) -> bool:
    seen, todo = {start}, [start]
    while todo:
        for nxt in GRAPH[todo.pop()]:
            if nxt == goal:
                return True
            if nxt not in seen:
                seen.add(nxt)
                todo.append(nxt)
    return False


def layer_of(module: str) -> str:
    """The layer of a module: its folder; the top package and ``__main__`` count as interfaces."""
    parts = module.split(".")
    head = parts[1] if len(parts) > 1 else "interfaces"
    return "interfaces" if head == "__main__" else head


def test_every_module_has_a_layer() -> None:
    lost = [m for m in MODULES if layer_of(m) not in ORDER and layer_of(m) not in APART]
    assert lost == [], f"modules outside the layers: {lost}"


def test_each_layer_imports_only_from_the_layers_below() -> None:
    upward = [
        f"{i.importer}:{i.line} imports {i.target} ({layer_of(i.importer)} -> {layer_of(i.target)})"
        for i in IMPORTS
        if layer_of(i.importer) in ORDER
        and layer_of(i.target) in ORDER
        and ORDER.index(layer_of(i.target)) > ORDER.index(layer_of(i.importer))
    ]
    assert upward == [], "imports that go up a layer:\n" + "\n".join(upward)


def test_no_layer_imports_the_top_package() -> None:
    """``from quadric_contact import X`` inside a layer would pull in the whole public API
    (the scan of ``IMPORTS`` leaves the top package out, as every module's ancestor)."""
    found = []
    for module, path in MODULES.items():
        if layer_of(module) == "interfaces":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            top = (isinstance(node, ast.ImportFrom) and node.level == 0 and node.module == PACKAGE) or (
                isinstance(node, ast.Import) and any(a.name == PACKAGE for a in node.names)
            )
            if top:
                found.append(f"{module}:{node.lineno}")
    assert found == [], found


def test_the_formulas_import_nothing_of_the_package() -> None:
    assert [i for i in IMPORTS if layer_of(i.importer) == "_generated"] == []


def test_the_scan_sees_the_imports() -> None:
    """The scan is not vacuous: it finds known imports of both kinds."""
    assert any(
        i.importer == f"{PACKAGE}.exact.rational"
        and i.target == f"{PACKAGE}.exact.reading"
        and not i.in_function
        for i in IMPORTS
    )
    assert any(i.importer in CODEGEN_IMPORTERS and is_codegen(i.target) and i.in_function for i in IMPORTS)
    assert any(i.in_function for i in IMPORTS) and any(not i.in_function for i in IMPORTS)
    assert _reaches(f"{PACKAGE}.families.family", f"{PACKAGE}.families.rational_functions")
    assert not _reaches(f"{PACKAGE}.families.rational_functions", f"{PACKAGE}.families.family")


def test_nothing_imports_the_code_generator_at_run_time() -> None:
    offenders = [
        f"{i.importer}:{i.line}"
        for i in IMPORTS
        if is_codegen(i.target) and not is_codegen(i.importer) and i.importer not in CODEGEN_IMPORTERS
    ]
    assert offenders == [], f"the code generator is development time only; imported by {offenders}"


def test_module_level_imports_have_no_cycle() -> None:
    cyclic = sorted(m for m in MODULES if _reaches(m, m))
    assert cyclic == [], f"modules on an import cycle: {cyclic}"


def test_no_function_level_import_dodges_a_cycle() -> None:
    dodging = sorted(
        f"{i.importer}:{i.line} -> {i.target}"
        for i in IMPORTS
        if i.in_function and _reaches(i.target, i.importer)
    )
    assert dodging == [], (
        "these imports inside functions hide an import cycle (the imported module imports the "
        f"importer at module level); break the cycle instead: {dodging}"
    )


@pytest.mark.parametrize(
    "modules",
    [
        # the modules that once imported the generator at run time
        "quadric_contact.families.family_numeric, quadric_contact.modes.smallness.binary64, "
        "quadric_contact.modes.stacks.batch, quadric_contact.testing.hardcases, "
        "quadric_contact.interfaces.benchmark, quadric_contact.modes.numbers.binary64",
        # what the tests import instead of the benchmark, and the command line
        "quadric_contact.testing.samples, quadric_contact.testing.peers, "
        "quadric_contact.testing.references, quadric_contact.interfaces.cli",
    ],
)
def test_importing_the_package_does_not_load_the_generator(modules: str) -> None:
    """Neither the generator's package nor any of its modules is loaded."""
    code = (
        f"import sys, quadric_contact, {modules}; "
        f"print(any(m == {CODEGEN!r} or m.startswith({CODEGEN + '.'!r}) for m in sys.modules))"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(SRC), os.environ.get("PYTHONPATH", "")])}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert out.stdout.strip() == "False", out.stderr


def _all_imports_graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for imp in IMPORTS:
        graph[imp.importer].add(imp.target)
    return graph


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iteratively)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    found: list[list[str]] = []
    counter = 0
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    top = stack.pop()
                    on.discard(top)
                    component.append(top)
                    if top == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_no_cycle_even_through_imports_inside_functions() -> None:
    """Within a folder (and so in the whole package: the layers order the folders), the graph of
    *every* import, at module level and inside functions, has no cycle: an import inside a
    function never closes a circle of modules that need one another."""
    cycles = _cycles(_all_imports_graph())
    assert cycles == [], "modules on an import cycle (imports inside functions counted):\n" + "\n".join(
        " -> ".join(c) for c in cycles
    )


def test_the_cycle_finder_finds_cycles() -> None:
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}, "e": set()}
    assert _cycles(graph) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


OPTIONAL = {
    "numba", "llvmlite", "sympy", "matplotlib", "PIL", "dask", "distributed", "flint", "mpmath",
    "coal", "fcl", "hppfcl", "nbformat", "nbclient", "playwright", "tqdm", "hypothesis", "fcntl",
    "resource", "IPython", "pytest", "scipy", "cProfile", "pstats", "tomllib",
}  # fmt: skip
"""Heavy or optional dependencies (or not on every platform) that a module may import where it
needs them, so that importing the package does not load them."""


def _function_level_imports() -> list[tuple[str, int, str, str]]:
    """``(module, line, imported module, the comment that says why)`` for every import inside a
    function of the package (an ``if TYPE_CHECKING:`` block aside)."""
    found = []
    for module, path in MODULES.items():
        text = path.read_text(encoding="utf-8")
        lines = text.splitlines()

        def walk(node: ast.AST, in_function: bool, module: str = module, lines: list[str] = lines) -> None:
            for child in ast.iter_child_nodes(node):
                if _is_type_checking(child):
                    continue
                if in_function and isinstance(child, ast.Import | ast.ImportFrom):
                    name = child.module or "" if isinstance(child, ast.ImportFrom) else child.names[0].name
                    if isinstance(child, ast.ImportFrom) and child.level:
                        name = PACKAGE
                    # the comment: on the line itself, or on the lines just above the group
                    why = lines[child.lineno - 1].partition("#")[2].strip()
                    k = child.lineno - 2
                    while not why and k >= 0 and lines[k].strip().startswith(("import ", "from ", "#")):
                        if lines[k].strip().startswith("#"):
                            why = lines[k].strip().lstrip("#").strip()
                        k -= 1
                    found.append((module, child.lineno, name, why))
                walk(
                    child,
                    in_function or isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda),
                )

        walk(ast.parse(text), False)
    return found


FUNCTION_IMPORTS = _function_level_imports()


def test_imports_inside_functions_are_optional_dependencies_or_commands() -> None:
    """An import inside a function is an optional or heavy dependency (:data:`OPTIONAL`) or, in
    the command line, a subcommand loaded when it runs; each says why in a comment."""
    wrong = []
    for module, line, name, why in FUNCTION_IMPORTS:
        top = name.split(".")[0]
        command = module.startswith(f"{PACKAGE}.interfaces.cli") or module == f"{PACKAGE}.__main__"
        allowed = top in OPTIONAL or (command and name.startswith(PACKAGE))
        if not allowed:
            wrong.append(f"{module}:{line} imports {name} inside a function")
        elif not why:
            wrong.append(f"{module}:{line} imports {name} inside a function without a comment saying why")
    assert wrong == [], "\n".join(wrong)


def test_the_function_import_scan_sees_them() -> None:
    assert any(name.startswith("numba") for _, _, name, _ in FUNCTION_IMPORTS)


def test_no_module_imports_names_from_a_package_that_encloses_it() -> None:
    """``from quadric_contact.modes import get_mode`` inside ``modes/`` would run the folder's
    ``__init__``, which imports the folder's modules: a circle the scans above leave out (they
    skip a module's enclosing packages).  Submodules may be named that way; other names not."""
    found = []
    for module, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.ImportFrom) or node.level or not node.module:
                continue
            if node.module == PACKAGE or not module.startswith(node.module + "."):
                continue
            names = [a.name for a in node.names if f"{node.module}.{a.name}" not in MODULES]
            if names:
                found.append(f"{module}:{node.lineno} imports {names} from {node.module}")
    assert found == [], found
