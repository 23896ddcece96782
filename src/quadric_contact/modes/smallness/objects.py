"""Smallness on stacks with Python number objects: ``ball`` (python-flint ``arb``),
``mpmath`` (plain, at ``dps`` digits) and ``exact`` (the scalar decision, cached per matrix).

``ball`` and ``mpmath`` evaluate the monomials of
:mod:`~quadric_contact.modes.smallness.tables` on primitives in their own numbers,
once per distinct matrix, and compare them per distinct pair:

* ``ball``: the invariants are exact rationals (the entries are; python-flint ``fmpq``),
  the eigenvalues of the quadratic part certified balls (``fmpq_poly.complex_roots``:
  isolating balls of the distinct roots, real ones with an exact zero imaginary part,
  with their multiplicities); a comparison is reported only when the ball of the
  difference excludes zero, or is exactly zero (an equality, which satisfies the
  non-strict conditions of Table 1); otherwise ``UNCERTAIN``.
* ``mpmath``: the entries at ``dps`` digits, ``mpmath.eigsy`` for the eigenvalues, plain
  comparisons: always an answer, possibly wrong at the boundary.

``exact`` is the scalar :func:`quadric_contact.theory.smallness.smallness` itself: the Table 2
parameters of every distinct ``E`` and ``Q`` are computed once (exact real algebraic
eigenvalues) and every distinct pair runs the corrected Table 1 row on them.

In every mode ``E`` must be a real ellipsoid; that is decided exactly for each distinct
``E`` (integer arithmetic), raising :class:`~quadric_contact.exact.errors.NotAnEllipsoidError`
as the other array predicates do.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.model.invariants import invariants
from quadric_contact.modes.codes import EXCLUDED, UNCERTAIN
from quadric_contact.modes.facts import table_kinds
from quadric_contact.modes.numbers.number_mode import NumberMode
from quadric_contact.modes.smallness.numbers import BallNumbers, MpmathNumbers, used_signs
from quadric_contact.modes.smallness.tables import E_SIDES, Q_SIDES, TABLE_CONDITIONS
from quadric_contact.modes.stacks.pairs import Pairs
from quadric_contact.modes.stacks.validation import exact_matrix, raise_not_ellipsoid, validate_rows
from quadric_contact.theory.smallness import ellipsoid_axes_squared, smallness_report, table_2_parameters

__all__ = ["BallNumbers", "MpmathNumbers", "exact_smallness", "object_smallness"]


def _unique(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    u, inverse = np.unique(rows, return_inverse=True)
    return u, np.asarray(inverse).reshape(-1)


def _check_ellipsoids(pairs: Pairs, rows: np.ndarray) -> list[Any]:
    """The exact Quadric of every ``E`` row, raising for one that is not a real ellipsoid."""
    out = []
    for r in rows:
        e = exact_matrix(pairs.E, int(r))
        if e._ellipsoid_sign() == 0:
            raise_not_ellipsoid(pairs.E, int(r))
        out.append(e)
    return out


def _code(inner: int, outer: int) -> int:
    if inner == 1:
        return 1
    if inner == 0:
        return {1: 4, 0: 0}.get(outer, UNCERTAIN)
    return UNCERTAIN


def _and3(values: list[int]) -> int:
    if 0 in values:
        return 0
    return 1 if all(v == 1 for v in values) else UNCERTAIN


def object_smallness(mode: NumberMode, pairs: Pairs, numbers: Any) -> np.ndarray:
    """Codes of every pair with the numbers of ``numbers`` (:class:`BallNumbers` or
    :class:`MpmathNumbers`); the types of the quadrics from ``mode.classify``."""
    n = pairs.n
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    ue, ie = _unique(pairs.e_rows())
    uq, iq = _unique(pairs.q_rows())
    validate_rows(pairs.E, ue, "E")
    validate_rows(pairs.Q, uq, "Q")
    ellipsoids = _check_ellipsoids(pairs, ue)
    kinds, signs = table_kinds(mode.classify(pairs.Q, uq))
    e_used = used_signs(None)
    with numbers.context():
        e_sides: list[list[Any] | None] = []
        for e in ellipsoids:
            sign = 1 if e.upper[0] > 0 else -1
            prim = numbers.primitives(e.upper, sign, e_used)
            e_sides.append(None if prim is None else numbers.sides(prim, E_SIDES))
        q_sides: list[list[Any] | None] = []
        for k, r in enumerate(uq):
            if kinds[k] < 0:
                q_sides.append(None)
                continue
            kind = TABLE_1_KINDS[kinds[k]]
            sides = Q_SIDES[kind]
            used = used_signs(kind)
            prim = numbers.primitives(tuple(pairs.Q.upper_exact(np.array([r]))[t][0] for t in range(10)),
                                      int(signs[k]), used)  # fmt: skip
            q_sides.append(None if prim is None else numbers.sides(prim, sides))
        combos, where = np.unique(np.stack([ie, iq], axis=1), axis=0, return_inverse=True)
        codes = np.empty(len(combos), dtype=np.int8)
        for c, (a, b) in enumerate(combos):
            if kinds[b] == -1:
                codes[c] = EXCLUDED
                continue
            es, qs = e_sides[a], q_sides[b]
            if kinds[b] == -2 or es is None or qs is None:
                codes[c] = UNCERTAIN
                continue
            inner, outer = TABLE_CONDITIONS[TABLE_1_KINDS[kinds[b]]]
            v_in = _and3([numbers.compare(qs[s], es[t], rel) for s, t, rel in inner])
            v_out = _and3([numbers.compare(qs[s], es[t], rel) for s, t, rel in outer]) if outer else 0
            codes[c] = _code(v_in, v_out)
    out[:] = codes[np.asarray(where).reshape(-1)]
    return out


def exact_smallness(mode: NumberMode, pairs: Pairs) -> np.ndarray:
    """Codes of every pair by the exact scalar decision (Tables 1-2 corrected), with the
    parameters of every distinct matrix computed once."""

    n = pairs.n
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    ue, ie = _unique(pairs.e_rows())
    uq, iq = _unique(pairs.q_rows())
    validate_rows(pairs.E, ue, "E")
    validate_rows(pairs.Q, uq, "Q")
    axes = [ellipsoid_axes_squared(invariants(e.as_ellipsoid())) for e in _check_ellipsoids(pairs, ue)]
    params: list[Any] = []
    for r in uq:
        q = exact_matrix(pairs.Q, int(r))
        kind = q.kind
        if kind not in TABLE_1_KINDS:
            params.append(None)
            continue
        q = q if q.canonical_sign > 0 else -q
        params.append((kind, table_2_parameters(kind, invariants(q))))
    combos, where = np.unique(np.stack([ie, iq], axis=1), axis=0, return_inverse=True)
    codes = np.empty(len(combos), dtype=np.int8)
    for c, (a, b) in enumerate(combos):
        if params[b] is None:
            codes[c] = EXCLUDED
            continue
        kind, p = params[b]
        report = smallness_report(kind, p, axes[a])
        codes[c] = 1 if report.table_4_applies else (4 if report.small else 0)
    out[:] = codes[np.asarray(where).reshape(-1)]
    return out
