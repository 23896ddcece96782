"""The signed distance of crossing ellipsoids on a float64 stack: ``qc.distance`` (the compiled
kernels, then the scalar certified path for the pairs they leave) and the depth kernel alone
(:mod:`quadric_contact.modes.distance.depth_kernel`).

Random pairs (semi-axes uniform in ``[0.3, 1.5]``, random orientations, centres uniform in
``[-0.5, 0.5]^3``) are kept when a binary64 minimiser of ``phi(u) = h_E(u) + h_K(-u)`` finds
their interiors crossing.  Printed: the time of ``qc.distance`` per pair after a warm call (the
kernels compiled or loaded), split into the kernels and the scalar path; the depth kernel's time
per pair over the stack (median of five runs) and, each pair timed alone, the median, 90th
percentile and maximum; the cells (points of the Minkowski difference) a pair used; the
enclosures' relative widths; and the pairs left to the scalar path, with their depths.

    PYTHONPATH=src python benchmarks/bench_depth.py [--pairs 2000] [--seed 0]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import quadric_contact as qc
from quadric_contact.modes.distance.depth_kernel import _kernel, crossing_ellipsoids_cells
from quadric_contact.testing.samples import ellipsoid_matrix, float_depth


def _stack(rng: np.random.Generator, m: int) -> np.ndarray:
    out = np.zeros((m, 4, 4))
    for k in range(m):
        R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        axes = rng.uniform(0.3, 1.5, 3)
        out[k] = ellipsoid_matrix(axes, R, rng.uniform(-0.5, 0.5, 3))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    Es, Ks, depth = [], [], []
    while len(Es) < args.pairs:
        E, K = _stack(rng, 256), _stack(rng, 256)
        for k in range(256):
            d, _ = float_depth(E[k], K[k], grid=2000, steps=20)
            if d > 0 and len(Es) < args.pairs:
                Es.append(E[k])
                Ks.append(K[k])
                depth.append(d)
    Es, Ks, depth = np.array(Es), np.array(Ks), np.array(depth)
    n = len(Es)

    qc.distance(Es[:8], Ks[:8])  # compiled or loaded
    enc, rest, cells = crossing_ellipsoids_cells(Es, Ks)
    left = np.flatnonzero(rest)
    t0 = time.perf_counter()
    got = qc.distance(Es, Ks)
    total = time.perf_counter() - t0
    t0 = time.perf_counter()
    qc.distance(Es[~rest], Ks[~rest])
    kernels = time.perf_counter() - t0
    assert np.array_equal(got[~rest], enc[~rest])

    runs = []
    for _ in range(5):
        t0 = time.perf_counter()
        crossing_ellipsoids_cells(Es, Ks)
        runs.append(time.perf_counter() - t0)
    out, flag, work = np.empty((n, 2)), np.empty(n, dtype=np.uint8), np.empty(n, dtype=np.int64)
    best, cover = np.empty((n, 3)), np.zeros((n, 5))
    empty = []
    alone = np.empty(n)
    for k in range(n):
        t0 = time.perf_counter()
        _kernel(Es, Ks, 1e-12, cover, out, flag, work, best, k, k)
        empty.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        _kernel(Es, Ks, 1e-12, cover, out, flag, work, best, k, k + 1)
        alone[k] = time.perf_counter() - t0
    alone -= np.median(empty)  # the call's own cost
    width = (enc[~rest, 1] - enc[~rest, 0]) / np.abs(enc[~rest, 1])

    print(f"### the signed distance of {n:,} random crossing ellipsoid pairs (float64 stack)\n")
    print("| | time / pair |")
    print("| --- | ---: |")
    print(f"| `qc.distance`, the whole stack | {total / n * 1e6:,.1f} µs |")
    answered = n - len(left)
    print(f"| `qc.distance`, the {answered:,} pairs the kernels answer | {kernels / answered * 1e6:.1f} µs |")
    if len(left):
        scalar = (total - kernels * n / (n - len(left))) / len(left)
        print(f"| the scalar path, each of the {len(left)} pairs left | {scalar * 1e3:,.0f} ms |")
    print(f"| depth kernel over the stack (median of 5 runs) | {np.median(runs) / n * 1e6:.1f} µs |")
    p50, p90, pmax = np.percentile(alone, [50, 90, 100]) * 1e6
    print(f"| depth kernel, each pair alone: median / p90 / max | {p50:.1f} / {p90:.1f} / {pmax:.1f} µs |")
    c50, c90, cmax = np.percentile(cells, [50, 90, 100])
    print(f"\ncells a pair: median {c50:.0f}, p90 {c90:.0f}, max {cmax:.0f}")
    print(f"relative width of the enclosures: median {np.median(width):.1e}, max {np.max(width):.1e}")
    print(f"left to the scalar path: {len(left)} of {n:,}", end="")
    if len(left):
        shown = ", ".join(f"{d:.1e}" for d in np.sort(depth[left])[:10])
        print(f" (binary64 depths {shown}{', ...' if len(left) > 10 else ''})")
    else:
        print()


if __name__ == "__main__":
    main()
