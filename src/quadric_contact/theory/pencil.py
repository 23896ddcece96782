"""The pencil ``lambda*E + Q`` and its characteristic polynomial (paper eq. (1)).

``P(lambda) = det(lambda*E + Q) = c4 lambda^4 + c3 lambda^3 + c2 lambda^2 + c1 lambda + c0``
with ``c4 = det E`` and ``c0 = det Q``.

Exactness at speed
------------------
Each matrix is brought to integer form ``E = E_int / d_E``, ``Q = Q_int / d_Q``
(exact; a float's denominator is a power of two).  The generated closed form
then runs on Python integers: ``C_k`` = the coefficients of
``det(lambda*E_int + Q_int)``, and

    c_k = C_k / (d_E^k d_Q^(4-k)),   P(lambda) = d_Q^-4 * P_int(lambda * d_Q / d_E).

So the roots of ``P`` are those of ``P_int`` times the positive number
``d_E / d_Q``: signs, multiplicities and the real/non-real nature agree, and
every sign decision is taken on integers.  The rational coefficients are
built only when somebody asks for them.
"""

from __future__ import annotations

from collections.abc import Sequence
from fractions import Fraction
from functools import cached_property
from typing import Any

import flint

from quadric_contact._generated.formulas import pencil_coefficients
from quadric_contact.exact.descartes import RootSigns, root_signs
from quadric_contact.exact.discriminants import RootStructure, paper_deltas, root_structure
from quadric_contact.exact.printing import int_text
from quadric_contact.model.quadric import Quadric, as_quadric

__all__ = ["CharacteristicPolynomial", "as_quadric", "characteristic_polynomial"]


class CharacteristicPolynomial:
    """``P(lambda) = det(lambda*E + Q)`` with exact coefficients.

    Attributes
    ----------
    E : Quadric
        The ellipsoid actually used (normalised to ``det E < 0`` unless the
        polynomial was built with ``normalize=False``).
    Q : Quadric
        The other quadric, exactly as given.
    e_flipped : bool
        True if the caller's ellipsoid matrix had ``det > 0`` (inside
        positive) and was replaced by its negative.

    References
    ----------
    Eq. (1), eq. (7); Section 3.2 (``deltas``); Theorem 13 (``signs``).

    Examples
    --------
    Example 17, the bee and the trunk ``S2``; the paper prints
    ``P2 = -0.3 l^4 + 45.7375 l^3 + 34.125 l^2 - 11.6625 l + 0.25`` and
    ``Delta_4 = 6.90965e8``:

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> P2 = characteristic_polynomial(bee, "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> [float(c) for c in reversed(P2.coefficients)]
    [-0.3, 45.7375, 34.125, -11.6625, 0.25]
    >>> f"{float(P2.deltas()[2]):.6g}", P2.structure.describe(), P2.signs.pattern
    ('6.90965e+08', '4 real (4 distinct)', '-+++')

    Example 11:

    >>> P = characteristic_polynomial("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
    >>> P
    CharacteristicPolynomial(-12*lambda**4 - 12*lambda**3 - 67*lambda**2 - 64*lambda - 16)
    >>> P.deltas()[1:]
    (Fraction(-13790208, 1), Fraction(0, 1))
    """

    def __init__(
        self, E: Quadric, Q: Quadric, e_flipped: bool = False, ints: tuple[int, ...] | None = None
    ) -> None:
        self.E = E
        self.Q = Q
        self.e_flipped = e_flipped
        eI, dE = E.integer_form()
        qI, dQ = Q.integer_form()
        # ``ints``: the coefficients, when the caller has them already (of these integer forms)
        self._ints: tuple[int, ...] = pencil_coefficients(*eI, *qI) if ints is None else ints
        self._scale = (dE, dQ)

    # -- coefficients ----------------------------------------------------------

    @property
    def integer_coefficients(self) -> tuple[int, ...]:
        """``C_0 .. C_4`` of ``det(lambda*E_int + Q_int)``: same root structure, same signs."""
        return self._ints

    @property
    def root_scale(self) -> Fraction:
        """``d_E / d_Q``: the roots of ``P`` are those of the integer polynomial times this."""
        dE, dQ = self._scale
        return Fraction(dE, dQ)

    @cached_property
    def coefficients(self) -> tuple[Fraction, ...]:
        """``(c0, c1, c2, c3, c4)`` exactly."""
        dE, dQ = self._scale
        return tuple(Fraction(C, dE**k * dQ ** (4 - k)) for k, C in enumerate(self._ints))

    def __getitem__(self, k: int) -> Fraction:
        return self.coefficients[k]

    @property
    def degree(self) -> int:
        """Degree of ``P`` (4: ``c4 = det E != 0`` for an ellipsoid)."""
        for k in range(4, -1, -1):
            if self._ints[k]:
                return k
        return -1

    def __call__(self, lam: Any) -> Any:
        """``P(lam)`` by Horner's rule on the exact coefficients (any number type)."""
        acc: Any = 0
        for c in reversed(self.coefficients):
            acc = acc * lam + c
        return acc

    # -- discrimination system and roots -------------------------------------

    @cached_property
    def structure(self) -> RootStructure:
        """Exact numbers and multiplicities of real and non-real roots."""
        return root_structure(self._ints)

    @cached_property
    def signs(self) -> RootSigns:
        """Exact root-sign pattern (Descartes where real-rooted, else certified isolation)."""
        return root_signs(self._ints, self.structure)

    def deltas(self) -> tuple[Fraction, Fraction, Fraction]:
        """The paper's ``(Delta_2, Delta_3, Delta_4)`` (Section 3.2) of the rational coefficients.

        ``Delta_4`` with the corrected fifth term (erratum ``delta4-term``);
        see :func:`~quadric_contact.exact.discriminants.paper_deltas`.
        """
        d2, d3, d4 = paper_deltas(self.coefficients)
        return Fraction(d2), Fraction(d3), Fraction(d4)

    def delta_signs(self) -> tuple[int, int, int]:
        """Signs of ``(Delta_2, Delta_3, Delta_4)``: those of Yang's ``D_2 .. D_4``
        (positive multiples), already computed on the integer polynomial."""
        _, s2, s3, s4 = self.structure.sequence_signs
        return (s2, s3, s4)

    def roots(self, digits: int = 17) -> list[tuple[Any, int]]:
        """Certified root enclosures ``(acb ball, multiplicity)`` (python-flint),
        real roots first in increasing order with exactly zero imaginary part."""
        old = flint.ctx.dps
        try:
            flint.ctx.dps = digits
            f = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in self.coefficients])
            return list(f.complex_roots())
        finally:
            flint.ctx.dps = old

    # -- presentation ------------------------------------------------------------

    def as_sympy(self, symbol: str = "lambda") -> Any:
        """``P`` as a sympy expression in ``symbol`` (exact rational coefficients)."""
        import sympy  # sympy is heavy: only for sympy output

        lam = sympy.Symbol(symbol)
        return sum(
            (sympy.Rational(c.numerator, c.denominator) * lam**k for k, c in enumerate(self.coefficients)),
            sympy.Integer(0),
        )

    def __str__(self) -> str:
        """``P`` in descending powers of ``lambda``, in sympy's notation
        (``-2*lambda**3/3 + 1``), written here so that coefficients of any size
        print (see :mod:`~quadric_contact.exact.printing`)."""
        terms = []
        for k in range(len(self.coefficients) - 1, -1, -1):
            c = self.coefficients[k]
            if not c:
                continue
            p, q = abs(c.numerator), c.denominator
            power = "" if k == 0 else "lambda" if k == 1 else f"lambda**{k}"
            body = int_text(p) if not power else power if p == 1 else f"{int_text(p)}*{power}"
            if q != 1:
                body += f"/{int_text(q)}"
            terms.append(("-" if c < 0 else "+", body))
        if not terms:
            return "0"
        first_sign, first = terms[0]
        return ("-" if first_sign == "-" else "") + first + "".join(f" {s} {b}" for s, b in terms[1:])

    def __repr__(self) -> str:
        return f"CharacteristicPolynomial({self})"

    def __eq__(self, other: object) -> bool:
        if isinstance(other, CharacteristicPolynomial):
            return self.coefficients == other.coefficients
        if isinstance(other, Sequence):
            return tuple(Fraction(c) for c in other) == self.coefficients
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.coefficients)


def characteristic_polynomial(E: Any, Q: Any, *, normalize: bool = True) -> CharacteristicPolynomial:
    """``P(lambda) = det(lambda*E + Q)`` (eq. (1)) with exact coefficients.

    Parameters
    ----------
    E : Quadric, 4x4 matrix-like or equation
        A real ellipsoid.  With ``normalize=True`` (default) its matrix is
        replaced by its negative when its inside is positive, so that
        ``det E < 0`` as the paper assumes (``result.e_flipped`` says so).
    Q : Quadric, 4x4 matrix-like or equation
        Any quadric, taken exactly as given (its sign fixes ``R-`` and ``R+``).
    normalize : bool
        ``False`` computes ``det(lambda*E + Q)`` for any two symmetric
        matrices, without checking that ``E`` is an ellipsoid.

    Returns
    -------
    CharacteristicPolynomial

    Raises
    ------
    NotAnEllipsoidError
        If ``normalize`` and ``E`` is not a real ellipsoid.

    References
    ----------
    Paper eq. (1); the closed form is derived and checked in :mod:`quadric_contact.codegen`.

    Examples
    --------
    Example 17, the bee and the separating plane ``z = 6``:

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> characteristic_polynomial(bee, "z - 6").coefficients
    (Fraction(0, 1), Fraction(0, 1), Fraction(-1, 4), Fraction(-3, 2), Fraction(-3, 10))
    """
    e = as_quadric(E, "E")
    q = as_quadric(Q, "Q")
    if not normalize:
        return CharacteristicPolynomial(e, q, False)
    # Sylvester's criterion on the quadratic part of E, then det E < 0, which is P's leading
    # coefficient: the ellipsoid test and P share that determinant
    sign = e._quadratic_part_sign()
    if sign:
        C = pencil_coefficients(*e.integer_form()[0], *q.integer_form()[0])
        if C[4] < 0:
            if sign > 0:
                return CharacteristicPolynomial(e, q, False, C)
            # det(lambda (-E) + Q) = P(-lambda): the odd coefficients change sign
            return CharacteristicPolynomial(-e, q, True, (C[0], -C[1], C[2], -C[3], C[4]))
    raise e._not_an_ellipsoid()
