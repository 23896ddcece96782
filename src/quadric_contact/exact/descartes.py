"""Descartes' rule of signs and exact root-sign patterns.

For a polynomial whose roots are all real, the number of positive roots
(with multiplicity) *equals* the number of sign variations of its
coefficients, and the number of negative roots equals that of ``P(-x)``:
the rule is exact (Curtiss 1918).  Where ``P`` has non-real roots the rule
only bounds, so the pattern is obtained by certified root isolation instead
(FLINT's ``arb_fmpz_poly_complex_roots``: isolating balls, real roots
certified real, refined until every real root's sign is decided).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from quadric_contact.exact.algebraic import real_roots
from quadric_contact.exact.discriminants import RootStructure, exact_coefficients, root_structure, strip

__all__ = ["RootSigns", "root_signs", "sign_variations"]


def sign_variations(values: Sequence[Any]) -> int:
    """Number of sign changes in a sequence, zeros ignored (Descartes' rule of signs).

    Parameters
    ----------
    values : sequence of real numbers

    Returns
    -------
    int
        For the coefficients ``c0, c1, ...`` of a real-rooted polynomial: its
        number of positive roots (Theorem 13, Table 4).

    Examples
    --------
    Example 17: ``P2`` has coefficients ``0.25, -11.6625, 34.125, 45.7375, -0.3``:
    three positive roots, the bee is outside the trunk.

    >>> sign_variations([0.25, -11.6625, 34.125, 45.7375, -0.3])
    3
    """
    count = 0
    last = 0
    for v in values:
        s = (v > 0) - (v < 0)
        if s:
            if last and s != last:
                count += 1
            last = s
    return count


@dataclass(frozen=True)
class RootSigns:
    """How many roots are negative, zero, positive and non-real (with multiplicity).

    Attributes
    ----------
    negative, zero, positive, nonreal : int
        Root counts with multiplicity.
    method : str
        ``"descartes"`` (exact sign variations; the polynomial is
        real-rooted) or ``"isolation"`` (certified root isolation).

    Examples
    --------
    Theorem 14, eq. (12): the unit sphere centred at ``(0, 0, 2)`` and the
    plane ``z = 0`` give ``P = -lambda^2 (1 + 4 lambda (lambda - 2)) / 4``,
    with roots ``0, 0, 1 +- sqrt(3)/2``: the sphere is in ``R+``.

    >>> from fractions import Fraction
    >>> s = root_signs([0, 0, Fraction(-1, 4), 2, -1])
    >>> s.pattern, s.method, s.negated().pattern
    ('00++', 'descartes', '--00')
    """

    negative: int
    zero: int
    positive: int
    nonreal: int
    method: str

    @property
    def pattern(self) -> str:
        """The signs of the real roots in increasing order, e.g. ``'--0+'``;
        non-real roots are appended as ``'c'``."""
        return "-" * self.negative + "0" * self.zero + "+" * self.positive + "c" * self.nonreal

    def negated(self) -> RootSigns:
        """The pattern of ``P(-x)``."""
        return RootSigns(self.positive, self.zero, self.negative, self.nonreal, self.method)

    def __str__(self) -> str:
        return self.pattern


def root_signs(coeffs: Sequence[Any], structure: RootStructure | None = None) -> RootSigns:
    """Exact counts of negative, zero, positive and non-real roots of ``sum coeffs[k] x^k``.

    Parameters
    ----------
    coeffs : sequence of exact numbers
        ``c0, c1, ...`` (lowest degree first).
    structure : RootStructure, optional
        The :func:`~quadric_contact.exact.discriminants.root_structure` of the
        polynomial, if already known.

    Returns
    -------
    RootSigns
        Exact counts; ``.pattern`` is the row notation of Table 4
        (``'--++'``).  Where all roots are real the counts are Descartes'
        sign variations, which are then exact (Curtiss 1918); otherwise the
        real roots are isolated with certified balls.

    References
    ----------
    Theorem 13 and Table 4 (root signs and coefficient signs); Lemma 12.

    Examples
    --------
    Example 17, the bee and the hyperboloid S2 (the bee is outside, ``R+``):

    >>> from fractions import Fraction as F
    >>> root_signs([F(1, 4), F(-933, 80), F(273, 8), F(3659, 80), F(-3, 10)]).pattern
    '-+++'
    """
    c = strip(exact_coefficients(coeffs))
    if structure is None:
        structure = root_structure(c)
    zero = next(i for i, v in enumerate(c) if v != 0)
    if structure.all_real:
        positive = sign_variations(c)
        negative = sign_variations([v if k % 2 == 0 else -v for k, v in enumerate(c)])
        return RootSigns(negative, zero, positive, 0, "descartes")
    negative = positive = 0
    for r, m in real_roots(c[zero:], multiplicities=True):
        if r.sign() > 0:
            positive += m
        else:
            negative += m
    return RootSigns(negative, zero, positive, 2 * structure.nonreal_pairs, "isolation")
