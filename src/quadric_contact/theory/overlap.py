"""Do the solids overlap?  The question of hard-particle Monte Carlo and collision libraries.

The predicates of the paper ask about *surfaces*: do they cross, on which side of ``Q``
is the surface of ``E``.  Users of HOOMD-blue (``test_overlap`` of two ellipsoids),
FCL/coal (``collide``) and hard-particle Monte Carlo ask about *solids*: an ellipsoid
inside another overlaps it although the surfaces do not cross.  This module answers that
question exactly for one pair (:func:`overlap_exact`); :func:`quadric_contact.overlap`
answers it for single pairs and stacks in every number mode.

The solids
----------
The solid of the ellipsoid ``E`` is its inside.  The solid of ``Q`` is its region
``R- = {X^T Q X <= 0}`` for ``Q`` with the sign of its standard form of Table 1
(:attr:`~quadric_contact.Quadric.canonical_sign`; the matrix as given for the two types
whose two sides are congruent, the plane and the hyperbolic paraboloid); type of ``Q``,
its standard form (Table 1), its solid ``R-``:

* ellipsoid, ``x^2/a^2 + y^2/b^2 + z^2/c^2 - 1``: the inside;
* hyperboloid of one sheet, ``x^2/a^2 + y^2/b^2 - z^2/c^2 - 1``: the inside of the tube;
* hyperboloid of two sheets, ``x^2/a^2 + y^2/b^2 - z^2/c^2 + 1``: the two cups;
* elliptic paraboloid, ``x^2/a^2 + y^2/b^2 - z``: the inside (``z >= ..``);
* hyperbolic paraboloid, the matrix as given: ``X^T Q X <= 0`` (one side);
* elliptic cylinder, ``x^2/a^2 + y^2/b^2 - 1``: the inside;
* hyperbolic cylinder, ``x^2/a^2 - y^2/b^2 - 1``: the region between the sheets (holding
  the axis);
* parabolic cylinder, ``x^2/a^2 - z``: the inside (``z >= ..``);
* parallel planes, ``x^2/a^2 - 1``: the slab between them;
* plane, the matrix as given (``n . x - d``): the half-space ``n . x <= d``.

Quadrics without a row of Table 1 and not planes (cones, intersecting planes, imaginary
quadrics, double planes, the zero matrix) are refused with
:class:`~quadric_contact.exact.errors.ExcludedQuadricError`.

The answers (:class:`~quadric_contact.modes.OverlapCode`)
---------------------------------------------------------
``SEPARATE``
    the closed solids are disjoint;
``TOUCHING``
    they meet and their interiors are disjoint (a tangency from outside);
``OVERLAPPING``
    their interiors meet, containment either way included: an ellipsoid inside another,
    even touching its boundary from inside, overlaps it (the interiors meet), so
    "touching from inside" is an overlap, not a touch;
``UNCERTAIN``
    only in the modes that abstain (``filter``, ``ball``).

Peers differ on a touch (HOOMD-blue's ellipsoid test and FCL's libccd solver answer no
overlap, FCL's own GJK solver answers overlap): ``touching="separate"`` (synonym
``"no-overlap"``) or ``touching="overlap"`` reads ``TOUCHING`` with their convention, after
the decision, in every mode and input form.

How it is decided
-----------------
With ``f = X^T Q X`` (``Q`` with the sign of its solid) on the surface of ``E``:

* the surfaces cross (``f`` takes both signs) => ``OVERLAPPING``;
* ``f <= 0`` on ``E`` (``E`` in the solid, touching its boundary or not) => ``OVERLAPPING``:
  no type has a bounded component of ``{f > 0}``, so all of ``E`` is in the solid;
* ``f > 0`` on ``E`` => ``SEPARATE``, but for an ellipsoid ``Q``, which may lie inside
  ``E``; ``f >= 0`` with a zero => ``TOUCHING``, with the same exception: no other type
  has a bounded component of ``{f < 0}``.

For two ellipsoids the Wang-Wang-Kim condition decides all three at once
(``proofs/wwk_2001_ellipsoid_separation.py``): with both matrices negative inside,
``P(lambda) = det(lambda E + Q)`` has at most two positive roots, and

* two distinct positive roots  <=>  ``SEPARATE``;
* a double positive root       <=>  ``TOUCHING`` (from outside);
* no positive root             <=>  ``OVERLAPPING``.

For the other types the separation certificate (a definite member of the pencil,
:mod:`quadric_contact.theory.certificate`) settles everything but tangencies, and the exact
relative position (:func:`~quadric_contact.theory.regions.relative_position_exact`) the rest.
The tangent points come from the singular members of the pencil at its multiple roots
(:mod:`quadric_contact.theory.contact_kind`).

References
----------
W. Wang, J. Wang, M.-S. Kim, An algebraic condition for the separation of two ellipsoids,
Computer Aided Geometric Design 18 (2001) 531-539.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from quadric_contact.exact.algebraic import QuadraticNumber, real_roots
from quadric_contact.exact.errors import ExcludedQuadricError, QuadricContactError, UndecidedError
from quadric_contact.model.classification import REFUSED_KINDS, TABLE_1_KINDS, QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.certificate import SeparationCertificate, separation_certificate
from quadric_contact.theory.contact_kind import _member, _multiple_roots
from quadric_contact.theory.pencil import CharacteristicPolynomial, as_quadric, characteristic_polynomial
from quadric_contact.theory.regions import relative_position_exact
from quadric_contact.theory.results import OverlapCode, Region

if TYPE_CHECKING:
    from quadric_contact.theory.contact_kind import SingularMember

__all__ = [
    "SOLID_KINDS",
    "TOUCHING_CONVENTIONS",
    "OverlapResult",
    "TouchingError",
    "apply_touching",
    "check_touching",
    "overlap_exact",
    "solid_of",
]

SOLID_KINDS: tuple[QuadricKind, ...] = (*TABLE_1_KINDS, QuadricKind.PLANE)
"""The types of ``Q`` whose solid :func:`overlap_exact` knows (Table 1 and the plane)."""

TOUCHING_CONVENTIONS: dict[str | None, OverlapCode | None] = {
    None: None,
    "separate": OverlapCode.SEPARATE,
    "no-overlap": OverlapCode.SEPARATE,
    "overlap": OverlapCode.OVERLAPPING,
}
"""How ``TOUCHING`` is read: reported as such (None, the default), as no overlap
(``"separate"``, or its synonym ``"no-overlap"``: HOOMD-blue's ellipsoid test, FCL's libccd
solver) or as an overlap (``"overlap"``: FCL's GJK solver)."""


class TouchingError(QuadricContactError, ValueError):
    """A touch was read as a yes or a no without a convention: pass ``touching="separate"``
    or ``touching="overlap"`` to :func:`~quadric_contact.overlap`, or read ``.code``."""


def check_touching(touching: str | None) -> OverlapCode | None:
    """The code a touch is read as (None: reported as ``TOUCHING``).

    Raises
    ------
    ValueError
        For a value that is not a key of :data:`TOUCHING_CONVENTIONS`.
    """
    if touching not in TOUCHING_CONVENTIONS:
        raise ValueError(
            f"touching must be None, 'separate' (or 'no-overlap') or 'overlap', got {touching!r}: None "
            "reports TOUCHING, 'separate' reads a touch as no overlap (HOOMD-blue, FCL's libccd), "
            "'overlap' as an overlap (FCL's GJK)"
        )
    return TOUCHING_CONVENTIONS[touching]


def apply_touching(codes: Any, touching: str | None) -> Any:
    """``codes`` (an int8 array of :class:`OverlapCode`, numpy or dask) with ``TOUCHING``
    read by the convention ``touching`` (unchanged for None).

    Examples
    --------
    >>> apply_touching(np.array([0, 1, 2, 3], dtype=np.int8), "separate")
    array([0, 1, 2, 0], dtype=int8)
    """
    target = check_touching(touching)
    if target is None:
        return codes
    return np.where(codes == OverlapCode.TOUCHING, np.int8(target), codes).astype(np.int8)


def solid_of(Q: Any, name: str = "Q") -> Quadric:
    """``Q`` with the sign of its solid: ``R- = {X^T Q X <= 0}`` of the result is the solid.

    Raises
    ------
    ExcludedQuadricError
        For a type without a solid (not in Table 1 and not a plane).

    Examples
    --------
    >>> solid_of("1 - x**2 - y**2 - z**2").equation()     # the unit ball, inside negative
    'x**2 + y**2 + z**2 - 1'
    >>> solid_of("1 - z").equation()                       # a plane: the matrix as given
    '1 - z'
    """
    q = as_quadric(Q, name)
    kind = q.kind
    if kind not in SOLID_KINDS:
        reason = kind.excluded_reason if kind in REFUSED_KINDS else None
        raise ExcludedQuadricError(
            f"{name} is {kind.value}: overlap is defined for the types of Table 1 and planes"
            + (f" ({reason})" if reason else ""),
            q,
            kind=kind,
        )
    return q if q.canonical_sign > 0 else -q


@dataclass(frozen=True)
class OverlapResult:
    """Answer of :func:`~quadric_contact.overlap` for one pair.

    Attributes
    ----------
    code : OverlapCode
        The answer, with the caller's convention for a touch applied (``SEPARATE``,
        ``OVERLAPPING``, ``TOUCHING`` or, in the abstaining modes, ``UNCERTAIN``).
    touching : bool or None
        The closed solids touch (meet with disjoint interiors), whatever the convention;
        None when undecided.
    decided_by : str or None
        ``"Wang-Wang-Kim"`` (two ellipsoids: the positive roots of ``P``),
        ``"separation certificate"`` (a definite member of the pencil, or four simple
        roots and none), ``"Remark 9"`` (non-real roots: the surfaces cross), ``"Theorem
        14"`` (a plane), or the result that decided the relative position.
    reason : str
        One sentence on why.
    polynomial : CharacteristicPolynomial
        ``det(lambda E + Q)`` for ``E`` (paper's sign) and ``Q`` with the sign of its solid.
    region : Region or None
        Where the surface of ``E`` lies against that ``Q`` (``R-``: in the solid, ``R+``:
        outside it, ``contact``: the surfaces cross), when it was needed or implied.
    certificate : SeparationCertificate or None
        The separation certificate, when it was computed.
    members : tuple of SingularMember
        Touching: the singular members ``lambda0 E + Q`` at the multiple roots of ``P``,
        whose singular points on ``E`` are the points of tangency.
    convention : str or None
        The ``touching`` option the answer was given with.
    mode : str
        The number mode that decided (``"exact"`` on the exact scalar path).

    Examples
    --------
    Two unit spheres two apart touch; HOOMD-blue's convention reads it as no overlap:

    >>> from quadric_contact import overlap
    >>> r = overlap("x**2 + y**2 + z**2 - 1", "(x - 2)**2 + y**2 + z**2 - 1")
    >>> r.code, r.decided_by, r.tangent_points
    (<OverlapCode.TOUCHING: 3>, 'Wang-Wang-Kim', ((1, 0, 0),))
    >>> bool(overlap("x**2 + y**2 + z**2 - 1", "(x - 2)**2 + y**2 + z**2 - 1", touching="separate"))
    False
    """

    code: OverlapCode
    touching: bool | None
    decided_by: str | None
    reason: str
    polynomial: CharacteristicPolynomial
    region: Region | None = None
    certificate: SeparationCertificate | None = None
    members: tuple[SingularMember, ...] = field(default=(), repr=False)
    convention: str | None = None
    mode: str = "exact"

    @property
    def decided(self) -> bool:
        return self.code is not OverlapCode.UNCERTAIN

    @property
    def relation(self) -> OverlapCode:
        """The geometric answer before the convention (``TOUCHING`` for a touch)."""
        return OverlapCode.TOUCHING if self.touching else self.code

    @property
    def overlapping(self) -> bool | None:
        """True or False, or None for ``TOUCHING`` (without a convention) and ``UNCERTAIN``."""
        return self.code.overlapping

    @property
    def tangent_points(self) -> tuple[tuple[Any, ...], ...]:
        """The points where the solids touch, exactly (coordinates in Q, as ints and
        Fractions, or in Q(sqrt d) as :class:`~quadric_contact.exact.algebraic.QuadraticNumber`),
        where they are isolated points in such a field; see :attr:`members` for the count
        and for a curve of tangency."""
        return tuple(tuple(_plain(c) for c in p) for m in self.members for p in m.points)

    @property
    def tangent_curve(self) -> bool:
        """The solids touch along a curve."""
        return any(m.curve for m in self.members)

    def __bool__(self) -> bool:
        if self.code is OverlapCode.UNCERTAIN:
            raise UndecidedError(f"overlap is undecided: {self.reason}", self)
        if self.code is OverlapCode.TOUCHING:
            raise TouchingError(
                "the solids touch (they meet, their interiors do not): pass touching='separate' "
                "(HOOMD-blue, FCL's libccd) or touching='overlap' (FCL's GJK) to read a touch as a "
                "yes or a no",
                self,
            )
        return self.code is OverlapCode.OVERLAPPING

    def to_dict(self) -> dict[str, Any]:
        """Everything as JSON-ready data (exact numbers as strings)."""
        return {
            "overlap": self.code.name.lower(),
            "relation": self.relation.name.lower(),
            "touching": self.touching,
            "convention": self.convention,
            "mode": self.mode,
            "decided_by": self.decided_by,
            "reason": self.reason,
            "region": None if self.region is None else self.region.value,
            "tangent_points": [[str(c) for c in p] for p in self.tangent_points],
            "tangent_curve": self.tangent_curve,
            "certificate": None if self.certificate is None else str(self.certificate),
            "polynomial": str(self.polynomial),
        }

    def __str__(self) -> str:
        name = self.code.name.lower()
        if self.touching and self.code is not OverlapCode.TOUCHING:
            name += f" (touching, read as {name} by touching={self.convention!r})"
        return f"{name} ({self.decided_by or 'undecided'}: {self.reason})"


def _plain(c: QuadraticNumber) -> Any:
    if c.d == 1:
        return int(c.a) if c.a.denominator == 1 else c.a
    return c


def _touching_members(P: CharacteristicPolynomial) -> tuple[SingularMember, ...]:
    """The singular members at the multiple roots of ``P`` with a point of tangency on ``E``
    (or a curve): where the surfaces touch."""
    members = []
    for lam in _multiple_roots(P):
        m, coincident = _member(lam, P.E, P.Q)
        if m.tangent_points or m.curve or coincident:
            members.append(m)
    return tuple(members)


def _approx(r: Any) -> str:
    return r.approx(6) if hasattr(r, "approx") else str(r)


def overlap_exact(E: Any, Q: Any, *, touching: str | None = None) -> OverlapResult:
    """Do the solids of the ellipsoid ``E`` and of ``Q`` overlap?  Decided exactly for one pair
    (the scalar path of :func:`quadric_contact.overlap` in the ``certified`` and ``exact`` modes).

    Parameters
    ----------
    E : Quadric, equation or matrix-like
        A real ellipsoid (either sign); its solid is its inside.
    Q : Quadric, equation or matrix-like
        A quadric of Table 1 or a plane; its solid is ``R-`` for the sign of its standard
        form (the half-space ``X^T Q X <= 0`` of the matrix as given for a plane).
    touching : {None, "separate", "overlap"}
        How to read a touch (see :data:`TOUCHING_CONVENTIONS`).

    Returns
    -------
    OverlapResult

    Raises
    ------
    NotAnEllipsoidError, ExcludedQuadricError, and the input errors.

    References
    ----------
    Wang, Wang and Kim (2001); the separation certificate; Theorems 13 and 14.

    Examples
    --------
    HOOMD-blue's test ellipsoids (semi-axes 3, 1, 2 and 2, 3, 1) five apart along ``x`` touch;
    at 4.9 they overlap, at 5.1 they are apart; an ellipsoid inside another overlaps it:

    >>> a = Quadric.ellipsoid(3, 1, 2)
    >>> [overlap_exact(a, Quadric.ellipsoid(2, 3, 1, center=(d, 0, 0))).code.name for d in ("4.9", 5, "5.1")]
    ['OVERLAPPING', 'TOUCHING', 'SEPARATE']
    >>> overlap_exact(Quadric.ellipsoid(20, 40, 50), Quadric.sphere(10)).reason
    'P has no positive root: the interiors meet'
    """
    convention = check_touching(touching)
    e = as_quadric(E, "E").as_ellipsoid()
    q = solid_of(Q)
    P = characteristic_polynomial(e, q)
    result = _two_ellipsoids(P) if q.kind is QuadricKind.ELLIPSOID else _other(P, e, q)
    if result.touching and convention is not None:
        result = replace(result, code=convention, convention=touching)
    elif touching is not None:
        result = replace(result, convention=touching)
    return result


def _two_ellipsoids(P: CharacteristicPolynomial) -> OverlapResult:
    """Wang, Wang and Kim: the positive roots of ``P`` decide."""
    roots = real_roots(list(P.coefficients), multiplicities=True)
    positive = [(r, m) for r, m in roots if r.sign() > 0]
    by = "Wang-Wang-Kim"
    if not positive:
        return OverlapResult(
            OverlapCode.OVERLAPPING, False, by, "P has no positive root: the interiors meet", P
        )
    if len(positive) == 2 and all(m == 1 for _, m in positive):
        cert = separation_certificate(P)
        (r1, _), (r2, _) = positive
        return OverlapResult(
            OverlapCode.SEPARATE,
            False,
            by,
            f"two distinct positive roots {_approx(r1)} < {_approx(r2)} of P: {cert}; no point is in "
            "both solids",
            P,
            Region.R_PLUS,
            cert,
        )
    if len(positive) == 1 and positive[0][1] == 2:
        members = _touching_members(P)
        return OverlapResult(
            OverlapCode.TOUCHING,
            True,
            by,
            f"a double positive root {_approx(positive[0][0])} of P: the solids touch from outside",
            P,
            Region.R_PLUS,
            None,
            members,
        )
    raise AssertionError(  # pragma: no cover - excluded by the Wang-Wang-Kim theorem
        f"two ellipsoids with positive roots {positive}: impossible (at most two, counted with multiplicity)"
    )


def _other(P: CharacteristicPolynomial, e: Quadric, q: Quadric) -> OverlapResult:
    """Any other type: the separation certificate, else the exact relative position."""
    cert = separation_certificate(P)
    by = "separation certificate"
    if cert.region is Region.R_PLUS:
        return OverlapResult(
            OverlapCode.SEPARATE, False, by, f"{cert}: E is strictly outside the solid", P, cert.region, cert
        )
    if cert.region is Region.R_MINUS:
        return OverlapResult(
            OverlapCode.OVERLAPPING,
            False,
            by,
            f"{cert}: E is strictly inside the solid",
            P,
            cert.region,
            cert,
        )
    if cert.region is Region.CONTACT:
        return OverlapResult(
            OverlapCode.OVERLAPPING, False, by, f"{cert}: the surfaces cross", P, cert.region, cert
        )

    region = relative_position_exact(e, q)
    if region.region is Region.CONTACT:
        return OverlapResult(
            OverlapCode.OVERLAPPING, False, region.decided_by, "the surfaces cross", P, Region.CONTACT, cert
        )
    members = _touching_members(P)
    if region.region is Region.R_MINUS:
        return OverlapResult(
            OverlapCode.OVERLAPPING,
            False,
            region.decided_by,
            "E is inside the solid, touching its boundary from inside: the interiors meet",
            P,
            Region.R_MINUS,
            cert,
            members,
        )
    if region.region is not Region.R_PLUS:  # pragma: no cover - the exact path always decides
        raise AssertionError(f"relative position undecided: {region}")
    return OverlapResult(
        OverlapCode.TOUCHING,
        True,
        region.decided_by,
        "E is outside the solid and touches its boundary (no definite member of the pencil)",
        P,
        Region.R_PLUS,
        cert,
        members,
    )
