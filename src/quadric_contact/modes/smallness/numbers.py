"""The numbers the smallness stages evaluate Tables 1-2 with: certified balls and mpmath.

:class:`BallNumbers` (python-flint ``arb`` balls at ``prec`` bits: exact invariants,
certified eigenvalues, a comparison only when the ball of the difference excludes zero
or is exactly zero) and :class:`MpmathNumbers` (mpmath at ``dps`` digits, plain
comparisons) compute the primitives of one matrix and the monomials of
:mod:`~quadric_contact.modes.smallness.tables` on them; the ``ball`` and ``mpmath``
modes use them for whole stacks (:mod:`~quadric_contact.modes.smallness.objects`), and
the float filter refines, once per matrix, the sides it could not certify with
:func:`ball_sides` (:mod:`~quadric_contact.modes.smallness.binary64`).  Their precision
is set with :func:`~quadric_contact.exact.precision.working_precision`, the package's one
lock-holding precision context (a bare change of ``flint.ctx.prec`` or ``mpmath.mp``
would race with it under dask's threads).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact._generated import kernels
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.modes.codes import UNCERTAIN
from quadric_contact.modes.smallness.tables import (
    E_SIDES,
    GE,
    NPRIM,
    Q_SIDES,
    evaluate,
    kind_signs,
)

__all__ = ["BallNumbers", "MpmathNumbers", "ball_sides", "used_signs"]

_INV = (6, 2, 1, 5, 4, 0)  # primitives P .. T: outputs of quadric_invariants


class BallNumbers:
    """Primitives and comparisons in python-flint ``arb`` balls at ``prec`` bits."""

    certified = True

    def __init__(self, prec: int) -> None:
        self.prec = prec

    def context(self) -> Any:
        """The working precision of the balls (:func:`~quadric_contact.exact.precision.working_precision`)."""
        return working_precision(self.prec)

    def primitives(self, upper: tuple[Any, ...], sign: int, signs: tuple[int, ...]) -> list[Any] | None:
        """The primitives (None where not used) of the matrix ``sign * upper``, or None when a
        required sign is not certain."""
        import flint  # import cost

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
        return UNCERTAIN


class MpmathNumbers:
    """Primitives and plain comparisons with mpmath at ``dps`` digits."""

    certified = False

    def __init__(self, dps: int) -> None:
        self.dps = dps

    def context(self) -> Any:
        """mpmath's working digits (:func:`~quadric_contact.exact.precision.working_precision`)."""
        return working_precision(dps=self.dps)

    def primitives(self, upper: tuple[Any, ...], sign: int, signs: tuple[int, ...]) -> list[Any] | None:
        import mpmath  # import cost

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
        import mpmath  # import cost

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
    import flint  # import cost

    lo, hi = ball.lower(), ball.upper()
    f, g = float(lo.mid()), float(hi.mid())
    while flint.arb(f) > lo:
        f = math.nextafter(f, -math.inf)
    while flint.arb(g) < hi:
        g = math.nextafter(g, math.inf)
    return f, g
