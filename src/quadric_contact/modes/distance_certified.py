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

from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.theory.contact_scale import centred_form
from quadric_contact.theory.distance import CONVEX_SOLIDS, is_sphere
from quadric_contact.theory.distance_critical import critical_distance
from quadric_contact.theory.overlap import overlap_exact, solid_of
from quadric_contact.theory.results import OverlapCode

__all__ = ["DistanceEnclosure", "distance_certified"]

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
        mid, rad = _fraction(self.distance.mid()), _fraction(self.distance.rad())
        return mid - rad, mid + rad  # exactly: lower()/upper() would round to the context's precision

    def __float__(self) -> float:
        return float(self.distance.mid())


def _fraction(x: Any) -> Fraction:
    m, e = x.mid().man_exp()
    m, e = int(m), int(e)
    return Fraction(m * 2**e) if e >= 0 else Fraction(m, 2**-e)


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
    from quadric_contact.theory.distance import _solve3

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
    if is_sphere(e):
        return _sphere(e, K, digits)
    return _curved(e, K, digits)


def _curved(E: Quadric, K: Quadric, digits: int) -> DistanceEnclosure:
    """Any ellipsoid against a curved quadric: the extremal contact critical point
    (:mod:`quadric_contact.theory.distance_critical`); a non-convex solid needs the solids
    apart, decided exactly first."""
    convex = K.kind in CONVEX_SOLIDS
    touching = False
    if not convex:
        code = overlap_exact(E, K).code
        if code is OverlapCode.OVERLAPPING:
            raise UndecidedError(
                f"the ellipsoid crosses the solid of {K.kind.value}, which is not convex: its "
                "penetration depth (the translation distance) is not computed",
                E,
                other=K,
            )
        touching = code is OverlapCode.TOUCHING
    r = critical_distance(E, K, convex=convex, digits=digits)
    dist = flint.arb(0) if touching else r.distance
    return DistanceEnclosure(dist, r.point_E, r.point_Q, r.normal, r.bits, "ellipsoid-quadric")
