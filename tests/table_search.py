"""Placements for searching Tables 1 and 2 for counterexamples (tests and benchmarks).

The adversarial placements are the ones the proof of Lemma 3 uses: ``E``
touching ``Q`` at a vertex (where the principal curvatures of ``Q`` are
extreme) with its axes along the principal directions there, then pushed a
little across the surface; and ``E`` centred at the centre of ``Q`` with its
axes along those of ``Q`` (the size conditions).  Random rational placements
near a rational point of ``Q`` complete them.  Everything is exact: signed
permutation matrices, rational points of the standard surfaces, and the
exact geometric decision to count the intersection curves.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction
from itertools import permutations, product

from quadric_contact import Quadric, QuadricKind, characteristic_polynomial
from quadric_contact.model.motions import RigidMotion
from quadric_contact.theory.geometric import GeometricDecision, decide_geometrically

F = Fraction
K = QuadricKind

# Vertices of the standard forms: (point, unit normal axis index, sign).
_AXES = ((1, 0, 0), (0, 1, 0), (0, 0, 1))


def vertices(kind: QuadricKind, p: dict[str, Fraction]) -> list[tuple[tuple[Fraction, ...], int, int]]:
    a, b, c = p.get("a"), p.get("b"), p.get("c")
    z = F(0)
    if kind is K.ELLIPSOID:
        return [((a, z, z), 0, 1), ((z, b, z), 1, 1), ((z, z, c), 2, 1), ((-a, z, z), 0, -1)]
    if kind is K.HYPERBOLOID_ONE_SHEET:
        return [((a, z, z), 0, 1), ((z, b, z), 1, 1)]
    if kind is K.HYPERBOLOID_TWO_SHEETS:
        return [((z, z, c), 2, 1), ((z, z, -c), 2, -1)]
    if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID, K.PARABOLIC_CYLINDER):
        return [((z, z, z), 2, 1)]
    if kind is K.ELLIPTIC_CYLINDER:
        return [((a, z, z), 0, 1), ((z, b, z), 1, 1)]
    if kind is K.HYPERBOLIC_CYLINDER:
        return [((a, z, z), 0, 1), ((-a, z, z), 0, -1)]
    return [((a, z, z), 0, 1), ((-a, z, z), 0, -1)]  # parallel planes


def _rotation_taking(axes_to: tuple[int, int, int], signs: tuple[int, int, int]) -> RigidMotion | None:
    """The signed permutation sending E's axis i (semi-axis order of the
    ellipsoid constructor) to coordinate axis axes_to[i] with sign signs[i],
    if it is a rotation."""
    R = [[F(0)] * 3 for _ in range(3)]
    for i, (j, s) in enumerate(zip(axes_to, signs, strict=True)):
        R[j][i] = F(s)
    det = (
        R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1])
        - R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0])
        + R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0])
    )
    if det != 1:
        return None
    return RigidMotion.from_matrix(R)


def _aligned_rotations() -> list[RigidMotion]:
    out = []
    for perm in permutations(range(3)):
        for signs in product((1, -1), repeat=3):
            m = _rotation_taking(perm, signs)  # type: ignore[arg-type]
            if m is not None and all(s == 1 for s in signs[:2]):
                out.append(m)
    return out


ALIGNED = _aligned_rotations()


@dataclass(frozen=True)
class Placement:
    E: Quadric
    description: str


def adversarial_placements(
    kind: QuadricKind,
    params: dict[str, Fraction],
    axes: tuple[Fraction, Fraction, Fraction],
    *,
    thorough: bool = True,
) -> Iterator[Placement]:
    """E (semi-axes ``axes``) touching Q at each vertex with each aligned
    orientation, from both sides, pushed across or set back by several depths;
    then centred at Q's centre in each aligned orientation.  ``thorough=False``
    keeps two vertices and three depths (for the default test run)."""
    al = max(axes)
    vs = vertices(kind, params)
    for point, n_axis, n_sign in vs if thorough else vs[:2]:
        for m in ALIGNED:
            R = m.rotation
            # semi-axis of E along the normal axis: column index with R[n_axis][i] != 0
            i = next(k for k in range(3) if R[n_axis][k] != 0)
            s_n = axes[i]
            for side in (1, -1):
                # depth > 0: E crosses the surface by depth at the vertex; depth < 0: E is
                # set back from it (lobes of E around the vertex may still cross)
                # (the lobes that cross near the boundary of the curvature condition are
                # shallow: set-backs down to 1e-6 of the semi-axis)
                depths = (
                    (s_n / 20, s_n / 3, *(-s_n / 4 / 10**k for k in range(7)))
                    if thorough
                    else (s_n / 20, -s_n / 40, -s_n / 4000)
                )
                for depth in depths:
                    offset = side * n_sign * (s_n - depth)
                    center = list(point)
                    center[n_axis] += offset
                    e = Quadric.ellipsoid(*axes).moved(RigidMotion(R, tuple(center)))
                    # a small generic perturbation (rotation moving E's ends by ~|depth|/25,
                    # shift ~|depth|/100) makes the critical points non-degenerate so that
                    # curves are counted, without closing the lobes
                    nq = int(200 * al / abs(depth)) + 1
                    wiggle = RigidMotion.from_translation(center) @ RigidMotion.from_quaternion(nq, 1, 2, 3)
                    wiggle = wiggle @ RigidMotion.from_translation([-v for v in center])
                    nudge = RigidMotion.from_translation((depth / 97, depth / 89, depth / 83))
                    yield Placement(
                        e.moved(nudge @ wiggle),
                        f"vertex {point}, side {side}, depth {depth}, axes {m.rotation}",
                    )
    for m in ALIGNED:
        for shift in (F(0), al / 3):
            e = Quadric.ellipsoid(*axes).moved(RigidMotion(m.rotation, (shift, F(0), F(0))))
            wiggle = RigidMotion.from_quaternion(200, 1, 2, 3, (al / 97, al / 89, al / 83))
            yield Placement(e.moved(wiggle), f"centre + ({shift}, 0, 0), axes {m.rotation}")


def corollary_10_says_transversal(e: Quadric, q: Quadric) -> bool:
    """Corollary 10 as printed: Delta_4 < 0, or Delta_4 = 0 and Delta_3 < 0."""
    _, s3, s4 = characteristic_polynomial(e, q).delta_signs()
    return s4 < 0 or (s4 == 0 and s3 < 0)


@dataclass(frozen=True)
class Finding:
    placement: Placement
    geometric: GeometricDecision
    corollary_10: bool

    @property
    def two_curves(self) -> bool:
        return self.geometric.curves == 2

    @property
    def corollary_10_wrong(self) -> bool:
        return self.corollary_10 != self.geometric.transversal


def examine(placement: Placement, q: Quadric) -> Finding:
    g = decide_geometrically(placement.E, q)
    return Finding(placement, g, corollary_10_says_transversal(placement.E, q))


def first_two_curve_placement(
    kind: QuadricKind,
    params: dict[str, Fraction],
    axes: tuple[Fraction, Fraction, Fraction],
    *,
    thorough: bool = True,
) -> Finding | None:
    q = Quadric.standard(kind, **params)
    for pl in adversarial_placements(kind, params, axes, thorough=thorough):
        f = examine(pl, q)
        if f.two_curves:
            return f
    return None
