"""Cost of the exact smallness decision and of the exact geometric decision,
and how often Corollary 10 alone is wrong on pairs that are not small.

Run from the repository root::

    PYTHONPATH=src python benchmarks/bench_smallness.py [--pairs N] [--seed S]

Prints three tables:

1. Exact smallness (Tables 1/2, corrected) per pair, for pairs in standard
   position moved by rational rigid motions (rational eigenvalues) and for
   random integer matrices (irrational eigenvalues), with the share of
   comparisons that needed exact algebraic numbers (certified balls did not
   separate the sides); compared, as ratios in the same run, with a float
   peer (numpy eigenvalues, the same formulas, no certification) and with
   the characteristic polynomial alone (the cost of Corollary 10 itself).
   The float peer's disagreements with the exact verdict are counted.
2. The exact geometric decision per pair, compared with Corollary 10.
3. Corollary 10 on pairs that are not small, by type of Q: E is drawn at
   ``u`` times the largest scale allowed by Table 1 (``u`` in 1.5, 3, 10),
   placed at random near a vertex of Q or adversarially (touching a vertex
   along the principal directions, pushed across or set back); the rate at
   which Corollary 10's answer (Delta_4 < 0 or Delta_4 = 0 and Delta_3 < 0)
   differs from the exact geometric answer, over all placements and over
   the placements in transversal contact.

Timings are wall-clock on a shared machine: treat them as indicative and
re-measure on a quiet one.
"""

from __future__ import annotations

import argparse
import importlib
import random
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(ROOT))

from tests.table_search import adversarial_placements, corollary_10_says_transversal, vertices  # noqa: E402
from tests.test_table_verification import ORDERED, max_scale  # noqa: E402

from quadric_contact import Quadric, QuadricKind, characteristic_polynomial  # noqa: E402
from quadric_contact.model.classification import TABLE_1_KINDS  # noqa: E402
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion  # noqa: E402
from quadric_contact.theory.geometric import decide_geometrically  # noqa: E402
from quadric_contact.theory.smallness import smallness  # noqa: E402

# the module itself (the package re-exports the function under the same name)
smallness_module = importlib.import_module("quadric_contact.theory.smallness")

F = Fraction
K = QuadricKind


def rand_frac(rng: random.Random, lo: float, hi: float, den: int = 8) -> Fraction:
    return Fraction(rng.randint(int(lo * den), int(hi * den)), den)


def rand_motion(rng: random.Random, bound: int = 5) -> RigidMotion:
    q = [rng.randint(-4, 4) for _ in range(4)]
    if not any(q):
        q[0] = 1
    R = rotation_from_quaternion(*q)
    t = tuple(rand_frac(rng, -bound, bound) for _ in range(3))
    return RigidMotion(R, t)


def standard_pair(rng: random.Random, kind: QuadricKind, u: Fraction) -> tuple[Quadric, Quadric, dict, tuple]:
    ps = [rand_frac(rng, 0.5, 5) or F(1, 2) for _ in Quadric.standard_parameters(kind)]
    n = ORDERED.get(kind, 0)
    ps = sorted(ps[:n], reverse=True) + ps[n:]
    p = dict(zip("abc", ps, strict=False))
    shape = tuple(sorted((rand_frac(rng, 0.25, 3) or F(1, 4) for _ in range(3)), reverse=True))
    s = max_scale(kind, p, shape) * u
    axes = tuple(s * v for v in shape)
    return Quadric.ellipsoid(*axes), Quadric.standard(kind, **p), p, axes


def random_integer_pair(rng: random.Random) -> tuple[Quadric, Quadric]:
    """E with a random integer positive definite quadratic part, Q a random
    integer symmetric matrix of a Table 1 type: irrational eigenvalues in general."""
    while True:
        M = [[rng.randint(-3, 3) for _ in range(3)] for _ in range(3)]
        A = [
            [sum(M[k][i] * M[k][j] for k in range(3)) + (3 if i == j else 0) for j in range(3)]
            for i in range(3)
        ]
        c = [rng.randint(-5, 5) for _ in range(3)]
        b = [-sum(A[i][j] * c[j] for j in range(3)) for i in range(3)]
        cc = sum(c[i] * A[i][j] * c[j] for i in range(3) for j in range(3)) - rng.randint(1, 30)
        e = Quadric.from_coefficients(A, b, cc)
        S = [[rng.randint(-4, 4) for _ in range(4)] for _ in range(4)]
        S = [[S[i][j] + S[j][i] for j in range(4)] for i in range(4)]
        q = Quadric(S)
        if e.kind is K.ELLIPSOID and q.kind in TABLE_1_KINDS:
            return e, q


class Counter:
    """Counts how often the smallness comparisons needed exact algebraic numbers."""

    def __init__(self) -> None:
        self.calls = 0
        self.exact = 0
        self._orig = smallness_module.compare_quantities

    def __enter__(self) -> Counter:
        def wrapped(x, y):  # type: ignore[no-untyped-def]
            self.calls += 1
            if not (x.is_rational() and y.is_rational()):
                for bits in (64, 160):
                    d = x.ball(bits) - y.ball(bits)
                    if d > 0 or d < 0:
                        break
                else:
                    self.exact += 1
            return self._orig(x, y)

        smallness_module.compare_quantities = wrapped
        return self

    def __exit__(self, *exc: object) -> None:
        smallness_module.compare_quantities = self._orig


def float_smallness(e: Quadric, q: Quadric) -> bool:
    """A float peer: numpy eigenvalues and the corrected formulas, uncertified."""
    qs = q if q.canonical_sign > 0 else -q
    E = e.as_ellipsoid().to_numpy(float)
    Q = qs.to_numpy(float)
    ne = np.linalg.eigvalsh(E[:3, :3])
    d2 = -np.linalg.det(E) / np.prod(ne)
    al2, ga2 = d2 / ne[0], d2 / ne[2]
    kE = np.sqrt(ga2) / al2
    mu = np.linalg.eigvalsh(Q[:3, :3])
    kind = q.kind
    A00 = Q[:3, :3]
    J = (
        (A00[0, 0] * A00[1, 1] - A00[0, 1] ** 2)
        + (A00[0, 0] * A00[2, 2] - A00[0, 2] ** 2)
        + (A00[1, 1] * A00[2, 2] - A00[1, 2] ** 2)
    )
    detQ = np.linalg.det(Q)
    nz = sorted((m for m in mu if abs(m) > 1e-12 * max(1.0, abs(mu).max())), key=abs)
    if kind is K.ELLIPSOID:
        d = -detQ / np.prod(mu)
        a2, c2 = d / mu[0], d / mu[2]
        inner = c2 >= al2 and np.sqrt(a2) / c2 <= kE
        outer = ga2 >= a2 and np.sqrt(al2) / ga2 <= np.sqrt(c2) / a2
        return bool(inner or outer)
    if kind in (K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS):
        pos = sorted(m for m in mu if m > 0)
        neg = next(m for m in mu if m < 0)
        d = (-detQ if kind is K.HYPERBOLOID_ONE_SHEET else detQ) / np.prod(mu)
        a2, b2, c2 = d / pos[0], d / pos[1], -d / neg
        if kind is K.HYPERBOLOID_ONE_SHEET:
            return bool(b2 >= al2 and max(np.sqrt(a2) / b2, np.sqrt(a2) / c2) <= kE)
        return bool(c2 >= al2 and np.sqrt(c2) / b2 <= kE)
    if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        L = np.sqrt(-4 * detQ / J)
        return bool(2 * abs(nz[-1]) / L <= kE)
    # cylinders and planes: K and J'
    Kv = sum(np.linalg.det(np.delete(np.delete(Q, i, 0), i, 1)) for i in range(3))
    if kind in (K.ELLIPTIC_CYLINDER, K.HYPERBOLIC_CYLINDER):
        M2 = -Kv / J
        if kind is K.ELLIPTIC_CYLINDER:
            a2, b2 = M2 / nz[0], M2 / nz[1]
            return bool(b2 >= al2 and np.sqrt(a2) / b2 <= kE)
        p = max(mu)
        n = min(mu)
        a2, b2 = M2 / p, -M2 / n
        return bool(a2 >= al2 and np.sqrt(a2) / b2 <= kE)
    if kind is K.PARABOLIC_CYLINDER:
        m = nz[-1]
        d = np.sqrt(-4 * Kv / m)
        return bool(2 * m / d <= kE)
    m = nz[-1]
    Jp = sum(Q[i, i] * Q[3, 3] - Q[i, 3] ** 2 for i in range(3))
    return bool(-Jp / m**2 >= al2)


def timed(fn, *args):  # type: ignore[no-untyped-def]
    t = time.perf_counter()
    out = fn(*args)
    return out, time.perf_counter() - t


def table_1_costs(rng: random.Random, n: int) -> None:
    print("\n1. Exact smallness per pair (median, mean in ms; ratios to peers measured in the same run)")
    header = (
        f"{'pairs':<34} {'n':>4} {'exact ms':>9} {'mean':>7} {'algebraic':>9} "
        f"{'float ms':>8} {'exact/float':>11} {'P ms':>6} {'exact/P':>8} {'float wrong':>11}"
    )
    print(header)
    print("-" * len(header))
    groups: dict[str, list[tuple[Quadric, Quadric]]] = {
        "standard forms, moved": [],
        "near the boundary (u = 1), moved": [],
        "random integer matrices": [],
    }
    for _ in range(n):
        kind = rng.choice(TABLE_1_KINDS)
        u = rng.choice([F(1, 2), F(2)])
        e, q, _, _ = standard_pair(rng, kind, u)
        m1, m2 = rand_motion(rng), rand_motion(rng)
        groups["standard forms, moved"].append((e.moved(m1), q.moved(m2)))
        e, q, _, _ = standard_pair(rng, kind, F(1))
        groups["near the boundary (u = 1), moved"].append((e.moved(m1), q.moved(m2)))
        groups["random integer matrices"].append(random_integer_pair(rng))
    for name, pairs in groups.items():
        t_exact, t_float, t_poly, wrong = [], [], [], 0
        with Counter() as counter:
            for e, q in pairs:
                r, dt = timed(smallness, e, q)
                t_exact.append(dt)
                fv, dt = timed(float_smallness, e, q)
                t_float.append(dt)
                wrong += fv != r.small
                _, dt = timed(characteristic_polynomial, e, q)
                t_poly.append(dt)
        me, mf, mp = (statistics.median(t) * 1e3 for t in (t_exact, t_float, t_poly))
        share = f"{counter.exact}/{counter.calls}"
        print(
            f"{name:<34} {len(pairs):>4} {me:>9.2f} {statistics.mean(t_exact) * 1e3:>7.2f} {share:>9} "
            f"{mf:>8.3f} {me / mf:>11.0f} {mp:>6.2f} {me / mp:>8.1f} {wrong:>11}"
        )


def geometric_costs(rng: random.Random, n: int) -> None:
    print("\n2. Exact geometric decision per pair (E placed at random near Q)")
    header = f"{'type of Q':<26} {'n':>4} {'geom ms':>8} {'mean':>7} {'P+Cor10 ms':>10} {'ratio':>6}"
    print(header)
    print("-" * len(header))
    for kind in TABLE_1_KINDS:
        tg, tc = [], []
        for _ in range(max(1, n // len(TABLE_1_KINDS))):
            e, q, p, axes = standard_pair(rng, kind, rng.choice([F(1, 2), F(3)]))
            point, _, _ = rng.choice(vertices(kind, p))
            center = tuple(point[i] + rand_frac(rng, -2, 2) * axes[0] for i in range(3))
            e = Quadric.ellipsoid(*axes).moved(RigidMotion(rand_motion(rng).rotation, center))
            m = rand_motion(rng)
            e, q = e.moved(m), q.moved(m)
            _, dt = timed(decide_geometrically, e, q)
            tg.append(dt)
            _, dt = timed(corollary_10_says_transversal, e, q)
            tc.append(dt)
        mg, mc = statistics.median(tg) * 1e3, statistics.median(tc) * 1e3
        print(
            f"{kind.value:<26} {len(tg):>4} {mg:>8.2f} {statistics.mean(tg) * 1e3:>7.2f}"
            f" {mc:>10.2f} {mg / mc:>6.1f}"
        )


def corollary_10_rates(rng: random.Random, n: int) -> None:
    print("\n3. Corollary 10 alone on pairs that are NOT small (exact geometric decision as reference)")
    header = (
        f"{'type of Q':<26} {'placements':<12} {'n':>5} {'contact':>8} {'Cor10 wrong':>11} "
        f"{'rate':>7} {'rate | contact':>14}"
    )
    print(header)
    print("-" * len(header))
    totals = {"random": [0, 0, 0], "adversarial": [0, 0, 0]}
    for kind in TABLE_1_KINDS:
        rows = {"random": [0, 0, 0], "adversarial": [0, 0, 0]}
        for _ in range(max(1, n // len(TABLE_1_KINDS))):
            u = rng.choice([F(3, 2), F(3), F(10)])
            e0, q, p, axes = standard_pair(rng, kind, u)
            if smallness(e0, q).small:  # an ellipsoid scaled up may enclose Q: small again
                continue
            point, _, _ = rng.choice(vertices(kind, p))
            placements = []
            for _ in range(4):
                center = tuple(point[i] + rand_frac(rng, -1, 1) * axes[0] for i in range(3))
                placements.append(
                    ("random", Quadric.ellipsoid(*axes).moved(RigidMotion(rand_motion(rng).rotation, center)))
                )
            adv = list(adversarial_placements(kind, p, axes))
            placements += [("adversarial", pl.E) for pl in rng.sample(adv, min(4, len(adv)))]
            for how, e in placements:
                g = decide_geometrically(e, q)
                c10 = corollary_10_says_transversal(e, q)
                r = rows[how]
                r[0] += 1
                r[1] += g.transversal
                r[2] += c10 != g.transversal
        for how, (cnt, contact, wrong) in rows.items():
            totals[how] = [a + b for a, b in zip(totals[how], (cnt, contact, wrong), strict=True)]
            # a rate over no pair is not a number: "n/a" (no pairs, or none in contact)
            rate = f"{wrong / cnt:.1%}" if cnt else "n/a"
            rate_c = f"{wrong / contact:.1%}" if contact else "n/a"
            print(f"{kind.value:<26} {how:<12} {cnt:>5} {contact:>8} {wrong:>11} {rate:>7} {rate_c:>14}")
    for how, (cnt, contact, wrong) in totals.items():
        print(
            f"{'all types':<26} {how:<12} {cnt:>5} {contact:>8} {wrong:>11}"
            f" {wrong / cnt:>7.1%} {wrong / max(contact, 1):>14.1%}"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pairs", type=int, default=90, help="pairs per table (default 90)")
    ap.add_argument("--seed", type=int, default=2022)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    print(f"bench_smallness: {args.pairs} pairs per table, seed {args.seed}")
    table_1_costs(rng, args.pairs)
    geometric_costs(rng, args.pairs)
    corollary_10_rates(rng, args.pairs)


if __name__ == "__main__":
    main()
