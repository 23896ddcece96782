"""How far apart, how deep: the certified signed distance against coal and python-fcl.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_distance.py [--pairs N] [--seed S] [--directions D]

The pairs every library gets, in binary64: an ellipsoid with semi-axes ``(a, b, c)``,
axis-aligned at the origin, against a sphere of radius ``rho`` centred at ``x`` (coal and FCL
take ``Ellipsoid(a, b, c)`` and ``Sphere(rho)`` with a translation), and the same ellipsoids
against a half-space ``n . x <= d`` (``Halfspace(n, d)``).  The package takes the exact
rational values of the same binary64 numbers (a float is an exact dyadic rational), so every
library answers about the same pair; the ellipsoid is axis-aligned so that no rotation matrix
rounded to binary64 (not exactly orthogonal) makes the pairs differ.

The reference is :func:`quadric_contact.modes.distance.certified.distance_certified` asked
for 30 digits: an arb enclosure of the exact signed distance of the pair (the global minimum:
every critical point is isolated), cross-checked against the exact algebraic answer of
:func:`quadric_contact.theory.distance.distance_exact` on the first pairs of every table.
The error of a method is ``|its distance - the reference|``; for the certified method asked
for 16 digits it is bounded by its own enclosure's width.

Tables:

1. *random pairs*: semi-axes 0.5-2, radius 0.2-1, centres in ``[-4, 4]^3`` (about a quarter
   of the pairs penetrate);
2. *near tangency*: the sphere placed at ``10^-k`` (``k = 1..15``) from touching along the
   outward normal of a point of the ellipsoid, in ``--directions`` directions: the error of
   each method at each gap;
3. *deep penetration*: the centre of the sphere inside the ellipsoid;
4. *half-spaces*: random ellipsoids against random half-spaces, both sides of touching;
5. *two ellipsoids*: random pairs, deep penetration and near tangency (the second ellipsoid
   placed so that the supporting planes with a common normal are ``10^-k`` apart), where the
   package isolates every critical point of the contact system by the Krawczyk operator (the
   reference: the same method asked for 30 digits; no exact path exists for this pair);
6. *stack distance*: the compiled duality kernel on a float64 stack of ellipsoid pairs (time
   a pair, widths), the scalar path on the pairs it leaves, coal on the same pairs;
7. *first-contact scale*: the compiled certified kernel's throughput on a float64 stack of
   ellipsoid pairs (the block kernel on one and two threads, the scalar kernel), against the
   exact scalar path; then the same with ``scale="both"`` (its own kernel, and the fraction of
   pairs it certifies).

The ``float`` mode of the package is a binary64 interval enclosure (its error is bounded).

Times are medians of wall-clock time per pair on a shared machine, with the Python call
included for every method (coal and python-fcl through their bindings, one pair per call):
indicative only.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact import Quadric
from quadric_contact.modes.distance.certified import distance_certified
from quadric_contact.modes.distances import distance
from quadric_contact.theory.distance import distance_exact


def _ellipsoid(axes: tuple[float, float, float]) -> Quadric:
    return Quadric.ellipsoid(*(Fraction(a) for a in axes))


def _sphere(rho: float, centre: np.ndarray) -> Quadric:
    return Quadric.sphere(Fraction(rho), [Fraction(float(x)) for x in centre])


def _halfspace(n: np.ndarray, d: float) -> Quadric:
    return Quadric.plane([Fraction(float(x)) for x in n], Fraction(d))


def _coal(tolerance: float | None = None) -> Callable[..., float] | None:
    try:
        import coal
    except ImportError:
        return None
    req = coal.DistanceRequest()
    req.enable_signed_distance = True
    if tolerance is not None:  # coal's defaults are 1e-6 (GJK) and 1e-6 (EPA)
        req.gjk_tolerance = tolerance
        req.epa_tolerance = tolerance
        req.gjk_max_iterations = 1000
        req.epa_max_iterations = 1000
    ident = coal.Transform3s()

    def run(kind: str, axes: Any, other: Any) -> float:
        e = coal.Ellipsoid(*axes)
        res = coal.DistanceResult()
        if kind == "sphere":
            rho, centre = other
            t = coal.Transform3s(np.eye(3), np.asarray(centre, dtype=float))
            return float(coal.distance(coal.Sphere(rho), t, e, ident, req, res))
        if kind == "ellipsoid":
            axes2, centre = other
            t = coal.Transform3s(np.eye(3), np.asarray(centre, dtype=float))
            return float(coal.distance(e, ident, coal.Ellipsoid(*axes2), t, req, res))
        n, d = other
        return float(coal.distance(e, ident, coal.Halfspace(np.asarray(n, dtype=float), d), ident, req, res))

    return run


def _fcl() -> Callable[..., float] | None:
    try:
        import fcl
    except ImportError:
        return None
    req = fcl.DistanceRequest(enable_nearest_points=False, enable_signed_distance=True)

    def run(kind: str, axes: Any, other: Any) -> float | None:
        if kind == "halfspace":
            return None  # FCL has no distance between an ellipsoid and a half-space ("not supported")
        e = fcl.CollisionObject(fcl.Ellipsoid(*axes), fcl.Transform())
        if kind == "ellipsoid":
            axes2, centre = other
            o = fcl.CollisionObject(fcl.Ellipsoid(*axes2), fcl.Transform(np.asarray(centre, dtype=float)))
            return float(fcl.distance(e, o, req, fcl.DistanceResult()))
        rho, centre = other
        o = fcl.CollisionObject(fcl.Sphere(rho), fcl.Transform(np.asarray(centre, dtype=float)))
        return float(fcl.distance(o, e, req, fcl.DistanceResult()))

    return run


def _moved(axes: Any, centre: Any) -> Quadric:
    return Quadric.ellipsoid(*(Fraction(a) for a in axes), center=[Fraction(float(x)) for x in centre])


def _ours(kind: str, axes: Any, other: Any, digits: int = 16) -> Any:
    e = _ellipsoid(axes)
    if kind == "ellipsoid":
        return distance_certified(e, _moved(*other), digits=digits)
    if kind == "sphere":
        rho, centre = other
        return distance_certified(_sphere(rho, centre), e, digits=digits)
    n, d = other
    return distance_certified(e, _halfspace(n, d), digits=digits)


def _reference(kind: str, axes: Any, other: Any) -> Fraction:
    lo, hi = _ours(kind, axes, other, digits=30).bounds
    return (lo + hi) / 2


def _float_mode(kind: str, axes: Any, other: Any) -> float:
    e = _ellipsoid(axes)
    if kind == "ellipsoid":
        q = _moved(*other)
    elif kind == "sphere":
        e, q = _sphere(*other), e
    else:
        q = _halfspace(*other)
    return distance(e, q, mode="float").distance


def _exact(kind: str, axes: Any, other: Any) -> Any:
    e = _ellipsoid(axes)
    if kind == "sphere":
        rho, centre = other
        return distance_exact(_sphere(rho, centre), e).distance
    n, d = other
    return distance_exact(e, _halfspace(n, d)).distance


def _unit(rng: np.random.Generator) -> np.ndarray:
    v = rng.normal(size=3)
    return v / np.linalg.norm(v)


def _surface_point(axes: tuple[float, float, float], u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A point of the ellipsoid along ``u`` from its centre and the outward unit normal there."""
    a = np.asarray(axes)
    p = u / math.sqrt(float(np.sum((u / a) ** 2)))
    n = p / a**2
    return p, n / np.linalg.norm(n)


def _error(value: float, ref: Fraction) -> float | None:
    """``|value - ref|``, or None for an answer that is not a distance (not finite, or off by
    more than 10^6: a solver's failure value)."""
    if not math.isfinite(value) or abs(value) > 1e6:
        return None
    return float(abs(Fraction(value) - ref))


def _timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _run(
    name: str, pairs: list[tuple[str, Any, Any]], methods: dict[str, Callable[..., Any]], check_exact: int
) -> dict:
    refs = [_reference(*p) for p in pairs]
    for p, r in zip(pairs[:check_exact], refs, strict=False):
        if p[0] == "ellipsoid":
            break  # no exact path for two ellipsoids: the reference is the certified enclosure
        x = _exact(*p)
        assert abs(Fraction(x.decimal(40)) - r) <= abs(r) * Fraction(1, 10**28) + Fraction(1, 10**40), (
            p,
            x,
            r,
        )
    rows = {}
    for label, fn in methods.items():
        times, errs, rel, failed = [], [], [], 0
        for p, r in zip(pairs, refs, strict=True):
            got, dt = _timed(lambda p=p, fn=fn: fn(*p))
            if got is None:
                break
            times.append(dt)
            e = _error(float(got), r)
            if e is None:
                failed += 1
                continue
            errs.append(e)
            rel.append(e / abs(float(r)) if r != 0 else math.inf)
        if times:
            rows[label] = (
                statistics.median(times),
                statistics.median(errs) if errs else math.nan,
                max(errs, default=math.nan),
                max(rel, default=math.nan),
                failed,
            )
    print(f"\n### {name} ({len(pairs)} pairs; the first {check_exact} checked against the exact answer)\n")
    print("| method | median time / pair | median abs. error | max abs. error | max rel. error | failed |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for label, (t, me, mx, mr, nf) in rows.items():
        print(f"| {label} | {t * 1e6:,.0f} µs | {me:.1e} | {mx:.1e} | {mr:.1e} | {nf} |")
    return rows


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=200)
    ap.add_argument("--directions", type=int, default=4)
    ap.add_argument("--seed", type=int, default=31)
    ap.add_argument("--ellipsoid-pairs", type=int, default=16)
    ap.add_argument("--scale-pairs", type=int, default=1_000_000)
    ap.add_argument("--stack-pairs", type=int, default=200_000)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)

    def ours(kind: str, axes: Any, other: Any) -> float:
        return float(_ours(kind, axes, other))

    methods: dict[str, Callable[..., Any]] = {
        "quadric-contact certified (16 digits)": ours,
        "quadric-contact float (interval bound)": _float_mode,
    }
    peers: tuple[tuple[str, Callable[[], Any]], ...] = (
        ("coal (GJK/EPA, default tolerances)", _coal),
        ("coal (tolerances 1e-12)", lambda: _coal(1e-12)),
        ("python-fcl (GJK/EPA)", _fcl),
    )
    for label, make in peers:
        fn = make()
        if fn is not None:
            methods[label] = fn
        else:
            print(f"{label}: not installed, skipped")

    def axes() -> tuple[float, float, float]:
        return tuple(float(x) for x in rng.uniform(0.5, 2.0, 3))  # type: ignore[return-value]

    random_pairs = []
    while len(random_pairs) < args.pairs:
        random_pairs.append(("sphere", axes(), (float(rng.uniform(0.2, 1.0)), rng.uniform(-4, 4, 3))))
    _run("random pairs: sphere against ellipsoid", random_pairs, methods, 5)

    deep = []
    for _ in range(max(10, args.pairs // 4)):
        ax = axes()
        p, n = _surface_point(ax, _unit(rng))
        h = 0.3 * min(ax)
        deep.append(("sphere", ax, (float(rng.uniform(0.2, 1.0)), p - h * n)))
    _run("deep penetration: the centre of the sphere inside the ellipsoid", deep, methods, 3)

    half = []
    for _ in range(max(10, args.pairs // 4)):
        ax = axes()
        n = _unit(rng)
        d = float(rng.uniform(-3, 3))
        half.append(("halfspace", ax, (n, d)))
    _run("half-spaces: ellipsoid against a half-space", half, methods, 3)

    _ellipsoid_tables(rng, methods, args.ellipsoid_pairs)
    _distance_stack(rng, args.stack_pairs)
    _scale_throughput(rng, args.scale_pairs)

    print("\n### near tangency: the sphere at 10^-k from touching (max abs. error over the directions)\n")
    header = "| k | reference distance | " + " | ".join(methods) + " |"
    print(header)
    print("| ---: | ---: |" + " ---: |" * len(methods))
    dirs = [_unit(rng) for _ in range(args.directions)]
    ax = (1.5, 1.0, 0.5)
    for k in range(1, 16):
        gap = 10.0**-k
        pairs = []
        for u in dirs:
            p, n = _surface_point(ax, u)
            rho = 0.25
            pairs.append(("sphere", ax, (rho, p + (rho + gap) * n)))
        refs = [_reference(*q) for q in pairs]
        if k in (1, 8, 15):
            x = _exact(*pairs[0])
            assert abs(Fraction(x.decimal(40)) - refs[0]) <= Fraction(1, 10**28)
        cells = []
        for fn in methods.values():
            errs = [_error(float(fn(*q)), r) for q, r in zip(pairs, refs, strict=True)]
            ok = [e for e in errs if e is not None]
            cells.append(
                (f"{max(ok):.1e}" if ok else "-")
                + (f" ({len(errs) - len(ok)} failed)" if len(ok) < len(errs) else "")
            )
        print(f"| {k} | {float(refs[0]):.3e} | " + " | ".join(cells) + " |")


def _support(axes: Any, n: np.ndarray) -> np.ndarray:
    """The point of the axis-aligned ellipsoid at the origin whose outward normal is ``n``."""
    a2 = np.asarray(axes) ** 2
    return a2 * n / math.sqrt(float(np.sum(a2 * n * n)))


def _ellipsoid_tables(rng: np.random.Generator, methods: dict[str, Callable[..., Any]], count: int) -> None:
    """Two ellipsoids (axis-aligned, the second translated): random, deep, near tangency."""

    def axes() -> tuple[float, float, float]:
        return tuple(float(x) for x in rng.uniform(0.5, 2.0, 3))  # type: ignore[return-value]

    rand = [("ellipsoid", axes(), (axes(), rng.uniform(-4, 4, 3))) for _ in range(count)]
    _run("random pairs: ellipsoid against ellipsoid", rand, methods, 0)
    deep = []
    for _ in range(max(4, count // 2)):
        a, b = axes(), axes()
        deep.append(("ellipsoid", a, (b, rng.uniform(-0.4, 0.4, 3) * min(a))))
    _run("deep penetration: two ellipsoids, centres close", deep, methods, 0)
    print("\n### near tangency: two ellipsoids at 10^-k from touching (max abs. error over 2 directions)\n")
    print("| k | reference distance | " + " | ".join(methods) + " |")
    print("| ---: | ---: |" + " ---: |" * len(methods))
    a, b = (1.5, 1.0, 0.5), (0.7, 1.2, 0.9)
    dirs = [_unit(rng) for _ in range(2)]
    for k in (1, 3, 5, 7, 9, 11, 13, 15):
        gap = 10.0**-k
        # supporting planes with the common normal n, gap apart: the distance is the gap
        pairs = [("ellipsoid", a, (b, _support(a, n) + gap * n + _support(b, n))) for n in dirs]
        refs = [_reference(*q) for q in pairs]
        cells = []
        for fn in methods.values():
            errs = [_error(float(fn(*q)), r) for q, r in zip(pairs, refs, strict=True)]
            ok = [e for e in errs if e is not None]
            cells.append(
                (f"{max(ok):.1e}" if ok else "-")
                + (f" ({len(errs) - len(ok)} failed)" if len(ok) < len(errs) else "")
            )
        print(f"| {k} | {float(refs[0]):.3e} | " + " | ".join(cells) + " |")


def _ellipsoid_stack(rng: np.random.Generator, m: int, spread: float = 4.0) -> np.ndarray:
    """``m`` random rotated ellipsoids (semi-axes 0.3-1.5, centres in ``[-spread, spread]^3``)."""
    from quadric_contact.testing.samples import ellipsoid_matrix

    out = np.zeros((m, 4, 4))
    for k in range(m):
        R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        axes = rng.uniform(0.3, 1.5, 3)
        out[k] = ellipsoid_matrix(axes, R, rng.uniform(-spread, spread, 3))
    return out


def _distance_stack(rng: np.random.Generator, n: int) -> None:
    """The certified distance on a float64 stack of ellipsoid pairs: the compiled duality
    kernel (separated pairs, 1e-12 relative), the compiled depth kernel (the crossing pairs it
    leaves) and the scalar path for what both leave, as ``qc.distance`` runs them; coal on the
    same pairs for the ratio."""
    if n <= 0:
        return
    from quadric_contact.modes.distance.apart_kernel import separated_ellipsoids
    from quadric_contact.modes.distance.depth_kernel import crossing_ellipsoids

    base = min(n, 4096)
    Es, Ks = _ellipsoid_stack(rng, base), _ellipsoid_stack(rng, base)
    reps = max(1, n // base)
    Es, Ks = np.tile(Es, (reps, 1, 1)), np.tile(Ks, (reps, 1, 1))
    separated_ellipsoids(Es[:10], Ks[:10])  # compiled or loaded
    crossing_ellipsoids(Es[:10], Ks[:10])
    t0 = time.perf_counter()
    enc, rest = separated_ellipsoids(Es, Ks)
    dt = time.perf_counter() - t0
    width = (enc[~rest, 1] - enc[~rest, 0]) / enc[~rest, 0]
    crossing = np.flatnonzero(rest)
    t0 = time.perf_counter()
    enc2, rest2 = crossing_ellipsoids(Es[crossing], Ks[crossing])
    dt2 = time.perf_counter() - t0
    width2 = (enc2[~rest2, 1] - enc2[~rest2, 0]) / np.abs(enc2[~rest2, 1])
    left = crossing[rest2]
    t1 = time.perf_counter()
    sample = left[:3]
    for k in sample:
        distance(Quadric.from_matrix(Es[k]), Quadric.from_matrix(Ks[k]), digits=12)
    scalar = (time.perf_counter() - t1) / max(1, len(sample))
    print(f"\n### certified distance on a stack of {len(Es):,} ellipsoid pairs\n")
    print("| path | pairs | time / pair | median rel. width | max rel. width |")
    print("| --- | ---: | ---: | ---: | ---: |")
    print(
        f"| compiled duality kernel (separated pairs) | {int((~rest).sum()):,} | "
        f"{dt / len(Es) * 1e6:.2f} µs | {np.median(width):.1e} | {np.max(width):.1e} |"
    )
    if crossing.size:
        print(
            f"| compiled depth kernel (the crossing pairs it leaves) | {int((~rest2).sum()):,} | "
            f"{dt2 / crossing.size * 1e6:.2f} µs | "
            + (f"{np.median(width2):.1e} | {np.max(width2):.1e} |" if width2.size else "- | - |")
        )
    print(
        f"| scalar certified path (the pairs left: touching or too shallow) | {left.size:,} | "
        + (f"{scalar * 1e6:,.0f} µs | - | - |" if left.size else "- | - | - |")
    )
    mean = (dt + dt2 + left.size * scalar) / len(Es)
    print(f"\nmean time a pair, every path: {mean * 1e6:,.2f} µs")
    coal_fn = _coal()
    if coal_fn is None:
        return
    import coal

    req = coal.DistanceRequest()
    req.enable_signed_distance = True
    res = coal.DistanceResult()
    shapes = []
    for k in range(min(base, 2000)):
        pair = []
        for M in (Es[k], Ks[k]):
            A, a = M[:3, :3], M[:3, 3]
            c = -np.linalg.solve(A, a)
            r = c @ A @ c - M[3, 3]
            w, V = np.linalg.eigh(A / r)
            pair.append((coal.Ellipsoid(*(1 / np.sqrt(w))), coal.Transform3s(V, c)))
        shapes.append(pair)
    t2 = time.perf_counter()
    for (s1, t1_), (s2, t2_) in shapes:
        coal.distance(s1, t1_, s2, t2_, req, res)
    dc = (time.perf_counter() - t2) / len(shapes)
    print(
        f"coal (GJK/EPA, default tolerances, one call a pair) on the same pairs: {dc * 1e6:.2f} µs a pair; "
        f"ratio kernel / coal: {dt / len(Es) / dc:.2f}"
    )


def _scale_throughput(rng: np.random.Generator, n: int) -> None:
    """The certified first-contact scale on a float64 stack of ellipsoid pairs (the compiled
    kernel), against the exact scalar path on a few of them."""
    if n <= 0:
        return
    from quadric_contact.modes.distance.scale_blocks import scale_stack
    from quadric_contact.modes.distances import contact_scale

    base = min(n, 4096)
    Es, Qs = _ellipsoid_stack(rng, base), _ellipsoid_stack(rng, base)
    reps = max(1, n // base)
    Es, Qs = np.tile(Es, (reps, 1, 1)), np.tile(Qs, (reps, 1, 1))
    scale_stack(Es[:10], Qs[:10])  # compiled or loaded
    scale_stack(Es[:10], Qs[:10], blocks=False)

    def timed(**kw: Any) -> tuple[float, np.ndarray, np.ndarray]:
        best = math.inf
        for _ in range(3):
            t0 = time.perf_counter()
            enc, rest = scale_stack(Es, Qs, **kw)
            best = min(best, time.perf_counter() - t0)
        return best, enc, rest

    runs = [(f"block kernel, {t} thread{'s' if t > 1 else ''}", *timed(threads=t)) for t in (1, 2)]
    runs.append(("scalar kernel, 2 threads", *timed(threads=2, blocks=False)))
    t1 = time.perf_counter()
    for k in range(5):
        contact_scale(Quadric.from_matrix(Es[k]), Quadric.from_matrix(Qs[k]))
    exact = (time.perf_counter() - t1) / 5
    print(f"\n### first-contact scale on a stack of {len(Es):,} ellipsoid pairs (certified kernel)\n")
    print("| method | pairs / s | median rel. width | max rel. width | left to the exact path |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for name, dt, enc, rest in runs:
        width = (enc[:, 1] - enc[:, 0]) / enc[:, 1]
        print(
            f"| {name} | {len(Es) / dt:,.0f} | {np.median(width[~rest]):.1e} | "
            f"{np.max(width[~rest]):.1e} | {int(rest.sum())} |"
        )
    print(f"| exact scalar path | {1 / exact:,.0f} | 0 | 0 | - |")
    print(f"\nratio block kernel (1 thread) / exact: {len(Es) / runs[0][1] * exact:,.0f}x")
    _scale_both_throughput(Es, Qs)


def _scale_both_throughput(Es: np.ndarray, Qs: np.ndarray) -> None:
    """``scale="both"`` (the Perram-Wertheim scale) on the same stack: the compiled kernel of
    :mod:`quadric_contact.modes.distance.scale_both` (pairs a second, the fraction it certifies), against the
    exact scalar path."""
    from quadric_contact.modes.distance.scale_both import _flags
    from quadric_contact.modes.distances import contact_scale

    _flags(Es[:10], Qs[:10])  # compiled or loaded
    _flags(Es[:10], Qs[:10], blocks=False)
    rows = []
    for name, kw in (
        ("block kernel, 1 thread", {"threads": 1}),
        ("block kernel, 2 threads", {"threads": 2}),
        ("scalar kernel, 2 threads", {"threads": 2, "blocks": False}),
    ):
        best = math.inf
        for _ in range(3):
            t0 = time.perf_counter()
            enc, flag = _flags(Es, Qs, **kw)  # type: ignore[arg-type]
            best = min(best, time.perf_counter() - t0)
        rows.append((name, best, enc, flag))
    t1 = time.perf_counter()
    for k in range(5):
        contact_scale(Quadric.from_matrix(Es[k]), Quadric.from_matrix(Qs[k]), scale="both")
    exact = (time.perf_counter() - t1) / 5
    print(f'\n### first-contact scale, scale="both", on the same {len(Es):,} pairs (certified kernel)\n')
    print(
        "| method | pairs / s | left to the exact path | in the blocks | median rel. width | max rel. width |"
    )
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name, dt, enc, flag in rows:
        ok = flag != 1
        width = (enc[ok, 1] - enc[ok, 0]) / enc[ok, 1]
        print(
            f"| {name} | {len(Es) / dt:,.0f} | {int((~ok).sum())} | {(flag == 0).mean():.5f} | "
            f"{np.median(width):.1e} | {np.max(width):.1e} |"
        )
    print(f"| exact scalar path | {1 / exact:,.1f} | - | - | 0 | 0 |")


if __name__ == "__main__":
    main()
