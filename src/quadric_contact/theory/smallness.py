"""The smallness condition (Definition 1), exactly: Tables 1 and 2, corrected.

Definition 1: the ellipsoid ``E`` is *small* with respect to ``Q`` when the
two surfaces cannot meet in two curves, whatever the relative position.
Lemma 4 (Table 1, standard forms) and Theorem 5 (Table 2, general position,
through the invariants of Section 2.4) turn it into inequalities between
the semi-axes ``alpha >= beta >= gamma`` of ``E`` and the parameters
``a, b, c`` of ``Q``: *size* conditions (a length of ``Q`` at least
``alpha``) and a *curvature* condition (Lemma 3: the largest principal
curvature of ``Q`` at most the smallest of ``E``, ``gamma / alpha^2``).

How the decision is exact
-------------------------
Every side of every inequality is positive, so each inequality is decided
on the *squares* of its sides (squaring preserves the order of positive
numbers).  The squares are rational functions of the eigenvalues of
``Q00`` and ``E00`` (real algebraic numbers, roots of cubics over Q) and of
rational invariants (``det``, ``J``, ``K``, ``J'``): for instance the
squared curvature of an ellipsoid is ``a^2/c^4 = mu_3^2/(mu_1 d^2)`` with
``d^2 = -det Q/det Q00``.  A comparison is first tried with certified ball
arithmetic; when the balls overlap, both sides are built as exact real
algebraic numbers (:mod:`quadric_contact.exact.algebraic`) and compared exactly
(equal exactly when their minimal polynomials and root indices agree).
There is no tolerance anywhere.

Where the printed tables are wrong (see :data:`quadric_contact.paper.errata.ERRATA`)
------------------------------------------------------------------------------------
* Hyperboloid of one sheet (Tables 1, 2): the curvature condition must use
  the largest principal curvature ``max(a/b^2, a/c^2)``; the table keeps
  only ``a/c^2``.  A flat ellipsoid pressed against the inside of the
  throat meets the surface in two curves although the printed conditions
  hold (``tests/test_smallness.py::test_h1_counterexample``).
* Ellipsoid (Table 1, Lemma 4): the conditions are sufficient but not
  necessary.  For two ellipsoids Definition 1 is symmetric, so ``E`` is also
  small when ``Q`` is small with respect to ``E`` (two spheres of any radii
  meet in at most one circle).  In that *enclosing* case Theorem 2 and
  Corollary 10 hold, but Theorem 13 / Table 4 do not (a sphere around a
  smaller sphere has the root signs of ``R-`` while its surface lies in
  ``R+``); :attr:`SmallnessReport.table_4_applies` says which case holds.
* Table 2, hyperbolic cylinder: with the printed reduced equation
  ``x^2/a'^2 - y^2/b'^2 = M^2`` the transverse semi-axis is ``M a'``, so the
  size condition is ``M a' >= delta' alpha'`` (printed: ``M b'``), and no
  ordering ``a' >= b'`` can be imposed.
* Table 2, parabolic cylinder: ``d'^2 = -4 K a'^2`` (printed ``4 K a'^2``,
  which is negative).

The conditions used here are the corrected ones; the printed verdict is
kept in :attr:`SmallnessReport.paper_small`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from quadric_contact.exact.algebraic import RealAlgebraic, algebraic_sqrt, algebraic_value
from quadric_contact.exact.errors import (
    ExcludedQuadricError,
    NotANumberError,
    ShapeError,
    UndecidedError,
)
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.quantity import (
    EXACT,
    Quantity,
    compare_quantities,
    sorted_desc,
)
from quadric_contact.exact.rational import to_fraction
from quadric_contact.model.classification import TABLE_1_KINDS, QuadricKind
from quadric_contact.model.invariants import QuadricInvariants, invariants
from quadric_contact.model.quadric import Quadric
from quadric_contact.theory.pencil import as_quadric

__all__ = [
    "Condition",
    "SmallnessReport",
    "ellipsoid_axes_squared",
    "row_sides",
    "smallness",
    "smallness_report",
    "table_1",
    "table_2_parameters",
]

K = QuadricKind

# -- conditions and reports --------------------------------------------------------------


@dataclass(frozen=True)
class Condition:
    """One inequality of Table 1 / Table 2, decided exactly.

    ``lhs relation rhs`` with ``relation`` ``">="`` or ``"<="``; both sides
    are positive lengths or curvatures, decided on their squares.

    Attributes
    ----------
    name : str
        The inequality in Table 1 notation, e.g. ``"a/c^2 <= gamma/alpha^2"``.
    table_2 : str
        The same inequality in Table 2 notation.
    holds : bool
        Exact verdict.
    source : str
        ``"Table 1"`` (as printed), ``"corrected"`` (added or changed, see
        ``erratum``) or ``"enclosing"`` (the roles of E and Q exchanged).
    erratum : str or None
        Key of the :data:`~quadric_contact.paper.errata.ERRATA` entry when the
        condition differs from the printed tables.
    """

    name: str
    table_2: str
    relation: str
    holds: bool
    source: str
    erratum: str | None
    lhs_squared: Quantity = field(repr=False, compare=False)
    rhs_squared: Quantity = field(repr=False, compare=False)

    @property
    def lhs(self) -> Any:
        """The left side as an exact sympy expression."""
        import sympy  # sympy is heavy: only for sympy output

        return sympy.sqrt(self.lhs_squared.sympy())

    @property
    def rhs(self) -> Any:
        """The right side as an exact sympy expression."""
        import sympy  # sympy is heavy: only for sympy output

        return sympy.sqrt(self.rhs_squared.sympy())

    @property
    def lhs_exact(self) -> RealAlgebraic:
        """The left side as an exact real algebraic number."""
        return algebraic_sqrt(self.lhs_squared.exact())

    @property
    def rhs_exact(self) -> RealAlgebraic:
        """The right side as an exact real algebraic number."""
        return algebraic_sqrt(self.rhs_squared.exact())

    def decimal(self, side: str, digits: int = 15) -> str:
        """``side`` (``"lhs"`` or ``"rhs"``) to ``digits`` significant digits (certified ball arithmetic)."""
        q = self.lhs_squared if side == "lhs" else self.rhs_squared
        bits = int(digits * 3.33) + 32
        with working_precision(bits):
            v = q.ball(bits)
            return v.sqrt().str(digits, radius=False)

    @property
    def lhs_decimal(self) -> str:
        """The left side to 15 significant digits."""
        return self.decimal("lhs")

    @property
    def rhs_decimal(self) -> str:
        """The right side to 15 significant digits."""
        return self.decimal("rhs")

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "table_2": self.table_2,
            "holds": self.holds,
            "source": self.source,
            "erratum": self.erratum,
            "lhs": str(self.lhs),
            "rhs": str(self.rhs),
            "lhs_decimal": self.lhs_decimal,
            "rhs_decimal": self.rhs_decimal,
        }

    def __str__(self) -> str:
        mark = "holds" if self.holds else "FAILS"
        tail = f"  [{self.source}: {self.erratum}]" if self.erratum else ""
        lhs, rhs = self.decimal("lhs", 8), self.decimal("rhs", 8)
        return f"{self.name:<26} {lhs:>16} {self.relation} {rhs:<16} {mark}{tail}"


@dataclass(frozen=True)
class SmallnessReport:
    """Exact answer to "is ``E`` small with respect to ``Q``?" (Definition 1).

    Attributes
    ----------
    small : bool
        The exact verdict with the corrected conditions.
    kind : QuadricKind
        The type of ``Q`` used (decided exactly).
    conditions : tuple of Condition
        The conditions of the row of ``kind`` (corrected); all must hold,
        unless the enclosing alternative holds.
    alternative : tuple of Condition
        Ellipsoids only: the same conditions with the roles of ``E`` and ``Q``
        exchanged (``Q`` small with respect to ``E``); Definition 1 is
        symmetric for two ellipsoids.
    paper_small : bool
        The verdict of the conditions exactly as printed in Table 1 (and
        Table 2, which agrees with Table 1 where it is not misprinted).
    table_4_applies : bool
        ``small`` and ``E`` cannot enclose ``Q``: Theorem 13 / Table 4 may
        be used.  False in the enclosing case (see the module docstring).
    parameters : dict
        The semi-axes ``alpha, beta, gamma`` of ``E`` and the parameters
        ``a, b, c`` of ``Q`` in its Table 1 standard form, squared, exact.

    Examples
    --------
    Example 17, the bee and the trunk: the paper's ``alpha = beta = 1``,
    ``gamma = 1/sqrt(3)``, ``delta = 1/sqrt(10)`` are the Table 2 reduction; the
    Table 1 semi-axes are ``delta alpha = 0.316228`` and so on.

    >>> r = smallness("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1", "x**2 + y**2 - 0.25*(z-3)**2 - 1")
    >>> bool(r), r.failed, [r.parameter(p, 6) for p in ("alpha", "gamma", "a", "b", "c")]
    (True, (), ['0.316228', '0.182574', '1.00000', '1.00000', '2.00000'])
    """

    small: bool | None
    kind: QuadricKind
    conditions: tuple[Condition, ...]
    alternative: tuple[Condition, ...]
    paper_small: bool | None
    table_4_applies: bool
    parameters: dict[str, Any] = field(repr=False, compare=False)
    mode: str = "exact"

    @property
    def decided(self) -> bool:
        """False only for an ``UNCERTAIN`` answer of an abstaining number mode."""
        return self.small is not None

    def __bool__(self) -> bool:
        if self.small is None:
            raise UndecidedError(f"smallness is undecided in {self.mode} mode", self)
        return self.small

    @property
    def failed(self) -> tuple[Condition, ...]:
        """The conditions (of the corrected row) that do not hold."""
        return tuple(c for c in self.conditions if not c.holds)

    def parameter(self, name: str, digits: int = 15) -> str:
        """Decimal value of a parameter (``"a"``, ``"alpha"``, ...)."""
        q = self.parameters[name]
        bits = int(digits * 3.33) + 32
        with working_precision(bits):
            return q.ball(bits).sqrt().str(digits, radius=False)

    def to_dict(self) -> dict[str, Any]:
        return {
            "small": self.small,
            "kind": self.kind.value,
            "paper_small": self.paper_small,
            "table_4_applies": self.table_4_applies,
            "conditions": [c.to_dict() for c in self.conditions],
            "alternative": [c.to_dict() for c in self.alternative],
            "parameters": {k: self.parameter(k) for k in self.parameters},
        }

    def __str__(self) -> str:
        verdict = {True: "small", False: "NOT small", None: "UNDECIDED (small or not)"}[self.small]
        if not self.conditions:
            return (
                f"E is {verdict} with respect to Q ({self.kind.value}), decided in {self.mode} mode; "
                "the exact smallness report shows the conditions"
            )
        lines = [f"E is {verdict} with respect to Q ({self.kind.value}); Table 1 (corrected):"]
        lines += [f"  {c}" for c in self.conditions]
        if self.alternative:
            lines.append("  or, Q small with respect to E (two ellipsoids: Definition 1 is symmetric):")
            lines += [f"  {c}" for c in self.alternative]
        if self.paper_small != self.small:
            lines.append(f"  the printed tables say: {'small' if self.paper_small else 'not small'}")
        if self.small and not self.table_4_applies:
            lines.append("  E can enclose Q: Corollary 10 applies, Theorem 13 / Table 4 do not")
        return "\n".join(lines)


# -- Table 1 on squared parameters ----------------------------------------------------------

_ERR_H1 = "table-1-h1-curvature"
_ERR_ELL = "table-1-ellipsoid-enclosing"
_ERR_HC = "table-2-hyperbolic-cylinder-size"

# Table 2 notation of the Table 1 quantities (a = a'd', alpha = alpha' delta', ...).
_T2 = {
    "alpha": "delta' alpha'",
    "gamma/alpha^2": "gamma'/(delta' alpha'^2)",
}


def _size(
    lhs: str,
    l2: Quantity,
    rhs: str,
    r2: Quantity,
    t2: str,
    source: str = "Table 1",
    erratum: str | None = None,
) -> Condition:
    return Condition(f"{lhs} >= {rhs}", t2, ">=", compare_quantities(l2, r2) >= 0, source, erratum, l2, r2)


def _curv(
    lhs: str,
    l2: Quantity,
    rhs: str,
    r2: Quantity,
    t2: str,
    source: str = "Table 1",
    erratum: str | None = None,
) -> Condition:
    return Condition(f"{lhs} <= {rhs}", t2, "<=", compare_quantities(l2, r2) <= 0, source, erratum, l2, r2)


Side = tuple[str, str, Any, str, Any, str, str, "str | None"]
"""One inequality of a row: ``(relation, lhs name, lhs^2, rhs name, rhs^2, Table 2 text,
source, erratum)``; ``relation`` is ``">="`` (a size) or ``"<="`` (a curvature)."""


def row_sides(kind: QuadricKind, p: dict[str, Any], e: dict[str, Any]) -> tuple[list[Side], list[Side]]:
    """The corrected Table 1 row for ``kind`` as squared sides: (conditions, enclosing alternative).

    ``p``: squared parameters ``a, b, c`` of Q (Table 1 standard form, with Table 1's
    orderings); ``e``: squared semi-axes ``alpha >= beta >= gamma``.  Only ``+ - * /`` and
    integer powers are applied to them, so they may be exact quantities (decided here) or
    symbolic expressions (the parametric families of :mod:`quadric_contact.families.family`).
    """
    al2, ga2 = e["alpha"], e["gamma"]
    kE2 = ga2 / al2**2  # (gamma/alpha^2)^2, the smallest principal curvature of E, squared
    t2k = "gamma'/(delta' alpha'^2)"
    t2a = "delta' alpha'"
    T1 = "Table 1"
    if kind is K.ELLIPSOID:
        a2, c2 = p["a"], p["c"]
        return [
            (">=", "c", c2, "alpha", al2, f"d'c' >= {t2a}", T1, None),
            ("<=", "a/c^2", a2 / c2**2, "gamma/alpha^2", kE2, f"a'/(d'c'^2) <= {t2k}", T1, None),
        ], [
            (">=", "gamma", ga2, "a", a2, "delta' gamma' >= d'a'", "enclosing", _ERR_ELL),
            (
                "<=",
                "alpha/gamma^2",
                al2 / ga2**2,
                "c/a^2",
                c2 / a2**2,
                "alpha'/(delta' gamma'^2) <= c'/(d'a'^2)",
                "enclosing",
                _ERR_ELL,
            ),
        ]
    if kind is K.HYPERBOLOID_ONE_SHEET:
        a2, b2, c2 = p["a"], p["b"], p["c"]
        return [
            (">=", "b", b2, "alpha", al2, f"b'd' >= {t2a}", T1, None),
            ("<=", "a/c^2", a2 / c2**2, "gamma/alpha^2", kE2, f"a'/(d'c'^2) <= {t2k}", T1, None),
            ("<=", "a/b^2", a2 / b2**2, "gamma/alpha^2", kE2, f"a'/(d'b'^2) <= {t2k}", "corrected", _ERR_H1),
        ], []
    if kind is K.HYPERBOLOID_TWO_SHEETS:
        b2, c2 = p["b"], p["c"]
        return [
            (">=", "c", c2, "alpha", al2, f"c'd' >= {t2a}", T1, None),
            ("<=", "c/b^2", c2 / b2**2, "gamma/alpha^2", kE2, f"c'/(d'b'^2) <= {t2k}", T1, None),
        ], []
    if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        b2 = p["b"]
        return [("<=", "2/b^2", 4 / b2**2, "gamma/alpha^2", kE2, f"2/(L b'^2) <= {t2k}", T1, None)], []
    if kind is K.ELLIPTIC_CYLINDER:
        a2, b2 = p["a"], p["b"]
        return [
            (">=", "b", b2, "alpha", al2, f"M b' >= {t2a}", T1, None),
            ("<=", "a/b^2", a2 / b2**2, "gamma/alpha^2", kE2, f"a'/(M b'^2) <= {t2k}", T1, None),
        ], []
    if kind is K.HYPERBOLIC_CYLINDER:
        a2, b2 = p["a"], p["b"]
        return [
            (">=", "a", a2, "alpha", al2, f"M a' >= {t2a}  (printed: M b')", T1, _ERR_HC),
            ("<=", "a/b^2", a2 / b2**2, "gamma/alpha^2", kE2, f"a'/(M b'^2) <= {t2k}", T1, None),
        ], []
    if kind is K.PARABOLIC_CYLINDER:
        a2 = p["a"]
        return [("<=", "2/a^2", 4 / a2**2, "gamma/alpha^2", kE2, f"2/(d'a'^2) <= {t2k}", T1, None)], []
    if kind is K.PARALLEL_PLANES:
        return [(">=", "a", p["a"], "alpha", al2, f"a'd' >= {t2a}", T1, None)], []
    raise ExcludedQuadricError(f"{kind.value} has no row in Table 1", kind, kind=kind)


def _decided(side: Side) -> Condition:
    relation, lhs, l2, rhs, r2, t2, source, erratum = side
    make = _size if relation == ">=" else _curv
    return make(lhs, l2, rhs, r2, t2, source, erratum)


def _rows(
    kind: QuadricKind, p: dict[str, Quantity], e: dict[str, Quantity]
) -> tuple[list[Condition], list[Condition]]:
    """The corrected Table 1 row for ``kind``, decided exactly: (conditions, enclosing alternative)."""
    conds, alt = row_sides(kind, p, e)
    return [_decided(c) for c in conds], [_decided(c) for c in alt]


def smallness_report(kind: QuadricKind, p: dict[str, Quantity], e: dict[str, Quantity]) -> SmallnessReport:
    """The decision of Definition 1 through Tables 1-2 (corrected) from the parameters.

    Parameters
    ----------
    kind : QuadricKind
        The type of ``Q`` (a row of Table 1).
    p : dict
        The Table 2 parameters of ``Q`` (:func:`table_2_parameters`, ``Q`` with its
        canonical sign).
    e : dict
        The squared semi-axes of ``E`` (:func:`ellipsoid_axes_squared`).

    Returns
    -------
    SmallnessReport
        As :func:`smallness`, which is this function on the parameters of one pair; the
        number modes call it directly to compute the parameters of every distinct matrix
        of a stack once.
    """
    conds, alt = _rows(kind, p, e)
    inner = all(c.holds for c in conds)
    outer = bool(alt) and all(c.holds for c in alt)
    printed = all(c.holds for c in conds if c.source == "Table 1")
    params = {**e, **p}
    return SmallnessReport(
        small=inner or outer,
        kind=kind,
        conditions=tuple(conds),
        alternative=tuple(alt),
        paper_small=printed,
        table_4_applies=inner,
        parameters=params,
    )


# -- Table 1: standard forms ----------------------------------------------------------------

_TABLE_1_PARAMS = {
    K.ELLIPSOID: "abc",
    K.HYPERBOLOID_ONE_SHEET: "abc",
    K.HYPERBOLOID_TWO_SHEETS: "abc",
    K.ELLIPTIC_PARABOLOID: "ab",
    K.HYPERBOLIC_PARABOLOID: "ab",
    K.ELLIPTIC_CYLINDER: "ab",
    K.HYPERBOLIC_CYLINDER: "ab",
    K.PARABOLIC_CYLINDER: "a",
    K.PARALLEL_PLANES: "a",
}


def _square(value: Any, name: str) -> Quantity:
    """The square of a positive parameter, exactly (int, Fraction, float, decimal
    string, sympy expression with a rational square, or RealAlgebraic)."""
    if isinstance(value, RealAlgebraic):
        if value.sign() <= 0:
            raise NotANumberError(f"parameter {name} must be positive, got {value}", value)
        return Quantity.of(algebraic_value(lambda x: x * x, [value]))
    mod = type(value).__module__ or ""
    if mod.startswith("sympy"):
        import sympy  # sympy is heavy: only for sympy input

        sq = sympy.nsimplify(sympy.expand(value**2))
        if not (sq.is_Rational and value.is_positive):
            raise NotANumberError(
                f"parameter {name} must be a positive number with a rational square, got {value}", value
            )
        return Quantity.of(Fraction(int(sq.p), int(sq.q)))
    v = to_fraction(value)
    if v <= 0:
        raise NotANumberError(f"parameter {name} must be positive, got {value}", value)
    return Quantity.of(v * v)


def table_1(kind: QuadricKind | str, *, alpha: Any, beta: Any, gamma: Any, **params: Any) -> SmallnessReport:
    """Table 1 (corrected): smallness for ``Q`` in standard form.

    Parameters
    ----------
    kind : QuadricKind or str
        A type of Table 1.
    alpha, beta, gamma : positive numbers
        Semi-axes of ``E`` (eq. (2)); sorted so that ``alpha >= beta >= gamma``.
    a, b, c : positive numbers
        The parameters of the standard form of ``Q`` in Table 1 (as many as
        its equation has).  Where Table 1 orders them (``a >= b >= c`` for the
        ellipsoid, ``a >= b`` for the hyperboloids, paraboloids and the
        elliptic cylinder) they are sorted first; for the hyperbolic
        paraboloid the smaller of ``a, b`` is the one that matters and for
        the hyperbolic cylinder ``a`` is the transverse semi-axis.
        Values may be ints, Fractions, floats (exact), decimal strings,
        sympy expressions with rational squares (``sympy.sqrt(3)/3``) or
        RealAlgebraic.

    Returns
    -------
    SmallnessReport

    Raises
    ------
    ExcludedQuadricError
        ``kind`` is not a type of Table 1.

    References
    ----------
    Lemma 3, Lemma 4, Table 1; the corrections are listed in the module
    docstring.

    Examples
    --------
    The throat of the hyperboloid ``S2`` of Example 17 and the bee:

    >>> import sympy
    >>> r = table_1("hyperboloid of one sheet", a=1, b=1, c=2,
    ...             alpha=sympy.sqrt(10)/10, beta=sympy.sqrt(10)/10, gamma=sympy.sqrt(30)/30)
    >>> r.small, [c.name for c in r.conditions]
    (True, ['b >= alpha', 'a/c^2 <= gamma/alpha^2', 'a/b^2 <= gamma/alpha^2'])
    """
    kind = QuadricKind(kind)
    if kind not in _TABLE_1_PARAMS:
        raise ExcludedQuadricError(
            f"{kind.value} has no row in Table 1"
            + (f" ({kind.excluded_reason})" if kind.excluded_reason else ""),
            kind,
            kind=kind,
        )
    names = _TABLE_1_PARAMS[kind]
    if set(params) != set(names):
        raise ShapeError(
            f"the standard {kind.value} takes parameters {', '.join(names)}; got {', '.join(sorted(params))}",
            params,
        )
    sq = {n: _square(params[n], n) for n in names}
    es = sorted_desc([_square(alpha, "alpha"), _square(beta, "beta"), _square(gamma, "gamma")])
    e = {"alpha": es[0], "beta": es[1], "gamma": es[2]}
    if kind is K.ELLIPSOID:
        s = sorted_desc([sq["a"], sq["b"], sq["c"]])
        sq = {"a": s[0], "b": s[1], "c": s[2]}
    elif kind in (
        K.HYPERBOLOID_ONE_SHEET,
        K.HYPERBOLOID_TWO_SHEETS,
        K.ELLIPTIC_PARABOLOID,
        K.ELLIPTIC_CYLINDER,
        K.HYPERBOLIC_PARABOLOID,
    ):
        s = sorted_desc([sq["a"], sq["b"]])
        sq = {**sq, "a": s[0], "b": s[1]}
    return smallness_report(kind, sq, e)


# -- Table 2: general position ---------------------------------------------------------------


def ellipsoid_axes_squared(inv: QuadricInvariants, num: Any = EXACT) -> dict[str, Any]:
    """Squared semi-axes of a real ellipsoid from its invariants (det < 0 sign)."""
    n1, n2, n3 = inv.eigenvalues  # increasing, positive
    Q_ = num.of
    d2 = Q_(-inv.det / inv.det00)  # E: sum nu_i X_i^2 = d2 in principal axes
    return {"alpha": d2 / Q_(n1), "beta": d2 / Q_(n2), "gamma": d2 / Q_(n3)}


def _signed(eigs: Sequence[RealAlgebraic]) -> tuple[list[RealAlgebraic], list[RealAlgebraic], int]:
    pos = [m for m in eigs if m.sign() > 0]
    neg = [m for m in eigs if m.sign() < 0]
    return pos, neg, 3 - len(pos) - len(neg)


def table_2_parameters(kind: QuadricKind, inv: Any, num: Any = EXACT) -> dict[str, Any]:
    """Squared Table 1 parameters ``a, b, c`` of ``Q`` (canonical sign) from its
    invariants (Table 2, with the corrections of the module docstring), in the numbers ``num``."""
    pos, neg, _ = _signed(inv.eigenvalues)
    Q_ = num.of
    if kind is K.ELLIPSOID:
        d2 = Q_(-inv.det / inv.det00)
        m1, m2, m3 = pos
        return {"a": d2 / Q_(m1), "b": d2 / Q_(m2), "c": d2 / Q_(m3)}
    if kind in (K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS):
        d2 = Q_(-inv.det / inv.det00) if kind is K.HYPERBOLOID_ONE_SHEET else Q_(inv.det / inv.det00)
        p1, p2 = pos
        (n,) = neg
        return {"a": d2 / Q_(p1), "b": d2 / Q_(p2), "c": -d2 / Q_(n)}
    if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        L = num.sqrt(-4 * inv.det / inv.J)
        nz = [m for m in inv.eigenvalues if m.sign() != 0]
        mags = num.sorted_desc([Q_(m) if m.sign() > 0 else -Q_(m) for m in nz])
        # a^2 = L/|mu| : the larger |mu| gives the smaller parameter b
        return {"a": L / mags[1], "b": L / mags[0]}
    if kind is K.ELLIPTIC_CYLINDER:
        M2 = Q_(-inv.K / inv.J)
        m1, m2 = pos
        return {"a": M2 / Q_(m1), "b": M2 / Q_(m2)}
    if kind is K.HYPERBOLIC_CYLINDER:
        M2 = Q_(-inv.K / inv.J)
        (p,) = pos
        (n,) = neg
        return {"a": M2 / Q_(p), "b": -M2 / Q_(n)}
    if kind is K.PARABOLIC_CYLINDER:
        (m,) = pos
        mu = num.rational(m)  # rank 1: the eigenvalue is the trace, rational
        d = num.sqrt(-4 * inv.K / mu)
        return {"a": Q_(d) / Q_(mu)}
    if kind is K.PARALLEL_PLANES:
        (m,) = pos
        mu = num.rational(m)
        return {"a": Q_(-inv.J_prime / (mu * mu))}
    raise ExcludedQuadricError(f"{kind.value} has no row in Table 2", kind, kind=kind)


def _normalized_pair(E: Any, Q: Any) -> tuple[Quadric, Quadric]:
    e = as_quadric(E, "E").as_ellipsoid()
    q = as_quadric(Q, "Q")
    kind = q.kind
    if kind not in TABLE_1_KINDS:
        why = kind.excluded_reason or "not a type of Table 1"
        raise ExcludedQuadricError(
            f"smallness is defined for the quadrics of Table 1; Q is {kind.value}: {why}", q, kind=kind
        )
    return e, (q if q.canonical_sign > 0 else -q)


def smallness(E: Any, Q: Any) -> SmallnessReport:
    """Is the ellipsoid ``E`` small with respect to the quadric ``Q`` (Definition 1)?

    Exact decision from the invariants of Section 2.4 (Theorem 5, Table 2),
    with the corrections listed in the module docstring.

    Parameters
    ----------
    E : Quadric, matrix-like or equation
        A real ellipsoid (either sign of its matrix).
    Q : Quadric, matrix-like or equation
        A quadric of one of the nine types of Table 1 (either sign).

    Returns
    -------
    SmallnessReport
        ``.small`` is the verdict; ``.conditions`` the inequalities with both
        sides exact and in decimals.

    Raises
    ------
    NotAnEllipsoidError
        ``E`` is not a real ellipsoid.
    ExcludedQuadricError
        ``Q`` is a cone, intersecting or coincident planes, a plane, or has
        no real points (Section 2: no ellipsoid is small with respect to a
        cone or intersecting planes; a plane needs no smallness, Theorem 14).

    References
    ----------
    Definition 1, Lemma 3, Lemma 4, Theorem 5, Tables 1 and 2, Example 17.

    Examples
    --------
    Example 17: the bee is small with respect to both pieces of the tree.

    >>> bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    >>> r = smallness(bee, "x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
    >>> r.small, [(c.decimal("lhs", 6), c.decimal("rhs", 6)) for c in r.conditions]
    (True, [('2.58199', '0.316228'), ('0.670820', '1.82574')])
    >>> smallness(bee, "x**2 + y**2 - 0.25*(z-3)**2 - 1").small
    True
    """
    e, q = _normalized_pair(E, Q)
    kind = q.kind
    return smallness_report(
        kind, table_2_parameters(kind, invariants(q)), ellipsoid_axes_squared(invariants(e))
    )
