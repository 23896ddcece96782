"""Result objects of the predicates.

Every answer says which result of the paper decided it and the values it
looked at, so that a user can audit it; an answer the theory did not decide
says so (``decided is False``) and refuses to be read as a boolean.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from enum import IntEnum, StrEnum
from fractions import Fraction
from functools import cached_property
from typing import TYPE_CHECKING, Any

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.printing import json_number

if TYPE_CHECKING:
    from quadric_contact.exact.descartes import RootSigns
    from quadric_contact.exact.discriminants import RootStructure
    from quadric_contact.theory.pencil import CharacteristicPolynomial

__all__ = ["ContactResult", "OverlapCode", "PlaneSideResult", "Region", "RegionResult"]


class Region(StrEnum):
    """Where the ellipsoid is with respect to ``Q`` (paper eq. (8)).

    ``R-`` is ``{X^T Q X <= 0}``, ``R+`` is ``{X^T Q X >= 0}`` for the matrix
    *as given*; tangent contact still counts as ``R-`` or ``R+``; ``contact``
    means transversal contact.

    Examples
    --------
    >>> Region("R-").swapped(), Region.R_PLUS == "R+"
    (<Region.R_PLUS: 'R+'>, True)
    """

    R_MINUS = "R-"
    R_PLUS = "R+"
    CONTACT = "contact"

    def __str__(self) -> str:
        return self.value

    def swapped(self) -> Region:
        """The region for ``-Q``."""
        return {Region.R_MINUS: Region.R_PLUS, Region.R_PLUS: Region.R_MINUS}.get(self, self)


def _json_number(x: Any) -> Any:
    return json_number(x) if isinstance(x, Fraction) else x


def _poly_dict(P: CharacteristicPolynomial) -> dict[str, Any]:
    d2, d3, d4 = P.deltas()
    return {
        "polynomial": str(P),
        "coefficients": [_json_number(c) for c in P.coefficients],
        "delta2": _json_number(d2),
        "delta3": _json_number(d3),
        "delta4": _json_number(d4),
        "roots": P.structure.describe(),
        "root_signs": P.signs.pattern,
        "root_signs_method": P.signs.method,
        "e_flipped": P.e_flipped,
    }


@dataclass(frozen=True, eq=False, repr=False)
class ContactResult:
    """Answer of :func:`~quadric_contact.transversal_contact`.

    Attributes
    ----------
    transversal : bool or None
        None when the theory did not decide.
    decided_by : str or None
        The result that decided it ("Remark 9", "Corollary 10", "Theorem 14",
        "geometric decision", ...).
    reason : str
        One sentence on why (written when first read: the constructor's third argument, ``because``,
        is the sentence or a function without arguments that writes it).
    polynomial : CharacteristicPolynomial
    smallness : object
        The smallness report used (or ``"asserted by caller"``, or None).
    geometric : SeparationCertificate, GeometricDecision or None
        The exact smallness-free decision, when one decided (``decided_by`` is
        ``"separation certificate"`` or ``"geometric decision"``).
    mode : str
        The number mode that decided (``"exact"`` for the exact scalar path of the
        ``certified`` and ``exact`` modes); the polynomial and its Deltas are exact
        in every mode, for audit.

    Examples
    --------
    Example 17, the bee and the trunk:

    >>> from quadric_contact import transversal_contact
    >>> r = transversal_contact("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> r.transversal, r.decided_by
    (False, 'signature sequence')
    >>> r.reason
    'the member 3675/32 E + Q is positive definite: X^T Q X > 0 on E (R+, strictly)'
    >>> f"{float(r.delta4):.6g}", r.root_signs.pattern
    ('6.90965e+08', '-+++')
    """

    transversal: bool | None
    decided_by: str | None
    because: str | Callable[[], str]
    polynomial: CharacteristicPolynomial
    smallness: Any = None
    geometric: Any = None
    mode: str = "exact"

    @cached_property
    def reason(self) -> str:
        """One sentence on why.  Writing it (exact numbers in decimal) costs about as much as a
        tenth of the decision on binary64 input, so it is written when first read."""
        return self.because if isinstance(self.because, str) else self.because()

    def _key(self) -> tuple[Any, ...]:
        return (
            self.transversal,
            self.decided_by,
            self.reason,
            self.polynomial,
            self.smallness,
            self.geometric,
            self.mode,
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, ContactResult):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash((self.transversal, self.decided_by, self.reason, self.mode))

    def __repr__(self) -> str:
        return (
            f"ContactResult(transversal={self.transversal!r}, decided_by={self.decided_by!r}, "
            f"reason={self.reason!r}, polynomial={self.polynomial!r}, smallness={self.smallness!r}, "
            f"geometric={self.geometric!r}, mode={self.mode!r})"
        )

    @property
    def decided(self) -> bool:
        """The theory (or the geometric decision) gave an answer."""
        return self.transversal is not None

    def __bool__(self) -> bool:
        if self.transversal is None:
            raise UndecidedError(f"transversal contact is undecided: {self.reason}", self)
        return self.transversal

    @property
    def delta3(self) -> Fraction:
        """The paper's ``Delta_3`` of ``P`` (Section 3.2)."""
        return self.polynomial.deltas()[1]

    @property
    def delta4(self) -> Fraction:
        """The paper's ``Delta_4`` of ``P`` (Section 3.2, corrected)."""
        return self.polynomial.deltas()[2]

    @property
    def root_structure(self) -> RootStructure:
        """Exact numbers and multiplicities of the real and non-real roots of ``P``."""
        return self.polynomial.structure

    @property
    def root_signs(self) -> RootSigns:
        """Exact root-sign pattern of ``P`` (Table 4 notation)."""
        return self.polynomial.signs

    def to_dict(self) -> dict[str, Any]:
        """Everything as JSON-ready data (exact numbers as strings)."""
        return {
            "transversal_contact": self.transversal,
            "decided": self.decided,
            "mode": self.mode,
            "decided_by": self.decided_by,
            "reason": self.reason,
            "smallness": _smallness_repr(self.smallness),
            **_poly_dict(self.polynomial),
            "geometric": None if self.geometric is None else str(self.geometric),
        }

    def __str__(self) -> str:
        verdict = {True: "transversal contact", False: "no transversal contact", None: "UNDECIDED"}[
            self.transversal
        ]
        return f"{verdict} ({self.decided_by or 'no result applies'}: {self.reason})"


def _smallness_repr(s: Any) -> Any:
    if s is None or isinstance(s, (str, bool)):
        return s
    verdict = getattr(s, "small", None)
    return {"small": verdict, "report": str(s)}


@dataclass(frozen=True)
class RegionResult:
    """Answer of :func:`~quadric_contact.relative_position`.

    Compares equal to its :class:`Region` (``result == "R-"`` works).

    Attributes
    ----------
    region : Region or None
        ``R-``, ``R+``, ``contact``, or None when undecided.
    decided_by : str or None
        ``"Theorem 13 / Table 4"``, ``"Theorem 14"``, ``"Remark 9"``,
        ``"geometric decision"``, ...
    reason : str
    polynomial : CharacteristicPolynomial
    contact : ContactResult or None
        The transversal-contact decision it relied on (exact path).
    expected : dict
        The Table 4 root-sign pattern of each region for ``Q`` as given.
    mode : str
        The number mode that decided (``"exact"`` on the exact scalar path).

    Examples
    --------
    >>> from quadric_contact import relative_position
    >>> r = relative_position("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> r == "R+", r.expected
    (True, {'R-': '---+', 'R+': '-+++'})
    """

    region: Region | None
    decided_by: str | None
    reason: str
    polynomial: CharacteristicPolynomial
    contact: ContactResult | None
    expected: dict[str, str] = field(default_factory=dict)
    mode: str = "exact"

    @property
    def decided(self) -> bool:
        """A region (or contact) was decided."""
        return self.region is not None

    def require(self) -> Region:
        """The region, or :class:`UndecidedError` if the theory did not decide."""
        if self.region is None:
            raise UndecidedError(f"relative position is undecided: {self.reason}", self)
        return self.region

    def __bool__(self) -> bool:
        raise TypeError("a RegionResult has no truth value; compare it with a Region")

    def __eq__(self, other: object) -> bool:
        if isinstance(other, RegionResult):
            return self.region == other.region and self.polynomial == other.polynomial
        if isinstance(other, (Region, str)):
            return self.region is not None and self.region == Region(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.region)

    def to_dict(self) -> dict[str, Any]:
        """Everything as JSON-ready data (exact numbers as strings)."""
        return {
            "region": self.region.value if self.region else None,
            "decided": self.decided,
            "mode": self.mode,
            "decided_by": self.decided_by,
            "reason": self.reason,
            "table_4_patterns": self.expected,
            **_poly_dict(self.polynomial),
        }

    def __str__(self) -> str:
        where = self.region.value if self.region else "UNDECIDED"
        return f"{where} ({self.decided_by or 'no result applies'}: {self.reason})"


@dataclass(frozen=True)
class PlaneSideResult:
    """Answer of :func:`~quadric_contact.plane_side` (Theorem 14, Corollary 15).

    ``zone`` is ``R-`` (Algorithm 1's Zone 2), ``R+`` (Zone 1) or ``contact``
    (Zone 0, transversal contact), or None when an abstaining number mode cannot
    tell; ``tangent`` is True when the plane touches the ellipsoid (a double
    non-zero root), None when the number mode does not decide tangency.  ``c2, c3, c4`` are the
    coefficients of ``P(lambda) = lambda^2 (c4 lambda^2 + c3 lambda + c2)``
    (eq. (12)) and ``center_value`` the plane's equation at the ellipsoid's
    centre (Remark 16).

    Examples
    --------
    Example 17, Algorithm 1 for the bee and the plane ``z = 6``:

    >>> from quadric_contact import plane_side
    >>> r = plane_side("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "z - 6")
    >>> print(r)
    R- (Corollary 15: c3^2 > 4 c4 c2 and c3 < 0)
    >>> r.discriminant, r.tangent
    (Fraction(39, 20), False)
    """

    zone: Region | None
    tangent: bool | None
    decided_by: str | None
    reason: str
    polynomial: CharacteristicPolynomial
    c2: Fraction
    c3: Fraction
    c4: Fraction
    center_value: Fraction
    mode: str = "exact"

    @property
    def decided(self) -> bool:
        """False only for an ``UNCERTAIN`` answer of an abstaining number mode."""
        return self.zone is not None

    @property
    def discriminant(self) -> Fraction:
        """``c3^2 - 4 c4 c2``: negative exactly when the contact is transversal."""
        return self.c3 * self.c3 - 4 * self.c4 * self.c2

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (Region, str)):
            return self.zone is not None and self.zone == Region(other)
        if isinstance(other, PlaneSideResult):
            return self.zone == other.zone and self.polynomial == other.polynomial
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.zone)

    @property
    def algorithm_1_zone(self) -> int:
        """Zone number of Algorithm 1: 1 for R+, 2 for R-, 0 for contact."""
        if self.zone is None:
            raise UndecidedError(f"the zone is undecided: {self.reason}", self)
        return {Region.R_PLUS: 1, Region.R_MINUS: 2, Region.CONTACT: 0}[self.zone]

    def to_dict(self) -> dict[str, Any]:
        """Everything as JSON-ready data (exact numbers as strings)."""
        return {
            "zone": None if self.zone is None else self.zone.value,
            "algorithm_1_zone": None if self.zone is None else self.algorithm_1_zone,
            "mode": self.mode,
            "tangent": self.tangent,
            "decided_by": self.decided_by,
            "reason": self.reason,
            "c3_squared_minus_4_c4_c2": _json_number(self.discriminant),
            "center_value": _json_number(self.center_value),
            **_poly_dict(self.polynomial),
        }

    def __str__(self) -> str:
        t = " (tangent)" if self.tangent else ""
        where = "UNDECIDED" if self.zone is None else self.zone.value
        return f"{where}{t} ({self.decided_by or 'no result applies'}: {self.reason})"


class OverlapCode(IntEnum):
    """Codes of the array predicate :func:`~quadric_contact.overlap` (do the solids overlap?).

    The solid of ``E`` is its inside; the solid of ``Q`` is its region ``R-`` for the sign
    of its standard form (the matrix as given for a plane or a hyperbolic paraboloid):
    ``SEPARATE`` the closed solids are disjoint; ``OVERLAPPING`` their interiors meet
    (containment either way included); ``TOUCHING`` they meet and their interiors are
    disjoint.  ``UNCERTAIN`` (2, abstaining modes only) is non-zero, so a cast to bool reads
    it as a possible overlap, never as a clearance; so is ``TOUCHING`` (3), unless the caller
    chose a convention (``touching="separate"`` or ``"overlap"``).

    Also the code of an exact :class:`~quadric_contact.theory.overlap.OverlapResult`; it lives
    here, with the other results, so that :mod:`quadric_contact.theory.overlap` does not import
    the number modes (:mod:`quadric_contact.modes.codes` re-exports it with the other codes).
    """

    SEPARATE = 0
    OVERLAPPING = 1
    UNCERTAIN = 2
    TOUCHING = 3

    @property
    def overlapping(self) -> bool | None:
        """True (interiors meet), False (closed solids disjoint), None (touching, uncertain)."""
        return {OverlapCode.SEPARATE: False, OverlapCode.OVERLAPPING: True}.get(self)
