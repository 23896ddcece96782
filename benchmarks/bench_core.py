"""Cost per pair of the exact core: characteristic polynomial + transversal contact.

Measures, for float input (numpy float64 matrices, taken as exact dyadic
rationals) and for rational input (Fractions), the time per pair of

* building the two :class:`Quadric` objects from matrices,
* ``characteristic_polynomial`` (exact coefficients, integer fast path),
* ``transversal_contact`` with the discriminant decision (smallness asserted,
  so that the cost of the smallness test, measured elsewhere, is excluded),

and compares them in the same run with two peers: a sympy determinant with
sympy's discriminant (the textbook exact route), and numpy's eigenvalues of
``-Q E^-1`` per pair (fast, not exact).

Run: ``python benchmarks/bench_core.py [--pairs N]``.
"""

from __future__ import annotations

import argparse
import random
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from quadric_contact import Quadric, characteristic_polynomial, transversal_contact
from quadric_contact.model.motions import rotation_from_quaternion


def random_pairs(n: int, seed: int, rational: bool) -> list[tuple[Any, Any]]:
    """Random ellipsoid / quadric pairs as 4x4 matrices (floats or Fractions)."""
    rng = random.Random(seed)
    pairs = []
    for _ in range(n):
        q = tuple(rng.randint(-5, 5) for _ in range(4))
        R = rotation_from_quaternion(*q) if any(q) else None
        axes = [Fraction(rng.randint(1, 40), rng.randint(1, 12)) for _ in range(3)]
        center = [Fraction(rng.randint(-60, 60), rng.randint(1, 7)) for _ in range(3)]
        e = Quadric.ellipsoid(*axes, center=center, rotation=R)
        kinds = [
            "x**2/{a} + y**2/{b} - z**2/{c} - 1",
            "x**2/{a} + y**2/{b} - z",
            "x**2/{a} + y**2/{b} + z**2/{c} - 1",
        ]
        eq = rng.choice(kinds).format(a=rng.randint(1, 30), b=rng.randint(1, 30), c=rng.randint(1, 30))
        qq = Quadric.from_equation(eq).rotated((1, rng.randint(-3, 3), rng.randint(-3, 3), 2))
        if rational:
            pairs.append((e.matrix, qq.matrix))
        else:
            pairs.append((e.to_numpy(float), qq.to_numpy(float)))
    return pairs


def timeit(fn: Callable[[Any, Any], Any], pairs: list[tuple[Any, Any]], repeat: int = 7) -> float:
    """Best-of-``repeat`` mean time per pair in microseconds."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for e, q in pairs:
            fn(e, q)
        best = min(best, (time.perf_counter() - t0) / len(pairs))
    return best * 1e6


def sympy_route(e: Any, q: Any) -> bool:
    lam = sp.Symbol("lambda")

    def exact(m: Any, i: int, j: int) -> Any:
        v = m[i][j]
        return sp.Rational(str(v)) if isinstance(v, Fraction) else sp.Rational(v)

    E = sp.Matrix(4, 4, lambda i, j: exact(e, i, j))
    Q = sp.Matrix(4, 4, lambda i, j: exact(q, i, j))
    P = sp.Poly((lam * E + Q).det(method="berkowitz"), lam)
    return bool(sp.discriminant(P) < 0)


def numpy_route(e: Any, q: Any) -> bool:
    E = np.asarray(e, dtype=float)
    Q = np.asarray(q, dtype=float)
    w = np.linalg.eigvals(-Q @ np.linalg.inv(E))
    return bool(np.any(np.abs(w.imag) > 1e-9 * np.max(np.abs(w))))


def build(e: Any, q: Any) -> Any:
    return Quadric.from_matrix(e), Quadric.from_matrix(q)


def build_and_pencil(e: Any, q: Any) -> Any:
    # Fresh Quadric objects each time, so that no cached work is reused.
    return characteristic_polynomial(Quadric.from_matrix(e), Quadric.from_matrix(q)).integer_coefficients


def end_to_end(e: Any, q: Any) -> Any:
    return transversal_contact(Quadric.from_matrix(e), Quadric.from_matrix(q), small=True).transversal


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--pairs", type=int, default=400)
    args = parser.parse_args()
    rows = []
    for label, rational in (("float", False), ("rational", True)):
        pairs = random_pairs(args.pairs, seed=7, rational=rational)
        t_build = timeit(build, pairs)
        t_pencil = timeit(build_and_pencil, pairs) - t_build
        t_total = timeit(end_to_end, pairs)
        t_decide = t_total - t_build
        few = pairs[: max(10, args.pairs // 40)]
        t_sympy = timeit(sympy_route, few, repeat=1)
        t_numpy = timeit(numpy_route, pairs)
        contact = sum(1 for e, q in pairs if end_to_end(e, q))
        rows.append((label, t_build, t_pencil, t_decide, t_total, t_sympy, t_numpy, contact, len(pairs)))
    print(
        f"{'input':9} {'build':>8} {'P(l)':>8} {'P+decide':>9} {'total':>8} {'sympy':>9} {'numpy':>8}"
        f" {'sympy/total':>12} {'total/numpy':>12}  contact"
    )
    for label, b, p, d, t, s, n, c, npairs in rows:
        print(
            f"{label:9} {b:8.1f} {p:8.1f} {d:9.1f} {t:8.1f} {s:9.0f} {n:8.1f} {s / t:12.0f} {t / n:12.1f}"
            f"  {c}/{npairs}"
        )
    print(
        "times in microseconds per pair (best of 7 runs); build = two Quadric.from_matrix;"
        " P(l) = characteristic_polynomial; P+decide = characteristic_polynomial +"
        " transversal_contact(small=True); total includes build; sympy = sympy det + discriminant;"
        " numpy = eigvals of -Q E^-1 with a tolerance (not exact)."
    )


if __name__ == "__main__":
    main()
