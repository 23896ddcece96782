"""The signed distance in certified ball arithmetic: enclosures to a requested number of digits,
without forming exact algebraic numbers.

The same number as :func:`quadric_contact.theory.distance.distance_exact` (same definition,
same pairs), enclosed by arb balls (python-flint):

* an ellipsoid against a plane: the closed form ``(n . c - d - sqrt(r k)) / |n|`` in balls;
* any other ellipsoid against a curved quadric: the extremal critical point of the contact
  system, every critical point isolated by the Krawczyk operator
  (:mod:`quadric_contact.theory.distance_critical`; the least ``t >= 0`` for a non-convex solid,
  whose solids must be apart, decided exactly);
* a sphere against a quadric: every critical point of ``|p - c|^2`` on the surface of ``Q`` is
  regular (``det(I + mu Q00) != 0``) when the secular polynomial ``S`` and ``det(I + mu Q00)``
  have no common factor (an eigen critical set at ``mu_e`` makes ``adj(I + mu_e Q00)(c - mu_e b)``
  vanish, hence ``S(mu_e) = 0``): this is decided exactly (a gcd over Q).  The real roots of
  ``S`` are then isolated by arb's certified complex root finder (real roots come with an exact
  zero imaginary part), ``|p(mu) - c|^2`` is enclosed at each, and the least of them encloses
  ``|c - p*|^2``: the minimum of finitely many enclosed numbers is enclosed by the minima of the
  ends, whatever ties there are.  Every critical point is isolated, so the minimum is the global
  one.  With a common factor (a symmetric configuration) the exact path answers.

The precision doubles until the enclosure is ``digits`` significant digits wide, or until it
is within ``2^-bits`` absolutely of zero (a touch, whose distance is exactly 0, is enclosed,
not decided: the exact path decides it).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import fraction_of
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.modes.distance.depth_kernel import covered_outside_cap, depth_and_minimiser
from quadric_contact.modes.distance.nonconvex import nonconvex_depth
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.distance import CONVEX_SOLIDS, _det3, _solve3, is_sphere
from quadric_contact.theory.distance_critical import critical_distance
from quadric_contact.theory.overlap import overlap_exact, solid_of
from quadric_contact.theory.results import OverlapCode

__all__ = ["DistanceEnclosure", "apart_ellipsoids", "crossing_ellipsoids", "distance_certified"]

MAX_BITS = 4096
"""The working precision at which an enclosure that is still too wide is returned as it is."""


@dataclass(frozen=True)
class DistanceEnclosure:
    """A certified enclosure of the signed distance and of its witnesses.

    Attributes
    ----------
    distance : flint.arb
        Contains the exact signed distance (same definition as
        :class:`~quadric_contact.theory.distance.DistanceResult`).
    point_E, point_Q, normal : tuple of 3 flint.arb, or None
        Enclose the witnesses when the nearest critical point is singled out (None otherwise).
    bits : int
        The working precision that gave the enclosure.
    method : str
    """

    distance: Any
    point_E: tuple[Any, Any, Any] | None
    point_Q: tuple[Any, Any, Any] | None
    normal: tuple[Any, Any, Any] | None
    bits: int
    method: str

    @property
    def bounds(self) -> tuple[Fraction, Fraction]:
        """Rational ends ``lo <= distance <= hi``."""
        mid, rad = fraction_of(self.distance.mid()), fraction_of(self.distance.rad())
        return mid - rad, mid + rad  # exactly: lower()/upper() would round to the context's precision

    def __float__(self) -> float:
        return float(self.distance.mid())


def _arb(x: Fraction) -> Any:
    return flint.arb(flint.fmpq(x.numerator, x.denominator))


def _good(x: Any, digits: int, bits: int) -> bool:
    if not x.is_finite():
        return False
    rad = x.rad()
    scale = abs(x.mid())
    # relative width 10^-digits, or (a touch) absolutely within 10^-(2 digits) of 0
    return bool(rad <= scale * flint.arb(10) ** (-digits) or scale + rad <= flint.arb(10) ** (-2 * digits))


def _plane(E: Quadric, K: Quadric, digits: int) -> DistanceEnclosure:
    A, c, r = centred_form(E)
    n = [2 * K[i, 3] for i in range(3)]
    d = -K[3, 3]

    Ainv_n = _solve3(A, n)
    k = sum(n[i] * Ainv_n[i] for i in range(3))
    N = sum((x * x for x in n), Fraction(0))
    nc = sum((n[i] * c[i] for i in range(3)), Fraction(0))
    bits = 64
    while True:
        with working_precision(bits):
            root = _arb(r * k).sqrt()
            norm = _arb(N).sqrt()
            dist = (_arb(nc - d) - root) / norm
            point_E = tuple(_arb(c[i]) - root * _arb(Ainv_n[i] / k) for i in range(3))
            point_Q = tuple(point_E[i] - (_arb(nc - d) - root) * _arb(n[i] / N) for i in range(3))
            normal = tuple(_arb(n[i]) / norm for i in range(3))
        if _good(dist, digits, bits) or bits >= MAX_BITS:
            return DistanceEnclosure(dist, point_E, point_Q, normal, bits, "ellipsoid-plane")
        bits *= 2


def _secular(K: Quadric, c: Sequence[Fraction]) -> tuple[Any, Any, list[Any]]:
    """``(S, det, adj_rhs)``: the secular polynomial, ``det(I + mu Q00)`` and
    ``adj(I + mu Q00)(c - mu b)``."""

    def q(x: Fraction) -> Any:
        return flint.fmpq(x.numerator, x.denominator)

    M = [[flint.fmpq_poly([int(i == j), q(K[i, j])]) for j in range(3)] for i in range(3)]
    b = [q(K[i, 3]) for i in range(3)]
    rhs = [flint.fmpq_poly([q(c[i]), -b[i]]) for i in range(3)]

    def det3(m: Any) -> Any:
        return (
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        )

    det = det3(M)
    adj_rhs = [
        det3([[rhs[i] if kk == j else M[i][kk] for kk in range(3)] for i in range(3)]) for j in range(3)
    ]
    S = flint.fmpq_poly([0])
    for i in range(3):
        for j in range(3):
            S += adj_rhs[i] * adj_rhs[j] * q(K[i, j])
        S += 2 * det * adj_rhs[i] * b[i]
    S += det * det * q(K[3, 3])
    return S, det, adj_rhs


def _sphere(E: Quadric, K: Quadric, digits: int) -> DistanceEnclosure:
    A, c, r = centred_form(E)
    rho2 = r / A[0][0]
    inside = K.value_at(c) < 0
    if inside and K.kind not in CONVEX_SOLIDS:
        raise UndecidedError(
            f"the centre of the sphere lies in the solid of {K.kind.value}, which is not convex: "
            "its penetration depth (the translation distance) is not computed",
            E,
            other=K,
        )
    S, det, adj_rhs = _secular(K, c)
    if S.is_zero() or S.gcd(det).degree() > 0:
        raise UndecidedError(
            "a symmetric configuration: eigen critical sets (the exact path answers)", E, other=K
        )
    bits = 64
    while True:
        with working_precision(bits):
            roots = [z.real for z, _ in S.complex_roots() if z.imag == 0]
            best = None
            for mu in roots:
                dm = _poly(det, mu)
                p = [_poly(adj_rhs[i], mu) / dm for i in range(3)]
                v = [p[i] - _arb(c[i]) for i in range(3)]
                d2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]  # (arb ** 2 is exp(2 log x): no)
                if best is None or d2.upper() < best[0].lower():
                    best = (d2, p, True)
                elif not (d2.lower() > best[0].upper()):
                    # overlapping: the minimum is enclosed by the minima of the ends
                    lo = min(d2.lower(), best[0].lower())
                    hi = min(d2.upper(), best[0].upper())
                    best = (lo.union(hi), best[1], False)
            if best is None:
                raise UndecidedError(f"{K.kind.value} has no point nearest to the centre", E, other=K)
            d2, p, single = best
            dc = d2.sqrt()
            rho = _arb(rho2).sqrt()
            dist = (-dc - rho) if inside else (dc - rho)
            witnesses: tuple[Any, Any, Any] = (None, None, None)
            if single:
                side = 1 if inside else -1
                normal = tuple((p[i] - _arb(c[i])) * side / dc for i in range(3))
                point_E = tuple(_arb(c[i]) - rho * normal[i] for i in range(3))
                witnesses = (point_E, tuple(p), normal)
        if not inside and K.kind not in CONVEX_SOLIDS and dist < 0:
            raise UndecidedError(
                f"the sphere crosses the solid of {K.kind.value}, which is not convex: its penetration "
                "depth (the translation distance) is not computed",
                E,
                other=K,
            )
        if _good(dist, digits, bits) or bits >= MAX_BITS:
            return DistanceEnclosure(dist, *witnesses, bits, "sphere-quadric")
        bits *= 2


def _poly(p: Any, x: Any) -> Any:
    out = flint.arb(0)
    for a in reversed(p.coeffs()):
        out = out * x + flint.arb(a)
    return out


def distance_certified(E: Any, Q: Any, *, digits: int = 15) -> DistanceEnclosure:
    """Enclose the signed distance of the ellipsoid ``E`` from the solid of ``Q``.

    Parameters
    ----------
    E, Q : Quadric, equation or matrix-like
        As :func:`~quadric_contact.theory.distance.distance_exact`.
    digits : int
        Significant digits asked (the enclosure is at most ``10^-digits`` relative wide).

    Returns
    -------
    DistanceEnclosure

    Raises
    ------
    UndecidedError
        For the depth into a non-convex solid, and for a symmetric configuration (critical
        points that are not isolated), which the exact path answers for a sphere.

    Examples
    --------
    >>> r = distance_certified("9*((x - 5)**2 + (y - 3)**2 + (z - 2)**2) - 1", "x - 2*y + 3", digits=20)
    >>> r.distance.str(20, radius=False)
    '0.56109385766658254523'
    >>> r.distance.rad() < 1e-20 * abs(r.distance.mid())
    True
    """
    e = as_quadric(E, "E").as_ellipsoid()
    K = solid_of(Q)
    if K.kind is QuadricKind.PLANE:
        return _plane(e, K, digits)
    code = None if K.kind in CONVEX_SOLIDS else overlap_exact(e, K).code
    if code is OverlapCode.OVERLAPPING:
        return _nonconvex(e, K, digits)
    if is_sphere(e):
        return _sphere(e, K, digits)
    return _curved(e, K, digits, code)


def _nonconvex(E: Quadric, K: Quadric, digits: int) -> DistanceEnclosure:
    """The depth into a solid that is not convex, between an inscribed ellipsoid and a free
    translation checked exactly (:mod:`quadric_contact.modes.distance.nonconvex`)."""
    found = nonconvex_depth(E, K, digits, _ellipsoids)
    if found is None:
        raise UndecidedError(
            f"the ellipsoid crosses the solid of {K.kind.value}, which is not convex: its penetration "
            "depth (the translation distance) was not certified (no inscribed ellipsoid tried met a "
            "free translation: a nearest free position touching in two points, say)",
            E,
            other=K,
        )
    # no witnesses: the inscribed ellipsoid's contact is K's only where the two bounds are equal
    return DistanceEnclosure(found.distance, None, None, None, found.bits, "inscribed ellipsoid")


def _inverse3(A: Sequence[Sequence[Fraction]]) -> list[list[Fraction]]:
    """The inverse of a 3x3 matrix of Fractions (positive definite here), exactly."""
    cof = [
        [
            A[(i + 1) % 3][(j + 1) % 3] * A[(i + 2) % 3][(j + 2) % 3]
            - A[(i + 1) % 3][(j + 2) % 3] * A[(i + 2) % 3][(j + 1) % 3]
            for j in range(3)
        ]
        for i in range(3)
    ]
    det = sum(A[0][j] * cof[0][j] for j in range(3))
    return [[cof[j][i] / det for j in range(3)] for i in range(3)]  # adj = cof^T, symmetric A


def _support_system(
    parts: Sequence[Any], v: Sequence[Any], one: Any, sqrt: Any
) -> tuple[list[Any], list[list[Any]]]:
    """``F(u, lambda) = (grad phi(u) + lambda u, (u . u - 1) / 2)`` and its Jacobian at
    ``v = (u, lambda)``, in the arithmetic of ``one`` (floats, or arb balls of a box): ``phi(u) =
    h_E(u) + h_K(-u)``, ``h(u) = u . c + sqrt(r u^T B u)`` (``B = A^-1``), ``parts`` the
    ``(c, B, sqrt r, sign)`` of ``E`` (sign 1) and ``K`` (sign -1)."""
    u, lam = list(v[:3]), v[3]
    g = [lam * u[i] for i in range(3)]
    H = [[(lam if i == j else 0 * one) for j in range(3)] for i in range(3)]
    for c, B, root_r, sign in parts:
        Bu = [B[i][0] * u[0] + B[i][1] * u[1] + B[i][2] * u[2] for i in range(3)]
        s = sqrt(u[0] * Bu[0] + u[1] * Bu[1] + u[2] * Bu[2])
        k = root_r / s
        k3 = k / (s * s)
        for i in range(3):
            g[i] = g[i] + sign * c[i] + k * Bu[i]
            for j in range(3):
                H[i][j] = H[i][j] + k * B[i][j] - k3 * Bu[i] * Bu[j]
    F = [*g, (u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - one) / 2]
    J = [[*H[i], u[i]] for i in range(3)] + [[u[0], u[1], u[2], 0 * one]]
    return F, J


def _float_parts(forms: Sequence[Any], Bs: Sequence[Any]) -> list[Any]:
    """The ``(c, B, sqrt r, sign)`` of ``E`` (sign 1) and ``K`` (sign -1) in binary64."""
    return [
        (
            np.array([float(x) for x in c]),
            np.array([[float(x) for x in row] for row in B]),
            math.sqrt(float(r)),
            sign,
        )
        for (_, c, r), B, sign in zip(forms, Bs, (1, -1), strict=True)
    ]


def _arb_parts(forms: Sequence[Any], Bs: Sequence[Any]) -> list[Any]:
    """The ``(c, B, sqrt r, sign)`` of ``E`` and ``K`` in balls of the working precision."""
    return [
        ([_arb(x) for x in c], [[_arb(x) for x in row] for row in B], _arb(r).sqrt(), sign)
        for (_, c, r), B, sign in zip(forms, Bs, (1, -1), strict=True)
    ]


def _float_newton(parts: Sequence[Any], v: np.ndarray) -> np.ndarray | None:
    """Newton's method on ``F(u, lambda) = 0`` in binary64 from ``v``; None where it fails."""
    for _ in range(60):
        Fv, Jv = _support_system(parts, list(v), 1.0, math.sqrt)
        try:
            step = np.linalg.solve(np.array(Jv, dtype=float), np.array(Fv, dtype=float))
        except np.linalg.LinAlgError:
            return None
        v = v - step
        if not np.all(np.isfinite(v)):
            return None
        if np.max(np.abs(step)) <= 1e-15 * (1.0 + np.max(np.abs(v))):
            break
    return v


def _isolated_root(parts: Sequence[Any], v: Any, bits: int, radius: Sequence[Any] | None) -> Any:
    """The Krawczyk operator at the working precision ``bits`` (inside ``working_precision``).

    Newton's method on the midpoints from ``v`` gives ``m``; with ``X = m +- radius`` (by
    default ``2^(40 - bits) (1 + |m_i|)``, a box of the precision's own size),
    ``K(X) = m - Y F(m) + (I - Y J(X)) (X - m)`` in the interior of ``X`` proves ``F`` has exactly
    one zero in ``X``, and it lies in ``K(X)``.  Returns ``(X, K(X))``, or None where a matrix is
    singular or the test fails."""
    one = flint.arb(1)
    sqrt = flint.arb.sqrt
    m = [flint.arb(float(x)) for x in v]
    for _ in range(max(2, (bits // 50).bit_length() + 2)):
        Fm, Jm = _support_system(parts, m, one, sqrt)
        try:
            step = flint.arb_mat([[x.mid() for x in row] for row in Jm]).solve(
                flint.arb_mat([[x.mid()] for x in Fm])
            )
        except ZeroDivisionError:
            return None
        m = [(m[i] - step[i, 0]).mid() for i in range(4)]
    if radius is None:
        width = flint.arb(2) ** (40 - bits)
        radius = [width * (1 + abs(m[i]).mid()) for i in range(4)]
    X = [flint.arb(m[i], radius[i]) for i in range(4)]
    Fm, Jm = _support_system(parts, m, one, sqrt)
    try:
        Y = flint.arb_mat([[x.mid() for x in row] for row in Jm]).inv()
    except ZeroDivisionError:
        return None
    Y = flint.arb_mat([[Y[i, j].mid() for j in range(4)] for i in range(4)])
    _, JX = _support_system(parts, X, one, sqrt)
    R = flint.arb_mat(4, 4, [int(i == j) for i in range(4) for j in range(4)]) - Y * flint.arb_mat(JX)
    Km = Y * flint.arb_mat([[x] for x in Fm])
    D = R * flint.arb_mat([[X[i] - m[i]] for i in range(4)])
    Kx = [m[i] - Km[i, 0] + D[i, 0] for i in range(4)]
    if not all(X[i].contains_interior(Kx[i]) for i in range(4)):
        return None
    return X, Kx


def _witnesses(parts: Sequence[Any], u_box: Sequence[Any]) -> tuple[Any, Any, Any]:
    """The support points ``c_E + sqrt(r_E) B_E u / |u|_B_E`` and ``c_K - sqrt(r_K) B_K u /
    |u|_B_K`` of a box of directions, and the normal ``-u`` of ``K`` at the second."""
    points = []
    for c, B, root_r, sign in parts:
        Bu = [B[i][0] * u_box[0] + B[i][1] * u_box[1] + B[i][2] * u_box[2] for i in range(3)]
        k = root_r / (u_box[0] * Bu[0] + u_box[1] * Bu[1] + u_box[2] * Bu[2]).sqrt()
        points.append(tuple(c[i] + sign * k * Bu[i] for i in range(3)))
    return points[0], points[1], tuple(-x for x in u_box)


def _forms(E: Quadric, K: Quadric) -> tuple[list[Any], list[Any]]:
    """The centred forms ``(A, c, r)`` of ``E`` and ``K`` and the inverses ``B = A^-1``."""
    forms = [centred_form(E), centred_form(K)]
    return forms, [_inverse3(A) for A, _, _ in forms]


def apart_ellipsoids(
    E: Quadric, K: Quadric, digits: int, known: tuple[list[Any], list[Any]] | None = None
) -> DistanceEnclosure | None:
    """Two ellipsoids whose solids are apart, from one isolated root (``proofs/
    distance_of_separated_ellipsoids.py``): ``phi(u) = h_E(u) + h_K(-u)`` is convex and
    ``dist(E, K) = -min over |u| <= 1 of phi(u)`` when positive.  A root of
    ``grad phi(u) + lambda u = 0``, ``|u| = 1`` with ``lambda > 0`` is a KKT point of that convex
    program, hence its minimum, and ``phi(u) = u . grad phi(u) = -lambda`` (``phi`` is positively
    homogeneous): the distance is ``lambda``, the witnesses are the support points
    ``c_E + sqrt(r_E) B_E u / |u|_B_E`` and ``c_K - sqrt(r_K) B_K u / |u|_B_K``, the normal of
    ``K`` there is ``-u``.  Newton's method in binary64 then in balls finds the root; the
    Krawczyk operator on a box around it proves it unique there and encloses it.  None where
    the search fails or the test does not pass (the general route then answers); ``known``:
    :func:`_forms` of the pair, when the caller has them."""
    forms, Bs = known or _forms(E, K)
    fparts = _float_parts(forms, Bs)
    # binary64 start: Newton's method from the direction of the centres
    axis = fparts[1][0] - fparts[0][0]
    if not np.all(np.isfinite(axis)) or not np.any(axis):
        return None
    u = axis / np.linalg.norm(axis)
    Fu, _ = _support_system(fparts, [*u, 0.0], 1.0, math.sqrt)
    v = _float_newton(fparts, np.array([*u, -float(np.dot(u, Fu[:3]))]))  # lambda = -u . grad phi(u)
    if v is None or v[3] <= 0:
        return None  # not apart (or not found): the general route
    bits = min(max(64, int(digits * 3.33) + 32), MAX_BITS)
    while True:
        with working_precision(bits):
            parts = _arb_parts(forms, Bs)
            root = _isolated_root(parts, v, bits, None)
            if root is None or not root[1][3] > 0:
                return None
            dist = root[1][3]
            point_E, point_Q, normal = _witnesses(parts, root[1][:3])
        if _good(dist, digits, bits) or bits >= MAX_BITS:
            return DistanceEnclosure(dist, point_E, point_Q, normal, bits, "ellipsoid-ellipsoid")
        bits = min(2 * bits, MAX_BITS)


CAP = 1e-4
"""The angular radius of the cap of directions the isolating box of a crossing pair holds."""
LOCATE = 1e-6
"""The relative width the depth kernel is asked for when it only locates the minimum: the
global lower bound needs to be no tighter (the root's box holds the interval it leaves), and
shallow pairs, which the kernel cannot enclose to ``1e-12``, are located at this width (or,
shallower still, at a thousand times it)."""


def crossing_ellipsoids(
    E: Quadric, K: Quadric, digits: int, known: tuple[list[Any], list[Any]] | None = None
) -> DistanceEnclosure | None:
    """Two crossing ellipsoids, from one isolated root and a covering of
    the rest of the sphere (``proofs/depth_of_crossing_ellipsoids.py``, "the cap"): the depth is
    ``d* = min over unit u of phi(u)``.

    1. The compiled depth kernel
       (:func:`~quadric_contact.modes.distance.depth_kernel.depth_and_minimiser`, at the width
       :data:`LOCATE`) gives ``phi >= lo`` on the whole sphere and a float minimiser.
    2. The Krawczyk operator on a box ``X``, ``u`` within ``w`` of the minimiser and ``lambda``
       over an interval that holds ``[-r, -lo]``, proves ``F(u, lambda) = 0`` has one root in
       ``X``; ``d_c = -lambda`` at it is a value of ``phi`` on the sphere (``phi(u) = -lambda``
       at a root), so ``d* <= d_c``.
    3. The kernel proves ``phi >= r`` outside the cap of directions within ``0.9 w`` of the
       minimiser, with ``r >= d_c`` (binary64, rounded up).  The kernel excuses a cell whose
       corners pass ``w . c >= cos(0.8 w) |w|`` in binary64, which puts them within ``0.9 w`` of
       ``c`` (the rounding is far below ``cos(0.8 w) - cos(0.9 w)``); a unit vector within
       ``0.9 w`` of ``c``, itself within ``0.1 w`` of the box's centre, lies in the box.

    Entries that are not binary64 numbers: the kernel runs on the pair rounded to binary64,
    whose ``phi`` is within ``gap`` of the pair's on the whole sphere (:func:`_rounding_gap`), so
    its lower bound less ``gap`` bounds ``phi`` below, and the covering is asked for ``r + gap``.

    Then ``d* = d_c``: a global minimiser outside the cap has ``phi >= r >= d_c``; one inside with
    ``phi < r`` is a critical point, a root ``(u, -phi(u))`` of ``F`` in ``X``, hence the root.
    The witnesses are those of :func:`apart_ellipsoids` at the root.  None where a step fails
    (two minima nearly equal, a flat ``phi``, a rounded matrix that is no ellipsoid): the general
    route then answers; ``known`` as for :func:`apart_ellipsoids`."""
    try:
        Ef, Kf = E.to_numpy(), K.to_numpy()
    except OverflowError:
        return None  # entries beyond binary64: the general route refuses or answers
    if not (np.all(np.isfinite(Ef)) and np.all(np.isfinite(Kf))):
        return None
    forms, Bs = known or _forms(E, K)
    gaps = [_rounding_gap(E, Ef, forms[0]), _rounding_gap(K, Kf, forms[1])]
    if gaps[0] is None or gaps[1] is None:
        return None
    gap = _float_up(gaps[0] + gaps[1])  # |phi - phi of the binary64 pair| <= gap on the sphere
    found = depth_and_minimiser(Ef, Kf, LOCATE) or depth_and_minimiser(Ef, Kf, 1e3 * LOCATE)
    if found is None:
        return None
    lo, hi, u = found
    lo = _dn(lo - gap)  # phi >= lo of the binary64 pair, less the gap (rounded down)
    fparts = _float_parts(forms, Bs)
    v = _float_newton(fparts, np.array([*u, -hi]))
    if v is None or not v[3] < 0 or abs(float(np.dot(v[:3], v[:3])) - 1) > 1e-12:
        return None
    centre = v[:3] / np.linalg.norm(v[:3])
    # the longest semi-axis, about: sqrt(r) times the largest row sum of |A^-1|
    size = max(root_r * math.sqrt(float(np.max(np.sum(np.abs(B), axis=1)))) for _, B, root_r, _ in fparts)
    for w, c in ((CAP, 256), (CAP, 4096), (CAP / 10, 4096)):
        with working_precision(128):
            parts = _arb_parts(forms, Bs)
            # lambda's interval: it holds [-r, -lo] (r a few units in the last place above d_c,
            # within the kernel's width of lo), with room for the image of the u-box, whose
            # lambda part is about w^2 times the ellipsoids' size wide
            lam_rad = flint.arb(c * w * w * size + 4 * (hi - lo))
            wide = _isolated_root(parts, v, 128, [flint.arb(w)] * 3 + [lam_rad])
            if wide is None:
                continue
            X = wide[0]
            if not all(abs(float(X[i].mid()) - centre[i]) <= 0.1 * w for i in range(3)):
                continue  # the cap's centre must be within 0.1 w of the box's: the cap is in X
            # the root, narrowly: a box inside X holds the one root of X
            narrow = _isolated_root(parts, v, 128, None)
            if narrow is None or not all(X[i].contains(narrow[0][i]) for i in range(4)):
                continue
            r = math.nextafter(float(-narrow[1][3].lower()), math.inf)  # d_c <= r
            if not (X[3].contains(flint.arb(-r)) and X[3].contains(flint.arb(-lo))):
                continue
        # phi of the binary64 pair >= r + gap outside the cap puts the pair's own phi >= r there
        if not covered_outside_cap(Ef, Kf, _float_up(Fraction(r) + Fraction(gap)), centre, math.cos(0.8 * w)):
            return None  # phi below the root's value elsewhere: another (near) minimum
        break
    else:
        return None
    bits = min(max(64, int(digits * 3.33) + 32), MAX_BITS)
    while True:
        with working_precision(bits):
            parts = _arb_parts(forms, Bs)
            root = _isolated_root(parts, v, bits, None)
            if root is None:
                return None
            Xn, Kn = root
            # the narrow box in the wide one: the same root
            if not all(X[i].contains(Xn[i]) for i in range(4)):
                return None
            dist = Kn[3]
            point_E, point_Q, normal = _witnesses(parts, Kn[:3])
        if _good(dist, digits, bits) or bits >= MAX_BITS:
            return DistanceEnclosure(dist, point_E, point_Q, normal, bits, "crossing ellipsoids")
        bits = min(2 * bits, MAX_BITS)


def _rounding_gap(Q: Quadric, Qf: np.ndarray, form: Any = None) -> Fraction | None:
    """A bound of ``|h_Q(u) - h_Q'(u)|`` over unit ``u``, ``h`` the support functions of the
    ellipsoid ``Q`` and of ``Q'``, its matrix rounded to binary64 (``Qf``); 0 when the entries are
    binary64 numbers, None when ``Q'`` is no ellipsoid with the same inside; ``form``: the
    :func:`~quadric_contact.theory.contact_scale.centred_form` of ``Q``, when the caller has it.

    With ``h(u) = u . c + sqrt(u^T M u)``, ``M = r A^-1`` (``M'`` likewise):
    ``|h - h'| <= |c - c'| + |u^T (M - M') u| / (sqrt(u^T M u) + sqrt(u^T M' u))
    <= |c - c'| + ||M - M'||_F / (sqrt(m) + sqrt(m'))``, ``m = r / max_i sum_j |A_ij|`` at most
    the least eigenvalue of ``M`` (a row sum bounds the largest of ``A``)."""
    rounded = [[Fraction(float(Qf[i, j])) for j in range(4)] for i in range(4)]
    if all(rounded[i][j] == Q[i, j] for i in range(4) for j in range(4)):
        return Fraction(0)
    A2 = [row[:3] for row in rounded[:3]]
    minors = (A2[0][0], A2[0][0] * A2[1][1] - A2[0][1] * A2[1][0], _det3(A2))
    if not all(x > 0 for x in minors):
        return None
    Qr = Quadric.from_matrix(rounded)
    if not _inside_negative(Qr):
        return None
    forms = [form or centred_form(Q), centred_form(Qr)]
    Ms, cs, least = [], [], []
    for A, c, r in forms:
        B = _inverse3(A)
        Ms.append([[r * B[i][j] for j in range(3)] for i in range(3)])
        cs.append(c)
        least.append(r / max(sum(abs(x) for x in row) for row in A))
    centre2 = sum(((cs[0][i] - cs[1][i]) ** 2 for i in range(3)), Fraction(0))
    frob2 = sum(((Ms[0][i][j] - Ms[1][i][j]) ** 2 for i in range(3) for j in range(3)), Fraction(0))
    return _sqrt_up(centre2) + _sqrt_up(frob2) / (_sqrt_dn(least[0]) + _sqrt_dn(least[1]))


def _inside_negative(Q: Quadric) -> bool:
    """``Q(c) < 0`` at the centre: the solid is the side the rounded matrix keeps."""
    c = Q.center()
    return c is not None and Q.value_at(c) < 0


def _sqrt_up(x: Fraction) -> Fraction:
    """A rational at least ``sqrt(x)`` (``x >= 0``), within a relative ``2^-50``."""
    if x == 0:
        return Fraction(0)
    s = Fraction(math.sqrt(float(x)))
    while s * s < x:
        s *= 1 + Fraction(1, 2**50)
    return s


def _sqrt_dn(x: Fraction) -> Fraction:
    """A rational at most ``sqrt(x)`` (``x > 0``), within a relative ``2^-50``."""
    s = Fraction(math.sqrt(float(x)))
    while s * s > x:
        s *= 1 - Fraction(1, 2**50)
    return s


def _float_up(x: Fraction) -> float:
    """The least binary64 number at least ``x``."""
    f = float(x)
    return f if Fraction(f) >= x else math.nextafter(f, math.inf)


def _dn(x: float) -> float:
    return math.nextafter(x, -math.inf)


def _ellipsoids(E: Quadric, K: Quadric, digits: int) -> DistanceEnclosure:
    """Two ellipsoids (a sphere too), by the routes of :func:`_curved`."""
    return _curved(E, K, digits)


def _curved(E: Quadric, K: Quadric, digits: int, code: OverlapCode | None = None) -> DistanceEnclosure:
    """Any ellipsoid against a curved quadric: the extremal contact critical point
    (:mod:`quadric_contact.theory.distance_critical`); a non-convex solid needs the solids
    apart, decided exactly first."""
    if K.kind is QuadricKind.ELLIPSOID:
        both = _forms(E, K)
        found = apart_ellipsoids(E, K, digits, both) or crossing_ellipsoids(E, K, digits, both)
        if found is not None:
            return found
    convex = K.kind in CONVEX_SOLIDS
    touching = False
    if not convex:
        code = code or overlap_exact(E, K).code
        if code is OverlapCode.OVERLAPPING:
            return _nonconvex(E, K, digits)
        touching = code is OverlapCode.TOUCHING
    r = critical_distance(E, K, convex=convex, digits=digits)
    dist = flint.arb(0) if touching else r.distance
    return DistanceEnclosure(dist, r.point_E, r.point_Q, r.normal, r.bits, "ellipsoid-quadric")
