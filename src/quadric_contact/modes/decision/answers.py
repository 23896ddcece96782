"""From signs to answers: the part of every predicate that no number mode changes.

A number mode produces three-valued signs (``-1, 0, 1`` and ``UNCERTAIN = 2``) of
``c0 .. c4``, ``Delta_2 .. Delta_4`` and a few invariants; the functions here turn
them into :class:`~quadric_contact.modes.codes.ContactCode` and
:class:`~quadric_contact.modes.codes.RegionCode`.  They are written once, as
small scalar functions over integers that numba compiles into the float kernels
and that the other modes call through :func:`contact_from_signs` and
:func:`~quadric_contact.modes.kernels.support_drivers.region_from_signs`.  An uncertain sign
is resolved by trying every value it could take: the answer is given only if all of them agree.

Conventions
-----------
* The signs of ``c0 .. c4`` are those of ``det(lambda E + Q)`` for ``E`` with the
  paper's sign (``det E < 0``, inside negative): a mode that meets ``-E`` negates
  ``c1`` and ``c3`` (the roots change sign) before calling in.
* ``c4 = det E != 0`` for an ellipsoid, so Yang's ``D_1 = 4 c4^2 > 0`` and the
  signs of ``D_2, D_3, D_4`` are those of the paper's ``Delta_2, Delta_3, Delta_4``
  (:func:`quadric_contact.codegen.derive_paper_deltas`).
* A quadric enters through its *row*: ``2 * kind_index + (canonical sign < 0)``
  (:data:`KINDS` order), or :data:`UNCERTAIN_ROW`.
"""

from __future__ import annotations

from functools import cache
from itertools import pairwise, product
from typing import Any

import numpy as np

from quadric_contact.exact.discriminants import revised_sign_list
from quadric_contact.model.classification import (
    NO_REAL_POINTS,
    QuadricKind,
    inertia_from_minor_sums,
    kind_from_inertia,
)
from quadric_contact.modes.codes import UNCERTAIN, ContactCode, RegionCode
from quadric_contact.modes.kernels import signs
from quadric_contact.modes.kernels._jit import njit
from quadric_contact.theory.regions import ROOT_SIGN_TABLE
from quadric_contact.theory.results import Region

__all__ = [
    "CONTACT_TABLE",
    "KINDS",
    "ROWS",
    "UNCERTAIN_ROW",
    "contact_from_signs",
    "ellipsoid_from_signs",
    "ellipsoid_status",
    "kind_from_invariant_signs",
    "masks_from_invariant_signs",
    "region_code",
    "region_code_masked",
    "row_of",
    "rows_from_invariant_signs",
    "rows_from_masks",
    "sign_index",
]

_CONCRETE = (-1, 0, 1)


sign_index = signs.sign_index
"""``-1, 0, 1, UNCERTAIN`` -> ``0, 1, 2, 3`` (the index into the tables): the kernels' own
(:func:`~quadric_contact.modes.kernels.signs.sign_index`), on scalars and on columns."""


def _completions(signs: tuple[int, ...]) -> list[tuple[int, ...]]:
    choices = [_CONCRETE if s == UNCERTAIN else (s,) for s in signs]
    return list(product(*choices))


# -- transversal contact: Yang's revised sign list -----------------------------------


def _contact_certain(s2: int, s3: int, s4: int) -> int:
    """Non-real roots iff the revised sign list of ``(D1, D2, D3, D4)`` with ``D1 > 0``
    has a sign change (Yang 1999, Theorem 1; see :mod:`quadric_contact.exact.discriminants`)."""
    rev = [s for s in revised_sign_list([1, s2, s3, s4]) if s]
    changes = sum(1 for a, b in pairwise(rev) if a != b)
    return int(ContactCode.CONTACT if changes else ContactCode.NO_CONTACT)


def _build_contact_table() -> np.ndarray:
    table = np.empty(64, dtype=np.int8)
    for s2, s3, s4 in product((-1, 0, 1, UNCERTAIN), repeat=3):
        answers = {_contact_certain(*c) for c in _completions((s2, s3, s4))}
        code = answers.pop() if len(answers) == 1 else int(ContactCode.UNCERTAIN)
        table[sign_index(s2) + 4 * sign_index(s3) + 16 * sign_index(s4)] = code
    return table


CONTACT_TABLE = _build_contact_table()
""":class:`ContactCode` for the signs of ``(Delta_2, Delta_3, Delta_4)``, indexed by
``sign_index(s2) + 4 sign_index(s3) + 16 sign_index(s4)``."""


def contact_from_signs(s2: Any, s3: Any, s4: Any) -> np.ndarray:
    """Vectorised :data:`CONTACT_TABLE` lookup (int8 sign arrays in, int8 codes out)."""
    idx = sign_index(_column(s2)) + 4 * sign_index(_column(s3)) + 16 * sign_index(_column(s4))
    return CONTACT_TABLE[idx]


def _column(s: Any) -> np.ndarray:
    """Signs as an array of indices' type (:func:`sign_index` of it indexes the tables)."""
    return np.asarray(s, dtype=np.intp)


# -- is E an ellipsoid (Sylvester) -----------------------------------------------------

ELLIPSOID_NOT = 0
ELLIPSOID_YES = 1
ELLIPSOID_UNCERTAIN = 2


def ellipsoid_status(s_a00: int, s_m2: int, s_m3: int, s_det: int) -> int:
    """Is the symmetric ``E`` a real ellipsoid (either sign)?

    Sylvester: the quadratic part is definite iff ``m2 > 0`` and ``m3`` has the
    sign of ``a00 != 0``; then ``E`` is a real ellipsoid iff ``det E < 0`` (for
    ``E`` and ``-E`` alike, the determinant of a 4x4 matrix being even).
    ``s_a00`` is the sign of an input entry, always certain.
    """
    c1 = 2 if s_m2 == UNCERTAIN else int(s_m2 == 1)
    c2 = 2 if s_m3 == UNCERTAIN else int(s_m3 == s_a00 and s_a00 != 0)
    c3 = 2 if s_det == UNCERTAIN else int(s_det == -1)
    if c1 == 0 or c2 == 0 or c3 == 0:
        return ELLIPSOID_NOT
    if c1 == 2 or c2 == 2 or c3 == 2:
        return ELLIPSOID_UNCERTAIN
    return ELLIPSOID_YES


def _build_ellipsoid_table() -> np.ndarray:
    table = np.empty((3, 4, 4, 4), dtype=np.int8)
    for sa, s2, s3, s4 in product((-1, 0, 1), *([(-1, 0, 1, UNCERTAIN)] * 3)):
        table[sa + 1, sign_index(s2), sign_index(s3), sign_index(s4)] = ellipsoid_status(sa, s2, s3, s4)
    return table


ELLIPSOID_TABLE = _build_ellipsoid_table()
""":func:`ellipsoid_status` indexed by ``[s_a00 + 1, sign_index(m2), sign_index(m3), sign_index(det)]``."""


def ellipsoid_from_signs(s_a00: Any, s_m2: Any, s_m3: Any, s_det: Any) -> np.ndarray:
    """Vectorised :data:`ELLIPSOID_TABLE` lookup."""
    sa = np.asarray(s_a00, dtype=np.intp) + 1
    m2, m3, det = sign_index(_column(s_m2)), sign_index(_column(s_m3)), sign_index(_column(s_det))
    return ELLIPSOID_TABLE[sa, m2, m3, det]


# -- quadric types and their Table 4 rows -----------------------------------------------

KINDS: tuple[QuadricKind, ...] = tuple(QuadricKind)
"""Kind index order of the rows."""

ROW_TABLE = 0  # a row of Table 4 (Theorem 14 for planes)
ROW_EXCLUDED = 1  # real points but no row of Table 4
ROW_NO_REAL_POINTS = 2
ROW_UNCERTAIN = 3


def _pattern_counts(pattern: str) -> tuple[int, int]:
    return pattern.count("-"), pattern.count("0")


def _row(kind: QuadricKind, sign: int) -> tuple[int, int, int, int, int]:
    if kind in NO_REAL_POINTS:
        return (ROW_NO_REAL_POINTS, -1, -1, -1, -1)
    if kind not in ROOT_SIGN_TABLE:
        return (ROW_EXCLUDED, -1, -1, -1, -1)
    expected = dict(ROOT_SIGN_TABLE[kind])
    if sign < 0:
        # As relative_position does: for -Q_std the roots change sign and R-/R+ swap.
        flip = str.maketrans("-+", "+-")
        expected = {
            r.swapped(): "".join(sorted(p.translate(flip), key="-0+".index)) for r, p in expected.items()
        }
    mn, mz = _pattern_counts(expected[Region.R_MINUS])
    pn, pz = _pattern_counts(expected[Region.R_PLUS])
    return (ROW_TABLE, mn, mz, pn, pz)


def _build_rows() -> np.ndarray:
    rows = [_row(kind, sign) for kind in KINDS for sign in (1, -1)]
    rows.append((ROW_UNCERTAIN, -1, -1, -1, -1))
    return np.array(rows, dtype=np.int8)


ROWS = _build_rows()
"""``(class, R- negatives, R- zeros, R+ negatives, R+ zeros)`` per row: the numbers of
negative and zero roots Table 4 (as :mod:`quadric_contact.theory.regions` derives it)
expects in each region, for the caller's sign of ``Q``."""

UNCERTAIN_ROW = len(ROWS) - 1


def row_of(kind: QuadricKind, canonical_sign: int) -> int:
    """The row of a quadric of type ``kind`` whose matrix has canonical sign ``canonical_sign``."""
    return 2 * KINDS.index(kind) + (1 if canonical_sign < 0 else 0)


@cache
def kind_from_invariant_signs(signs: tuple[int, ...]) -> tuple[QuadricKind, int]:
    """Type and canonical sign from the signs of ``(trA, J, detA, E1, E2, E3, E4, q33)``.

    The same rule as :func:`quadric_contact.model.classification.classify`, which
    needs only these signs: the inertias come from Descartes' rule on the
    characteristic polynomials (exact, their roots are real) and the canonical
    sign from the inertias (and, for the empty quadric, from ``q33``).  A test
    checks the two agree.
    """
    sa, sq, s33 = signs[:3], signs[3:7], signs[7]
    raw_a = inertia_from_minor_sums(sa)
    raw_q = inertia_from_minor_sums(sq)
    ia, iq = (raw_a.flipped(), raw_q.flipped()) if raw_a.negative > raw_a.positive else (raw_a, raw_q)
    kind = kind_from_inertia(ia, iq)
    if raw_a.positive != raw_a.negative:
        sign = 1 if raw_a.positive > raw_a.negative else -1
    elif kind is QuadricKind.HYPERBOLIC_CYLINDER:
        sign = 1 if raw_q.negative > raw_q.positive else -1
    elif kind is QuadricKind.EMPTY:
        sign = 1 if s33 > 0 else -1
    else:
        sign = 1
    return kind, sign


@cache
def _row_of_signs(signs: tuple[int, ...]) -> int | None:
    """The row of the invariant signs ``signs`` (all certain), or None where no quadric has
    them: ``rank A <= rank Q <= rank A + 2`` for every quadric (bordering ``A`` adds a row and
    a column), and a completion of uncertain signs, or a plain mode's rounded reading, can
    break it (``A`` of rank 0 with ``Q`` of rank 4)."""
    ra = inertia_from_minor_sums(signs[:3]).rank
    rq = inertia_from_minor_sums(signs[3:7]).rank
    if not ra <= rq <= ra + 2:
        return None
    return row_of(*kind_from_invariant_signs(signs))


def masks_from_invariant_signs(signs: np.ndarray) -> np.ndarray:
    """Candidate rows for an ``(n, 8)`` int8 array of invariant signs, as int64 bit masks
    (bit ``r`` for row ``r``): one bit where the signs are certain, the rows of every type
    the uncertain signs allow otherwise (:func:`region_code_masked` resolves them)."""
    signs = np.asarray(signs, dtype=np.int8)
    out = np.zeros(signs.shape[0], dtype=np.int64)
    if signs.shape[0] == 0:
        return out
    # Each sign (-1, 0, 1, UNCERTAIN) is two bits of a 16-bit key: the distinct combinations
    # are found by counting, not by sorting the rows (np.unique(axis=0) sorts them).
    key = np.zeros(signs.shape[0], dtype=np.int64)
    for j in range(8):
        key |= (signs[:, j].astype(np.int64) + 1) << (2 * j)
    present = np.flatnonzero(np.bincount(key, minlength=1 << 16))
    masks = np.zeros(1 << 16, dtype=np.int64)
    for k in present:
        combo = tuple(int((k >> (2 * j)) & 3) - 1 for j in range(8))
        rows = {row for c in _completions(combo) if (row := _row_of_signs(c)) is not None}
        masks[k] = sum(1 << r for r in rows)  # 0 (uncertain) if no quadric has these signs
    out[:] = masks[key]
    return out


def rows_from_masks(masks: np.ndarray) -> np.ndarray:
    """The row of each single-bit mask, :data:`UNCERTAIN_ROW` for the others."""
    masks = np.asarray(masks, dtype=np.int64)
    single = (masks != 0) & ((masks & (masks - 1)) == 0)
    # 2^r = 0.5 * 2^(r + 1) exactly in binary64 (r < 63): the exponent is the row, without
    # gathering the single-bit masks out and scattering their rows back
    row = np.frexp(masks.astype(np.float64))[1] - 1
    return np.where(single, row, UNCERTAIN_ROW).astype(np.int16)


def rows_from_invariant_signs(signs: np.ndarray) -> np.ndarray:
    """Rows for an ``(n, 8)`` int8 array of invariant signs (:data:`UNCERTAIN_ROW`
    where the type is uncertain)."""
    return rows_from_masks(masks_from_invariant_signs(signs))


# -- relative position (Theorem 13, Table 4) ----------------------------------------------


@njit(inline=True)
def _step(count: int, last: int, s: int) -> tuple[int, int]:
    if s == 0:
        return count, last
    if last != 0 and s != last:
        return count + 1, s
    return count, s


@njit(inline=True)
def _variations(a: int, b: int, c: int, d: int, e: int) -> int:
    """Sign variations of ``(a, b, c, d, e)``, zeros skipped (Descartes)."""
    count, last = _step(0, 0, a)
    count, last = _step(count, last, b)
    count, last = _step(count, last, c)
    count, last = _step(count, last, d)
    count, last = _step(count, last, e)
    return count


@njit(inline=True)
def region_code(
    contact: int,
    s0: int,
    s1: int,
    s2: int,
    s3: int,
    s4: int,
    klass: int,
    minus_neg: int,
    minus_zero: int,
    plus_neg: int,
    plus_zero: int,
) -> int:
    """:class:`RegionCode` from the contact code, the signs of ``c0 .. c4`` (paper's
    sign of ``E``) and the row of ``Q`` (unpacked from :data:`ROWS`).

    In the order of :func:`quadric_contact.theory.regions.decide_region`: a quadric
    without real points is excluded; non-real roots mean contact; a type without
    a row is excluded; otherwise Descartes' rule (exact, all roots being real)
    counts the negative and zero roots and Table 4 names the region.
    """
    if klass == ROW_NO_REAL_POINTS:
        return 4  # EXCLUDED
    if contact == 2 or klass == ROW_UNCERTAIN:
        return 2  # UNCERTAIN
    if contact == 1:
        return 0  # CONTACT
    if klass == ROW_EXCLUDED:
        return 4
    if s0 == 2 or s1 == 2 or s2 == 2 or s3 == 2 or s4 == 2:
        return 2
    zero = 0
    if s0 == 0:
        zero = 1
        if s1 == 0:
            zero = 2
            if s2 == 0:
                zero = 3
                if s3 == 0:
                    zero = 4
    negative = _variations(s0 * 1, -s1 * 1, s2 * 1, -s3 * 1, s4 * 1)
    if negative == minus_neg and zero == minus_zero:
        return -1  # R_MINUS
    if negative == plus_neg and zero == plus_zero:
        return 1  # R_PLUS
    return 3  # NO_ROW


@njit(inline=True)
def region_code_masked(
    contact: int, s0: int, s1: int, s2: int, s3: int, s4: int, row: int, mask: int, rows: Any
) -> int:
    """:func:`region_code` for a quadric known by its row, or, when ``row`` is
    :data:`UNCERTAIN_ROW`, by the bit mask of its candidate rows: the answer is given
    when every candidate gives the same one (``rows`` is :data:`ROWS`)."""
    if row != UNCERTAIN_ROW:
        return region_code(
            contact, s0, s1, s2, s3, s4, rows[row, 0], rows[row, 1], rows[row, 2], rows[row, 3], rows[row, 4]
        )
    answer = -99
    for r in range(UNCERTAIN_ROW):
        if (mask >> r) & 1:
            code = region_code(
                contact, s0, s1, s2, s3, s4, rows[r, 0], rows[r, 1], rows[r, 2], rows[r, 3], rows[r, 4]
            )
            if answer == -99:
                answer = code
            elif code != answer:
                return 2
    return 2 if answer == -99 else answer


def check_tables() -> None:
    """Internal consistency of the tables (run by the tests)."""
    assert CONTACT_TABLE.min() >= 0 and CONTACT_TABLE.max() <= 2
    assert RegionCode.R_MINUS == -1 and RegionCode.R_PLUS == 1 and RegionCode.CONTACT == 0
    assert RegionCode.UNCERTAIN == UNCERTAIN == ContactCode.UNCERTAIN
