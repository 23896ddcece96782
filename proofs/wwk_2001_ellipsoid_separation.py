"""Wang, Wang and Kim (2001): the roots of the pencil tell whether two ellipsoids overlap.

Not a result of the paper: the separation condition of W. Wang, J. Wang and M.-S. Kim
(An algebraic condition for the separation of two ellipsoids, CAGD 18 (2001) 531-539),
on which :func:`quadric_contact.theory.overlap` decides two ellipsoids.  It is proved here for
the pencil of the package, ``P(l) = det(l E + Q)``, with both matrices negative inside
(the paper's normalisation of ``E``; ``Q`` with the sign of its standard form).

Claim.  ``P`` has at least two negative roots (counted with multiplicity), hence at most
two positive ones, and

* two distinct positive roots  <=>  the closed solids are disjoint (``SEPARATE``);
* a double positive root        <=>  they meet and their interiors do not (``TOUCHING``);
* no positive root              <=>  the interiors meet (``OVERLAPPING``).

The sign is the one of WWK's ``det(l A + B)`` with ``A``, ``B`` negative inside; the
package's ``l E + Q`` is that pencil, so the roots that mark separation are positive.

The argument.  Write ``e(x) = (x, 1)^T E (x, 1)`` and ``q(x)`` likewise: convex quadratic
functions (the upper blocks ``A_E``, ``A_Q`` of ``E``, ``Q`` are positive definite), the
solids are ``{e <= 0}`` and ``{q <= 0}``, both with interior points.

1. For ``l >= 0`` the function ``l e + q`` is convex with the positive definite block
   ``A(l) = l A_E + A_Q``, and its minimum over ``R^3`` is
   ``m(l) = P(l) / d(l)`` with ``d(l) = det A(l) > 0`` (Schur complement: check
   ``schur_minimum``).  ``m`` is concave (a minimum of functions affine in ``l``),
   ``m(0) = min q < 0`` and ``m(l) / l -> min e < 0``; accordingly ``P(0) = det Q < 0`` and
   the leading coefficient ``det E < 0`` (check ``ellipsoid_determinant``).
2. Minimax (convex duality for the convex functions ``e``, ``q``; Sion's theorem on
   ``R^3 x [0, 1]``): ``min_x max(e, q) = max_{t in [0, 1]} min_x (t e + (1 - t) q)``, the
   maximum attained at an inner ``t`` since both ends are negative; with ``l = t / (1 - t)``
   the sign of ``min_x max(e, q)`` is the sign of ``sup_{l > 0} m(l)``, attained.  So the
   solids are disjoint iff ``m > 0`` somewhere on ``(0, inf)``, touch iff ``max m = 0``,
   and their interiors meet iff ``m < 0`` on ``(0, inf)``.
3. The zeros of ``m`` on ``(0, inf)`` are the positive roots of ``P``, with the same
   multiplicities (``d > 0``; check ``multiplicity_transfer``).  A concave ``m``, negative
   at both ends and not zero on an interval (``P`` is not the zero polynomial), is
   positive exactly between two distinct zeros, where it crosses with non-zero slope
   (simple roots); if its maximum is 0 it has one zero, where ``m' = 0`` (a root of
   multiplicity at least 2); if its maximum is negative it has none.
4. The inertia count of :mod:`._real_pencils` (``nu(l)``, the number of positive
   eigenvalues of ``l E + Q``): ``nu(0) = n_+(Q) = 3`` (``det Q < 0`` and a positive definite
   ``3 x 3`` block), ``nu(-inf) = n_+(-E) = 1``, and a root of multiplicity ``k`` changes
   ``nu`` by at most ``k``: the negative roots count at least ``3 - 1 = 2``, so the positive
   roots at most 2, and a double positive root is exactly double.

What is checked and how.  Steps 1 and 3 and the inertia facts of step 4 symbolically
(``schur_minimum``, ``ellipsoid_determinant``, ``multiplicity_transfer``); the family of
two spheres completely (``two_spheres``), with an exact construction of every case; the
root reading against the exact extremes of ``q`` on the surface of ``E``, which decide the
overlap without the pencil, on random exact pairs (evidence).

Not proven here: step 2, the minimax theorem (a standard result of convex analysis, not
re-derived), which the evidence search supports.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import sympy as sp

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure, search_settings

from ._plane_pencil import LAM, ellipsoid_matrix

proof = Proof(
    "Wang-Wang-Kim 2001",
    "two ellipsoids: two distinct positive roots iff apart, a double one iff touching",
    not_proven=(
        "step 2, the minimax equality min_x max(e, q) = max_t min_x (t e + (1 - t) q) for the two "
        "convex quadratic functions (Sion's theorem), is a standard theorem, not re-derived here"
    ),
)


def _symmetric3(name: str) -> sp.Matrix:
    return sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"{name}{min(i, j)}{max(i, j)}", real=True))


@proof.check(
    "min over x of (x, 1)^T M (x, 1) = det M / det A at x* = -A^-1 b, for a positive definite block A",
    method=Method.IDENTITY,
)
def schur_minimum() -> Finding:
    A = _symmetric3("a")
    b = sp.Matrix(sp.symbols("b0:3", real=True))
    c = sp.Symbol("c", real=True)
    M = sp.zeros(4, 4)
    M[:3, :3], M[:3, 3], M[3, :3], M[3, 3] = A, b, b.T, c
    x = sp.Matrix(sp.symbols("x0:3", real=True))
    detA = A.det(method="berkowitz")
    x_star = -A.adjugate() * b / detA
    f = sp.expand((x.T * A * x)[0, 0] + 2 * (b.T * x)[0, 0] + c)
    f_star = c + (b.T * x_star)[0, 0]
    # f(x) - f(x*) = (x - x*)^T A (x - x*): x* is the minimiser when A > 0
    square = ((x - x_star).T * A * (x - x_star))[0, 0]
    ensure(sp.simplify(f - f_star - square) == 0, "f(x) - f(x*) = (x - x*)^T A (x - x*)")
    ensure(sp.simplify(f_star - M.det(method="berkowitz") / detA) == 0, "f(x*) = det M / det A")
    return agrees(
        "(x, 1)^T M (x, 1) = f(x*) + (x - x*)^T A (x - x*) with f(x*) = det M / det A: for l >= 0 the "
        "minimum of l e + q over R^3 is m(l) = P(l) / det(l A_E + A_Q), of the sign of P(l)"
    )


@proof.check(
    "an ellipsoid (x - c)^T A (x - c) - 1 has det = -det A: P(0) = det Q < 0, leading coefficient det E < 0",
    method=Method.IDENTITY,
)
def ellipsoid_determinant() -> Finding:
    A = _symmetric3("a")
    centre = sp.Matrix(sp.symbols("c0:3", real=True))
    det = ellipsoid_matrix(A, centre).det(method="berkowitz")
    ensure(sp.expand(det + A.det(method="berkowitz")) == 0, "det = -det A")
    return agrees(
        "det = -det A < 0 for A > 0: P(0) = det Q < 0 and P(l) ~ det(E) l^4 -> -inf; Q has one negative "
        "and, by its positive definite 3 x 3 block (interlacing), three positive eigenvalues, as -E has "
        "three negative ones: nu(0) = 3 and nu(-inf) = 1 in the inertia count"
    )


@proof.check(
    "P = m d with d(l0) != 0: l0 is a zero of P of the order it is a zero of m (orders 1, 2, 3)",
    method=Method.IDENTITY,
)
def multiplicity_transfer() -> Finding:
    m, d = sp.Function("m")(LAM), sp.Function("d")(LAM)
    P = m * d
    # the k-th derivative of P is d m^(k) + (terms in m, .., m^(k-1)) (Leibniz)
    for k in (1, 2, 3):
        rest = sp.expand(sp.diff(P, LAM, k) - d * sp.diff(m, LAM, k))
        lower = {sp.diff(m, LAM, j) if j else m for j in range(k)}
        ensure(
            all(any(t.has(g) for g in lower) for t in sp.Add.make_args(rest)),
            f"P^({k}) - d m^({k}) involves m and its derivatives of order < {k} only",
        )
    return agrees(
        "P^(k) = d m^(k) + a combination of m, .., m^(k-1): with d(l0) > 0 the zeros of P on (0, inf) are "
        "those of m, with the same multiplicities"
    )


@proof.check(
    "the centre rule of the arrays: D^2 e(c_Q) is the polynomial centre_value computes, and a surface of E "
    "missing the solid of Q leaves Q inside E or apart from it, as its centre is",
    method=Method.IDENTITY,
)
def centre_rule() -> Finding:
    from quadric_contact.exact.entries import ENTRY_INDICES
    from quadric_contact.modes.decision.pipeline import centre_value

    def symmetric4(name: str) -> sp.Matrix:
        return sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"{name}{min(i, j)}{max(i, j)}", real=True))

    E, Q = symmetric4("e"), symmetric4("q")
    A, b = Q[:3, :3], Q[:3, 3]
    D = A.det(method="berkowitz")
    centre = -A.adjugate() * b
    X = sp.Matrix([*centre, D])  # D (c_Q, 1): the homogeneous centre times D
    want = sp.expand((X.T * E * X)[0, 0])
    got = sp.expand(centre_value([E[i, j] for i, j in ENTRY_INDICES], [Q[i, j] for i, j in ENTRY_INDICES]))
    ensure(got == want, "centre_value = (D c_Q, D)^T E (D c_Q, D) = D^2 e(c_Q)")
    return agrees(
        "centre_value(E, Q) = D^2 e(c_Q) identically.  Where the surface of E lies in {q > 0}, the solid "
        "{q <= 0} of an ellipsoid Q (convex, so connected, and holding c_Q) misses the surface {e = 0}: it "
        "lies in {e < 0} or in {e > 0} whole, so Q is inside E (the solids overlap) iff e(c_Q) < 0, and "
        "the solids are apart iff e(c_Q) > 0 (the reading of _geometry below, which the search checks)"
    )


def _two_spheres() -> tuple[sp.Expr, sp.Symbol, sp.Symbol]:
    dist, r = sp.symbols("d r", positive=True)
    E = sp.diag(1, 1, 1, -1)
    Q = ellipsoid_matrix(sp.eye(3), sp.Matrix([dist, 0, 0])) + sp.diag(0, 0, 0, 1 - r**2)
    return sp.expand((LAM * E + Q).det(method="berkowitz")), dist, r


@proof.check(
    "two spheres (radii 1 and r, centres d apart): every case and its roots, symbolically",
    method=Method.CASES,
)
def two_spheres() -> Finding:
    P, dist, r = _two_spheres()
    g = -(LAM**2) + (dist**2 - r**2 - 1) * LAM - r**2
    ensure(sp.expand(P - (LAM + 1) ** 2 * g) == 0, "P = (l + 1)^2 (-l^2 + (d^2 - r^2 - 1) l - r^2)")
    disc = sp.expand((dist**2 - r**2 - 1) ** 2 - 4 * r**2)
    ensure(sp.expand(disc - (dist**2 - (r + 1) ** 2) * (dist**2 - (r - 1) ** 2)) == 0, "discriminant")
    # the quadratic: product r^2 > 0, sum d^2 - r^2 - 1, discriminant (d^2 - (r+1)^2)(d^2 - (r-1)^2)
    cases = {
        # name: (d, r, geometry of the balls, positive roots expected)
        "apart": (3, 1, "SEPARATE", "two distinct"),
        "touching from outside": (2, 1, "TOUCHING", "double"),
        "crossing": (1, 1, "OVERLAPPING", "none"),
        "touching from inside": (1, 2, "OVERLAPPING", "none"),
        "containment": (Fraction(1, 2), 2, "OVERLAPPING", "none"),
        "containment, the other way": (Fraction(1, 2), Fraction(1, 4), "OVERLAPPING", "none"),
    }
    for name, (dv, rv, geometry, expected) in cases.items():
        dv, rv = sp.Rational(dv), sp.Rational(rv)
        # the balls: apart iff d > 1 + r, touching iff d = 1 + r, else the interiors meet
        truth = "SEPARATE" if dv > 1 + rv else ("TOUCHING" if dv == 1 + rv else "OVERLAPPING")
        ensure(truth == geometry, f"{name}: the balls are {truth}")
        roots = sp.roots(sp.Poly(P.subs({dist: dv, r: rv}), LAM))
        positive = sorted(m for z, m in roots.items() if z.is_positive)
        negative = sum(m for z, m in roots.items() if z.is_negative)
        got = {(): "none", (1, 1): "two distinct", (2,): "double"}.get(tuple(positive), str(positive))
        ensure(got == expected and negative >= 2, f"{name}: roots {roots}")
    return agrees(
        "P = (l + 1)^2 g(l), g with product of roots r^2 > 0, sum d^2 - r^2 - 1 and discriminant "
        "(d^2 - (r + 1)^2)(d^2 - (r - 1)^2): two distinct positive roots iff d > r + 1 (apart), a double "
        "positive one iff d = r + 1 (touching), non-real ones iff |r - 1| < d < r + 1 (crossing), negative "
        "ones iff d <= |r - 1| (one ball inside the other, touching from inside at equality)"
    )


def _root_reading(e: Any, q: Any) -> str:
    """The WWK reading of the exact roots of ``det(l E + Q)`` (sympy's real roots)."""
    from quadric_contact.theory.overlap import solid_of
    from quadric_contact.theory.pencil import characteristic_polynomial

    P = characteristic_polynomial(e.as_ellipsoid(), solid_of(q))
    poly = sp.Poly([sp.Rational(c.numerator, c.denominator) for c in reversed(P.coefficients)], LAM)
    roots = sp.Poly(poly, LAM).real_roots()
    ensure(sum(1 for z in roots if z < 0) >= 2, f"at least two negative roots: {roots}")
    positive = [z for z in roots if z > 0]
    if not positive:
        return "OVERLAPPING"
    if len(positive) == 2 and positive[0] != positive[1]:
        return "SEPARATE"
    ensure(len(positive) == 2, f"at most two positive roots: {roots}")
    return "TOUCHING"


def _geometry(e: Any, q: Any) -> str:
    """Overlap from the exact extremes of ``q`` on the surface of ``e`` (no pencil), and the
    centre of ``q`` for an ellipsoid ``q`` that may lie inside ``e``."""
    from quadric_contact.theory.geometric import decide_geometrically
    from quadric_contact.theory.overlap import solid_of

    e, q = e.as_ellipsoid(), solid_of(q)
    g = decide_geometrically(e, q)
    lo, hi = g.minimum.sign(), g.maximum.sign()
    if hi <= 0 or lo < 0:
        return "OVERLAPPING"
    centre = q.center()
    if centre is not None and e.value_at(centre) < 0:
        return "OVERLAPPING"
    return "SEPARATE" if lo > 0 else "TOUCHING"


@proof.search(
    "random exact ellipsoid pairs: the root reading equals the overlap decided from the extremes of q on E",
    examples=30,
    large=300,
    detail="apart, crossing, nested and tangent pairs",
)
def root_reading_against_geometry(examples: int) -> Finding:
    from hypothesis import given
    from hypothesis import strategies as st

    from quadric_contact.testing.strategies import ellipsoids, rigid_motions, tangent_pairs

    seen: dict[str, int] = {}

    def kind(pair: tuple[Any, Any]) -> bool:
        return all(x.kind.name == "ELLIPSOID" for x in pair)

    @search_settings(examples)
    @given(
        pair=st.tuples(ellipsoids(), ellipsoids(max_axis=6))
        | tangent_pairs().filter(kind)
        | tangent_pairs(inside=True).filter(kind),
        motion=rigid_motions(),
    )
    def search(pair: tuple[Any, Any], motion: Any) -> None:
        e, q = (x.moved(motion) for x in pair)
        want = _geometry(e, q)
        ensure(_root_reading(e, q) == want, f"{e} / {q}: the geometry says {want}")
        seen[want] = seen.get(want, 0) + 1

    search()
    return agrees(", ".join(f"{v} {k.lower()}" for k, v in sorted(seen.items())) + ": the roots agree")
