"""Corollary 15: the side of a plane from c2, c3, c4.

Claim (printed).  For an ellipsoid and a plane with
``P = c4 l^4 + c3 l^3 + c2 l^2``: (1) transversal contact iff
``c3^2 < 4 c1 c2``; (2) otherwise ``E`` is in ``R+`` iff ``c3 > 0`` and in
``R-`` iff ``c3 < 0``.  Proof: ``Delta_4 = 0`` always; transversal contact is
``Delta_3 < 0``, "which reduces to ``0 < 4 c1 c2 - c3^2``"; ``c4 < 0`` and
``c2 < 0`` by eq. (12), and Descartes' rule gives (2).

What is checked and how.  Symbolic identities on the general pencil of an
ellipsoid ``(x - m)^T A (x - m) = 1`` (generic symmetric ``A``) and a plane
``n . x = d``: ``c0 = c1 = 0``, so ``Delta_4 = 0`` and the printed condition
``c3^2 < 4 c1 c2`` reads ``c3^2 < 0`` and never holds; ``Delta_3`` with
``c0 = c1 = 0`` is ``c2^2 (c3^2 - 4 c4 c2)``, so the true condition is
``c3^2 < 4 c4 c2``; ``c4 = -det A < 0`` and ``c2 = -n^T adj(A) n / 4 < 0``
(``adj A = det(A) A^-1`` is positive definite).  Exact construction: the bee
of Example 17 against the plane ``z = 11/2`` through its centre, a transversal
contact the printed condition misses.  Part (2) is an exhaustive case
analysis of the sign patterns ``(c4, c3, c2) = (-, s, -)`` of a real-rooted
``c4 l^2 + c3 l + c2`` (Descartes' rule is exact there).
"""

from __future__ import annotations

import itertools

import sympy as sp

from quadric_contact import Region, characteristic_polynomial, paper, plane_side
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, differs, ensure

from ._plane_pencil import general_plane_pencil

proof = Proof("Corollary 15", "c3^2 < 4 c4 c2 and the sign of c3 decide a plane")

C = sp.symbols("c0:5")


def general_pencil() -> tuple[list[sp.Expr], sp.Matrix, sp.Matrix]:
    """Coefficients of det(l E + P) for (x - m)^T A (x - m) = 1 and the plane n.x = d."""
    c, A, _, n, _ = general_plane_pencil()
    return c, A, n


def printed_delta(key: str) -> sp.Expr:
    return sp.sympify(paper.PRINTED[key], locals={str(c): c for c in C})


@proof.check(
    "(1) as printed: transversal contact iff c3^2 < 4 c1 c2",
    method=Method.IDENTITY,
    erratum="corollary-15-c1",
)
def condition_1() -> Finding:
    c, A, n = general_pencil()
    ensure(c[0] == 0, "c0 = 0")
    if c[1] != 0:
        return agrees("c1 is not identically zero")
    return differs(
        "transversal contact iff c3^2 < 4 c1 c2",
        "transversal contact iff c3^2 < 4 c4 c2: for every ellipsoid and plane c1 = c0 = 0 identically, "
        "so the printed condition (c3^2 < 0) never holds",
    )


@proof.check(
    "proof of (1): Delta_4 = 0 and Delta_3 < 0 reduces to ...",
    method=Method.IDENTITY,
    erratum="corollary-15-c1",
)
def proof_reduction() -> Finding:
    plane = {C[0]: 0, C[1]: 0}
    d4 = sp.expand(printed_delta("Delta4").subs(plane))
    ensure(d4 == 0, "Delta_4 = 0 when c0 = c1 = 0")
    d3 = sp.factor(printed_delta("Delta3").subs(plane))
    ensure(sp.expand(d3 - C[2] ** 2 * (C[3] ** 2 - 4 * C[4] * C[2])) == 0, f"Delta_3 = {d3}")
    return differs(
        "Delta_3 < 0 reduces to 0 < 4 c1 c2 - c3^2",
        "Delta_3 = c2^2 (c3^2 - 4 c4 c2) when c0 = c1 = 0, so (c2 != 0) Delta_3 < 0 iff 0 < 4 c4 c2 - c3^2",
    )


@proof.check("c4 < 0 and c2 < 0 for every ellipsoid and plane", method=Method.IDENTITY)
def signs_c4_c2() -> Finding:
    c, A, n = general_pencil()
    ensure(sp.expand(c[4] + A.det()) == 0, "c4 = -det A")
    ensure(sp.expand(c[2] + (n.T * A.adjugate() * n)[0, 0] / 4) == 0, "c2 = -n^T adj(A) n / 4")
    ensure(sp.simplify(A.adjugate() - A.det() * A.inv()) == sp.zeros(3, 3), "adj A = det(A) A^-1")
    return agrees(
        "c4 = -det A < 0 and c2 = -n^T adj(A) n / 4 < 0, adj A = det(A) A^-1 being positive definite"
    )


@proof.check(
    "the printed condition misses a real transversal contact (Example 17's bee)",
    method=Method.CONSTRUCTION,
    erratum="corollary-15-c1",
)
def misses_contact() -> Finding:
    bee = paper.PRINTED["Example 17 E"]
    side = plane_side(bee, "z - 11/2")  # the plane through the bee's centre
    P = characteristic_polynomial(bee, "z - 11/2")
    c0, c1, c2, c3, c4 = P.coefficients
    ensure(
        side.zone is Region.CONTACT and not P.structure.all_real, "the plane through the centre cuts the bee"
    )
    printed_says = c3 * c3 < 4 * c1 * c2
    true_says = c3 * c3 < 4 * c4 * c2
    ensure(true_says, "c3^2 < 4 c4 c2 detects it")
    if printed_says:
        return agrees("the printed condition detects the contact")
    return differs(
        f"c3^2 < 4 c1 c2 is false ({c3 * c3} < {4 * c1 * c2}): no contact",
        f"the plane z = 11/2 through the bee's centre cuts it; c3^2 = {c3 * c3} < 4 c4 c2 = {4 * c4 * c2}",
    )


@proof.check("(2): with no transversal contact, R+ iff c3 > 0 and R- iff c3 < 0", method=Method.CASES)
def part_2() -> Finding:
    # c4 l^2 + c3 l + c2 with c4 < 0, c2 < 0, real roots: Descartes is exact.
    for s3 in (-1, 0, 1):
        signs = [-1, s3, -1]  # c4, c3, c2 (decreasing degree)
        nonzero = [s for s in signs if s]
        variations = sum(1 for a, b in itertools.pairwise(nonzero) if a != b)
        ensure(variations == (2 if s3 > 0 else 0), f"c3 sign {s3}")
    # c3 = 0 with c4 c2 > 0 means c3^2 < 4 c4 c2: transversal contact, so never the case here.
    return agrees(
        "for c4 < 0, c2 < 0 and real roots: c3 > 0 gives 2 sign changes (two positive roots: R+ by "
        "Theorem 14), c3 < 0 none (two negative roots: R-); c3 = 0 would be transversal contact"
    )
