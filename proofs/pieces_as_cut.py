"""Pieces as cut: where the curve of a transversal contact meets a cutting plane.

Not a result of the paper: the package's geometric reading of Section 5.2, where a piece
is its quadric ``Q`` cut by a plane ``Π`` (kept closed half-space ``H``), and the
ellipsoid ``E`` is in contact with the piece iff the curve ``C = E ∩ Q`` of a transversal
contact has a point in ``H`` (:mod:`quadric_contact.theory.sections`,
:mod:`quadric_contact.scenes.cut_pieces`).  Algorithm 1's reading (the paper's, kept as
``reading = "paper"``) counts the whole quadric as soon as ``E`` reaches the piece's zone.

Claim.

1. Restricted to ``Π`` through a rational affine frame, ``E`` and ``Q`` are conics
   ``E_Π``, ``Q_Π`` (3x3 matrices ``M^T E M``) and ``C ∩ Π = E_Π ∩ Q_Π``; ``E_Π`` has a
   definite quadratic part, hence no real point at infinity.
2. ``C`` meets ``Π`` iff no member of ``λ E_Π + Q_Π`` is definite (Finsler-Calabi for
   ternary forms), decided by the inertia at one rational ``λ`` per gap between the real
   roots of the cubic ``det(λ E_Π + Q_Π)``.
3. Conics tangent at a point make the cubic's discriminant vanish; in particular, where
   ``C`` touches ``Π`` (the tangent line of ``C`` lies in ``Π``) the section conics are
   tangent.  For a moving ellipsoid the section's discriminant ``G(t)`` is therefore zero
   at every time ``C(t)`` starts or stops meeting ``Π``; the double root of a cubic with
   one, ``(9 c3 c0 - c2 c1) / (2 (c2^2 - 3 c3 c1))``, gives the member whose rank tells a
   single (real) point of tangency from two.
4. The levels ``π = s`` sweep ``C``: at a critical point of ``π`` on a smooth ``C`` the
   level plane contains the tangent line, so the level conics are tangent and the
   discriminant in ``s`` vanishes; ``π(C)`` is a finite union of closed intervals with such
   ends, and sampling one level between consecutive critical levels on the kept side
   decides whether ``C`` meets ``H``.
5. Over time the answer changes only at real roots of ``G``, of the zone's discriminant
   ``c3^2 - 4 c4 c2`` (Corollary 15) and of the pencil's ``Δ4`` (and of the polynomials
   that decide the whole-quadric contact): between them ``C(t)`` is smooth and moves by an
   isotopy (when ``Δ4 ≢ 0``; when ``Q`` is a plane or homothetic to ``E``, ``C`` is one
   plane section of ``E``), never meeting ``Π`` where it did not (the number of real
   points of ``E_Π ∩ Q_Π`` is constant where the four complex ones stay distinct), so the
   side(s) its components lie on do not change.

What is checked and how.  Symbolic identities: the frame restricts a generic quadric
(``section_restriction``), the pencil coefficients and the cubic discriminant of the
package are sympy's (``pencil_coefficients``, ``cubic_discriminant``), the double-root
formula (``double_root``), generic conics tangent at a point have a vanishing
discriminant (``tangent_conics``), and a level plane containing the tangent line of
``C`` cuts tangent conics (``critical_levels``).  Exact computation: the scout of the
scene ``bees_with_interests`` meets the crown as cut at a root of a closed form written
without pencils (the scout and the crown are homothetic, so ``C`` lies in their radical
plane), and the paper's reading starts at the scout's tangency with ``z = 6``
(``scout_and_crown``).  Evidence: the conic decision of step 2 against dense sampling of
the ellipse (``conics_sampled``).

Not proven here: Calabi's theorem for ternary forms, and that a pencil of conics whose
cubic has distinct roots has four distinct base points (Segre's classification of
pencils of conics): standard results, not re-derived; the evidence search supports the
first.
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import sympy as sp

from quadric_contact import Quadric
from quadric_contact.exact.algebraic import sign_at
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure
from quadric_contact.theory.sections import (
    conic_pencil_coefficients,
    conics_meet,
    cubic_discriminant,
    plane_form,
    section_frame,
    section_matrix,
)

proof = Proof(
    "Pieces as cut",
    "E crosses Q ∩ H iff the curve E ∩ Q meets H; the events where it meets the plane are roots of "
    "the section's discriminant",
    not_proven=(
        "Calabi's theorem for ternary quadratic forms (no common real zero implies a definite "
        "combination) and Segre's classification of pencils of conics (distinct roots of det(l A + B) "
        "iff four distinct base points), standard results not re-derived here"
    ),
    relies_on=("Corollary 15",),
)

LAM = sp.Symbol("lambda")


def _generic(name: str, n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"{name}{min(i, j)}{max(i, j)}", real=True))


@proof.check(
    "the rational frame of a plane restricts a generic quadric to the conic of its points",
    method=Method.IDENTITY,
)
def section_restriction() -> Finding:
    Q = _generic("q", 4)
    upper = [Q[i, j] for i in range(4) for j in range(i, 4)]
    u, v = sp.symbols("u v", real=True)
    planes = ["x + 2*y - 3*z + 5", "2*x - y + 7", "3*x - 4"]  # the frame's three branches
    for text in planes:
        plane = Quadric.from_equation(text)
        S = sp.Matrix(section_matrix(upper, plane, one=sp.Integer(1)))
        dirs, origin, step = section_frame(plane)
        n, d = plane_form(plane)
        point = [u * dirs[0][k] + v * dirs[1][k] + origin[k] for k in range(4)]
        on_plane = sp.expand(sum(n[k] * point[k] for k in range(3)) + d) == 0
        ensure(on_plane, f"{text}: the frame is in the plane")
        ensure(
            sum(n[k] * step[k] for k in range(3)) == 1 and step[3] == 0,
            f"{text}: the step moves the plane's form by one",
        )
        X = sp.Matrix(point)
        conic = (sp.Matrix([u, v, 1]).T * S * sp.Matrix([u, v, 1]))[0, 0]
        ensure(sp.expand((X.T * Q * X)[0, 0] - conic) == 0, f"{text}: M^T Q M is the restriction")
    return agrees(
        "for every quadric, M^T Q M with the frame M = [d1, d2, origin] is the conic of Q on the plane, "
        "in each of the frame's three branches"
    )


@proof.check(
    "det(l A + B) of two 3x3 symmetric matrices: the package's coefficients are sympy's",
    method=Method.IDENTITY,
)
def pencil_coefficients() -> Finding:
    A, B = _generic("a", 3), _generic("b", 3)
    c = conic_pencil_coefficients(A.tolist(), B.tolist())
    poly = sp.Poly((LAM * A + B).det(method="berkowitz"), LAM)
    ensure(all(sp.expand(c[k] - poly.coeff_monomial(LAM**k)) == 0 for k in range(4)), "c0..c3")
    return agrees("c3 = det A, c0 = det B, and the mixed determinants are c2 and c1")


@proof.check("the cubic discriminant of the package is sympy's", method=Method.IDENTITY)
def cubic_discriminant_is_sympys() -> Finding:
    k = sp.symbols("k0:4", real=True)
    generic = sp.Poly(sum(k[i] * LAM**i for i in range(4)), LAM)
    ensure(sp.expand(cubic_discriminant(*k) - sp.discriminant(generic)) == 0, "discriminant")
    return agrees("18 c3 c2 c1 c0 - 4 c2^3 c0 + c2^2 c1^2 - 4 c3 c1^3 - 27 c3^2 c0^2 is the discriminant")


@proof.check(
    "a cubic a (l - p)^2 (l - q): 9 a d - b c = 2 a^2 p (p - q)^2 and b^2 - 3 a c = a^2 (p - q)^2",
    method=Method.IDENTITY,
)
def double_root() -> Finding:
    a, p, q = sp.symbols("a p q", real=True)
    cubic = sp.Poly(sp.expand(a * (LAM - p) ** 2 * (LAM - q)), LAM)
    c0, c1, c2, c3 = (cubic.coeff_monomial(LAM**k) for k in range(4))
    ensure(sp.expand(9 * c3 * c0 - c2 * c1 - 2 * a**2 * p * (p - q) ** 2) == 0, "numerator")
    ensure(sp.expand(c2**2 - 3 * c3 * c1 - a**2 * (p - q) ** 2) == 0, "denominator")
    return agrees(
        "with a double root p and a simple root q != p, p = (9 c3 c0 - c2 c1) / (2 (c2^2 - 3 c3 c1)); "
        "c2^2 = 3 c3 c1 is a triple root"
    )


@proof.check(
    "two generic conics tangent at a point: the discriminant of det(l A + B) is identically zero",
    method=Method.IDENTITY,
)
def tangent_conics() -> Finding:
    # both through the origin (entry 22 zero) with the tangent line y = 0 there (entry 02 zero)
    A = _generic("a", 3).subs({sp.Symbol("a22", real=True): 0, sp.Symbol("a02", real=True): 0})
    B = _generic("b", 3).subs({sp.Symbol("b22", real=True): 0, sp.Symbol("b02", real=True): 0})
    c = conic_pencil_coefficients(A.tolist(), B.tolist())
    ensure(sp.expand(cubic_discriminant(*c)) == 0, "discriminant of tangent conics")
    return agrees("conics tangent at a common point give a multiple root of det(l A + B): G = 0 there")


@proof.check(
    "a level plane that contains the tangent line of E ∩ Q at a point cuts conics tangent there",
    method=Method.IDENTITY,
)
def critical_levels() -> Finding:
    # generic quadrics through the origin; the tangent line of E ∩ Q at 0 is grad E x grad Q,
    # horizontal iff (e1, e2) and (q1, q2) are parallel: q1 = k e1, q2 = k e2
    E, Q = _generic("e", 4), _generic("q", 4)
    k = sp.Symbol("k", real=True)
    zero = {sp.Symbol("e33", real=True): 0, sp.Symbol("q33", real=True): 0}
    E, Q = E.subs(zero), Q.subs(zero)
    Q = Q.subs({sp.Symbol("q03", real=True): k * E[0, 3], sp.Symbol("q13", real=True): k * E[1, 3]})
    level = Quadric.from_equation("z")
    A = section_matrix([E[i, j] for i in range(4) for j in range(i, 4)], level, one=sp.Integer(1))
    B = section_matrix([Q[i, j] for i in range(4) for j in range(i, 4)], level, one=sp.Integer(1))
    c = conic_pencil_coefficients(A, B)
    ensure(sp.expand(cubic_discriminant(*c)) == 0, "tangent level conics")
    return agrees(
        "at a critical point of the plane's form on a smooth E ∩ Q the level conics are tangent: the "
        "critical levels are roots of the discriminant in s"
    )


@proof.check(
    "the scout of bees_with_interests meets the crown as cut at a root of a closed form; "
    "as a whole quadric when its top reaches z = 6",
    method=Method.COMPUTATION,
)
def scout_and_crown() -> Finding:
    from quadric_contact.scenes.scene_toml import builtin_scene
    from quadric_contact.scenes.simulate import simulate

    t, x, y, z = sp.symbols("t x y z", real=True)
    s = (t - 2) / 2  # the second keyframe segment: (5/4, 1/2, 5) at t = 2 to (5/2, 0, 15/2) at t = 4
    cx = sp.Rational(5, 4) + s * sp.Rational(5, 4)
    cy, cz = sp.Rational(1, 2) - s / 2, 5 + s * sp.Rational(5, 2)
    scout = (x - cx) ** 2 + (y - cy) ** 2 + 3 * (z - cz) ** 2 - sp.Rational(1, 10)
    crown = x**2 + y**2 + 3 * (z - sp.Rational(836291, 100000)) ** 2 - 20
    radical = sp.expand(scout - crown).subs(z, 6)  # homothetic: E - Q is a plane, met by z = 6 in a line
    a, b, e = radical.coeff(x), radical.coeff(y), -radical.subs({x: 0, y: 0})
    radius2 = sp.Rational(1, 10) - 3 * (6 - cz) ** 2  # the scout's circle at z = 6
    h = sp.Poly(sp.expand((a * cx + b * cy - e) ** 2 - (a**2 + b**2) * radius2), t)
    top = sp.Poly(sp.expand((6 - cz) ** 2 - sp.Rational(1, 30)), t)

    def coeffs(p: sp.Poly) -> list[Fraction]:
        return [Fraction(int(c.p), int(c.q)) for c in reversed(p.all_coeffs())]

    found = {}
    for reading in ("geometry", "paper"):
        pair = simulate(builtin_scene("bees_with_interests"), reading=reading).pair("scout", "tree")
        for ev in pair.events:
            before = dict((ev.before or ev.at).pieces).get("crown")
            after = dict((ev.after or ev.at).pieces).get("crown")
            if (before is None or not before.contact) and after is not None and after.contact:
                found[reading] = ev.time
                break
    geo, paper = found["geometry"], found["paper"]
    ensure(sign_at(coeffs(h), geo) == 0, "the geometric start is a root of the closed form")
    ensure(not geo.is_rational and geo.decimal(10) == "2.6623162741", f"geometric start {geo.decimal(10)}")
    ensure(sign_at(coeffs(top), paper) == 0, "the paper's start is where the scout's top reaches z = 6")
    ensure(paper.decimal(10) == "2.6539406513", f"paper's start {paper.decimal(10)}")
    return agrees(
        f"the crown as cut from t = {geo.decimal(10)} (root of degree {geo.degree} of the closed form), "
        f"the whole crown from t = {paper.decimal(10)}"
    )


@proof.search(
    "conics share a real point iff no member of l A + B is definite (A an ellipse)",
    examples=150,
    large=1500,
    unit="random rational pairs",
    detail="against 20001 points of the ellipse",
    requires=(),
)
def conics_sampled(n: int) -> Finding:
    rng = random.Random(20261127)
    theta = np.linspace(0, 2 * np.pi, 20001)
    z0 = Quadric.from_equation("z")
    compared = 0
    for _ in range(n):
        E = Quadric.ellipsoid(
            Fraction(rng.randint(2, 12), rng.randint(2, 6)),
            Fraction(rng.randint(2, 12), rng.randint(2, 6)),
            1,
            center=(Fraction(rng.randint(-8, 8), 4), Fraction(rng.randint(-8, 8), 4), 0),
        )
        Q = Quadric._from_upper(tuple(Fraction(rng.randint(-6, 6), rng.randint(1, 3)) for _ in range(10)))
        A, B = section_matrix(E.upper, z0), section_matrix(Q.upper, z0)
        Af = np.array([[float(v) for v in row] for row in A])
        Bf = np.array([[float(v) for v in row] for row in B])
        c = -np.linalg.solve(Af[:2, :2], Af[:2, 2])
        k = float(c @ Af[:2, :2] @ c) - Af[2, 2]
        w, V = np.linalg.eigh(Af[:2, :2])
        pts = c + (np.stack([np.cos(theta), np.sin(theta)], 1) * np.sqrt(k / w)) @ V.T
        X = np.hstack([pts, np.ones((len(theta), 1))])
        vals = np.einsum("ni,ij,nj->n", X, Bf, X)
        tol = 1e-9 * float(np.abs(Bf).max())
        if vals.min() < -tol and vals.max() > tol:
            expected = True
        elif vals.min() > tol or vals.max() < -tol:
            expected = False
        else:
            continue
        ensure(conics_meet(A, B) == expected, f"conics {A} and {B}")
        compared += 1
    ensure(compared >= n // 2, f"only {compared} decidable pairs")
    return agrees(f"{compared} pairs: the definite-member test and the sampled sign change agree")
