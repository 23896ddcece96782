"""Mutual contact events: two moving ellipsoids change state only at roots of a discriminant in t.

Not a result of the paper: the reduction on which :mod:`quadric_contact.scenes.mutual`
tracks the contacts of moving ellipsoids with each other.  Each body moves rigidly by the
scene's motion on a segment: a polynomial centre path ``p(t)`` and a rotation
``R(t) = M(q(t)) / n(t)``, ``n = |q|^2``, of a polynomial quaternion ``q(t)`` (``n = 1``
without rotation).  ``G(t) = [[M^T, n c0 - M^T p], [0, n]]`` has polynomial entries and
``A(t) = G^T E0 G`` (:meth:`~quadric_contact.scenes.trajectory.MotionSegment.moved_upper`)
is ``n(t)^2`` times the matrix of the moved ellipsoid.

Claim.

1. *The pencil.*  With ``A(t)``, ``B(t)`` the two bodies' matrices so built, both negative
   inside, ``P(l; t) = det(l A(t) + B(t))`` has coefficients ``c0(t) .. c4(t)`` that are
   polynomials in ``t``; ``c4 = det A(t) = n_a(t)^8 det E_a < 0`` and
   ``c0 = det B(t) = n_b(t)^8 det E_b < 0`` for every ``t``.  A positive factor on either
   matrix scales the roots by a positive number (``c_k(a A, b B) = a^k b^(4-k) c_k(A, B)``), so
   at every time ``P`` has the positive roots, with their multiplicities, of the pencil of the
   moved ellipsoids themselves, and Wang-Wang-Kim reads the state off them.  Working in the
   frame of one body instead (the other moved by ``H_a^-1 H_b``) gives the pencil
   ``det(K^T (l A + B) K) = det(K)^2 P`` with ``K = n_a H_a`` (``det K = n_a^4``): the same roots,
   at a higher degree in ``t``; the pencil time-dependent on both sides needs no division and
   keeps the lower degree.
2. *Events.*  The state (apart: two distinct positive roots; touching: a double positive
   root; overlapping: none) changes only at real roots of ``Δ4(t)``, the discriminant in
   ``l`` of ``P``, when ``Δ4`` is not identically zero.  On an interval where ``Δ4 != 0`` the
   four roots are distinct and continuous in ``t`` (``c4 != 0``: the degree never drops); a
   real root stays real (a non-real root has its conjugate as a distinct partner), never
   crosses 0 (``c0 != 0``) and never meets another, so the number of positive roots is
   constant.  The apart and overlapping sets of times are open, so where the states on the
   two sides of a root differ the pair touches at the root; where they agree it touches iff
   the double root ``-s0 / s1`` of the first subresultant ``s1 l + s0`` of ``P`` and ``P'`` is
   positive; ``s1 = -2 a^5 (p - q)^2 (p - s)^2 (q - s)^2`` for ``P = a (l - p)^2 (l - q) (l - s)``
   vanishes only at a triple root or two double roots (left undecided, never guessed).
   Between roots of ``Δ4`` the state at a rational time needs no root isolation:
   ``Δ4 < 0`` means exactly two real roots, the two negative ones of Wang-Wang-Kim
   (overlapping); ``Δ4 > 0`` means four real roots (not none: two are negative), where
   Descartes' rule of signs is exact (two sign changes of ``c0 .. c4``: apart; none:
   overlapping).
3. *The structural double root.*  When the quadratic blocks satisfy ``q S_b(t) = p S_a(t)``
   for polynomials ``p``, ``q`` without a common factor (similar bodies in the same
   orientation: congruent ones that only translate, ``q = 1``, and two spheres whatever their
   rotations, whose matrices are varying positive multiples ``n(t)^2`` of a sphere's),
   ``k = p / q > 0`` (a ratio of positive definite blocks; ``q`` never vanishes) and
   ``N = q B - p A`` has a zero quadratic block, so ``adj N = 0`` and ``det(e A + N)`` has no
   terms of degree 0 or 1 in ``e`` (Jacobi's formula): ``q^4 P(l) = det((q l + p) A + N)`` has
   the root ``l = -k < 0`` of multiplicity at least 2 at every time, ``Δ4 ≡ 0``, and
   ``P = (q l + p)^2 (r2 l^2 + r1 l + r0)`` over ``Q[t]`` (Gauss's lemma: ``q l + p`` is
   primitive) with ``r2 = c4 / q^2``, ``r1 = (c3 - 2 p q r2) / q^2``,
   ``r0 = (c2 - 2 p q r1 - p^2 r2) / q^2``.  The positive roots are those of the quadratic
   (``r2``, ``r0`` never vanish), and the argument of step 2 runs with its discriminant
   ``r1^2 - 4 r2 r0`` in place of ``Δ4`` and its double root ``-r1 / (2 r2)``; where it is
   positive the two real roots have the sign of their sum ``-r1 / r2`` (their product
   ``r0 / r2`` is positive): apart iff ``r1 r2 < 0``.  Any other pencil with ``Δ4 ≡ 0``
   (coaxial spheroids moving along their common axis) is split into its irreducible factors
   over ``Q[t]``: each is square-free in ``l`` with a leading coefficient dividing ``c4``, so
   its roots are simple and continuous, and they meet another factor's only at roots of the
   resultant; the state changes only at real roots of these discriminants and resultants, and
   at one of them the common root ``-s0 / s1`` of the first subresultant decides a touch
   (undecided where ``s1`` vanishes too).
4. *The broad phase.*  On a window ``[a, b]`` the swept box of a body contains every placement:
   the centre ``p(m + s) = Σ a_k s^k`` (the Taylor shift, exact) stays within
   ``a_0 ± Σ_{k>=1} |a_k| h^k`` for ``|s| <= h``; a body ``(x - c)^T S (x - c) <= m`` reaches
   ``c_i ± sqrt(m (S^-1)_ii)`` along axis ``i`` (Cauchy-Schwarz in the inner product of ``S``,
   attained), and at most ``sqrt(m / L)`` from its centre in any direction, for any ``L`` with
   ``S - L I`` positive definite (so under any rotation); the rational square roots are rounded
   up, and the floats of the sweep rounded outwards.  Boxes that do not meet hold bodies that do
   not meet, at any time of the window: a pruned pair is apart there, as the pencil would say.
   Likewise a kept pair whose centres stay farther apart than the sum of the two bounds of the
   largest semi-axes (``|p_a(t) - p_b(t)|^2 - (rho_a + rho_b)^2`` positive at ``a`` without a
   real root in ``[a, b]``, decided exactly) is apart on the window without a pencil.

What is checked and how.  Symbolic identities: the rotation's determinant and the degrees of
freedom of the moved matrix (``moved_determinant``), the pencil's end coefficients and its
scaling (``pencil_ends_and_scaling``), the package's ``Δ4`` is the discriminant
(``delta4_is_the_discriminant``), the subresultant's double root and where it vanishes
(``subresultant_double_root``), the sign of the discriminant by the roots' kinds
(``discriminant_sign``), the structural double root (``structural_double_root``) and
the quotient's coefficients (``quadratic_factor``), the Taylor shift and Cauchy-Schwarz of the
swept box (``swept_box_bounds``).  Exact computation: two spheres, one turning, have a
ratio ``k(t)`` that is not constant and the factorization over ``Q[t]`` (``turning_spheres``);
a turning body's pencil in the frame of
the other equals ``n_a^8`` times the pencil on both sides (``relative_frame``); the rational
square root is an upper bound (``square_root_rounded_up``).  Cross-checks (the full profile),
no part of the proof: the timelines of random moving pairs (translating, turning, similar, two
spheres one of which turns) against the static exact decision at sampled rational times and at
the rational events (``timelines_sampled``); random swept boxes contain the exact extents of the
body at sampled times (``boxes_contain_the_bodies``).

Not proven here: that the roots of a polynomial of constant degree depend continuously on its
coefficients (a standard result), used in steps 2 and 3; the correct rounding of ``float`` of a
rational (Python's documented behaviour), used for the sweep's outward rounding.
"""

from __future__ import annotations

import random
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint
import sympy as sp

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure

from ._plane_pencil import LAM, ellipsoid_matrix

proof = Proof(
    "Mutual contact events",
    "two moving ellipsoids change state only at real roots of the discriminant in t of det(l A(t) + B(t)); "
    "the structural double root of similar bodies; sound swept boxes",
    not_proven=(
        "the continuity of the roots of a polynomial of constant degree in its coefficients and the "
        "correct rounding of float(Fraction), standard facts not re-derived"
    ),
    relies_on=("Wang-Wang-Kim 2001",),
)


def _symmetric(name: str, n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"{name}{min(i, j)}{max(i, j)}", real=True))


def _upper(M: sp.Matrix) -> list[Any]:
    return [M[i, j] for i in range(4) for j in range(i, 4)]


def _rotation_times_n(w: Any, x: Any, y: Any, z: Any) -> list[list[Any]]:
    """``M(q) = |q|^2 R(q)``, as :meth:`MotionSegment.moved_upper` writes it (rows)."""
    return [
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z],
    ]


@proof.check(
    "M(q)^T M(q) = |q|^4 I and det M(q) = |q|^6: det G = n^4 and det(G^T E0 G) = n^8 det E0",
    method=Method.IDENTITY,
)
def moved_determinant() -> Finding:
    w, x, y, z = sp.symbols("w x y z", real=True)
    n = w * w + x * x + y * y + z * z
    M = sp.Matrix(_rotation_times_n(w, x, y, z))
    ensure(sp.expand(M.T * M - n**2 * sp.eye(3)) == sp.zeros(3, 3), "M^T M = n^2 I")
    ensure(sp.expand(M.det() - n**3) == 0, "det M = n^3")
    p = sp.Matrix(sp.symbols("p0:3", real=True))
    c0 = sp.Matrix(sp.symbols("g0:3", real=True))
    G = sp.zeros(4, 4)
    G[:3, :3] = M.T
    G[:3, 3] = n * c0 - M.T * p
    G[3, 3] = n
    ensure(sp.expand(G.det() - n**4) == 0, "det G = n^4")
    return agrees(
        "M/n is a rotation and det G = n^4 for every quaternion and centre path: det A(t) = n_a(t)^8 det E_a "
        "< 0 and det B(t) = n_b(t)^8 det E_b < 0 at every time (n > 0 on the segment)"
    )


@proof.check(
    "det(l A + B): c4 = det A, c0 = det B, and c_k(a A, b B) = a^k b^(4-k) c_k(A, B)",
    method=Method.IDENTITY,
)
def pencil_ends_and_scaling() -> Finding:
    from quadric_contact._generated.formulas import pencil_coefficients

    A, B = _symmetric("a", 4), _symmetric("b", 4)
    c = pencil_coefficients(*_upper(A), *_upper(B))
    ensure(sp.expand(c[4] - A.det(method="berkowitz")) == 0, "c4 = det A")
    ensure(sp.expand(c[0] - B.det(method="berkowitz")) == 0, "c0 = det B")
    al, be = sp.symbols("alpha beta", positive=True)
    scaled = pencil_coefficients(*(al * v for v in _upper(A)), *(be * v for v in _upper(B)))
    for k in range(5):
        ensure(sp.expand(scaled[k] - al**k * be ** (4 - k) * c[k]) == 0, f"c{k} scales by a^{k} b^{4 - k}")
    return agrees(
        "P_{aA,bB}(l) = b^4 P_{A,B}(a l / b): positive factors on A(t) and B(t) multiply the roots by "
        "b / a > 0, keeping their signs and multiplicities; c4(t) and c0(t) never vanish, so no root meets "
        "0 or infinity"
    )


@proof.check("the package's Δ4 is the discriminant of c4 l^4 + .. + c0", method=Method.IDENTITY)
def delta4_is_the_discriminant() -> Finding:
    from quadric_contact._generated.formulas import paper_deltas

    c = sp.symbols("c0:5", real=True)
    quartic = sp.Poly(sum(c[i] * LAM**i for i in range(5)), LAM)
    ensure(sp.expand(paper_deltas(*c)[2] - sp.discriminant(quartic)) == 0, "Δ4 = disc")
    return agrees("Δ4(t) vanishes exactly where two roots of P(l; t) coincide (c4(t) != 0)")


@proof.check(
    "P = a (l - p)^2 (l - q) (l - s): the first subresultant of P and P' is s1 l + s0 with "
    "-s0 / s1 = p and s1 = -2 a^5 (p - q)^2 (p - s)^2 (q - s)^2",
    method=Method.IDENTITY,
)
def subresultant_double_root() -> Finding:
    from quadric_contact.scenes.mutual import _subresultant_1

    a, p, q, s = sp.symbols("a p q s", real=True)
    P = sp.Poly(sp.expand(a * (LAM - p) ** 2 * (LAM - q) * (LAM - s)), LAM)
    c = [P.coeff_monomial(LAM**k) for k in range(5)]
    s1f, s0f = _subresultant_1()
    s1, s0 = sp.expand(s1f(*c, const=sp.Rational)), sp.expand(s0f(*c, const=sp.Rational))
    ensure(sp.expand(s1 + 2 * a**5 * (p - q) ** 2 * (p - s) ** 2 * (q - s) ** 2) == 0, "s1")
    ensure(sp.expand(s0 + p * s1) == 0, "s0 = -p s1")
    return agrees(
        "at a root of Δ4 with one double root p (q, s distinct from p and each other, possibly non-real), "
        "s1 != 0 and p = -s0 / s1 is real: the pair touches iff it is positive; s1 = 0 means a triple root "
        "or two double roots (then the state is left undecided, not guessed)"
    )


@proof.check(
    "a quartic with two real roots and a conjugate pair has Δ4 < 0; with two conjugate pairs Δ4 > 0",
    method=Method.IDENTITY,
)
def discriminant_sign() -> Finding:
    a, p, q, u, v, u2, w = sp.symbols("a p q u v u2 w", real=True)
    two = sp.Poly(sp.expand(a * (LAM - p) * (LAM - q) * ((LAM - u) ** 2 + v**2)), LAM)
    closed = -4 * a**6 * v**2 * (p - q) ** 2 * ((p - u) ** 2 + v**2) ** 2 * ((q - u) ** 2 + v**2) ** 2
    ensure(sp.expand(sp.discriminant(two) - closed) == 0, "two real roots")
    none = sp.Poly(sp.expand(a * ((LAM - u) ** 2 + v**2) * ((LAM - u2) ** 2 + w**2)), LAM)
    pairs = ((u - u2) ** 2 + (v - w) ** 2) * ((u - u2) ** 2 + (v + w) ** 2)
    ensure(sp.expand(sp.discriminant(none) - 16 * a**6 * v**2 * w**2 * pairs**2) == 0, "no real root")
    return agrees(
        "Δ4 = -4 a^6 v^2 (p - q)^2 |p - z|^4 |q - z|^4 < 0 with two simple real roots p, q and z = u + iv; "
        "a square times 16 a^6 v^2 w^2 > 0 with none; a product of squares > 0 with four: where Δ4 != 0 "
        "its sign tells two real roots (< 0) from four or none (> 0)"
    )


@proof.check(
    "q S_b = p S_a: N = q B - p A has a zero quadratic block, adj N = 0 and det(e A + N) = O(e^2)",
    method=Method.IDENTITY,
)
def structural_double_root() -> Finding:
    A = _symmetric("a", 4)
    w = sp.symbols("w0:3", real=True)
    r = sp.Symbol("r", real=True)
    N = sp.zeros(4, 4)
    for i in range(3):
        N[i, 3] = N[3, i] = w[i]
    N[3, 3] = r
    ensure(N.adjugate() == sp.zeros(4, 4), "adj N = 0")
    e = sp.Symbol("e")
    D = sp.Poly(sp.expand((e * A + N).det(method="berkowitz")), e)
    ensure(D.coeff_monomial(1) == 0 and D.coeff_monomial(e) == 0, "no terms of degree 0 and 1 in e")
    # and for two similar bodies written out: (x - u)^T S (x - u) <= 1 and (x - v)^T (k S) (x - v) <= m
    S = _symmetric("s", 3)
    u, v = sp.Matrix(sp.symbols("u0:3", real=True)), sp.Matrix(sp.symbols("v0:3", real=True))
    k, m = sp.symbols("k m", positive=True)
    Ea = ellipsoid_matrix(S, u)
    Eb = ellipsoid_matrix(k * S, v) + sp.diag(0, 0, 0, 1 - m)
    Nb = Eb - k * Ea
    ensure(Nb[:3, :3] == sp.zeros(3, 3), "B - k A has a zero quadratic block")
    return agrees(
        "det(l A + B) = det((l + k) A + N) with N = B - k A of rank <= 2: l = -k is a root of multiplicity "
        ">= 2 at every time (Jacobi: the e-coefficient is tr(adj(N) A) = 0), and -k < 0 since k S_a = S_b "
        "with both positive definite; Δ4 ≡ 0"
    )


@proof.check(
    "(q l + p)^2 (r2 l^2 + r1 l + r0): r2 = c4 / q^2, r1 = (c3 - 2 p q r2) / q^2, "
    "r0 = (c2 - 2 p q r1 - p^2 r2) / q^2, c1 = 2 p q r0 + p^2 r1, c0 = p^2 r0",
    method=Method.IDENTITY,
)
def quadratic_factor() -> Finding:
    p, q, r0, r1, r2 = sp.symbols("p q r0 r1 r2", real=True)
    P = sp.Poly(sp.expand((q * LAM + p) ** 2 * (r2 * LAM**2 + r1 * LAM + r0)), LAM)
    c = [P.coeff_monomial(LAM**j) for j in range(5)]
    ensure(sp.expand(c[4] - q**2 * r2) == 0, "r2")
    ensure(sp.expand(c[3] - 2 * p * q * r2 - q**2 * r1) == 0, "r1")
    ensure(sp.expand(c[2] - 2 * p * q * r1 - p**2 * r2 - q**2 * r0) == 0, "r0")
    ensure(sp.expand(c[1] - 2 * p * q * r0 - p**2 * r1) == 0 and sp.expand(c[0] - p**2 * r0) == 0, "c1, c0")
    return agrees(
        "the quotient is read off c4, c3, c2 and checked on c1, c0; r2 = c4 / q^2 < 0 and r0 = c0 / p^2 < 0 "
        "never vanish, so its positive roots change only at roots of r1^2 - 4 r2 r0, and a double one is "
        "-r1 / (2 r2)"
    )


@proof.check(
    "two spheres, one turning: the quadratic blocks keep a ratio k(t) that is not constant, and "
    "P = (q l + p)^2 R exactly",
    method=Method.COMPUTATION,
)
def turning_spheres() -> Finding:
    from quadric_contact import Quadric
    from quadric_contact._generated.formulas import pencil_coefficients
    from quadric_contact.scenes.mutual import _exact_quotient, _homothety
    from quadric_contact.scenes.trajectory import PolynomialMotion

    F = Fraction
    Sa, Sb = Quadric.sphere(F(1, 5), (0, 0, 1)), Quadric.sphere(F(3, 10), (-2, 0, 1))
    (sa,) = PolynomialMotion(((0,), (0,), (0,)), ((1,), (0, F(1, 4)), (0,), (0, F(1, 4)))).segments(
        F(0), F(4), Sa.center()
    )
    (sb,) = PolynomialMotion(((0, 1), (0,), (0,))).segments(F(0), F(4), Sb.center())
    A, B = sa.moved_upper(-Sa, Sa.center()), sb.moved_upper(-Sb, Sb.center())
    k = _homothety(A, B)
    ensure(k is not None and k[1].degree() > 0, "a ratio of polynomials, not a constant")
    assert k is not None
    p, q = k
    c = pencil_coefficients(*A, *B)
    r2 = _exact_quotient(c[4], q * q)
    r1 = _exact_quotient(c[3] - 2 * p * q * r2, q * q)
    r0 = _exact_quotient(c[2] - 2 * p * q * r1 - p * p * r2, q * q)
    ensure((c[1] - 2 * p * q * r0 - p * p * r1).is_zero() and (c[0] - p * p * r0).is_zero(), "c1, c0")
    return agrees(
        f"k(t) = ({p}) / ({q}); the quotient's coefficients are polynomials of degrees "
        f"{r0.degree()}, {r1.degree()}, {r2.degree()} in t"
    )


@proof.check(
    "swept box: the Taylor shift is exact, Cauchy-Schwarz in the inner product of S bounds the extent, "
    "attained at sqrt(m / (e^T S^-1 e)) S^-1 e; y^T S y >= L |y|^2 when S - L I is positive definite",
    method=Method.IDENTITY,
)
def swept_box_bounds() -> Finding:
    tt, m_, s_ = sp.symbols("t m s", real=True)
    a = sp.symbols("a0:4", real=True)
    p = sum(a[i] * tt**i for i in range(4))
    shifted = sp.Poly(sp.expand(p.subs(tt, m_ + s_)), s_)
    taylor = sum(sp.diff(p, tt, k).subs(tt, m_) / sp.factorial(k) * s_**k for k in range(4))
    ensure(sp.expand(shifted.as_expr() - taylor) == 0, "p(m + s) = Σ p^(k)(m) s^k / k!")
    S = _symmetric("s", 3)
    y, u = sp.Matrix(sp.symbols("y0:3", real=True)), sp.Matrix(sp.symbols("u0:3", real=True))
    sigma = sp.Symbol("sigma", real=True)
    form = sp.expand(((u + sigma * y).T * S * (u + sigma * y))[0, 0])
    q = sp.Poly(form, sigma)
    uSu, uSy, ySy = (u.T * S * u)[0, 0], (u.T * S * y)[0, 0], (y.T * S * y)[0, 0]
    ensure(
        sp.expand(q.coeff_monomial(1) - uSu) == 0
        and sp.expand(q.coeff_monomial(sigma) - 2 * uSy) == 0
        and sp.expand(q.coeff_monomial(sigma**2) - ySy) == 0,
        "(u + σ y)^T S (u + σ y) = u^T S u + 2 σ u^T S y + σ^2 y^T S y >= 0: "
        "(u^T S y)^2 <= (u^T S u)(y^T S y)",
    )
    # with u = S^-1 e: u^T S y = e . y and u^T S u = e^T S^-1 e; the bound is attained at y = c S^-1 e
    e = sp.Matrix([1, 0, 0])
    Sinv = S.adjugate() / S.det()
    ystar = Sinv * e
    ensure(sp.simplify((ystar.T * S * ystar)[0, 0] - (e.T * Sinv * e)[0, 0]) == 0, "y* on the level")
    L = sp.Symbol("L", real=True)
    ensure(
        sp.expand((y.T * S * y)[0, 0] - L * (y.T * y)[0, 0] - (y.T * (S - L * sp.eye(3)) * y)[0, 0]) == 0, "L"
    )
    return agrees(
        "the centre stays within a_0 ± Σ |a_k| h^k on [m - h, m + h]; a body reaches exactly "
        "c_i ± sqrt(m (S^-1)_ii) along axis i, and at most sqrt(m / L) from its centre in any direction: "
        "the box of the centre's range widened by these contains every placement of the window"
    )


@proof.check(
    "a turning body's pencil in the frame of the other is n_a^8 times the pencil on both sides, "
    "at a higher degree in t",
    method=Method.COMPUTATION,
)
def relative_frame() -> Finding:
    from quadric_contact import Quadric
    from quadric_contact._generated.formulas import pencil_coefficients
    from quadric_contact.scenes.trajectory import PolynomialMotion

    F = Fraction
    Ea = Quadric.ellipsoid(F(4, 5), F(1, 5), F(1, 4), center=(0, 0, 1))
    Eb = Quadric.ellipsoid(F(1, 3), F(1, 4), F(1, 5), center=(F(1, 2), -2, 1))
    ma = PolynomialMotion(((0, F(1, 4)), (0,), (0, F(-1, 8))), ((1,), (0,), (0,), (0, F(1, 2))))
    mb = PolynomialMotion(((0, F(-1, 5)), (0, 1), (0,)), ((1,), (0, F(1, 3)), (0,), (0,)))
    span = (F(0), F(4))
    (sa,) = ma.segments(*span, Ea.center())
    (sb,) = mb.segments(*span, Eb.center())

    def neg(q: Quadric) -> Quadric:
        return -q if q.canonical_sign < 0 else q

    A, B = sa.moved_upper(neg(Ea), Ea.center()), sb.moved_upper(neg(Eb), Eb.center())
    both = pencil_coefficients(*A, *B)
    # K = n_a H_a = [[M_a, n_a p_a - M_a c_a], [0, n_a]]: world = K body / n_a for body a
    w, x, y, z = sa.quaternion
    Ma = _rotation_times_n(w, x, y, z)
    na = sa.norm_poly()
    ca = [flint.fmpq_poly([flint.fmpq(v.numerator, v.denominator)]) for v in Ea.center()]
    zero = 0 * na
    K = [[*Ma[i], na * sa.center[i] - sum((Ma[i][j] * ca[j] for j in range(3)), zero)] for i in range(3)]
    K.append([zero, zero, zero, na])

    def full(u: Any) -> list[list[Any]]:
        idx = [(i, j) for i in range(4) for j in range(i, 4)]
        out = [[zero] * 4 for _ in range(4)]
        for v, (i, j) in zip(u, idx, strict=True):
            out[i][j] = out[j][i] = v
        return out

    def congruent(X: list[list[Any]]) -> list[Any]:
        KX = [[sum((K[r][i] * X[r][j] for r in range(4)), zero) for j in range(4)] for i in range(4)]
        Y = [[sum((KX[i][r] * K[r][j] for r in range(4)), zero) for j in range(4)] for i in range(4)]
        return [Y[i][j] for i in range(4) for j in range(i, 4)]

    Ar, Br = congruent(full(A)), congruent(full(B))
    # A seen from its own frame (its initial placement) is constant up to the factor n_a^4
    for v, e0 in zip(Ar, neg(Ea).upper, strict=True):
        ensure(v == na**4 * flint.fmpq(e0.numerator, e0.denominator), "K^T A K = n_a^4 E_a in a's frame")
    rel = pencil_coefficients(*Ar, *Br)
    factor = na**8
    ensure(all(r == factor * c for r, c in zip(rel, both, strict=True)), "c_k^rel = n_a^8 c_k")
    degrees = [c.degree() for c in both], [c.degree() for c in rel]
    return agrees(
        f"the same roots in l at every time; degrees in t of c0..c4 on both sides {degrees[0]}, in the frame "
        f"of the turning body {degrees[1]}"
    )


def _sqrt_up(x: Fraction) -> Fraction:
    from quadric_contact.scenes.broadphase import _sqrt_up as up

    return up(x)


@proof.check(
    "the broad phase's rational square root is an upper bound within 2^-24 relative (every x = i / j, "
    "1 <= i, j <= 60, and powers of ten)",
    method=Method.COMPUTATION,
)
def square_root_rounded_up() -> Finding:
    count = 0
    xs = [Fraction(i, j) for i in range(1, 61) for j in range(1, 61)]
    xs += [Fraction(10) ** k for k in range(-12, 13)]
    for xv in xs:
        r = _sqrt_up(xv)
        ensure(r >= 0 and r * r >= xv, f"sqrt_up({xv})^2 >= {xv}")
        ensure((r - Fraction(1, 1 << 24)) ** 2 < xv or r <= Fraction(1, 1 << 24), f"sqrt_up({xv}) is tight")
        count += 1
    return agrees(
        f"{count} values: ceil(sqrt(ceil(x 4^24))) / 2^24 >= sqrt(x), one step of 2^-24 above at most "
        "(an integer square root rounded up, of a number rounded up)"
    )


# -- cross-checks: the implementation against the statement ------------------------------------------


def _random_pairs(rng: random.Random, n: int) -> list[Any]:
    from quadric_contact import Quadric
    from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
    from quadric_contact.scenes.trajectory import PolynomialMotion

    F = Fraction
    scenes = []
    for i in range(n):
        kind = i % 4  # 0: generic shapes, 1: congruent translates, 2: one turning, 3: spheres, one turning
        bodies = []
        shape = tuple(F(rng.randint(2, 6), 10) for _ in range(3))
        meet = (F(rng.randint(-4, 4), 8), F(rng.randint(-4, 4), 8), F(rng.randint(-4, 4), 8))
        for b in range(2):
            axes = shape if kind == 1 else tuple(F(rng.randint(2, 6), 10) for _ in range(3))
            if kind == 3:
                axes = (axes[0],) * 3
            start = tuple(F(rng.randint(-12, 12), 4) for _ in range(3))
            # aim at a point near the common one at a time in the span
            at = F(rng.randint(1, 3))
            velocity = tuple((meet[k] + F(rng.randint(-2, 2), 10) - start[k]) / at for k in range(3))
            q = None
            if kind in (2, 3) and b == 0:
                axis = rng.randrange(3)
                q = ((1,), *(((0, F(rng.randint(1, 4), 4)) if k == axis else (0,)) for k in range(3)))
            motion = PolynomialMotion(tuple((F(0), v) for v in velocity), q)
            E = Quadric.ellipsoid(*axes, center=start).as_ellipsoid()
            bodies.append(MovingEllipsoid(f"b{b}", E, motion))
        scenes.append(Scene(f"pair {i}", (), tuple(bodies), (F(0), F(4)), ("contact",), mutual=("b0", "b1")))
    return scenes


def _static(scene: Any, t: Fraction) -> str:
    from quadric_contact.theory.overlap import overlap_exact

    ea, eb = scene.ellipsoids
    A = ea.trajectory.placed(ea.quadric, t, *scene.span)
    B = eb.trajectory.placed(eb.quadric, t, *scene.span)
    return {"SEPARATE": "apart", "TOUCHING": "touching", "OVERLAPPING": "overlapping"}[
        overlap_exact(A, B).code.name
    ]


@proof.search(
    "random moving pairs: the timeline's state equals the static exact decision at sampled times and events",
    examples=0,
    large=60,
    unit="random pairs",
    detail="generic, congruent translates, one turning, spheres; 17 even times, every gap, rational events",
    method=Method.CROSS_CHECK,
    requires=(),
)
def timelines_sampled(n: int) -> Finding:
    from quadric_contact.exact.algebraic import rational_between
    from quadric_contact.scenes.mutual import mutual_contacts

    rng = random.Random(20261127)
    compared, events, met = 0, 0, 0
    for scene in _random_pairs(rng, n):
        found = mutual_contacts(scene, broad_phase=False)
        t0, t1 = scene.span
        if not found:
            times = [t0 + (t1 - t0) * Fraction(k, 16) for k in range(17)]
            for t in times:
                ensure(_static(scene, t) == "apart", f"{scene.name}: apart at {t}")
            compared += len(times)
            continue
        (pair,) = found
        met += 1
        cuts = [t0, *(e.time for e in pair.events), t1]
        times = [t0 + (t1 - t0) * Fraction(k, 16) for k in range(17)]
        times += [rational_between(a, b) for a, b in pairwise(cuts)]
        times += [e.time.as_fraction() for e in pair.events if e.time.is_rational]
        for t in times:
            ensure(pair.state_at(t) == _static(scene, t), f"{scene.name} at t = {t}")
        compared += len(times)
        events += len(pair.events)
    ensure(met >= n // 3, f"only {met} of {n} pairs meet")
    return agrees(f"{n} pairs ({met} meet, {events} events): the states agree at {compared} rational times")


@proof.search(
    "random swept boxes contain the exact axis extents of the body at sampled times",
    examples=0,
    large=300,
    unit="random (body, window) pairs",
    detail="8 times each, a quarter turning",
    method=Method.CROSS_CHECK,
    requires=(),
)
def boxes_contain_the_bodies(n: int) -> Finding:
    from quadric_contact import Quadric
    from quadric_contact.scenes.broadphase import ellipsoid_extents, swept_box
    from quadric_contact.scenes.trajectory import PolynomialMotion

    F = Fraction
    rng = random.Random(17)
    checked = 0
    for i in range(n):
        axes = tuple(F(rng.randint(1, 8), rng.randint(2, 9)) for _ in range(3))
        centre = tuple(F(rng.randint(-9, 9), 3) for _ in range(3))
        E = Quadric.ellipsoid(*axes, center=centre)
        if i % 3 == 0:  # a body already turned: not axis-aligned
            from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion

            E = E.moved(
                RigidMotion.from_translation(centre)
                @ RigidMotion(rotation_from_quaternion(1, F(1, 2), F(1, 3), 0))
                @ RigidMotion.from_translation(tuple(-v for v in centre))
            )
        translation = tuple(
            tuple(F(rng.randint(-6, 6), 4) for _ in range(rng.randint(1, 3))) for _ in range(3)
        )
        q = ((1,), (0, F(1, 2)), (0,), (F(1, 3),)) if i % 4 == 0 else None
        (seg,) = PolynomialMotion(translation, q).segments(F(0), F(2), E.center())
        a, b = sorted(F(rng.randint(0, 16), 8) for _ in range(2))
        if a == b:
            b = a + F(1, 8)
        half, rho = ellipsoid_extents(E)
        box = swept_box(seg, half, rho, a, b)
        for k in range(8):
            t = a + (b - a) * F(k, 7)
            placed = E.moved(seg.rigid_motion(t, E.center()))
            e = placed.as_ellipsoid()
            S = [[e.matrix[r][c] for c in range(3)] for r in range(3)]
            c = e.center()
            level = -e.value_at(c) if S[0][0] > 0 else e.value_at(c)
            if S[0][0] < 0:
                S = [[-v for v in row] for row in S]
            cof = [
                S[(ax + 1) % 3][(ax + 1) % 3] * S[(ax + 2) % 3][(ax + 2) % 3]
                - S[(ax + 1) % 3][(ax + 2) % 3] ** 2
                for ax in range(3)
            ]
            det = sum(
                S[0][j] * (S[1][(j + 1) % 3] * S[2][(j + 2) % 3] - S[1][(j + 2) % 3] * S[2][(j + 1) % 3])
                for j in range(3)
            )
            for ax in range(3):
                reach2 = level * cof[ax] / det  # m (S^-1)_ii, the squared reach along the axis
                lo, hi = box[ax]
                ensure(c[ax] - lo >= 0 and (c[ax] - lo) ** 2 >= reach2, f"body {i}: low side {ax} at t = {t}")
                ensure(
                    hi - c[ax] >= 0 and (hi - c[ax]) ** 2 >= reach2, f"body {i}: high side {ax} at t = {t}"
                )
            checked += 1
    return agrees(f"{checked} placements: every box holds the body's exact extent along each axis")
