"""Exact affine type of a real quadric, from invariants.

The type of ``X^T Q X = 0`` (``Q = [[A, b], [b^T, c]]``) is decided by the
inertia of the quadratic part ``A`` and of the whole matrix ``Q``.  Both are
exact: the characteristic polynomial of a symmetric rational matrix has
rational coefficients (sums of principal minors) and only real roots, so
Descartes' rule of signs counts its positive roots *exactly*.

The rules (``pA >= nA`` after replacing ``Q`` by ``-Q`` if needed; ``r`` is
a rank, ``(p, n)`` an inertia):

======  ======  ====================================================================
rank A  rank Q  type
======  ======  ====================================================================
3       4       A definite: ellipsoid if Q ~ (3,1), imaginary ellipsoid if (4,0);
                A indefinite: one-sheet hyperboloid if Q ~ (2,2), two sheets if (3,1)
3       3       imaginary cone (a point) if A definite, else cone
2       4       elliptic paraboloid if A definite on its range, else hyperbolic
2       3       A semidefinite: elliptic cylinder if Q ~ (2,1), imaginary if (3,0);
                else hyperbolic cylinder
2       2       imaginary intersecting planes (a line) if A semidefinite, else
                intersecting planes
1       3       parabolic cylinder
1       2       parallel planes if Q ~ (1,1), imaginary parallel planes if (2,0)
1       1       coincident planes
0       2       plane
0       1       empty (``c = 0`` with ``c != 0``)
0       0       the zero matrix (every point)
======  ======  ====================================================================
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from quadric_contact._generated.formulas import pencil_coefficients
from quadric_contact.exact.descartes import sign_variations

__all__ = [
    "NO_REAL_POINTS",
    "REFUSED_KINDS",
    "TABLE_1_KINDS",
    "Inertia",
    "QuadricKind",
    "classify",
    "inertia_from_minor_sums",
    "kind_from_inertia",
    "principal_minor_sums_3",
    "principal_minor_sums_4",
]


class QuadricKind(StrEnum):
    """Affine type of a real quadric ``X^T Q X = 0``.

    The nine types of Table 1 are the ``Q`` the theory covers
    (:attr:`in_table_1`); a plane is treated by Theorem 14; the others are
    excluded (:attr:`excluded_reason`) or have no real surface.

    Examples
    --------
    >>> QuadricKind("hyperboloid of one sheet").in_table_1
    True
    >>> QuadricKind.CONE.excluded_reason
    'a cone: no ellipsoid is small with respect to it (Section 2)'
    """

    ELLIPSOID = "ellipsoid"
    HYPERBOLOID_ONE_SHEET = "hyperboloid of one sheet"
    HYPERBOLOID_TWO_SHEETS = "hyperboloid of two sheets"
    ELLIPTIC_PARABOLOID = "elliptic paraboloid"
    HYPERBOLIC_PARABOLOID = "hyperbolic paraboloid"
    ELLIPTIC_CYLINDER = "elliptic cylinder"
    HYPERBOLIC_CYLINDER = "hyperbolic cylinder"
    PARABOLIC_CYLINDER = "parabolic cylinder"
    PARALLEL_PLANES = "parallel planes"
    PLANE = "plane"
    CONE = "cone"
    INTERSECTING_PLANES = "intersecting planes"
    COINCIDENT_PLANES = "coincident planes"
    IMAGINARY_ELLIPSOID = "imaginary ellipsoid"
    IMAGINARY_CONE = "imaginary cone"
    IMAGINARY_ELLIPTIC_CYLINDER = "imaginary elliptic cylinder"
    IMAGINARY_INTERSECTING_PLANES = "imaginary intersecting planes"
    IMAGINARY_PARALLEL_PLANES = "imaginary parallel planes"
    EMPTY = "empty"
    ZERO = "zero matrix"

    def __str__(self) -> str:
        return self.value

    @property
    def in_table_1(self) -> bool:
        """One of the nine types of the paper's Table 1 (the theory's ``Q``)."""
        return self in TABLE_1_KINDS

    @property
    def is_degenerate(self) -> bool:
        """``det Q = 0`` (cylinders, planes, cones, ...)."""
        return self not in _NONDEGENERATE

    @property
    def real_points(self) -> str:
        """What the real point set is, in words."""
        return _REAL_POINTS.get(self, "a surface")

    @property
    def excluded_reason(self) -> str | None:
        """Why the paper's theory (Theorem 2, Table 4) excludes this type, or None."""
        return _EXCLUDED.get(self)


TABLE_1_KINDS: tuple[QuadricKind, ...] = (
    QuadricKind.ELLIPSOID,
    QuadricKind.HYPERBOLOID_ONE_SHEET,
    QuadricKind.HYPERBOLOID_TWO_SHEETS,
    QuadricKind.ELLIPTIC_PARABOLOID,
    QuadricKind.HYPERBOLIC_PARABOLOID,
    QuadricKind.ELLIPTIC_CYLINDER,
    QuadricKind.HYPERBOLIC_CYLINDER,
    QuadricKind.PARABOLIC_CYLINDER,
    QuadricKind.PARALLEL_PLANES,
)

NO_REAL_POINTS: frozenset[QuadricKind] = frozenset(
    {
        QuadricKind.IMAGINARY_ELLIPSOID,
        QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER,
        QuadricKind.IMAGINARY_PARALLEL_PLANES,
        QuadricKind.EMPTY,
    }
)
"""Types without a real point: nothing to touch or cross.  ``X^T Q X`` keeps one sign on
all of space (the matrix is semidefinite, or a nonzero constant): an ellipsoid lies in
``R+`` when that sign is positive (:attr:`Quadric.canonical_sign` > 0), in ``R-``
otherwise.  (An imaginary cone is one real point and imaginary intersecting planes a
real line: an ellipsoid can touch them, so they are not here.)"""

REFUSED_KINDS: frozenset[QuadricKind] = frozenset({QuadricKind.COINCIDENT_PLANES, QuadricKind.ZERO})
"""Types no predicate answers for: a plane counted twice (``X^T Q X`` does not change sign
across it, so its sign cannot see a crossing; pass the plane itself) and the zero matrix."""


_NONDEGENERATE = {
    QuadricKind.ELLIPSOID,
    QuadricKind.HYPERBOLOID_ONE_SHEET,
    QuadricKind.HYPERBOLOID_TWO_SHEETS,
    QuadricKind.ELLIPTIC_PARABOLOID,
    QuadricKind.HYPERBOLIC_PARABOLOID,
    QuadricKind.IMAGINARY_ELLIPSOID,
}

_REAL_POINTS = {
    QuadricKind.IMAGINARY_ELLIPSOID: "no real points",
    QuadricKind.IMAGINARY_CONE: "a single point",
    QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER: "no real points",
    QuadricKind.IMAGINARY_INTERSECTING_PLANES: "a line",
    QuadricKind.IMAGINARY_PARALLEL_PLANES: "no real points",
    QuadricKind.EMPTY: "no points",
    QuadricKind.ZERO: "every point of space",
    QuadricKind.PLANE: "a plane",
    QuadricKind.COINCIDENT_PLANES: "a plane counted twice",
    QuadricKind.PARALLEL_PLANES: "two parallel planes",
    QuadricKind.INTERSECTING_PLANES: "two planes meeting in a line",
}

_EXCLUDED = {
    QuadricKind.CONE: "a cone: no ellipsoid is small with respect to it (Section 2)",
    QuadricKind.INTERSECTING_PLANES: (
        "intersecting planes: no ellipsoid is small with respect to them (Section 2)"
    ),
    QuadricKind.COINCIDENT_PLANES: (
        "coincident planes are excluded by the paper (Section 1); use the plane itself"
    ),
    QuadricKind.PLANE: "a plane is treated by Theorem 14 / Corollary 15 (use plane_side)",
    QuadricKind.IMAGINARY_ELLIPSOID: "an imaginary quadric has no real points",
    QuadricKind.IMAGINARY_CONE: "an imaginary cone is a single real point",
    QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER: "an imaginary quadric has no real points",
    QuadricKind.IMAGINARY_INTERSECTING_PLANES: "imaginary intersecting planes are a single real line",
    QuadricKind.IMAGINARY_PARALLEL_PLANES: "an imaginary quadric has no real points",
    QuadricKind.EMPTY: "the equation has no solutions",
    QuadricKind.ZERO: "the zero matrix is not a surface",
}


@dataclass(frozen=True)
class Inertia:
    """Numbers of positive, negative and zero eigenvalues of a symmetric matrix."""

    positive: int
    negative: int
    zero: int

    @property
    def rank(self) -> int:
        """Number of non-zero eigenvalues."""
        return self.positive + self.negative

    def flipped(self) -> Inertia:
        """The inertia of the negated matrix."""
        return Inertia(self.negative, self.positive, self.zero)


def principal_minor_sums_3(a: Sequence[Any]) -> tuple[Any, Any, Any]:
    """``(tr A, J, det A)`` for the symmetric 3x3 ``A``.

    Parameters
    ----------
    a : sequence of 6 numbers
        The upper entries ``(a00, a01, a02, a11, a12, a22)``.

    Returns
    -------
    tuple
        The trace, ``J`` (the paper's invariant: the sum of the principal 2x2
        minors, Section 2.4) and the determinant.

    Examples
    --------
    >>> principal_minor_sums_3((1, 0, 0, 1, 0, 3))   # the bee's x^2 + y^2 + 3 z^2
    (5, 7, 3)
    """
    a00, a01, a02, a11, a12, a22 = a
    tr = a00 + a11 + a22
    J = (a00 * a11 - a01 * a01) + (a00 * a22 - a02 * a02) + (a11 * a22 - a12 * a12)
    det = a00 * (a11 * a22 - a12 * a12) - a01 * (a01 * a22 - a12 * a02) + a02 * (a01 * a12 - a11 * a02)
    return tr, J, det


def principal_minor_sums_4(m: Sequence[Any]) -> tuple[Any, Any, Any, Any]:
    """``(E1, E2, E3, E4)``: sums of the principal minors of each order of the
    symmetric 4x4 matrix with upper entries ``m`` (``ENTRY_INDICES`` order).

    They are the coefficients of ``det(t*I + M) = t^4 + E1 t^3 + E2 t^2 + E3 t + E4``,
    computed with the generated pencil formula at ``E = I``.

    Parameters
    ----------
    m : sequence of 10 numbers
        The upper entries ``(q00, q01, q02, q03, q11, q12, q13, q22, q23, q33)``.

    Returns
    -------
    tuple
        ``(E1, E2, E3, E4)``; ``E4 = det M``.
    """
    one = m[0] * 0 + 1
    zero = m[0] * 0
    c0, c1, c2, c3, _ = pencil_coefficients(one, zero, zero, zero, one, zero, zero, one, zero, one, *m)
    return c3, c2, c1, c0


def inertia_from_minor_sums(sums: Sequence[Any]) -> Inertia:
    """Exact inertia of a symmetric ``n x n`` matrix from ``(E1, .., En)``.

    ``det(t I - M) = t^n - E1 t^(n-1) + E2 t^(n-2) - ...`` has only real
    roots, so Descartes' rule counts the positive eigenvalues exactly; the
    zero eigenvalues are the trailing zero coefficients.

    Parameters
    ----------
    sums : sequence
        ``(E1, .., En)``, the sums of the principal minors of each order.

    Returns
    -------
    Inertia

    Examples
    --------
    The hyperboloid ``x^2 + y^2 - z^2/4 - 1`` has a matrix of inertia (2, 2):

    >>> from quadric_contact import Quadric
    >>> upper = Quadric.from_equation("x**2 + y**2 - z**2/4 - 1").upper
    >>> inertia_from_minor_sums(principal_minor_sums_4(upper))
    Inertia(positive=2, negative=2, zero=0)
    """
    n = len(sums)
    rank = 0
    for k in range(n, 0, -1):
        if sums[k - 1] != 0:
            rank = k
            break
    charpoly = [1] + [(-1) ** k * sums[k - 1] for k in range(1, n + 1)]
    positive = sign_variations(charpoly)
    return Inertia(positive, rank - positive, n - rank)


def classify(m: Sequence[Any]) -> tuple[QuadricKind, int]:
    """Type of the quadric with upper entries ``m`` and its *canonical sign*.

    The canonical sign ``s`` is ``+1`` or ``-1`` such that ``s*Q`` has the
    sign of the paper's standard form (Table 1: ellipsoid ``x^2/a^2 + ... - 1``,
    inside negative); for the types whose standard form is congruent to its own
    negative (hyperbolic paraboloid, plane) it is ``+1``.

    Parameters
    ----------
    m : sequence of 10 exact numbers
        The upper entries of the matrix.

    Returns
    -------
    (QuadricKind, int)

    References
    ----------
    Table 1 (the types and their standard forms).

    Examples
    --------
    The unit sphere written with its inside positive:

    >>> from quadric_contact import Quadric
    >>> classify(Quadric.from_equation("1 - x**2 - y**2 - z**2").upper)
    (<QuadricKind.ELLIPSOID: 'ellipsoid'>, -1)
    """
    a = (m[0], m[1], m[2], m[4], m[5], m[7])
    raw_a = inertia_from_minor_sums(principal_minor_sums_3(a))
    raw_q = inertia_from_minor_sums(principal_minor_sums_4(m))
    ia, iq = (raw_a.flipped(), raw_q.flipped()) if raw_a.negative > raw_a.positive else (raw_a, raw_q)
    kind = kind_from_inertia(ia, iq)
    # Canonical sign: where the quadratic part has more positive than negative
    # eigenvalues it fixes the sign; otherwise the standard form decides.
    if raw_a.positive != raw_a.negative:
        sign = 1 if raw_a.positive > raw_a.negative else -1
    elif kind is QuadricKind.HYPERBOLIC_CYLINDER:
        sign = 1 if raw_q.negative > raw_q.positive else -1  # x^2/a^2 - y^2/b^2 - 1 ~ (1, 2)
    elif kind is QuadricKind.EMPTY:
        sign = 1 if m[9] > 0 else -1
    else:
        sign = 1  # hyperbolic paraboloid, intersecting planes, plane: Q ~ -Q
    return kind, sign


def kind_from_inertia(ia: Inertia, iq: Inertia) -> QuadricKind:
    """The affine type from the inertias of the quadratic part ``A`` and of ``Q``: the table
    of the module docstring (``ia`` normalised to ``positive >= negative``).

    Shared by :func:`classify` (exact inertias) and the number modes
    (:mod:`quadric_contact.modes.decision.answers`: inertias from certified signs)."""
    rA, rQ = ia.rank, iq.rank
    if rA == 3:
        if rQ == 4:
            if ia.negative == 0:
                return QuadricKind.ELLIPSOID if iq.positive == 3 else QuadricKind.IMAGINARY_ELLIPSOID
            return (
                QuadricKind.HYPERBOLOID_ONE_SHEET if iq.positive == 2 else QuadricKind.HYPERBOLOID_TWO_SHEETS
            )
        return QuadricKind.IMAGINARY_CONE if ia.negative == 0 else QuadricKind.CONE
    if rA == 2:
        if rQ == 4:
            return QuadricKind.ELLIPTIC_PARABOLOID if ia.negative == 0 else QuadricKind.HYPERBOLIC_PARABOLOID
        if rQ == 3:
            if ia.negative == 0:
                return (
                    QuadricKind.ELLIPTIC_CYLINDER
                    if iq.positive == 2
                    else QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER
                )
            return QuadricKind.HYPERBOLIC_CYLINDER
        return (
            QuadricKind.IMAGINARY_INTERSECTING_PLANES if ia.negative == 0 else QuadricKind.INTERSECTING_PLANES
        )
    if rA == 1:
        if rQ == 3:
            return QuadricKind.PARABOLIC_CYLINDER
        if rQ == 2:
            return QuadricKind.PARALLEL_PLANES if iq.negative == 1 else QuadricKind.IMAGINARY_PARALLEL_PLANES
        return QuadricKind.COINCIDENT_PLANES
    if rQ > 2:
        raise ValueError(f"no quadric has a quadratic part of rank 0 and a matrix of rank {rQ}")
    return {2: QuadricKind.PLANE, 1: QuadricKind.EMPTY, 0: QuadricKind.ZERO}[rQ]
