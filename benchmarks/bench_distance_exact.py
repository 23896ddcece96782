"""The exact signed distance of a sphere from a quadric, per type of the quadric: the time of the
public call ``qc.distance(E, Q, mode="exact")``, against the previous route.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_distance_exact.py [--pairs N] [--seed S] [--before K] [--profile]

The pairs, for every type with a solid (the nine of Table 1 and the plane; a cone has no solid
and is refused):

* ``E``: a sphere given by its binary64 matrix, centre uniform in ``[-3, 3]^3`` and radius in
  ``[0.1, 1]`` (the corner entry ``|c|^2 - rho^2`` rounded to binary64: ``rho^2`` is then a
  dyadic rational, ``rho`` irrational); for a solid that is not convex the centre is drawn
  outside it (a centre inside is refused at once: the depth into such a solid is not defined
  by one critical point);
* ``Q``: the standard form of its type with binary64 entries (parameters uniform in
  ``[1, 4]``), placed at random and negated with probability 1/2.  First table, binary64
  entries: the ellipsoid and the hyperboloids rotated in binary64
  (:func:`quadric_contact.testing.samples.random_pairs`), the plane with a random binary64
  normal and offset, and the six types with ``det Q00 = 0`` (which a rotation rounded to
  binary64 destroys: the rounded matrix is a thin hyperboloid) with their axes permuted at
  random and a binary64 translation (the zeros of ``Q00`` stay exact).  Second table, the six
  degenerate types rotated exactly by a random integer quaternion (components in ``[-4, 4]``)
  and translated by a binary64 vector: rational entries, longer numbers.

Columns: the pairs answered; the pairs refused with the reason (the sphere crosses a
non-convex solid; decided exactly, in about 0.1 ms); how many answered pairs the certified
secular root settled (the rest take the general route: a circle of nearest points, or the
hard case of the secular equation); the median, 90th percentile and maximum time of the
public call over the answered pairs (parsing included; the result holds the exact distance);
the median times of then reading the witness ``point_Q`` and then the normal and ``point_E``
(the witnesses are computed when first read); and the median time of the previous route (the
first-contact scale from the pencil's discriminant, then the root of the secular equation at
that distance, ``point_Q`` with the result; the plane by real algebraic arithmetic) on the
first ``--before`` answered pairs, whose distance and ``point_Q`` are checked equal to the new
ones.  ``--profile`` prints where the time of the first table goes (cProfile).

Times are wall-clock on a shared machine: indicative only.
"""

from __future__ import annotations

import argparse
import contextlib
import cProfile
import math
import pstats
import statistics
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np

import quadric_contact as qc
from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.model.motions import RigidMotion
from quadric_contact.model.quadric import as_quadric
from quadric_contact.testing.references import plane_distance_reference
from quadric_contact.testing.samples import SAMPLE_KINDS, _moved, _standard_forms, random_pairs
from quadric_contact.theory.distance import CONVEX_SOLIDS, DistanceResult, _sphere_quadric_general
from quadric_contact.theory.distance_sphere import sphere_distance, sphere_pair
from quadric_contact.theory.overlap import solid_of

ROTATED_KINDS = (QuadricKind.ELLIPSOID, QuadricKind.HYPERBOLOID_ONE_SHEET, QuadricKind.HYPERBOLOID_TWO_SHEETS)
"""The types that keep their type under a rotation rounded to binary64 (``det Q00 != 0``)."""

DEGENERATE_KINDS = tuple(k for k in SAMPLE_KINDS if k not in ROTATED_KINDS and k is not QuadricKind.PLANE)


def _sphere(rng: np.random.Generator) -> np.ndarray:
    c = rng.uniform(-3, 3, 3)
    rho = rng.uniform(0.1, 1.0)
    E = np.eye(4)
    E[:3, 3] = E[3, :3] = -c
    E[3, 3] = c @ c - rho * rho
    return E


def _standard(kind: QuadricKind, rng: np.random.Generator) -> np.ndarray:
    """The standard form with parameters in ``[1, 4]``, its entries in binary64."""
    p = np.sort(rng.uniform(1.0, 4.0, size=(1, 3)), axis=1)[:, ::-1]
    return _standard_forms(np.array([SAMPLE_KINDS.index(kind)]), p)


def _axis_aligned(kind: QuadricKind, rng: np.random.Generator) -> np.ndarray:
    """Axes permuted at random, a binary64 translation: ``Q00`` keeps its exact zeros, the
    rounded linear and constant entries keep the type (checked)."""
    while True:
        P = np.eye(3)[rng.permutation(3)] * rng.choice([-1.0, 1.0], 3)[:, None]
        if np.linalg.det(P) < 0:
            P[0] = -P[0]
        Q = _moved(_standard(kind, rng), P[None], rng.uniform(-3, 3, size=(1, 3)))[0]
        Q *= -1.0 if rng.random() < 0.5 else 1.0
        if as_quadric(Q).kind is kind:
            return Q


def _rationally_placed(kind: QuadricKind, rng: np.random.Generator) -> Quadric:
    """A rotation from a random integer quaternion (components in ``[-4, 4]``) and a binary64
    translation, exactly: rational entries."""
    q = Quadric.from_matrix(_standard(kind, rng)[0])
    w = (0, 0, 0, 0)
    while not any(w):
        w = tuple(int(x) for x in rng.integers(-4, 5, 4))
    t = [Fraction(float(x)) for x in rng.uniform(-3, 3, 3)]
    q = q.moved(RigidMotion.from_quaternion(*w, translation=t))
    return -q if rng.random() < 0.5 else q


def _quadric(kind: QuadricKind, rng: np.random.Generator, placement: str) -> Any:
    if kind is QuadricKind.PLANE:
        n = rng.normal(size=3)
        return Quadric.plane([Fraction(float(x)) for x in n], Fraction(float(rng.uniform(-3, 3))))
    if placement == "rational":
        return _rationally_placed(kind, rng)
    if kind in ROTATED_KINDS:
        while True:  # a binary64 rotation keeps these types (checked)
            _, Q, _ = random_pairs(1, rng, kinds=(kind,))
            if as_quadric(Q[0]).kind is kind:
                return Q[0]
    return _axis_aligned(kind, rng)


def pairs_of(kind: QuadricKind, n: int, rng: np.random.Generator, placement: str = "binary64") -> list[Any]:
    """``n`` pairs (a sphere as a binary64 matrix, ``Q`` of type ``kind``); for a solid that is
    not convex, the sphere's centre is drawn outside it (a centre inside is refused at once)."""
    out = []
    for _ in range(n):
        Q = _quadric(kind, rng, placement)
        K = solid_of(Q)
        E = _sphere(rng)
        for _ in range(100):
            if kind in CONVEX_SOLIDS or K.value_at([Fraction(-float(x)) for x in E[3, :3]]) >= 0:
                break
            E = _sphere(rng)
        out.append((E, Q))
    return out


def _previous_plane(E: Any, Q: Any) -> tuple[RealAlgebraic, tuple[RealAlgebraic, ...]]:
    """The previous closed form of a sphere against a plane, in real algebraic arithmetic
    (:func:`~quadric_contact.testing.references.plane_distance_reference`): the distance and
    ``point_Q``."""
    dist, point_Q, _, _ = plane_distance_reference(as_quadric(E).as_ellipsoid(), solid_of(Q))
    return dist, point_Q


def _previous(E: Any, Q: Any) -> Any:
    K = solid_of(Q)
    if K.kind is QuadricKind.PLANE:
        return _previous_plane(E, Q)
    return _sphere_quadric_general(as_quadric(E).as_ellipsoid(), K)


def _timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def _ms(t: float) -> str:
    if not math.isfinite(t):
        return "-"
    return f"{t * 1e3:.2f} ms" if t < 1 else f"{t:.2f} s"


def run_kind(draw: Callable[[], tuple[np.ndarray, Any]], n: int, before: int) -> dict[str, Any]:
    """Time the public call on pairs from ``draw()`` until ``n`` are answered (at most ``20 n``
    drawn), then the first read of ``point_Q``; then the previous route on the first
    ``before`` answered pairs."""
    times, reads, normals, refused, certified = [], [], [], 0, 0
    answered: list[tuple[np.ndarray, Any, DistanceResult]] = []
    warm = 3  # the first calls load modules and fill caches: not timed
    for _ in range(20 * n):
        if len(answered) >= n:
            break
        E, Q = draw()
        try:
            r, dt = _timed(lambda E=E, Q=Q: qc.distance(E, Q, mode="exact"))
        except UndecidedError:
            refused += 1
            continue
        if warm:
            warm -= 1
            continue
        times.append(dt)
        reads.append(_timed(lambda r=r: r.point_Q)[1])
        normals.append(_timed(lambda r=r: r.normal)[1])
        answered.append((E, Q, r))
        K = solid_of(Q)
        if K.kind is QuadricKind.PLANE or sphere_distance(sphere_pair(as_quadric(E).as_ellipsoid(), K)):
            certified += 1
    old = []
    for E, Q, r in answered[:before]:
        prev, dt = _timed(lambda E=E, Q=Q: _previous(E, Q))
        old.append(dt)
        if isinstance(prev, DistanceResult):
            prev = (prev.distance, prev.point_Q)
        assert prev == (r.distance, r.point_Q), (E, Q)
    return {
        "answered": len(times),
        "refused": refused,
        "certified": certified,
        "median": statistics.median(times) if times else math.nan,
        "p90": float(np.percentile(times, 90)) if times else math.nan,
        "max": max(times, default=math.nan),
        "point_Q": statistics.median(reads) if reads else math.nan,
        "normal": statistics.median(normals) if normals else math.nan,
        "before": statistics.median(old) if old else math.nan,
        "before_n": len(old),
    }


HEADER = (
    "| Q | entries | answered | refused (non-convex) | certified root | median | p90 | max "
    "| then point_Q | then normal, point_E | previous route (median) |\n"
    "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
)


def _row(kind: QuadricKind, entries: str, row: dict[str, Any]) -> str:
    before = f"{_ms(row['before'])} ({row['before_n']})" if row["before_n"] else "-"
    return (
        f"| {kind.value} | {entries} | {row['answered']} | {row['refused']} | {row['certified']} "
        f"| {_ms(row['median'])} | {_ms(row['p90'])} | {_ms(row['max'])} | {_ms(row['point_Q'])} "
        f"| {_ms(row['normal'])} | {before} |"
    )


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=50, help="answered pairs per type")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--before", type=int, default=3, help="pairs per type timed on the previous route")
    ap.add_argument("--profile", action="store_true", help="cProfile the public call on the first table")
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    seen: list[tuple[np.ndarray, Any]] = []

    def drawer(kind: QuadricKind, placement: str) -> Callable[[], tuple[np.ndarray, Any]]:
        def draw() -> tuple[np.ndarray, Any]:
            pair = pairs_of(kind, 1, rng, placement)[0]
            seen.append(pair)
            return pair

        return draw

    print(f"### exact distance of a sphere from a quadric, binary64 entries ({args.pairs} pairs a type)\n")
    print(HEADER)
    for kind in SAMPLE_KINDS:
        entries = "binary64" + (
            "" if kind in ROTATED_KINDS or kind is QuadricKind.PLANE else ", axis-aligned"
        )
        print(_row(kind, entries, run_kind(drawer(kind, "binary64"), args.pairs, args.before)), flush=True)
    first = list(seen)
    print(f"\n### the degenerate types placed by rational rotations ({args.pairs} pairs a type)\n")
    print(HEADER)
    for kind in DEGENERATE_KINDS:
        print(_row(kind, "rational", run_kind(drawer(kind, "rational"), args.pairs, args.before)), flush=True)
    if args.profile:
        profile = cProfile.Profile()
        profile.enable()
        for E, Q in first:
            with contextlib.suppress(UndecidedError):
                qc.distance(E, Q, mode="exact")
        profile.disable()
        print("\n### where the time goes (cProfile over the pairs of the first table)\n")
        pstats.Stats(profile).sort_stats("tottime").print_stats(20)


if __name__ == "__main__":
    main()
