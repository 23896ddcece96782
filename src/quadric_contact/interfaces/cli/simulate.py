"""``quadric-contact simulate [SCENE]``: run a scene, print its exact event timeline and work ledger."""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
import warnings
from dataclasses import replace
from pathlib import Path
from typing import Any

from quadric_contact.exact.bounds import (
    MAX_CLI_BODIES,
    MAX_CLI_COUNT,
    MAX_CLI_PROCESSES,
    MAX_FRAMES,
    MAX_PLACES,
)
from quadric_contact.exact.errors import SceneError
from quadric_contact.exact.optional import pyplot
from quadric_contact.interfaces.animation import render_gif
from quadric_contact.interfaces.cli.arguments import check_output_path, integer
from quadric_contact.interfaces.cli.exits import EXIT_BAD_INPUT, EXIT_OK
from quadric_contact.interfaces.plotting import render_png
from quadric_contact.scenes.manybody import GENERATED_SCENES, many_body_scene
from quadric_contact.scenes.scene_model import EFFECTS
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names, load_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.simulation_reports import Plan


def register(sub: Any) -> None:
    p = sub.add_parser(
        "simulate",
        help="run a scene: exact event times, only the requested effects, work ledger",
        description="Run a scene file (TOML) or a built-in scene (default: the bee and the tree of "
        "Example 17) and print the event timeline with exact event times and the work ledger. "
        "Exit status: 0 done, 2 bad scene or option.",
    )
    p.add_argument(
        "scene",
        nargs="?",
        default="bee_and_tree",
        help="a scene file, a built-in scene name, or many_bodies (a generated scene: --bodies, --pieces)",
    )
    p.add_argument("--list", action="store_true", help="list the built-in scenes and exit")
    p.add_argument(
        "--effects",
        help="comma-separated effects replacing the scene's "
        "(zone, contact, contact_kind, relative_position, first_contact, smallness, distance)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the timeline")
    p.add_argument("--output", "-o", metavar="FILE", help="also write the JSON result to FILE")
    p.add_argument("--plot", metavar="FILE.png", help="draw the pieces, planes and path coloured by state")
    p.add_argument(
        "--animate",
        metavar="FILE.gif",
        help="an animated GIF of the bodies moving, coloured by state, with the timeline",
    )
    p.add_argument(
        "--frames",
        type=integer("--frames", 2, MAX_FRAMES),
        default=40,
        help="frames of the animation (default 40)",
    )
    p.add_argument(
        "--places",
        type=integer("--places", 0, MAX_PLACES),
        help="decimal places of the event times (default: the scene's)",
    )
    p.add_argument(
        "--broad-phase",
        action="store_true",
        help="prune planes, pieces and stretches of time with certified swept-volume bounds first "
        "(same timelines; on by default for many_bodies)",
    )
    p.add_argument(
        "--workers",
        type=integer("--workers", 0, MAX_CLI_PROCESSES),
        default=None,
        help="processes to share the ellipsoids and the pairs of bodies (0: one per core; default 1)",
    )
    p.add_argument(
        "--bodies",
        type=integer("--bodies", 1, MAX_CLI_BODIES),
        default=1000,
        help="many_bodies: number of ellipsoids (default 1000)",
    )
    p.add_argument(
        "--pieces",
        type=integer("--pieces", 1, MAX_CLI_BODIES),
        default=16,
        help="many_bodies: pieces of the totem (default 16)",
    )
    p.add_argument(
        "--seed",
        type=integer("--seed", 0, MAX_CLI_COUNT),
        default=0,
        help="many_bodies: the seed of the generated scene",
    )
    p.add_argument(
        "--mutual",
        action="store_true",
        help="also the contacts of the moving ellipsoids with each other (for a scene file: as if "
        "it said mutual = true)",
    )
    p.add_argument(
        "--on-not-small",
        choices=("refuse", "warn"),
        help="what to do when an ellipsoid is not small with respect to a piece (default: the scene's)",
    )
    p.add_argument(
        "--events",
        choices=("summary", "all"),
        default="summary",
        help="summary (default): at most a few dozen events per pair and a bounded report; "
        "all: every event of every pair",
    )
    p.add_argument(
        "--reading",
        choices=("geometry", "paper"),
        help="geometry: a piece is its quadric as cut by its planes; paper: Algorithm 1's reading, "
        "a piece whose zone is reached counts as its whole quadric (default: the scene's, else geometry)",
    )
    p.add_argument(
        "--full",
        action="store_true",
        help="evaluate every effect for every piece on every segment (to compare with the lazy plan)",
    )
    prog = p.add_mutually_exclusive_group()
    prog.add_argument("--progress", dest="progress", action="store_true", default=None, help="show progress")
    prog.add_argument("--no-progress", dest="progress", action="store_false", help="never show progress")
    p.set_defaults(func=run)


def _write_atomically(path: str, data: bytes) -> None:
    target = Path(path)
    folder = target.parent if str(target.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", dir=folder)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def run(args: argparse.Namespace) -> int:
    if args.list:
        for name in builtin_scene_names():
            s = builtin_scene(name, check_smallness=False)
            print(f"{name:24s} {s.name}")
        for name, what in GENERATED_SCENES.items():
            print(f"{name:24s} {what}")
        return EXIT_OK
    effects = None
    if args.effects is not None:
        effects = [e.strip() for e in args.effects.split(",") if e.strip()]
        bad = [e for e in effects if e not in EFFECTS]
        if bad or not effects:
            raise SceneError(
                f"--effects: expected a comma-separated subset of {', '.join(EFFECTS)}, got {args.effects!r}"
            )
    for option, out in (("--output", args.output), ("--plot", args.plot), ("--animate", args.animate)):
        if out is not None:
            check_output_path(option, out)  # before the run, not after it

    broad_phase = args.broad_phase
    if args.scene in GENERATED_SCENES and not Path(args.scene).exists():
        if args.bodies < 1 or args.pieces < 1:
            raise SceneError(
                f"--bodies and --pieces: expected positive numbers, got {args.bodies}, {args.pieces}"
            )
        scene = many_body_scene(
            args.bodies, args.pieces, seed=args.seed, check_smallness=False, mutual=args.mutual
        )
        broad_phase = True
    else:
        # load without checking smallness; the run checks it only if its effects need it
        scene = load_scene(args.scene, check_smallness=False)
        if args.mutual:
            scene = replace(scene, mutual=tuple(e.name for e in scene.ellipsoids))
    plan_effects = effects if effects is not None else list(scene.effects)
    Plan.from_effects(plan_effects)  # validate before any work
    if args.plot or args.animate:
        pyplot()  # fail early when matplotlib is missing
    with warnings.catch_warnings():  # the report prints the scene's warnings itself
        warnings.simplefilter("ignore")
        result = simulate(
            scene,
            effects=effects,
            full=args.full,
            progress=args.progress,
            on_not_small=args.on_not_small,
            broad_phase=broad_phase and not args.full,
            workers=1 if args.workers is None else args.workers,
            reading=args.reading,
        )
    places = args.places
    payload = json.dumps(result.to_dict(places), indent=2) + "\n" if args.json or args.output else ""
    png = None
    if args.plot:
        png = render_png(result)
    gif = None
    if args.animate:
        gif = render_gif(result, frames=args.frames, progress=args.progress)
    # everything succeeded: now write (each file appears whole or not at all)
    if args.output:
        _write_atomically(args.output, payload.encode())
    if png is not None:
        _write_atomically(args.plot, png)
    if gif is not None:
        _write_atomically(args.animate, gif)
    if args.json:
        sys.stdout.write(payload)
    else:
        print(result.format_text(places, events=args.events))
        if args.plot:
            print(f"plot written to {args.plot}")
        if args.animate:
            print(f"animation written to {args.animate}")
    return EXIT_OK if result is not None else EXIT_BAD_INPUT
