"""Example 6: Table 2 on a quadric whose type is numerically ambiguous.

Claim (printed).  For the printed decimal matrices ``Q`` and ``E``, the
eigenvalues of ``Q00`` are ``1.7485e-7, 0.99999991, -1.00000038`` and
``det Q = 1.0000019781303608 > 0``: ``Q`` may be read as a hyperbolic paraboloid
(``b = 0.9999998094301916``, ``L = 2.00000169069926``, curvature
``2/(L b^2) = 0.9999995357904882``) or as a hyperboloid of one sheet
(``d = 2391.4871252673324``, curvature ``a/(d c^2) = 0.9999995357904464``);
both estimates agree, the ellipsoid has ``alpha, beta, gamma, delta = 1.17162,
0.73910, 0.67501, 1.18107`` and minimum curvature ``0.41635``, so the pair is
not small whichever reading is used.

What is checked and how (exact computation with the package's public API:
:func:`~quadric_contact.model.invariants.invariants`,
:func:`~quadric_contact.paper.printed_tables.printed_table_2`,
:func:`~quadric_contact.theory.smallness.smallness`).  The printed matrices are read
as exact decimals.  The type of ``Q`` is decided exactly (the small eigenvalue
is exactly positive: a one-sheet hyperboloid).  The ``Q`` side of the printed
numbers is recomputed exactly from the printed ``Q``: they agree to float64
accuracy (relative ``1e-14``; ``1e-8`` for the quantities built on the
eigenvalue ``1.7e-7``, whose relative condition number is about ``1e7``).
The ``E`` side was computed by the paper from unrounded matrices; it is
checked against enclosures valid for every matrix whose entries round to
the printed six digits (ball arithmetic: entries as balls, eigenvalues
widened by Weyl's bound ``|mu_i(A + D) - mu_i(A)| <= ||D||_F``): each printed
value lies in its enclosure, and the conclusion (minimum curvature of ``E``
below both estimates for ``Q``) holds on the whole box.
"""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

import flint

from quadric_contact import Quadric, QuadricKind, paper
from quadric_contact._generated.formulas import det_symmetric_4
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.classification import principal_minor_sums_3
from quadric_contact.model.invariants import invariants
from quadric_contact.paper.printed_tables import printed_table_2
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure
from quadric_contact.theory.smallness import smallness

proof = Proof("Example 6", "Table 2 on a numerically ambiguous quadric: not small either way")

P = paper.PRINTED
UPPER = [(i, j) for i in range(4) for j in range(i, 4)]


def rows(name: str) -> list[list[str]]:
    return [r.split() for r in P[name].split(";")]


def matrix(name: str) -> Quadric:
    return Quadric([[Fraction(v) for v in r] for r in rows(name)])


def fmpq(x: Fraction) -> flint.fmpq:
    return flint.fmpq(x.numerator, x.denominator)


def half_unit(text: str) -> Fraction:
    """Half a unit in the sixth significant digit of a printed entry."""
    d = Decimal(text)
    return Fraction(Decimal(1).scaleb(math.floor(math.log10(abs(d))) - 5)) / 2


def rel(a: float, b: float) -> float:
    return abs(a / b - 1)


@proof.check("the type of the printed Q is decided exactly", method=Method.COMPUTATION)
def exact_type() -> Finding:
    Q, E = matrix("Example 6 Q"), matrix("Example 6 E")
    ensure(Q.kind is QuadricKind.HYPERBOLOID_ONE_SHEET, f"Q is {Q.kind}")
    ensure(E.kind is QuadricKind.ELLIPSOID, f"E is {E.kind}")
    inv = invariants(Q)
    small = inv.eigenvalues[1]
    ensure(small.sign() > 0 and inv.det > 0, "small eigenvalue > 0, det Q > 0")
    return agrees(
        f"exactly, Q00 has eigenvalues {', '.join(m.approx(10) for m in inv.eigenvalues)} (the small one "
        f"positive) and det Q = {float(inv.det):.16g} > 0: a hyperboloid of one sheet; E is an ellipsoid"
    )


@proof.check("the Q-side numbers are those of the printed Q, to float64 accuracy", method=Method.COMPUTATION)
def q_numbers() -> Finding:
    Q, E = matrix("Example 6 Q"), matrix("Example 6 E")
    inv = invariants(Q)
    ev = P["Example 6 EV"].split()
    checked = []
    for printed, value in zip(ev, (inv.eigenvalues[1], inv.eigenvalues[2], inv.eigenvalues[0]), strict=True):
        tol = 1e-8 if abs(float(printed)) < 1e-3 else 1e-14
        ensure(rel(float(value), float(printed)) < tol, f"eigenvalue {printed} vs {value.approx(17)}")
        checked.append(printed)
    ensure(rel(float(inv.det), float(P["Example 6 det Q"])) < 1e-14, "det Q")
    hp = printed_table_2(E, Q, reading="hyperbolic paraboloid")
    h1 = printed_table_2(E, Q, reading="hyperboloid of one sheet")
    pairs = [
        ("b", hp.value("b'"), P["Example 6 paraboloid b"], 1e-14),
        ("L", hp.value("L"), P["Example 6 paraboloid L"], 1e-14),
        ("2/(L b^2)", hp.conditions[0].decimal("lhs", 20), P["Example 6 paraboloid curvature"], 1e-14),
        ("a/(d c^2)", h1.conditions[1].decimal("lhs", 20), P["Example 6 hyperboloid curvature"], 1e-14),
        ("d", h1.value("d'"), P["Example 6 hyperboloid d"], 1e-8),
    ]
    for name, got, printed, tol in pairs:
        ensure(rel(float(got), float(printed)) < tol, f"{name}: {got} vs printed {printed}")
        checked.append(f"{name} = {printed}")
    return agrees("exact values of the printed Q reproduce " + ", ".join(checked))


def box(name: str) -> dict[str, object]:
    """Enclosures of det, J and the eigenvalues over every matrix rounding to the printed one."""
    r = rows(name)
    balls = [flint.arb(fmpq(Fraction(r[i][j])), fmpq(half_unit(r[i][j]))) for i, j in UPPER]
    det = det_symmetric_4(*balls)
    _, J, _ = principal_minor_sums_3((balls[0], balls[1], balls[2], balls[4], balls[5], balls[7]))
    frob2 = sum(half_unit(r[i][j]) ** 2 * (1 if i == j else 2) for i, j in UPPER if j < 3)
    radius = flint.arb(fmpq(frob2)).sqrt()
    eig = [m.enclosure(200) + flint.arb(0, radius.upper()) for m in invariants(matrix(name)).eigenvalues]
    return {"det": det, "J": J, "eig": eig}


def inside(printed: str, ball: flint.arb) -> bool:
    return ball.contains(flint.arb(fmpq(Fraction(printed))))


@proof.check(
    "the E-side numbers lie in their enclosures over the rounding box; the conclusion holds on it",
    method=Method.COMPUTATION,
)
def e_numbers_and_conclusion() -> Finding:
    with working_precision(200):
        q, e = box("Example 6 Q"), box("Example 6 E")
        n1, n2, n3 = e["eig"]  # type: ignore[misc]
        alpha, beta, gamma = 1 / n1.sqrt(), 1 / n2.sqrt(), 1 / n3.sqrt()
        delta = (-e["det"] / (n1 * n2 * n3)).sqrt()  # type: ignore[operator]
        k_e = gamma / (delta * alpha**2)
        for name, ball in (
            ("alpha", alpha),
            ("beta", beta),
            ("gamma", gamma),
            ("delta", delta),
            ("E curvature", k_e),
        ):
            ensure(inside(P[f"Example 6 {name}"], ball), f"{name}: {P[f'Example 6 {name}']} not in {ball}")
        mu3 = -q["eig"][0]  # type: ignore[index]
        mu2 = q["eig"][2]  # type: ignore[index]
        k_hp = 2 * mu3 / (-4 * q["det"] / q["J"]).sqrt()  # type: ignore[operator]
        k_h1 = mu2.sqrt() * mu3 * mu3.sqrt() / q["det"].sqrt()  # type: ignore[union-attr]
        ensure(k_e.upper() < k_hp.lower() and k_e.upper() < k_h1.lower(), "not small on the whole box")
    Q, E = matrix("Example 6 Q"), matrix("Example 6 E")
    report = smallness(E, Q)
    ensure(not report.small and not report.paper_small, "not small (exact, printed matrices)")
    for reading in ("hyperbolic paraboloid", "hyperboloid of one sheet"):
        ensure(printed_table_2(E, Q, reading=reading).small is False, f"{reading} reading: not small")
    return agrees(
        "alpha, beta, gamma, delta and gamma/(delta alpha^2) as printed lie in their enclosures (delta only "
        f"to {float(delta.rad()):.1g}: the printed E is rounded); the minimum curvature of E, at most "
        f"{float(k_e.upper()):.5f}, is below both estimates for Q (at least "
        f"{float(min(k_hp.lower(), k_h1.lower())):.5f}) "
        "for every matrix consistent with the printed digits: not small, in both readings and exactly"
    )


@proof.check(
    "both readings estimate the largest curvature of Q alike (0.99999954)", method=Method.COMPUTATION
)
def readings_agree() -> Finding:
    Q, E = matrix("Example 6 Q"), matrix("Example 6 E")
    hp = printed_table_2(E, Q, reading="hyperbolic paraboloid").conditions[0].decimal("lhs", 8)
    h1 = printed_table_2(E, Q, reading="hyperboloid of one sheet").conditions[1].decimal("lhs", 8)
    exact = smallness(E, Q).conditions[1].decimal("lhs", 8)
    ensure(hp == h1 == exact, f"{hp}, {h1}, {exact}")
    return agrees(
        f"2/(L b^2) = a/(d c^2) = {hp} to 8 digits, and the exact one-sheet value is {exact}: the smallness "
        "verdict does not depend on how the near-zero eigenvalue is read"
    )
