"""``quadric-contact codegen``: regenerate (or check) the generated formulas."""

from __future__ import annotations

import argparse
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser("codegen", help="regenerate the closed forms derived with sympy")
    p.add_argument("--check", action="store_true", help="only check that the generated file is current")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from quadric_contact import codegen  # the codegen command loads the generator only when it runs

    return codegen.main(["--check"] if args.check else [])
