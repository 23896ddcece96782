"""Scene benchmark: the lazy plan against a full evaluation and against dense sampling.

Prints, for the default scene (the bee and the tree, Example 17) and for a
larger generated scene (N ellipsoids on keyframed tours around a totem of M
quadric pieces separated by a balanced tree of M - 1 planes):

* wall time and the work ledger of the lazy plan (only what the effects need,
  Algorithms 1-2 in time) and of the full evaluation (every effect for every
  piece on every segment), as a ratio measured in the same run;
* for comparison with the usual practice, the static Algorithm 2 evaluated at
  S evenly spaced sample times per ellipsoid (time per run, and how many of
  the exact contact intervals the samples miss entirely).

Usage::

    PYTHONPATH=src python benchmarks/bench_scenes.py [--n 24] [--m 16] [--segments 4]
        [--samples 400] [--repeat 3] [--write-scene big.toml]

``--write-scene`` saves the generated scene, so that
``quadric-contact simulate big.toml`` runs it from the command line.
Timings on a shared machine are noisy: compare the ratios.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from quadric_contact.scenes.composite import algorithm_2
from quadric_contact.scenes.scene_toml import builtin_scene, parse_scene
from quadric_contact.scenes.simulate import simulate


def totem_scene(n: int, m: int, segments: int, effects: list[str]) -> str:
    """TOML of N small ellipsoids touring a stack of M pieces (z in [2k, 2k + 2]).

    Piece k alternates between a sphere of radius 3/2 centred at height 2k + 1
    and a one-sheet hyperboloid with its waist (radius 1) there; the pieces are
    separated by the planes z = 2k in a balanced binary tree.
    """

    def tree(lo: int, hi: int) -> str:  # pieces lo .. hi-1
        if hi - lo == 1:
            return f'"p{lo}"'
        mid = (lo + hi) // 2
        return f'{{ plane = "z = {2 * mid}", plus = {tree(mid, hi)}, minus = {tree(lo, mid)} }}'

    out = [
        "[scene]",
        f'name = "Totem: {n} ellipsoids, {m} pieces"',
        f"time = [0, {segments}]",
        f"effects = {effects!r}".replace("'", '"'),
        'on_not_small = "warn"',
        "",
        "[[object]]",
        'name = "totem"',
        f"tree = {tree(0, m)}",
    ]
    for k in range(m):
        c = 2 * k + 1
        eq = f"x^2 + y^2 + (z - {c})^2 = 2.25" if k % 2 == 0 else f"x^2 + y^2 - (z - {c})^2/4 = 1"
        out += ["", "[[object.piece]]", f'name = "p{k}"', f'equation = "{eq}"']
    height = 2 * m
    for i in range(n):
        # a deterministic tour: radius 1.2 .. 2.6, heights spread over the totem
        keys = []
        for j in range(segments + 1):
            ang = (i * 7 + j * 3) % 12
            r = Fraction(12 + (i * 5 + j * 11) % 15, 10)
            z = Fraction((i * 37 + j * 53) % (10 * height), 10)
            # positions on a 12-gon with rational coordinates (3-4-5 style directions)
            dirs = [
                (1, 0),
                (Fraction(4, 5), Fraction(3, 5)),
                (0, 1),
                (Fraction(-3, 5), Fraction(4, 5)),
                (-1, 0),
                (Fraction(-4, 5), Fraction(-3, 5)),
                (0, -1),
                (Fraction(3, 5), Fraction(-4, 5)),
                (Fraction(3, 5), Fraction(4, 5)),
                (Fraction(-4, 5), Fraction(3, 5)),
                (Fraction(-3, 5), Fraction(-4, 5)),
                (Fraction(4, 5), Fraction(-3, 5)),
            ]
            dx, dy = dirs[ang]
            keys.append(f'{{ t = {j}, at = ["{r * dx}", "{r * dy}", "{z}"] }}')
        out += [
            "",
            "[[ellipsoid]]",
            f'name = "e{i}"',
            'standard = "ellipsoid"',
            "semi_axes = [0.2, 0.15, 0.1]",
            "[ellipsoid.motion]",
            'type = "keyframes"',
            "keys = [" + ", ".join(keys) + "]",
        ]
    return "\n".join(out) + "\n"


def timed(fn, repeat):
    times, result = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), result


def sampling(scene, samples):
    """Static Algorithm 2 at evenly spaced times; returns (seconds, contacts seen per pair)."""
    t0, t1 = scene.span
    seen = {}
    start = time.perf_counter()
    for ell in scene.ellipsoids:
        for obj in scene.objects:
            small = {p.name: scene.smallness.get((ell.name, obj.name, p.name)) for p in obj.pieces}
            small = {
                k: (v.report if v is not None and v.report is not None else bool(v and v.small))
                for k, v in small.items()
            }
            hits = []
            for i in range(samples + 1):
                t = t0 + (t1 - t0) * Fraction(i, samples)
                E = ell.trajectory.placed(ell.quadric, t, t0, t1)
                hits.append((t, algorithm_2(E, obj, small=small).contact))
            seen[(ell.name, obj.name)] = hits
    return time.perf_counter() - start, seen


def lean_sampling(scene, samples):
    """The cheapest exact sampling: at each sample time the pencils of Algorithms 1-2
    only (Corollary 15 on the integer coefficients, Corollary 10 on the root
    structure), without the audit values of the public predicates."""
    from quadric_contact.model.quadric import Quadric
    from quadric_contact.scenes.composite import Piece
    from quadric_contact.scenes.trajectory import poly_eval
    from quadric_contact.theory.pencil import CharacteristicPolynomial

    t0, t1 = scene.span
    seen = {}
    start = time.perf_counter()
    for ell in scene.ellipsoids:
        segs = ell.trajectory.segments(t0, t1, ell.center)
        uppers = [seg.moved_upper(ell.quadric, ell.center) for seg in segs]
        for obj in scene.objects:
            hits = []
            for i in range(samples + 1):
                t = t0 + (t1 - t0) * Fraction(i, samples)
                k = next(j for j, seg in enumerate(segs) if seg.t0 <= t <= seg.t1)
                E = Quadric._from_upper(tuple(poly_eval(p, t) for p in uppers[k]))
                contact = False

                def visit(node, E=E):
                    nonlocal contact
                    if node is None:
                        return
                    if isinstance(node, Piece):
                        P = CharacteristicPolynomial(E, node.quadric)
                        if not P.structure.all_real:
                            contact = True
                        return
                    C = CharacteristicPolynomial(E, node.plane).integer_coefficients
                    disc = C[3] * C[3] - 4 * C[4] * C[2]
                    if disc < 0 or C[3] > 0:
                        visit(node.plus)
                    if disc < 0 or C[3] < 0:
                        visit(node.minus)

                visit(obj.root)
                for p in obj.extra_pieces:
                    visit(p)
                hits.append((t, contact))
            seen[(ell.name, obj.name)] = hits
    return time.perf_counter() - start, seen


def missed_intervals(result, seen):
    """Exact contact intervals that no sample falls into."""
    missed = total = 0
    for pair in result.pairs:
        hits = seen[(pair.ellipsoid, pair.object.name)]
        for ep in pair.episodes:
            if ep.state.contact and ep.start != ep.end:
                total += 1
                lo, hi = float(ep.start), float(ep.end)
                if not any(lo <= float(t) <= hi and c for t, c in hits):
                    missed += 1
    return missed, total


def report(title, scene, repeat, samples):
    print(f"\n== {title}")
    print(
        f"   {len(scene.ellipsoids)} ellipsoid(s), {sum(len(o.pieces) for o in scene.objects)} piece(s), "
        f"{sum(len(o.splits()) for o in scene.objects)} plane(s), effects {list(scene.effects)}"
    )
    lazy_t, lazy = timed(lambda: simulate(scene, progress=False), repeat)
    full_t, full = timed(lambda: simulate(scene, full=True, progress=False), repeat)
    events = sum(len(p.events) for p in lazy.pairs)
    print(f"   lazy plan : {lazy_t * 1000:9.1f} ms  ({events} events)")
    print(f"   full eval : {full_t * 1000:9.1f} ms  (ratio full/lazy {full_t / lazy_t:5.2f})")
    n = samples + 1
    samp_t, seen = sampling(scene, samples)
    missed, total = missed_intervals(lazy, seen)
    print(
        f"   sampling  : {samp_t * 1000:9.1f} ms  for {n} runs of the public algorithm_2 per ellipsoid "
        f"(ratio {samp_t / lazy_t:5.2f}); misses {missed} of {total} contact intervals"
    )
    lean_t, lean_seen = lean_sampling(scene, samples)
    lean_missed, _ = missed_intervals(lazy, lean_seen)
    print(
        f"   lean samp.: {lean_t * 1000:9.1f} ms  for {n} bare pencil evaluations of Algorithms 1-2 per "
        f"ellipsoid (ratio {lean_t / lazy_t:5.2f}); misses {lean_missed} of {total}"
    )
    shortest = min(
        (
            float(ep.end) - float(ep.start)
            for p in lazy.pairs
            for ep in p.episodes
            if ep.state.contact and ep.start != ep.end
        ),
        default=None,
    )
    if shortest:
        span = float(scene.span[1] - scene.span[0])
        need = int(span / shortest) + 1
        est = lean_t * need / n
        print(
            f"   to be sure to see every contact interval, sampling needs a step below the shortest one "
            f"({shortest:.3g}): >= {need} samples per ellipsoid, about {est * 1000:.0f} ms at the lean rate "
            f"(ratio {est / lazy_t:.2f}), and still no exact times"
        )
    print("   ledger of the lazy plan (full = every effect for every piece on every segment):")
    for line in lazy.ledger.format().splitlines():
        print("     " + line)
    print("   ledger of the full evaluation (done):")
    for line in full.ledger.format().splitlines()[1:]:
        print("     " + line.split()[0].ljust(28) + line.split()[1].rjust(8))
    return lazy


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=24, help="ellipsoids in the generated scene")
    ap.add_argument("--m", type=int, default=16, help="pieces in the generated scene")
    ap.add_argument("--segments", type=int, default=4, help="keyframe segments per ellipsoid")
    ap.add_argument(
        "--samples", type=int, default=200, help="sample times per ellipsoid for the sampling peer"
    )
    ap.add_argument("--repeat", type=int, default=3, help="runs per measurement (median)")
    ap.add_argument("--write-scene", metavar="FILE", help="save the generated scene as TOML")
    args = ap.parse_args(argv)

    report("default scene: the bee and the tree (Example 17)", builtin_scene(), args.repeat, args.samples)
    text = totem_scene(args.n, args.m, args.segments, ["zone", "contact", "first_contact"])
    if args.write_scene:
        Path(args.write_scene).write_text(text)
        print(
            f"\n(generated scene written to {args.write_scene}: quadric-contact simulate {args.write_scene})"
        )
    t = time.perf_counter()
    scene = parse_scene(text, "<totem>")
    print(
        f"\n(loading the generated scene, with {len(scene.smallness)} exact smallness checks: "
        f"{(time.perf_counter() - t) * 1000:.0f} ms)"
    )
    report(f"generated scene: {args.n} ellipsoids x {args.m} pieces", scene, args.repeat, args.samples)
    zone = parse_scene(
        text.replace('effects = ["zone", "contact", "first_contact"]', 'effects = ["zone"]'), "<z>"
    )
    zt, zr = timed(lambda: simulate(zone, progress=False), args.repeat)
    pencils = sum(v["characteristic_polynomials"] for k, v in zr.ledger.by_target.items() if "/" in k)
    print(
        f"\n== the same scene with effects ['zone'] only: {zt * 1000:.1f} ms; "
        f"pencils of pieces formed: {pencils}"
    )


if __name__ == "__main__":
    main()
