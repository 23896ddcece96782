"""Regenerate the generated code, or check that it is current: ``python -m quadric_contact.codegen``.

Every file of :mod:`quadric_contact._generated` in turn (formulas, kernels, blocks,
double-double programs), each after its derivations are checked; with ``--check`` nothing is
written and the exit status says whether every file equals what the generator makes.
``quadric-contact codegen`` runs the same.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence

from quadric_contact.codegen.blocks import BLOCKS_PATH, regenerate_blocks
from quadric_contact.codegen.dd_programs import DD_PATH, regenerate_dd
from quadric_contact.codegen.formulas import GENERATED_PATH, regenerate
from quadric_contact.codegen.kernels import KERNELS_PATH, regenerate_kernels

__all__ = ["main"]


DESCRIPTION = "Derive the package's closed forms with sympy and emit them as straight-line code."


def main(argv: Sequence[str] | None = None) -> int:
    """Regenerate every generated file (``--check``: only compare); the exit status is 0 when
    every file was current."""
    parser = argparse.ArgumentParser(prog="quadric-contact codegen", description=DESCRIPTION)
    parser.add_argument("--check", action="store_true", help="only check that the file is current")
    args = parser.parse_args(argv)
    status = 0
    for path, fn in (
        (GENERATED_PATH, regenerate),
        (KERNELS_PATH, regenerate_kernels),
        (BLOCKS_PATH, regenerate_blocks),
        (DD_PATH, regenerate_dd),
    ):
        same = fn(check=args.check)
        if args.check:
            print(f"{path.name}: " + ("current" if same else "OUT OF DATE"))
            status |= 0 if same else 1
        else:
            print(f"wrote {path} ({'unchanged' if same else 'changed'})")
    return status
