"""A root of an integer polynomial singled out by a certified ball: the isolating interval of a
:class:`~quadric_contact.exact.algebraic.RealAlgebraic` without a root isolation of the whole
polynomial.

A number known to be a root of an irreducible polynomial ``p`` and to lie in a ball ``X``
(``arb``, evaluated from its definition) is the only root of ``p`` in ``X`` when ``p``
changes sign across the ends of ``X`` (exact rational signs) and ``p'`` has no zero on ``X``
(a certified enclosure of ``p'(X)`` that excludes 0): then ``p`` is monotone on ``X``.  When a
number is a root of a product of irreducible factors, the factor it belongs to is the only one
whose enclosure on the ball holds 0 (at a precision where the others exclude it).  A ball too
wide for either test gives None: the caller narrows it and asks again.

Examples
--------
>>> import flint
>>> x = root_in_ball(flint.fmpz_poly([-2, 0, 1]), flint.arb(2).sqrt())
>>> x.decimal(10), x.minpoly
('1.4142135624', (Fraction(-2, 1), Fraction(0, 1), Fraction(1, 1)))
>>> root_among([flint.fmpz_poly([-3, 1]), flint.fmpz_poly([-2, 0, 1])], flint.arb(3))
RealAlgebraic(3)
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.rational import fraction_of

__all__ = ["ball_ends", "primitive", "root_among", "root_in_ball", "sign_at_rational"]


def primitive(p: Any) -> Any:
    """``p`` (an ``fmpz_poly``) divided by its content, with a positive leading coefficient.

    >>> primitive(flint.fmpz_poly([4, -6]))
    3*x + (-2)
    """
    c = p.content()
    if p.leading_coefficient() < 0:
        c = -c
    return p if c == 1 else flint.fmpz_poly([a // c for a in p.coeffs()])


def sign_at_rational(p: Any, x: Fraction) -> int:
    """The exact sign of the ``fmpz_poly`` ``p`` at the rational ``x``."""
    v = p(flint.fmpq(x.numerator, x.denominator))
    return (v > 0) - (v < 0)


def ball_ends(ball: Any) -> tuple[Fraction, Fraction]:
    """The exact ends ``mid - rad, mid + rad`` of a ball (read without rounding)."""
    mid, rad = fraction_of(ball.mid()), fraction_of(ball.rad())
    return mid - rad, mid + rad


def root_in_ball(p: Any, ball: Any) -> RealAlgebraic | None:
    """The root of the irreducible ``fmpz_poly`` ``p`` known to lie in ``ball``, with the ball's
    ends for an isolating interval; None when the ball is too wide to tell it from the other
    roots.

    Parameters
    ----------
    p : fmpz_poly
        Irreducible over Q, primitive, with a positive leading coefficient (not checked: the
        caller knows it).
    ball : arb
        Holds a root of ``p`` (the caller knows it).
    """
    if p.degree() == 1:
        root = Fraction(-int(p[0]), int(p[1]))
        return RealAlgebraic(root) if ball.contains(flint.fmpq(root.numerator, root.denominator)) else None
    if not ball.is_finite():
        return None
    lo, hi = ball_ends(ball)
    if not lo < hi or sign_at_rational(p, lo) * sign_at_rational(p, hi) >= 0:
        return None
    if p.derivative()(ball).contains(0):
        return None
    return RealAlgebraic._from_integer_polynomial(p, lo, hi)


def root_among(factors: Sequence[Any], ball: Any) -> RealAlgebraic | None:
    """The root in ``ball`` of the one irreducible factor (``fmpz_poly``) that can vanish on
    it, a product of ``factors`` being known to vanish at a number in the ball; None when
    several can."""
    if not ball.is_finite():
        return None
    hits = [g for g in factors if g(ball).contains(0)]
    return root_in_ball(primitive(hits[0]), ball) if len(hits) == 1 else None
