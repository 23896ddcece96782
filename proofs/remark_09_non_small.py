"""Remark 9: smallness cannot be dropped from Theorem 2; non-real roots always mean crossing.

Claim.  Without smallness, two intersection curves occur with Segre types
``[1111]_4`` and ``[(11)11]_3`` (four real roots), and a curve plus an
isolated tangent point with ``[211]_3`` and ``[2(11)]_2`` (real roots): so
Theorem 2 fails for non-small ellipsoids.  Conversely, non-real roots imply
transversal contact for any pair.

What is checked and how.  Exact constructions, each an ellipsoid that the
package's exact :func:`~quadric_contact.theory.smallness.smallness` finds not small,
whose real intersection with ``Q`` (computed exactly, see ``_intersection``)
is two curves, respectively a curve and an isolated tangent point, with the
stated Segre characteristic; for each, Corollary 10's test (``Delta_4 < 0``, or
``Delta_4 = 0`` and ``Delta_3 < 0``) says "no transversal contact" although the
surfaces cross.

The converse is proved, for an ellipsoid ``E`` and any quadric ``Q`` (the paper
states it for any two quadrics; only this case is used).  Let
``(mu E + Q) v = 0`` with ``mu = alpha + i beta``, ``beta != 0``, ``v = x + i y``.
(i) ``x`` and ``y`` are linearly independent: otherwise ``v`` is a complex
multiple of a real ``x`` with ``(mu E + Q) x = 0``, whose imaginary part gives
``beta E x = 0``, so ``x = 0``.  (ii) On the plane ``span(x, y)`` the 2 x 2
forms ``E2, Q2`` of ``E, Q`` satisfy ``(mu E2 + Q2) (1, i)^T = 0``, and
``(1, -i) M (1, i)^T = trace M`` for a symmetric ``M`` (identity), so
``mu trace E2 + trace Q2 = 0``: both traces vanish.  (iii) ``E2 != 0``: else
``Q2 = 0`` too and ``span(x, y)`` would be a plane on which the form of ``E``
vanishes, but a form of signature (3, 1) vanishes on no plane (the plane
would meet the 3-dimensional space on which it is positive definite).  A
non-zero trace-free ``E2`` has ``det E2 = -(e^2 + f^2) < 0`` (identity): it is
indefinite, with two real isotropic lines ``u1, u2``.  (iv) In the basis
``(u1, u2)``, ``E2 = [[0, h], [h, 0]]`` and ``det(l E2 + Q2) = q1 q2 - (h l + q)^2``
with ``q1 = Q(u1)``, ``q2 = Q(u2)`` (identity); it vanishes at the non-real
``mu``, so ``q1 q2 < 0``.  (v) ``u1, u2`` are real with ``E(u) = 0``; their last
coordinate is not 0 (the quadratic part of an ellipsoid is definite): they
are points of the surface of ``E`` on opposite sides of ``Q``.  The
construction is also carried out exactly on Example 11's pencil.
Cross-check of the package (full profile): 1000 hypothesis examples of
ellipsoids (images of the unit sphere under rational affine maps, so that
their rational points are known) and Table 1 quadrics; whenever the package
finds a non-real root, two rational points of the ellipsoid on opposite sides
of ``Q`` are found near the extremes of ``Q`` on it (a float search; the points
are checked exactly).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp

from quadric_contact import Quadric, characteristic_polynomial, paper
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure, search_settings
from quadric_contact.theory.smallness import smallness

from ._intersection import contact_type, segre, show_segre

proof = Proof("Remark 9", "without smallness Theorem 2 fails; non-real roots always mean crossing")

F = Fraction

CASES = {
    "two curves [1111]_4": (
        Quadric.ellipsoid(3, 1, F(1, 2)),
        Quadric.sphere(2),
        "x^2/9 + y^2 + 4z^2 = 1 and x^2 + y^2 + z^2 = 4",
    ),
    "two curves [(11)11]_3": (
        Quadric.ellipsoid(3, 1, 1),
        Quadric.sphere(2),
        "x^2/9 + y^2 + z^2 = 1 and x^2 + y^2 + z^2 = 4",
    ),
    "curve and isolated tangent point [211]_3": (
        Quadric.ellipsoid(3, 1, F(1, 2)),
        Quadric.sphere(2, (-1, 0, 0)),
        "x^2/9 + y^2 + 4z^2 = 1 and the sphere of radius 2 centred at (-1, 0, 0)",
    ),
    "curve and isolated tangent point [2(11)]_2": (
        Quadric.ellipsoid(3, 1, 1),
        Quadric.sphere(2, (-1, 0, 0)),
        "x^2/9 + y^2 + z^2 = 1 and the sphere of radius 2 centred at (-1, 0, 0)",
    ),
}


def corollary_10(E: Quadric, Q: Quadric) -> bool:
    _, d3, d4 = characteristic_polynomial(E, Q).deltas()
    return d4 < 0 or (d4 == 0 and d3 < 0)


def _case(key: str) -> str:
    E, Q, what = CASES[key]
    expected_contact, expected_segre = key.rsplit(" ", 1)
    kind = contact_type(E, Q)
    ensure(kind == expected_contact, f"{what}: {kind}")
    computed = show_segre(segre(E, Q))
    ensure(computed == expected_segre, f"{what}: Segre {computed}")
    ensure(characteristic_polynomial(E, Q).structure.all_real, f"{what}: real roots")
    ensure(not smallness(E, Q).small, f"{what}: E is not small")
    ensure(not corollary_10(E, Q), f"{what}: Corollary 10's test would report contact")
    return f"{what}: {kind}, {computed}"


@proof.check(
    "two curves with Segre types [1111]_4 and [(11)11]_3 (four real roots)", method=Method.CONSTRUCTION
)
def two_curves() -> Finding:
    found = [_case(k) for k in CASES if k.startswith("two curves")]
    return agrees(
        "; ".join(found) + ": E is not small, the roots are real and Corollary 10 says 'no transversal "
        "contact' although the surfaces cross"
    )


@proof.check(
    "a curve and an isolated tangent point: [211]_3 and [2(11)]_2 (real roots)", method=Method.CONSTRUCTION
)
def curve_and_point() -> Finding:
    found = [_case(k) for k in CASES if k.startswith("curve and")]
    return agrees("; ".join(found) + ": not small, real roots, the surfaces cross (Lemma 8's excluded case)")


@proof.check(
    "non-real roots imply points of E on both sides of Q: the identities of the argument",
    method=Method.IDENTITY,
)
def nonreal_means_crossing() -> Finding:
    m11, m12, m22, e, f, h, q, q1, q2 = sp.symbols("m11 m12 m22 e f h q q1 q2", real=True)
    lam = sp.Symbol("lambda")
    M = sp.Matrix([[m11, m12], [m12, m22]])
    ensure(
        sp.expand((sp.Matrix([[1, -sp.I]]) * M * sp.Matrix([1, sp.I]))[0, 0] - (m11 + m22)) == 0,
        "(1, -i) M (1, i)^T = trace M",
    )
    ensure(sp.expand(sp.Matrix([[e, f], [f, -e]]).det() + e**2 + f**2) == 0, "det of a trace-free E2")
    pencil = lam * sp.Matrix([[0, h], [h, 0]]) + sp.Matrix([[q1, q], [q, q2]])
    ensure(sp.expand(pencil.det() - (q1 * q2 - (h * lam + q) ** 2)) == 0, "the pencil in an isotropic basis")
    # (h mu + q)^2 = q1 q2 with h mu + q non-real (h != 0, mu non-real): a negative real square.
    a, b = sp.symbols("a b", real=True)
    ensure(sp.im(sp.expand((a + sp.I * b) ** 2)) == 2 * a * b, "a non-real number with a real square")
    return agrees(
        "(1, -i) M (1, i)^T = trace M, det [[e, f], [f, -e]] = -(e^2 + f^2), det(l [[0, h], [h, 0]] + Q2) = "
        "q1 q2 - (h l + q)^2: a non-real root mu makes (h mu + q)^2 = q1 q2 the square of a non-real number "
        "whose square is real, i.e. of a non-zero imaginary one, so Q(u1) Q(u2) = q1 q2 < 0"
    )


@proof.check(
    "the argument carried out exactly on Example 11: two points of E on opposite sides of Q",
    method=Method.CONSTRUCTION,
)
def nonreal_points_example_11() -> Finding:
    E = Quadric.from_equation(paper.PRINTED["Example 11 E"]).to_sympy()
    Q = Quadric.from_equation(paper.PRINTED["Example 11 Q"]).to_sympy()
    lam = sp.Symbol("lambda")
    roots = sp.roots(sp.Poly((lam * E + Q).det(), lam))
    mu = next(r for r in roots if sp.im(r) > 0)
    kernel = (mu * E + Q).nullspace(simplify=True)
    ensure(len(kernel) == 1, "a simple non-real root")
    v = kernel[0].applyfunc(sp.expand)
    x, y = v.applyfunc(sp.re), v.applyfunc(sp.im)
    B = sp.Matrix.hstack(x, y)
    ensure(B.rank() == 2, "(i) x and y are independent")
    E2, Q2 = (B.T * E * B).applyfunc(sp.simplify), (B.T * Q * B).applyfunc(sp.simplify)
    ensure(sp.simplify(E2.trace()) == 0 and sp.simplify(Q2.trace()) == 0, "(ii) trace-free")
    e, f = E2[0, 0], E2[0, 1]
    ensure(sp.simplify(e**2 + f**2) != 0, "(iii) E2 != 0")
    rho = sp.sqrt(e**2 + f**2)
    if e != 0:
        directions = [sp.Matrix([f - s * rho, -e]) for s in (1, -1)]
    else:
        directions = [sp.Matrix([1, 0]), sp.Matrix([0, 1])]
    values, points = [], []
    for d in directions:
        u = (B * d).applyfunc(sp.simplify)
        ensure(sp.simplify((u.T * E * u)[0, 0]) == 0, "u is E-isotropic")
        ensure(u[3] != 0, "(v) a point of the affine surface")
        point = tuple(sp.simplify(u[i] / u[3]) for i in range(3))
        values.append(sp.simplify((u.T * Q * u)[0, 0] / u[3] ** 2))
        points.append(point)
    ensure(values[0] * values[1] < 0, f"(iv) opposite signs: {values}")
    return agrees(
        f"mu = {mu}: the points {points[0]} and {points[1]} of E give Q = {values[0]} and {values[1]}"
    )


def on_sphere(s: Fraction, t: Fraction, pole: int) -> tuple[Fraction, Fraction, Fraction]:
    """The rational point of the unit sphere with stereographic coordinates (s, t) from the pole +-z."""
    d = s * s + t * t + 1
    return (2 * s / d, 2 * t / d, pole * (s * s + t * t - 1) / d)


def extreme_points(M: np.ndarray, b: np.ndarray, k: float) -> list[np.ndarray]:
    """Approximate minimiser and maximiser of u^T M u + 2 b.u + k on the unit sphere (a float search;
    only its rounding to rational points is used, and those are checked exactly)."""
    rng = np.random.default_rng(0)
    u = rng.normal(size=(5000, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    values = np.einsum("ij,jk,ik->i", u, M, u) + 2 * u @ b + k
    step = 0.5 / (np.linalg.norm(M, 2) + np.linalg.norm(b) + 1e-300)
    out = []
    for sign in (1.0, -1.0):
        for start in np.argsort(sign * values)[:3]:
            v = u[start].copy()
            out.append(v.copy())
            for _ in range(200):  # projected gradient steps
                g = sign * (2 * M @ v + 2 * b)
                v = v - step * (g - (g @ v) * v)
                v /= np.linalg.norm(v)
            out.append(v)
    return out


def rational_points_near(v: np.ndarray) -> list[tuple[Fraction, Fraction, Fraction]]:
    """Rational points of the unit sphere close to the unit vector v (several precisions)."""
    pole = -1 if v[2] > 0 else 1  # project from the pole far from v
    s, t = v[0] / (1 - pole * v[2]), v[1] / (1 - pole * v[2])
    return [
        on_sphere(Fraction(s).limit_denominator(10**k), Fraction(t).limit_denominator(10**k), pole)
        for k in (2, 4, 6, 9)
    ]


@proof.search(
    "the package's characteristic polynomial: non-real roots come with points of E on both sides of Q",
    examples=0,
    large=1000,
    detail="exact rational points near the extremes of Q on E",
    method=Method.CROSS_CHECK,
)
def crossing_cross_check(examples: int) -> Finding:
    from hypothesis import given
    from hypothesis import strategies as st

    from quadric_contact.testing.strategies import quadrics, rotations

    seen = {"non-real": 0, "real": 0}
    axis = st.fractions(F(1, 4), 3, max_denominator=6)
    coord = st.fractions(-6, 6, max_denominator=4)

    @search_settings(examples)
    @given(
        axes=st.tuples(axis, axis, axis),
        rot=rotations(),
        centre=st.tuples(coord, coord, coord),
        q=quadrics(moved=True, bound=4),
    )
    def search(axes: tuple, rot: tuple, centre: tuple, q: Quadric) -> None:
        E = Quadric.ellipsoid(*axes, center=centre, rotation=rot)
        P = characteristic_polynomial(E, q)
        if P.structure.all_real:
            seen["real"] += 1
            return
        seen["non-real"] += 1
        # E = centre + R diag(axes) u, |u| = 1: Q(u) = u^T M u + 2 b.u + k; look for both signs exactly.
        R = [[Fraction(v) for v in row] for row in rot]
        D = [[R[i][j] * axes[j] for j in range(3)] for i in range(3)]

        def point(u: tuple[Fraction, ...]) -> tuple[Fraction, ...]:
            return tuple(centre[i] + sum(D[i][j] * u[j] for j in range(3)) for i in range(3))

        Qm = np.array([[float(v) for v in row] for row in q.matrix])
        Dm = np.array([[float(v) for v in row] for row in D])
        cm = np.array([float(v) for v in centre])
        A, bq = Qm[:3, :3], Qm[:3, 3]
        M = Dm.T @ A @ Dm
        b = Dm.T @ (A @ cm + bq)
        k = cm @ A @ cm + 2 * bq @ cm + Qm[3, 3]
        signs = set()
        for v in extreme_points(M, b, k):
            for u in rational_points_near(v):
                value = q.value_at(point(u))
                signs.add((value > 0) - (value < 0))
        ensure({1, -1} <= signs, f"no sign change found on E for a pencil with non-real roots: {E}, {q}")

    search()
    ensure(seen["non-real"] > 20, f"enough pencils with non-real roots: {seen}")
    return agrees(
        f"{seen['non-real']} pencils with non-real roots: each ellipsoid has points on both sides of Q"
    )
