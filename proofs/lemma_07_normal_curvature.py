"""Lemma 7: at a tangent point on an intersection curve, a normal curvature coincides.

Claim.  If ``E`` and ``Q`` meet in a curve ``C`` and are tangent at a point
``p`` of ``C``, then the normal curvatures of the two surfaces at ``p`` in the
direction of ``C`` are equal.

What is checked and how.  Symbolic identity: two quadric surfaces through the
origin with the common tangent plane ``z = 0``, ``F = 2 f z + F2(x, y) + ...``
and ``G = 2 g z + G2(x, y) + ...`` (generic coefficients), have local graphs
``z = -F2/(2f) + O(3)`` and ``z = -G2/(2g) + O(3)``; the lowest-order part
of ``F`` restricted to ``G = 0`` is ``F2 - (f/g) G2``, so the tangent
directions of the intersection at the origin are the zeros of
``F2/f - G2/g``, which is ``-(kappa_F - kappa_G)`` for the normal curvatures
``kappa = -v^T H v / |grad|`` with respect to the common normal.  Exact
constructions (Fig. 4): the sphere ``x^2 + y^2 + (z - 1)^2 = 1`` with the
saddle ``z = x^2 - y^2`` (a node: tangent directions ``y = +-x/sqrt 3``) and
with the cylinder ``y^2 + (z - 1/2)^2 = 1/4`` (tangent directions
``y = +-x``); in each the intersection has real branches through ``p`` and
the normal curvatures in their directions coincide (``kappa = 1``).
"""

from __future__ import annotations

import sympy as sp

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure

proof = Proof("Lemma 7", "a common normal curvature at a tangent point of an intersection curve")

x, y, z, t = sp.symbols("x y z t", real=True)


def second_order(F: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """(f, F2): F = 2 f z + F2(x, y) + (terms with z of order >= 2 or z times x, y)."""
    poly = sp.Poly(sp.expand(F), x, y, z)
    f = poly.coeff_monomial(z) / 2
    F2 = sum(poly.coeff_monomial(m) * m for m in (x**2, x * y, y**2))
    ensure(
        poly.coeff_monomial(1) == 0 and poly.coeff_monomial(x) == 0 and poly.coeff_monomial(y) == 0,
        "0 is on F, tangent plane z = 0",
    )
    return f, F2


def normal_curvature(F: sp.Expr, theta: sp.Expr) -> sp.Expr:
    """Normal curvature of F = 0 at the origin in the direction (cos t, sin t, 0), w.r.t. the normal +z."""
    f, F2 = second_order(F)
    v = {x: sp.cos(theta), y: sp.sin(theta)}
    # Graph z = -F2/(2f) + ...: the normal curvature w.r.t. +z is the second derivative along v.
    return sp.simplify(-2 * F2.subs(v) / (2 * f))


@proof.check(
    "the tangent cone of the intersection is where the normal curvatures agree", method=Method.IDENTITY
)
def tangent_cone_identity() -> Finding:
    fc = sp.symbols("f1:11")
    gc = sp.symbols("g1:11")
    mons = [z, x**2, x * y, y**2, z**2, x * z, y * z]
    F = 2 * fc[0] * z + sum(c * m for c, m in zip(fc[1:], mons[1:], strict=False))
    G = 2 * gc[0] * z + sum(c * m for c, m in zip(gc[1:], mons[1:], strict=False))
    # On G = 0, z = zeta(x, y) = -G2/(2 g) + O(3); substitute the series to second order in F.
    s = sp.Symbol("s")  # scale: x -> s x, y -> s y
    zeta = sp.Symbol("zeta")
    G_s = sp.expand(G.subs({x: s * x, y: s * y, z: zeta}))
    # zeta = a2 s^2 + O(s^3) solves G_s = 0 to order 2.
    a2 = sp.Symbol("a2")
    eq2 = sp.expand(G_s.subs(zeta, a2 * s**2)).coeff(s, 2)
    a2v = sp.solve(eq2, a2)[0]
    F_on_G = sp.expand(F.subs({x: s * x, y: s * y, z: a2v * s**2})).coeff(s, 2)
    f, F2 = second_order(F)
    g, G2 = second_order(G)
    ensure(sp.simplify(F_on_G - (F2 - f / g * G2)) == 0, "lowest order of F on G = 0 is F2 - (f/g) G2")
    theta = sp.Symbol("theta", real=True)
    kF, kG = normal_curvature(F, theta), normal_curvature(G, theta)
    cone = (F2 / f - G2 / g).subs({x: sp.cos(theta), y: sp.sin(theta)})
    ensure(sp.simplify(cone + (kF - kG)) == 0, "F2/f - G2/g = -(kappa_F - kappa_G) on unit directions")
    return agrees(
        "for quadrics tangent at 0 (plane z = 0), F restricted to G = 0 starts with F2 - (f/g) G2 = "
        "-f (kappa_F - kappa_G)(v): the intersection's tangent directions at the tangent point are exactly "
        "those where the normal curvatures coincide"
    )


EXAMPLES = {
    "saddle z = x^2 - y^2": (x**2 + y**2 + z**2 - 2 * z, x**2 - y**2 - z),
    "cylinder y^2 + (z - 1/2)^2 = 1/4": (x**2 + y**2 + z**2 - 2 * z, y**2 + z**2 - z),
}


@proof.check(
    "Fig. 4 constructions: the sphere with a saddle and with a cylinder, tangent at 0",
    method=Method.CONSTRUCTION,
)
def constructions() -> Finding:
    found = []
    theta = sp.Symbol("theta", real=True)
    for name, (E, Q) in EXAMPLES.items():
        # The intersection's lowest-order part after eliminating z (both are graphs near 0).
        f, F2 = second_order(E)
        g, G2 = second_order(Q)
        cone = sp.factor(sp.expand(F2 / f - G2 / g))
        slopes = sp.solve(cone.subs(x, 1), y)
        ensure(len(slopes) == 2 and all(m.is_real for m in slopes), f"{name}: two real branches through 0")
        for m in slopes:
            angle = sp.atan(m)
            kE, kQ = normal_curvature(E, angle), normal_curvature(Q, angle)
            ensure(sp.simplify(kE - kQ) == 0, f"{name}: curvatures {kE}, {kQ}")
        ensure(sp.simplify(normal_curvature(E, theta) - 1) == 0, "the unit sphere has normal curvature 1")
        found.append(
            f"{name}: branches y = {', '.join(f'{sp.nsimplify(m)} x' for m in slopes)}, kappa = 1 on both"
        )
    return agrees("; ".join(found))
