"""The path one call takes through the package's files: how many files it enters, and how
often the running code switches from one file to another.

A measure of how far data travels, not of speed: a ``sys.setprofile`` hook records every
Python function the call runs (compiled kernels run as one step of their Python caller), and
counts the package's files entered (and how many of them are in ``modes/``) and the switches
between consecutive events in different files of the package.

Run from the repository root::

    PYTHONPATH=src python benchmarks/walk_call.py [--pairs N] [--mode certified] [--question contact]

The pairs are a population of ``quadric-contact bench``: "similar sizes" (ellipsoids of
semi-axes 0.5-2 against ellipsoids of semi-axes 2-5, random rotations) or "every type" (small
ellipsoids against a quadric of every type).  One call warms the
kernels first, so that the walk is the steady state's.
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path
from types import FrameType
from typing import Any

import numpy as np

import quadric_contact as qc
from quadric_contact.testing.samples import random_ellipsoids, random_pairs

PACKAGE = Path(qc.__file__).resolve().parent

QUESTIONS = {
    "contact": qc.transversal_contact,
    "region": qc.relative_position,
    "overlap": qc.overlap,
}


def _package_file(frame: FrameType | None) -> str | None:
    if frame is None:
        return None
    name = frame.f_code.co_filename
    try:
        return str(Path(name).resolve().relative_to(PACKAGE))
    except ValueError:
        return None


def walk(fn: Any, *args: Any, **kwargs: Any) -> tuple[Counter[str], int]:
    """The package's files ``fn(*args, **kwargs)`` runs code in (with the number of function
    calls in each) and the number of switches between files of the package."""
    entered: Counter[str] = Counter()
    state = {"file": None, "switches": 0}

    def hook(frame: FrameType, event: str, arg: Any) -> None:
        if event == "call":
            here = _package_file(frame)
            if here is not None:
                entered[here] += 1
        elif event == "return":
            here = _package_file(frame.f_back)
        else:
            return
        if here is not None and here != state["file"]:
            if state["file"] is not None:
                state["switches"] += 1
            state["file"] = here

    sys.setprofile(hook)
    try:
        fn(*args, **kwargs)
    finally:
        sys.setprofile(None)
    return entered, int(state["switches"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", type=int, default=2000)
    parser.add_argument("--mode", default="certified")
    parser.add_argument("--question", choices=sorted(QUESTIONS), default="contact")
    parser.add_argument("--population", choices=("similar", "every-type"), default="similar")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--files", action="store_true", help="list the files entered")
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    if args.population == "similar":
        E, _ = random_ellipsoids(args.pairs, rng, axes=(0.5, 2.0), box=3.0)
        Q, _ = random_ellipsoids(args.pairs, rng, axes=(2.0, 5.0), box=0.0)
    else:
        E, Q, _ = random_pairs(args.pairs, rng)
    fn = QUESTIONS[args.question]
    fn(E, Q, mode=args.mode)
    entered, switches = walk(fn, E, Q, mode=args.mode)
    in_modes = [f for f in entered if f.startswith("modes")]
    print(f"{args.question}, mode {args.mode!r}, a stack of {args.pairs} pairs ({args.population})")
    print("| files entered | of them in modes/ | file switches | function calls |")
    print("|---:|---:|---:|---:|")
    print(f"| {len(entered)} | {len(in_modes)} | {switches} | {sum(entered.values())} |")
    if args.files:
        for name, calls in sorted(entered.items()):
            print(f"  {calls:6d}  {name}")


if __name__ == "__main__":
    main()
