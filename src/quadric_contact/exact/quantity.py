"""Exact quantities: rational functions of real algebraic numbers, decided lazily.

The smallness conditions (Tables 1 and 2) compare squares of lengths and
curvatures that are rational functions of eigenvalues (roots of cubics over
Q) and rational invariants.  A :class:`Quantity` keeps such a function and
its arguments; a comparison (:func:`compare_quantities`) is first tried with
certified balls at two precisions, and only when they overlap are both sides
built as exact :class:`~quadric_contact.exact.algebraic.RealAlgebraic` numbers and
compared exactly.  There is no tolerance anywhere.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from fractions import Fraction
from typing import Any

import flint

from quadric_contact.exact.algebraic import RealAlgebraic, algebraic_value
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import fmpq_of

__all__ = ["EXACT", "ExactNumbers", "Quantity", "compare_quantities", "sorted_desc", "sqrt_rational"]


# -- exact quantities --------------------------------------------------------------------


class Quantity:
    """A rational function of real algebraic numbers, evaluated lazily:
    certified balls for quick decisions, an exact RealAlgebraic on demand."""

    __slots__ = ("_exact", "args", "display", "fn")

    def __init__(
        self,
        args: tuple[RealAlgebraic, ...],
        fn: Callable[[Sequence[Any], Callable[[Fraction], Any]], Any],
        display: Callable[[], Any],
    ) -> None:
        self.args = args
        self.fn = fn
        self.display = display
        self._exact: RealAlgebraic | None = None

    @classmethod
    def of(cls, value: Any) -> Quantity:
        if isinstance(value, Quantity):
            return value
        if isinstance(value, RealAlgebraic) and not value.is_rational:
            return cls((value,), lambda v, c: v[0], value.to_sympy)
        q = value.as_fraction() if isinstance(value, RealAlgebraic) else Fraction(value)

        def show() -> Any:
            import sympy  # sympy is heavy: only for sympy output

            return sympy.Rational(q.numerator, q.denominator)

        return cls((), lambda v, c: c(q), show)

    def _combine(self, other: Any, op: Callable[[Any, Any], Any], sym: Callable[[Any, Any], Any]) -> Quantity:
        o = Quantity.of(other)
        args = list(self.args)
        keys = [(a.minpoly, a.index) for a in args]
        idx_o = []
        for a in o.args:
            k = (a.minpoly, a.index)
            if k in keys:
                idx_o.append(keys.index(k))
            else:
                keys.append(k)
                args.append(a)
                idx_o.append(len(args) - 1)
        n_self = len(self.args)
        f1, f2 = self.fn, o.fn

        def fn(v: Sequence[Any], c: Callable[[Fraction], Any]) -> Any:
            return op(f1(v[:n_self], c), f2([v[i] for i in idx_o], c))

        d1, d2 = self.display, o.display
        return Quantity(tuple(args), fn, lambda: sym(d1(), d2()))

    def __add__(self, o: Any) -> Quantity:
        return self._combine(o, lambda x, y: x + y, lambda x, y: x + y)

    def __sub__(self, o: Any) -> Quantity:
        return self._combine(o, lambda x, y: x - y, lambda x, y: x - y)

    def __mul__(self, o: Any) -> Quantity:
        return self._combine(o, lambda x, y: x * y, lambda x, y: x * y)

    def __truediv__(self, o: Any) -> Quantity:
        return self._combine(o, lambda x, y: x / y, lambda x, y: x / y)

    def __rtruediv__(self, o: Any) -> Quantity:
        return Quantity.of(o) / self

    def __rmul__(self, o: Any) -> Quantity:
        return Quantity.of(o) * self

    def __neg__(self) -> Quantity:
        return Quantity.of(0) - self

    def __pow__(self, n: int) -> Quantity:
        f = self.fn
        d = self.display
        return Quantity(self.args, lambda v, c: f(v, c) ** n, lambda: d() ** n)

    # -- evaluation ---------------------------------------------------------------

    def ball(self, bits: int) -> Any:
        with working_precision(bits):
            vals = [a.enclosure(bits) for a in self.args]
            return self.fn(vals, lambda q: flint.arb(fmpq_of(q)))

    def exact(self) -> RealAlgebraic:
        if self._exact is None:
            f = self.fn

            def run(*vals: Any, const: Callable[[Fraction], Any] = Fraction) -> Any:
                return f(vals, const)

            run.takes_const = True  # type: ignore[attr-defined]
            self._exact = algebraic_value(run, self.args)
        return self._exact

    def is_rational(self) -> bool:
        return not self.args

    def sympy(self) -> Any:
        return self.display()


def compare_quantities(x: Quantity, y: Quantity) -> int:
    """Exact sign of ``x - y``: certified balls first, exact algebraic numbers if needed."""
    if x.is_rational() and y.is_rational():
        a = x.fn([], Fraction)
        b = y.fn([], Fraction)
        return (a > b) - (a < b)
    for bits in (64, 160):
        d = x.ball(bits) - y.ball(bits)
        if d > 0:
            return 1
        if d < 0:
            return -1
    ex, ey = x.exact(), y.exact()
    return (ex > ey) - (ex < ey)


def sorted_desc(qs: list[Quantity]) -> list[Quantity]:
    def cmp(x: Quantity, y: Quantity) -> int:
        return compare_quantities(y, x)

    return sorted(qs, key=functools.cmp_to_key(cmp))


def sqrt_rational(q: Fraction) -> Quantity:
    return Quantity.of(RealAlgebraic.sqrt(q))


class ExactNumbers:
    """The numbers the Table 2 formulas below are written in: exact quantities (balls
    first, real algebraic numbers on demand).  :mod:`quadric_contact.families.family` passes
    symbolic ones (rational functions of a family's parameters) with the same methods."""

    @staticmethod
    def of(value: Any) -> Quantity:
        return Quantity.of(value)

    @staticmethod
    def rational(value: RealAlgebraic) -> Fraction:
        """A rational eigenvalue (a rank-one quadratic part's only non-zero one: its trace)."""
        return value.as_fraction()

    @staticmethod
    def sqrt(value: Fraction) -> Quantity:
        return sqrt_rational(value)

    @staticmethod
    def sorted_desc(values: list[Quantity]) -> list[Quantity]:
        return sorted_desc(values)


EXACT = ExactNumbers()
