"""Theorem 14 and eq. (12): an ellipsoid and a plane.

Claim.  For any ellipsoid ``E`` and plane ``P`` (no smallness needed), ``E``
and ``P`` are in transversal contact iff ``det(l E + P)`` has two non-real
roots; 0 is always a double root, and without transversal contact the other
two roots are positive if ``E`` is in ``R+`` and negative if it is in ``R-``.
The proof reduces to the sphere ``S`` of radius ``r`` centred at
``(0, 0, z_c)`` and the plane ``z = 0``, where
``P(l) = -l^2 (r^2 + 4 l (l - z_c)) / (4 r^6)`` (eq. (12)) with the roots
``0, 0, (z_c +- sqrt(z_c^2 - r^2)) / 2``.

What is checked and how.  Symbolic identities: eq. (12) for the printed
matrices ``S`` and ``P_0``; its roots; the sign of the non-zero roots (their
product is ``r^2/4 > 0`` and their sum ``z_c``).  The reduction is replaced by
a direct symbolic proof for the general case: an ellipsoid
``(x - m)^T A (x - m) = 1`` with a generic symmetric ``A`` (six symbols) and
centre ``m``, and the plane ``n . x = d``, give
``P = l^2 (c4 l^2 + c3 l + c2)`` with ``c4 = -det A``,
``c3 = det A (n . m - d)`` and ``c2 = -n^T adj(A) n / 4``, hence
``c3^2 - 4 c4 c2 = det(A)^2 ((n . m - d)^2 - n^T A^-1 n)``.  As
``n . m +- sqrt(n^T A^-1 n)`` are the extreme values of ``n . x`` on the
ellipsoid (the maximiser ``m + A^-1 n / sqrt(n^T A^-1 n)`` is checked to lie
on it, and Cauchy-Schwarz bounds every other point), the plane cuts the
ellipsoid iff ``c3^2 < 4 c4 c2`` iff the two non-zero roots are non-real;
otherwise their product ``c2/c4 > 0`` and their sum ``-c3/c4`` has the sign
of ``n . m - d``, the side of the centre.
"""

from __future__ import annotations

import sympy as sp

from quadric_contact import paper
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure

from ._plane_pencil import LAM, general_plane_pencil

proof = Proof("Theorem 14", "an ellipsoid and a plane: roots 0, 0 and a pair", covers=("eq. (12)",))


def sphere_and_plane() -> tuple[sp.Expr, sp.Symbol, sp.Symbol]:
    r, zc = sp.symbols("r z_c", positive=True)
    S = sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -zc], [0, 0, -zc, zc**2 - r**2]]) / r**2
    half = sp.Rational(1, 2)
    P0 = sp.Matrix([[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, half], [0, 0, half, 0]])
    return sp.expand((LAM * S + P0).det()), r, zc


@proof.check("eq. (12): det(l S + P_0) = -l^2 (r^2 + 4 l (l - z_c)) / (4 r^6)", method=Method.IDENTITY)
def eq_12() -> Finding:
    P, r, zc = sphere_and_plane()
    z_c = sp.Symbol("z_c", positive=True)
    printed = sp.sympify(
        paper.PRINTED["eq. (12)"].replace("lambda", "LAM"), locals={"LAM": LAM, "r": r, "z_c": z_c}
    )
    ensure(sp.simplify(P - printed.subs(z_c, zc)) == 0, f"P = {sp.factor(P)}")
    return agrees("det(l S + P_0) = -l^2 (r^2 + 4 l (l - z_c)) / (4 r^6) identically")


@proof.check("roots 0, 0, (z_c +- sqrt(z_c^2 - r^2)) / 2 and their signs", method=Method.IDENTITY)
def roots_and_signs() -> Finding:
    r, zc = sp.symbols("r z_c", real=True)
    quadratic = r**2 + 4 * LAM * (LAM - zc)
    for sign in (1, -1):
        root = (zc + sign * sp.sqrt(zc**2 - r**2)) / 2
        ensure(sp.expand(quadratic.subs(LAM, root)) == 0, f"root {root}")
    poly = sp.Poly(quadratic, LAM)
    a, b, c = poly.all_coeffs()
    ensure(sp.expand(b**2 - 4 * a * c - 16 * (zc**2 - r**2)) == 0, "discriminant 16 (z_c^2 - r^2)")
    ensure(sp.simplify(c / a - r**2 / 4) == 0 and sp.simplify(-b / a - zc) == 0, "product r^2/4, sum z_c")
    return agrees(
        "the non-zero roots are non-real iff z_c^2 < r^2 (the sphere cuts z = 0); otherwise their product "
        "is r^2/4 > 0 and their sum z_c: both positive iff z_c >= r (S in R+ = {z >= 0}), both negative "
        "iff z_c <= -r (S in R-)"
    )


@proof.check(
    "general ellipsoid and plane: c0 = c1 = 0, c4 = -det A, c3 = det A (n.m - d), c2 = -n^T adj(A) n / 4",
    method=Method.IDENTITY,
)
def general_coefficients() -> Finding:
    c, A, m, n, d = general_plane_pencil()
    detA = A.det()
    ensure(c[0] == 0 and c[1] == 0, "0 is a double root")
    ensure(sp.expand(c[4] + detA) == 0, "c4 = -det A")
    ensure(sp.expand(c[3] - detA * ((n.T * m)[0, 0] - d)) == 0, "c3 = det A (n.m - d)")
    ensure(sp.expand(c[2] + (n.T * A.adjugate() * n)[0, 0] / 4) == 0, "c2 = -n^T adj(A) n / 4")
    return agrees(
        "P = l^2 (c4 l^2 + c3 l + c2) with c4 = -det A < 0 and c2 = -n^T adj(A) n / 4 < 0 for A > 0"
    )


@proof.check(
    "transversal contact iff the non-zero roots are non-real, for any ellipsoid", method=Method.IDENTITY
)
def general_transversal() -> Finding:
    c, A, m, n, d = general_plane_pencil()
    detA = A.det()
    Ainv_nn = (n.T * A.adjugate() * n)[0, 0] / detA
    h = (n.T * m)[0, 0] - d
    ensure(sp.simplify(c[3] ** 2 - 4 * c[4] * c[2] - detA**2 * (h**2 - Ainv_nn)) == 0, "c3^2 - 4 c4 c2")
    # The maximiser of n.x on the ellipsoid and the value there.
    t = sp.Symbol("t", positive=True)  # t = sqrt(n^T A^-1 n)
    x_star = m + A.adjugate() * n / detA / t
    on_ellipsoid = ((x_star - m).T * A * (x_star - m))[0, 0] - 1
    ensure(sp.simplify(on_ellipsoid.subs(t, sp.sqrt(Ainv_nn))) == 0, "the maximiser lies on the ellipsoid")
    value = (n.T * x_star)[0, 0] - d
    ensure(
        sp.simplify(value - h - Ainv_nn / t) == 0,
        "n.x* - d = n.m - d + (n^T A^-1 n) / t, t = sqrt(n^T A^-1 n)",
    )
    return agrees(
        "c3^2 - 4 c4 c2 = det(A)^2 ((n.m - d)^2 - n^T A^-1 n), and n.x ranges over "
        "n.m +- sqrt(n^T A^-1 n) on the ellipsoid: the plane cuts it iff the non-zero roots are non-real; "
        "otherwise their sum -c3/c4 has the sign of n.m - d (R+ or R-) and their product c2/c4 > 0"
    )
