"""Exact facts about each quadric of a stack, computed once per quadric and shared by every
number mode: its invariant signs, its candidate rows of Table 4 (its type and canonical sign),
the structural zeros it puts in the pencil (``det Q = 0`` makes ``c0 = 0`` for every ``E``,
``rank Q <= 2`` makes ``c1 = 0`` too), and, per pair, a quadratic part of ``Q`` proportional
to that of ``E`` (``Delta_4 = 0``).

The facts are exact whatever the mode: the binary64 readings here are certified (a rigorous
error bound, then double-double, :func:`float_invariant_signs` with ``filtered=True``) and
what they cannot tell is read in integer arithmetic (:func:`exact_invariant_signs`).  The plain
``float`` mode reads the same kernels without the bound (``filtered=False``): its signs are
not facts, and it says so.

Every number mode imports this module; it imports no mode.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from quadric_contact._generated import kernels
from quadric_contact.model.classification import TABLE_1_KINDS, QuadricKind
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.decision.answers import (
    KINDS,
    UNCERTAIN_ROW,
    masks_from_invariant_signs,
    row_of,
    rows_from_masks,
)
from quadric_contact.modes.kernels import errorbounds as eb
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.modes.kernels.numpy_backend import numpy_ellipsoid_signs, numpy_invariant_signs
from quadric_contact.modes.kernels.support import ellipsoid_signs_kernel, invariant_signs_kernel
from quadric_contact.modes.kernels.threads import run_parallel
from quadric_contact.modes.stacks.integers import integer_rows
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs
from quadric_contact.modes.stacks.rows import unique_rows
from quadric_contact.modes.stacks.validation import validate_rows

__all__ = [
    "certified_ellipsoid_signs",
    "exact_facts",
    "exact_invariant_signs",
    "exact_signs",
    "float_invariant_signs",
    "integer_invariant_signs",
    "proportional_exact",
    "structural_bits",
    "structural_facts",
    "table_kinds",
    "used_rows",
]


def exact_signs(x: np.ndarray) -> np.ndarray:
    """int8 signs of exact numbers (integers, Fractions, fmpz), element by element."""
    return (np.asarray(x > 0, dtype=np.int8) - np.asarray(x < 0, dtype=np.int8)).astype(np.int8)


def integer_invariant_signs(Q: MatrixStack, rows: np.ndarray) -> np.ndarray:
    """``(k, 8)`` int8 exact signs of ``(trA, J, detA, E1 .. E4, q33)`` of the quadrics ``rows``,
    in integer arithmetic (each matrix times its own positive scale: the signs do not change),
    computed every time: :func:`exact_invariant_signs` keeps them."""
    rows = np.asarray(rows, dtype=np.intp)
    validate_rows(Q, rows, "Q")
    cols = integer_rows(Q, rows)
    values = kernels.quadric_invariants(*cols)
    return np.stack([exact_signs(v) for v in values] + [exact_signs(cols[9])], axis=1).astype(np.int8)


def exact_invariant_signs(Q: MatrixStack, rows: np.ndarray) -> np.ndarray:
    """:func:`integer_invariant_signs`, once per quadric: kept with the stack (which lives for
    one call), so that the stages of a decision that need them (the types, the structural
    zeros) share one computation."""
    rows = np.asarray(rows, dtype=np.intp)
    known, signs = Q.exact_signs_memo()
    need = np.unique(rows[~known[rows]])
    if need.size:
        signs[need] = integer_invariant_signs(Q, need)
        known[need] = True
    return signs[rows]


def structural_bits(signs: np.ndarray) -> np.ndarray:
    """Bit 0: ``det Q = 0``; bit 1: ``rank Q <= 2`` (``E4 = E3 = 0``), from certain invariant
    signs (for a symmetric matrix the rank is 4 minus the trailing zeros of ``E1 .. E4``)."""
    det_zero = signs[:, 6] == 0
    return (det_zero.astype(np.int8) | ((det_zero & (signs[:, 5] == 0)).astype(np.int8) << 1)).astype(np.int8)


def structural_facts(Q: MatrixStack, rows: np.ndarray) -> np.ndarray:
    """:func:`structural_bits` of the quadrics ``rows``, exactly (once per quadric)."""
    return structural_bits(exact_invariant_signs(Q, np.asarray(rows, dtype=np.intp)))


_ELLIPSOID_PLUS = np.int64(1) << row_of(QuadricKind.ELLIPSOID, 1)
_ELLIPSOID_MINUS = np.int64(1) << row_of(QuadricKind.ELLIPSOID, -1)


def ellipsoid_masks(ell: np.ndarray) -> np.ndarray:
    """Table 4 candidate masks from :func:`certified_ellipsoid_signs` (0 where it cannot tell)."""
    return np.where(ell > 0, _ELLIPSOID_PLUS, np.where(ell < 0, _ELLIPSOID_MINUS, np.int64(0)))


def float_invariant_signs(
    Q: np.ndarray, *, filtered: bool, rounded: bool = False, backend: str = "numba"
) -> np.ndarray:
    """``(m, 8)`` int8 signs of ``(trA, J, detA, E1, E2, E3, E4, q33)`` for every quadric.

    ``filtered``: certain signs, ``UNCERTAIN`` elsewhere: binary64 with the bounds
    :data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_ERRBOUND` and, for binary64
    input (not ``rounded`` from exact input), the quadrics with a sign binary64 cannot tell
    read again in double-double
    (:data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND` and, for ``JA``,
    ``detA``, ``E4``,
    :data:`~quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_COFACTOR_ERRBOUND`): what it
    leaves is a value within about 1e-30 of its magnitude (in practice, an exact zero), or
    input outside the guard.  Not ``filtered``: the plain binary64 signs (the ``float`` mode's;
    not facts)."""
    out = np.empty((Q.shape[0], 8), dtype=np.int8)
    K = np.array(eb.INVARIANTS_ERRBOUND[rounded])
    KD = np.array(eb.INVARIANTS_DD_ERRBOUND)
    KC = np.array(eb.INVARIANTS_DD_COFACTOR_ERRBOUND)
    dd = filtered and not rounded
    if backend == "numpy" or not HAVE_NUMBA:
        return numpy_invariant_signs(Q, filtered, K, (KD, KC) if dd else None)
    flat = np.ascontiguousarray(Q).reshape(-1, 16)
    run_parallel(
        lambda lo, hi: invariant_signs_kernel(flat, lo, hi, K, KD, KC, filtered, dd, out), Q.shape[0]
    )
    return out


def certified_ellipsoid_signs(Q: np.ndarray, *, backend: str = "numba") -> np.ndarray:
    """``(m,)`` int8: +1/-1 where the binary64 quadric ``Q[k]`` (not rounded from exact input) is
    certainly an ellipsoid of that canonical sign, 0 where this short test cannot tell (the
    invariant signs decide those)."""
    if backend == "numpy" or not HAVE_NUMBA:
        return numpy_ellipsoid_signs(np.asarray(Q, dtype=np.float64))
    out = np.empty(Q.shape[0], dtype=np.int8)
    flat = np.ascontiguousarray(Q).reshape(-1, 16)
    run_parallel(lambda lo, hi: ellipsoid_signs_kernel(flat, lo, hi, out), Q.shape[0])
    return out


def used_rows(index: np.ndarray | None, m: int, n: int) -> np.ndarray:
    """The distinct rows of a stack that ``n`` pairs use (no sorting when they use them all)."""
    if index is None:
        return np.arange(m, dtype=np.intp) if m == n else np.zeros(1, dtype=np.intp)
    return unique_rows(index, m)


def exact_facts(Q: MatrixStack, rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact facts about the quadrics ``rows``, from their exact invariant signs, once per
    quadric: ``(flags, masks)``, ``flags`` the :func:`structural_bits` and ``masks`` their
    Table 4 rows.

    For binary64 input the signs are certified before any integer is formed: a quadric the
    short test finds an ellipsoid needs none (``det Q != 0``, rank 4, its type known), and the
    others get the filtered signs of :func:`float_invariant_signs` (binary64, then
    double-double); only a quadric with a sign neither can tell (in practice an exact zero of
    an invariant that is not a product of zeros) goes to integer arithmetic
    (:func:`exact_invariant_signs`)."""
    rows = np.asarray(rows, dtype=np.intp)
    flags = np.zeros(rows.size, dtype=np.int8)
    masks = np.zeros(rows.size, dtype=np.int64)
    todo = np.arange(rows.size)
    if not Q.rounded and rows.size:
        # (the environment of a simulation is asked about on every call)
        ell = certified_ellipsoid_signs(Q.rows_floats(rows))
        masks = ellipsoid_masks(ell)
        todo = np.flatnonzero(ell == 0)
        if todo.size:
            signs = float_invariant_signs(Q.rows_floats(rows[todo]), filtered=True)
            sure = (signs[:, :7] != UNCERTAIN).all(axis=1)
            flags[todo[sure]] = structural_bits(signs[sure])
            masks[todo[sure]] = masks_from_invariant_signs(signs[sure])
            todo = todo[~sure]
    if todo.size:
        signs = exact_invariant_signs(Q, rows[todo])
        flags[todo] = structural_bits(signs)
        masks[todo] = masks_from_invariant_signs(signs)
    return flags, masks


def proportional_exact(pairs: Pairs, e_rows: np.ndarray, q_rows: np.ndarray) -> np.ndarray:
    """Per pair: the quadratic part of ``Q`` is a multiple of that of ``E``, exactly (then
    ``Delta_4 = 0``)."""
    quad = (0, 1, 2, 4, 5, 7)
    ue, ie = np.unique(e_rows, return_inverse=True)
    uq, iq = np.unique(q_rows, return_inverse=True)
    # as Fractions: a binary64 entry times a Fraction would be taken in binary64 (and overflow
    # for an exact entry beyond its range)
    exact = np.frompyfunc(Fraction, 1, 1)
    ecols = [exact(c) for c in pairs.E.upper_exact(ue)]
    qcols = [exact(c) for c in pairs.Q.upper_exact(uq)]
    out = np.ones(len(e_rows), dtype=bool)
    e00, q00 = ecols[0][ie], qcols[0][iq]
    for t in quad[1:]:
        a = (qcols[t][iq] * e00 - q00 * ecols[t][ie]).astype(object)
        out &= np.array([Fraction(v) == 0 for v in a], dtype=bool)
    return out


def table_kinds(masks: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(kinds, signs)`` from candidate-row bit masks (:meth:`NumberMode.classify`): the index of
    the type in TABLE_1_KINDS and its canonical sign; ``-1`` where the type is certainly without
    a row in Table 1 (every candidate is), ``-2`` where it is uncertain."""
    masks = np.asarray(masks, dtype=np.int64)
    rows = rows_from_masks(masks).astype(np.intp)
    lookup = np.array(
        [TABLE_1_KINDS.index(k) if k in TABLE_1_KINDS else -1 for k in KINDS for _ in (1, -1)] + [-2]
    )
    kinds = lookup[rows].astype(np.int64)
    signs = np.where(rows % 2 == 1, -1, 1).astype(np.int64)
    unsure = np.flatnonzero(rows == UNCERTAIN_ROW)
    for mask in np.unique(masks[unsure]):
        candidates = [r for r in range(UNCERTAIN_ROW) if (int(mask) >> r) & 1]
        if candidates and all(lookup[r] == -1 for r in candidates):
            kinds[unsure[masks[unsure] == mask]] = -1
    return kinds, signs
