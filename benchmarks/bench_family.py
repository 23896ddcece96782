"""Parametric families: building the exact quantities, and evaluating them on a grid.

Two measurements.

1. **Building** the family's exact quantities (the coefficients ``c0 .. c4`` of
   ``P(lambda)`` and ``Delta_2, Delta_3, Delta_4``) over Q(parameters): the package
   (python-flint ``fmpq_mpoly`` running the generated closed form, :mod:`quadric_contact.families.family`)
   against sympy (``det(lambda E + Q)`` by Berkowitz, expanded, and the Deltas of the
   expanded coefficients, expanded).  Both must give the same polynomials, or the run stops.

2. **Evaluating** one quantity on a ``N x N`` grid of binary64 parameter values (default
   1000 x 1000), in evaluations per second, for each backend of :meth:`Family.lambdify`
   (``numpy``, ``numba``, ``certified``; ``mpmath`` and ``exact`` on a random subsample of
   the grid) against ``sympy.lambdify`` of the expanded expression (numpy), with the
   largest error of each against the exact values on the subsample: the largest relative
   error (over points where the exact value is not zero) and, for the certified signs, the
   number of wrong signs (must be 0) and the fraction left uncertain.

Run: ``PYTHONPATH=src python benchmarks/bench_family.py [--grid N] [--sample K] [--repeat R]``.
The figures are wall-clock on the machine that ran them: re-measure rather than quote them.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
import sympy as sp

from quadric_contact import family
from quadric_contact.exact.discriminants import paper_deltas

TRUNK = "x^2 + y^2 - 0.25*(z - 3)^2 - 1"

CASES = {
    # name: (E, Q, parameters, grid ranges, quantity)
    "bee centre (u, w) / trunk": (
        "(x - u)^2 + y^2 + 3*(z - w)^2 - 0.1",
        TRUNK,
        "u w",
        ((-4.0, 4.0), (-2.0, 12.0)),
        "Delta4",
    ),
    "bee centre (u, v, w) / trunk": (
        "(x - u)^2 + (y - v)^2 + 3*(z - w)^2 - 0.1",
        TRUNK,
        "u v w",
        None,
        "Delta4",
    ),
    "semi-axis s, position v / throat": (
        "x^2/s^2 + 4*(y - v)^2 + 9*(z - 1/3)^2 - 1",
        "x^2 + y^2 - z^2/4 - 1",
        "s v",
        ((0.05, 2.0), (-3.0, 3.0)),
        "Delta4",
    ),
}


def best(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """The smallest wall-clock time of ``repeat`` runs, and the last result."""
    times = []
    out = None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def build_sympy(fam: Any) -> tuple[list[sp.Expr], list[sp.Expr]]:
    """The peer: sympy's determinant of ``lambda E + Q`` (Berkowitz), expanded, and the Deltas."""
    lam = sp.Symbol("lambda")
    num, den = sp.fraction(sp.cancel(sp.together((lam * fam.E + fam.Q).det(method="berkowitz"))))
    P = sp.Poly(sp.expand(num), lam)
    cs = [sp.cancel(P.coeff_monomial(lam**k) / den) for k in range(5)]
    ds = [sp.cancel(sp.together(d)) for d in paper_deltas(cs)]
    return cs, ds


NAMES = ("c0", "c1", "c2", "c3", "c4", "Delta2", "Delta3", "Delta4")


def building(repeat: int) -> None:
    print("Building the exact quantities (c0..c4, Delta2..Delta4) over Q(parameters)")
    head = f"{'family':<34} {'package (flint)':>16} {'+ sympy display':>16} {'sympy':>10} {'sympy/flint':>12}"
    print(head + "  equal")
    for name, (E, Q, params, _, _) in CASES.items():

        def flint_build(E: str = E, Q: str = Q, params: str = params) -> Any:
            f = family(E, Q, params)
            for n in NAMES:  # the exact rational functions (fmpq_mpoly)
                f.quantity(n)
            return f

        def display(f: Any) -> None:
            f.coefficients  # noqa: B018 - sympy expressions of the same quantities
            f.deltas  # noqa: B018

        t_flint, fam = best(flint_build, repeat)
        t_display, _ = best(lambda fam=fam: display(fam), 1)
        t_sympy, (cs, ds) = best(lambda fam=fam: build_sympy(fam), 1)
        ours = [*fam.coefficients, *fam.deltas]
        equal = all(sp.cancel(a - b) == 0 for a, b in zip([*cs, *ds], ours, strict=True))
        if not equal:
            raise SystemExit(f"{name}: sympy and the package disagree")
        print(
            f"{name:<34} {t_flint * 1e3:>13.2f} ms {t_display * 1e3:>13.1f} ms {t_sympy * 1e3:>7.0f} ms "
            f"{t_sympy / t_flint:>11.0f}x  {equal}"
        )
    print("  (package: family() from the equations, reference point and exact quantities; the sympy")
    print("   expressions are made only when asked for, once; sympy: det(lambda E + Q) by Berkowitz,")
    print("   expanded, and the Deltas of its coefficients, from the same sympy matrices)")
    print()


def evaluating(grid: int, sample: int, repeat: int, seed: int) -> None:
    rng = np.random.default_rng(seed)
    for name, (E, Q, params, ranges, quantity) in CASES.items():
        if ranges is not None:
            evaluate_case(name, family(E, Q, params), quantity, ranges, grid, sample, repeat, rng)


def evaluate_case(
    name: str,
    fam: Any,
    quantity: str,
    ranges: tuple[tuple[float, float], tuple[float, float]],
    grid: int,
    sample: int,
    repeat: int,
    rng: np.random.Generator,
) -> None:
    from mpmath.libmp import to_rational

    q = fam.quantity(quantity)
    (a, b), (c, d) = ranges
    U, W = np.meshgrid(np.linspace(a, b, grid), np.linspace(c, d, grid), indexing="ij")
    n = U.size
    pick = rng.choice(n, size=min(sample, n), replace=False)
    us, ws = U.reshape(-1)[pick], W.reshape(-1)[pick]
    exact_fn = fam.lambdify(quantity, "exact")
    t_exact, exact_vals = best(lambda: exact_fn(us, ws), 1)
    exact = [Fraction(v) for v in exact_vals]
    kind = "polynomial" if q.is_polynomial else "rational function"
    prog = fam.lambdify(quantity).compiled.program
    print(
        f"{quantity} of '{name}': {kind} of degree {q.value.degree}, {len(q.numerator)} terms; "
        f"generated program: {prog.operations} operations (Horner form, shared subexpressions)"
    )
    print(f"  grid {grid} x {grid} = {n} points; errors against exact values on {len(pick)} of them")
    print(f"  {'backend':<34} {'evaluations/s':>14} {'vs sympy':>9}  largest error")

    def errors(values: Any) -> str:
        worst = 0.0
        for v, e in zip(values, exact, strict=True):
            if e != 0:
                worst = max(worst, float(abs(Fraction(v) - e) / abs(e)))
        return f"relative {worst:.2e}"

    expr = sp.expand(q.expr) if q.is_polynomial else sp.cancel(q.expr)
    t_lam, peer = best(lambda: sp.lambdify(fam.symbols, expr, "numpy"), 1)
    t_peer, _ = best(lambda: peer(U, W), repeat)
    rows = [("sympy.lambdify (expanded)", n / t_peer, errors(np.asarray(peer(us, ws), dtype=float)))]
    for backend in ("numpy", "numba", "certified"):
        f = fam.lambdify(quantity, backend)
        f(U[:2, :2], W[:2, :2])  # compile (numba) outside the timing
        t, full = best(lambda f=f: f(U, W), repeat)
        sub = f(us, ws)
        if backend == "certified":
            wrong = sum(1 for s, e in zip(sub, exact, strict=True) if s not in (2, (e > 0) - (e < 0)))
            err = f"signs: {wrong} wrong, {float(np.mean(full == 2)):.2%} uncertain"
        else:
            err = errors(sub)
        rows.append((f"package {backend}", n / t, err))
    mp = fam.lambdify(quantity, "mpmath", dps=30)
    t_mp, mp_vals = best(lambda: mp(us, ws), 1)
    mp_err = errors([Fraction(*to_rational(v._mpf_)) for v in mp_vals])
    rows.append(("package mpmath (30 digits)", len(pick) / t_mp, mp_err))
    rows.append(("package exact (flint, per point)", len(pick) / t_exact, "reference"))
    peer_rate = rows[0][1]
    for label, rate, err in rows:
        print(f"  {label:<34} {rate:>14,.0f} {rate / peer_rate:>8.2f}x  {err}")
    print(f"  (sympy.lambdify built its function in {t_lam * 1e3:.0f} ms)")
    print()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--grid", type=int, default=1000, help="grid points per axis (default 1000)")
    parser.add_argument("--sample", type=int, default=2000, help="points checked exactly (default 2000)")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs, best kept (default 3)")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    building(args.repeat)
    evaluating(args.grid, args.sample, args.repeat, args.seed)


if __name__ == "__main__":
    main()
