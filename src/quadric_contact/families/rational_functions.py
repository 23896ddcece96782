"""Rational functions of a family's parameters, and the smallness conditions built from them.

The values every module of the families works with: :class:`RationalFunction` (an
element of Q(parameters), exact), :class:`FamilyCondition` (one smallness inequality of
Tables 1-2 over a family) and :class:`FamilySmallness` (the whole row), and the reader
of a sympy expression as a rational function (:func:`_sympy_rational`).

They live below :mod:`quadric_contact.families.family` so that the modules that compute with a
family (:mod:`~quadric_contact.families.family_smallness`, :mod:`~quadric_contact.families.family_numeric`,
:mod:`~quadric_contact.families.family_maps`) import them without importing
:mod:`~quadric_contact.families.family`, which imports those modules for its conveniences
(:attr:`Family.smallness <quadric_contact.families.family.Family.smallness>`,
:meth:`~quadric_contact.families.family.Family.lambdify`,
:meth:`~quadric_contact.families.family.Family.contact_map`).  :mod:`quadric_contact.families.family`
re-exports every public name here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any

import flint
import sympy as sp

from quadric_contact.exact.errors import EquationError, NotANumberError
from quadric_contact.exact.rational import fmpq_of, to_fraction
from quadric_contact.model.classification import QuadricKind

__all__ = ["FamilyCondition", "FamilySmallness", "RationalFunction"]


class RationalFunction:
    """An element of Q(parameters): ``num / den`` with ``fmpq_mpoly`` numerator and
    denominator over the same context, coprime, the denominator with leading coefficient 1
    (so ``den == 1`` for a polynomial).

    Supports ``+ - *``, ``/`` by a non-zero element, ``**`` with a non-negative integer,
    exact evaluation and conversion to sympy.

    Examples
    --------
    >>> ctx = flint.fmpq_mpoly_ctx.get(("s",), "lex")
    >>> (s,) = ctx.gens()
    >>> r = RationalFunction(ctx.constant(1), s * s) - RationalFunction(ctx.constant(1))
    >>> r, r.is_polynomial, r.evaluate([Fraction(1, 2)])
    ((-s^2 + 1)/(s^2), False, Fraction(3, 1))
    """

    __slots__ = ("den", "num")

    def __init__(self, num: Any, den: Any = None, *, normalized: bool = False) -> None:
        if den is None:
            self.num, self.den = num, num.context().constant(1)
            return
        if den.is_zero():
            raise ZeroDivisionError("a rational function with zero denominator")
        if not normalized:
            if den.is_constant():
                num, den = num / den.leading_coefficient(), den.context().constant(1)
            else:
                g = num.gcd(den)
                if not g.is_one():
                    num, den = num / g, den / g
                lc = den.leading_coefficient()
                if lc != 1:
                    num, den = num / lc, den / lc
        self.num, self.den = num, den

    @property
    def context(self) -> Any:
        return self.num.context()

    @property
    def is_polynomial(self) -> bool:
        """True when the denominator is 1."""
        return bool(self.den.is_one())

    @property
    def is_constant(self) -> bool:
        return bool(self.num.is_constant() and self.den.is_one())

    def is_zero(self) -> bool:
        return bool(self.num.is_zero())

    @property
    def degree(self) -> int:
        """The larger total degree of numerator and denominator."""
        return max(int(self.num.total_degree()), int(self.den.total_degree()), 0)

    def _lift(self, other: Any) -> RationalFunction:
        if isinstance(other, RationalFunction):
            return other
        value = to_fraction(other)
        return RationalFunction(self.context.constant(flint.fmpq(value.numerator, value.denominator)))

    def __add__(self, other: Any) -> RationalFunction:
        o = self._lift(other)
        if self.den.is_one() and o.den.is_one():
            return RationalFunction(self.num + o.num)
        if self.den == o.den:
            return RationalFunction(self.num + o.num, self.den)
        return RationalFunction(self.num * o.den + o.num * self.den, self.den * o.den)

    __radd__ = __add__

    def __neg__(self) -> RationalFunction:
        return RationalFunction(-self.num, self.den, normalized=True)

    def __sub__(self, other: Any) -> RationalFunction:
        return self + (-self._lift(other))

    def __rsub__(self, other: Any) -> RationalFunction:
        return self._lift(other) - self

    def __mul__(self, other: Any) -> RationalFunction:
        o = self._lift(other)
        if self.den.is_one() and o.den.is_one():
            return RationalFunction(self.num * o.num)
        return RationalFunction(self.num * o.num, self.den * o.den)

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> RationalFunction:
        o = self._lift(other)
        if o.is_zero():
            raise ZeroDivisionError("division by the zero rational function")
        return RationalFunction(self.num * o.den, self.den * o.num)

    def __rtruediv__(self, other: Any) -> RationalFunction:
        return self._lift(other) / self

    def __pow__(self, n: int) -> RationalFunction:
        if n < 0:
            return RationalFunction(self.den**-n, self.num**-n)
        return RationalFunction(self.num**n, self.den**n, normalized=True)

    def __eq__(self, other: object) -> bool:
        if isinstance(other, RationalFunction):
            return bool(self.num == other.num and self.den == other.den)
        try:
            return self == self._lift(other)
        except (TypeError, ValueError, NotANumberError):
            return NotImplemented

    def __hash__(self) -> int:
        return hash((str(self.num), str(self.den)))

    def evaluate(self, values: Sequence[Any]) -> Fraction:
        """The exact value at ``values`` (one number per parameter, in order).

        Raises
        ------
        ZeroDivisionError
            At a pole.
        """
        args = [_exact_fmpq(v) for v in values]
        d = self.den(*args) if args else self.den.leading_coefficient()
        if d == 0:
            raise ZeroDivisionError("the point is a pole of the rational function")
        n = self.num(*args) if args else (self.num.leading_coefficient() if not self.num.is_zero() else 0)
        q = flint.fmpq(n) / d
        return Fraction(int(q.p), int(q.q))

    def substitute(self, values: Mapping[int, Any]) -> RationalFunction:
        """Substitute exact numbers for some parameters (by index); the context stays."""
        if not values:
            return self
        names = self.context.names()
        subs = {names[i]: _exact_fmpq(v) for i, v in values.items()}
        return RationalFunction(self.num.subs(subs), self.den.subs(subs))

    def to_sympy(self, symbols: Sequence[sp.Symbol]) -> sp.Expr:
        """The exact sympy expression in ``symbols`` (one per parameter)."""
        return _poly_to_sympy(self.num, symbols) / _poly_to_sympy(self.den, symbols)

    def __repr__(self) -> str:
        if self.den.is_one():
            return f"({self.num})"
        return f"({self.num})/({self.den})"


def _exact_fmpq(value: Any) -> Any:
    """A user number (anything :func:`~quadric_contact.exact.rational.to_fraction` takes) or an ``fmpq``."""
    return value if isinstance(value, flint.fmpq) else fmpq_of(to_fraction(value))


def _poly_to_sympy(p: Any, symbols: Sequence[sp.Symbol]) -> sp.Expr:
    # One Add of all the terms: adding them one by one re-flattens the sum each time,
    # quadratic in the terms (a Delta4 of 2214 terms took 77 s, now 0.1 s).
    terms = []
    for mono, c in p.to_dict().items():
        powers = [s ** int(e) for s, e in zip(symbols, mono, strict=True) if e]
        terms.append(sp.Mul(sp.Rational(int(c.p), int(c.q)), *powers))
    return sp.Add(*terms)


def _poly_from_sympy(poly: sp.Poly, ctx: Any) -> Any:
    d = {}
    for mono, c in poly.terms():
        c = sp.Rational(c)
        d[tuple(int(e) for e in mono)] = flint.fmpq(int(c.p), int(c.q))
    return ctx.from_dict(d) if d else ctx.constant(0)


def _sympy_rational(expr: Any, symbols: Sequence[sp.Symbol], pctx: Any, what: str) -> RationalFunction:
    """A sympy expression (an object built by the caller, never text) as a rational function
    of ``symbols`` with rational coefficients."""
    if not isinstance(expr, sp.Expr):
        raise EquationError(f"{what}: {expr!r} is not an algebraic expression", expr)
    others = expr.free_symbols - set(symbols)
    if others:
        raise EquationError(
            f"{what}: {expr} has symbols that are not declared parameters: {sorted(map(str, others))}", expr
        )
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    out = []
    for part in (num, den):
        if not symbols:
            if not part.is_Rational:
                raise EquationError(f"{what}: {expr} is not a rational number", expr)
            out.append(pctx.constant(flint.fmpq(int(part.p), int(part.q))))
            continue
        try:
            poly = sp.Poly(part, *symbols, domain=sp.QQ)
        except (sp.PolynomialError, sp.CoercionFailed) as exc:
            raise EquationError(
                f"{what}: {expr} is not a quotient of polynomials over Q: {exc}", expr
            ) from exc
        out.append(_poly_from_sympy(poly, pctx))
    return RationalFunction(out[0], out[1])


@dataclass(frozen=True)
class FamilyCondition:
    """One smallness inequality of Tables 1-2 (corrected) over a family.

    ``value`` is ``lhs^2 - rhs^2``, a rational function of the parameters (both sides are
    positive, so the inequality holds exactly when ``value >= 0`` for ``relation`` ``">="``
    and ``value <= 0`` for ``"<="``), valid where the family's assumptions hold
    (:attr:`FamilySmallness.assumptions`).
    """

    name: str
    relation: str
    value: RationalFunction
    lhs_squared: sp.Expr
    rhs_squared: sp.Expr
    source: str
    erratum: str | None
    symbols: tuple[sp.Symbol, ...] = field(repr=False)

    @property
    def is_polynomial(self) -> bool:
        return self.value.is_polynomial

    @cached_property
    def expr(self) -> sp.Expr:
        return self.value.to_sympy(self.symbols)

    def holds_at(self, values: Sequence[Any]) -> bool:
        v = self.value.evaluate(values)
        return v >= 0 if self.relation == ">=" else v <= 0

    def __str__(self) -> str:
        kind = "polynomial" if self.is_polynomial else "rational function"
        tail = f" [{self.source}: {self.erratum}]" if self.erratum else ""
        return f"{self.name}: {self.lhs_squared} {self.relation} {self.rhs_squared}  ({kind}){tail}"


@dataclass(frozen=True)
class FamilySmallness:
    """Tables 1-2 (corrected) over a family: is ``E(p)`` small with respect to ``Q(p)``?

    Attributes
    ----------
    status : str
        ``"constant"``: the invariants of Section 2.4 that smallness depends on (Theorem 5)
        do not depend on the parameters (a family that only moves ``E`` or ``Q``): the
        answer is :attr:`report`'s everywhere ``Q`` keeps its type.
        ``"polynomial"`` / ``"rational"``: the eigenvalues of both quadratic parts are
        rational functions of the parameters, and every squared condition is a
        polynomial / some are quotients (:attr:`conditions`).
        ``"algebraic"``: an eigenvalue is a root of an irreducible factor of degree 2 or 3
        of the characteristic polynomial over Q(parameters); the conditions are algebraic
        functions, decided point by point (``smallness()`` at the point, or the maps).
        ``"excluded"``: ``Q`` has no row of Table 1 at the reference point.
    kind : QuadricKind
        The type of ``Q`` at the reference point.
    report : SmallnessReport or None
        The exact decision at the reference point.
    conditions, alternative : tuple of FamilyCondition
        The row of ``kind`` (and, for two ellipsoids, the enclosing alternative).
    assumptions : tuple
        Sympy relations under which :attr:`conditions` are the row's conditions: the signs
        and the order of the eigenvalues at the reference point (they fix which one is
        ``alpha``, ``a``, ...).
    explanation : str
    """

    status: str
    kind: QuadricKind
    report: Any
    conditions: tuple[FamilyCondition, ...]
    alternative: tuple[FamilyCondition, ...]
    assumptions: tuple[Any, ...]
    explanation: str

    @property
    def not_polynomial(self) -> list[str]:
        """Names of the conditions that are quotients of polynomials, not polynomials."""
        return [c.name for c in (*self.conditions, *self.alternative) if not c.is_polynomial]

    def __str__(self) -> str:
        lines = [f"smallness over the family ({self.status}): {self.explanation}"]
        lines += [f"  {c}" for c in self.conditions]
        if self.alternative:
            lines.append("  or (enclosing, Q small with respect to E):")
            lines += [f"    {c}" for c in self.alternative]
        if self.assumptions and self.conditions:
            lines.append("  where: " + ", ".join(str(a) for a in self.assumptions))
        return "\n".join(lines)
