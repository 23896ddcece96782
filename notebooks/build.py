"""Build the teaching notebooks from their sources.

Each notebook ``notebooks/NN_name.ipynb`` is generated from
``notebooks/src/NN_name.py``, a plain Python file in the "percent" format:

* ``# %%`` starts a code cell;
* ``# %% [markdown]`` starts a markdown cell whose lines start with ``# ``.

Edit the sources, then run ``python notebooks/build.py``; the test suite
checks that every notebook is current and runs each one top to bottom.
Notebooks are stored without outputs.
"""

from __future__ import annotations

import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
SOURCES = HERE / "src"


def parse(text: str) -> list[tuple[str, str]]:
    """Split a percent-format source into ``(kind, source)`` cells."""
    cells: list[tuple[str, list[str]]] = []
    for line in text.splitlines():
        if line.startswith("# %%"):
            kind = "markdown" if "[markdown]" in line else "code"
            cells.append((kind, []))
            continue
        if not cells:
            if line.strip():
                raise ValueError("a notebook source must start with a '# %%' line")
            continue
        kind, lines = cells[-1]
        if kind == "markdown":
            if line.strip() == "#":
                line = ""
            elif line.startswith("# "):
                line = line[2:]
            elif line.strip():
                raise ValueError(f"markdown line does not start with '# ': {line!r}")
        lines.append(line)
    return [(kind, "\n".join(lines).strip("\n")) for kind, lines in cells]


def build(source: Path) -> str:
    """The ``.ipynb`` text for one source file (deterministic: fixed cell ids)."""
    nb = nbformat.v4.new_notebook()
    nb.metadata = {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"},
    }
    for i, (kind, text) in enumerate(parse(source.read_text())):
        make = nbformat.v4.new_markdown_cell if kind == "markdown" else nbformat.v4.new_code_cell
        cell = make(text)
        cell["id"] = f"{source.stem}-{i:02d}"
        nb.cells.append(cell)
    return nbformat.writes(nb) + "\n"


def target(source: Path) -> Path:
    return HERE / f"{source.stem}.ipynb"


def main(argv: list[str]) -> int:
    check = "--check" in argv
    stale = []
    for source in sorted(SOURCES.glob("*.py")):
        text = build(source)
        out = target(source)
        if check:
            if not out.exists() or out.read_text() != text:
                stale.append(out.name)
        else:
            out.write_text(text)
            print(f"wrote {out.relative_to(HERE.parent)}")
    if check and stale:
        print("out of date: " + ", ".join(stale) + " (run python notebooks/build.py)")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
