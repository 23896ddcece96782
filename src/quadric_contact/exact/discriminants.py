"""The complete discrimination system of a polynomial (Yang 1999) and the
exact classification of its roots.

For ``f`` of degree ``n`` the *discriminant sequence* ``D_1, .., D_n`` is the
list of even-order principal minors of the discrimination matrix of ``f``
and ``f'`` (the subresultant-based sequence of Yang 1999).  Its *revised sign
list* gives, exactly (Yang 1999, Theorem 1):

* the number of distinct pairs of non-real conjugate roots: the number ``v``
  of sign changes of the revised list;
* the number of distinct real roots: ``l - 2v`` with ``l`` the number of
  non-zero members;
* ``deg gcd(f, f') = n - k`` for the last non-zero ``D_k``.

Multiplicities follow by applying the same to ``gcd(f, f')``, whose roots are
the multiple roots of ``f`` with multiplicity lowered by one, and so on.  The
formulas are the generated ones (:mod:`quadric_contact.codegen`); the
paper's ``Delta_3`` and ``Delta_4`` (Section 3.2) are ``D_3/(2 c4^2)`` and
``D_4/c4^2``: same signs, since ``c4 = det E != 0``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint

from quadric_contact._generated import formulas
from quadric_contact.exact.errors import DegeneratePencilError
from quadric_contact.exact.rational import sign, to_fraction

__all__ = [
    "RootStructure",
    "discrimination_sequence",
    "paper_deltas",
    "revised_sign_list",
    "root_structure",
    "strip",
]

_SEQUENCES: dict[int, Any] = {
    1: formulas.discrimination_sequence_1,
    2: formulas.discrimination_sequence_2,
    3: formulas.discrimination_sequence_3,
    4: formulas.discrimination_sequence_4,
}


def exact_coefficients(coeffs: Sequence[Any]) -> list[Any]:
    """The coefficients as exact numbers: ints and Fractions as they are, anything else through
    :func:`~quadric_contact.exact.rational.to_fraction` (numpy integers, binary64 values as the
    dyadic rationals they store, decimal strings; a bool, NaN or complex is refused there)."""
    return [x if type(x) in (int, Fraction) else to_fraction(x) for x in coeffs]


def strip(coeffs: Sequence[Any]) -> list[Any]:
    """Drop zero leading (highest-degree) coefficients.

    Parameters
    ----------
    coeffs : sequence of numbers
        ``c0, c1, ...`` (lowest degree first).

    Returns
    -------
    list
        The same coefficients without the trailing zeros of the list, so that
        the last one is the true leading coefficient (empty for the zero
        polynomial).

    Examples
    --------
    >>> strip([0, 0, -1, -3, 0])
    [0, 0, -1, -3]
    """
    out = list(coeffs)
    while out and out[-1] == 0:
        out.pop()
    return out


def discrimination_sequence(coeffs: Sequence[Any]) -> tuple[Any, ...]:
    """Yang's discrimination sequence ``(D_1, .., D_n)`` of ``f = sum coeffs[k] x^k``.

    Parameters
    ----------
    coeffs : sequence
        ``c0, c1, ...`` of a polynomial of degree ``n <= 4`` (zero leading
        coefficients are dropped first).  Any number type with ``+ - *``:
        ints, Fractions, floats, numpy arrays, sympy symbols, flint balls.

    Returns
    -------
    tuple
        ``(D_1, .., D_n)``, the even-order principal minors of the
        discrimination matrix of ``f`` and ``f'``; empty for a constant.

    Raises
    ------
    ValueError
        If the degree is above 4.

    References
    ----------
    Yang (1999), the complete discrimination system; Section 3.2 of the paper
    (``D_3 = 2 c4^2 Delta_3``, ``D_4 = c4^2 Delta_4``).

    Examples
    --------
    Example 11: ``P = -(1 + 2 lambda)^2 (16 + 3 lambda^2)``.

    >>> P = [-16, -64, -67, -12, -12]
    >>> discrimination_sequence(P)   # D_3 = 2 c4^2 Delta_3, D_4 = c4^2 Delta_4
    (576, -864000, -3971579904, 0)
    """
    c = strip(coeffs)
    n = len(c) - 1
    if n < 1:
        return ()
    if n > 4:
        raise ValueError(f"degree {n} > 4 is not supported")
    return tuple(_SEQUENCES[n](*c))


def paper_deltas(coeffs: Sequence[Any]) -> tuple[Any, Any, Any]:
    """``(Delta_2, Delta_3, Delta_4)`` of a quartic, with the paper's normalisation.

    Parameters
    ----------
    coeffs : sequence
        ``c0 .. c4`` (missing high coefficients are taken as 0); any number
        type with ``+ - *``.

    Returns
    -------
    tuple
        ``(Delta_2, Delta_3, Delta_4)``: ``D_2 / c4^2``, ``D_3 / (2 c4^2)`` and
        ``D_4 / c4^2`` (Yang's sequence divided by positive factors, so the
        signs agree when ``c4 != 0``).  ``Delta_4`` is the corrected formula
        (erratum ``delta4-term``: the printed fifth term is wrong).

    References
    ----------
    Section 3.2 (the formulas), Corollary 10 (their use), Algorithm 1.

    Examples
    --------
    Example 17, the bee and the plane ``z = 6``: the paper prints
    ``P0 = lambda^2 (-0.3 lambda^2 - 1.5 lambda - 0.25)`` and
    ``Delta_3 = 0.121875``:

    >>> from fractions import Fraction as F
    >>> d2, d3, d4 = paper_deltas([0, 0, F(-1, 4), F(-3, 2), F(-3, 10)])
    >>> d3, float(d3), d4
    (Fraction(39, 320), 0.121875, Fraction(0, 1))

    Example 11.  The paper prints ``Delta_4 = 0`` and ``Delta_3 = -400``; the
    printed formula gives ``Delta_3 = -13790208`` (same sign; see
    :data:`quadric_contact.paper.errata.ERRATA`):

    >>> paper_deltas([-16, -64, -67, -12, -12])
    (-6000, -13790208, 0)
    """
    c = list(coeffs) + [0] * (5 - len(coeffs))
    return formulas.paper_deltas(*c[:5])


def revised_sign_list(signs: Sequence[int]) -> list[int]:
    """Yang's revised sign list of a sign list.

    Each run of ``k`` zeros that follows a non-zero sign ``s`` and precedes
    another non-zero sign becomes ``[-s, -s, s, s, -s, -s, ...]`` (the
    ``r``-th zero gets ``(-1)^(r(r+1)/2) s``).  Trailing zeros are kept.

    Parameters
    ----------
    signs : sequence of int
        Signs (-1, 0, 1) of ``D_1, .., D_n``.

    Returns
    -------
    list of int
        The revised list: its number ``v`` of sign changes is the number of
        distinct pairs of non-real roots, and ``l - 2v`` (``l`` the number of
        non-zero entries) the number of distinct real roots.

    References
    ----------
    Yang (1999), Theorem 1.

    Examples
    --------
    >>> revised_sign_list([1, 0, 0, 1])
    [1, -1, -1, 1]
    >>> revised_sign_list([1, -1, 0, 0])   # trailing zeros: a multiple root
    [1, -1, 0, 0]
    """
    out = list(signs)
    last_nonzero = max((i for i, s in enumerate(out) if s), default=-1)
    i = 0
    while i <= last_nonzero:
        if out[i] == 0:
            j = i
            while out[j] == 0:
                j += 1
            s = out[i - 1]
            for r in range(1, j - i + 1):
                out[i + r - 1] = s * (-1) ** (r * (r + 1) // 2)
            i = j
        i += 1
    return out


@dataclass(frozen=True)
class RootStructure:
    """Exact numbers and multiplicities of the real and non-real roots.

    Attributes
    ----------
    degree : int
    real : tuple of int
        Multiplicities of the distinct real roots, decreasing.
    nonreal : tuple of int
        Multiplicities of the distinct non-real conjugate pairs (each pair
        listed once), decreasing.
    sequence_signs : tuple of int
        Signs of Yang's ``D_1 .. D_n`` (for a quartic: ``D_1`` and the signs
        of the paper's ``Delta_2 .. Delta_4``).

    Examples
    --------
    ``(x^2 - 1)^2``: two double real roots.

    >>> s = root_structure([1, 0, -2, 0, 1])
    >>> s.real, s.nonreal, s.real_count, s.has_multiple_root
    ((2, 2), (), 4, True)
    """

    degree: int
    real: tuple[int, ...]
    nonreal: tuple[int, ...]
    sequence_signs: tuple[int, ...]

    @property
    def distinct_real(self) -> int:
        """Number of distinct real roots."""
        return len(self.real)

    @property
    def nonreal_pairs(self) -> int:
        """Number of non-real conjugate pairs, counted with multiplicity."""
        return sum(self.nonreal)

    @property
    def real_count(self) -> int:
        """Number of real roots counted with multiplicity."""
        return sum(self.real)

    @property
    def all_real(self) -> bool:
        """No non-real root (Theorem 2: no transversal contact for a small ellipsoid)."""
        return not self.nonreal

    @property
    def has_multiple_root(self) -> bool:
        """Some root (real or not) is multiple: ``Delta_4 = 0``."""
        return any(m > 1 for m in self.real + self.nonreal)

    def describe(self) -> str:
        """In words, e.g. ``'2 real (1 distinct, multiplicities [2]), 2 non-real (1 distinct pair(s))'``."""
        parts = []
        if self.real:
            parts.append(
                f"{self.real_count} real ({self.distinct_real} distinct"
                + (f", multiplicities {list(self.real)}" if self.has_multiple_root else "")
                + ")"
            )
        if self.nonreal:
            parts.append(f"{2 * self.nonreal_pairs} non-real ({len(self.nonreal)} distinct pair(s))")
        return ", ".join(parts) if parts else "no roots"


def _to_int_poly(coeffs: Sequence[Any]) -> list[int]:
    fr = [c if isinstance(c, (int, Fraction)) else Fraction(c) for c in coeffs]
    d = math.lcm(*(Fraction(c).denominator for c in fr)) if fr else 1
    return [int(Fraction(c) * d) for c in fr]


_FORM_RELATIVE = 1e-14
"""Relative error bound of :func:`binary64_forms`.  In the generated program of the three forms
(:func:`~quadric_contact._generated.formulas.quartic_sign_forms`, products and sums from the
left, as the tests pin it) each monomial, expanded, carries at most 22 roundings: a monomial of
``I`` has two inputs, each rounded once, two products and at most two sums, 6 in all; one of
``J`` at most 10; ``27 Delta_4 = 4 I^3 - J^2`` then has ``3 * 6 + 4 = 22`` for ``4 I^3`` and
``2 * 10 + 2 = 22`` for ``J^2``; ``Delta_3`` has 14 and ``Delta_2`` 5.  So ``|computed - exact|
<= gamma_22 M``, with ``M`` the same program on absolute values (:func:`magnitude_programs`), and
the computed ``M`` is at least ``(1 - gamma_22) M``: ``gamma_22 / (1 - gamma_22) < 2.5e-15``, and
the bound's own product adds one rounding.  The tests check the bound in exact arithmetic."""
_FORM_ABSOLUTE = 2.0**-1000
"""Absolute slack for underflow: with the coefficients scaled into ``[-1, 1]`` no intermediate
exceeds ``4 * 16^3 + 137^2``, so a product rounded in the subnormal range (absolute error at most
``2^-1075``; a sum there is exact), carried through the rest of the program, moves the result by
far less than this."""


def magnitude_programs(a0: Any, a1: Any, a2: Any, a3: Any, a4: Any) -> tuple[Any, Any, Any]:
    """The program of :func:`~quadric_contact._generated.formulas.quartic_sign_forms` on the
    absolute values ``a_k = |c_k|``, every difference made a sum: the ``M`` of the error bound
    ``gamma_k M`` of that program in binary64."""
    m2 = 8 * a2 * a4 + 3 * a3 * a3
    m3 = (
        16 * a0 * a2 * a4 * a4 + 6 * a0 * a3 * a3 * a4 + 18 * a1 * a1 * a4 * a4 + 14 * a1 * a2 * a3 * a4
        + 3 * a1 * a3 * a3 * a3 + 4 * a2 * a2 * a2 * a4 + a2 * a2 * a3 * a3
    )  # fmt: skip
    i = 12 * a0 * a4 + 3 * a1 * a3 + a2 * a2
    j = 72 * a0 * a2 * a4 + 27 * a0 * a3 * a3 + 27 * a1 * a1 * a4 + 9 * a1 * a2 * a3 + 2 * a2 * a2 * a2
    return m2, m3, 4 * i * i * i + j * j


def binary64_forms(c: Sequence[Any]) -> tuple[tuple[float, float], ...] | None:
    """For integer coefficients ``c0 .. c4``: the three forms of
    :func:`~quadric_contact._generated.formulas.quartic_sign_forms`, the generated program itself, in binary64
    on the coefficients scaled by ``2^-t`` into ``[-1, 1]`` (``t`` the bit length of the largest;
    form ``k`` of degree ``2k`` is then scaled by ``2^(-2k t)``: the same sign), each with its
    error bound ``_FORM_RELATIVE * M + _FORM_ABSOLUTE``.  None for other coefficients or beyond
    binary64's range."""
    if len(c) != 5:
        return None
    c0, c1, c2, c3, c4 = c
    if not (type(c0) is int and type(c1) is int and type(c2) is int and type(c3) is int and type(c4) is int):
        return None
    top = max(abs(c0), abs(c1), abs(c2), abs(c3), abs(c4)).bit_length()
    try:  # ldexp rounds the integer to binary64 first (once), then scales exactly
        f0, f1, f2, f3, f4 = (math.ldexp(c0, -top), math.ldexp(c1, -top), math.ldexp(c2, -top),
                              math.ldexp(c3, -top), math.ldexp(c4, -top))  # fmt: skip
    except OverflowError:  # a coefficient beyond binary64's range
        return None
    d2, d3, d4 = formulas.quartic_sign_forms(f0, f1, f2, f3, f4)
    m2, m3, m4 = magnitude_programs(abs(f0), abs(f1), abs(f2), abs(f3), abs(f4))
    r, a = _FORM_RELATIVE, _FORM_ABSOLUTE
    return (d2, r * m2 + a), (d3, r * m3 + a), (d4, r * m4 + a)


def _binary64_form_signs(c: Sequence[Any]) -> tuple[int, int, int] | None:
    """The signs of the three forms where :func:`binary64_forms` certifies all three (an exact
    zero never is), else None."""
    forms = binary64_forms(c)
    if forms is None:
        return None
    (d2, b2), (d3, b3), (d4, b4) = forms
    if not (abs(d2) > b2 and abs(d3) > b3 and abs(d4) > b4):
        return None
    return (1 if d2 > 0 else -1), (1 if d3 > 0 else -1), (1 if d4 > 0 else -1)


def quartic_form_signs(c: Sequence[Any]) -> tuple[int, int, int]:
    """The signs of ``(Delta_2, Delta_3, 27 Delta_4)`` of the quartic ``sum c[k] x^k`` (exact
    coefficients): in binary64 where :func:`binary64_forms` certifies them, exactly otherwise.
    The same signs either way."""
    fast = _binary64_form_signs(c)
    if fast is not None:
        return fast
    d2, d3, d4 = formulas.quartic_sign_forms(*c)
    return sign(d2), sign(d3), sign(d4)


def _counts(c: Sequence[Any]) -> tuple[int, int, int, tuple[int, ...]]:
    """(distinct real, distinct nonreal pairs, deg gcd(f, f'), signs of D) for exact coefficients."""
    n = len(c) - 1
    if n == 0:
        return 0, 0, 0, ()
    # quartic: D_1 = 4 c4^2 > 0 and D_k = (positive) * Delta_k for k = 2, 3, 4: the paper's
    # normalisation has the same signs and much smaller numbers
    signs: tuple[int, ...] = (
        (1, *quartic_form_signs(c)) if n == 4 else tuple(sign(d) for d in discrimination_sequence(c))
    )
    if n == 4:
        return _QUARTIC_COUNTS[signs]
    return _counts_of_signs(signs)


def _counts_of_signs(signs: tuple[int, ...]) -> tuple[int, int, int, tuple[int, ...]]:
    """:func:`_counts` from the signs of ``D_1 .. D_n`` (Yang's Theorem 1)."""
    n = len(signs)
    rev = revised_sign_list(list(signs))
    nonzero = [s for s in rev if s]
    v = sum(1 for a, b in pairwise(nonzero) if a != b)
    k = max((i + 1 for i, s in enumerate(signs) if s), default=0)
    return len(nonzero) - 2 * v, v, n - k, signs


_QUARTIC_COUNTS: dict[tuple[int, ...], tuple[int, int, int, tuple[int, ...]]] = {
    (1, s2, s3, s4): _counts_of_signs((1, s2, s3, s4))
    for s2 in (-1, 0, 1)
    for s3 in (-1, 0, 1)
    for s4 in (-1, 0, 1)
}
""":func:`_counts` of a quartic for each sign list of ``D_1 .. D_4`` (``D_1 > 0``): read once."""


def root_structure(coeffs: Sequence[Any]) -> RootStructure:
    """Classify the roots of ``sum coeffs[k] x^k`` exactly (degree <= 4).

    Parameters
    ----------
    coeffs : sequence of exact numbers
        ``c0, c1, ...`` (ints or Fractions; zero leading coefficients are dropped).

    Returns
    -------
    RootStructure
        Numbers and multiplicities of the real roots and of the non-real
        pairs, from the signs of the discrimination sequence (and, for the
        multiplicities, of that of ``gcd(f, f')``).

    References
    ----------
    Yang (1999), Theorem 1; Section 3.2 and Corollary 10 of the paper.

    Raises
    ------
    DegeneratePencilError
        If the polynomial is identically zero.

    Examples
    --------
    >>> root_structure([-16, -64, -67, -12, -12]).describe()   # Example 11
    '2 real (1 distinct, multiplicities [2]), 2 non-real (1 distinct pair(s))'
    """
    c = strip(exact_coefficients(coeffs))
    if not c:
        raise DegeneratePencilError("the polynomial vanishes identically", tuple(coeffs))
    n = len(c) - 1
    real_f, pairs_f, gdeg, signs = _counts(c)
    if gdeg == 0:
        return RootStructure(n, (1,) * real_f, (1,) * pairs_f, signs)

    ints = _to_int_poly(c)
    f = flint.fmpz_poly(ints)
    g = f.gcd(f.derivative())
    inner = root_structure([int(t) for t in g.coeffs()])
    real = sorted([m + 1 for m in inner.real] + [1] * (real_f - inner.distinct_real), reverse=True)
    pairs = sorted([m + 1 for m in inner.nonreal] + [1] * (pairs_f - len(inner.nonreal)), reverse=True)
    return RootStructure(n, tuple(real), tuple(pairs), signs)
