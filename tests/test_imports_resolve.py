"""Every ``from quadric_contact... import name`` in the repository resolves: the benchmarks,
docs scripts, proofs and notebooks sources are not all run by the default suite, and a module
that moved or a name that was renamed must not leave one of them broken."""

from __future__ import annotations

import ast
import importlib
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _python_files() -> list[Path]:
    """The checkout's Python files as they are: tracked or new (not ignored), not deleted."""
    out = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.py"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    if out.returncode == 0 and out.stdout.strip():
        return sorted({ROOT / f for f in out.stdout.split() if (ROOT / f).exists()})
    folders = ("src", "tests", "proofs", "benchmarks", "docs", "notebooks")
    return [p for d in folders for p in (ROOT / d).rglob("*.py")]


def _unresolved(path: Path) -> list[str]:
    bad = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        ours = isinstance(node, ast.ImportFrom) and (node.module or "").startswith("quadric_contact")
        if ours and isinstance(node, ast.ImportFrom) and node.level == 0 and node.module is not None:
            try:
                module = importlib.import_module(node.module)
            except ImportError as exc:
                bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {exc}")
                continue
            for alias in node.names:
                if alias.name == "*" or hasattr(module, alias.name):
                    continue
                try:
                    importlib.import_module(f"{node.module}.{alias.name}")
                except ImportError:
                    bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.module} has no {alias.name}")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("quadric_contact"):
                    try:
                        importlib.import_module(alias.name)
                    except ImportError as exc:
                        bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {exc}")
    return bad


def test_every_import_of_the_package_resolves():
    files = _python_files()
    assert any("benchmarks" in p.parts for p in files)
    bad = [line for path in files for line in _unresolved(path)]
    assert bad == [], "\n".join(bad)
