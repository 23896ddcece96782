"""Many-body benchmark: the broad phase against the lazy engine and against fixed-step sampling.

The generated scene (``quadric_contact.scenes.manybody.many_body_scene``: N ellipsoids on
straight paths around a totem of M quadric pieces separated by M - 1 planes) is
run

* with the certified broad phase on W worker processes (the command-line
  default for ``quadric-contact simulate many_bodies``), and on one;
* with the lazy engine alone (no broad phase), on one process;

and the timelines are compared (they must be identical).  Then the usual
practice, fixed-step sampling, is run at several step counts S: at each of S + 1
evenly spaced times every ellipsoid's matrix is evaluated (binary64) and
Algorithms 1-2 are applied to the whole stack with the array predicates
(``relative_position`` on the planes, ``transversal_contact`` on the pieces the
zones reach, certified mode); for each S the time and the number of exact
contact intervals in which no sample saw the contact are printed.

With ``--mutual`` the bodies' contacts with each other are wanted too (the whole
job: contacts with the totem and mutual contacts, one ``simulate`` call), and a
subset of the pairs of bodies (``--dense-pairs``: pairs that meet and near misses)
is compared with the static exact decision at ``--dense-samples`` evenly spaced
rational times (the contact intervals that sampling finds and the timelines miss:
0 expected).

Usage::

    PYTHONPATH=src python benchmarks/bench_manybody.py [--n 1000] [--m 16] [--workers 2]
        [--steps 10,100,1000] [--skip-lazy] [--mutual] [--dense-pairs 30] [--dense-samples 256]

The time target of the whole job, 1000 bodies with the totem of 16 pieces and mutual
contacts on 2 processes, is 60 s: ``--mutual --skip-lazy --steps ""`` runs just that
(and the dense check).

The machine is shared: the figures are indicative.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import quadric_contact as qc
from quadric_contact.scenes.composite import Piece
from quadric_contact.scenes.manybody import many_body_scene
from quadric_contact.scenes.simulate import simulate


def _entry_polys(scene):
    """Per ellipsoid, the ten upper entries of its matrix as float coefficient arrays in t
    (one motion segment per ellipsoid in the generated scene)."""
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


_UPPER = [(i, j) for i in range(4) for j in range(i, 4)]


def _matrices(coeffs, t):
    vals = np.zeros(coeffs.shape[:2])
    for d in range(coeffs.shape[2] - 1, -1, -1):
        vals = vals * t + coeffs[:, :, d]
    M = np.zeros((coeffs.shape[0], 4, 4))
    for k, (i, j) in enumerate(_UPPER):
        M[:, i, j] = M[:, j, i] = vals[:, k]
    return M


def sampling(scene, steps, mode="certified"):
    """Fixed-step sampling with the array predicates: returns (seconds, seen) where
    ``seen[(ellipsoid index, piece name)]`` lists the sample times with contact."""
    (obj,) = scene.objects
    coeffs = _entry_polys(scene)
    t0, t1 = scene.span
    n = len(scene.ellipsoids)
    seen: dict[tuple[int, str], list[float]] = {}
    start = time.perf_counter()
    for k in range(steps + 1):
        t = float(t0 + (t1 - t0) * Fraction(k, steps))
        E = _matrices(coeffs, t)

        def visit(node, mask, E=E, t=t):
            if node is None or not mask.any():
                return
            idx = np.flatnonzero(mask)
            if isinstance(node, Piece):
                hit = qc.transversal_contact(E[idx], node.quadric.to_numpy(float), mode=mode) != 0
                for i in idx[hit]:
                    seen.setdefault((int(i), node.name), []).append(t)
                return
            side = qc.relative_position(E[idx], node.plane.to_numpy(float), mode=mode)
            plus = np.zeros(n, dtype=bool)
            minus = np.zeros(n, dtype=bool)
            plus[idx] = (side == 1) | (side == 0)
            minus[idx] = (side == -1) | (side == 0)
            visit(node.plus, plus)
            visit(node.minus, minus)

        visit(obj.root, np.ones(n, dtype=bool))
    return time.perf_counter() - start, seen


def missed(result, seen):
    """(missed, total): exact contact intervals (per ellipsoid and piece) without a
    sample that saw that contact."""
    index = {e.name: i for i, e in enumerate(result.scene.ellipsoids)}
    total = miss = 0
    for pair in result.pairs:
        i = index[pair.ellipsoid]
        for piece in pair.object.pieces:
            run = None
            intervals = []
            for ep in pair.episodes:
                v = dict(ep.state.pieces).get(piece.name)
                if v is not None and v.contact:
                    run = [run[0] if run else ep.start, ep.end]
                elif run:
                    intervals.append(run)
                    run = None
            if run:
                intervals.append(run)
            for a, b in intervals:
                if a == b:
                    continue
                total += 1
                lo, hi = float(a), float(b)
                if not any(lo <= s <= hi for s in seen.get((i, piece.name), [])):
                    miss += 1
    return miss, total


def same_timelines(a, b):
    """The same events in every pair, the times compared exactly."""
    return all(
        p.ellipsoid == q.ellipsoid
        and len(p.events) == len(q.events)
        and all(
            e.time.compare(f.time) == 0 and e.changes() == f.changes()
            for e, f in zip(p.events, q.events, strict=True)
        )
        for p, q in zip(a.pairs, b.pairs, strict=True)
    )


def _cpu_seconds():
    """CPU time of this process and of its finished children (the workers)."""
    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def _mutual_report(scene, broad, args):
    """The mutual part of the whole job, and the dense exact sampling of a subset of pairs."""
    from quadric_contact.testing.mutual_sampling import dense_check, near_pairs

    led = broad.ledger.done
    met = broad.mutual or []
    print(
        f"  mutual: {len(met)} pairs of bodies meet; {led['mutual_pencils']} pencils det(l A(t) + B(t)), "
        f"{led['separated_windows']} (pair, window) certified apart by their centres, "
        f"{led['pruned_pairs']} pairs pruned in all (totem targets and pairs of bodies)"
    )
    if args.dense_pairs <= 0:
        return
    meeting = (2 * args.dense_pairs + 2) // 3
    pairs = near_pairs(scene, met, meeting=meeting, near=args.dense_pairs - meeting, seed=args.seed)
    t = time.perf_counter()
    check = dense_check(scene, met, pairs, samples=args.dense_samples, workers=args.workers)
    print(
        f"  dense exact sampling of {check.pairs} pairs ({meeting} that meet, the rest near misses) at "
        f"{check.samples + 1} times each: {time.perf_counter() - t:.1f} s; {check.sampled_intervals} sampled "
        f"contact intervals, {check.missed} missed by the timelines, {len(check.disagreements)} samples that "
        f"disagree; {check.exact_intervals} exact intervals, {check.unseen} shorter than the step"
    )


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1000, help="ellipsoids")
    ap.add_argument("--m", type=int, default=16, help="pieces of the totem")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--workers", type=int, default=2, help="processes for the broad-phase run")
    ap.add_argument("--steps", default="10,100,1000", help="step counts of the sampling peer")
    ap.add_argument("--skip-lazy", action="store_true", help="do not run the engine without the broad phase")
    ap.add_argument("--mutual", action="store_true", help="also the contacts of the bodies with each other")
    ap.add_argument("--dense-pairs", type=int, default=30, help="--mutual: pairs checked by dense sampling")
    ap.add_argument("--dense-samples", type=int, default=256, help="--mutual: sample times per pair")
    args = ap.parse_args(argv)

    t = time.perf_counter()
    scene = many_body_scene(args.n, args.m, seed=args.seed, mutual=args.mutual)
    print(
        f"scene: {args.n} ellipsoids, {args.m} pieces, {args.m - 1} planes; generated and checked "
        f"({scene.work.done['smallness_checks']} exact smallness checks, one per shape and piece) "
        f"in {time.perf_counter() - t:.2f} s"
    )
    unit = qc.Quadric.sphere(1).to_numpy(float)
    for plane_or_piece in (unit, qc.Quadric.plane((0, 0, 1), 0).to_numpy(float)):  # load the kernels first
        if not args.steps.strip():
            break  # no sampling peer: no kernels
        qc.transversal_contact(unit[None], plane_or_piece)
        qc.relative_position(unit[None], plane_or_piece)

    cpu = _cpu_seconds()
    broad = simulate(scene, broad_phase=True, workers=args.workers, progress=False)
    cpu = _cpu_seconds() - cpu
    events = sum(len(p.events) for p in broad.pairs)
    print(
        f"\nbroad phase + exact events, {args.workers} processes: {broad.seconds:8.2f} s  ({events} events; "
        f"{cpu:.2f} s of CPU in all processes: the machine may be shared)"
    )
    if args.mutual:
        _mutual_report(scene, broad, args)
        if args.skip_lazy and not args.steps.strip():
            return
    one = simulate(scene, broad_phase=True, progress=False)
    print(f"broad phase + exact events, 1 process  : {one.seconds:8.2f} s")
    led = broad.ledger.done
    print(
        f"  ledger: {led['broad_phase_tests']} box tests, {led['pruned_pairs']} (ellipsoid, segment, "
        f"plane or piece) pairs pruned, {led['pruned_stretches']} stretches pruned, "
        f"{led['characteristic_polynomials']} pencils in time formed "
        f"(of {broad.ledger.full['characteristic_polynomials']} for every plane and piece), "
        f"{led['static_pencils']} static pencils, {events} events"
    )
    if not args.skip_lazy:
        lazy = simulate(scene, progress=False)
        same = same_timelines(lazy, broad)
        print(
            f"lazy engine without the broad phase, 1 process: {lazy.seconds:8.2f} s "
            f"({lazy.ledger.done['characteristic_polynomials']} pencils in time; "
            f"timelines {'identical' if same else 'DIFFERENT'})"
        )
        print(f"  ratio lazy / broad (1 process): {lazy.seconds / one.seconds:.2f}")
    print("\nfixed-step sampling (array predicates, certified mode, binary64 matrices):")
    for steps in [int(s) for s in args.steps.split(",") if s.strip()]:
        secs, seen = sampling(scene, steps)
        miss, total = missed(broad, seen)
        print(
            f"  {steps:6d} steps: {secs:8.2f} s; misses {miss} of {total} exact contact intervals "
            f"({100 * miss / max(total, 1):.1f}%), and gives no event time"
        )


if __name__ == "__main__":
    main()
