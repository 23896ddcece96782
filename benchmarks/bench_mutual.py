"""Mutual contacts of many moving ellipsoids: exact event times against fixed-step sampling.

The generated scene (``many_body_scene``: N ellipsoids on straight paths around a totem,
one in ten turning) is run with ``mutual`` on:

* exactly (:func:`quadric_contact.scenes.mutual.mutual_contacts`: the certified broad
  phase on swept boxes, then the pencil ``det(λ A(t) + B(t))`` of each pair it keeps);
  with ``--check``, also without the broad phase, and the timelines compared;
* by fixed-step sampling, the usual practice, at several step counts S: at each of
  S + 1 evenly spaced times every ellipsoid's matrix is evaluated (binary64), pairs are
  pruned by bounding spheres (numpy) and the rest decided by the array predicate
  ``qc.overlap`` (certified mode); for each S the time and the number of exact contact
  intervals (maximal intervals where a pair touches or overlaps) in which no sample saw
  the contact.

The exact timelines themselves are compared, on a subset of pairs (``--dense-pairs``: pairs
that meet and near misses), with the static exact decision at ``--dense-samples`` evenly
spaced rational times (``quadric_contact.testing.mutual_sampling``): the row "dense exact
sampling" counts the sampled contact intervals the timelines miss (0 expected).

And the whole scene with the totem and mutual contacts (``simulate``, broad phase on
two workers) for the time of the complete job.

Usage::

    PYTHONPATH=src python benchmarks/bench_mutual.py [--n 1000] [--m 16] [--steps 10,100,1000]
        [--check] [--whole] [--dense-pairs 30] [--dense-samples 256]

The machine is shared: the figures are indicative.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import quadric_contact as qc
from quadric_contact.scenes.broadphase import ellipsoid_extents
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.manybody import many_body_scene
from quadric_contact.scenes.mutual import OVERLAPPING, TOUCHING, mutual_contacts
from quadric_contact.scenes.simulate import simulate

_UPPER = [(i, j) for i in range(4) for j in range(i, 4)]


def _entry_polys(scene):
    out = []
    for e in scene.ellipsoids:
        (seg,) = e.trajectory.segments(scene.span[0], scene.span[1], e.center)
        out.append([[float(c) for c in p.coeffs()] or [0.0] for p in seg.moved_upper(e.quadric, e.center)])
    deg = max(len(c) for row in out for c in row)
    coeffs = np.zeros((len(out), 10, deg))
    for i, row in enumerate(out):
        for k, c in enumerate(row):
            coeffs[i, k, : len(c)] = c
    return coeffs


def _matrices(coeffs, t):
    vals = np.zeros(coeffs.shape[:2])
    for d in range(coeffs.shape[2] - 1, -1, -1):
        vals = vals * t + coeffs[:, :, d]
    M = np.zeros((coeffs.shape[0], 4, 4))
    for k, (i, j) in enumerate(_UPPER):
        M[:, i, j] = M[:, j, i] = vals[:, k]
    return M


def intervals(results, t0):
    """(a, b, start, end) of every maximal stretch where a pair touches or overlaps."""
    meet = (TOUCHING, OVERLAPPING)
    out = []
    for m in results:
        start = t0 if m.start in meet else None
        for e in m.events:
            if start is None and (e.at in meet or e.after in meet):
                start = e.time
            if start is not None and e.after not in meet:
                out.append((m.a, m.b, start, e.time))
                start = None
        if start is not None:
            out.append((m.a, m.b, start, None))
    return out


def sampling(scene, steps):
    """Returns (seconds, seen): ``seen[(a, b)]`` the sample times where the pair met."""
    coeffs = _entry_polys(scene)
    names = [e.name for e in scene.ellipsoids]
    radius = np.array([float(ellipsoid_extents(e.quadric)[1]) for e in scene.ellipsoids])
    t0, t1 = float(scene.span[0]), float(scene.span[1])
    seen: dict[tuple[str, str], list[float]] = {}
    start = time.perf_counter()
    iu, ju = np.triu_indices(len(names), 1)
    for k in range(steps + 1):
        t = t0 + (t1 - t0) * k / steps
        M = _matrices(coeffs, t)
        centres = -np.linalg.solve(M[:, :3, :3], M[:, :3, 3][..., None])[..., 0]
        d = np.linalg.norm(centres[iu] - centres[ju], axis=1)
        near = d <= radius[iu] + radius[ju]
        if not near.any():
            continue
        a, b = iu[near], ju[near]
        codes = np.asarray(qc.overlap(M[a], M[b], touching="overlap"))
        for i, j, c in zip(a, b, codes, strict=True):
            if c:
                seen.setdefault((names[i], names[j]), []).append(t)
    return time.perf_counter() - start, seen


def missed(found, seen):
    out = 0
    for a, b, start, end in found:
        lo, hi = float(start), (float("inf") if end is None else float(end))
        times = seen.get((a, b), []) + seen.get((b, a), [])
        if not any(lo - 1e-12 <= t <= hi + 1e-12 for t in times):
            out += 1
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000)
    ap.add_argument("--m", type=int, default=16)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--steps", default="10,100,1000")
    ap.add_argument("--check", action="store_true", help="also the run without the broad phase (N^2 pencils)")
    ap.add_argument("--whole", action="store_true", help="also the whole scene: totem and mutual contacts")
    ap.add_argument("--dense-pairs", type=int, default=30, help="pairs checked by dense exact sampling")
    ap.add_argument("--dense-samples", type=int, default=256, help="sample times per pair of the dense check")
    args = ap.parse_args(argv)
    scene = many_body_scene(args.n, args.m, seed=args.seed, check_smallness=False, mutual=True)
    ledger = Ledger()
    started = time.perf_counter()
    exact = mutual_contacts(scene, ledger=ledger)
    exact_s = time.perf_counter() - started
    found = intervals(exact, scene.span[0])
    print(f"{args.n} moving ellipsoids (seed {args.seed}), time span {scene.span[0]}..{scene.span[1]}")
    print(f"{'method':38s} {'seconds':>9s} {'contact intervals':>18s} {'missed':>7s}")
    pencils = ledger.done.get("mutual_pencils", 0)
    print(f"{'exact, broad phase (' + str(pencils) + ' pencils)':38s} {exact_s:9.2f} {len(found):18d} {0:7d}")
    if args.check:
        started = time.perf_counter()
        every = mutual_contacts(scene, broad_phase=False)
        every_s = time.perf_counter() - started
        same = [(m.a, m.b, [e.time.decimal(15) for e in m.events]) for m in every] == [
            (m.a, m.b, [e.time.decimal(15) for e in m.events]) for m in exact
        ]
        n_every = len(intervals(every, scene.span[0]))
        print(f"{'exact, every pair':38s} {every_s:9.2f} {n_every:18d} {0:7d}  same: {same}")
    if args.dense_pairs > 0:
        from quadric_contact.testing.mutual_sampling import dense_check, near_pairs

        meeting = (2 * args.dense_pairs + 2) // 3
        pairs = near_pairs(scene, exact, meeting=meeting, near=args.dense_pairs - meeting, seed=args.seed)
        started = time.perf_counter()
        check = dense_check(scene, exact, pairs, samples=args.dense_samples, workers=2)
        seconds = time.perf_counter() - started
        label = f"dense exact sampling, {check.pairs} pairs x {check.samples + 1}"
        print(
            f"{label:38s} {seconds:9.2f} {check.sampled_intervals:18d} {check.missed:7d}"
            f"  (timelines against samples: {len(check.disagreements)} disagreements)"
        )
    for steps in [int(s) for s in args.steps.split(",") if s.strip()]:
        seconds, seen = sampling(scene, steps)
        label = f"fixed-step sampling, {steps} steps"
        print(f"{label:38s} {seconds:9.2f} {'':18s} {missed(found, seen):7d}")
    if args.whole:
        started = time.perf_counter()
        result = simulate(scene, broad_phase=True, workers=2, progress=False)
        print(
            f"whole scene (totem of {args.m} pieces, contacts with it and mutual, 2 workers): "
            f"{time.perf_counter() - started:.1f} s, {sum(len(p.events) for p in result.pairs)} events with "
            f"the totem, {len(result.mutual or [])} pairs of bodies meet"
        )


if __name__ == "__main__":
    main()
