"""Section 3.2: the two members Delta_3 and Delta_4 of the discrimination system.

Claim (printed).  For ``P = c4 l^4 + c3 l^3 + c2 l^2 + c1 l + c0`` the paper
prints Delta_3 and Delta_4 (after Yang 1999 and Emiris-Tsigaridas 2008) and
uses their signs in Corollary 10 and Algorithms 1-2.

What is checked and how.  Yang's discrimination matrix of ``P`` and ``P'`` is
built here from its definition (rows alternating shifted copies of the
coefficients of ``P`` and of ``P'``) and its leading principal minors of even
order ``D_1 .. D_4`` are expanded by sympy.  Symbolic identities: the printed
Delta_3 equals ``D_3 / (2 c4^2)`` term by term; ``D_4 / c4^2`` equals the
classical discriminant of ``P`` (sympy's resultant-based one), so it is the
Delta_4 the paper means; the printed Delta_4 differs from it in exactly one
term, ``-27 c0^2 c4^4`` printed for ``-27 c0^2 c3^4``, a term that is not even
isobaric (weight 16 where every term of a quartic discriminant has weight 12).
Exact construction: a sphere centred on the surface of an ellipsoid (so in
transversal contact) for which the printed Delta_4 is positive and the true
one negative, so the printed formula in Corollary 10 would report no contact.
"""

from __future__ import annotations

import sympy as sp

from quadric_contact import Quadric, characteristic_polynomial, paper
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, differs, ensure

proof = Proof("Section 3.2", "the discriminants Delta_3 and Delta_4 of a quartic")

C = sp.symbols("c0:5")
LAM = sp.Symbol("lambda")
NAMES = {str(s): s for s in C}


def printed(key: str) -> sp.Expr:
    return sp.expand(sp.sympify(paper.PRINTED[key], locals=NAMES))


def yang_minors() -> list[sp.Expr]:
    """``D_1 .. D_4`` of the discrimination matrix of ``P`` and ``P'`` (Yang 1999, Def. 1)."""
    a = [C[4], C[3], C[2], C[1], C[0]]  # highest degree first
    da = [4 * C[4], 3 * C[3], 2 * C[2], C[1]]
    M = sp.zeros(8, 8)
    for i in range(4):
        for j, coef in enumerate(a):
            M[2 * i, i + j] = coef
        for j, coef in enumerate(da):
            M[2 * i + 1, i + 1 + j] = coef
    return [sp.expand(M[: 2 * k, : 2 * k].det(method="berkowitz")) for k in range(1, 5)]


def terms(expr: sp.Expr) -> dict[tuple[int, ...], sp.Integer]:
    return dict(sp.Poly(expr, *C).terms())


def weight(monomial: tuple[int, ...]) -> int:
    return sum(i * e for i, e in enumerate(monomial))


@proof.check("printed Delta_3 = D_3 / (2 c4^2), term by term", method=Method.IDENTITY)
def delta3() -> Finding:
    D = yang_minors()
    ensure(sp.expand(D[0] - 4 * C[4] ** 2) == 0, "D_1 = 4 c4^2 > 0")
    difference = sp.expand(2 * C[4] ** 2 * printed("Delta3") - D[2])
    ensure(difference == 0, f"2 c4^2 Delta_3 - D_3 = {difference}")
    return agrees("2 c4^2 * (printed Delta_3) = D_3 identically, so sign(Delta_3) = sign(D_3)")


@proof.check("D_4 / c4^2 is the discriminant of P", method=Method.IDENTITY)
def delta4_is_discriminant() -> Finding:
    D4 = yang_minors()[3]
    q, r = sp.div(sp.Poly(D4, *C), sp.Poly(C[4] ** 2, *C))
    ensure(r.is_zero, "c4^2 divides D_4")
    P = sum(C[k] * LAM**k for k in range(5))
    disc = sp.discriminant(P, LAM)
    ensure(sp.expand(q.as_expr() - disc) == 0, "D_4 / c4^2 equals sympy's discriminant")
    ensure(all(weight(m) == 12 and sum(m) == 6 for m in terms(disc)), "the discriminant is isobaric")
    return agrees("D_4 / c4^2 = disc(P): homogeneous of degree 6, isobaric of weight 12 in c0..c4")


@proof.check("printed Delta_4 = D_4 / c4^2, term by term", method=Method.IDENTITY, erratum="delta4-term")
def delta4() -> Finding:
    true = terms(sp.expand(yang_minors()[3] / C[4] ** 2))
    shown = terms(printed("Delta4"))
    only_printed = {m: k for m, k in shown.items() if true.get(m) != k}
    only_true = {m: k for m, k in true.items() if shown.get(m) != k}
    if not only_printed and not only_true:
        return agrees("the printed Delta_4 equals D_4 / c4^2")

    def show(d: dict[tuple[int, ...], sp.Integer]) -> str:
        return " + ".join(str(k * sp.Mul(*(c**e for c, e in zip(C, m, strict=True)))) for m, k in d.items())

    weights = sorted({weight(m) for m in only_printed})
    return differs(
        f"{show(only_printed)} (weight {', '.join(map(str, weights))})",
        f"{show(only_true)} (weight 12, like every other term); all other 15 terms agree",
    )


@proof.check(
    "the misprint changes the answer of Corollary 10 on a real pair",
    method=Method.CONSTRUCTION,
    erratum="delta4-term",
)
def delta4_consequence() -> Finding:
    Q = Quadric.ellipsoid(3, 2, 1)
    E = Quadric.sphere(1, (-3, 0, 0))  # centred at the vertex (-3, 0, 0) of Q: Q takes both signs on E
    ensure(Q.value_at((-3, 0, 0)) == 0, "the centre of the sphere is on Q")
    ensure(Q.value_at((-2, 0, 0)) < 0 < Q.value_at((-4, 0, 0)), "E has points on both sides of Q")
    P = characteristic_polynomial(E, Q)
    ensure(not P.structure.all_real, "P has non-real roots (transversal contact)")
    true = P.deltas()[2]
    values = {NAMES[f"c{k}"]: sp.Rational(c.numerator, c.denominator) for k, c in enumerate(P.coefficients)}
    shown = printed("Delta4").subs(values)
    if (shown < 0) == (true < 0):
        return agrees("the printed Delta_4 has the sign of the true one on this pair")
    return differs(
        f"Delta_4 = {sp.N(shown, 6)} > 0 for the unit sphere centred at the vertex (-3, 0, 0) of "
        "x^2/9 + y^2/4 + z^2 = 1 (Corollary 10 would say: no transversal contact)",
        f"Delta_4 = {sp.N(true, 6)} < 0: the two surfaces cross (points (-2,0,0) and (-4,0,0) of the "
        "sphere lie on opposite sides)",
    )
