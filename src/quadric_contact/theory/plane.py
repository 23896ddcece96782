"""An ellipsoid against a plane (Theorem 14, Corollary 15, Remark 16).

For any ellipsoid ``E`` (no smallness needed) and a plane ``P``,
``det(lambda*E + P) = lambda^2 (c4 lambda^2 + c3 lambda + c2)`` (eq. (12)):

* transversal contact iff ``c3^2 < 4 c4 c2`` (Corollary 15 (1); the paper
  prints ``4 c1 c2``, which is always 0 for a plane: an erratum);
* otherwise ``E`` is in ``R+`` iff ``c3 > 0`` and in ``R-`` iff ``c3 < 0``
  (Corollary 15 (2)); ``c3^2 = 4 c4 c2`` is tangency.

Every sign is taken on the integer polynomial (see :mod:`quadric_contact.theory.pencil`).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from quadric_contact.exact.errors import NotAPlaneError
from quadric_contact.model.classification import QuadricKind
from quadric_contact.theory.pencil import as_quadric, characteristic_polynomial
from quadric_contact.theory.results import PlaneSideResult, Region

__all__ = ["plane_side_exact"]


def plane_side_exact(E: Any, P: Any) -> PlaneSideResult:
    """Which side of the plane ``P`` is the ellipsoid ``E`` on, or does it cross it?
    Decided exactly for one pair (the scalar path of the ``certified`` and ``exact``
    modes of :func:`quadric_contact.plane_side`).

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid (either sign).
    P : Quadric, matrix-like or equation
        A plane (a matrix with zero quadratic part); ``R-`` is where
        ``X^T P X <= 0``.

    Returns
    -------
    PlaneSideResult
        ``.zone`` is ``R-`` (Algorithm 1's Zone 2), ``R+`` (Zone 1) or
        ``contact`` (Zone 0); ``.tangent``; the coefficients used and, for
        audit, the value of the plane's equation at the centre of ``E``
        (Remark 16), whose sign agrees whenever there is no contact.

    Raises
    ------
    NotAPlaneError
        If ``P`` is not a plane.
    NotAnEllipsoidError
        If ``E`` is not a real ellipsoid.

    References
    ----------
    Theorem 14, Corollary 15, Remark 16, Algorithm 1.

    Examples
    --------
    Example 17, the bee against the plane ``z = 6``: ``c3 = -3/2 < 0``, Zone 2.

    >>> r = plane_side_exact("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "z - 6")
    >>> r.zone, r.algorithm_1_zone, r.c3
    (<Region.R_MINUS: 'R-'>, 2, Fraction(-3, 2))

    Theorem 14, eq. (12): the unit sphere centred at ``(0, 0, 2)`` and the
    plane ``z = 0``, ``P = -lambda^2 (1 + 4 lambda (lambda - 2)) / 4``:

    >>> from quadric_contact import Quadric
    >>> r = plane_side_exact(Quadric.sphere(1, center=(0, 0, 2)), "z")
    >>> r.polynomial.coefficients[2:], r.zone
    ((Fraction(-1, 4), Fraction(2, 1), Fraction(-1, 1)), <Region.R_PLUS: 'R+'>)

    Remark 16: for ``E`` with semi-axes ``alpha, beta, gamma`` (eq. (2)
    normalisation) ``c3`` is the plane's equation at the centre divided by
    ``alpha^2 beta^2 gamma^2``:

    >>> r = plane_side_exact(Quadric.ellipsoid(2, 1, 1, center=(1, 2, 3)), "x + 2*y + 2*z - 4")
    >>> r.center_value, r.c3, r.c3 == r.center_value / (2**2 * 1**2 * 1**2)
    (Fraction(7, 1), Fraction(7, 4), True)
    """
    plane = as_quadric(P, "P")
    if plane.kind is not QuadricKind.PLANE:
        raise NotAPlaneError(f"expected a plane, got {plane.kind.value}", plane, kind=plane.kind)
    poly = characteristic_polynomial(E, plane)
    C = poly.integer_coefficients
    assert C[0] == 0 and C[1] == 0, "a plane gives c0 = c1 = 0 (eq. (12))"
    disc = C[3] * C[3] - 4 * C[4] * C[2]  # same sign as c3^2 - 4 c4 c2
    c0, c1, c2, c3, c4 = poly.coefficients
    center = poly.E.center()
    assert center is not None
    center_value = plane.value_at(center)
    if disc < 0:
        zone, tangent = Region.CONTACT, False
        reason = "c3^2 < 4 c4 c2: the two non-zero roots are non-real"
    else:
        tangent = disc == 0
        zone = Region.R_PLUS if C[3] > 0 else Region.R_MINUS
        reason = f"c3^2 {'=' if tangent else '>'} 4 c4 c2 and c3 {'>' if C[3] > 0 else '<'} 0"
    return PlaneSideResult(
        zone, tangent, "Corollary 15", reason, poly, Fraction(c2), Fraction(c3), Fraction(c4), center_value
    )
