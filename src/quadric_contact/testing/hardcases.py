"""Hard cases for the number modes, built from exact constructions.

Every case is a pair ``(E, Q)`` of exact rational matrices with what the
construction intends (contact or not, which region) and how it is fed to the
predicates: as exact rationals, or as their binary64 rounding (then the
answer that counts is the exact one *for the rounded matrices*, which the
fixture generator computes with the exact scalar path; near tangency the
rounding itself may move the configuration to the other side).

Families
--------
``ladder``
    For every type of Table 1 and the plane, a small ellipsoid (semi-axes 1/4
    along the normal, 1/8 across: far more curved than ``Q``, so the contact is
    a single point and it is small with respect to ``Q``) touching ``Q`` at a
    vertex from the ``R-`` side and from the ``R+`` side, then moved along the
    normal by ``d = 10^-2 .. 10^-16`` away (no contact) or into ``Q``
    (transversal contact), and the exact tangency ``d = 0``; everything moved
    by one rational rigid motion (quaternion ``(2, -1, 3, 1)``, translation
    ``(1/3, -2/7, 5/11)``) and rounded to binary64.
``ladder-exact``
    The same for ``d = 10^-8`` and ``10^-16``, fed as exact rationals.
``huge-offset``
    The ladder for five types, translated by ``(10^6, -10^6, 10^6)``.
``thin`` / ``nearly-spherical``
    The ladder with a needle ellipsoid (axis ratio ``10^-4``) or with
    semi-axes ``1/4 (1, 1 + 10^-12, 1 - 10^-12)``.
``dyadic-tangent``
    Exact tangencies (and ``d = 2^-10, 2^-15, 2^-20``) with power-of-two
    parameters, moved by a dyadic affine map (shears and a translation with
    dyadic entries): binary64 holds every entry exactly, the pencil roots are
    those of the untransformed pair (``det(H)^2`` is a positive factor), and
    contact and regions are affine invariants; the cylinders, parallel planes
    and planes carry their structural zeros ``c0 = 0`` (and ``c1 = 0``) exactly.
``example-11``
    Example 11 (``Delta_4 = 0``, ``Delta_3 < 0``) and four dyadic affine images.
``delta4-zero``
    Pairs with the same quadratic part (``Delta_4 = 0`` identically): the bee
    and the crown ``S1`` of Example 17, a small sphere near a large one (inside
    and outside, 8 distances each way), and an ellipsoid near a larger copy of
    itself (rotated by the rational rotation: both roundings of the quadratic
    part are the same floats, so ``Delta_4 = 0`` for the rounded input too).
``near-degenerate``
    Example 6's matrices (the printed decimals) and quadrics within ``10^-8 ..
    10^-16`` of a cylinder, a plane and a cone.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.motions import RigidMotion, rotation_from_quaternion
from quadric_contact.model.quadric import Quadric

__all__ = ["FAMILIES", "HardCase", "hard_cases"]

K = QuadricKind
F = Fraction

ROTATION = rotation_from_quaternion(2, -1, 3, 1)
TRANSLATION = (F(1, 3), F(-2, 7), F(5, 11))
HUGE_TRANSLATION = (F(10**6), F(-(10**6)), F(10**6))
DISTANCES = tuple(F(1, 10**k) for k in range(2, 17))
SHORT_DISTANCES = tuple(F(1, 10**k) for k in (2, 4, 6, 8, 10, 12))


@dataclass(frozen=True)
class HardCase:
    """One pair of the hard-case suite.

    Attributes
    ----------
    id, family, description : str
    E, Q : tuple of Fraction
        The ten upper entries of the exact constructions.
    exact_input : bool
        Fed as exact rationals (True) or as their binary64 rounding (False).
    intended_contact, intended_region : bool / str or None
        What the construction intends for the exact matrices.
    kind : str
        Type of ``Q`` (of the exact construction).
    distance, direction, side : str or None
        Ladder coordinates: ``"1e-7"``, ``"away"``/``"into"``/``"tangent"``, ``"R-"``/``"R+"``.
    geometry : dict or None
        Semi-axes, rotation and centre of ``E`` (and of ``Q`` when it is an
        ellipsoid), for peers that take shapes rather than matrices.
    """

    id: str
    family: str
    description: str
    E: tuple[Fraction, ...]
    Q: tuple[Fraction, ...]
    exact_input: bool
    intended_contact: bool | None
    intended_region: str | None
    kind: str
    distance: str | None = None
    direction: str | None = None
    side: str | None = None
    geometry: dict[str, Any] | None = field(default=None, compare=False)

    def matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """The input as the predicates receive it: ``(4, 4)`` float64 arrays (rounded) or
        object arrays of Fractions."""
        return _full(self.E, self.exact_input), _full(self.Q, self.exact_input)

    def input_quadrics(self) -> tuple[Quadric, Quadric]:
        """The input as exact :class:`Quadric` objects (the binary64 rounding, taken exactly,
        for float input)."""
        e, q = self.matrices()
        return Quadric.from_matrix(e), Quadric.from_matrix(q)

    @property
    def rounding_is_exact(self) -> bool:
        """True when binary64 holds every entry exactly (the input is the construction)."""
        return all(F(float(v)) == v for v in self.E + self.Q)


def _full(upper: Sequence[Fraction], exact: bool) -> np.ndarray:
    m = np.empty((4, 4), dtype=object if exact else np.float64)
    for (i, j), v in zip(ENTRY_INDICES, upper, strict=True):
        m[i, j] = m[j, i] = v if exact else float(v)
    return m


# -- the ladder ------------------------------------------------------------------------


def _at_vertex(q: Quadric, vertex: tuple[int, int, int]) -> tuple[Quadric, tuple[int, int, int], int, int]:
    """``(Q, vertex, axis, plus)``: the axis of the normal at ``vertex`` and the direction
    of ``R+`` along it, read off the gradient of ``X^T Q X`` there (exactly one
    coordinate of it is non-zero at these vertices)."""
    if q.value_at(vertex) != 0:
        raise ValueError(f"{vertex} is not on {q}")
    X = (*(F(v) for v in vertex), F(1))
    grad = [2 * sum((q.matrix[i][j] * X[j] for j in range(4)), F(0)) for i in range(3)]
    axes = [i for i in range(3) if grad[i] != 0]
    if len(axes) != 1:
        raise ValueError(f"the normal of {q} at {vertex} is not along an axis: {grad}")
    return q, vertex, axes[0], 1 if grad[axes[0]] > 0 else -1


# kind: (Q, vertex, axis of the normal, direction of R+ along it), the last two derived
_LADDER_Q: dict[QuadricKind, tuple[Quadric, tuple[int, int, int], int, int]] = {
    K.ELLIPSOID: _at_vertex(Quadric.ellipsoid(4, 3, 2), (0, 0, 2)),
    K.HYPERBOLOID_ONE_SHEET: _at_vertex(Quadric.hyperboloid_one_sheet(2, 3, 2), (2, 0, 0)),
    K.HYPERBOLOID_TWO_SHEETS: _at_vertex(Quadric.hyperboloid_two_sheets(3, 2, 2), (0, 0, 2)),
    K.ELLIPTIC_PARABOLOID: _at_vertex(Quadric.elliptic_paraboloid(3, 2), (0, 0, 0)),
    K.HYPERBOLIC_PARABOLOID: _at_vertex(Quadric.hyperbolic_paraboloid(3, 2), (0, 0, 0)),
    K.ELLIPTIC_CYLINDER: _at_vertex(Quadric.elliptic_cylinder(3, 2), (3, 0, 0)),
    K.HYPERBOLIC_CYLINDER: _at_vertex(Quadric.hyperbolic_cylinder(3, 2), (3, 0, 0)),
    K.PARABOLIC_CYLINDER: _at_vertex(Quadric.parabolic_cylinder(3), (0, 0, 0)),
    K.PARALLEL_PLANES: _at_vertex(Quadric.parallel_planes(3), (3, 0, 0)),
    K.PLANE: _at_vertex(Quadric.plane((0, 0, 1), 0), (0, 0, 0)),
}

# The same with power-of-two parameters (for the dyadic family).
_DYADIC_Q: dict[QuadricKind, tuple[Quadric, tuple[int, int, int], int, int]] = {
    K.ELLIPSOID: _at_vertex(Quadric.ellipsoid(4, 2, 2), (0, 0, 2)),
    K.HYPERBOLOID_ONE_SHEET: _at_vertex(Quadric.hyperboloid_one_sheet(2, 4, 2), (2, 0, 0)),
    K.HYPERBOLOID_TWO_SHEETS: _at_vertex(Quadric.hyperboloid_two_sheets(4, 2, 2), (0, 0, 2)),
    K.ELLIPTIC_PARABOLOID: _at_vertex(Quadric.elliptic_paraboloid(4, 2), (0, 0, 0)),
    K.HYPERBOLIC_PARABOLOID: _at_vertex(Quadric.hyperbolic_paraboloid(4, 2), (0, 0, 0)),
    K.ELLIPTIC_CYLINDER: _at_vertex(Quadric.elliptic_cylinder(4, 2), (4, 0, 0)),
    K.HYPERBOLIC_CYLINDER: _at_vertex(Quadric.hyperbolic_cylinder(4, 2), (4, 0, 0)),
    K.PARABOLIC_CYLINDER: _at_vertex(Quadric.parabolic_cylinder(4), (0, 0, 0)),
    K.PARALLEL_PLANES: _at_vertex(Quadric.parallel_planes(4), (4, 0, 0)),
    K.PLANE: _at_vertex(Quadric.plane((0, 0, 1), 0), (0, 0, 0)),
}

_G = F(1, 4)  # semi-axis of E along the normal
_H = F(1, 8)  # across


def _probe(
    table: dict[QuadricKind, tuple[Quadric, tuple[int, int, int], int, int]],
    kind: QuadricKind,
    side: str,
    shift: Fraction,
    axes: tuple[Fraction, Fraction, Fraction] | None = None,
) -> tuple[Quadric, Quadric, tuple[Fraction, ...], tuple[Fraction, ...]]:
    """``(E, Q, axes, centre)``: ``E`` on the ``side`` of ``Q``, its surface ``shift`` away from
    tangency along the normal (negative: into ``Q``)."""
    q, vertex, axis, plus = table[kind]
    g, h1, h2 = axes if axes is not None else (_G, _H, _H)
    semi = [h1, h2]
    semi.insert(axis, g)
    direction = plus if side == "R+" else -plus
    center = [F(v) for v in vertex]
    center[axis] += direction * (g + shift)
    e = Quadric.ellipsoid(semi[0], semi[1], semi[2], center=center)
    return e, q, tuple(semi), tuple(center)


def _motion(translation: Sequence[Fraction]) -> RigidMotion:
    tx, ty, tz = translation
    return RigidMotion(ROTATION, (F(tx), F(ty), F(tz)))


def _geometry(
    axes: Sequence[Fraction], center: Sequence[Fraction], motion: RigidMotion | None
) -> dict[str, Any]:
    R = ROTATION if motion is not None else ((1, 0, 0), (0, 1, 0), (0, 0, 1))
    c = [F(v) for v in center]
    if motion is not None:
        c = [sum((R[i][k] * c[k] for k in range(3)), F(0)) + motion.translation[i] for i in range(3)]
    return {
        "axes": [float(a) for a in axes],
        "rotation": [[float(v) for v in row] for row in R],
        "center": [float(v) for v in c],
    }


def _region_of(side: str, direction: str) -> tuple[bool, str]:
    if direction == "into":
        return True, "contact"
    return False, side


def _ladder_family(
    family: str,
    kinds: Sequence[QuadricKind],
    distances: Sequence[Fraction],
    translation: Sequence[Fraction],
    *,
    axes: tuple[Fraction, Fraction, Fraction] | None = None,
    tangent: bool = True,
    exact_input: bool = False,
    note: str = "",
) -> Iterator[HardCase]:
    motion = _motion(translation)
    for kind in kinds:
        for side in ("R-", "R+"):
            steps: list[tuple[Fraction, str]] = [(F(0), "tangent")] if tangent else []
            for d in distances:
                steps += [(d, "away"), (-d, "into")]
            for shift, direction in steps:
                e, q, semi, center = _probe(_LADDER_Q, kind, side, shift, axes)
                e, q = e.moved(motion), q.moved(motion)
                contact, region = _region_of(side, direction)
                dist = "0" if shift == 0 else f"1e-{len(str(abs(shift).denominator)) - 1}"
                geometry = {"E": _geometry(semi, center, motion)}
                if kind is K.ELLIPSOID:
                    geometry["Q"] = _geometry((F(4), F(3), F(2)), (F(0), F(0), F(0)), motion)
                yield HardCase(
                    id=f"{family}/{kind.name.lower()}/{side}/{direction}/{dist}",
                    family=family,
                    description=f"{kind.value}, ellipsoid on the {side} side, "
                    + ("exactly tangent" if direction == "tangent" else f"{direction} by {dist}")
                    + note,
                    E=e.upper,
                    Q=q.upper,
                    exact_input=exact_input,
                    intended_contact=contact,
                    intended_region=region,
                    kind=kind.value,
                    distance=dist,
                    direction=direction,
                    side=side,
                    geometry=geometry,
                )


# -- dyadic affine images ---------------------------------------------------------------------


Affine = tuple[tuple[tuple[Fraction, ...], ...], tuple[Fraction, ...]]


def _dyadic_affine(variant: int = 0) -> Affine:
    """An affine map ``x -> L x + t`` with dyadic ``L`` (a product of shears, det 1, so
    ``L^-1`` is dyadic too) and dyadic ``t``."""
    shears: list[tuple[tuple[Any, ...], ...]] = [
        ((1, F(1, 2), 0), (0, 1, 0), (0, 0, 1)),
        ((1, 0, 0), (F(-3, 4), 1, 0), (0, 0, 1)),
        ((1, 0, 0), (0, 1, 0), (F(1, 4), F(5, 8), 1)),
        ((1, 0, F(-1, 8)), (0, 1, F(3, 8)), (0, 0, 1)),
    ]
    order = [shears[(variant + k) % 4] for k in range(4)]
    L: list[list[Fraction]] = [[F(int(i == j)) for j in range(3)] for i in range(3)]
    for S in order:
        L = [[sum((F(L[i][k]) * F(S[k][j]) for k in range(3)), F(0)) for j in range(3)] for i in range(3)]
    t = [(F(3, 8), F(-5, 4), F(7, 16)), (F(-1, 2), F(1, 16), F(9, 4))][variant % 2]
    return tuple(tuple(r) for r in L), tuple(t)


def _affine_image(q: Quadric, affine: Affine) -> Quadric:
    """``H^-T Q H^-1`` for the affine map ``H: x -> L x + t`` (exact): the image of the quadric."""
    import sympy  # sympy is heavy: only to build these cases

    L, t = affine
    Lm = sympy.Matrix(3, 3, lambda i, j: sympy.Rational(F(L[i][j]).numerator, F(L[i][j]).denominator))
    Li = Lm.inv()
    tv = sympy.Matrix([sympy.Rational(F(v).numerator, F(v).denominator) for v in t])
    Hinv = sympy.zeros(4, 4)
    Hinv[:3, :3] = Li
    Hinv[:3, 3] = -Li * tv
    Hinv[3, 3] = 1
    M = Hinv.T * q.to_sympy() * Hinv
    return Quadric.from_matrix([[F(int(M[i, j].p), int(M[i, j].q)) for j in range(4)] for i in range(4)])


def _dyadic_family() -> Iterator[HardCase]:
    for variant, kind in enumerate(_DYADIC_Q):
        motion = _dyadic_affine(variant)
        for side in ("R-", "R+"):
            steps = [(F(0), "tangent")]
            for k in (10, 15, 20):
                steps += [(F(1, 2**k), "away"), (-F(1, 2**k), "into")]
            for shift, direction in steps:
                e, q, _, _ = _probe(_DYADIC_Q, kind, side, shift)
                e, q = _affine_image(e, motion), _affine_image(q, motion)
                contact, region = _region_of(side, direction)
                dist = "0" if shift == 0 else f"2^-{abs(shift).denominator.bit_length() - 1}"
                case = HardCase(
                    id=f"dyadic-tangent/{kind.name.lower()}/{side}/{direction}/{dist}",
                    family="dyadic-tangent",
                    description=f"{kind.value}, {side} side, {direction} by {dist}, dyadic affine image "
                    "(binary64 holds it exactly)",
                    E=e.upper,
                    Q=q.upper,
                    exact_input=False,
                    intended_contact=contact,
                    intended_region=region,
                    kind=kind.value,
                    distance=dist,
                    direction=direction,
                    side=side,
                )
                if case.rounding_is_exact:
                    yield case


def _example_11() -> Iterator[HardCase]:
    e = Quadric.from_equation("2*x**2 + 2*y**2 + 3*z**2 - 1")
    q = Quadric.from_equation("x**2 + y**2 + 8*z")
    yield HardCase(
        "example-11/paper",
        "example-11",
        "Example 11: P = -(1 + 2 lambda)^2 (16 + 3 lambda^2), Delta_4 = 0, Delta_3 < 0",
        e.upper,
        q.upper,
        False,
        True,
        "contact",
        q.kind.value,
    )
    for variant in range(4):
        m = _dyadic_affine(variant)
        yield HardCase(
            f"example-11/affine-{variant}",
            "example-11",
            f"Example 11 moved by dyadic affine map {variant} (same pencil roots)",
            _affine_image(e, m).upper,
            _affine_image(q, m).upper,
            False,
            True,
            "contact",
            q.kind.value,
        )


def _delta4_zero() -> Iterator[HardCase]:
    bee = Quadric.from_equation("(x - 3)**2 + (y - 3)**2 + 3*(z - 5.5)**2 - 0.1")
    s1 = Quadric.from_equation("x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
    for exact in (False, True):
        yield HardCase(
            f"delta4-zero/bee-crown/{'exact' if exact else 'float'}",
            "delta4-zero",
            "Example 17: the bee against the crown S1 (same quadratic part diag(1, 1, 3))",
            bee.upper,
            s1.upper,
            exact,
            False,
            "R+",
            s1.kind.value,
        )
    # A sphere of radius 1/4 near a sphere of radius 2, both scaled to quadratic part I.
    big = Quadric.sphere(2).scaled(4)
    for side, base in (("R-", F(2) - F(1, 4)), ("R+", F(2) + F(1, 4))):
        for k in (2, 4, 6, 8, 10, 12, 14, 16):
            d = F(1, 10**k)
            for direction, shift in (("away", d), ("into", -d)):
                r = base - shift if side == "R-" else base + shift
                small = Quadric.sphere(F(1, 4), center=(r * F(3, 5), r * F(4, 5), 0)).scaled(F(1, 16))
                contact, region = _region_of(side, direction)
                yield HardCase(
                    f"delta4-zero/spheres/{side}/{direction}/1e-{k}",
                    "delta4-zero",
                    f"sphere of radius 1/4 {'inside' if side == 'R-' else 'outside'} a sphere of radius 2, "
                    f"{direction} from tangency by 1e-{k}",
                    small.upper,
                    big.upper,
                    False,
                    contact,
                    region,
                    big.kind.value,
                    f"1e-{k}",
                    direction,
                    side,
                )
    # An ellipsoid near a copy of itself three times as large, both rotated; the copy's
    # matrix is scaled by 9 so that the two quadratic parts are the same rationals.
    axes = (F(1, 2), F(1, 3), F(1, 4))
    big = Quadric.ellipsoid(3 * axes[0], 3 * axes[1], 3 * axes[2], rotation=ROTATION).scaled(9)
    for k in (3, 6, 9, 12, 15):
        d = F(1, 10**k)
        for side, direction, z in (
            ("R-", "away", 3 * axes[2] - axes[2] - d),
            ("R-", "into", 3 * axes[2] - axes[2] + d),
            ("R+", "away", 3 * axes[2] + axes[2] + d),
            ("R+", "into", 3 * axes[2] + axes[2] - d),
        ):
            center = [ROTATION[i][2] * z for i in range(3)]
            e = Quadric.ellipsoid(*axes, center=center, rotation=ROTATION)
            contact, region = _region_of(side, direction)
            yield HardCase(
                f"delta4-zero/copies/{side}/{direction}/1e-{k}",
                "delta4-zero",
                f"ellipsoid and its copy scaled by 3 (same quadratic part), {side} side, "
                f"{direction} by 1e-{k}",
                e.upper,
                big.upper,
                False,
                contact,
                region,
                big.kind.value,
                f"1e-{k}",
                direction,
                side,
            )


_EXAMPLE_6_Q = (
    ("-0.426777", "-0.800103", "0.176777", "-6.57593"),
    ("-0.800103", "0.5", "0.331414", "-1.16043"),
    ("0.176777", "0.331414", "-0.0732233", "1.64145"),
    ("-6.57593", "-1.16043", "1.64145", "-42.4962"),
)
_EXAMPLE_6_E = (
    ("1.82853", "0.58657", "0.000852152", "13.6556"),
    ("0.58657", "1.09505", "-0.242965", "8.48796"),
    ("0.000852152", "-0.242965", "1.83023", "3.48535"),
    ("13.6556", "8.48796", "3.48535", "131.077"),
)


def _near_degenerate() -> Iterator[HardCase]:
    e6 = Quadric.from_matrix(_EXAMPLE_6_E)
    q6 = Quadric.from_matrix(_EXAMPLE_6_Q)
    for exact in (False, True):
        yield HardCase(
            f"near-degenerate/example-6/{'exact' if exact else 'float'}",
            "near-degenerate",
            "Example 6: Q within 1.7e-7 of a hyperbolic paraboloid (printed decimals)",
            e6.upper,
            q6.upper,
            exact,
            None,
            None,
            q6.kind.value,
        )
    motion = _motion(TRANSLATION)
    probe = Quadric.ellipsoid(F(1, 4), F(1, 8), F(1, 8), center=(F(3, 2), F(1, 2), F(1, 3))).moved(motion)
    for k in (8, 12, 16):
        eps = F(1, 10**k)
        near = {
            "cylinder": Quadric.diagonal(F(1, 9), F(1, 4), eps, -1),
            "plane": Quadric.from_coefficients([[eps, 0, 0], [0, eps, 0], [0, 0, eps]], [0, 0, F(1, 2)], -1),
            "cone": Quadric.diagonal(1, 1, -1, -eps),
        }
        for name, q in near.items():
            q = q.moved(motion)
            yield HardCase(
                f"near-degenerate/{name}/1e-{k}",
                "near-degenerate",
                f"a quadric within 1e-{k} of a {name} (in the coefficients), and a small ellipsoid",
                probe.upper,
                q.upper,
                False,
                None,
                None,
                q.kind.value,
                f"1e-{k}",
            )


FAMILIES = (
    "ladder",
    "ladder-exact",
    "huge-offset",
    "thin",
    "nearly-spherical",
    "dyadic-tangent",
    "example-11",
    "delta4-zero",
    "near-degenerate",
)


def hard_cases(families: Sequence[str] = FAMILIES) -> list[HardCase]:
    """All hard cases of the given families (deterministic order)."""
    five = (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.ELLIPTIC_CYLINDER, K.PARALLEL_PLANES, K.PLANE)
    four = (K.ELLIPSOID, K.HYPERBOLOID_TWO_SHEETS, K.HYPERBOLIC_PARABOLOID, K.PLANE)
    makers = {
        "ladder": lambda: _ladder_family("ladder", list(_LADDER_Q), DISTANCES, TRANSLATION),
        "ladder-exact": lambda: _ladder_family(
            "ladder-exact", list(_LADDER_Q), (F(1, 10**8), F(1, 10**16)), TRANSLATION, exact_input=True
        ),
        "huge-offset": lambda: _ladder_family(
            "huge-offset", five, SHORT_DISTANCES, HUGE_TRANSLATION, note=", translated by 1e6"
        ),
        "thin": lambda: _ladder_family(
            "thin",
            four,
            SHORT_DISTANCES,
            TRANSLATION,
            axes=(_G, _G / 10**4, _G / 10**4),
            note=", needle 1e-4",
        ),
        "nearly-spherical": lambda: _ladder_family(
            "nearly-spherical",
            four,
            SHORT_DISTANCES,
            TRANSLATION,
            axes=(_G, _G * (1 + F(1, 10**12)), _G * (1 - F(1, 10**12))),
            note=", axes 1 +- 1e-12",
        ),
        "dyadic-tangent": _dyadic_family,
        "example-11": _example_11,
        "delta4-zero": _delta4_zero,
        "near-degenerate": _near_degenerate,
    }
    out: list[HardCase] = []
    for family in families:
        if family not in makers:
            raise ValueError(f"unknown family {family!r}; choose from {FAMILIES}")
        out.extend(makers[family]())
    return out
