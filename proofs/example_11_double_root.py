"""Example 11: a double real root and a non-real pair (possibility (2) of Corollary 10).

Claim (printed).  For the ellipsoid ``2x^2 + 2y^2 + 3z^2 - 1 = 0`` and the
elliptic paraboloid ``x^2 + y^2 + 8z = 0``, ``P(l) = -(1 + 2l)^2 (16 + 3l^2)``,
with the real double root ``-1/2`` and the roots ``+-4i/sqrt(3)``;
``Delta_4 = 0`` and ``Delta_3 = -400``, so the quadrics are in transversal
contact (Corollary 10 (2)); by Remark 9 smallness need not be checked.

What is checked and how (exact computation).  ``P`` from the package's exact
pencil equals the printed product; sympy's exact roots are ``-1/2`` (twice)
and ``+-4 i / sqrt 3``; ``Delta_4`` and ``Delta_3`` are evaluated with the
formulas of Section 3.2 (``Delta_3`` as printed, which Section 3.2 proves
correct): ``Delta_4 = 0`` as printed, ``Delta_3 = -13790208`` and not
``-400``.  That no normalisation of ``P`` explains ``-400`` is an exhaustive
argument: for ``s P(k l)`` (any rational ``s, k``), and for the reversed
polynomial, ``Delta_3`` is multiplied by ``s^4 k^10`` (a weighted-homogeneity
identity checked symbolically), and the required factor ``-400 / Delta_3`` has
a prime with an odd exponent, which ``s^4 k^10`` never has.  The conclusion
(transversal contact) is confirmed geometrically: the points ``(0, 0, +-1/sqrt 3)``
of the ellipsoid lie on opposite sides of the paraboloid.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from quadric_contact import characteristic_polynomial, paper, transversal_contact
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, differs, ensure

proof = Proof("Example 11", "transversal contact detected by Delta_4 = 0 and Delta_3 < 0")

LAM = sp.Symbol("lambda")
C = sp.symbols("c0:5")
E_TEXT, Q_TEXT = paper.PRINTED["Example 11 E"], paper.PRINTED["Example 11 Q"]


def printed_delta3(coeffs: list[sp.Rational]) -> sp.Rational:
    formula = sp.sympify(paper.PRINTED["Delta3"], locals={str(c): c for c in C})
    return formula.subs(dict(zip(C, coeffs, strict=True)))


def pencil() -> tuple[object, list[sp.Rational]]:
    P = characteristic_polynomial(E_TEXT, Q_TEXT)
    return P, [sp.Rational(c.numerator, c.denominator) for c in P.coefficients]


@proof.check("P(l) = -(1 + 2l)^2 (16 + 3l^2) and its roots", method=Method.COMPUTATION)
def polynomial() -> Finding:
    P, _ = pencil()
    printed = sp.sympify(paper.PRINTED["Example 11 P"].replace("lambda", "LAM"), locals={"LAM": LAM})
    ensure(sp.expand(P.as_sympy() - printed) == 0, f"P = {P} differs from the printed product")
    roots = sp.roots(sp.Poly(printed, LAM))
    expected = {sp.Rational(-1, 2): 2, 4 * sp.I / sp.sqrt(3): 1, -4 * sp.I / sp.sqrt(3): 1}
    ensure({sp.nsimplify(r): m for r, m in roots.items()} == expected, f"roots {roots}")
    ensure(P.structure.real == (2,) and P.structure.nonreal == (1,), P.structure.describe())
    return agrees(
        "P = -12 l^4 - 12 l^3 - 67 l^2 - 64 l - 16 = -(1 + 2l)^2 (16 + 3l^2); roots -1/2 (double), "
        "+-4i/sqrt 3"
    )


@proof.check("Delta_4 = 0", method=Method.COMPUTATION)
def delta4() -> Finding:
    P, _ = pencil()
    d4 = P.deltas()[2]
    ensure(d4 == int(paper.PRINTED["Example 11 Delta4"]) == 0, f"Delta_4 = {d4}")
    return agrees("Delta_4 = 0 (a multiple root)")


@proof.check("Delta_3 = -400", method=Method.COMPUTATION, erratum="example-11-delta3")
def delta3() -> Finding:
    P, coeffs = pencil()
    value = printed_delta3(coeffs)
    ensure(value == P.deltas()[1], "the package's Delta_3 agrees with the printed formula")
    shown = sp.Integer(paper.PRINTED["Example 11 Delta3"])
    if value == shown:
        return agrees(f"Delta_3 = {value}")
    ensure((value < 0) == (shown < 0), "the sign, which is all Corollary 10 uses, agrees")
    return differs(f"Delta_3 = {shown}", f"Delta_3 = {value} (same sign: the conclusion stands)")


@proof.check(
    "no rescaling s P(k l), nor the reversed polynomial, has Delta_3 = -400",
    method=Method.CASES,
    erratum="example-11-delta3",
)
def no_normalisation_gives_printed() -> Finding:
    s, k = sp.symbols("s k", positive=True)
    generic = sp.sympify(paper.PRINTED["Delta3"], locals={str(c): c for c in C})
    scaled = generic.subs({C[i]: s * k**i * C[i] for i in range(5)}, simultaneous=True)
    ensure(sp.expand(scaled - s**4 * k**10 * generic) == 0, "Delta_3(s P(k l)) = s^4 k^10 Delta_3(P)")
    _, coeffs = pencil()
    target = sp.Integer(paper.PRINTED["Example 11 Delta3"])
    explained = []
    for label, cs in (("P", coeffs), ("reversed P", coeffs[::-1])):
        value = printed_delta3(cs)
        ratio = Fraction(int(target), int(value)) if value != 0 else None
        if ratio is None or ratio <= 0:
            continue
        exponents = {
            **sp.factorint(ratio.numerator),
            **{p: -e for p, e in sp.factorint(ratio.denominator).items()},
        }
        if all(e % 2 == 0 for e in exponents.values()):
            explained.append(label)  # s^4 k^10 can have only even exponents: this case might be explained
        ensure(label != "P" or any(e % 2 for e in exponents.values()), f"{label}: ratio {ratio} {exponents}")
    if explained:
        return agrees(f"a rescaling of {explained} may give -400")
    _, c = pencil()
    return differs(
        "Delta_3 = -400",
        f"-400 / Delta_3 = {Fraction(-400, int(printed_delta3(c)))} has a prime with an odd exponent, "
        "while rescaling P or l multiplies Delta_3 by s^4 k^10 (only even exponents); likewise for the "
        "reversed polynomial: -400 is no normalisation of Delta_3",
    )


@proof.check(
    "the quadrics are in transversal contact (Remark 9: no smallness needed)", method=Method.CONSTRUCTION
)
def transversal() -> Finding:
    x, y, z = sp.symbols("x y z")
    E = sp.sympify(E_TEXT, locals={"x": x, "y": y, "z": z})
    Q = sp.sympify(Q_TEXT, locals={"x": x, "y": y, "z": z})
    signs = set()
    for p in ((0, 0, 1 / sp.sqrt(3)), (0, 0, -1 / sp.sqrt(3))):
        point = dict(zip((x, y, z), p, strict=True))
        ensure(sp.simplify(E.subs(point)) == 0, f"{p} is on the ellipsoid")
        signs.add(sp.sign(Q.subs(point)))
    ensure(signs == {-1, 1}, "the ellipsoid has points on both sides of the paraboloid")
    r = transversal_contact(E_TEXT, Q_TEXT)
    ensure(bool(r) and r.decided_by == "Remark 9", str(r))
    return agrees(
        "(0, 0, +-1/sqrt 3) on the ellipsoid give Q = +-8/sqrt 3: the surfaces cross, as Delta_3 < 0 says"
    )
