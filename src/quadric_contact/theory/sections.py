"""Plane sections of a pencil: where the curve ``E ∩ Q`` meets a cutting plane.

A piece of an object is a quadric ``Q`` cut by planes.  An ellipsoid ``E``
crosses the piece as cut, ``Q ∩ H`` with ``H`` the kept closed half-space of
a plane ``Π``, iff the real curve ``C = E ∩ Q`` of a transversal contact has a
point in ``H``.  This module decides that exactly, one dimension down from
the paper's pencil ``λE + Q``:

* restricted to a plane, ``E`` and ``Q`` are conics ``E_Π``, ``Q_Π`` (3x3
  symmetric matrices, :func:`section_matrix`) and ``C ∩ Π = E_Π ∩ Q_Π``;
* ``E_Π`` has a definite quadratic part (that of ``E`` restricted to the
  plane's directions), so it has no real point at infinity, and two real
  ternary quadratic forms without a common real zero have a definite
  combination (Finsler-Calabi, ``n = 3``): the conics share a real point iff
  no member of ``λ E_Π + Q_Π`` is definite (:func:`conics_meet`).  The
  inertia of the member is constant between the real roots of the cubic
  ``det(λ E_Π + Q_Π)``, so one rational sample per gap decides;
* the levels ``π = s`` of the plane's linear form sweep ``C``:
  ``π(C)`` is a finite union of closed intervals whose ends are levels
  where the level conics are tangent (critical values of ``π`` on a smooth
  ``C``: the cubic's discriminant :func:`cubic_discriminant` in ``s``
  vanishes) or where the level plane touches ``E``; ``C`` meets ``H`` iff
  it meets ``Π`` or a level sampled between consecutive such critical
  levels on the kept side meets ``C`` (:func:`curve_meets_half_space`).

The reduction, and the claim that the answer can change in time only where
the section's discriminant, ``E``'s zone or the pencil's discriminant
changes sign, is proved in ``proofs/pieces_as_cut.py``.

Coefficient order as everywhere in the package: ``c0, c1, c2, c3`` with
``det(λA + B) = c3 λ^3 + c2 λ^2 + c1 λ + c0``.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint

from quadric_contact.exact.algebraic import rational_between, real_roots
from quadric_contact.exact.rational import fmpq_of
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric

__all__ = [
    "conic_pencil_coefficients",
    "conics_meet",
    "cubic_discriminant",
    "curve_meets_half_space",
    "plane_form",
    "section_frame",
    "section_matrix",
]

Mat3 = list[list[Any]]


def plane_form(plane: Quadric) -> tuple[tuple[Fraction, Fraction, Fraction], Fraction]:
    """``(n, d)`` with ``X^T P X = n . x + d``: the plane's linear form (``R+`` is ``π >= 0``).

    Examples
    --------
    >>> plane_form(Quadric.from_equation("z - 6"))
    ((Fraction(0, 1), Fraction(0, 1), Fraction(1, 1)), Fraction(-6, 1))
    """
    if plane.kind is not QuadricKind.PLANE:
        raise ValueError(f"expected a plane, got {plane.kind.value}")
    u = plane.upper  # q00 q01 q02 q03 q11 q12 q13 q22 q23 q33
    return (2 * u[3], 2 * u[6], 2 * u[8]), u[9]


def section_frame(plane: Quadric) -> tuple[list[list[Fraction]], list[Fraction], list[Fraction]]:
    """A rational affine frame of the levels ``π = s`` of a plane.

    Returns ``(directions, origin, step)``: homogeneous 4-vectors, two
    directions spanning the plane's direction space (last coordinate 0), a
    point ``origin`` with ``π = 0`` and ``step`` with ``π(origin + s step) = s``.
    The map ``(u, v, w) -> u d1 + v d2 + w (origin + s step)`` is a bijection
    from the projective plane onto the level plane ``π = s``.
    """
    n, d = plane_form(plane)
    k = max(i for i in range(3) if n[i] != 0)
    dirs = []
    for i in range(3):
        if i == k:
            continue
        v = [Fraction(0)] * 4
        v[i] = Fraction(1)
        v[k] = -n[i] / n[k]
        dirs.append(v)
    origin = [Fraction(0)] * 4
    origin[k] = -d / n[k]
    origin[3] = Fraction(1)
    step = [Fraction(0)] * 4
    step[k] = 1 / n[k]
    return dirs, origin, step


def section_matrix(entries: Sequence[Any], plane: Quadric, *, level: bool = False, one: Any = 1) -> Mat3:
    """The 3x3 matrix of a quadric restricted to the plane ``π = 0`` (or to every level ``π = s``).

    Parameters
    ----------
    entries : sequence
        The ten upper entries ``(q00, q01, q02, q03, q11, q12, q13, q22, q23, q33)``
        in any ring that holds the rationals (Fraction, ``fmpq_poly`` in ``t``).
    plane : Quadric
    level : bool
        Entries as ``fmpq_poly`` in the level ``s`` (``entries`` must then be
        rational): the section by ``π = s`` for every ``s``.
    one : ring element
        The ring's one (``fmpq_poly([1])`` for polynomial entries).

    Examples
    --------
    The unit sphere cut by ``z = 0`` is the unit circle:

    >>> [[str(v) for v in row] for row in section_matrix(Quadric.sphere(1).upper, Quadric.from_equation("z"))]
    [['1', '0', '0'], ['0', '1', '0'], ['0', '0', '-1']]
    """
    dirs, origin, step = section_frame(plane)
    if level:
        s = flint.fmpq_poly([0, 1])
        cols: list[list[Any]] = [
            [flint.fmpq_poly([fmpq_of(v)]) for v in dirs[0]],
            [flint.fmpq_poly([fmpq_of(v)]) for v in dirs[1]],
            [fmpq_of(o) + fmpq_of(st) * s for o, st in zip(origin, step, strict=True)],
        ]
        ring: list[Any] = [flint.fmpq_poly([fmpq_of(Fraction(v))]) for v in entries]
    else:
        cast = fmpq_of if isinstance(one, flint.fmpq_poly) else Fraction
        cols = [[cast(v) for v in dirs[0]], [cast(v) for v in dirs[1]], [cast(v) for v in origin]]
        ring = list(entries)
    idx = {ij: k for k, ij in enumerate((i, j) for i in range(4) for j in range(i, 4))}
    Q = [[ring[idx[(min(i, j), max(i, j))]] for j in range(4)] for i in range(4)]
    out: Mat3 = [[None] * 3 for _ in range(3)]
    for a in range(3):
        Qa = [sum((Q[i][j] * cols[a][j] for j in range(4) if cols[a][j] != 0), one * 0) for i in range(4)]
        for b in range(a, 3):
            v = sum((cols[b][i] * Qa[i] for i in range(4) if cols[b][i] != 0), one * 0)
            out[a][b] = out[b][a] = v
    return out


def _det3(M: Mat3) -> Any:
    return (
        M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
        - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
        + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
    )


def conic_pencil_coefficients(A: Mat3, B: Mat3) -> tuple[Any, Any, Any, Any]:
    """``(c0, c1, c2, c3)`` of ``det(λA + B)`` for 3x3 matrices over any commutative ring.

    ``c3 = det A``, ``c0 = det B``, ``c2`` (``c1``) the sum of the three
    determinants with one row of ``B`` (of ``A``) in ``A`` (in ``B``).

    Examples
    --------
    >>> I = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> conic_pencil_coefficients(I, I)
    (1, 3, 3, 1)
    """

    def mixed(X: Mat3, Y: Mat3) -> Any:
        total = None
        for r in range(3):
            M = [Y[i] if i == r else X[i] for i in range(3)]
            v = _det3(M)
            total = v if total is None else total + v
        return total

    return _det3(B), mixed(B, A), mixed(A, B), _det3(A)


def cubic_discriminant(c0: Any, c1: Any, c2: Any, c3: Any) -> Any:
    """The discriminant of ``c3 λ^3 + c2 λ^2 + c1 λ + c0``:
    ``18 c3 c2 c1 c0 - 4 c2^3 c0 + c2^2 c1^2 - 4 c3 c1^3 - 27 c3^2 c0^2``.

    Examples
    --------
    ``(λ - 1)^2 (λ + 2) = λ^3 - 3 λ + 2``:

    >>> cubic_discriminant(2, -3, 0, 1)
    0
    """
    return (
        18 * c3 * c2 * c1 * c0
        - 4 * c2 * c2 * c2 * c0
        + c2 * c2 * c1 * c1
        - 4 * c3 * c1 * c1 * c1
        - 27 * c3 * c3 * c0 * c0
    )


def _definite(M: Mat3) -> bool:
    m1 = M[0][0]
    m2 = M[0][0] * M[1][1] - M[0][1] * M[1][0]
    m3 = _det3(M)
    return m2 > 0 and ((m1 > 0 and m3 > 0) or (m1 < 0 and m3 < 0))


def conics_meet(A: Mat3, B: Mat3) -> bool:
    """Do two real conics share a real point?  ``A`` must have a definite
    quadratic part (an ellipse, a point or an empty conic), ``B`` is any conic.

    Exact (rationals, computed with flint).  By Finsler-Calabi for ternary
    forms, the conics have no common real projective point iff some
    combination ``aA + bB`` is definite; ``A`` has no real point at infinity, so projective and affine
    common points agree.  ``A`` itself is not definite when it is a real
    ellipse, and a combination with ``b != 0`` is ``±(λA + B)``: the member's
    inertia is constant between the real roots of ``det(λA + B)``, which is
    sampled once per gap.

    Parameters
    ----------
    A, B : 3x3 nested sequences of rationals (Fraction, int or flint ``fmpq``)

    Returns
    -------
    bool

    Examples
    --------
    The unit circle against circles of radius 1/2 centred at ``(1, 0)`` and ``(2, 0)``:

    >>> F = Fraction
    >>> circle = [[F(1), F(0), F(0)], [F(0), F(1), F(0)], [F(0), F(0), F(-1)]]
    >>> near = [[F(1), F(0), F(-1)], [F(0), F(1), F(0)], [F(-1), F(0), F(3, 4)]]
    >>> far = [[F(1), F(0), F(-2)], [F(0), F(1), F(0)], [F(-2), F(0), F(15, 4)]]
    >>> conics_meet(circle, near), conics_meet(circle, far)
    (True, False)
    """
    # exact rationals in C (flint): the same numbers as Fractions, faster
    A = [[v if isinstance(v, flint.fmpq) else fmpq_of(Fraction(v)) for v in row] for row in A]
    B = [[v if isinstance(v, flint.fmpq) else fmpq_of(Fraction(v)) for v in row] for row in B]
    poly = flint.fmpq_poly(list(conic_pencil_coefficients(A, B)))
    if poly.is_zero():  # every member singular: A would be singular, which has no definite part
        raise ValueError("det(lambda A + B) vanishes identically: A is not a proper conic")
    roots = real_roots(poly)
    points: list[Any] = [None, *roots, None]
    for left, right in pairwise(points):
        if left is None and right is None:
            lam = Fraction(0)
        elif left is None:
            lam = rational_between(right.lo - 1, right)
        elif right is None:
            lam = rational_between(left, left.hi + 1)
        else:
            lam = rational_between(left, right)
        q = fmpq_of(lam)
        M = [[q * A[i][j] + B[i][j] for j in range(3)] for i in range(3)]
        if _definite(M):
            return False
    return True


def _poly_of_ring(v: Any) -> Any:
    return v if isinstance(v, flint.fmpq_poly) else flint.fmpq_poly([fmpq_of(Fraction(v))])


def curve_meets_half_space(E: Quadric, Q: Quadric, plane: Quadric, side: int) -> bool | None:
    """Does the real curve ``E ∩ Q`` have a point in the closed half-space ``side * π >= 0``?

    Parameters
    ----------
    E : Quadric
        An ellipsoid.
    Q : Quadric
        Any quadric.
    plane : Quadric
        The cutting plane ``π = 0``.
    side : {1, -1}
        ``1``: the kept side is ``R+`` of the plane; ``-1``: ``R-``.

    Returns
    -------
    bool or None
        None when the level conics are tangent at every level (the
        discriminant in ``s`` vanishes identically, e.g. ``Q`` a plane
        parallel to the cut), where the sweep does not apply.  The answer
        counts the curve's non-isolated points only (isolated real points of
        ``E ∩ Q`` are tangencies, not crossings); it is exact for the curve of
        a transversal contact whose pencil has four distinct roots.

    Examples
    --------
    Two unit spheres centred at the origin and at ``(1, 0, 1)`` meet in a
    circle in the plane ``x + z = 1`` with ``0 <= z <= 1``:

    >>> S, T = Quadric.sphere(1), Quadric.sphere(1, center=(1, 0, 1))
    >>> z = lambda h: Quadric.from_equation(f"z - {h}")
    >>> curve_meets_half_space(S, T, z("3/4"), 1), curve_meets_half_space(S, T, z("3/2"), 1)
    (True, False)
    >>> curve_meets_half_space(S, T, z("3/2"), -1), curve_meets_half_space(S, T, z("-1/10"), -1)
    (True, False)
    """
    if conics_meet(section_matrix(E.upper, plane), section_matrix(Q.upper, plane)):
        return True
    one = flint.fmpq_poly([1])
    A = section_matrix(E.upper, plane, level=True, one=one)
    B = section_matrix(Q.upper, plane, level=True, one=one)
    c = [_poly_of_ring(x) for x in conic_pencil_coefficients(A, B)]
    disc = cubic_discriminant(*c)
    if disc.is_zero():
        return None
    critical = disc * c[3]  # tangent level conics; levels touching E
    roots = [r for r in real_roots(critical) if side * r.sign() > 0]
    if side < 0:
        roots = roots[::-1]
    points: list[Any] = [Fraction(0), *roots]
    samples = []
    for k in range(len(points)):
        here = points[k]
        if k + 1 < len(points):
            pair = (here, points[k + 1]) if side > 0 else (points[k + 1], here)
            samples.append(rational_between(*pair))
        else:  # beyond the last critical level
            edge = here if isinstance(here, Fraction) else (here.hi if side > 0 else here.lo)
            samples.append(edge + side)
    for s in samples:
        q = fmpq_of(s)
        As = [[x(q) for x in row] for row in A]
        Bs = [[x(q) for x in row] for row in B]
        if conics_meet(As, Bs):
            return True
    return False
