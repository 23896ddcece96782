"""What every number mode shares: the three-valued sign, the result codes of the
array predicates, the inputs they work on and the counts of who decided what.

A number mode is an object (CGAL's filtered kernels, mpmath's contexts): the
array predicates hand it validated matrices and read back codes; nothing in
the predicates branches on the mode's name.  The mode's base class itself,
which hands the questions to the pipeline, is
:class:`~quadric_contact.modes.number_mode.NumberMode`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import IntEnum
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.theory.results import OverlapCode, Region

__all__ = [
    "ContactCode",
    "ContactKindCode",
    "CriterionCode",
    "MatrixStack",
    "OverlapCode",
    "Pairs",
    "RegionCode",
    "Sign",
    "SmallnessCode",
    "StageCounts",
]


class Sign(IntEnum):
    """A sign as a number mode knows it.

    ``UNCERTAIN`` means "this mode cannot tell"; it is never read as ``False``
    (``bool(Sign.UNCERTAIN)`` raises :class:`~quadric_contact.exact.errors.UndecidedError`),
    and in the int8 arrays of the modes its value 2 is non-zero.
    """

    NEGATIVE = -1
    ZERO = 0
    POSITIVE = 1
    UNCERTAIN = 2

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

    NO_CONTACT = 0
    CONTACT = 1
    UNCERTAIN = 2

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
    UNCERTAIN = 2


class ContactKindCode(IntEnum):
    """Codes of the array predicate :func:`~quadric_contact.contact_kind` (the rows of Table 3).

    ``NONE`` no contact, ``TRANSVERSAL`` the surfaces cross, ``UNCERTAIN`` (abstaining
    modes only), ``TANGENT_POINT``, ``TWO_TANGENT_POINTS``, ``TANGENT_CURVE``.
    """

    NONE = 0
    TRANSVERSAL = 1
    UNCERTAIN = 2
    TANGENT_POINT = 3
    TWO_TANGENT_POINTS = 4
    TANGENT_CURVE = 5

    @classmethod
    def from_kind(cls, kind: Any) -> ContactKindCode:
        """The code of a :class:`~quadric_contact.theory.contact_kind.ContactKind`."""
        return cls[str(getattr(kind, "name", kind)).upper()]

    def to_kind(self) -> Any:
        """The :class:`~quadric_contact.theory.contact_kind.ContactKind` of the code."""
        from quadric_contact.theory.contact_kind import ContactKind

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
    UNCERTAIN = 2
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

    R_MINUS = -1
    CONTACT = 0
    R_PLUS = 1
    UNCERTAIN = 2
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


@dataclass
class StageCounts:
    """How many entries each stage of a mode decided, and how many stayed undecided.

    ``decided`` maps a stage name (``"float"``, ``"filter"``, ``"ball"``,
    ``"mpmath"``, ``"exact"``) to a count; ``undecided`` counts entries returned
    ``UNCERTAIN``.
    """

    decided: dict[str, int] = field(default_factory=dict)
    undecided: int = 0

    @property
    def total(self) -> int:
        return sum(self.decided.values()) + self.undecided

    @property
    def escalated(self) -> int:
        """Entries the first stage left to a later one (or left undecided)."""
        first = next(iter(self.decided.values()), 0)
        return self.total - first

    def add(self, stage: str, count: int) -> None:
        self.decided[stage] = self.decided.get(stage, 0) + int(count)

    def merge(self, other: StageCounts) -> None:
        for stage, count in other.decided.items():
            self.add(stage, count)
        self.undecided += other.undecided

    def __str__(self) -> str:
        parts = [f"{stage} {count}" for stage, count in self.decided.items() if count]
        if self.undecided:
            parts.append(f"undecided {self.undecided}")
        return ", ".join(parts) or "nothing"


class MatrixStack:
    """Validated symmetric matrices, ``n`` of them.

    Attributes
    ----------
    floats : ndarray, shape (n, 4, 4), float64
        The matrices in binary64 (C-contiguous).  When ``exact`` is None they
        *are* the input (a float is an exact dyadic rational); otherwise they are
        the correctly rounded values of ``exact``.  For packed input they are made
        from ``packed`` on first use (the fast kernels read ``packed`` itself).
    exact : ndarray of Fraction, shape (n, 10), or None
        The upper entries exactly, when the input was not binary64.
    checked : bool
        Symmetry and finiteness were verified on conversion (exact or packed input);
        float input is verified by the kernels that read it.
    name : str
        ``"E"`` or ``"Q"``, for messages.
    shape : tuple of int
        The caller's batch shape (``()`` for a single matrix), for messages.
    packed : ndarray, shape (n, 10), float64, or None
        The ten upper entries of each matrix (:func:`quadric_contact.pack`), when the
        input came packed.
    """

    __slots__ = ("_exact_signs", "_floats", "checked", "exact", "name", "packed", "shape")

    def __init__(
        self,
        floats: np.ndarray | None,
        exact: np.ndarray | None = None,
        checked: bool = False,
        name: str = "M",
        shape: tuple[int, ...] = (),
        packed: np.ndarray | None = None,
    ) -> None:
        if floats is None and packed is None:
            raise ValueError("a MatrixStack needs floats or packed entries")
        self._floats = floats
        self.exact = exact
        self.checked = checked
        self.name = name
        self.shape = shape
        self.packed = packed
        self._exact_signs: tuple[np.ndarray, np.ndarray] | None = None

    def exact_signs_memo(self) -> tuple[np.ndarray, np.ndarray]:
        """``(known, signs)``: per matrix, whether its exact invariant signs (``(8,)`` int8, as
        :meth:`quadric_contact.modes.objects.ObjectMode.invariant_signs` gives them) have been
        computed, and those signs; filled by the exact mode, once per matrix and stack."""
        if self._exact_signs is None:
            n = len(self)
            self._exact_signs = (np.zeros(n, dtype=bool), np.zeros((n, 8), dtype=np.int8))
        return self._exact_signs

    @property
    def floats(self) -> np.ndarray:
        if self._floats is None:
            from quadric_contact.modes.packing import unpack

            assert self.packed is not None
            self._floats = np.ascontiguousarray(unpack(self.packed))
        return self._floats

    @property
    def packed_only(self) -> bool:
        """Whether the stack holds packed entries that have not been unpacked (reading
        :attr:`floats` would unpack all of them)."""
        return self._floats is None

    def rows_floats(self, rows: np.ndarray) -> np.ndarray:
        """``floats[rows]`` (a new ``(k, 4, 4)`` array), without unpacking the rest of a packed stack."""
        if self._floats is None:
            from quadric_contact.modes.packing import unpack

            assert self.packed is not None
            return np.ascontiguousarray(unpack(self.packed[rows]))
        return np.ascontiguousarray(self._floats[rows])

    def kernel_array(self) -> tuple[np.ndarray, bool]:
        """The array the fast kernels read and whether it is packed: ``(n, 10)`` packed
        entries, or the ``(n, 16)`` flat view of ``floats``."""
        if self.packed is not None:
            return self.packed, True
        return self.floats.reshape(-1, 16), False

    def where(self, row: int) -> str:
        """``E[2, 1]``-style position of a matrix in the caller's array."""
        if not self.shape:
            return self.name
        idx = np.unravel_index(int(row), self.shape)
        return f"{self.name}[{', '.join(str(int(i)) for i in idx)}]"

    def __len__(self) -> int:
        return int((self.packed if self._floats is None else self._floats).shape[0])  # type: ignore[union-attr]

    def __repr__(self) -> str:
        layout = "packed" if self.packed is not None else "float64"
        return (
            f"MatrixStack({self.name}, {len(self)} matrices, {layout}{', rounded' if self.rounded else ''})"
        )

    @property
    def rounded(self) -> bool:
        return self.exact is not None

    def upper_exact(self, rows: np.ndarray) -> list[np.ndarray]:
        """The ten upper-entry columns of ``rows`` as object arrays of exact rationals
        (Fractions, or Python floats standing for their exact dyadic values)."""
        from quadric_contact.exact.entries import ENTRY_INDICES

        if self.exact is not None:
            sub = self.exact[rows]
            return [sub[:, k] for k in range(10)]
        if self._floats is None:
            assert self.packed is not None
            psub = self.packed[rows]
            return [psub[:, k].astype(object) for k in range(10)]
        sub = self.floats[rows]
        return [sub[:, i, j].astype(object) for i, j in ENTRY_INDICES]


@dataclass(frozen=True)
class Pairs:
    """The pairs ``(E[e_index[p]], Q[q_index[p]])`` for ``p`` in ``range(n)``.

    ``e_index`` is None when pair ``p`` uses ``E[p]`` (same length) or ``E[0]``
    (a single ellipsoid); likewise ``q_index``.
    """

    E: MatrixStack
    Q: MatrixStack
    n: int
    e_index: np.ndarray | None = None
    q_index: np.ndarray | None = None

    def e_rows(self) -> np.ndarray:
        return _rows(self.e_index, len(self.E), self.n)

    def q_rows(self) -> np.ndarray:
        return _rows(self.q_index, len(self.Q), self.n)

    def e_rows_at(self, which: np.ndarray) -> np.ndarray:
        """``e_rows()[which]``, without the rows of the whole batch."""
        return _rows_of(self.e_index, len(self.E), self.n, np.asarray(which, dtype=np.intp))

    def q_rows_at(self, which: np.ndarray) -> np.ndarray:
        """``q_rows()[which]``, without the rows of the whole batch."""
        return _rows_of(self.q_index, len(self.Q), self.n, np.asarray(which, dtype=np.intp))

    def take(self, which: np.ndarray) -> Pairs:
        """The sub-batch of the pairs ``which`` (indices into ``range(n)``).  A single matrix
        stays unindexed (no index of zeros to build and read back)."""
        which = np.asarray(which, dtype=np.intp)

        def index(own: np.ndarray | None, m: int) -> np.ndarray | None:
            if own is None and m == 1:
                return None  # the one matrix
            return _rows_of(own, m, self.n, which)

        return Pairs(self.E, self.Q, int(which.size), index(self.e_index, len(self.E)),
                     index(self.q_index, len(self.Q)))  # fmt: skip

    def kernel_indices(self) -> tuple[np.ndarray, np.ndarray, int, int]:
        """``(e_index, q_index, e_stride, q_stride)`` as the float kernels read them:
        an empty index array means ``row = p * stride``."""
        empty = np.zeros(0, dtype=np.intp)
        out: list[Any] = []
        for index in (self.e_index, self.q_index):
            out.append(empty if index is None else np.ascontiguousarray(index, dtype=np.intp))
        strides = [0 if (self.e_index is not None or len(self.E) == 1) else 1]
        strides.append(0 if (self.q_index is not None or len(self.Q) == 1) else 1)
        return out[0], out[1], strides[0], strides[1]


def _rows_of(index: np.ndarray | None, m: int, n: int, which: np.ndarray) -> np.ndarray:
    """``_rows(index, m, n)[which]`` without building the rows of the whole batch (the cascade
    takes a few pairs out of millions)."""
    if index is not None:
        return np.asarray(index, dtype=np.intp)[which]
    if m == n:
        return which.copy()
    return np.zeros(which.size, dtype=np.intp)


def _rows(index: np.ndarray | None, m: int, n: int) -> np.ndarray:
    if index is not None:
        return np.asarray(index, dtype=np.intp)
    if m == n:
        return np.arange(n, dtype=np.intp)
    return np.zeros(n, dtype=np.intp)


def as_fraction_array(values: Any) -> np.ndarray:
    """An object array of Fractions (helper for tests and fixtures)."""
    arr = np.asarray(values, dtype=object)
    return np.vectorize(Fraction, otypes=[object])(arr)
