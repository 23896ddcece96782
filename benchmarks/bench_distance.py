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

The reference is :func:`quadric_contact.modes.distance_certified.distance_certified` asked
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
4. *half-spaces*: random ellipsoids against random half-spaces, both sides of touching.

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
from quadric_contact.modes.distance_certified import distance_certified
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
        if kind != "sphere":
            return None  # FCL has no distance between an ellipsoid and a half-space ("not supported")
        e = fcl.CollisionObject(fcl.Ellipsoid(*axes), fcl.Transform())
        rho, centre = other
        o = fcl.CollisionObject(fcl.Sphere(rho), fcl.Transform(np.asarray(centre, dtype=float)))
        return float(fcl.distance(o, e, req, fcl.DistanceResult()))

    return run


def _ours(kind: str, axes: Any, other: Any, digits: int = 16) -> Any:
    e = _ellipsoid(axes)
    if kind == "sphere":
        rho, centre = other
        return distance_certified(_sphere(rho, centre), e, digits=digits)
    n, d = other
    return distance_certified(e, _halfspace(n, d), digits=digits)


def _reference(kind: str, axes: Any, other: Any) -> Fraction:
    lo, hi = _ours(kind, axes, other, digits=30).bounds
    return (lo + hi) / 2


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
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)

    def ours(kind: str, axes: Any, other: Any) -> float:
        return float(_ours(kind, axes, other))

    methods: dict[str, Callable[..., Any]] = {"quadric-contact certified (16 digits)": ours}
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


if __name__ == "__main__":
    main()
