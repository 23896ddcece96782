"""Tables 1-2 (corrected) over a parametric family: where smallness is a rational condition.

Smallness depends only on the invariants of Section 2.4 (Theorem 5): the eigenvalues of
both quadratic parts, ``det``, and ``K``, ``J'`` where Table 2 uses them.  Over a family:

* when none of them depends on the parameters (``E`` or ``Q`` only moves rigidly: the bee's
  centre), smallness is *constant*, decided once exactly;
* when the characteristic polynomials of both quadratic parts split into linear factors over
  Q(parameters), every eigenvalue is a rational function of the parameters, and every
  squared condition of :func:`quadric_contact.theory.smallness.row_sides` (the corrected Table 1
  rows, the same code as the exact decision) is a rational function, polynomial or not;
  they are the row's conditions where the eigenvalues keep the signs and the order they
  have at the reference point (which decides which eigenvalue gives ``alpha``, ``a``, ...);
* otherwise some eigenvalue is an algebraic function (a root of an irreducible quadratic or
  cubic factor over Q(parameters)) and the conditions are algebraic, not rational.

The Table 2 formulas are run on sympy expressions through the number namespace of
:mod:`quadric_contact.theory.smallness` (``table_2_parameters``, ``ellipsoid_axes_squared``).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import flint
import sympy as sp

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.families.rational_functions import (
    FamilyCondition,
    FamilySmallness,
    RationalFunction,
    _sympy_rational,
)
from quadric_contact.model.classification import (
    TABLE_1_KINDS,
    QuadricKind,
    principal_minor_sums_3,
    principal_minor_sums_4,
)
from quadric_contact.theory.smallness import ellipsoid_axes_squared, row_sides, table_2_parameters
from quadric_contact.theory.smallness import smallness as smallness_exact

if TYPE_CHECKING:
    from quadric_contact.families.family import Family

__all__ = ["family_smallness"]


@dataclass(frozen=True)
class _Invariants:
    """The invariants of Section 2.4 as rational functions of the parameters."""

    trace: Any
    J: Any
    det00: Any
    det: Any
    K: Any
    J_prime: Any

    @staticmethod
    def of(entries: list[RationalFunction]) -> _Invariants:
        a = [entries[t] for t, (i, j) in enumerate(ENTRY_INDICES) if i < 3 and j < 3]
        tr, J, det00 = principal_minor_sums_3(a)
        _, e2, e3, e4 = principal_minor_sums_4(entries)
        return _Invariants(tr, J, det00, e4, e3 - det00, e2 - J)

    def constant(self, kind: QuadricKind | None = None) -> bool:
        """The invariants smallness reads do not depend on the parameters: the eigenvalues
        (through ``trace, J, det00``) and ``det``; ``K`` for the cylinders and ``J'`` for
        parallel planes, where Table 2 uses them (``kind``: the type of ``Q``; None for
        ``E``).  ``K`` and ``J'`` are not invariant under translations in general."""
        used = [self.trace, self.J, self.det00, self.det]
        if kind in _USES_K:
            used.append(self.K)
        if kind is QuadricKind.PARALLEL_PLANES:
            used.append(self.J_prime)
        return all(v.is_constant for v in used)


_USES_K = (QuadricKind.ELLIPTIC_CYLINDER, QuadricKind.HYPERBOLIC_CYLINDER, QuadricKind.PARABOLIC_CYLINDER)


class _Eigenvalue:
    """An eigenvalue that is a rational function of the parameters (a sympy expression),
    with its value at the reference point (for the sign and the order used)."""

    def __init__(self, expr: sp.Expr, value: Fraction) -> None:
        self.expr = expr
        self.value = value

    def sign(self) -> int:
        return (self.value > 0) - (self.value < 0)


@dataclass
class _SymbolicInvariants:
    eigenvalues: tuple[_Eigenvalue, ...]
    det: sp.Expr
    det00: sp.Expr
    J: sp.Expr
    K: sp.Expr
    J_prime: sp.Expr


class _SymbolicNumbers:
    """The number namespace of :mod:`quadric_contact.theory.smallness` for sympy expressions:
    comparisons are made at the reference point and recorded as assumptions."""

    def __init__(self, reference: dict[sp.Symbol, sp.Rational]) -> None:
        self.reference = reference
        self.assumptions: list[Any] = []

    def of(self, value: Any) -> sp.Expr:
        if isinstance(value, _Eigenvalue):
            return value.expr
        if isinstance(value, Fraction):
            return sp.Rational(value.numerator, value.denominator)
        return value

    def rational(self, value: _Eigenvalue) -> sp.Expr:
        return value.expr

    def sqrt(self, value: sp.Expr) -> sp.Expr:
        return sp.sqrt(value)

    def sorted_desc(self, values: list[sp.Expr]) -> list[sp.Expr]:
        keyed = sorted(values, key=lambda v: sp.N(v.subs(self.reference), 50), reverse=True)
        for a, b in itertools.pairwise(keyed):
            self.assumptions.append(sp.cancel(a - b) >= 0)
        return keyed


def _rational_eigenvalues(inv: _Invariants, fam: Family) -> tuple[list[RationalFunction] | None, Any]:
    """The eigenvalues of the quadratic part as rational functions (with multiplicity), or
    None and the first irreducible factor of degree >= 2 in ``t`` of its characteristic
    polynomial over Q(parameters)."""
    coeffs = [RationalFunction(fam.ctx.constant(1)), -inv.trace, inv.J, -inv.det00]  # t^3, t^2, t, 1
    d = fam.ctx.constant(1)
    for c in coeffs:
        if not c.den.is_one():
            d = d * (c.den / d.gcd(c.den))
    ctx2 = flint.fmpq_mpoly_ctx.get(("t_", *fam.parameters), "lex")
    terms: dict[tuple[int, ...], Any] = {}
    for k, c in enumerate(coeffs):
        num = c.num * (d / c.den)
        for mono, v in num.to_dict().items():
            terms[(3 - k, *(int(e) for e in mono))] = v
    _, factors = ctx2.from_dict(terms).factor()
    roots: list[RationalFunction] = []
    for f, mult in factors:
        by_t: dict[int, dict[tuple[int, ...], Any]] = {}
        for mono, v in f.to_dict().items():
            by_t.setdefault(int(mono[0]), {})[tuple(int(e) for e in mono[1:])] = v
        degree = max(by_t)
        if degree == 0:
            continue
        if degree > 1:
            return None, f
        a = fam.ctx.from_dict(by_t[1])
        b = fam.ctx.from_dict(by_t[0]) if 0 in by_t else fam.ctx.constant(0)
        roots += [RationalFunction(-b, a)] * int(mult)
    assert len(roots) == 3
    return roots, None


def family_smallness(fam: Family) -> FamilySmallness:
    """Tables 1-2 (corrected) over ``fam``; see :class:`quadric_contact.families.family.FamilySmallness`."""
    E0, Q0 = fam.E_reference, fam.Q_reference
    kind = Q0.kind
    if kind not in TABLE_1_KINDS:
        return FamilySmallness(
            "excluded", kind, None, (), (), (), f"Q is {kind.value} at the reference point: no row of Table 1"
        )
    report = smallness_exact(E0, Q0)
    q_entries = fam._q if Q0.canonical_sign > 0 else [-v for v in fam._q]
    inv_e, inv_q = _Invariants.of(fam._e), _Invariants.of(q_entries)
    if inv_e.constant() and inv_q.constant(kind):
        verdict = "small" if report.small else "not small"
        return FamilySmallness(
            "constant",
            kind,
            report,
            (),
            (),
            (),
            "the invariants of Section 2.4 (eigenvalues, det, K, J') do not depend on the parameters: "
            f"E is {verdict} with respect to Q ({kind.value}) wherever Q keeps its type (Theorem 5)",
        )
    symbols = fam.symbols
    ref = [fam.reference[p] for p in fam.parameters]
    reference = {s: sp.Rational(v.numerator, v.denominator) for s, v in zip(symbols, ref, strict=True)}
    numbers = _SymbolicNumbers(reference)
    sides = []
    for name, inv in (("E", inv_e), ("Q", inv_q)):
        roots, factor = _rational_eigenvalues(inv, fam)
        if roots is None:
            expr = sp.expand(
                sum(
                    sp.Rational(int(c.p), int(c.q))
                    * sp.Mul(*[s**e for s, e in zip((sp.Symbol("t"), *symbols), m, strict=True)])
                    for m, c in factor.to_dict().items()
                )
            )
            return FamilySmallness(
                "algebraic",
                kind,
                report,
                (),
                (),
                (),
                f"the eigenvalues of {name}'s quadratic part are roots of {expr} = 0 (irreducible over "
                "Q(parameters)): the conditions of Tables 1-2 are algebraic functions of the parameters, "
                "not rational ones; decide them point by point (smallness() at a point, or the maps)",
            )
        eigs = sorted(
            (_Eigenvalue(r.to_sympy(symbols), r.evaluate(ref)) for r in roots), key=lambda m: m.value
        )
        for m in eigs:
            rel = {1: m.expr > 0, -1: m.expr < 0, 0: sp.Eq(m.expr, 0)}[m.sign()]
            if rel is not sp.true:
                numbers.assumptions.append(rel)
        for a, b in itertools.pairwise(eigs):
            rel = sp.cancel(b.expr - a.expr) >= 0
            if rel is not sp.true:
                numbers.assumptions.append(rel)
        sides.append(
            _SymbolicInvariants(
                tuple(eigs),
                inv.det.to_sympy(symbols),
                inv.det00.to_sympy(symbols),
                inv.J.to_sympy(symbols),
                inv.K.to_sympy(symbols),
                inv.J_prime.to_sympy(symbols),
            )
        )
    e = ellipsoid_axes_squared(sides[0], numbers)  # type: ignore[arg-type]
    p = table_2_parameters(kind, sides[1], numbers)
    conds, alt = row_sides(kind, p, e)

    def condition(side: tuple[Any, ...]) -> FamilyCondition:
        relation, lhs, l2, rhs, r2, _, source, erratum = side
        l2, r2 = sp.cancel(l2), sp.cancel(r2)
        value = _sympy_rational(sp.cancel(l2 - r2), list(symbols), fam.ctx, f"{lhs} {relation} {rhs}")
        return FamilyCondition(f"{lhs} {relation} {rhs}", relation, value, l2, r2, source, erratum, symbols)

    try:
        c_conds = tuple(condition(c) for c in conds)
        c_alt = tuple(condition(c) for c in alt)
    except Exception as exc:  # a square root left: not rational (should not happen for Table 1's rows)
        return FamilySmallness("algebraic", kind, report, (), (), (), f"a condition is not rational: {exc}")
    status = "polynomial" if all(c.is_polynomial for c in (*c_conds, *c_alt)) else "rational"
    not_poly = [c.name for c in (*c_conds, *c_alt) if not c.is_polynomial]
    explanation = (
        "the eigenvalues of both quadratic parts are rational functions of the parameters; lhs^2 - rhs^2 "
        "of every condition is "
        + (
            "a polynomial"
            if status == "polynomial"
            else f"a rational function (not a polynomial: {', '.join(not_poly)})"
        )
        + f"; Q is {kind.value} at the reference point"
    )
    assumptions = tuple(dict.fromkeys(a for a in numbers.assumptions if a is not sp.true))
    return FamilySmallness(status, kind, report, c_conds, c_alt, assumptions, explanation)
