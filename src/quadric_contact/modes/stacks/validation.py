"""Diagnosing bad input for the array predicates, with the package's errors.

The float kernels only flag an entry as invalid; the functions here say which
matrix is at fault and why, and raise the matching error of
:mod:`quadric_contact.exact.errors` with the offending matrix attached.
"""

from __future__ import annotations

import numpy as np

from quadric_contact.exact.errors import (
    SYMMETRIZE_HINT,
    NonFiniteError,
    NotAnEllipsoidError,
    NotSymmetricError,
)
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.kernels.support_drivers import check_stack
from quadric_contact.modes.stacks.pairs import MatrixStack, Pairs

__all__ = ["diagnose", "exact_matrix", "raise_not_ellipsoid", "rows_view", "validate_rows"]


def rows_view(stack: MatrixStack, rows: np.ndarray) -> np.ndarray:
    """``stack.floats[rows]`` to read, not to write: the stack's own array when ``rows`` are all
    its rows in order (the common case of distinct pairs: no ``(n, 4, 4)`` copy), a gathered
    copy otherwise."""
    rows = np.asarray(rows)
    if _every_row(rows, len(stack)):
        return stack.floats
    return stack.rows_floats(rows)


def _every_row(rows: np.ndarray, n: int) -> bool:
    """Whether ``rows`` are ``0, 1, ..., n - 1`` in order."""
    every = rows.ndim == 1 and rows.size == n and n and rows[0] == 0 and rows[-1] == n - 1
    return bool(every and (n == 1 or bool((np.diff(rows) == 1).all())))


def validate_rows(stack: MatrixStack, rows: np.ndarray, name: str | None = None) -> None:
    """Raise for the first matrix among ``rows`` with a non-finite entry or that is not symmetric."""
    if stack.checked or len(rows) == 0:
        return
    rows = np.asarray(rows)
    if stack.packed is not None and stack.packed_only:
        # packed entries are symmetric by construction: only finiteness is left to check, and
        # it is read on the ten entries without unpacking the stack
        every = _every_row(rows, len(stack))
        finite = np.isfinite(stack.packed if every else stack.packed[rows]).all(axis=-1)
        if finite.all():
            stack.checked = every
            return
        k = int(np.argmin(finite))
        rows = rows[k : k + 1]
    sub = rows_view(stack, rows)
    flags = check_stack(sub)
    if not flags.any():
        if sub is stack.floats:
            stack.checked = True  # every row is fine: later stages need not read them again
        return
    k = int(np.argmax(flags != 0))
    row = int(rows[k])
    M = sub[k]
    where = stack.where(row)
    if flags[k] == 1:
        i, j = (int(v) for v in np.argwhere(~np.isfinite(M))[0])
        raise NonFiniteError(
            f"{where} has a non-finite entry at ({i}, {j}): {M[i, j]!r}", M, entry=(i, j), index=row
        )
    i, j = (int(v) for v in np.argwhere(M != M.T)[0])
    i, j = min(i, j), max(i, j)
    raise NotSymmetricError(
        f"{where} is not symmetric: M[{i},{j}] = {M[i, j]!r} but M[{j},{i}] = {M[j, i]!r}; {SYMMETRIZE_HINT}",
        M,
        entry=(i, j),
        index=row,
    )


def exact_matrix(stack: MatrixStack, row: int) -> Quadric:
    """The exact :class:`~quadric_contact.Quadric` of a matrix of the stack."""
    if stack.exact is not None:
        return Quadric._from_upper(tuple(stack.exact[row]))
    return Quadric.from_matrix(stack.rows_floats(np.array([row]))[0])


def raise_not_ellipsoid(stack: MatrixStack, row: int) -> None:
    """Raise :class:`NotAnEllipsoidError` for the matrix ``row`` (exact type in the details)."""
    q = exact_matrix(stack, row)
    kind = q.kind
    raise NotAnEllipsoidError(
        f"{stack.where(row)} is not a real ellipsoid: it is {kind.value} ({kind.real_points})",
        q,
        kind=kind,
        index=int(row),
    )


def diagnose(pairs: Pairs, which: np.ndarray) -> np.ndarray:
    """Raise for the first really invalid pair among ``which`` (the pairs a kernel flagged
    ``INVALID``); return ``UNCERTAIN`` for pairs flagged only because a plain float test could
    not see ``E`` as an ellipsoid."""
    e_rows, q_rows = pairs.e_rows_at(which), pairs.q_rows_at(which)
    validate_rows(pairs.E, np.unique(e_rows))
    validate_rows(pairs.Q, np.unique(q_rows))
    for row in np.unique(e_rows):
        if exact_matrix(pairs.E, int(row))._ellipsoid_sign() == 0:
            raise_not_ellipsoid(pairs.E, int(row))
    return np.full(which.size, UNCERTAIN, dtype=np.int8)
