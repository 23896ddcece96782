"""``quadric-contact bench``: what accuracy costs, measured on this machine.

Prints a table (markdown) of every mode and peer (time per test, fraction wrong,
fraction undecided) on random and hard pairs, throughput against batch size,
the memory-bandwidth limit, the escalation rate and a summary of ratios against the
peers and the read bandwidth measured in the same run; writes the table, a JSON dump and
a plot (time against error, throughput) to ``--out`` (default: the user cache directory,
``~/.cache/quadric-contact/bench`` on Linux) and says where.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path
from typing import Any

from quadric_contact.interfaces.cli.arguments import user_cache_dir

BENCH_EXTRAS = ("matplotlib", "fcl")


def register(sub: Any) -> None:
    p = sub.add_parser(
        "bench",
        help="measure the number modes against their peers (time against accuracy)",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    p.add_argument(
        "--profile",
        choices=("quick", "full", "smoke"),
        default="quick",
        help="quick (default, about a minute), full (several minutes), smoke (seconds: a check that it runs)",
    )
    p.add_argument(
        "--out",
        type=Path,
        default=None,
        metavar="DIR",
        help="directory for table, JSON and plot (default: the user cache directory, "
        "$XDG_CACHE_HOME/quadric-contact/bench or ~/.cache/quadric-contact/bench on Linux)",
    )
    p.add_argument("--no-plot", action="store_true", help="do not draw the plot")
    p.add_argument("--seed", type=int, default=0, help="seed of the random pairs")
    p.add_argument(
        "--huge",
        action="store_true",
        help="also process 1e8 pairs in dask chunks and report the peak memory (takes several minutes)",
    )
    p.add_argument("--huge-pairs", type=float, default=1e8, help="pairs of the chunked run (default 1e8)")
    p.set_defaults(func=run)


def missing_extras() -> list[str]:
    """Optional packages of the ``bench`` extra that are not installed."""
    return [name for name in BENCH_EXTRAS if importlib.util.find_spec(name) is None]


def run(args: argparse.Namespace) -> int:
    from quadric_contact.interfaces import benchmark  # the bench command loads its harness only when it runs

    missing = missing_extras()
    if missing:
        names = {"fcl": "python-fcl"}
        print(
            "note: not installed: "
            + ", ".join(names.get(m, m) for m in missing)
            + ' (pip install ".[bench]"); those measurements are skipped',
            file=sys.stderr,
        )
    report = benchmark.run(
        args.profile,
        seed=args.seed,
        huge=args.huge,
        huge_pairs=int(args.huge_pairs),
        log=lambda msg: print(msg, file=sys.stderr),
    )
    out: Path = args.out if args.out is not None else user_cache_dir("bench")
    out.mkdir(parents=True, exist_ok=True)
    plot_path = None if args.no_plot else benchmark.plot(report, out / f"bench_{args.profile}.png")
    table = report.table()
    written = [out / f"bench_{args.profile}.md", out / f"bench_{args.profile}.json"]
    written[0].write_text(table)
    written[1].write_text(report.to_json())
    print(table)
    files = ", ".join(p.name for p in [*written, *([plot_path] if plot_path else [])])
    why = "" if plot_path else " (no plot: matplotlib missing or --no-plot)"
    print(f"wrote {files} to {out.resolve()}{why}")
    return 0
