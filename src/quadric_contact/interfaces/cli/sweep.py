"""``quadric-contact sweep [SCENE]``: one scene under many perturbations, serially or on a dask cluster."""

from __future__ import annotations

import argparse
import json
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any


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
    p.add_argument("--perturbations", "-n", type=int, default=10_000, help="number of runs (default 10000)")
    p.add_argument(
        "--amplitude", default="1/20", help="largest offset per coordinate, a rational such as 1/20 or 0.05"
    )
    p.add_argument("--seed", type=int, default=0, help="seed of the perturbations (default 0)")
    p.add_argument(
        "--effects",
        default="first_contact",
        help="comma-separated effects of every run (default: first_contact; 'scene': the scene's own)",
    )
    p.add_argument("--places", type=int, default=12, help="decimal places of the times kept (default 12)")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--scheduler", metavar="ADDRESS", help="the address of a dask.distributed scheduler")
    where.add_argument("--serial", action="store_true", help="run here, one run after another")
    p.add_argument("--workers", type=int, default=2, help="workers of the LocalCluster (default 2)")
    p.add_argument(
        "--threads", type=int, default=1, help="threads per worker of the LocalCluster (default 1)"
    )
    p.add_argument("--chunk", type=int, help="runs per task (default: about 8 tasks per worker)")
    p.add_argument("--output", "-o", metavar="FILE", help="write every run's summary as JSON to FILE")
    prog = p.add_mutually_exclusive_group()
    prog.add_argument("--progress", dest="progress", action="store_true", default=None, help="show progress")
    prog.add_argument("--no-progress", dest="progress", action="store_false", help="never show progress")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from quadric_contact.exact.errors import SceneError
    from quadric_contact.interfaces.cli.simulate import _write_atomically
    from quadric_contact.scenes.scene import EFFECTS, builtin_scene_names
    from quadric_contact.scenes.sweep import run_sweep

    try:
        amplitude = Fraction(args.amplitude)
    except (ValueError, ZeroDivisionError) as exc:
        raise SceneError(
            f"--amplitude: expected a rational such as 1/20 or 0.05, got {args.amplitude!r}"
        ) from exc
    if (
        args.perturbations < 1
        or args.workers < 1
        or args.threads < 1
        or (args.chunk is not None and args.chunk < 1)
    ):
        raise SceneError("--perturbations, --workers, --threads and --chunk: expected positive numbers")
    if not 0 <= args.places <= 1000:
        raise SceneError(f"--places: expected an integer in [0, 1000], got {args.places}")
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
        try:
            text, source = path.read_text(encoding="utf-8"), str(path)
        except (OSError, UnicodeDecodeError) as exc:
            raise SceneError(f"{path}: cannot read the scene file: {exc}") from exc
    elif args.scene in builtin_scene_names():
        from importlib import resources

        res = resources.files("quadric_contact").joinpath("scenes", f"{args.scene}.toml")
        text, source = res.read_text(encoding="utf-8"), f"<built-in scene {args.scene}>"
    else:
        raise SceneError(f"{args.scene}: no such file (built-in scenes: {', '.join(builtin_scene_names())})")
    if args.output:
        folder = Path(args.output).parent
        if str(folder) and not folder.is_dir():
            raise SceneError(f"{args.output}: the folder {folder} does not exist")
    result = run_sweep(
        text,
        source,
        args.perturbations,
        seed=args.seed,
        amplitude=amplitude,
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
