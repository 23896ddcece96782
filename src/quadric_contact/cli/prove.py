"""``quadric-contact prove [NAME ...]``: re-derive the paper's numbered results.

Prints one line per result: ``PASS``, or ``DIFFERS`` with what the paper
prints and what is true (a recorded erratum), or ``FAIL`` / ``ERROR``.  Exit
status 0 when every check that ran matched its recorded expectation, 1
otherwise, 2 for bad input (an unknown name, no ``proofs/`` directory).
"""

from __future__ import annotations

import argparse
import sys
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser(
        "prove",
        help="re-derive the paper's numbered results in exact arithmetic (proofs/)",
        description="Run the machine-checked proofs of proofs/: one line per result, PASS or DIFFERS "
        "(a recorded erratum: what the paper prints and what is true). Exit status 0 when every "
        "check matched its recorded expectation, 1 otherwise, 2 for bad input.",
    )
    p.add_argument(
        "names",
        nargs="*",
        metavar="NAME",
        help="results to run: module name, a prefix of it, or the label ('lemma_03', 'Lemma 3', "
        "'table 4'); default all",
    )
    p.add_argument("--proofs", metavar="DIR", help="the proofs directory (default: found from the checkout)")
    p.add_argument("--fast", action="store_true", help="skip the slow checks (they are reported as skipped)")
    p.add_argument("-v", "--verbose", action="store_true", help="also print one line per check")
    p.add_argument("--list", action="store_true", help="list the results and their checks, run nothing")
    p.add_argument(
        "--report",
        action="store_true",
        help="run every check and write proofs/REPORT.md (only if all matched their expectation)",
    )
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..proving import (
        REPORT_NAME,
        CheckRecord,
        find_proofs_dir,
        load_proofs,
        run_proof,
        select,
        write_report,
    )
    from . import EXIT_FAILED, EXIT_OK

    def show_check(rec: CheckRecord) -> None:
        if args.verbose:
            print(
                f"    {rec.status.value:<8} {rec.spec.name} ({rec.seconds:.2f}s): {rec.describe()}",
                flush=True,
            )

    if args.report:
        if args.names or args.fast:
            print(
                "quadric-contact prove: --report runs every check; give no names and no --fast",
                file=sys.stderr,
            )
            return 2
        path, records = write_report(args.proofs, on_check=show_check)
        for r in records:
            print(r.line())
        if all(r.ok for r in records):
            print(f"wrote {path}")
            return EXIT_OK
        print(f"not writing {path}: some checks did not match their expectation", file=sys.stderr)
        return EXIT_FAILED

    directory = find_proofs_dir(args.proofs)
    proofs = select(load_proofs(directory), args.names)
    if args.list:
        for p in proofs:
            print(f"{p.name}  {p.result}: {p.title}")
            for c in p.checks:
                extra = f" [erratum {c.erratum}]" if c.erratum else ""
                slow = " (slow)" if c.slow else ""
                print(f"    {c.name}: {c.title} -- {c.method_text}{slow}{extra}")
        return EXIT_OK
    records = []
    for p in proofs:
        record = run_proof(p, include_slow=not args.fast, on_check=show_check)
        print(record.line(), flush=True)
        records.append(record)
    ok = all(r.ok for r in records)
    n_diff = sum(1 for r in records for c in r.checks if c.status.value == "DIFFERS")
    n_bad = sum(1 for r in records for c in r.checks if not c.status.ok)
    print(
        f"{len(records)} results, {sum(len(r.checks) for r in records)} checks: "
        f"{n_diff} demonstrate recorded errata, {n_bad} failed"
        + ("" if ok else f"; see {directory / REPORT_NAME} for the expectations")
    )
    return EXIT_OK if ok else EXIT_FAILED
