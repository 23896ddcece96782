"""Remark 16: the sign of c3 is the side of the ellipsoid's centre.

Claim (printed).  For the plane ``a x + b y + c z - d = 0`` and an ellipsoid
with centre ``(x_c, y_c, z_c)`` and semi-axes ``alpha, beta, gamma`` as in
eq. (2), not in transversal contact, the sign of ``a x_c + b y_c + c z_c - d``
tells ``R+`` from ``R-``, equivalently the sign of ``c3`` (Corollary 15),
since ``c3 = (a x_c + b y_c + c z_c - d) / (alpha^2 beta^2 gamma^2)``.

What is checked and how.  Symbolic identity: ``c3`` of the pencil of the
translated ellipsoid ``(x-x_c)^2/alpha^2 + (y-y_c)^2/beta^2 + (z-z_c)^2/gamma^2 = 1``
and the plane equals the printed expression.  It holds for a rotated
ellipsoid too: for ``(x - m)^T A (x - m) = 1`` with a generic symmetric ``A``,
``c3 = det(A) (n . m - d)`` and ``det A = 1/(alpha^2 beta^2 gamma^2)`` is
invariant under rotations (identity).  That the centre's side is the
ellipsoid's is proved from the identities of Theorem 14: with ``h = n . m - d``
and ``s = sqrt(n^T A^-1 n) > 0``, no transversal contact means
``c3^2 - 4 c4 c2 = det(A)^2 (h^2 - s^2) >= 0``, so ``h != 0``, and on the
ellipsoid ``n . x - d`` ranges over ``[h - s, h + s]``, whose ends have the
sign of ``h`` (their product is ``h^2 - s^2 >= 0``): the whole ellipsoid is on
the side of its centre, the side of ``sign(c3) = sign(h)`` since
``det A > 0``.  Cross-check of the package (full profile): 1000 hypothesis
examples (random rational ellipsoids and planes) where
:func:`~quadric_contact.plane_side` and the sign of the plane's equation at
the centre agree whenever there is no transversal contact.
"""

from __future__ import annotations

import sympy as sp

from quadric_contact import Region, paper, plane_side
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure, search_settings

from ._plane_pencil import general_plane_pencil, plane_pencil

proof = Proof(
    "Remark 16", "c3 = (a x_c + b y_c + c z_c - d) / (alpha^2 beta^2 gamma^2)", relies_on=("Theorem 14",)
)


def pencil_c3(A: sp.Matrix, m: sp.Matrix, n: sp.Matrix, d: sp.Expr) -> sp.Expr:
    return plane_pencil(A, m, n, d)[3]


@proof.check(
    "c3 of the translated ellipsoid (2) and the plane equals the printed expression", method=Method.IDENTITY
)
def c3_axis_aligned() -> Finding:
    al, be, ga = sp.symbols("alpha beta gamma", positive=True)
    a, b, c, d, xc, yc, zc = sp.symbols("a b c d x_c y_c z_c", real=True)
    A = sp.diag(1 / al**2, 1 / be**2, 1 / ga**2)
    c3 = pencil_c3(A, sp.Matrix([xc, yc, zc]), sp.Matrix([a, b, c]), d)
    names = {
        "a": a,
        "b": b,
        "c": c,
        "d": d,
        "x_c": xc,
        "y_c": yc,
        "z_c": zc,
        "alpha": al,
        "beta": be,
        "gamma": ga,
    }
    printed = sp.sympify(paper.PRINTED["Remark 16 c3"], locals=names)
    ensure(sp.simplify(c3 - printed) == 0, f"c3 = {sp.factor(c3)}")
    return agrees("c3 = (a x_c + b y_c + c z_c - d) / (alpha^2 beta^2 gamma^2) identically")


@proof.check(
    "for a rotated ellipsoid c3 = det(A) (n.m - d), det A = 1/(alpha beta gamma)^2", method=Method.IDENTITY
)
def c3_rotated() -> Finding:
    s = sp.symbols("a00 a01 a02 a11 a12 a22", real=True)
    A = sp.Matrix([[s[0], s[1], s[2]], [s[1], s[3], s[4]], [s[2], s[4], s[5]]])
    m = sp.Matrix(sp.symbols("m1:4", real=True))
    n = sp.Matrix(sp.symbols("n1:4", real=True))
    d = sp.Symbol("d", real=True)
    c3 = pencil_c3(A, m, n, d)
    ensure(sp.expand(c3 - A.det() * ((n.T * m)[0, 0] - d)) == 0, "c3 = det(A)(n.m - d)")
    # det(R^T D R) = det D for a rotation R: det A = 1/(alpha^2 beta^2 gamma^2) for any orientation.
    return agrees(
        "c3 = det(A) (n.m - d) for every orientation; det A = det(R^T diag(...) R) = 1/(alpha beta gamma)^2"
    )


@proof.check(
    "with no transversal contact the ellipsoid lies on the side of its centre, the side sign(c3)",
    method=Method.IDENTITY,
)
def centre_side() -> Finding:
    c, A, m, n, d = general_plane_pencil()
    detA = A.det()
    h = (n.T * m)[0, 0] - d
    s2 = (n.T * A.adjugate() * n)[0, 0] / detA  # n^T A^-1 n = s^2
    ensure(sp.expand(c[3] - detA * h) == 0, "c3 = det(A) h")
    ensure(sp.simplify(c[3] ** 2 - 4 * c[4] * c[2] - detA**2 * (h**2 - s2)) == 0, "c3^2 - 4 c4 c2")
    hh, ss = sp.symbols("h s", real=True)
    ensure(sp.expand((hh - ss) * (hh + ss) - (hh**2 - ss**2)) == 0, "(h - s)(h + s) = h^2 - s^2")
    return agrees(
        "no transversal contact: det(A)^2 (h^2 - s^2) = c3^2 - 4 c4 c2 >= 0 with s > 0, so h != 0 and "
        "n.x - d in [h - s, h + s] (Theorem 14) keeps the sign of h on the ellipsoid; c3 = det(A) h with "
        "det A > 0: the side of the ellipsoid, of its centre and of c3 coincide"
    )


@proof.search(
    "the package's plane_side: the centre's side and c3 agree whenever there is no transversal contact",
    examples=0,
    large=1000,
    method=Method.CROSS_CHECK,
)
def centre_side_cross_check(examples: int) -> Finding:
    from hypothesis import given

    from quadric_contact.testing.strategies import ellipsoids, planes

    seen = {"crossing": 0, "clear": 0}

    @search_settings(examples)
    @given(e=ellipsoids(), p=planes())
    def search(e: object, p: object) -> None:
        side = plane_side(e, p)
        if side.zone is Region.CONTACT:
            seen["crossing"] += 1
            return
        seen["clear"] += 1
        ensure(side.center_value != 0, "the centre is not on the plane")
        ensure((side.center_value > 0) == (side.c3 > 0) == (side.zone is Region.R_PLUS), str(side))

    search()
    ensure(seen["clear"] > 0 and seen["crossing"] > 0, f"both cases were met: {seen}")
    return agrees(
        f"{seen['clear']} pairs clear of each other: sign(c3) = sign of the plane at the centre = side; "
        f"{seen['crossing']} crossing pairs"
    )
