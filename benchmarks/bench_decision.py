"""The complete decision against the criterion kernel, the exact scalar decision, and the float
mode where rounding misleads: the sections of ``quadric-contact bench`` on the decision table
(:mod:`quadric_contact.theory.decision`), on their own.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_decision.py [--pairs N] [--scalar-pairs M] [--seed S]

Three tables, each from the functions ``quadric-contact bench`` runs:

1. for each population (small ellipsoids against one environment, pairs of similar sizes,
   pairs with a quadric of every type), the certified criterion kernel alone and the complete
   decision of each question (transversal contact, region, overlap; certified and float) on
   the same pairs, as a fraction of the kernel's throughput in the same run, with the fraction
   of the pairs that reached the exact stage and the float mode's wrong answers; then the same
   certified calls with numba's run-time compile of the kernels instead of the native ones the
   package was built with, and how fast the native ones are against it;
2. the exact scalar decision, one pair at a time (binary64 input): median, 90th percentile,
   slowest, and the rows of the table that decided;
3. the float mode on the symmetric placements (:mod:`quadric_contact.testing.symmetric`) and on
   the hard-case ladders down to ``1e-12``, against the exact decision.
"""

from __future__ import annotations

import argparse

import numpy as np

from quadric_contact.interfaces import benchmark


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pairs", type=int, default=200_000, help="pairs per population (table 1)")
    parser.add_argument("--scalar-pairs", type=int, default=1_000, help="pairs per population (table 2)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    cfg = {"complete_pairs": args.pairs, "fcl_complete_pairs": 0, "exact_scalar_pairs": args.scalar_pairs}
    report = benchmark.Report(profile="decision", machine=benchmark.machine_info())
    rng = np.random.default_rng(args.seed)
    benchmark._complete(report, cfg, rng)
    benchmark._exact_scalar(report, cfg, rng)
    benchmark._float_families(report)
    print(report.table())


if __name__ == "__main__":
    main()
