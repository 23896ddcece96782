"""The codes of the array predicates, in one place (the integers the decision table reads are
:mod:`quadric_contact.theory.decision`'s, the layer below): the three-valued :class:`Sign`, the
result codes of each question, ``UNCERTAIN`` and ``INVALID``, the counts of which stage
decided how many entries, and the :class:`Provenance` (a :class:`Step` and its numbers) that
names a stage.

Every kernel, number mode and table of the package reads these names from here: the integer
constants (``UNCERTAIN``, ``INVALID``, ``EXCLUDED``) are what compiled code compares with, the
enums what callers read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum, IntEnum
from typing import Any

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.theory import decision as _table
from quadric_contact.theory.contact_kind import ContactKind
from quadric_contact.theory.results import OverlapCode, Region

__all__ = [
    "EXCLUDED",
    "INVALID",
    "UNCERTAIN",
    "ContactCode",
    "ContactKindCode",
    "CriterionCode",
    "OverlapCode",
    "Provenance",
    "RegionCode",
    "Sign",
    "SmallnessCode",
    "StageCounts",
    "StageMethod",
    "Step",
]

UNCERTAIN = _table.UNCERTAIN
"""The code of 'this mode cannot tell' (2) in every int8 array of the package (``Sign.UNCERTAIN``,
``ContactCode.UNCERTAIN``, ...): never read as false."""

EXCLUDED = 3
"""The smallness code of a quadric without a row of Table 1 (``SmallnessCode.EXCLUDED``)."""


class Sign(IntEnum):
    """A sign as a number mode knows it.

    ``UNCERTAIN`` means "this mode cannot tell"; it is never read as ``False``
    (``bool(Sign.UNCERTAIN)`` raises :class:`~quadric_contact.exact.errors.UndecidedError`),
    and in the int8 arrays of the modes its value 2 is non-zero.
    """

    NEGATIVE = -1
    ZERO = 0
    POSITIVE = 1
    UNCERTAIN = UNCERTAIN

    def __bool__(self) -> bool:
        if self is Sign.UNCERTAIN:
            raise UndecidedError("an UNCERTAIN sign has no truth value", self)
        return self is not Sign.ZERO

    @property
    def certain(self) -> bool:
        return self is not Sign.UNCERTAIN


class ContactCode(IntEnum):
    """Codes of the array predicate :func:`~quadric_contact.transversal_contact` (int8 arrays).

    ``CONTACT``: the surfaces of ``E`` and ``Q`` cross (transversal contact);
    ``NO_CONTACT``: they do not (apart, or touching without crossing); for every
    pair, small or not.  ``UNCERTAIN`` (only from the modes that abstain, ``filter``
    and ``ball``) is 2: non-zero, so a cast to bool reads it as a possible contact,
    never as a clearance.
    """

    NO_CONTACT = _table.NO_CONTACT
    CONTACT = _table.CONTACT
    UNCERTAIN = UNCERTAIN

    @property
    def transversal(self) -> bool | None:
        """True, False, or None for ``UNCERTAIN``."""
        return None if self is ContactCode.UNCERTAIN else self is ContactCode.CONTACT


class CriterionCode(IntEnum):
    """Codes of :func:`~quadric_contact.corollary_10`, the paper's raw criterion: the nature
    of the roots of ``P(lambda) = det(lambda E + Q)``, not the geometry.

    ``NON_REAL``: ``P`` has a pair of non-real roots (transversal contact for any pair,
    Remark 9); ``ALL_REAL``: all roots are real (no transversal contact *when* ``E`` is
    small with respect to ``Q``, Corollary 10; for a plane always, Theorem 14);
    ``UNCERTAIN``: the mode cannot tell.
    """

    ALL_REAL = 0
    NON_REAL = 1
    UNCERTAIN = UNCERTAIN


class ContactKindCode(IntEnum):
    """Codes of the array predicate :func:`~quadric_contact.contact_kind` (the rows of Table 3).

    ``NONE`` no contact, ``TRANSVERSAL`` the surfaces cross, ``UNCERTAIN`` (abstaining
    modes only), ``TANGENT_POINT``, ``TWO_TANGENT_POINTS``, ``TANGENT_CURVE``.
    """

    NONE = 0
    TRANSVERSAL = 1
    UNCERTAIN = UNCERTAIN
    TANGENT_POINT = 3
    TWO_TANGENT_POINTS = 4
    TANGENT_CURVE = 5

    @classmethod
    def from_kind(cls, kind: Any) -> ContactKindCode:
        """The code of a :class:`~quadric_contact.theory.contact_kind.ContactKind`."""
        return cls[str(getattr(kind, "name", kind)).upper()]

    def to_kind(self) -> Any:
        """The :class:`~quadric_contact.theory.contact_kind.ContactKind` of the code."""
        return ContactKind[self.name]


class SmallnessCode(IntEnum):
    """Codes of the array smallness predicate (int8 arrays).

    ``SMALL``: ``E`` is small with respect to ``Q`` in the direct sense (Table 1 row of
    ``Q`` holds): Corollary 10 and Theorem 13 / Table 4 apply.  ``SMALL_ENCLOSING``:
    two ellipsoids, small only because ``Q`` is small with respect to ``E``
    (Definition 1 is symmetric): Corollary 10 holds, Table 4 does not (the
    scalar report has ``small and not table_4_applies``).  ``EXCLUDED``: ``Q`` has no
    row in Table 1 (a plane, a cone, intersecting or coincident planes, a quadric
    without real points); the scalar :func:`~quadric_contact.theory.smallness.smallness`
    raises :class:`~quadric_contact.exact.errors.ExcludedQuadricError` there.
    ``UNCERTAIN`` only comes from the modes that abstain; it is non-zero, so a cast
    to bool never reads it as "not small".
    """

    NOT_SMALL = 0
    SMALL = 1
    UNCERTAIN = UNCERTAIN
    EXCLUDED = 3
    SMALL_ENCLOSING = 4

    @property
    def small(self) -> bool | None:
        """Definition 1: True for both small codes, False for ``NOT_SMALL``, None otherwise."""
        if self in (SmallnessCode.SMALL, SmallnessCode.SMALL_ENCLOSING):
            return True
        return False if self is SmallnessCode.NOT_SMALL else None

    @property
    def table_4_applies(self) -> bool | None:
        """True only for ``SMALL`` (Theorem 13 / Table 4 may be used), None when unknown."""
        if self in (SmallnessCode.UNCERTAIN, SmallnessCode.EXCLUDED):
            return None
        return self is SmallnessCode.SMALL


class RegionCode(IntEnum):
    """Codes of the array predicates :func:`~quadric_contact.relative_position` and
    :func:`~quadric_contact.plane_side` (int8 arrays).

    The three regions of :class:`~quadric_contact.theory.results.Region` are the sign of
    ``X^T Q X`` over the surface of the ellipsoid: ``R_MINUS = -1`` (``<= 0``),
    ``CONTACT = 0`` (both signs: the surfaces cross), ``R_PLUS = 1`` (``>= 0``);
    tangency counts as being in a region.  ``UNCERTAIN`` (2): an abstaining mode
    cannot tell.  Only the paper's raw reading of Table 4 (internal: the criterion
    stage) produces the last two: ``NO_ROW`` (3) all roots are real but their sign
    pattern is in no row of Table 4 for the type of ``Q``; ``EXCLUDED`` (4) ``Q`` is
    of a type without a row.
    """

    R_MINUS = _table.R_MINUS
    CONTACT = _table.R_CONTACT
    R_PLUS = _table.R_PLUS
    UNCERTAIN = UNCERTAIN
    NO_ROW = 3
    EXCLUDED = 4

    @property
    def region(self) -> Region | None:
        """The :class:`Region`, or None for the codes that are not regions."""
        return _CODE_TO_REGION.get(self)

    @classmethod
    def from_region(cls, region: Region | str | None) -> RegionCode:
        """The code of a region (None, as from an undecided result, is ``NO_ROW``)."""
        if region is None:
            return cls.NO_ROW
        return {v: k for k, v in _CODE_TO_REGION.items()}[Region(region)]


_CODE_TO_REGION = {
    RegionCode.R_MINUS: Region.R_MINUS,
    RegionCode.CONTACT: Region.CONTACT,
    RegionCode.R_PLUS: Region.R_PLUS,
}

INVALID = 5
"""Internal code of the float kernels: the entry failed validation (the
predicates diagnose it and raise the matching error)."""


class Step(Enum):
    """A step of the decision (:mod:`~quadric_contact.modes.decision.pipeline`), or of a mode's
    own questions, that can settle an entry; its value is how the stage counts name it."""

    CRITERION = "criterion"
    """The paper's criterion: the nature (and for a side, the signs) of the roots of ``P``."""
    SMALLNESS = "smallness"
    """Definition 1 through Tables 1-2 (the smallness question)."""
    SEPARATION = "separation"
    """The pencil's signature sequence, read through the decision table."""
    NO_REAL_POINTS = "no real points"
    """``Q`` has no real surface: it is never crossed, and ``X^T Q X`` has one sign."""
    EXACT_PAIR = "exact pair"
    """The exact scalar predicates, pair by pair."""


@dataclass(frozen=True)
class Provenance:
    """Which step settled an entry, and in what numbers: the data behind a stage count's name.

    ``str()`` gives the name the counts are keyed by: ``"<step> (<arithmetic>)"``, or the step
    alone when ``arithmetic`` is None.

    Attributes
    ----------
    step : Step
    arithmetic : str or None
        The numbers the step ran in, as the mode's stage names them (``"filter"``, ``"ball"``,
        ``"exact"``, ``"float"``, ``"mpmath"``, ...); for the steps that ran in no mode's numbers,
        what settled the entry instead: ``"type"`` (the type of ``Q``) or ``"outside binary64's
        range"`` (a plain mode's pairs that binary64 cannot hold, decided exactly).

    Examples
    --------
    >>> str(Provenance(Step.CRITERION, "filter")), str(Provenance(Step.EXACT_PAIR))
    ('criterion (filter)', 'exact pair')
    """

    step: Step
    arithmetic: str | None = None

    def __str__(self) -> str:
        if self.arithmetic is None:
            return self.step.value
        return f"{self.step.value} ({self.arithmetic})"


class StageMethod(Enum):
    """A stage a number mode implements (:class:`~quadric_contact.modes.NumberMode`): what the
    decision (:mod:`~quadric_contact.modes.decision.pipeline`) and the certified cascade ask a
    mode to run, as data; :meth:`run` calls it."""

    CRITERION_CONTACT = "criterion_contact"
    """The criterion: non-real roots or not."""
    CRITERION_REGION = "criterion_region"
    """The criterion and Table 4's reading of the root signs."""
    SEPARATION = "separation"
    """The separation certificate."""
    SMALLNESS = "smallness"
    """Definition 1 through Tables 1-2."""

    def run(self, mode: Any, pairs: Any) -> Any:
        """The codes of this stage of ``mode`` for ``pairs``."""
        if self is StageMethod.CRITERION_CONTACT:
            return mode.criterion_contact(pairs)
        if self is StageMethod.CRITERION_REGION:
            return mode.criterion_region(pairs)
        if self is StageMethod.SEPARATION:
            return mode.separation(pairs)
        return mode.smallness(pairs)


@dataclass
class StageCounts:
    """How many entries each stage of a mode decided, and how many stayed undecided.

    ``decided`` maps a stage name to a count: ``str()`` of the stage's :class:`Provenance`
    (``"criterion (filter)"``, ``"separation (exact)"``, ``"exact pair"``, ...), or a name given
    as a string; ``undecided`` counts entries returned ``UNCERTAIN``.  ``provenance`` holds the
    :class:`Provenance` behind each name that was added as one.
    """

    decided: dict[str, int] = field(default_factory=dict)
    undecided: int = 0
    provenance: dict[str, Provenance] = field(default_factory=dict, repr=False, compare=False)

    @property
    def total(self) -> int:
        return sum(self.decided.values()) + self.undecided

    @property
    def escalated(self) -> int:
        """Entries the first stage left to a later one (or left undecided)."""
        first = next(iter(self.decided.values()), 0)
        return self.total - first

    def add(self, stage: Provenance | str, count: int) -> None:
        """Count ``count`` entries (negative: take them back) as decided by ``stage``."""
        name = str(stage)
        self.decided[name] = self.decided.get(name, 0) + int(count)
        if isinstance(stage, Provenance):
            self.provenance.setdefault(name, stage)

    def merge(self, other: StageCounts) -> None:
        for stage, count in other.decided.items():
            self.add(other.provenance.get(stage, stage), count)
        self.undecided += other.undecided

    def deciding(self) -> Provenance | None:
        """The :class:`Provenance` of the first stage that decided an entry (for a stack of one:
        the stage that decided it); None when no stage decided one (or it was named by a
        string only).

        Examples
        --------
        >>> counts = StageCounts()
        >>> counts.add(Provenance(Step.CRITERION, "filter"), 0)
        >>> counts.add(Provenance(Step.SEPARATION, "filter"), 1)
        >>> counts.deciding()
        Provenance(step=<Step.SEPARATION: 'separation'>, arithmetic='filter')
        """
        name = next((stage for stage, count in self.decided.items() if count), None)
        return None if name is None else self.provenance.get(name)

    def __str__(self) -> str:
        parts = [f"{stage} {count}" for stage, count in self.decided.items() if count]
        if self.undecided:
            parts.append(f"undecided {self.undecided}")
        return ", ".join(parts) or "nothing"
