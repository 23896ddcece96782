"""Remark 9: smallness cannot be dropped from Theorem 2; non-real roots always mean crossing.

Claim.  Without smallness, two intersection curves occur with Segre types
``[1111]_4`` and ``[(11)11]_3`` (four real roots), and a curve plus an
isolated tangent point with ``[211]_3`` and ``[2(11)]_2`` (real roots): so
Theorem 2 fails for non-small ellipsoids.  Conversely, non-real roots imply
transversal contact for any pair.

What is checked and how.  Exact constructions, each an ellipsoid that the
package's exact :func:`~quadric_contact.smallness.smallness` finds not small,
whose real intersection with ``Q`` (computed exactly, see ``_intersection``)
is two curves, respectively a curve and an isolated tangent point, with the
stated Segre characteristic; for each, Corollary 10's test (``Delta_4 < 0``, or
``Delta_4 = 0`` and ``Delta_3 < 0``) says "no transversal contact" although the
surfaces cross.  Evidence for the converse: 200 hypothesis examples of
ellipsoids (images of the unit sphere under rational affine maps, so that
their rational points are known) and Table 1 quadrics; whenever ``P`` has a
non-real root, two rational points of the ellipsoid on opposite sides of
``Q`` are found: a float search locates the minimum and maximum of ``Q`` on
the ellipsoid, nearby rational points of the unit sphere (stereographic
parametrisation) are mapped onto the ellipsoid and ``Q`` is evaluated there
exactly; 4000 examples in the slow profile.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric, characteristic_polynomial
from quadric_contact.proving import Finding, Method, Proof, agrees, ensure, search_settings
from quadric_contact.smallness import smallness
from quadric_contact.strategies import quadrics, rotations

from ._intersection import contact_type, segre, show_segre

proof = Proof("Remark 9", "without smallness Theorem 2 fails; non-real roots always mean crossing")

F = Fraction
EXAMPLES = 200

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
    "non-real roots imply points of E on both sides of Q",
    examples=EXAMPLES,
    large=4000,
    detail="exact rational points near the extremes of Q on E",
)
def nonreal_means_crossing(examples: int) -> Finding:
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
