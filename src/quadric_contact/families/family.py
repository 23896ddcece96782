"""Parametric families: the pencil of ``E(p)`` and ``Q(p)`` exactly over Q(parameters).

A *family* is a pair of quadrics whose matrix entries are polynomials, or quotients of
polynomials, with rational coefficients in a few declared parameters: the bee's centre
``(u, w)``, a semi-axis ``s``, a position along a path.  :func:`family` reads the pair
(equations through the package's own parser, or sympy objects and matrices built by the
caller) and gives, exactly as elements of Q(parameters):

* the coefficients ``c0 .. c4`` of ``P(lambda) = det(lambda E + Q)`` (eq. (1));
* the discrimination system ``Delta_2, Delta_3, Delta_4`` of Section 3.2, with the
  corrected ``Delta_4`` (erratum ``delta4-term``), and Corollary 10's criterion on them;
* the coefficient-sign conditions of Table 4 (Theorem 13), derived from Descartes' rule;
* Corollary 15's condition where ``Q`` is a plane (erratum ``corollary-15-c1``);
* the smallness conditions of Tables 1-2 (corrected) where they are rational functions of
  the parameters, and what they are where they are not (:class:`FamilySmallness`);
* the curves where the answers can change (:attr:`Family.boundaries`).

Exactness and speed
-------------------
The arithmetic is python-flint's multivariate polynomials over Q (``fmpq_mpoly``): the
entries are brought to ``E = E_int / d_E`` and ``Q = Q_int / d_Q`` with polynomial
``E_int, Q_int, d_E, d_Q``, the generated closed form of :mod:`quadric_contact.codegen`
runs on them, and ``c_k = C_k / (d_E^k d_Q^(4-k))`` as in :mod:`quadric_contact.theory.pencil`;
each ``Delta_j`` is homogeneous and isobaric in ``c0 .. c4`` (degree ``d_j``, weight
``w_j``, read off the derived formula), so ``Delta_j = Delta_j(C) / (d_E^w_j
d_Q^(4 d_j - w_j))``.  Sympy expressions are made only for display.
``benchmarks/bench_family.py`` measures this against sympy.

Numbers for many parameter values come from :meth:`Family.lambdify`
(:mod:`quadric_contact.families.family_numeric`), pictures over two parameters from
:meth:`Family.contact_map` (:mod:`quadric_contact.families.family_maps`).

Module structure: the values every families module shares (:class:`RationalFunction`,
:class:`FamilyCondition`, :class:`FamilySmallness`) live in
:mod:`quadric_contact.families.rational_functions` and are re-exported here.  The modules that
compute with a family (:mod:`~quadric_contact.families.family_smallness`,
:mod:`~quadric_contact.families.family_numeric`, :mod:`~quadric_contact.families.family_maps`) import
those values, never this module (a :class:`Family` reaches them as an argument), and
this module imports them at module level for the conveniences
:attr:`Family.smallness`, :meth:`Family.lambdify` and :meth:`Family.contact_map`,
which are thin calls of their functions.

Sign conventions
----------------
``E`` is normalised once, at the family's *reference point* (the first of a fixed list of
small rational points where ``E`` is a real ellipsoid, or the ``at=`` given), to
``det E < 0`` as the paper assumes (``Family.e_flipped`` says when it was negated); the
type of ``Q``, its canonical sign and the order of the eigenvalues used by the smallness
formulas are those at the reference point, and the statements that depend on them say so.
A real ellipsoid cannot turn into one with the other sign without degenerating, so the
normalisation holds wherever ``E`` is a real ellipsoid connected to the reference point.
"""

from __future__ import annotations

import functools
import inspect
import itertools
import keyword
import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any

import flint
import sympy as sp

from quadric_contact._generated.formulas import paper_deltas, pencil_coefficients
from quadric_contact.exact.bounds import MAX_PARAMETERS, MAX_REFERENCE_POINTS
from quadric_contact.exact.descartes import sign_variations
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.errors import (
    ChoiceError,
    EquationError,
    NotAnEllipsoidError,
    NotSymmetricError,
    ShapeError,
)
from quadric_contact.exact.rational import to_fraction
from quadric_contact.exact.reading import MAX_DEGREE, MAX_DIGITS, Refusal, evaluate, parse_expression
from quadric_contact.families.family_budget import CountedPolynomial, PolynomialBudget
from quadric_contact.families.family_maps import contact_map
from quadric_contact.families.family_numeric import lambdify
from quadric_contact.families.family_smallness import family_smallness
from quadric_contact.families.rational_functions import (
    FamilyCondition,
    FamilySmallness,
    RationalFunction,
    _exact_fmpq,
    _poly_from_sympy,
    _poly_to_sympy,
    _sympy_rational,
)
from quadric_contact.model.classification import QuadricKind, principal_minor_sums_3
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.regions import region_patterns
from quadric_contact.theory.results import Region

__all__ = [
    "MAX_PARAMETERS",
    "Boundary",
    "Family",
    "FamilyCondition",
    "FamilySmallness",
    "Quantity",
    "RationalFunction",
    "SignRule",
    "family",
]


MAX_FAMILY_WORK = 20_000
"""Most term products the reader of a family's equations spends on one text (the
parameters multiply the terms: the bound of :data:`~quadric_contact.exact.reading.MAX_WORK`
for plain equations is lower)."""

_XYZ = ("x", "y", "z")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_LIMIT_BITS = int(MAX_DIGITS * 3.3219280948873626) + 1


def _height_bits(c: Any) -> int:
    return max(abs(int(c.p)).bit_length(), int(c.q).bit_length())


# -- reading a family ------------------------------------------------------------------------


class _FamilyAlgebra:
    """Polynomials in ``x, y, z`` whose coefficients are rational functions of the
    parameters, for :func:`~quadric_contact.exact.reading.evaluate`: an element is ``(num, den)``
    with ``num`` in ``Q[x, y, z, params]`` and ``den`` in ``Q[params]`` (same context).
    Division is by expressions in the parameters only; degrees, digits and work are
    bounded (:data:`~quadric_contact.exact.reading.MAX_DEGREE` in ``x, y, z`` and in the
    parameters, :data:`~quadric_contact.exact.reading.MAX_DIGITS`, :data:`MAX_FAMILY_WORK`)."""

    def __init__(self, parameters: Sequence[str]) -> None:
        self.ctx = flint.fmpq_mpoly_ctx.get((*_XYZ, *parameters), "lex")
        self.gens = dict(zip((*_XYZ, *parameters), self.ctx.gens(), strict=True))
        self.one = self.ctx.constant(1)
        self.work = 0

    # -- bookkeeping
    @staticmethod
    def degrees(p: Any) -> tuple[int, int]:
        """(total degree in x, y, z; total degree in the parameters)."""
        dx = dp = 0
        for mono in p.monoms():
            dx = max(dx, mono[0] + mono[1] + mono[2])
            dp = max(dp, sum(mono[3:]))
        return dx, dp

    def _check(self, *polys: Any) -> None:
        for p in polys:
            dx, dp = self.degrees(p)
            if dx > MAX_DEGREE or dp > MAX_DEGREE:
                raise Refusal(
                    f"a polynomial of degree {max(dx, dp)} {{where}}: more than the {MAX_DEGREE} allowed "
                    "(MAX_DEGREE, in x, y, z and in the parameters)"
                )
            for c in p.coeffs():
                if _height_bits(c) > _LIMIT_BITS:
                    raise Refusal(
                        f"a number with more than {MAX_DIGITS} digits (MAX_DIGITS) arises {{where}}"
                    )

    def _charge(self, steps: int) -> None:
        self.work += max(1, steps)
        if self.work > MAX_FAMILY_WORK:
            raise Refusal(
                f"more than {MAX_FAMILY_WORK} arithmetic steps (MAX_FAMILY_WORK) {{where}}: "
                "the input is too costly to expand"
            )

    def _reduce(self, num: Any, den: Any) -> tuple[Any, Any]:
        if den.is_constant():
            return num / den.leading_coefficient(), self.one
        self._charge(len(num) + len(den))
        g = num.gcd(den)
        if not g.is_one():
            num, den = num / g, den / g
        lc = den.leading_coefficient()
        return num / lc, den / lc

    # -- the operations
    def constant(self, value: Fraction) -> tuple[Any, Any]:
        return self.ctx.constant(flint.fmpq(value.numerator, value.denominator)), self.one

    def variable(self, name: str) -> tuple[Any, Any]:
        return self.gens[name], self.one

    def add(self, a: tuple[Any, Any], b: tuple[Any, Any]) -> tuple[Any, Any]:
        (na, da), (nb, db) = a, b
        if da == db:
            self._charge(min(len(na), len(nb)))
            out = self._reduce(na + nb, da)
        else:
            self._charge(len(na) * len(db) + len(nb) * len(da) + len(da) * len(db))
            out = self._reduce(na * db + nb * da, da * db)
        self._check(*out)
        return out

    def neg(self, a: tuple[Any, Any]) -> tuple[Any, Any]:
        return -a[0], a[1]

    def sub(self, a: tuple[Any, Any], b: tuple[Any, Any]) -> tuple[Any, Any]:
        return self.add(a, self.neg(b))

    def _product_degrees(self, *polys: Any) -> None:
        dx = sum(self.degrees(p)[0] for p in polys)
        dp = sum(self.degrees(p)[1] for p in polys)
        if dx > MAX_DEGREE or dp > MAX_DEGREE:
            raise Refusal(
                f"a product of degree {max(dx, dp)} {{where}}: more than the {MAX_DEGREE} allowed "
                "(MAX_DEGREE, in x, y, z and in the parameters)"
            )

    def mul(self, a: tuple[Any, Any], b: tuple[Any, Any]) -> tuple[Any, Any]:
        (na, da), (nb, db) = a, b
        self._product_degrees(na, nb)
        self._product_degrees(da, db)
        self._charge(len(na) * len(nb) + len(da) * len(db))
        out = self._reduce(na * nb, da * db)
        self._check(*out)
        return out

    def div(self, a: tuple[Any, Any], b: tuple[Any, Any]) -> tuple[Any, Any]:
        nb, db = b
        if self.degrees(nb)[0] > 0:
            raise Refusal("division by an expression in x, y, z {where}: the result is not a polynomial")
        if nb.is_zero():
            raise Refusal("division by zero {where}")
        return self.mul(a, (db, nb))

    def pow(self, a: tuple[Any, Any], n: int) -> tuple[Any, Any]:
        if n == 0:
            return self.one, self.one
        num, den = a
        dx, dp = self.degrees(num)
        dd = self.degrees(den)[1]
        if n * max(dx, dp, dd) > MAX_DEGREE:
            raise Refusal(
                f"a power of degree {n * max(dx, dp, dd)} {{where}}: more than the {MAX_DEGREE} allowed "
                "(MAX_DEGREE, in x, y, z and in the parameters)"
            )
        if num.is_constant() and den.is_one():
            c = num.leading_coefficient() if not num.is_zero() else flint.fmpq(0)
            if (_height_bits(c) - 1) * n >= _LIMIT_BITS:
                raise Refusal(f"a power with more than {MAX_DIGITS} digits (MAX_DIGITS) {{where}}")
            return self.ctx.constant(c**n), self.one
        out = (self.one, self.one)
        for _ in range(n):
            out = self.mul(out, a)
        return out


def _parameter_names(parameters: Any) -> tuple[str, ...]:
    if isinstance(parameters, str):
        names = [n for n in re.split(r"[\s,]+", parameters.strip()) if n]
    elif isinstance(parameters, sp.Symbol):
        names = [parameters.name]
    elif isinstance(parameters, Iterable):
        names = []
        for p in parameters:
            if isinstance(p, sp.Symbol):
                names.append(p.name)
            elif isinstance(p, str):
                names.append(p)
            else:
                raise EquationError(f"a parameter is a name or a sympy Symbol, got {p!r}", parameters)
    else:
        raise EquationError(
            f"parameters: expected names ('u w'), a list of names or sympy Symbols, got {parameters!r}",
            parameters,
        )
    if len(names) > MAX_PARAMETERS:  # before anything is done per name
        raise EquationError(
            f"at most {MAX_PARAMETERS} parameters (MAX_PARAMETERS), got {len(names)}", parameters
        )
    for n in names:
        if not _NAME.fullmatch(n):
            raise EquationError(f"parameters: {n!r} is not a name (letters, digits and _)", parameters)
        if n in _XYZ:
            raise EquationError(f"parameters: {n!r} is a coordinate, not a parameter", parameters)
        why = _reserved_names().get(n)
        if why is not None:
            raise EquationError(f"parameters: {n!r} is {why}; choose another name", parameters)
    if len(set(names)) != len(names):
        raise EquationError(f"parameters: a name is repeated in {names}", parameters)
    return tuple(names)


@functools.cache
def _reserved_names() -> dict[str, str]:
    """Names a parameter may not take, and why: a parameter named ``lambda`` would
    merge with the pencil's variable (``P`` would come out of degree 5), one named
    ``t`` with the time of the smallness conditions, a keyword or a keyword
    argument of the family's methods (``fam.at(name=...)``, ``contact_map(refine=...)``)
    could not be passed by name, and an attribute would be shadowed."""
    out: dict[str, str] = {}
    for n in (*keyword.kwlist, *keyword.softkwlist):
        out[n] = "a Python keyword"
    instance = ("parameters", "symbols", "ctx", "reference", "e_flipped", "E_reference", "Q_reference")
    for n in (*dir(Family), *instance):
        if not n.startswith("_"):
            out.setdefault(n, "an attribute of a family")
    for fn in (*(getattr(Family, n) for n in dir(Family) if not n.startswith("_")), contact_map, lambdify):
        if callable(fn):
            for arg in inspect.signature(fn).parameters:
                out.setdefault(arg, "a keyword argument of a family's methods")
    out["lambda"] = "the variable of the characteristic polynomial (lambda)"
    out["t"] = "the variable of the smallness conditions (t)"
    return out


def _drop_xyz(p: Any, pctx: Any) -> Any:
    """A polynomial of the reader's context that does not involve x, y, z, in the parameters' context."""
    d = {tuple(int(e) for e in mono[3:]): c for mono, c in p.to_dict().items()}
    return pctx.from_dict(d) if d else pctx.constant(0)


def _entries_from_polynomial(num: Any, den: Any, pctx: Any, name: str) -> list[RationalFunction]:
    """The ten upper matrix entries of ``num / den`` (``num`` in x, y, z and the parameters)."""
    groups: dict[tuple[int, ...], dict[tuple[int, ...], Any]] = {}
    for mono, c in num.to_dict().items():
        xyz = tuple(int(e) for e in mono[:3])
        if sum(xyz) > 2:
            raise EquationError(
                f"{name}: degree {sum(xyz)} in x, y, z after expansion; a quadric has degree <= 2"
            )
        groups.setdefault(xyz, {})[tuple(int(e) for e in mono[3:])] = c
    d = _drop_xyz(den, pctx)
    out = []
    for i, j in ENTRY_INDICES:
        e = [0, 0, 0]
        for k in (i, j):
            if k < 3:
                e[k] += 1
        terms = groups.get((e[0], e[1], e[2]), {})
        factor = flint.fmpq(1) if i == j else flint.fmpq(1, 2)
        p = pctx.from_dict(terms) if terms else pctx.constant(0)
        out.append(RationalFunction(p * factor, d))
    return out


def _read_text(text: str, parameters: tuple[str, ...], pctx: Any, name: str) -> list[RationalFunction]:
    tree = parse_expression(text, _XYZ, parameters, equation=True, what=name)
    alg = _FamilyAlgebra(parameters)
    num, den = evaluate(tree, alg, text=text, what=name)
    return _entries_from_polynomial(num, den, pctx, name)


def _read_sympy_equation(
    expr: Any, parameters: tuple[str, ...], pctx: Any, name: str
) -> list[RationalFunction]:
    if isinstance(expr, sp.Equality):
        expr = expr.lhs - expr.rhs
    xyz = sp.symbols("x y z")
    psyms = [sp.Symbol(p) for p in parameters]
    if not isinstance(expr, sp.Expr):
        raise EquationError(f"{name}: {expr!r} is not an algebraic expression", expr)
    others = expr.free_symbols - set(xyz) - set(psyms)
    if others:
        raise EquationError(
            f"{name}: {expr} has symbols other than x, y, z and the parameters: {sorted(map(str, others))}",
            expr,
        )
    num, den = sp.fraction(sp.cancel(sp.together(expr)))
    if den.free_symbols & set(xyz):
        raise EquationError(f"{name}: {expr} divides by an expression in x, y, z", expr)
    alg = _FamilyAlgebra(parameters)
    parts = []
    for part, gens in ((num, [*xyz, *psyms]), (den, [*xyz, *psyms])):
        try:
            poly = sp.Poly(part, *gens, domain=sp.QQ)
        except (sp.PolynomialError, sp.CoercionFailed) as exc:
            raise EquationError(
                f"{name}: {expr} is not a quotient of polynomials over Q: {exc}", expr
            ) from exc
        parts.append(_poly_from_sympy(poly, alg.ctx))
    return _entries_from_polynomial(parts[0], parts[1], pctx, name)


def _read_entry(value: Any, parameters: tuple[str, ...], pctx: Any, what: str) -> RationalFunction:
    if isinstance(value, RationalFunction):
        return value
    if isinstance(value, str):
        tree = parse_expression(value, (), parameters, what=what)
        num, den = evaluate(tree, _FamilyAlgebra(parameters), text=value, what=what)
        return RationalFunction(_drop_xyz(num, pctx), _drop_xyz(den, pctx))
    if isinstance(value, sp.Basic):
        return _sympy_rational(value, [sp.Symbol(p) for p in parameters], pctx, what)
    f = to_fraction(value)
    return RationalFunction(pctx.constant(flint.fmpq(f.numerator, f.denominator)))


def _read_matrix(value: Any, parameters: tuple[str, ...], pctx: Any, name: str) -> list[RationalFunction]:
    rows = value.tolist() if hasattr(value, "tolist") else value
    if isinstance(value, sp.MatrixBase):
        rows = [[value[i, j] for j in range(value.cols)] for i in range(value.rows)]
    try:
        shape_ok = len(rows) == 4 and all(len(r) == 4 for r in rows)
    except TypeError:
        shape_ok = False
    if not shape_ok:
        raise ShapeError(f"{name} must be a 4x4 matrix, an equation or a Quadric", value)
    m = [[_read_entry(rows[i][j], parameters, pctx, f"{name}[{i}, {j}]") for j in range(4)] for i in range(4)]
    for i in range(4):
        for j in range(i + 1, 4):
            if m[i][j] != m[j][i]:
                raise NotSymmetricError(
                    f"{name} is not symmetric: entry ({i}, {j}) is {m[i][j]}, entry ({j}, {i}) is {m[j][i]}",
                    value,
                    entry=(i, j),
                )
    return [m[i][j] for i, j in ENTRY_INDICES]


def _read(value: Any, parameters: tuple[str, ...], pctx: Any, name: str) -> list[RationalFunction]:
    """The ten upper entries of ``E`` or ``Q`` as rational functions of the parameters."""
    if isinstance(value, Quadric):
        return [_read_entry(v, parameters, pctx, name) for v in value.upper]
    if isinstance(value, str):
        return _read_text(value, parameters, pctx, name)
    if isinstance(value, sp.Basic) and not isinstance(value, sp.MatrixBase):
        return _read_sympy_equation(value, parameters, pctx, name)
    return _read_matrix(value, parameters, pctx, name)


# -- what a family says -------------------------------------------------------------------------


@dataclass(frozen=True)
class Quantity:
    """One exact quantity of a family: an element of Q(parameters).

    Attributes
    ----------
    name : str
        ``"c0" .. "c4"``, ``"Delta2"``, ``"Delta3"``, ``"Delta4"``, ``"plane discriminant"``,
        ``"E minor 1" .. "E minor 3"``, or the name of a smallness condition.
    value : RationalFunction
    description : str
    """

    name: str
    value: RationalFunction
    description: str
    symbols: tuple[sp.Symbol, ...] = field(repr=False)

    @property
    def is_polynomial(self) -> bool:
        return self.value.is_polynomial

    @property
    def numerator(self) -> Any:
        """The numerator (``fmpq_mpoly``); its sign times the denominator's is the quantity's."""
        return self.value.num

    @property
    def denominator(self) -> Any:
        return self.value.den

    @cached_property
    def expr(self) -> sp.Expr:
        """The exact sympy expression."""
        return self.value.to_sympy(self.symbols)

    def __str__(self) -> str:
        return f"{self.name} = {self.expr}"


@dataclass(frozen=True)
class SignRule:
    """Table 4 for one region, as conditions on the signs of ``c0 .. c4`` (Theorem 13).

    Derived, not copied: the sign vectors ``(s0, .., s4)`` with ``s4 = -1`` (``det E < 0``)
    for which Descartes' rule gives this root-sign pattern exactly (leading zeros = zero
    roots, sign changes of ``P(lambda)`` = positive roots, of ``P(-lambda)`` = negative
    roots, four in all; every such vector is realised by a real-rooted quartic, see
    ``proofs/theorem_13_table_4.py``).  The rule says where ``E`` is *when all roots of
    ``P`` are real and ``E`` is small* (Table 4 does not apply otherwise).

    Attributes
    ----------
    region : Region
    pattern : str
        The root signs, e.g. ``'-+++'``.
    vectors : tuple of tuple of int
        The admissible sign vectors of ``(c0, .., c4)``.
    """

    region: Region
    pattern: str
    vectors: tuple[tuple[int, ...], ...]

    @staticmethod
    def derive(region: Region, pattern: str) -> SignRule:
        neg, zero, pos = pattern.count("-"), pattern.count("0"), pattern.count("+")
        vectors = []
        for s in itertools.product((-1, 0, 1), repeat=4):
            v = (*s, -1)
            lead = next(i for i, x in enumerate(v) if x)
            if lead != zero:
                continue
            alt = [x * (-1) ** k for k, x in enumerate(v)]
            if sign_variations(v) == pos and sign_variations(alt) == neg:
                vectors.append(v)
        return SignRule(region, pattern, tuple(vectors))

    @property
    def changes(self) -> int:
        """Sign changes of ``(c0, .., c4)``: the number of positive roots."""
        return self.pattern.count("+")

    def fixed_signs(self) -> dict[int, int]:
        """The coefficients whose sign is the same in every admissible vector."""
        return {k: self.vectors[0][k] for k in range(5) if len({v[k] for v in self.vectors}) == 1}

    def describe(self) -> str:
        """The rule in Table 4's words: the fixed signs and the number of sign changes."""
        rel = {-1: "< 0", 0: "= 0", 1: "> 0"}
        fixed = ", ".join(f"c{k} {rel[s]}" for k, s in sorted(self.fixed_signs().items(), reverse=True))
        n = self.changes
        changes = "no sign changes" if n == 0 else f"{n} sign change{'s' if n > 1 else ''}"
        return f"{self.region.value} (roots {self.pattern}): {fixed}; {changes} of (c0, .., c4)"

    def holds(self, signs: Sequence[int]) -> bool:
        """True when the signs of ``(c0, .., c4)`` are one of the admissible vectors."""
        return tuple(int(s) for s in signs) in self.vectors

    def condition(self, coefficients: Sequence[sp.Expr]) -> Any:
        """The rule as a sympy Boolean in the given expressions for ``c0 .. c4``."""
        rel = {-1: lambda e: e < 0, 0: lambda e: sp.Eq(e, 0), 1: lambda e: e > 0}
        return sp.Or(
            *[sp.And(*[rel[s](c) for s, c in zip(v, coefficients, strict=True)]) for v in self.vectors]
        )

    def __str__(self) -> str:
        return self.describe()


@dataclass(frozen=True)
class Boundary:
    """A curve (a hypersurface) of parameter space where an answer can change.

    Attributes
    ----------
    name : str
        ``"Delta4"`` (or the first of ``Delta3``, ``Delta2`` that is not identically zero),
        ``"plane discriminant"``, ``"c0"``, ``"c4"``, ``"pole"``, or a smallness condition.
    factors : tuple
        The distinct irreducible factors (``fmpq_mpoly``) of the numerator: the curve is
        where one of them vanishes.
    why : str
    """

    name: str
    factors: tuple[Any, ...]
    why: str
    symbols: tuple[sp.Symbol, ...] = field(repr=False)

    @cached_property
    def exprs(self) -> tuple[sp.Expr, ...]:
        return tuple(_poly_to_sympy(f, self.symbols) for f in self.factors)

    def __str__(self) -> str:
        return f"{self.name} = 0: " + " * ".join(f"({e})" for e in self.exprs) + f"  ({self.why})"


def _isobaric_weights() -> tuple[tuple[int, int], ...]:
    """``(degree, weight)`` of ``Delta_2, Delta_3, Delta_4`` in ``c0 .. c4`` (``c_k`` of
    weight ``k``), read off the generated formula; each is homogeneous and isobaric."""
    cs = sp.symbols("c0:5")
    out = []
    for delta in paper_deltas(*cs):
        poly = sp.Poly(sp.expand(delta), *cs)
        degrees = {sum(m) for m in poly.monoms()}
        weights = {sum(k * e for k, e in enumerate(m)) for m in poly.monoms()}
        assert len(degrees) == 1 and len(weights) == 1, "a Delta that is not homogeneous and isobaric"
        out.append((degrees.pop(), weights.pop()))
    return tuple(out)


_DELTA_WEIGHTS = _isobaric_weights()


def _candidate_points(n: int) -> Iterable[tuple[Fraction, ...]]:
    """A fixed list of small rational points (all parameters 0, 1, 1/2, 2, -1, ...)."""
    values = [Fraction(v) for v in ("0", "1", "1/2", "2", "-1", "1/3", "3", "-1/2", "5/7", "-2")]
    if n == 0:
        yield ()
        return
    for k in range(1, len(values) + 1):
        for point in itertools.product(values[:k], repeat=n):
            if max(values.index(v) for v in point) == k - 1:
                yield point


class Family:
    """A parametric pair ``E(p)``, ``Q(p)``; build it with :func:`family`.

    Attributes
    ----------
    parameters : tuple of str
    symbols : tuple of sympy.Symbol
    reference : dict
        The reference point (parameter name to Fraction).
    e_flipped : bool
        The caller's ``E`` was negated so that ``det E < 0`` at the reference point.
    """

    def __init__(
        self,
        parameters: tuple[str, ...],
        e_entries: Sequence[RationalFunction],
        q_entries: Sequence[RationalFunction],
        *,
        at: Mapping[str, Any] | None = None,
    ) -> None:
        self.parameters = parameters
        self.symbols = tuple(sp.Symbol(p) for p in parameters)
        self.ctx = flint.fmpq_mpoly_ctx.get(parameters, "lex")
        self._e = list(e_entries)
        self._q = list(q_entries)
        self.reference = self._find_reference(at)
        ref = [self.reference[p] for p in parameters]
        E0 = Quadric.from_matrix(_matrix(self._e, ref))
        #: Whether ``E`` was negated so that ``det E < 0``, as the paper assumes.
        self.e_flipped = E0.as_ellipsoid() is not E0
        if self.e_flipped:
            self._e = [-v for v in self._e]
        self.Q_reference = Quadric.from_matrix(_matrix(self._q, ref))
        self.E_reference = Quadric.from_matrix(_matrix(self._e, ref))

    # -- construction helpers
    def _find_reference(self, at: Mapping[str, Any] | None) -> dict[str, Fraction]:
        if at is not None:
            unknown = set(at) - set(self.parameters)
            if unknown or set(at) != set(self.parameters):
                raise EquationError(
                    f"at= must give every parameter {self.parameters}, got {sorted(at)}", dict(at)
                )
            point = tuple(to_fraction(at[p]) for p in self.parameters)
            reason = self._not_an_ellipsoid(point)
            if reason:
                raise NotAnEllipsoidError(
                    f"at {dict(zip(self.parameters, point, strict=True))}: {reason}", at
                )
            return dict(zip(self.parameters, point, strict=True))
        # The first point where E is an ellipsoid; among the first few such points, one where
        # the quadratic parts have as many distinct eigenvalues as anywhere (a tie fixes the
        # order of two eigenvalues that differ elsewhere: the smallness formulas then hold on
        # one side of it only).
        best: tuple[int, tuple[Fraction, ...]] | None = None
        found = 0
        for point in itertools.islice(_candidate_points(len(self.parameters)), MAX_REFERENCE_POINTS):
            if self._not_an_ellipsoid(point):
                continue
            found += 1
            score = sum(_distinct_eigenvalues(_matrix(m, point)) for m in (self._e, self._q))
            if best is None or score > best[0]:
                best = (score, point)
            if found >= 12:
                break
        if best is not None:
            return dict(zip(self.parameters, best[1], strict=True))
        raise NotAnEllipsoidError(
            f"E is not a real ellipsoid at any of the first {MAX_REFERENCE_POINTS} small rational points "
            "tried (MAX_REFERENCE_POINTS); pass at= a point where it is",
            None,
        )

    def _not_an_ellipsoid(self, point: Sequence[Fraction]) -> str:
        return _ellipsoid_problem(self._e, self._q, point)

    # -- the matrices
    @cached_property
    def E(self) -> sp.Matrix:
        """``E`` as an exact sympy matrix (normalised, see :attr:`e_flipped`)."""
        return _sympy_matrix(self._e, self.symbols)

    @cached_property
    def Q(self) -> sp.Matrix:
        """``Q`` as an exact sympy matrix."""
        return _sympy_matrix(self._q, self.symbols)

    def _point(self, values: Mapping[str, Any]) -> list[Fraction]:
        missing = [p for p in self.parameters if p not in values]
        unknown = [k for k in values if k not in self.parameters]
        if missing or unknown:
            raise EquationError(
                f"give a value for every parameter {self.parameters}"
                + (f"; missing {missing}" if missing else "")
                + (f"; unknown {unknown}" if unknown else ""),
                dict(values),
            )
        return [to_fraction(values[p]) for p in self.parameters]

    def at(self, **values: Any) -> tuple[Quadric, Quadric]:
        """The exact pair ``(E, Q)`` at a point (every parameter given a number)."""
        point = self._point(values)
        return Quadric.from_matrix(_matrix(self._e, point)), Quadric.from_matrix(_matrix(self._q, point))

    def fix(self, **values: Any) -> Family:
        """The family with some parameters set to numbers (exactly); the others remain."""
        unknown = [k for k in values if k not in self.parameters]
        if unknown:
            raise EquationError(f"unknown parameters {unknown}; the family has {self.parameters}", values)
        rest = tuple(p for p in self.parameters if p not in values)
        idx = {self.parameters.index(k): to_fraction(v) for k, v in values.items()}
        ctx = flint.fmpq_mpoly_ctx.get(rest, "lex")

        def move(r: RationalFunction) -> RationalFunction:
            s = r.substitute(idx)
            return RationalFunction(_to_context(s.num, ctx), _to_context(s.den, ctx))

        ref_rest = {p: self.reference[p] for p in rest}
        fam_e, fam_q = [move(v) for v in self._e], [move(v) for v in self._q]
        keep = not _ellipsoid_problem(fam_e, fam_q, [ref_rest[p] for p in rest])
        return Family(rest, fam_e, fam_q, at=ref_rest if keep else None)

    # -- the pencil
    @cached_property
    def _integer_forms(self) -> tuple[list[Any], Any, list[Any], Any]:
        def clear(entries: Sequence[RationalFunction]) -> tuple[list[Any], Any]:
            d = self.ctx.constant(1)
            for v in entries:
                if not v.den.is_one():
                    d = d * (v.den / d.gcd(v.den))
            return [v.num * (d / v.den) for v in entries], d

        e_int, d_e = clear(self._e)
        q_int, d_q = clear(self._q)
        return e_int, d_e, q_int, d_q

    def _budget(self, what: str) -> PolynomialBudget:
        return PolynomialBudget(f"{what} of the family in {', '.join(self.parameters)}")

    @cached_property
    def _counted_coefficients(self) -> tuple[list[CountedPolynomial], CountedPolynomial, CountedPolynomial]:
        """``c0 .. c4`` with the denominators cleared, and the two denominators, built
        over counted polynomials: refused before a product that could exceed the budget."""
        e_int, d_e, q_int, d_q = self._integer_forms
        budget = self._budget("the characteristic polynomial")
        C = pencil_coefficients(*(CountedPolynomial(v, budget) for v in (*e_int, *q_int)))
        return list(C), CountedPolynomial(d_e, budget), CountedPolynomial(d_q, budget)

    @cached_property
    def _coefficients(self) -> tuple[RationalFunction, ...]:
        C, d_e, d_q = self._counted_coefficients
        return tuple(RationalFunction(C[k].p, (d_e**k * d_q ** (4 - k)).p) for k in range(5))

    @cached_property
    def _deltas(self) -> tuple[RationalFunction, ...]:
        C0, d_e0, d_q0 = self._counted_coefficients
        budget = self._budget("the discriminants Delta2, Delta3, Delta4")
        C = [CountedPolynomial(c.p, budget) for c in C0]
        d_e, d_q = CountedPolynomial(d_e0.p, budget), CountedPolynomial(d_q0.p, budget)
        return tuple(
            RationalFunction(D.p, (d_e**w * d_q ** (4 * d - w)).p)
            for D, (d, w) in zip(paper_deltas(*C), _DELTA_WEIGHTS, strict=True)
        )

    @property
    def coefficients(self) -> tuple[sp.Expr, ...]:
        """``(c0, .., c4)`` of ``P(lambda) = det(lambda E + Q)`` (eq. (1)), exact sympy expressions."""
        return tuple(self.quantity(f"c{k}").expr for k in range(5))

    @property
    def deltas(self) -> tuple[sp.Expr, ...]:
        """``(Delta_2, Delta_3, Delta_4)`` (Section 3.2; ``Delta_4`` corrected)."""
        return tuple(self.quantity(f"Delta{j}").expr for j in (2, 3, 4))

    def characteristic_polynomial(self, symbol: str = "lambda") -> sp.Expr:
        """``P(lambda)`` as a sympy expression in ``symbol`` and the parameters.

        Raises
        ------
        EquationError
            If ``symbol`` is a parameter or a coordinate (it would merge with it)."""
        if not isinstance(symbol, str) or not _NAME.fullmatch(symbol):
            raise EquationError(f"symbol: expected a name (letters, digits and _), got {symbol!r}", symbol)
        if symbol in self.parameters or symbol in _XYZ:
            raise EquationError(
                f"symbol: {symbol!r} is a parameter or a coordinate of the family {self.parameters}; "
                "P would merge with it: choose another name",
                symbol,
            )
        lam = sp.Symbol(symbol)
        return sum((c * lam**k for k, c in enumerate(self.coefficients)), sp.Integer(0))

    @property
    def q_is_plane(self) -> bool:
        """``Q`` is a plane for every parameter value: its quadratic part is identically zero."""
        return all(self._q[t].is_zero() for t, (i, j) in enumerate(ENTRY_INDICES) if i < 3 and j < 3)

    @property
    def q_kind(self) -> QuadricKind:
        """The type of ``Q`` at the reference point."""
        return self.Q_reference.kind

    @cached_property
    def _pencil_quantities(self) -> dict[str, Quantity]:
        """The quantities of the pencil and of ``E`` (no smallness: it is computed on demand)."""
        out: dict[str, Quantity] = {}
        sym = self.symbols

        def add(name: str, value: RationalFunction, description: str) -> None:
            out[name] = Quantity(name, value, description, sym)

        for k, c in enumerate(self._coefficients):
            add(f"c{k}", c, f"coefficient of lambda^{k} in P(lambda) = det(lambda E + Q), eq. (1)")
        for j, d in zip((2, 3, 4), self._deltas, strict=True):
            extra = " (corrected fifth term, erratum delta4-term)" if j == 4 else ""
            add(f"Delta{j}", d, f"the paper's Delta_{j}, Section 3.2{extra}")
        a = [self._e[t] for t, (i, j) in enumerate(ENTRY_INDICES) if i < 3 and j < 3]
        a00, a01, a02, a11, a12, a22 = a
        add("E minor 1", a00, "leading principal minor of order 1 of E's quadratic part (Sylvester)")
        add("E minor 2", a00 * a11 - a01 * a01, "leading principal minor of order 2 of E's quadratic part")
        add("E minor 3", principal_minor_sums_3(a)[2], "determinant of E's quadratic part")
        if self.q_is_plane:
            c0, c1, c2, c3, c4 = self._coefficients
            add(
                "plane discriminant",
                c3 * c3 - 4 * c4 * c2,
                "c3^2 - 4 c4 c2: transversal contact with the plane iff < 0 "
                "(Corollary 15, erratum corollary-15-c1)",
            )
        return out

    @cached_property
    def quantities(self) -> dict[str, Quantity]:
        """Every named exact quantity: the coefficients, the Deltas, the leading minors of
        ``E``'s quadratic part, the plane discriminant (planes) and the squared smallness
        conditions (where they are rational)."""
        out = dict(self._pencil_quantities)
        for cond in (*self.smallness.conditions, *self.smallness.alternative):
            description = f"lhs^2 - rhs^2 of {cond.name} (Tables 1-2): holds iff {cond.relation} 0"
            out[cond.name] = Quantity(cond.name, cond.value, description, self.symbols)
        return out

    def quantity(self, name: str) -> Quantity:
        """The exact quantity ``name`` (see :attr:`quantities`)."""
        if name in self._pencil_quantities:
            return self._pencil_quantities[name]
        try:
            return self.quantities[name]
        except (KeyError, TypeError):
            choices = sorted(self.quantities)
            raise ChoiceError(
                f"no quantity {name!r}; the family has {', '.join(choices)}", name, choices=choices
            ) from None

    def evaluate(self, name: str, **values: Any) -> Fraction:
        """The exact value of a quantity at a point."""
        return self.quantity(name).value.evaluate(self._point(values))

    # -- the paper's conditions
    @cached_property
    def table_4(self) -> dict[Region, SignRule]:
        """Table 4 for the type and sign of ``Q`` at the reference point: per region, the signs
        of ``c0 .. c4`` that Theorem 13 reads (empty for a type without a row)."""
        patterns = region_patterns(self.q_kind, self.Q_reference.canonical_sign)
        return {r: SignRule.derive(r, p) for r, p in patterns.items()}

    def table_4_condition(self, region: Region) -> Any:
        """Table 4's rule for ``region`` as a sympy Boolean in the parameters (coefficient signs;
        it decides the region when all roots are real and ``E`` is small)."""
        return self.table_4[region].condition(self.coefficients)

    @property
    def criterion(self) -> Any:
        """Corollary 10 as a sympy Boolean in the parameters: ``P`` has non-real roots
        (transversal contact for any pair, Remark 9) iff ``Delta_4 < 0``, or
        ``Delta_4 = 0`` and ``Delta_3 < 0``."""
        _, d3, d4 = self.deltas
        return sp.Or(d4 < 0, sp.And(sp.Eq(d4, 0), d3 < 0))

    @property
    def corollary_15(self) -> dict[str, Any] | None:
        """Where ``Q`` is a plane (Corollary 15, corrected): ``{"contact": c3^2 < 4 c4 c2,
        "R+": c3 > 0, "R-": c3 < 0}`` (the last two where there is no contact) as sympy
        relations in the parameters; None when ``Q`` is not a plane for every parameter."""
        if not self.q_is_plane:
            return None
        disc = self.quantity("plane discriminant").expr
        c3 = self.coefficients[3]
        return {"contact": disc < 0, "R+": c3 > 0, "R-": c3 < 0}

    @cached_property
    def smallness(self) -> FamilySmallness:
        """Tables 1-2 (corrected) over the family (see :class:`FamilySmallness`)."""
        return family_smallness(self)

    @cached_property
    def boundaries(self) -> tuple[Boundary, ...]:
        """Where the answers of the predicates can change: the pencil gets a multiple root
        (every tangency gives one), ``Q`` degenerates (``c0 = det Q``), ``E`` degenerates
        (``c4 = det E``), an entry has a pole.  Only the non-constant ones.

        A tangency at a point ``X`` of both surfaces makes ``(lambda0 E + Q) X = 0`` for some
        ``lambda0``; then ``P'(lambda0) = tr(adj(lambda0 E + Q) E) = k X^T E X = 0`` (the
        adjugate is ``k X X^T`` at rank 3 and zero below), so ``lambda0`` is a multiple root
        and ``Delta_4 = 0``."""
        out: list[Boundary] = []
        sym = self.symbols

        def add(name: str, poly: Any, why: str) -> None:
            if poly.is_constant():
                return
            _, factors = poly.factor()
            fs = tuple(f for f, _ in factors if not f.is_constant())
            if fs:
                out.append(Boundary(name, fs, why, sym))

        if self.q_is_plane:
            add(
                "plane discriminant",
                self.quantity("plane discriminant").numerator,
                "c3^2 = 4 c4 c2: E touches the plane (Corollary 15)",
            )
        else:
            for name in ("Delta4", "Delta3", "Delta2"):
                q = self.quantity(name)
                if not q.value.is_zero():
                    why = "a multiple root of P (every tangency gives one)"
                    if name != "Delta4":
                        why += "; Delta4 vanishes identically, so the next minor of the discrimination system"
                    add(name, q.numerator, why)
                    break
        add("c0", self._coefficients[0].num, "det Q = 0: Q degenerates")
        add("c4", self._coefficients[4].num, "det E = 0: E degenerates")
        poles = self.ctx.constant(1)
        for v in (*self._e, *self._q):
            if not v.den.is_one():
                poles = poles * (v.den / poles.gcd(v.den))
        add("pole", poles, "an entry of E or Q is undefined")
        return tuple(out)

    # -- numbers and pictures
    def lambdify(self, name: str, backend: str = "numpy", **options: Any) -> Any:
        """A vectorised function of parameter arrays for the quantity ``name``.

        See :func:`quadric_contact.families.family_numeric.lambdify` for the backends (``"numpy"``,
        ``"numba"``, ``"mpmath"``, ``"certified"``, ``"exact"``).
        """
        return lambdify(self, name, backend, **options)

    def contact_map(self, *, resolution: int | tuple[int, int] = 100, **ranges: Any) -> Any:
        """The grid of answers over two parameters.

        See :func:`quadric_contact.families.family_maps.contact_map`."""
        return contact_map(self, resolution=resolution, **ranges)

    def __repr__(self) -> str:
        return f"Family(parameters={self.parameters}, E={self.E.tolist()}, Q={self.Q.tolist()})"

    def describe(self) -> str:
        """A summary: the pencil's coefficients, the Deltas' sizes, smallness and Table 4."""
        lines = [
            f"family in {', '.join(self.parameters) or '(no parameters)'}; reference point {self.reference}"
        ]
        lines.append(
            f"Q at the reference point: {self.q_kind.value}"
            + (" (a plane everywhere)" if self.q_is_plane else "")
        )
        for name in ("c0", "c1", "c2", "c3", "c4", "Delta2", "Delta3", "Delta4"):
            q = self.quantity(name)
            kind = "polynomial" if q.is_polynomial else "rational function"
            lines.append(f"  {name}: {kind} of degree {q.value.degree}, {len(q.numerator)} terms")
        lines.append(str(self.smallness))
        for rule in self.table_4.values():
            lines.append(f"Table 4: {rule}")
        for b in self.boundaries:
            lines.append(f"boundary {b.name}: {len(b.factors)} factor(s) ({b.why})")
        return "\n".join(lines)


def _ellipsoid_problem(
    e: Sequence[RationalFunction], q: Sequence[RationalFunction], point: Sequence[Any]
) -> str:
    """Why ``E`` is not a real ellipsoid at ``point`` ("" when it is)."""
    try:
        m = _matrix(e, point)
        _matrix(q, point)
    except ZeroDivisionError:
        return "a pole of an entry"
    kind = Quadric.from_matrix(m).kind
    return "" if kind is QuadricKind.ELLIPSOID else f"E is {kind.value}"


def _distinct_eigenvalues(m: Sequence[Sequence[Fraction]]) -> int:
    """The number of distinct eigenvalues of the quadratic part of ``m`` (exact)."""
    a = [m[i][j] for i, j in ENTRY_INDICES if i < 3 and j < 3]
    tr, J, det00 = principal_minor_sums_3(a)
    f = flint.fmpq_poly([_exact_fmpq(-det00), _exact_fmpq(J), _exact_fmpq(-tr), 1])
    return int(f.degree() - f.gcd(f.derivative()).degree())


def _to_context(p: Any, ctx: Any) -> Any:
    """A polynomial that no longer involves the dropped parameters, in the smaller context."""
    names = p.context().names()
    keep = [names.index(n) for n in ctx.names()]
    d = {}
    for mono, c in p.to_dict().items():
        if any(mono[i] for i in range(len(names)) if i not in keep):
            raise AssertionError("a substituted parameter remains")
        d[tuple(mono[i] for i in keep)] = c
    return ctx.from_dict(d) if d else ctx.constant(0)


def _matrix(entries: Sequence[RationalFunction], point: Sequence[Any]) -> list[list[Fraction]]:
    values = [v.evaluate(point) for v in entries]
    m = [[Fraction(0)] * 4 for _ in range(4)]
    for (i, j), v in zip(ENTRY_INDICES, values, strict=True):
        m[i][j] = m[j][i] = v
    return m


def _sympy_matrix(entries: Sequence[RationalFunction], symbols: Sequence[sp.Symbol]) -> sp.Matrix:
    m = sp.zeros(4, 4)
    for (i, j), v in zip(ENTRY_INDICES, entries, strict=True):
        m[i, j] = m[j, i] = v.to_sympy(symbols)
    return m


def family(E: Any, Q: Any, parameters: Any, *, at: Mapping[str, Any] | None = None) -> Family:
    """A parametric family of pairs: the pencil of ``E(p)`` and ``Q(p)`` over Q(parameters).

    Parameters
    ----------
    E, Q : str, sympy expression or matrix, 4x4 matrix-like, or Quadric
        Equations in ``x, y, z`` whose coefficients are polynomials or quotients of
        polynomials with rational coefficients in the parameters (``"(x - u)^2 + y^2 +
        3*(z - w)^2 - 0.1"``; text is read by the package's own parser, with the declared
        parameters as the only other names, division by expressions in the parameters
        allowed), sympy expressions or equalities built by the caller, 4x4 matrices whose
        entries are numbers, sympy expressions in the parameters or text in the parameters
        (``"u/2"``), or constant :class:`Quadric` objects.  ``E`` must be a real ellipsoid
        somewhere (at the reference point).
    parameters : str or sequence
        The parameter names: ``"u w s"`` (spaces or commas), a list of names or of sympy
        Symbols.  Any other name in the text is refused.
    at : mapping, optional
        The reference point (a value for every parameter) where ``E`` is an ellipsoid: it
        fixes the sign normalisation of ``E``, the type of ``Q`` and the order of the
        eigenvalues used by the smallness formulas.  By default the first of a fixed list of
        small rational points where ``E`` is a real ellipsoid.

    Returns
    -------
    Family

    Raises
    ------
    EquationError
        Text the parser refuses (an undeclared name, a division by ``x``, ...), a bad
        parameter list, a non-rational sympy coefficient, degree above 2 in ``x, y, z``.
    ShapeError, NotSymmetricError
        A matrix that is not 4x4 or not symmetric.
    NotAnEllipsoidError
        ``E`` is a real ellipsoid at none of the points tried (or not at ``at``).

    References
    ----------
    Eq. (1), Section 3.2, Corollary 10, Theorem 13 and Table 4, Corollary 15, Tables 1-2.

    Examples
    --------
    The bee of Example 17 with its centre ``(u, 0, w)`` in the plane ``y = 0`` through the
    trunk:

    >>> from quadric_contact import family
    >>> fam = family("(x - u)^2 + y^2 + 3*(z - w)^2 - 0.1", "x^2 + y^2 - 0.25*(z - 3)^2 - 1", "u w")
    >>> fam.coefficients[4], fam.coefficients[0]
    (-3/10, 1/4)
    >>> fam.quantity("Delta4").is_polynomial, fam.smallness.status, fam.q_kind.value
    (True, 'constant', 'hyperboloid of one sheet')
    >>> print(fam.table_4[Region.R_PLUS])
    R+ (roots -+++): c4 < 0, c0 > 0; 3 sign changes of (c0, .., c4)
    >>> from quadric_contact import characteristic_polynomial
    >>> bee = "(x - 3)^2 + y^2 + 3*(z - 5.5)^2 - 0.1"
    >>> P = characteristic_polynomial(bee, "x^2 + y^2 - 0.25*(z - 3)^2 - 1")
    >>> fam.evaluate("c3", u=3, w=5.5) == P.coefficients[3]
    True

    Undeclared names are refused by the parser:

    >>> family("(x - v)^2 + y^2 + z^2 - 1", "z", "u")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    quadric_contact.exact.errors.EquationError: E: unknown name 'v' at position 6; allowed names: x, y, z, u
    ...
    """
    names = _parameter_names(parameters)
    pctx = flint.fmpq_mpoly_ctx.get(names, "lex")
    e = _read(E, names, pctx, "E")
    q = _read(Q, names, pctx, "Q")
    return Family(names, e, q, at=at)
