"""How far apart, or how deep: the signed distance of an ellipsoid from a quadric's solid,
exactly, with witness points and the normal.

Definition
----------
The solid of ``E`` is its inside; the solid ``K`` of ``Q`` is the one of
:mod:`quadric_contact.theory.overlap` (``R-`` of ``Q`` with the sign of its standard form of
Table 1; the half-space ``n . x <= d`` of a plane given as ``n . x - d``).  The *signed
distance* is

* ``dist(E, K) = min |x - y|`` over ``x`` in ``E``, ``y`` in ``K``, when the interiors are
  disjoint (``0`` for a touch);
* ``-depth`` when the interiors meet, with the *penetration depth*
  ``depth = min { |v| : E + v and K have disjoint interiors }`` (the translation distance of
  collision libraries).

``depth`` is computed where ``K`` is convex (ellipsoid, elliptic paraboloid, elliptic and
parabolic cylinders, the slab of parallel planes, the half-space); for the other solids
(hyperboloids, the hyperbolic paraboloid and cylinder) a crossing pair's depth is refused
(:class:`~quadric_contact.exact.errors.UndecidedError`), a separated pair's distance is given.

Witnesses: ``point_Q`` on the surface of ``Q``, ``point_E`` on the surface of ``E`` and the
unit ``normal`` of the surface of ``Q`` at ``point_Q``, pointing out of ``K``, with::

    point_E = point_Q + distance * normal

(apart: the closest points; crossing: ``point_E`` is the deepest point of ``E`` in ``K``, and
moving ``E`` by ``depth`` along ``normal`` separates the interiors).

What is exact here
------------------
* an ellipsoid ``(x - c)^T A (x - c) = r`` and a plane ``n . x = d``, in closed form: with
  ``k = n^T A^-1 n``, ``distance = (n . c - d - sqrt(r k)) / |n|``, ``point_E = c - sqrt(r / k)
  A^-1 n``, ``normal = n / |n|`` (the support function of ``E``);
  the numbers ``a + b sqrt(D)`` built from their quadratic polynomials, the distance from the
  quartic ``(N x^2 - a^2 - r k)^2 - 4 a^2 r k`` (``a = n . c - d``, ``N = |n|^2``);
* a sphere ``|x - c| = rho`` and any quadric with a solid: ``distance = +-|c - p*| - rho`` with
  ``p*`` the point of the surface of ``Q`` nearest to ``c`` (sign ``-`` for ``c`` in ``K``),
  read off the point-quadric secular equation ``(I + mu Q00) p = c - mu b``,
  ``q(p(mu)) det(I + mu Q00)^2 = 0``.  The root ``mu*`` with ``I + mu* Q00`` positive definite
  proves ``p(mu*)`` the one nearest point (:mod:`quadric_contact.theory.distance_sphere`);
  where there is none (a circle or a symmetric pair of nearest points), ``|c - p*| = rho s*``
  with ``s*`` the first-contact scale of the sphere
  (:mod:`quadric_contact.theory.contact_scale`), and ``p*`` the root of the secular equation
  at that distance.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.algebraic import (
    RealAlgebraic,
    algebraic_sqrt,
    algebraic_value,
    real_roots,
    sign_at,
)
from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.isolating import root_among
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.theory.contact_scale import centred_form, contact_scale_exact
from quadric_contact.theory.distance_sphere import sphere_distance, sphere_pair
from quadric_contact.theory.overlap import solid_of

__all__ = ["CONVEX_SOLIDS", "DistanceResult", "distance_exact", "is_sphere"]

CONVEX_SOLIDS: frozenset[QuadricKind] = frozenset(
    {
        QuadricKind.ELLIPSOID,
        QuadricKind.ELLIPTIC_PARABOLOID,
        QuadricKind.ELLIPTIC_CYLINDER,
        QuadricKind.PARABOLIC_CYLINDER,
        QuadricKind.PARALLEL_PLANES,
        QuadricKind.PLANE,
    }
)
"""The types whose solid (``R-`` in the standard sign) is convex: the penetration depth is
defined by the translation distance and computed for them."""

Point = tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic]


@dataclass(frozen=True, eq=False)
class DistanceResult:
    """The signed distance of ``E`` from the solid of ``Q``, exactly, with witnesses.

    Attributes
    ----------
    distance : RealAlgebraic
        Positive apart, ``0`` touching, ``-depth`` when the interiors meet.
    unique : bool
        The witness pair is the only one.
    method : str
        ``"ellipsoid-plane"`` or ``"sphere-quadric"``.
    point_Q, normal, point_E : tuple of 3 RealAlgebraic, or None (properties, computed when first read)
        The witness on the surface of ``Q``, the unit normal of ``Q``'s surface there, out of
        its solid, and the witness on the surface of ``E``:
        ``point_E = point_Q + distance * normal``.  None where the nearest points are not
        isolated (a circle or a sphere of them: ``unique`` is False).

    Two results are equal when their distances, witnesses ``point_Q``, ``unique`` and
    ``method`` are.
    """

    distance: RealAlgebraic
    unique: bool
    method: str
    _point_Q: Callable[[], Point | None] = field(repr=False)
    _witnesses: Callable[[], tuple[Point, Point] | None] = field(repr=False)

    @functools.cached_property
    def point_Q(self) -> Point | None:
        return self._point_Q()

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DistanceResult):
            return NotImplemented
        return (self.distance, self.unique, self.method, self.point_Q) == (
            other.distance,
            other.unique,
            other.method,
            other.point_Q,
        )

    def __hash__(self) -> int:
        return hash((self.distance, self.unique, self.method))

    def __float__(self) -> float:
        return float(self.distance)

    @functools.cached_property
    def _normal_and_point(self) -> tuple[Point, Point] | None:
        return self._witnesses()

    @property
    def normal(self) -> Point | None:
        w = self._normal_and_point
        return None if w is None else w[0]

    @property
    def point_E(self) -> Point | None:
        w = self._normal_and_point
        return None if w is None else w[1]

    @property
    def separated(self) -> bool:
        return self.distance.sign() > 0

    @property
    def penetrating(self) -> bool:
        return self.distance.sign() < 0


def _none() -> None:
    return None


def is_sphere(E: Quadric) -> bool:
    """Is the ellipsoid a sphere (its quadratic part a multiple of the identity)?"""
    a = E.quadratic_part
    return a[0][1] == a[0][2] == a[1][2] == 0 and a[0][0] == a[1][1] == a[2][2]


def _ra(x: Any) -> RealAlgebraic:
    return x if isinstance(x, RealAlgebraic) else RealAlgebraic(x)


def _solve3(A: Sequence[Sequence[Fraction]], v: Sequence[Fraction]) -> list[Fraction]:
    """``A^-1 v`` exactly (Cramer)."""

    def det(m: Sequence[Sequence[Fraction]]) -> Fraction:
        return (
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        )

    d = det(A)
    out = []
    for j in range(3):
        m = [[v[i] if k == j else A[i][k] for k in range(3)] for i in range(3)]
        out.append(det(m) / d)
    return out


def _ellipsoid_plane(E: Quadric, K: Quadric) -> DistanceResult:
    A, c, r = centred_form(E)
    n = [2 * K[i, 3] for i in range(3)]  # K: n . x - d  (as 2 b . x + q33)
    d = -K[3, 3]
    Ainv_n = _solve3(A, n)
    k = sum((n[i] * Ainv_n[i] for i in range(3)), Fraction(0))
    N = sum((x * x for x in n), Fraction(0))
    a = sum((n[i] * c[i] for i in range(3)), Fraction(0)) - d  # n . c - d
    rk = r * k
    # distance = (a - sqrt(r k)) / |n|; sqrt(r / k) = sqrt(r k) / k;
    # point_E = c - sqrt(r k) A^-1 n / k, point_Q = point_E - distance n / |n|
    dist = _quotient_of_roots(a, rk, N)

    def point_Q() -> Point:
        return tuple(  # type: ignore[return-value]
            _quadratic(c[i] - a * n[i] / N, n[i] / N - Ainv_n[i] / k, rk) for i in range(3)
        )

    def witnesses() -> tuple[Point, Point]:
        normal = tuple(_quadratic(Fraction(0), n[i] / N, N) for i in range(3))
        point_E = tuple(_quadratic(c[i], -Ainv_n[i] / k, rk) for i in range(3))
        return normal, point_E  # type: ignore[return-value]

    return DistanceResult(dist, True, "ellipsoid-plane", point_Q, witnesses)


def _quadratic(a: Fraction, b: Fraction, D: Fraction) -> RealAlgebraic:
    """``a + b sqrt(D)`` (rationals, ``D >= 0``), exactly: a root of
    ``x^2 - 2 a x + a^2 - b^2 D``, the larger one when ``b > 0``; its roots lie on either side
    of ``a``.

    >>> _quadratic(Fraction(1), Fraction(-1, 2), Fraction(8)).decimal(6)    # 1 - sqrt(2)
    '-0.414214'
    """
    if b == 0 or D == 0:
        return RealAlgebraic(a)
    p, q = D.numerator, D.denominator
    s = math.isqrt(p * q)
    if s * s == p * q:
        return RealAlgebraic(a + b * Fraction(s, q))
    up = b * Fraction(s + 1, q)  # |up| > |b| sqrt(D): sqrt(p / q) = sqrt(p q) / q
    lo, hi = (a, a + up) if b > 0 else (a + up, a)
    return RealAlgebraic._from_interval((a * a - b * b * D, -2 * a, Fraction(1)), lo, hi)


def _quotient_of_roots(a: Fraction, rk: Fraction, N: Fraction) -> RealAlgebraic:
    """``(a - sqrt(rk)) / sqrt(N)`` (``rk >= 0``, ``N > 0``), exactly: a root of
    ``(N x^2 - a^2 - rk)^2 - 4 a^2 rk``, singled out among the roots of its irreducible
    factors by certified balls.

    >>> _quotient_of_roots(Fraction(3), Fraction(1), Fraction(4))
    RealAlgebraic(1)
    """
    N2 = flint.fmpq_poly([_fmpq(-(a * a + rk)), 0, _fmpq(N)])
    P = N2 * N2 - _fmpq(4 * a * a * rk)
    _, factors = P.numer().factor()
    factors = [g for g, _ in factors]
    for bits in (64, 256, 1024, 4096):
        with working_precision(bits):
            ball = (flint.arb(_fmpq(a)) - flint.arb(_fmpq(rk)).sqrt()) / flint.arb(_fmpq(N)).sqrt()
            x = root_among(factors, ball)
        if x is not None:
            return x
    # distinct irreducible factors are told apart at some precision; should these not do
    root_rk, norm = RealAlgebraic.sqrt(rk), RealAlgebraic.sqrt(N)  # pragma: no cover
    return (root_rk * -1 + a) / norm  # pragma: no cover


def _fmpq(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def _foot_point(
    K: Quadric, c: Sequence[Fraction], d2: RealAlgebraic
) -> tuple[Point, RealAlgebraic, Callable[[Any, int], Any]] | None:
    """The point of the surface of ``K`` at squared distance ``d2`` (the least) from ``c``, read
    from the point-quadric secular equation; None when it is not a regular critical point (a
    symmetric configuration: a circle or sphere of nearest points)."""
    Q00 = [
        [flint.fmpq_poly([int(i == j), 0]) + flint.fmpq_poly([0, _q(K[i, j])]) for j in range(3)]
        for i in range(3)
    ]
    b = [_q(K[i, 3]) for i in range(3)]
    rhs = [flint.fmpq_poly([_q(c[i]), -b[i]]) for i in range(3)]  # c - mu b
    # adjugate solution: p = adj(M) rhs / det(M), M = I + mu Q00
    M = Q00
    det = _det3(M)
    adj_rhs = []
    for j in range(3):
        Mj = [[rhs[i] if kk == j else M[i][kk] for kk in range(3)] for i in range(3)]
        adj_rhs.append(_det3(Mj))
    # q(p) det^2 = P^T Q00 P + 2 det b.P + q33 det^2 with P = adj rhs
    q00 = [[_q(K[i, j]) for j in range(3)] for i in range(3)]
    S = flint.fmpq_poly([0])
    for i in range(3):
        for j in range(3):
            S += adj_rhs[i] * adj_rhs[j] * q00[i][j]
        S += 2 * det * adj_rhs[i] * b[i]
    S += det * det * _q(K[3, 3])
    if S.is_zero():
        return None
    for mu in real_roots(S):
        if _sign_poly_at(det, mu) == 0:
            continue

        def p_of(m: Any, i: int) -> Any:
            return _eval(adj_rhs[i], m) / _eval(det, m)

        def dist2(m: Any) -> Any:
            return sum(_square(p_of(m, i) - c[i]) for i in range(3))

        try:
            value = algebraic_value(dist2, [mu])
            if value.compare(d2) == 0:
                foot = tuple(algebraic_value(lambda m, i=i: p_of(m, i), [mu]) for i in range(3))
                return foot, mu, p_of  # type: ignore[return-value]
        except ZeroDivisionError:
            # the certified evaluation could not single the value out: no witness from this
            # multiplier (the result then reports no witness rather than an unproven one)
            continue
    return None


def _square(x: Any) -> Any:
    return x * x


def _q(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def _det3(m: Sequence[Sequence[Any]]) -> Any:
    return (
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    )


def _eval(p: Any, x: Any) -> Any:
    """Horner with the package's number types (``x`` a Fraction or a field element)."""
    cs = [Fraction(int(a.p), int(a.q)) for a in p.coeffs()] or [Fraction(0)]
    out: Any = x * 0 + cs[-1]
    for a in reversed(cs[:-1]):
        out = out * x + a
    return out


def _sign_poly_at(p: Any, x: RealAlgebraic) -> int:
    return sign_at(p, x)


def _sphere_quadric(E: Quadric, K: Quadric) -> DistanceResult:
    """A sphere against a curved quadric: the certified nearest point of the surface
    (:mod:`quadric_contact.theory.distance_sphere`), or the general route where its
    certificate does not apply."""
    pair = sphere_pair(E, K)
    _refuse_inside(E, K, pair.inside)
    fast = sphere_distance(pair)
    if fast is None:
        return _sphere_quadric_general(E, K)
    _refuse_crossing(E, K, pair.inside, fast.distance)

    def foot() -> Point:
        # the certified nearest point (its coordinates isolated when first read); the general
        # route's, should the balls not isolate them
        p = fast.foot()
        return p if p is not None else _sphere_quadric_general(E, K).point_Q  # type: ignore[return-value]

    nearest = functools.cache(foot)
    general = _sphere_witnesses(pair.centre, pair.r2, pair.inside, nearest, fast.multiplier)

    def witnesses() -> tuple[Point, Point]:
        w = fast.witnesses()  # the general arithmetic, should the balls not isolate them
        return w if w is not None else general()

    return DistanceResult(fast.distance, True, "sphere-quadric", nearest, witnesses)


def _refuse_inside(E: Quadric, K: Quadric, inside: bool) -> None:
    if inside and K.kind not in CONVEX_SOLIDS:
        raise UndecidedError(
            f"the centre of the sphere lies in the solid of {K.kind.value}, which is not convex: "
            "its penetration depth (the translation distance) is not computed",
            E,
            other=K,
        )


def _refuse_crossing(E: Quadric, K: Quadric, inside: bool, dist: RealAlgebraic) -> None:
    if not inside and dist.sign() < 0 and K.kind not in CONVEX_SOLIDS:
        raise UndecidedError(
            f"the sphere crosses the solid of {K.kind.value}, which is not convex: its penetration "
            "depth (the translation distance) is not computed",
            E,
            other=K,
        )


def _sphere_quadric_general(E: Quadric, K: Quadric) -> DistanceResult:
    """The general route: ``|c - p*| = rho s*`` from the first-contact scale (every
    configuration, symmetric ones included), ``p*`` the root of the secular equation at that
    distance."""
    A, c, r = centred_form(E)
    rho2 = r / A[0][0]
    rho = RealAlgebraic.sqrt(rho2)
    inside = K.value_at(c) < 0
    _refuse_inside(E, K, inside)
    scale = contact_scale_exact(E, K)
    dc2 = algebraic_value(lambda t: t * rho2, [scale.squared])  # |c - p*|^2
    dc = _ra(scale.scale) * rho
    dist = (dc * -1 - rho) if inside else (dc - rho)
    _refuse_crossing(E, K, inside, dist)
    found = _foot_point(K, c, dc2) if dc.sign() != 0 else None
    if found is None:
        return DistanceResult(dist, False, "sphere-quadric", _none, _none)
    foot, mu, p_of = found
    witnesses = _sphere_witnesses(c, rho2, inside, lambda: foot, lambda: (mu, p_of))
    return DistanceResult(dist, True, "sphere-quadric", lambda: foot, witnesses)


def _sphere_witnesses(
    c: Sequence[Fraction],
    rho2: Fraction,
    inside: bool,
    nearest: Callable[[], Point],
    multiplier: Callable[[], tuple[RealAlgebraic, Callable[[Any, int], Any]]],
) -> Callable[[], tuple[Point, Point]]:
    """The normal and ``point_E``, computed when first read, from the nearest point, the
    multiplier ``mu`` of it and ``p_of(m, i)``, the point of the secular equation at ``m``."""
    side = 1 if inside else -1

    def witnesses() -> tuple[Point, Point]:
        mu, p_of = multiplier()
        foot = nearest()

        # The normal, out of K: from c towards p* when c is inside K, away from it outside;
        # point_E = c - rho normal.  Each coordinate of the normal is the square root of a
        # number of Q(mu) (one generator, evaluated once) with a known sign, so no product of
        # high-degree algebraic numbers is formed.
        def unit(i: int) -> RealAlgebraic:
            sq = algebraic_value(
                lambda m: _square(p_of(m, i) - c[i]) / sum(_square(p_of(m, j) - c[j]) for j in range(3)), [mu]
            )
            u = algebraic_sqrt(sq)
            return u if side * (foot[i] - c[i]).sign() >= 0 else -u

        normal = tuple(unit(i) for i in range(3))
        rho = RealAlgebraic.sqrt(rho2)
        if rho.is_rational:
            r = rho.as_fraction()
            point_E = tuple(algebraic_value(lambda u, i=i: c[i] - r * u, [normal[i]]) for i in range(3))
        else:
            point_E = tuple(rho * -normal[i] + c[i] for i in range(3))
        return normal, point_E  # type: ignore[return-value]

    return witnesses


def distance_exact(E: Any, Q: Any) -> DistanceResult:
    """The signed distance of the ellipsoid ``E`` from the solid of ``Q``, exactly.

    Parameters
    ----------
    E : Quadric, equation or matrix-like
        A real ellipsoid; any ellipsoid against a plane, a sphere against any other type.
    Q : Quadric, equation or matrix-like
        A quadric of Table 1 or a plane (the types with a solid).

    Returns
    -------
    DistanceResult

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError
    UndecidedError
        For a pair outside the closed forms (an ellipsoid that is not a sphere against a
        curved quadric), or the depth into a non-convex solid.

    Examples
    --------
    >>> r = distance_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 + (z - 5)**2 - 4")
    >>> r.distance, [str(p) for p in r.point_E]
    (RealAlgebraic(2), ['0', '0', '1'])

    The unit ball at the centre of a ball of radius 3 must move 4 to clear it (the nearest
    points form a sphere, so no witness pair is singled out):

    >>> r = distance_exact("x**2 + y**2 + z**2 - 1", "x**2 + y**2 + z**2 - 9")
    >>> r.distance, r.unique
    (RealAlgebraic(-4), False)
    >>> distance_exact("x**2/4 + y**2 + z**2 - 1", "x - 3").distance.decimal(6)      # half-space x <= 3
    '-5.000000'
    >>> distance_exact("x**2/4 + y**2 + z**2 - 1", "3 - x").distance.decimal(6)      # half-space x >= 3
    '1.000000'
    """
    e = as_quadric(E, "E").as_ellipsoid()
    K = solid_of(Q)
    if K.kind is QuadricKind.PLANE:
        return _ellipsoid_plane(e, K)
    if is_sphere(e):
        return _sphere_quadric(e, K)
    raise UndecidedError(
        "an exact distance is given for an ellipsoid against a plane and a sphere against a "
        f"quadric; here an ellipsoid that is not a sphere against {K.kind.value}",
        e,
        other=K,
    )
