"""``quadric-contact sweep [SCENE]``: one scene under many perturbations, serially or on a dask cluster."""

from __future__ import annotations

import argparse
import json
import sys
from fractions import Fraction
from importlib import resources
from pathlib import Path
from typing import Any

from quadric_contact.exact.bounds import (
    MAX_AMPLITUDE,
    MAX_AMPLITUDE_DIGITS,
    MAX_CLI_COUNT,
    MAX_CLI_PROCESSES,
    MAX_PLACES,
)
from quadric_contact.exact.errors import SceneError
from quadric_contact.interfaces.cli.arguments import check_output_path, integer, rational
from quadric_contact.interfaces.cli.simulate import _write_atomically
from quadric_contact.scenes.scene_model import EFFECTS
from quadric_contact.scenes.scene_toml import builtin_scene_names, read_scene_file
from quadric_contact.scenes.sweep import check_scheduler_address, run_sweep


def register(sub: Any) -> None:
    p = sub.add_parser(
        "sweep",
        help="run a scene under many small perturbations of its paths (dask.distributed cluster)",
        description="Run a scene (default: the bee and the tree of Example 17) under N perturbations of "
        "its ellipsoids' paths, on a dask.distributed LocalCluster (default), on the cluster at "
        "--scheduler ADDRESS, or --serial; the results are the same whichever way, run by run. "
        "Exit status: 0 done, 2 bad scene or option.",
    )
    p.add_argument("scene", nargs="?", default="bee_and_tree", help="a scene file, or a built-in scene name")
    p.add_argument(
        "--perturbations",
        "-n",
        type=integer("--perturbations", 1, MAX_CLI_COUNT),
        default=10_000,
        help="number of runs (default 10000)",
    )
    p.add_argument(
        "--amplitude",
        type=rational("--amplitude", Fraction(0), Fraction(MAX_AMPLITUDE), max_digits=MAX_AMPLITUDE_DIGITS),
        default=Fraction(1, 20),
        help="largest offset per coordinate, a rational such as 1/20 or 0.05",
    )
    p.add_argument(
        "--seed",
        type=integer("--seed", 0, MAX_CLI_COUNT),
        default=0,
        help="seed of the perturbations (default 0)",
    )
    p.add_argument(
        "--effects",
        default="first_contact",
        help="comma-separated effects of every run (default: first_contact; 'scene': the scene's own)",
    )
    p.add_argument(
        "--places",
        type=integer("--places", 0, MAX_PLACES),
        default=12,
        help="decimal places of the times kept (default 12)",
    )
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="the address of a dask.distributed scheduler")
    where.add_argument("--serial", action="store_true", help="run here, one run after another")
    p.add_argument(
        "--workers",
        type=integer("--workers", 1, MAX_CLI_PROCESSES),
        default=2,
        help="workers of the LocalCluster (default 2)",
    )
    p.add_argument(
        "--threads",
        type=integer("--threads", 1, MAX_CLI_PROCESSES),
        default=1,
        help="threads per worker of the LocalCluster (default 1)",
    )
    p.add_argument(
        "--chunk",
        type=integer("--chunk", 1, MAX_CLI_COUNT),
        help="runs per task (default: about 8 tasks per worker)",
    )
    p.add_argument("--output", "-o", metavar="FILE", help="write every run's summary as JSON to FILE")
    prog = p.add_mutually_exclusive_group()
    prog.add_argument("--progress", dest="progress", action="store_true", default=None, help="show progress")
    prog.add_argument("--no-progress", dest="progress", action="store_false", help="never show progress")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    if args.scheduler is not None:
        check_scheduler_address(args.scheduler)  # before the scene is read

    effects: list[str] | None = None
    if args.effects.strip() != "scene":
        effects = [e.strip() for e in args.effects.split(",") if e.strip()]
        bad = [e for e in effects if e not in EFFECTS]
        if bad or not effects:
            raise SceneError(
                f"--effects: expected a comma-separated subset of {', '.join(EFFECTS)}, got {args.effects!r}"
            )
    path = Path(args.scene)
    if path.exists():
        text, source = read_scene_file(path), str(path)
    elif args.scene in builtin_scene_names():
        res = resources.files("quadric_contact").joinpath("scenes", f"{args.scene}.toml")
        text, source = res.read_text(encoding="utf-8"), f"<built-in scene {args.scene}>"
    else:
        raise SceneError(f"{args.scene}: no such file (built-in scenes: {', '.join(builtin_scene_names())})")
    if args.output:
        check_output_path("--output", args.output)
    result = run_sweep(
        text,
        source,
        args.perturbations,
        seed=args.seed,
        amplitude=args.amplitude,
        effects=effects,
        places=args.places,
        scheduler=args.scheduler,
        serial=args.serial,
        workers=args.workers,
        threads=args.threads,
        chunk=args.chunk,
        progress=args.progress,
    )
    if args.output:
        _write_atomically(args.output, (json.dumps(result.to_dict(), indent=1) + "\n").encode())
    print(result.format_text())
    if args.output:
        print(f"results written to {args.output}")
    sys.stdout.flush()
    return 0
