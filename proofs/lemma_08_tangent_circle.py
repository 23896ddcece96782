"""Lemma 8 and Fig. 5: under smallness, tangency along a curve means a circle.

Claim.  Let ``E`` be small with respect to ``Q``.  If they meet in a curve
``C`` and are tangent at a point ``p``, then ``p`` lies on ``C``, ``C`` is a
circle and the surfaces are tangent along ``C``.  Two ellipsoids sharing a
tangent circle are never small unless they are the same sphere (Fig. 5(i));
a circular cylinder or a circular one-sheet hyperboloid around a sphere gives
admissible examples (Fig. 5(ii)).

What is checked and how.  Exact constructions (intersection and tangency
computed exactly, see ``_intersection``; smallness by the package's exact
:func:`~quadric_contact.theory.smallness.smallness`): the unit sphere in the circular
cylinder of radius 1 and in the circular hyperboloid ``x^2 + y^2 - z^2/4 = 1``
(both small, tangent along a curve, which lies in a plane: the pencil has a
member of rank 1, a double plane, and the plane section of the sphere is a
circle); the unit sphere in the spheroid ``x^2 + y^2 + z^2/4 = 1`` (tangent
along the equator, not small).  Exhaustive case analysis (Table 1 with the
enclosing alternative) for concentric spheroids with a common equator of
radius ``R`` and polar semi-axes ``e`` (for ``E``) and ``q`` (for ``Q``): small
only if ``e = q = R``.  The excluded case of a curve plus an isolated tangent
point (Remark 9's construction, not small): translating the ellipsoid by
1/100 turns the isolated point into a second curve, as the proof says.

Not proven here: the lemma itself, for every small pair (a statement about
all positions, argued in the paper with Lemma 7; tangency is a measure-zero
event that no random search meets, so no search is run).
"""

from __future__ import annotations

import itertools
from fractions import Fraction

import sympy as sp

from quadric_contact import Quadric, RigidMotion
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure
from quadric_contact.theory.smallness import smallness

from ._intersection import contact_type, intersection, segre, show_segre, tangent_points

proof = Proof(
    "Lemma 8",
    "tangency along a curve is tangency along a circle",
    covers=("Fig. 5",),
    not_proven="the general statement, for every small ellipsoid and quadric: the paper's argument (with "
    "Lemma 7), supported by the constructions of Fig. 5, the case analysis of concentric spheroids and the "
    "translated construction of Remark 9.",
)

Z_TO_X = RigidMotion.from_matrix([[0, 0, 1], [0, 1, 0], [-1, 0, 0]])
ADMISSIBLE = {
    "unit sphere in the cylinder y^2 + z^2 = 1": (
        Quadric.sphere(1),
        Quadric.elliptic_cylinder(1, 1).moved(Z_TO_X),
    ),
    "unit sphere in the hyperboloid y^2 + z^2 - x^2/4 = 1": (
        Quadric.sphere(1),
        Quadric.hyperboloid_one_sheet(1, 1, 2).moved(Z_TO_X),
    ),
}


def circle_of_tangency(E: Quadric, Q: Quadric) -> str:
    kind = contact_type(E, Q)
    ensure(kind == "curve of tangency", f"contact {kind}")
    _, rank_one = tangent_points(E, Q)
    ensure(len(rank_one) == 1, "one member of rank 1: a double plane")
    (curve,) = [c for c in intersection(E, Q) if c.kind == "curve"]
    ensure(curve.lo == curve.hi, "the curve lies in a plane x = const")
    # The section of E by x = x0 is p y^2 + q z^2 = rhs: a circle iff p = q.
    M = E.matrix
    ensure(M[1][1] == M[2][2], "the plane section of E is a circle")
    return f"{show_segre(segre(E, Q))}, tangent along the circle in the plane x = {curve.lo}"


@proof.check(
    "Fig. 5(ii): a sphere in a circular cylinder and in a circular hyperboloid", method=Method.CONSTRUCTION
)
def admissible() -> Finding:
    found = []
    for name, (E, Q) in ADMISSIBLE.items():
        ensure(smallness(E, Q).small, f"{name}: small")
        found.append(f"{name}: small, {circle_of_tangency(E, Q)}")
    return agrees("; ".join(found))


@proof.check(
    "Fig. 5(i): a sphere in a spheroid sharing its equator is tangent along it, not small",
    method=Method.CONSTRUCTION,
)
def two_ellipsoids() -> Finding:
    E, Q = Quadric.sphere(1), Quadric.ellipsoid(2, 1, 1)  # the spheroid x^2/4 + y^2 + z^2 = 1, equator x = 0
    detail = circle_of_tangency(E, Q)
    ensure(not smallness(E, Q).small, "not small")
    return agrees(f"the unit sphere in x^2/4 + y^2 + z^2 = 1: {detail}; not small (Table 1)")


@proof.check(
    "two spheroids with a common tangent equator are small only if they are one sphere", method=Method.CASES
)
def coincident_spheres() -> Finding:
    u, v, w = sp.symbols("u v w", positive=True)
    checked = 0
    for se, sq in itertools.product("<=>", repeat=2):
        if se == sq == "=":
            continue
        # E = (R, R, e), Q = (R, R, q), parametrised by positive u, v, w so that every length is positive.
        R = v + (w if se == "<" else 0) + (u if sq == "<" else 0)
        e = {"<": R - w, "=": R, ">": R + w}[se]
        q = {"<": R - u, "=": R, ">": R + u}[sq]
        fails = []
        for (E_eq, E_pol, se_), (Q_eq, Q_pol, sq_) in (((R, e, se), (R, q, sq)), ((R, q, sq), (R, e, se))):
            alpha, gamma = (E_pol, E_eq) if se_ == ">" else (E_eq, E_pol)
            a, c = (Q_pol, Q_eq) if sq_ == ">" else (Q_eq, Q_pol)
            # Table 1 (ellipsoid): c >= alpha and a/c^2 <= gamma/alpha^2.
            fails.append(any(always_negative(k) for k in (c - alpha, gamma / alpha**2 - a / c**2)))
        ensure(all(fails), f"e {se} R, q {sq} R: one of them is small w.r.t. the other")
        checked += 1
    return agrees(
        f"in each of the {checked} cases (e <, =, > R and q <, =, > R, not both equal) a condition of "
        "Table 1 fails both for E w.r.t. Q and for Q w.r.t. E (Definition 1 is symmetric for two "
        "ellipsoids): only e = q = R, one sphere, is small"
    )


def always_negative(expr: sp.Expr) -> bool:
    """``expr < 0`` for all positive R, u, w: numerator and denominator have coefficients of one sign each."""
    num, den = sp.fraction(sp.together(sp.expand(expr)))
    if not expr.free_symbols:
        return bool(expr < 0)
    gens = sorted(expr.free_symbols, key=str)
    cn = sp.Poly(sp.expand(num), *gens).coeffs()
    cd = sp.Poly(sp.expand(den), *gens).coeffs() if den.free_symbols else [den]
    sn = {int(sp.sign(k)) for k in cn}
    sd = {int(sp.sign(k)) for k in cd}
    return len(sn) == 1 and len(sd) == 1 and sn.pop() * sd.pop() < 0


@proof.check(
    "a curve with an isolated tangent point becomes two curves after a small translation",
    method=Method.CONSTRUCTION,
)
def isolated_point_becomes_curve() -> Finding:
    E = Quadric.ellipsoid(3, 1, Fraction(1, 2))
    Q = Quadric.sphere(2, (-1, 0, 0))
    ensure(contact_type(E, Q) == "curve and isolated tangent point", "the excluded configuration")
    ensure(not smallness(E, Q).small, "not small")
    moved = E.translated((Fraction(-1, 100), 0, 0))
    ensure(contact_type(moved, Q) == "two curves", "after the translation: two curves")
    return agrees(
        "x^2/9 + y^2 + 4z^2 = 1 and the sphere of radius 2 centred at (-1, 0, 0) meet in a curve and the "
        "isolated tangent point (-3, 0, 0); moved by (-1/100, 0, 0) they meet in two curves, so the pair is "
        "not small"
    )
