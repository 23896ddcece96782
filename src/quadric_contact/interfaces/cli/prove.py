"""``quadric-contact prove [NAME ...]``: re-derive the paper's numbered results.

Prints one line per result: ``PASS``, or ``DIFFERS`` with what the paper
prints and what is true (a recorded erratum), or ``FAIL`` / ``ERROR``, then a
summary with each result's verdict (proven, proven with recorded errata,
evidence only).  The default profile (every proof and the small evidence
searches) takes about half a minute; ``--full`` adds the large searches and
the cross-checks of the package.  Exit status 0 when every check that ran
matched its recorded expectation, 1 otherwise, 2 for bad input (an unknown
name, no proofs found).  Nothing is written to the current directory: hypothesis, whose
searches some checks run, keeps its files in the user cache directory
(``~/.cache/quadric-contact/hypothesis`` on Linux) unless ``HYPOTHESIS_STORAGE_DIRECTORY``
names another.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from collections.abc import Iterator
from typing import Any

from quadric_contact.interfaces.cli.arguments import user_cache_dir
from quadric_contact.interfaces.cli.exits import EXIT_BAD_INPUT, EXIT_FAILED, EXIT_OK


def register(sub: Any) -> None:
    p = sub.add_parser(
        "prove",
        help="re-derive the paper's numbered results in exact arithmetic (proofs/)",
        description="Run the machine-checked proofs: one line per result, PASS or DIFFERS (a recorded "
        "erratum: what the paper prints and what is true), and each result's verdict (proven, proven "
        "with recorded errata, evidence only). The default profile takes about half a minute; --full "
        "runs every check. Exit status 0 when every check matched its recorded expectation, 1 "
        "otherwise, 2 for bad input.",
    )
    p.add_argument(
        "names",
        nargs="*",
        metavar="NAME",
        help="results to run: module name, a prefix of it, or the label ('lemma_03', 'Lemma 3', "
        "'table 4'); default all",
    )
    p.add_argument(
        "--proofs-dir",
        "--proofs",
        dest="proofs_dir",
        metavar="DIR",
        help="the proofs directory (default: proofs/ of the checkout the package runs from, else the "
        "proofs installed with the package; never the current directory, whose code would run)",
    )
    p.add_argument(
        "--full",
        action="store_true",
        help="run every check: also the large searches and the cross-checks (several minutes)",
    )
    # The default profile is what --fast used to select; the flag is kept so that old scripts run.
    p.add_argument("--fast", action="store_true", help=argparse.SUPPRESS)
    p.add_argument("-v", "--verbose", action="store_true", help="also print one line per check")
    p.add_argument("--list", action="store_true", help="list the results and their checks, run nothing")
    p.add_argument(
        "--report",
        action="store_true",
        help="run every check and write proofs/REPORT.md of the checkout (only if all matched)",
    )
    p.set_defaults(func=run)


@contextlib.contextmanager
def hypothesis_files_in_the_user_cache() -> Iterator[None]:
    """hypothesis keeps its files (the example database, which the proofs' searches do not use,
    and a cache of the constants of the code under test, which they fill) in ``.hypothesis/`` of
    the current directory.  While the proofs run they go to the user cache directory instead;
    ``HYPOTHESIS_STORAGE_DIRECTORY``, when set, is left to choose.  The folder hypothesis used
    before is restored afterwards (for a caller that runs ``prove`` in its own process)."""
    try:
        from hypothesis import configuration  # hypothesis is heavy and optional here
    except ImportError:  # the checks that need hypothesis say so and do not run
        yield
        return
    if os.environ.get("HYPOTHESIS_STORAGE_DIRECTORY"):
        yield
        return
    before = configuration.storage_directory(intent_to_write=False).home_directory
    configuration.set_hypothesis_home_dir(user_cache_dir("hypothesis"))
    try:
        yield
    finally:
        configuration.set_hypothesis_home_dir(before)


def run(args: argparse.Namespace) -> int:
    with hypothesis_files_in_the_user_cache():
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    # the prove command loads the proof runner only when it runs
    from quadric_contact.paper.proving import (
        REPORT_NAME,
        CheckRecord,
        Profile,
        Status,
        Verdict,
        find_proofs_dir,
        load_proofs,
        run_proof,
        select,
        write_report,
    )

    def show_check(rec: CheckRecord) -> None:
        if args.verbose:
            print(
                f"    {rec.status.value:<8} {rec.spec.name} ({rec.seconds:.2f}s): {rec.describe()}",
                flush=True,
            )

    if args.full and args.fast:
        print("quadric-contact prove: --full and --fast contradict each other", file=sys.stderr)
        return EXIT_BAD_INPUT
    start = time.perf_counter()
    if args.report:
        if args.names or args.fast:
            print(
                "quadric-contact prove: --report runs every check; give no names and no --fast",
                file=sys.stderr,
            )
            return EXIT_BAD_INPUT
        path, records = write_report(args.proofs_dir, on_check=show_check)
        for r in records:
            print(r.line())
        if all(c.status in (Status.PASS, Status.DIFFERS) for r in records for c in r.checks):
            print(f"wrote {path} ({time.perf_counter() - start:.1f} s)")
            return EXIT_OK
        print(
            f"not writing {path}: some checks did not run or did not match their expectation", file=sys.stderr
        )
        return EXIT_FAILED

    directory = find_proofs_dir(args.proofs_dir)
    proofs = select(load_proofs(directory), args.names)
    if args.list:
        for p in proofs:
            print(f"{p.name}  {p.result}: {p.title} [{p.verdict.value}]")
            for c in p.checks:
                extra = f" [erratum {c.erratum}]" if c.erratum else ""
                full = " (full profile)" if c.full else ""
                print(f"    {c.name}: {c.title} -- {c.method_text}{full}{extra}")
        return EXIT_OK
    profile = Profile.FULL if args.full else Profile.DEFAULT
    records = []
    for p in proofs:
        record = run_proof(p, profile=profile, on_check=show_check)
        print(record.line(), flush=True)
        records.append(record)
    ok = all(r.ok for r in records)
    ran = [c for r in records for c in r.checks if c.status is not Status.SKIPPED]
    n_diff = sum(1 for c in ran if c.status is Status.DIFFERS)
    n_bad = sum(1 for c in ran if not c.status.ok)
    n_not_run = sum(1 for r in records for c in r.checks if c.status is Status.SKIPPED)
    verdicts = {v: [r.proof.result for r in records if r.proof.verdict is v] for v in Verdict}
    print(
        f"{len(records)} results, {len(ran)} checks ({profile.value} profile"
        + (f"; {n_not_run} not run" if n_not_run else "")
        + f") in {time.perf_counter() - start:.1f} s: {n_diff} demonstrate recorded errata, {n_bad} failed"
        + ("" if ok else f"; see {directory / REPORT_NAME} for the expectations")
    )
    for verdict, results in verdicts.items():
        if results:
            print(f"  {verdict.value}: {', '.join(results)}")
    return EXIT_OK if ok else EXIT_FAILED
