"""Cost of smallness on stacks (Tables 1-2 corrected) in every number mode.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_smallness_arrays.py [--pairs N] [--seed S]

Prints one table per case, with the time per pair of each mode (wall clock, best of
``--repeat`` runs, all threads; and the process CPU time), the share of pairs each stage
of the certified cascade decided, and the ratio to the criterion alone
(``corollary_10(E, Q, mode="certified")``, which evaluates only the
characteristic polynomial's criterion on stacks) on the same pairs:

* ``broadcast``: many small ellipsoids (semi-axes 0.5-2, random rotations, centres in
  ``[-3, 3]^3``) against one ellipsoid of semi-axes 2-5, all in binary64 (the paper's use
  case);
* ``broadcast, exact cylinder``: the same ellipsoids against an elliptic cylinder given
  exactly (rational rotation and translation, rounded for the filter: its zero eigenvalue
  is rounded off, so its type and sides come from exact and ball arithmetic once);
* ``distinct``: as many distinct environment ellipsoids as small ones, one pair each.

``ball`` runs on the first ``--ball-pairs`` pairs and the scalar exact decision
(:func:`quadric_contact.theory.smallness.smallness`, one pair at a time) on the first
``--scalar-pairs``.  Timings are wall-clock on a shared machine: treat them as indicative
and re-measure on a quiet one.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from quadric_contact import Quadric, RigidMotion  # noqa: E402
from quadric_contact.modes import BallMode, CertifiedMode, FilterMode, FloatMode  # noqa: E402
from quadric_contact.modes.predicates import corollary_10  # noqa: E402
from quadric_contact.modes.predicates import smallness as smallness_codes  # noqa: E402
from quadric_contact.theory.smallness import smallness  # noqa: E402


def rotations(rng: np.random.Generator, n: int) -> np.ndarray:
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    R = np.empty((n, 3, 3))
    R[:, 0] = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=1)
    R[:, 1] = np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=1)
    R[:, 2] = np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=1)
    return R


def ellipsoids(rng: np.random.Generator, n: int, lo: float, hi: float, centre: float) -> np.ndarray:
    """``n`` random ellipsoids as binary64 matrices (``det < 0``, inside negative)."""
    axes = rng.uniform(lo, hi, size=(n, 3))
    R = rotations(rng, n)
    A = np.einsum("nij,nj,nkj->nik", R, 1 / axes**2, R)
    A = (A + np.swapaxes(A, 1, 2)) / 2
    c = rng.uniform(-centre, centre, size=(n, 3))
    M = np.zeros((n, 4, 4))
    M[:, :3, :3] = A
    b = -np.einsum("nij,nj->ni", A, c)
    M[:, :3, 3] = b
    M[:, 3, :3] = b
    M[:, 3, 3] = np.einsum("ni,ni->n", c, -b) - 1
    return M


def timed(fn: Any, repeat: int) -> tuple[float, float, Any]:
    """Best wall-clock and CPU seconds over ``repeat`` runs (after one warm-up), and the result."""
    out = fn()
    wall, cpu = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return min(wall), min(cpu), out


def scalar_code(e: Any, q: Any) -> int:
    r = smallness(
        Quadric.from_matrix(e) if isinstance(e, np.ndarray) else e,
        Quadric.from_matrix(q) if isinstance(q, np.ndarray) else q,
    )
    return 1 if r.table_4_applies else (4 if r.small else 0)


def run_case(name: str, E: Any, Q: Any, args: argparse.Namespace) -> list[str]:
    n = len(E)
    rows: list[tuple[str, float, float, str]] = []
    criterion = CertifiedMode()
    cw, cc, _ = timed(lambda: corollary_10(E, Q, mode=criterion), args.repeat)
    rows.append(("criterion only (certified)", cw / n, cc / n, str(criterion.last)))
    for label, mode in (("float", FloatMode()), ("filter", FilterMode())):
        w, c, codes = timed(lambda m=mode: smallness_codes(E, Q, mode=m), args.repeat)
        undecided = int(np.count_nonzero(codes == 2))
        rows.append((label, w / n, c / n, f"uncertain {undecided / n:.2e}"))
    certified = CertifiedMode()
    w, c, codes = timed(lambda: smallness_codes(E, Q, mode=certified), args.repeat)
    last = certified.last
    shares = ", ".join(f"{stage} {count / n:.2e}" for stage, count in last.decided.items())
    rows.append(("certified", w / n, c / n, shares))
    ratio = w / cw
    k = min(n, args.ball_pairs)
    Qk = Q if not isinstance(Q, np.ndarray) or Q.ndim == 2 else Q[:k]
    w, c, _ = timed(lambda: smallness_codes(E[:k], Qk, mode=BallMode()), 1)
    rows.append((f"ball ({k} pairs)", w / k, c / k, ""))
    k = min(n, args.scalar_pairs)
    pairs = [(E[i], Q if not isinstance(Q, np.ndarray) or Q.ndim == 2 else Q[i]) for i in range(k)]
    w, c, _ = timed(lambda: [scalar_code(e, q) for e, q in pairs], 1)
    rows.append((f"exact scalar ({k} pairs)", w / k, c / k, ""))
    lines = [f"{name}: {n} pairs, certified smallness / criterion = {ratio:.2f}"]
    lines.append(f"  {'mode':<30} {'ns/pair':>12} {'cpu ns/pair':>12}  decided / escalated")
    for label, wall, cpu, note in rows:
        lines.append(f"  {label:<30} {wall * 1e9:>12.1f} {cpu * 1e9:>12.1f}  {note}")
    return lines


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pairs", type=int, default=10**6)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--ball-pairs", type=int, default=2000)
    parser.add_argument("--scalar-pairs", type=int, default=30)
    args = parser.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    E = ellipsoids(rng, args.pairs, 0.5, 2, 3)
    environment = ellipsoids(rng, 1, 2, 5, 0)[0]
    cylinder = Quadric.elliptic_cylinder(Fraction(7, 2), Fraction(5, 2)).moved(
        RigidMotion.from_quaternion(1, 2, 0, 1, (Fraction(1, 3), 0, Fraction(-1, 7)))
    )
    distinct = ellipsoids(rng, args.pairs, 2, 5, 1)
    print(f"threads: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    for name, Q in (
        ("broadcast", environment),
        ("broadcast, exact cylinder", cylinder),
        ("distinct", distinct),
    ):
        print("\n".join(run_case(name, E, Q, args)))
        print()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
