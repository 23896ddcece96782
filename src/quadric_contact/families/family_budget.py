"""Polynomial arithmetic in the parameters of a family, counted before every step.

A family's characteristic polynomial and discriminants are built by straight-line
formulas (:func:`~quadric_contact._generated.formulas.pencil_coefficients`,
:func:`~quadric_contact._generated.formulas.paper_deltas`) over polynomials in
its parameters.  Their size is not known in advance and grows quickly (``Δ4`` is
of degree 24 in the matrix entries): eight parameters in 160 characters of
equations give a ``Δ4`` of nine million terms, and a larger product makes FLINT
fail to allocate and abort the interpreter.  So the formulas run over
:class:`CountedPolynomial`, which charges every product *before* it runs (the
product of the operands' term counts, which also bounds the terms of the
result) and checks the terms of what it built, and refuses with
:class:`~quadric_contact.exact.errors.WorkLimitError` when a bound of
:mod:`~quadric_contact.exact.bounds` is reached.
"""

from __future__ import annotations

from typing import Any

import flint

from quadric_contact.exact.bounds import MAX_FAMILY_TERMS, MAX_FAMILY_WORK_PRODUCTS
from quadric_contact.exact.errors import WorkLimitError

__all__ = ["CountedPolynomial", "PolynomialBudget"]


class PolynomialBudget:
    """The work allowed to one computation: at most ``products`` term-by-term
    products in all, charged before each product, and at most ``terms`` terms in
    any polynomial built, checked on each result (a result is never larger than
    the products that made it, so nothing is built beyond what the products
    allow).  ``what`` names the computation and its input in the error."""

    def __init__(self, what: str, *, terms: int = MAX_FAMILY_TERMS, products: int = MAX_FAMILY_WORK_PRODUCTS):
        self.what = what
        self.terms = terms
        self.products = products
        self.spent = 0

    def charge(self, products: int) -> None:
        """Refuse before a step that costs ``products`` term products beyond the budget."""
        self.spent += products
        if self.spent > self.products:
            raise WorkLimitError(
                f"{self.what}: more than {self.products} term products (MAX_FAMILY_WORK_PRODUCTS) "
                "would be spent",
                self.what,
                limit=self.products,
                needed=self.spent,
            )

    def built(self, p: Any) -> Any:
        """``p``, or a refusal if it has more than ``terms`` terms."""
        n = _terms(p)
        if n > self.terms:
            raise WorkLimitError(
                f"{self.what}: a polynomial of {n} terms in the parameters arises, more than "
                f"{self.terms} (MAX_FAMILY_TERMS)",
                self.what,
                limit=self.terms,
                needed=n,
            )
        return p


def _raw(x: Any) -> Any:
    return x.p if isinstance(x, CountedPolynomial) else x


def _terms(x: Any) -> int:
    return len(x) if isinstance(x, flint.fmpq_mpoly) else 1


class CountedPolynomial:
    """A ``flint.fmpq_mpoly`` whose ``+ - *`` charge a :class:`PolynomialBudget`
    before they run and check the size of what they built (a constant operand:
    ``int``, ``Fraction``, ``fmpq``)."""

    __slots__ = ("budget", "p")

    def __init__(self, p: Any, budget: PolynomialBudget) -> None:
        self.p = p
        self.budget = budget

    def _sum(self, a: Any, b: Any) -> CountedPolynomial:
        self.budget.charge(_terms(a) + _terms(b))
        return CountedPolynomial(self.budget.built(a + b), self.budget)

    def __add__(self, other: Any) -> CountedPolynomial:
        return self._sum(self.p, _raw(other))

    def __radd__(self, other: Any) -> CountedPolynomial:
        return self._sum(_raw(other), self.p)

    def __sub__(self, other: Any) -> CountedPolynomial:
        return self._sum(self.p, -_raw(other))

    def __rsub__(self, other: Any) -> CountedPolynomial:
        return self._sum(_raw(other), -self.p)

    def __neg__(self) -> CountedPolynomial:
        return CountedPolynomial(-self.p, self.budget)

    def __mul__(self, other: Any) -> CountedPolynomial:
        a, b = self.p, _raw(other)
        self.budget.charge(_terms(a) * _terms(b))
        return CountedPolynomial(self.budget.built(a * b), self.budget)

    __rmul__ = __mul__

    def __pow__(self, n: int) -> CountedPolynomial:
        out: Any = CountedPolynomial(self.p.context().constant(1), self.budget)
        for _ in range(n):
            out = out * self
        return out
