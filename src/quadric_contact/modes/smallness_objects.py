"""Smallness on stacks with Python number objects: ``ball`` (python-flint ``arb``),
``mpmath`` (plain, at ``dps`` digits) and ``exact`` (the scalar decision, cached per matrix).

``ball`` and ``mpmath`` evaluate the monomials of
:mod:`~quadric_contact.modes.smallness_tables` on primitives in their own numbers,
once per distinct matrix, and compare them per distinct pair:

* ``ball``: the invariants are exact rationals (the entries are; python-flint ``fmpq``),
  the eigenvalues of the quadratic part certified balls (``fmpq_poly.complex_roots``:
  isolating balls of the distinct roots, real ones with an exact zero imaginary part,
  with their multiplicities); a comparison is reported only when the ball of the
  difference excludes zero, or is exactly zero (an equality, which satisfies the
  non-strict conditions of Table 1); otherwise ``UNCERTAIN``.
* ``mpmath``: the entries at ``dps`` digits, ``mpmath.eigsy`` for the eigenvalues, plain
  comparisons: always an answer, possibly wrong at the boundary.

``exact`` is the scalar :func:`quadric_contact.smallness.smallness` itself: the Table 2
parameters of every distinct ``E`` and ``Q`` are computed once (exact real algebraic
eigenvalues) and every distinct pair runs the corrected Table 1 row on them.

In every mode ``E`` must be a real ellipsoid; that is decided exactly for each distinct
``E`` (integer arithmetic), raising :class:`~quadric_contact.errors.NotAnEllipsoidError`
as the other array predicates do.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

from .._generated import kernels
from ..classification import TABLE_1_KINDS
from .base import NumberMode, Pairs
from .smallness_float import table_kinds
from .smallness_tables import E_SIDES, GE, NPRIM, Q_SIDES, TABLE_CONDITIONS, evaluate, kind_signs
from .validation import exact_matrix, raise_not_ellipsoid, validate_rows

__all__ = ["BallNumbers", "MpmathNumbers", "exact_smallness", "object_smallness"]

_UNC = 2
_EXCL = 3
_INV = (6, 2, 1, 5, 4, 0)  # primitives P .. T: outputs of quadric_invariants


class BallNumbers:
    """Primitives and comparisons in python-flint ``arb`` balls at ``prec`` bits."""

    certified = True

    def __init__(self, prec: int) -> None:
        self.prec = prec

    def context(self) -> Any:
        import flint

        class _Prec:
            def __enter__(s) -> None:
                s.old = flint.ctx.prec
                flint.ctx.prec = self.prec

            def __exit__(s, *exc: object) -> None:
                flint.ctx.prec = s.old

        return _Prec()

    def primitives(self, upper: tuple[Any, ...], sign: int, signs: tuple[int, ...]) -> list[Any] | None:
        """The primitives (None where not used) of the matrix ``sign * upper``, or None when a
        required sign is not certain."""
        import flint

        q = [flint.fmpq(v.numerator, v.denominator) * sign for v in map(Fraction, upper)]
        inv = kernels.quadric_invariants(*q)
        out: list[Any] = [None] * NPRIM
        for j, k in enumerate(_INV):
            if signs[j]:
                v = inv[k] * signs[j]
                if v <= 0:
                    return None
                out[j] = flint.arb(v)
        if any(signs[6:]):
            poly = flint.fmpq_poly([-inv[2], inv[1], -inv[0], 1])
            eig: list[Any] = []
            for ball, mult in poly.complex_roots():
                if ball.imag.is_zero():
                    eig.extend([ball.real] * mult)
            if len(eig) != 3:
                return None
            eig.sort(key=lambda b: b.mid())
            for i in range(3):
                sg = signs[6 + i]
                if sg:
                    v = eig[i] * sg
                    if not v > 0:
                        return None
                    out[6 + i] = v
        return out

    @staticmethod
    def sides(prim: list[Any], monomials: Any) -> list[Any]:
        return [evaluate(prim, m) for m in monomials]

    @staticmethod
    def compare(q: Any, e: Any, relation: int) -> int:
        d = q - e if relation == GE else e - q
        if d > 0 or d.is_zero():
            return 1
        if d < 0:
            return 0
        return _UNC


class MpmathNumbers:
    """Primitives and plain comparisons with mpmath at ``dps`` digits."""

    certified = False

    def __init__(self, dps: int) -> None:
        self.dps = dps

    def context(self) -> Any:
        import mpmath

        return mpmath.workdps(self.dps)

    def primitives(self, upper: tuple[Any, ...], sign: int, signs: tuple[int, ...]) -> list[Any] | None:
        import mpmath

        q = [mpmath.mpf(v.numerator) / v.denominator * sign for v in map(Fraction, upper)]
        inv = kernels.quadric_invariants(*q)
        out: list[Any] = [None] * NPRIM
        for j, k in enumerate(_INV):
            if signs[j]:
                out[j] = abs(inv[k])
        if any(signs[6:]):
            A = mpmath.matrix([[q[0], q[1], q[2]], [q[1], q[4], q[5]], [q[2], q[5], q[7]]])
            eig = sorted(mpmath.eigsy(A, eigvals_only=True))
            for i in range(3):
                if signs[6 + i]:
                    out[6 + i] = abs(eig[i])
        return out

    @staticmethod
    def sides(prim: list[Any], monomials: Any) -> list[Any]:
        """The monomials; a zero denominator (an eigenvalue that came out as 0) gives infinity."""
        import mpmath

        out = []
        for m in monomials:
            try:
                out.append(evaluate(prim, m))
            except ZeroDivisionError:
                out.append(mpmath.inf)
        return out

    @staticmethod
    def compare(q: Any, e: Any, relation: int) -> int:
        return int(q >= e) if relation == GE else int(q <= e)


def used_signs(kind: Any | None) -> tuple[int, ...]:
    """The primitives the sides of ``kind`` use, with the signs they have (``None``: the
    ellipsoid ``E``); 0 for the unused ones."""
    sides = E_SIDES if kind is None else Q_SIDES[kind]
    signs = kind_signs(TABLE_1_KINDS[0] if kind is None else kind)
    return tuple(int(any(m[j] for m in sides)) * signs[j] for j in range(NPRIM))


def ball_sides(upper: tuple[Any, ...], sign: int, kind: Any | None, prec: int = 128) -> np.ndarray | None:
    """The sides of one matrix (``kind`` None: an ellipsoid ``E``; else a Table 1 kind of ``Q``
    with its canonical ``sign``) as binary64 intervals ``(lo_0, hi_0, lo_1, ...)`` (8 values,
    unused slots 1), from ball arithmetic rounded outward; None when the balls cannot give the
    signs the kind requires.  The float filter calls it, once per matrix, for the matrices
    whose own quantities it cannot certify."""
    numbers = BallNumbers(prec)
    with numbers.context():
        prim = numbers.primitives(upper, sign, used_signs(kind))
        if prim is None:
            return None
        sides = [evaluate(prim, m) for m in (E_SIDES if kind is None else Q_SIDES[kind])]
        out = np.ones(8)
        for k, ball in enumerate(sides):
            if not ball > 0:
                return None
            out[2 * k], out[2 * k + 1] = _outward(ball)
        return out


def _outward(ball: Any) -> tuple[float, float]:
    """Binary64 numbers ``lo <= ball <= hi`` (rounded outward)."""
    import math

    import flint

    lo, hi = ball.lower(), ball.upper()
    f, g = float(lo.mid()), float(hi.mid())
    while flint.arb(f) > lo:
        f = math.nextafter(f, -math.inf)
    while flint.arb(g) < hi:
        g = math.nextafter(g, math.inf)
    return f, g


def _unique(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    u, inverse = np.unique(rows, return_inverse=True)
    return u, np.asarray(inverse).reshape(-1)


def _check_ellipsoids(pairs: Pairs, rows: np.ndarray) -> list[Any]:
    """The exact Quadric of every ``E`` row, raising for one that is not a real ellipsoid."""
    out = []
    for r in rows:
        e = exact_matrix(pairs.E, int(r))
        if e._ellipsoid_sign() == 0:  # type: ignore[attr-defined]
            raise_not_ellipsoid(pairs.E, int(r))
        out.append(e)
    return out


def _code(inner: int, outer: int) -> int:
    if inner == 1:
        return 1
    if inner == 0:
        return {1: 4, 0: 0}.get(outer, _UNC)
    return _UNC


def _and3(values: list[int]) -> int:
    if 0 in values:
        return 0
    return 1 if all(v == 1 for v in values) else _UNC


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
                codes[c] = _EXCL
                continue
            es, qs = e_sides[a], q_sides[b]
            if kinds[b] == -2 or es is None or qs is None:
                codes[c] = _UNC
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
    from ..invariants import invariants
    from ..smallness import _ellipsoid_axes, _parameters, _report

    n = pairs.n
    out = np.empty(n, dtype=np.int8)
    if n == 0:
        return out
    ue, ie = _unique(pairs.e_rows())
    uq, iq = _unique(pairs.q_rows())
    validate_rows(pairs.E, ue, "E")
    validate_rows(pairs.Q, uq, "Q")
    axes = [_ellipsoid_axes(invariants(e.as_ellipsoid())) for e in _check_ellipsoids(pairs, ue)]
    params: list[Any] = []
    for r in uq:
        q = exact_matrix(pairs.Q, int(r))
        kind = q.kind  # type: ignore[attr-defined]
        if kind not in TABLE_1_KINDS:
            params.append(None)
            continue
        q = q if q.canonical_sign > 0 else -q  # type: ignore[attr-defined,operator]
        params.append((kind, _parameters(kind, invariants(q))))
    combos, where = np.unique(np.stack([ie, iq], axis=1), axis=0, return_inverse=True)
    codes = np.empty(len(combos), dtype=np.int8)
    for c, (a, b) in enumerate(combos):
        if params[b] is None:
            codes[c] = _EXCL
            continue
        kind, p = params[b]
        report = _report(kind, p, axes[a])
        codes[c] = 1 if report.table_4_applies else (4 if report.small else 0)
    out[:] = codes[np.asarray(where).reshape(-1)]
    return out
