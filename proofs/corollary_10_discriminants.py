"""Corollary 10: transversal contact from the signs of Delta_4 and Delta_3 (Yang 1999).

Claim.  For ``E`` small with respect to ``Q``, transversal contact holds iff
``Delta_4 < 0``, or ``Delta_4 = 0`` and ``Delta_3 < 0``.  Proof: by Theorem 2 the
transversal contacts are the Segre types ``[1111]_2`` and ``[(11)11]_1``, which
by Yang's classification of the roots of a quartic are ``Delta_4 < 0`` and
``Delta_4 = 0, Delta_3 < 0``.

What is checked and how.  Yang's classification, by exhaustive case analysis:
the discrimination sequence ``D_1 .. D_4`` (``D_1 = 4 c4^2 > 0``) is computed here
from its definition; for each of the 27 sign patterns of ``(D_2, D_3, D_4)``
Yang's revised sign list predicts the numbers of distinct real roots and of
distinct non-real pairs; every root configuration of a real quartic (9 of
them, with their multiplicities) is realised by many exact quartics (products
of rational linear factors and irreducible rational quadratics), and for each
the predicted counts equal the constructed ones.  On the sign patterns that
occur, ``Delta_4 < 0 or (Delta_4 = 0 and Delta_3 < 0)`` holds exactly for the
configurations with one simple non-real pair.  Then, over all 27 patterns
with Yang's counts (his Theorem 1): the impossible ones are discarded, the
test equals "a non-real root" on every pattern with at most one simple
non-real pair, and it misses exactly the patterns of two non-real pairs
(``D_4 > 0`` with ``D_2 <= 0`` or ``D_3 <= 0``) and of a double one
(``D_4 = D_3 = 0 > D_2``).  The corollary is nonetheless right: the pencil of
an ellipsoid has at most one pair of non-real roots.  Argument: if
``(mu E + Q) v = 0`` and ``(nu E + Q) w = 0`` then ``(mu - conj nu) w^H E v = 0``,
so two eigenvectors for eigenvalues in the upper half-plane (or a Jordan
chain of one) span a 2-dimensional subspace on which the Hermitian form of
``E`` vanishes, impossible for a form of inertia (3, 1); the identity is
checked symbolically and the conclusion by evidence (300 hypothesis examples
of ellipsoids against arbitrary symmetric matrices, 5000 in the slow profile,
roots counted by FLINT).
Evidence: 300 hypothesis examples of ellipsoids and Table 1 quadrics where
Corollary 10's test equals "P has a non-real root".
"""

from __future__ import annotations

import itertools
from collections import defaultdict
from fractions import Fraction

import flint
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric, characteristic_polynomial
from quadric_contact.discriminants import revised_sign_list
from quadric_contact.proving import Finding, Method, Proof, agrees, ensure, search_settings
from quadric_contact.strategies import ellipsoids, quadrics

proof = Proof("Corollary 10", "Delta_4 < 0, or Delta_4 = 0 and Delta_3 < 0, is transversal contact")

C = sp.symbols("c0:5")
EXAMPLES = 300


def _minors() -> list[sp.Expr]:
    a = [C[4], C[3], C[2], C[1], C[0]]
    da = [4 * C[4], 3 * C[3], 2 * C[2], C[1]]
    M = sp.zeros(8, 8)
    for i in range(4):
        for j, coef in enumerate(a):
            M[2 * i, i + j] = coef
        for j, coef in enumerate(da):
            M[2 * i + 1, i + 1 + j] = coef
    return [sp.expand(M[: 2 * k, : 2 * k].det(method="berkowitz")) for k in range(1, 5)]


_D = None


def discrimination(coeffs: list[Fraction]) -> tuple[int, int, int, int]:
    """Signs of Yang's D_1 .. D_4 for exact coefficients c0..c4."""
    global _D
    if _D is None:
        _D = [sp.lambdify(C, d, "math") for d in _minors()]
    values = [d(*coeffs) for d in _D]
    return tuple((v > 0) - (v < 0) for v in values)  # type: ignore[return-value]


def yang_counts(signs: tuple[int, ...]) -> tuple[int, int]:
    """(distinct real roots, distinct non-real pairs) by Yang's Theorem 1."""
    rev = [v for v in revised_sign_list(signs) if v]
    changes = sum(1 for u, v in itertools.pairwise(rev) if u != v)
    return len(rev) - 2 * changes, changes


def _mul(p: list[Fraction], q: list[Fraction]) -> list[Fraction]:
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, u in enumerate(p):
        for j, v in enumerate(q):
            out[i + j] += u * v
    return out


def witnesses() -> dict[str, list[list[Fraction]]]:
    """Exact quartics (c0..c4) for each root configuration of a real quartic."""
    roots = [Fraction(k, 2) for k in range(-6, 7)]
    quads = [(Fraction(b, 2), Fraction(c, 2)) for b in range(-4, 5) for c in range(1, 9) if b * b < 4 * c]
    lin = lambda r: [-r, Fraction(1)]  # noqa: E731
    quad = lambda bc: [bc[1], bc[0], Fraction(1)]  # noqa: E731
    out: dict[str, list[list[Fraction]]] = defaultdict(list)

    def add(config: str, factors: list[list[Fraction]]) -> None:
        p = [Fraction(-1)]
        for f in factors:
            p = _mul(p, f)
        out[config].append(p)

    for r in itertools.combinations(roots, 4):
        add("1111", [lin(v) for v in r])
    for r1, r2, r3 in itertools.permutations(roots[::2], 3):
        add("211", [lin(r1), lin(r1), lin(r2), lin(r3)])
        add("31", [lin(r1)] * 3 + [lin(r2)])
        add("22", [lin(r1)] * 2 + [lin(r2)] * 2)
        add("4", [lin(r3)] * 4)
    for q in quads:
        for r1, r2 in itertools.combinations(roots[::2], 2):
            add("11c", [lin(r1), lin(r2), quad(q)])
            add("2c", [lin(r1), lin(r1), quad(q)])
        add("c2", [quad(q), quad(q)])
    for q1, q2 in itertools.combinations(quads, 2):
        add("cc", [quad(q1), quad(q2)])
    return out


CONFIG_COUNTS = {  # (distinct real, distinct non-real pairs)
    "1111": (4, 0),
    "211": (3, 0),
    "22": (2, 0),
    "31": (2, 0),
    "4": (1, 0),
    "11c": (2, 1),
    "2c": (1, 1),
    "cc": (0, 2),
    "c2": (0, 1),
}


def criterion(signs: tuple[int, ...]) -> bool:
    """Corollary 10: Delta_4 < 0, or Delta_4 = 0 and Delta_3 < 0 (signs of D_4, D_3)."""
    return signs[3] < 0 or (signs[3] == 0 and signs[2] < 0)


@proof.check(
    "Yang's classification of the roots of a quartic, over all 27 sign patterns", method=Method.CASES
)
def yang_classification() -> Finding:
    seen: dict[tuple[int, ...], set[str]] = defaultdict(set)
    total = 0
    for config, polys in witnesses().items():
        for p in polys:
            signs = discrimination(p)
            ensure(signs[0] == 1, "D_1 = 4 c4^2 > 0")
            ensure(yang_counts(signs) == CONFIG_COUNTS[config], f"{config}: {signs} -> {yang_counts(signs)}")
            seen[signs[1:]].add(config)
            total += 1
    ensure(set(CONFIG_COUNTS) == {c for cs in seen.values() for c in cs}, "every configuration realised")
    occurring = sorted(seen)
    return agrees(
        f"{total} exact quartics of the 9 root configurations realise {len(occurring)} of the 27 sign "
        "patterns of (D2, D3, D4); on each, Yang's revised sign list gives the constructed numbers of "
        "distinct real roots and non-real pairs"
    )


@proof.check(
    "Corollary 10's test is 'a non-real root' on every sign pattern with at most one simple non-real pair",
    method=Method.CASES,
)
def criterion_cases() -> Finding:
    allowed, excluded, impossible = [], [], []
    for tail in itertools.product((-1, 0, 1), repeat=3):
        signs = (1, *tail)
        real, pairs = yang_counts(signs)
        last = max(i + 1 for i, v in enumerate(signs) if v)
        if real < 0 or real + 2 * pairs + (4 - last) != 4:
            impossible.append(tail)  # Yang's counts are inconsistent with degree 4: no quartic has it
        elif pairs >= 2 or (pairs == 1 and real == 0):
            excluded.append(tail)  # two non-real pairs, or a double non-real pair
            ensure(not criterion(signs), f"{tail}: the test fires on a pattern it does not cover")
        else:
            ensure(criterion(signs) == (pairs == 1), f"{tail}: test {criterion(signs)}, pairs {pairs}")
            allowed.append(tail)
    return agrees(
        f"of the 27 patterns of (D2, D3, D4): {len(impossible)} are impossible for a quartic, on the "
        f"{len(allowed)} with at most one simple non-real pair the test equals 'a non-real root', and it is "
        f"false on the {len(excluded)} with two non-real pairs or a double one {excluded}, which an "
        "ellipsoid's pencil cannot have"
    )


@proof.check("(mu - conj nu) w^H E v = 0 for eigenvectors of the pencil", method=Method.IDENTITY)
def neutral_eigenvectors() -> Finding:
    n = 4
    e = sp.Matrix(n, n, lambda i, j: sp.Symbol(f"e{min(i, j)}{max(i, j)}", real=True))
    q = sp.Matrix(n, n, lambda i, j: sp.Symbol(f"q{min(i, j)}{max(i, j)}", real=True))
    mu, nu = sp.symbols("mu nu")
    v = sp.Matrix(sp.symbols("v0:4"))
    w = sp.Matrix(sp.symbols("w0:4"))
    wh = w.conjugate().T
    # w^H (mu E + Q) v - conj(v^H (nu E + Q) w) = (mu - conj nu) w^H E v, since E, Q are real symmetric.
    lhs = (wh * (mu * e + q) * v)[0, 0] - sp.conjugate((v.conjugate().T * (nu * e + q) * w)[0, 0])
    ensure(sp.expand(lhs - (mu - sp.conjugate(nu)) * (wh * e * v)[0, 0]) == 0, "identity")
    return agrees(
        "if (mu E + Q) v = 0 and (nu E + Q) w = 0 then (mu - conj nu) w^H E v = 0: eigenvectors of "
        "eigenvalues in the upper half-plane are E-neutral and pairwise E-orthogonal; a form of inertia "
        "(3, 1) has no 2-dimensional neutral subspace, so an ellipsoid's pencil has at most one (simple) "
        "non-real pair"
    )


@proof.search(
    "ellipsoids against arbitrary symmetric matrices: never two non-real pairs",
    examples=EXAMPLES,
    large=5000,
)
def one_pair_evidence(examples: int) -> Finding:
    seen = defaultdict(int)
    entry = st.integers(-9, 9)

    @search_settings(examples)
    @given(e=ellipsoids(), upper=st.tuples(*([entry] * 10)))
    def search(e: Quadric, upper: tuple[int, ...]) -> None:
        Q = Quadric._from_upper(tuple(Fraction(u) for u in upper))
        P = characteristic_polynomial(e, Q)
        f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in P.coefficients])
        if f.degree() < 1:
            return
        nonreal = sum(m for r, m in f.complex_roots() if not (r.imag.is_exact() and r.imag == 0))
        ensure(nonreal <= 2, f"{nonreal} non-real roots for {e} and {Q.matrix}")
        seen[nonreal] += 1

    search()
    return agrees(f"non-real roots per pencil: {dict(sorted(seen.items()))}; never more than 2")


@proof.check(
    "ellipsoids and Table 1 quadrics: the test equals 'P has a non-real root'",
    method=Method.EVIDENCE,
    size=f"{EXAMPLES} hypothesis examples",
)
def criterion_evidence() -> Finding:
    seen = defaultdict(int)

    @search_settings(EXAMPLES)
    @given(e=ellipsoids(), q=quadrics())
    def search(e: Quadric, q: Quadric) -> None:
        P = characteristic_polynomial(e, q)
        signs = discrimination(list(P.coefficients))
        f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in P.coefficients])
        nonreal = any(not (r.imag.is_exact() and r.imag == 0) for r, _ in f.complex_roots())
        ensure(criterion(signs) == nonreal, f"{signs} vs non-real {nonreal}")
        seen[nonreal] += 1

    search()
    return agrees(
        f"{seen[True]} pencils with a non-real pair, {seen[False]} real-rooted: the test agrees on all"
    )
