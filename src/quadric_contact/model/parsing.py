"""The reader of a quadric's equation: ``"x^2 + y^2 - 0.25*(z - 3)^2 = 1"`` to its matrix.

:func:`parse_quadric_equation` reads an equation of degree at most 2 in
``x, y, z`` with the package's own expression reader
(:mod:`quadric_contact.exact.reading`: a tokenizer and a recursive-descent parser,
never ``eval``; its grammar, error messages and bounds are documented there)
and returns the ten upper entries of the symmetric matrix (eq. (6)) in the
order of :data:`~quadric_contact.exact.entries.ENTRY_INDICES`.  The readers of numbers
and polynomials (:func:`~quadric_contact.exact.reading.parse_number`,
:func:`~quadric_contact.exact.reading.parse_polynomial`, ...) are in
:mod:`quadric_contact.exact.reading`.
"""

from __future__ import annotations

from fractions import Fraction

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.reading import Polynomial, parse_polynomial

__all__ = ["parse_quadric_equation", "quadric_entries"]


def _quadric_monomials() -> tuple[tuple[tuple[int, ...], Fraction], ...]:
    out = []
    for i, j in ENTRY_INDICES:
        e = [0, 0, 0]
        for k in (i, j):
            if k < 3:
                e[k] += 1
        out.append((tuple(e), Fraction(1) if i == j else Fraction(1, 2)))
    return tuple(out)


_QUADRIC_MONOMIALS = _quadric_monomials()
"""For each upper entry ``(i, j)`` of the matrix: the monomial whose coefficient
it takes, and the factor (``1/2`` off the diagonal: ``2 q_ij x_i x_j``)."""


def quadric_entries(poly: Polynomial) -> tuple[Fraction, ...]:
    """The ten upper entries (``ENTRY_INDICES`` order) of the symmetric matrix of a
    polynomial of degree at most 2 in ``x, y, z`` (eq. (6))."""
    return tuple(poly.get(mono, Fraction(0)) * f for mono, f in _QUADRIC_MONOMIALS)


def parse_quadric_equation(text: str) -> tuple[Fraction, ...]:
    """Read an equation (or an expression ``= 0``) of degree at most 2 in ``x, y, z``.

    Returns
    -------
    tuple of 10 Fractions
        The upper entries of the symmetric matrix, in the order of
        :data:`~quadric_contact.exact.entries.ENTRY_INDICES`.

    Raises
    ------
    EquationError

    Examples
    --------
    >>> parse_quadric_equation("x^2 + y^2 - 0.25*(z - 3)^2 = 1")[7:]
    (Fraction(-1, 4), Fraction(3, 4), Fraction(-13, 4))
    >>> parse_quadric_equation("3(z - 1)^2")
    Traceback (most recent call last):
        ...
    quadric_contact.exact.errors.EquationError: equation: implicit multiplication at position 2: ...
        3(z - 1)^2
         ^
    """
    return quadric_entries(parse_polynomial(text, ("x", "y", "z"), max_degree=2, equation=True))
