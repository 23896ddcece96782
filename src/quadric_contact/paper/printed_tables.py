"""Table 2 of the paper exactly as printed, for Example 6 and the errata.

:func:`printed_table_2` evaluates one row of Table 2 with the formulas as the
paper prints them (also where they are wrong, see
:data:`quadric_contact.paper.errata.ERRATA`), so that Example 6's printed numbers and
the misprints can be checked; the corrected decision is
:func:`quadric_contact.theory.smallness.smallness`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.quantity import Quantity, compare_quantities
from quadric_contact.model.classification import TABLE_1_KINDS, QuadricKind
from quadric_contact.model.invariants import invariants
from quadric_contact.theory.pencil import as_quadric
from quadric_contact.theory.smallness import Condition

__all__ = ["PrintedTable2", "printed_table_2"]

K = QuadricKind


@dataclass(frozen=True)
class PrintedTable2:
    """The quantities and conditions of one row of Table 2 exactly as printed.

    ``quantities`` maps Table 2 names (``"a'"``, ``"d'"``, ``"L"``, ``"M"``,
    ``"alpha'"``, ``"delta'"``, ...) to their squares; a printed formula
    that yields a negative square makes the row undefined
    (``conditions`` is then empty and ``undefined`` says why).
    """

    reading: QuadricKind
    quantities: dict[str, Quantity]
    conditions: tuple[Condition, ...]
    undefined: str | None = None

    def value(self, name: str, digits: int = 17) -> str:
        """Decimal value of a quantity (the square root of its stored square)."""
        bits = int(digits * 3.33) + 32
        with working_precision(bits):
            return self.quantities[name].ball(bits).sqrt().str(digits, radius=False)

    def squared(self, name: str) -> RealAlgebraic:
        return self.quantities[name].exact()

    @property
    def small(self) -> bool | None:
        if self.undefined:
            return None
        return all(c.holds for c in self.conditions)


def printed_table_2(E: Any, Q: Any, *, reading: QuadricKind | str | None = None) -> PrintedTable2:
    """Evaluate one row of Table 2 *as printed*.

    Parameters
    ----------
    E, Q : Quadric, matrix-like or equation
    reading : QuadricKind or str, optional
        The row to use; default the exact type of ``Q``.  Another row reads
        ``Q`` as that type (Example 6 reads a hyperboloid with an eigenvalue
        close to 0 as a hyperbolic paraboloid): the eigenvalues of ``Q00``
        smallest in absolute value are taken as the zero ones, and the sign
        of ``Q`` is chosen so that the remaining ones have the printed signs.

    Returns
    -------
    PrintedTable2

    Raises
    ------
    ExcludedQuadricError
        ``reading`` (or the type of ``Q``) has no row in Table 2.

    References
    ----------
    Table 2, Example 6.

    Examples
    --------
    Example 6 read as a hyperbolic paraboloid: the paper prints
    ``L = 2.00000169069926``, ``b = 0.9999998094301916`` and the maximal
    curvature ``2/(L b^2) = 0.9999995357904882``, above the ellipsoid's
    smallest curvature (about 0.416): not small.

    >>> from fractions import Fraction
    >>> from quadric_contact.paper.printed import PRINTED
    >>> E, Q = (
    ...     [[Fraction(v) for v in row.split()] for row in PRINTED[f"Example 6 {name}"].split(";")]
    ...     for name in "EQ"
    ... )
    >>> t = printed_table_2(E, Q, reading="hyperbolic paraboloid")
    >>> t.value("L", 10), t.value("b'", 10)
    ('2.000001691', '0.9999998094')
    >>> [(c.decimal("lhs", 8), c.decimal("rhs", 8), c.holds) for c in t.conditions], t.small
    ([('0.99999954', '0.41631601', False)], False)
    """
    e = as_quadric(E, "E").as_ellipsoid()
    q = as_quadric(Q, "Q")
    kind = QuadricKind(reading) if reading is not None else q.kind
    if kind not in TABLE_1_KINDS:
        raise ExcludedQuadricError(f"{kind.value} has no row in Table 2", q, kind=kind)
    zeros = {
        K.ELLIPTIC_PARABOLOID: 1,
        K.HYPERBOLIC_PARABOLOID: 1,
        K.ELLIPTIC_CYLINDER: 1,
        K.HYPERBOLIC_CYLINDER: 1,
        K.PARABOLIC_CYLINDER: 2,
        K.PARALLEL_PLANES: 2,
    }.get(kind, 0)
    negs = {
        K.HYPERBOLOID_ONE_SHEET: 1,
        K.HYPERBOLOID_TWO_SHEETS: 1,
        K.HYPERBOLIC_PARABOLOID: 1,
        K.HYPERBOLIC_CYLINDER: 1,
    }.get(kind, 0)
    inv = invariants(q)
    Q_ = Quantity.of
    # the eigenvalues used: drop the `zeros` smallest in absolute value
    by_mag = sorted(inv.eigenvalues, key=lambda m: abs(float(m)))
    used = by_mag[zeros:]
    sign = 1
    if sum(1 for m in used if m.sign() < 0) != negs:
        sign = -1
    if kind is K.HYPERBOLIC_PARABOLOID:
        # printed: EV 1/a'^2, -1/b'^2 with a' >= b': the negative eigenvalue is the larger one
        lo_m, hi_m = sorted(used, key=float)
        if abs(float(hi_m)) > abs(float(lo_m)):
            sign = -1
    if kind is K.HYPERBOLIC_CYLINDER and -inv.K * sign / inv.J < 0:
        sign = -sign
    det, J, Kv, Jp = inv.det, inv.J, inv.K * sign, inv.J_prime
    vals = sorted((Q_(m) if sign > 0 else -Q_(m) for m in used), key=lambda x: float(x.ball(64).mid()))
    # vals increasing (signed, after normalisation)
    quantities: dict[str, Quantity] = {}
    ea = invariants(e)
    n1, n2, n3 = ea.eigenvalues
    quantities["alpha'"] = 1 / Q_(n1)
    quantities["beta'"] = 1 / Q_(n2)
    quantities["gamma'"] = 1 / Q_(n3)
    quantities["delta'"] = -quantities["alpha'"] * quantities["beta'"] * quantities["gamma'"] * Q_(ea.det)
    undefined = None
    if kind in (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS):
        if kind is K.ELLIPSOID:
            m1, m2, m3 = vals
            a2, b2, c2 = 1 / m1, 1 / m2, 1 / m3
            d2 = -a2 * b2 * c2 * Q_(det)
        else:
            n, p1, p2 = vals
            a2, b2, c2 = 1 / p1, 1 / p2, -1 / n
            d2 = a2 * b2 * c2 * Q_(det) * (1 if kind is K.HYPERBOLOID_ONE_SHEET else -1)
        quantities.update({"a'": a2, "b'": b2, "c'": c2, "d'": d2})
    elif kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        x, y = vals
        if kind is K.ELLIPTIC_PARABOLOID:
            quantities.update({"a'": 1 / x, "b'": 1 / y})
        else:
            quantities.update({"a'": 1 / y, "b'": -1 / x})
        quantities["L"] = Q_(-4 * det / J)
    elif kind in (K.ELLIPTIC_CYLINDER, K.HYPERBOLIC_CYLINDER):
        x, y = vals
        if kind is K.ELLIPTIC_CYLINDER:
            quantities.update({"a'": 1 / x, "b'": 1 / y})
        else:
            quantities.update({"a'": 1 / y, "b'": -1 / x})
        quantities["M"] = Q_(-Kv / J)
    elif kind is K.PARABOLIC_CYLINDER:
        (x,) = vals
        quantities["a'"] = 1 / x
        quantities["d'"] = Q_(4 * Kv) * quantities["a'"]  # printed: d'^2 = 4 K a'^2
    else:
        (x,) = vals
        quantities["a'"] = 1 / x
        quantities["d'"] = -quantities["a'"] * Q_(Jp)
    for name, v in quantities.items():
        if compare_quantities(v, Q_(0)) <= 0:
            undefined = f"the printed formula gives {name}^2 = {v.ball(64)} <= 0"
            return PrintedTable2(kind, quantities, (), undefined)
    g = quantities
    kE2 = g["gamma'"] / (g["delta'"] * g["alpha'"] ** 2)
    da2 = g["delta'"] * g["alpha'"]
    conds: list[Condition] = []
    t = "Table 2"

    def size(name: str, l2: Quantity) -> None:
        conds.append(Condition(name, name, ">=", compare_quantities(l2, da2) >= 0, t, None, l2, da2))

    def curv(name: str, l2: Quantity) -> None:
        conds.append(Condition(name, name, "<=", compare_quantities(l2, kE2) <= 0, t, None, l2, kE2))

    rhs = "gamma'/(delta' alpha'^2)"
    if kind is K.ELLIPSOID:
        size("d'c' >= delta' alpha'", g["d'"] * g["c'"])
        curv(f"a'/(d'c'^2) <= {rhs}", g["a'"] / (g["d'"] * g["c'"] ** 2))
    elif kind is K.HYPERBOLOID_ONE_SHEET:
        size("b'd' >= delta' alpha'", g["b'"] * g["d'"])
        curv(f"a'/(d'c'^2) <= {rhs}", g["a'"] / (g["d'"] * g["c'"] ** 2))
    elif kind is K.HYPERBOLOID_TWO_SHEETS:
        size("c'd' >= delta' alpha'", g["c'"] * g["d'"])
        curv(f"c'/(d'b'^2) <= {rhs}", g["c'"] / (g["d'"] * g["b'"] ** 2))
    elif kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        curv(f"2/(L b'^2) <= {rhs}", 4 / (g["L"] * g["b'"] ** 2))
    elif kind in (K.ELLIPTIC_CYLINDER, K.HYPERBOLIC_CYLINDER):
        size("M b' >= delta' alpha'", g["M"] * g["b'"])
        curv(f"a'/(M b'^2) <= {rhs}", g["a'"] / (g["M"] * g["b'"] ** 2))
    elif kind is K.PARABOLIC_CYLINDER:
        curv(f"2/(d'a'^2) <= {rhs}", 4 / (g["d'"] * g["a'"] ** 2))
    else:
        size("a'd' >= alpha' delta'", g["a'"] * g["d'"])
    return PrintedTable2(kind, quantities, tuple(conds), undefined)
