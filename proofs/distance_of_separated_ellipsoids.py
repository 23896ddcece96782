"""Distance of separated ellipsoids: one root of a four-equation system, isolated by the Krawczyk
operator, is the distance, and its support points are the witnesses.

Not a result of the paper: the route by which :func:`quadric_contact.distance` (``certified``
mode) answers one pair of ellipsoids whose solids are apart
(:func:`quadric_contact.modes.distance.certified.apart_ellipsoids`).  The solid of an
ellipsoid is ``(x - c)^T A (x - c) <= r`` with ``A`` positive definite and ``r > 0``;
``B = A^-1``, ``s(u) = sqrt(u^T B u)``, ``h(u) = u . c + sqrt(r) s(u)`` and
``phi(u) = h_E(u) + h_K(-u)``.

Claim.

1. Support point.  ``x*(u) = c + sqrt(r) B u / s(u)`` lies on the surface, the outward normal
   there is a positive multiple of ``u``, and ``u . x*(u) = h(u)``; so ``h`` is the support
   function of the solid and ``x*(u)`` its support point (unique: the solid is strictly convex).
2. Gradient and homogeneity.  ``grad h(u) = x*(u)``, hence ``grad phi(u) = x*_E(u) - y*_K(-u)``
   with ``y*_K(-u) = c_K - sqrt(r_K) B_K u / s_K(u)``, and ``u . grad phi(u) = phi(u)``.
3. The system.  The package's ``F(u, lambda) = (grad phi(u) + lambda u, (u . u - 1) / 2)`` and
   its Jacobian are those of ``phi`` (re-derived symbolically from ``phi``, not copied).
4. The distance.  If ``(u, lambda)`` solves ``F = 0`` with ``lambda > 0``, then the solids are
   apart, their distance is ``lambda``, the nearest points are ``x*_E(u)`` and ``y*_K(-u)``, and
   the outward unit normal of ``K`` at ``y*_K(-u)`` is ``-u``.  So a box in which the Krawczyk
   operator proves one root, with ``lambda > 0`` throughout, encloses the distance and the
   witnesses: no other critical point needs isolating.

The argument.  1 and 2 are identities (checked below).  For 4: ``phi`` is the support function of
the Minkowski difference ``D = E + (-K)``, which is convex, so ``phi`` is convex; when ``0`` is
not in ``D``, ``dist(E, K) = dist(0, D) = -min over |u| <= 1 of phi(u)`` (a separating plane of
``0`` and ``D``).  ``F = 0`` with ``lambda > 0`` are the Karush-Kuhn-Tucker conditions of that
convex program (the constraint ``|u|^2 <= 1`` active), which are sufficient: ``u`` is a minimiser,
and by 2, ``phi(u) = u . grad phi(u) = -lambda |u|^2 = -lambda < 0``: ``0`` is outside ``D`` and
the distance is ``lambda``.  ``grad phi(u) = x*_E(u) - y*_K(-u) = -lambda u`` puts the two support
points at distance ``lambda``, so they are the nearest points (unique, the solids being strictly
convex), and ``(x* - y*) / lambda = -u`` is the outward normal of ``K`` at ``y*`` (1, for ``K`` and
the direction ``-u``).

What is checked and how.  1, 2 and 3 are symbolic identities in generic symbols (a symmetric
``B``, ``c``, ``sqrt r``), 3 by evaluating the package's own system on the symbols; 4's identity
``phi(u) + lambda |u|^2 = u . F`` symbolically.  Cross-check (full profile): on random binary64
pairs read as exact rationals (general, elongated to 1:20, within about ``1e-6``, far apart), the
enclosure holds the distance found by brute force (a grid of directions, then Newton's method
at 40 digits on the exact matrices), and the witnesses lie on the surfaces, ``normal`` unit,
``point_E = point_Q + distance * normal``.

Not proven here: the support-function form of the distance of convex solids, the sufficiency of
the Karush-Kuhn-Tucker conditions for convex programs, and the Krawczyk test (a box holding its
Krawczyk image in its interior holds exactly one root), standard facts not re-derived.
"""

from __future__ import annotations

from typing import Any

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure
from quadric_contact.testing.samples import ellipsoid_matrix

from ._support_functions import least_support

proof = Proof(
    "Distance of separated ellipsoids",
    "one root of grad phi(u) + lambda u = 0, |u| = 1 with lambda > 0, isolated by the Krawczyk "
    "operator, is the distance of two separated ellipsoids, and its support points the witnesses",
    not_proven=(
        "the support-function form of the distance of convex solids, the sufficiency of the KKT "
        "conditions for convex programs and the Krawczyk test, standard facts not re-derived"
    ),
)


def _symbols(name: str) -> tuple[Any, Any, Any]:
    import sympy as sp

    c = sp.symbols(f"c{name}1:4", real=True)
    B = [[sp.Integer(0)] * 3 for _ in range(3)]
    for i in range(3):
        for j in range(i, 3):
            B[i][j] = B[j][i] = sp.Symbol(f"b{name}{i}{j}", real=True)
    return c, B, sp.Symbol(f"rho{name}", positive=True)


def _support(c: Any, B: Any, rho: Any, u: Any) -> Any:
    import sympy as sp

    return (sp.Matrix(c).T * u)[0] + rho * sp.sqrt((u.T * sp.Matrix(B) * u)[0])


def _pair() -> tuple[Any, Any, Any, list[Any], Any]:
    """Generic symbols of two ellipsoids: ``u`` (a tuple and a column), ``lambda``, the parts
    ``(c, B, sqrt r, sign)`` of ``E`` and ``K``, and ``phi(u) = h_E(u) + h_K(-u)``."""
    import sympy as sp

    us = sp.symbols("u1:4", real=True)
    u = sp.Matrix(us)
    (cE, BE, rE), (cK, BK, rK) = _symbols("E"), _symbols("K")
    phi = _support(cE, BE, rE, u) + _support(cK, BK, rK, -u)
    return us, u, sp.Symbol("lambda", real=True), [(cE, BE, rE, 1), (cK, BK, rK, -1)], phi


@proof.check(
    "support point: x*(u) = c + sqrt(r) B u / s(u) is on the surface, the normal A (x* - c) is "
    "sqrt(r) u / s(u), and u . x*(u) = h(u) (generic symmetric B = A^-1, c, r)",
    method=Method.IDENTITY,
)
def support_point() -> Finding:
    import sympy as sp

    c, B, rho = _symbols("")
    u = sp.Matrix(sp.symbols("u1:4", real=True))
    Bm = sp.Matrix(B)
    s = sp.sqrt((u.T * Bm * u)[0])
    x = sp.Matrix(c) + rho * Bm * u / s
    d = x - sp.Matrix(c)
    # (x - c)^T A (x - c) with A = B^-1: B^-1 d = rho u / s exactly, so no inverse is formed
    Ad = rho * u / s
    ensure(sp.simplify(Bm * Ad - d) == sp.zeros(3, 1), "A (x* - c) = sqrt(r) u / s")
    ensure(sp.simplify((d.T * Ad)[0] - rho**2) == 0, "x* on the surface")
    ensure(sp.simplify((u.T * x)[0] - _support(c, B, rho, u)) == 0, "u . x* = h(u)")
    return agrees("x* on the surface, outward normal along u with factor sqrt(r) / s(u) > 0, u . x* = h(u)")


@proof.check(
    "gradient and homogeneity: grad h(u) = x*(u), and u . grad phi(u) = phi(u) for phi(u) = h_E(u) + h_K(-u)",
    method=Method.IDENTITY,
)
def gradient_and_homogeneity() -> Finding:
    import sympy as sp

    u = sp.Matrix(sp.symbols("u1:4", real=True))
    (cE, BE, rE), (cK, BK, rK) = _symbols("E"), _symbols("K")
    h = _support(cE, BE, rE, u)
    xstar = sp.Matrix(cE) + rE * sp.Matrix(BE) * u / sp.sqrt((u.T * sp.Matrix(BE) * u)[0])
    grad = sp.Matrix([sp.diff(h, ui) for ui in u])
    ensure(sp.simplify(grad - xstar) == sp.zeros(3, 1), "grad h = x*")
    phi = h + _support(cK, BK, rK, -u)
    euler = sum(u[i] * sp.diff(phi, u[i]) for i in range(3))
    ensure(sp.simplify(euler - phi) == 0, "u . grad phi = phi")
    return agrees("grad h(u) = x*(u); u . grad phi(u) = phi(u)")


@proof.check(
    "the system: the package's F(u, lambda) and its Jacobian, evaluated on generic symbols, are "
    "grad phi(u) + lambda u, (u . u - 1) / 2 and sympy's Jacobian of it",
    method=Method.IDENTITY,
)
def system_re_derived() -> Finding:
    import sympy as sp

    from quadric_contact.modes.distance.certified import _support_system

    us, u, lam, parts, phi = _pair()
    F, J = _support_system(parts, [*us, lam], sp.Integer(1), sp.sqrt)
    Fs = [sp.diff(phi, us[i]) + lam * us[i] for i in range(3)] + [((u.T * u)[0] - 1) / 2]
    Js = sp.Matrix(Fs).jacobian([*us, lam])
    for i in range(4):
        ensure(sp.simplify(F[i] - Fs[i]) == 0, f"F[{i}] differs from sympy's")
        for j in range(4):
            ensure(sp.simplify(J[i][j] - Js[i, j]) == 0, f"J[{i}][{j}] differs from sympy's")
    return agrees("the 4 equations and the 16 entries of the Jacobian equal sympy's derivation from phi")


@proof.check(
    "the distance: phi(u) + lambda |u|^2 = u . (grad phi(u) + lambda u), so at a root "
    "phi(u) = -lambda on |u| = 1",
    method=Method.IDENTITY,
)
def value_at_a_root() -> Finding:
    import sympy as sp

    us, u, lam, _, phi = _pair()
    first = [sp.diff(phi, us[i]) + lam * us[i] for i in range(3)]
    ensure(sp.simplify(phi + lam * (u.T * u)[0] - sum(us[i] * first[i] for i in range(3))) == 0, "identity")
    return agrees(
        "phi(u) + lambda |u|^2 = u . (grad phi + lambda u): phi(u) = -lambda at a root with |u| = 1"
    )


@proof.check(
    "the enclosures hold the brute-force distance, and the witnesses lie on the surfaces along the "
    "normal (random binary64 pairs read as exact rationals: general, elongated, close, far)",
    method=Method.CROSS_CHECK,
    full=True,
    size="24 random pairs",
)
def enclosures_hold() -> Finding:
    import flint
    import mpmath
    import numpy as np

    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.distance.certified import apart_ellipsoids
    from quadric_contact.testing.samples import random_rotations
    from quadric_contact.theory.overlap import solid_of

    rng = np.random.default_rng(31)
    answered = 0
    for k in range(24):
        R1, R2 = random_rotations(2, rng)
        axes1, axes2 = rng.uniform(0.3, 1.5, (2, 3))
        if k % 4 == 1:
            axes1 = np.array([1.0, 0.2, 0.05]) * rng.uniform(0.8, 1.2, 3)
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        gap = {0: 1.0, 1: 0.5, 2: 1e-6, 3: 30.0}[k % 4]
        # K along ``direction`` from E, its centre past the sum of the largest axes and the gap
        centre = direction * (max(axes1) + max(axes2) + gap)
        E = ellipsoid_matrix(axes1, R1, np.zeros(3))
        K = ellipsoid_matrix(axes2, R2, centre)
        e, q = Quadric.from_matrix(E).as_ellipsoid(), solid_of(Quadric.from_matrix(K))
        r = apart_ellipsoids(e, q, 30)
        if r is None:
            continue
        answered += 1
        lo, hi = r.bounds
        with mpmath.workdps(80):  # (negated at the working precision: mpmath rounds every operation)
            value = -least_support(E, K)
            inside = (
                mpmath.mpf(lo.numerator) / lo.denominator
                <= value
                <= mpmath.mpf(hi.numerator) / hi.denominator
            )
        ensure(inside, f"pair {k}: {value} not in [{float(lo)}, {float(hi)}]")
        zero = flint.arb(0)
        for point, quad in ((r.point_E, e), (r.point_Q, q)):
            X = [*point, flint.arb(1)]
            form = sum(
                (flint.arb(flint.fmpq(quad[i, j].numerator, quad[i, j].denominator)) * X[i] * X[j])
                for i in range(4)
                for j in range(4)
            )
            ensure(form.contains(zero), f"pair {k}: a witness off its surface ({form})")
        n2 = sum(x * x for x in r.normal)
        ensure(n2.contains(flint.arb(1)), f"pair {k}: the normal is not unit")
        for i in range(3):
            ensure(
                (r.point_Q[i] + r.distance * r.normal[i] - r.point_E[i]).contains(zero),
                "point_E = point_Q + d n",
            )
    ensure(answered >= 20, f"only {answered} of 24 answered")
    return agrees(f"{answered} of 24 pairs answered; each enclosure holds the 40-digit brute-force distance")
