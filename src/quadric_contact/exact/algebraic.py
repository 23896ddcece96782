"""Exact real algebraic numbers: isolation, comparison, signs, arithmetic.

The invariants of Section 2.4 (eigenvalues of ``Q00``, the semi-axes and
curvatures built from them), the critical values of the geometric decision
and the event times of a moving ellipsoid are real algebraic numbers.  They
are all held by the one type of this module and compared *exactly*:

* A :class:`RealAlgebraic` is the only root of its minimal polynomial (monic,
  irreducible over Q) inside an isolating interval with rational ends; a
  rational number is held as itself (``lo == hi``).  Refinement is exact
  bisection; two numbers with the same minimal polynomial are equal exactly
  when the polynomial changes sign across the common part of their intervals,
  otherwise the intervals are refined until they are disjoint.  No tolerance
  is involved anywhere.
* :func:`real_roots` isolates the real roots of a polynomial over Q, on the
  whole line or in an interval, with one isolator: the polynomial is factored
  over Q and the roots of each irreducible factor are separated by bisection
  with Descartes' rule of signs (the Vincent-Collins-Akritas method).
* :func:`sign_at` is the one exact-sign routine: the sign of a polynomial at a
  rational or algebraic number (a divisibility test, then an exact Taylor
  bound on a shrinking isolating interval).
* :func:`algebraic_value` evaluates a rational expression at algebraic
  numbers and returns the result as a :class:`RealAlgebraic`: the
  expression is evaluated on the multiplication matrices of the tensor
  product of the number fields (a rational matrix whose eigenvalues are the
  values of the expression at all conjugates), its minimal polynomial is
  factored over Q, and the factor and root that hold the true value are
  identified with certified ball arithmetic (python-flint ``arb``).
* :class:`QuadraticNumber` is exact arithmetic in ``Q(sqrt(d))``, enough for
  the singular members of a pencil at a multiple root (a multiple root of a
  quartic over Q is rational or a quadratic irrational).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping, Sequence
from fractions import Fraction
from functools import lru_cache
from itertools import pairwise
from typing import Any, Protocol

import flint

from quadric_contact.exact.errors import EquationError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.rational import (
    dyadic_between,
    fmpq_of,
    fmpq_poly_of,
    fraction_of,
    near_midpoint,
    sign,
)

__all__ = [
    "QuadraticNumber",
    "RealAlgebraic",
    "algebraic_sqrt",
    "algebraic_value",
    "as_real_algebraic",
    "compile_expression",
    "irreducible_factors",
    "rational_between",
    "real_roots",
    "sign_at",
    "sort_roots",
]


class Counter(Protocol):
    """Where the exact layer counts its work (a :class:`~quadric_contact.scenes.ledger.Ledger`)."""

    def add(self, name: str, n: int = 1, *, target: str | None = None) -> None: ...


# -- flint helpers ---------------------------------------------------------------------


def _monic(p: Any) -> Any:
    return p / p.leading_coefficient()


def _key(p: Any) -> tuple[Fraction, ...]:
    """The coefficients of the monic multiple of ``p`` (the identity of a minimal polynomial)."""
    return tuple(fraction_of(c) for c in _monic(flint.fmpq_poly(p)).coeffs())


def _sign_rational(p: Any, x: Fraction) -> int:
    """Exact sign of an ``fmpq_poly`` at a rational."""
    if p.is_zero():
        return 0
    v = p(fmpq_of(x))  # an fmpq in lowest terms: its sign is its numerator's (no Fraction to build)
    return int(v.p > 0) - int(v.p < 0)


def _arb_interval(lo: Fraction, hi: Fraction) -> Any:
    """The ball ``[lo, hi]`` (exactly enclosing the interval at the current precision)."""
    mid = (lo + hi) / 2
    rad = (hi - lo) / 2
    # arb(mid, rad) rounds mid; widen the radius by the rounding error bound.
    m = flint.arb(fmpq_of(mid))
    r = flint.arb(fmpq_of(rad))
    return flint.arb(m.mid(), (r + m.rad()).upper())


# -- the root isolator -----------------------------------------------------------------


def _primitive(p: Any) -> Any:
    """The primitive integer polynomial with positive leading coefficient of an fmpq_poly/fmpz_poly."""
    z = flint.fmpz_poly(flint.fmpq_poly(p).numer())
    c = z.content()
    if c != 1 and c != 0:
        z = flint.fmpz_poly([int(a) // int(c) for a in z.coeffs()])
    if z.degree() >= 0 and z.leading_coefficient() < 0:
        z = -z
    return z


def irreducible_factors(p: Any, *, multiplicities: bool = False) -> list[Any]:
    """The distinct irreducible factors (of positive degree) of a nonzero polynomial over Q.

    Parameters
    ----------
    p : fmpq_poly, fmpz_poly or a sequence of coefficients ``c0, c1, ...``
    multiplicities : bool
        Return ``(factor, multiplicity)`` pairs.

    Returns
    -------
    list of fmpz_poly
        Primitive, with positive leading coefficient.

    Examples
    --------
    >>> irreducible_factors([0, 0, -2, 0, 1], multiplicities=True)
    [(x, 2), (x^2 + (-2), 1)]
    """
    if not isinstance(p, (flint.fmpq_poly, flint.fmpz_poly)):
        p = fmpq_poly_of(p)
    z = _primitive(p)
    if z.degree() <= 0:
        return []
    _, facs = z.factor()
    out = []
    for f, m in facs:
        if f.degree() >= 1:
            f = -f if f.leading_coefficient() < 0 else f
            out.append((f, int(m)) if multiplicities else f)
    return out


def _descartes_bound(f: Any, a: Fraction, b: Fraction) -> int:
    """An upper bound (exact parity) on the number of roots of ``f`` in ``(a, b)``:
    the sign variations of ``(1 + u)^n f((a + b u) / (1 + u))`` (Descartes' rule
    after the Moebius map of ``(0, oo)`` onto ``(a, b)``).  0 means no root."""
    h = flint.fmpq_poly(f)(flint.fmpq_poly([fmpq_of(a), fmpq_of(b - a)]))  # f on (a, b) <-> h on (0, 1)
    rev = flint.fmpq_poly(list(reversed(h.coeffs())))  # y^n h(1/y)
    g = rev(flint.fmpq_poly([1, 1]))  # roots of h in (0, 1) <-> positive roots of g
    signs = [1 if c > 0 else -1 for c in g.coeffs() if c != 0]
    return sum(1 for x, y in pairwise(signs) if x != y)


def _root_bound(f: Any) -> Fraction:
    """A power of two above the absolute value of every root (Cauchy's bound)."""
    cs = [fraction_of(c) for c in flint.fmpq_poly(f).coeffs()]
    bound = 1 + max(abs(c / cs[-1]) for c in cs[:-1])
    return Fraction(2) ** max(0, math.ceil(bound).bit_length())


def _isolate(f: Any, a: Fraction, b: Fraction) -> list[tuple[Fraction, Fraction]]:
    """Isolating intervals, in increasing order, of the roots in ``(a, b)`` of an irreducible
    polynomial ``f`` of degree > 1 (the package's one root isolator).

    Bisection with Descartes' rule (Vincent-Collins-Akritas): a piece with no sign
    variation holds no root, one with one variation exactly one (then ``f`` changes sign
    across it).  The roots are simple and irrational, so no bisection point is a root and
    the bisection ends."""
    out: list[tuple[Fraction, Fraction]] = []
    todo = [(a, b)]
    while todo:
        lo, hi = todo.pop()
        v = _descartes_bound(f, lo, hi)
        if v == 0:
            continue
        if v == 1:
            out.append((lo, hi))
            continue
        mid = (lo + hi) / 2
        todo += [(mid, hi), (lo, mid)]
    return sorted(out)


@lru_cache(maxsize=4096)
def _isolate_all(key: tuple[Fraction, ...]) -> tuple[tuple[Fraction, Fraction], ...]:
    """All real roots of the irreducible monic polynomial with coefficients ``key``."""
    if len(key) == 2:
        return ((-key[0], -key[0]),)
    f = fmpq_poly_of(key)
    B = _root_bound(f)
    return tuple(_isolate(f, -B, B))


def real_roots(
    poly: Any,
    lo: Fraction | None = None,
    hi: Fraction | None = None,
    *,
    closed: bool = False,
    multiplicities: bool = False,
    ledger: Counter | None = None,
    target: str | None = None,
) -> list[Any]:
    """The distinct real roots of a nonzero polynomial over Q, in increasing order, exactly.

    Parameters
    ----------
    poly : fmpq_poly, fmpz_poly, or a sequence of coefficients ``c0, c1, ...``
    lo, hi : Fraction, optional
        Only the roots in the open interval ``(lo, hi)`` (both or neither).
    closed : bool
        With ``lo, hi``: include roots equal to ``lo`` or ``hi``.
    multiplicities : bool
        Return ``(root, multiplicity)`` pairs.
    ledger, target
        Where to count the isolations (``root_isolations``, one per irreducible factor).

    Returns
    -------
    list of RealAlgebraic (or of pairs)

    Examples
    --------
    >>> [str(r) for r in real_roots([-2, 0, 1])]
    ['-1.41421356237310 (root 1 of x**2 - 2)', '1.41421356237310 (root 2 of x**2 - 2)']
    >>> real_roots([6, -5, 1])
    [RealAlgebraic(2), RealAlgebraic(3)]
    >>> [r.decimal(6) for r in real_roots([-2, 0, 1], Fraction(0), Fraction(10))]
    ['1.414214']
    """
    p = poly if isinstance(poly, (flint.fmpq_poly, flint.fmpz_poly)) else fmpq_poly_of(poly)
    if p.is_zero():
        raise ValueError("the zero polynomial has every number as a root")
    if (lo is None) != (hi is None):
        raise ValueError("give both ends of the interval or neither")
    found: list[tuple[RealAlgebraic, int]] = []
    for f, m in irreducible_factors(p, multiplicities=True):
        if ledger is not None:
            ledger.add("root_isolations", target=target)
        key = _key(f)
        if lo is None or hi is None:
            found += [(RealAlgebraic._make(key, i), m) for i in range(len(_isolate_all(key)))]
        elif f.degree() == 1:
            r = -key[0]
            if lo < r < hi or (closed and lo <= r <= hi):
                found.append((RealAlgebraic(r), m))
        elif lo < hi:
            found += [(RealAlgebraic._from_interval(key, a, b), m) for a, b in _isolate(f, lo, hi)]

    def by_root(u: tuple[RealAlgebraic, int], v: tuple[RealAlgebraic, int]) -> int:
        return u[0].compare(v[0])

    found.sort(key=functools.cmp_to_key(by_root))
    return found if multiplicities else [r for r, _ in found]


def sort_roots(roots: Sequence[RealAlgebraic]) -> list[RealAlgebraic]:
    """Sort exactly, dropping duplicates."""

    def by_value(u: RealAlgebraic, v: RealAlgebraic) -> int:
        return u.compare(v)

    ordered = sorted(roots, key=functools.cmp_to_key(by_value))
    out: list[RealAlgebraic] = []
    for r in ordered:
        if not out or out[-1].compare(r) != 0:
            out.append(r)
    return out


# -- real algebraic numbers ------------------------------------------------------------


class RealAlgebraic:
    """A real algebraic number, exactly.

    Attributes
    ----------
    minpoly : tuple of Fraction
        Coefficients ``c0, c1, .., 1`` of the monic minimal polynomial over Q.
    lo, hi : Fraction
        The current isolating interval: the number is the only root of
        ``minpoly`` in ``[lo, hi]`` (``lo == hi`` for a rational).
    index : int
        Position among the real roots of ``minpoly`` in increasing order
        (sympy's ``CRootOf`` index), found when first asked for.

    Examples
    --------
    >>> r = RealAlgebraic.sqrt(2)
    >>> r * r == 2, r > Fraction(141, 100), r.approx(20)
    (True, True, '1.4142135623730950488')
    >>> r.decimal(20), r.compare(Fraction(1414, 1000)), sign_at([-2, 0, 1], r)
    ('1.41421356237309504880', 1, 0)
    """

    __slots__ = ("_hi", "_index", "_lo", "_minpoly", "_z")
    _minpoly: tuple[Fraction, ...] | None
    _z: Any  # the primitive integer minimal polynomial, when the number was made from it
    _index: int | None
    _lo: Fraction
    _hi: Fraction

    def __init__(self, value: Any) -> None:
        if isinstance(value, RealAlgebraic):
            self._minpoly, self._z = value._minpoly, value._z
            self._index, self._lo, self._hi = value._index, value._lo, value._hi
            return
        v = Fraction(value)
        self.minpoly = (-v, Fraction(1))
        self._index = 0
        self._lo = self._hi = v

    @property
    def minpoly(self) -> tuple[Fraction, ...]:
        """The coefficients of the monic minimal polynomial (read off the integer polynomial
        when first asked for, for a number made by ``_from_integer_polynomial``)."""
        m = self._minpoly
        if m is None:
            m = self._minpoly = _key(self._z)
        return m

    @minpoly.setter
    def minpoly(self, key: tuple[Fraction, ...]) -> None:
        self._minpoly = key
        self._z = None

    @classmethod
    def _from_integer_polynomial(cls, z: Any, lo: Fraction, hi: Fraction) -> RealAlgebraic:
        """The only root in ``[lo, hi]`` (``lo < hi``) of ``z``, an irreducible primitive
        ``fmpz_poly`` of degree at least 2 with a positive leading coefficient (not checked);
        its monic rational coefficients are formed only if :attr:`minpoly` is read."""
        obj = cls.__new__(cls)
        obj._minpoly = None
        obj._z = z
        obj._index = None
        obj._lo, obj._hi = lo, hi
        return obj

    @classmethod
    def _make(cls, key: tuple[Fraction, ...], index: int) -> RealAlgebraic:
        obj = cls.__new__(cls)
        obj.minpoly = key
        obj._index = index
        obj._lo, obj._hi = _isolate_all(key)[index]
        return obj

    @classmethod
    def _from_interval(
        cls, key: tuple[Fraction, ...], lo: Fraction, hi: Fraction, index: int | None = None
    ) -> RealAlgebraic:
        obj = cls.__new__(cls)
        obj.minpoly = key
        obj._index = index
        obj._lo, obj._hi = lo, hi
        return obj

    @classmethod
    def root_in(cls, poly: Any, lo: Fraction, hi: Fraction) -> RealAlgebraic:
        """The root of the irreducible polynomial ``poly`` in ``[lo, hi]``.

        Parameters
        ----------
        poly : fmpq_poly, fmpz_poly or coefficients ``c0, c1, ...``
            Irreducible over Q, with exactly one root in ``[lo, hi]`` (checked:
            a sign change for degree > 1).

        Examples
        --------
        >>> RealAlgebraic.root_in([-2, 0, 1], Fraction(1), Fraction(2)).decimal(5)
        '1.41421'
        """
        p = poly if isinstance(poly, (flint.fmpq_poly, flint.fmpz_poly)) else fmpq_poly_of(poly)
        key = _key(p)
        if len(key) == 2:
            return cls(-key[0])
        q = fmpq_poly_of(key)
        if not (lo < hi and _sign_rational(q, lo) * _sign_rational(q, hi) < 0):
            raise ValueError(f"[{lo}, {hi}] does not isolate a root of {p}")
        return cls._from_interval(key, Fraction(lo), Fraction(hi))

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as the minimal polynomial and the isolating interval (for worker processes)."""
        return (RealAlgebraic._from_interval, (self.minpoly, self._lo, self._hi, self._index))

    @classmethod
    def sqrt(cls, value: Any) -> RealAlgebraic:
        """The non-negative square root of a non-negative rational."""
        v = Fraction(value)
        if v < 0:
            raise ValueError(f"sqrt of a negative number {v}")
        n, d = v.numerator, v.denominator
        rn, rd = math.isqrt(n), math.isqrt(d)
        if rn * rn == n and rd * rd == d:
            return cls(Fraction(rn, rd))
        return real_roots([-v, 0, 1])[1]

    # -- properties -----------------------------------------------------------------

    @property
    def degree(self) -> int:
        return len(self._minpoly) - 1 if self._minpoly is not None else int(self._z.degree())

    @property
    def is_rational(self) -> bool:
        return self.degree == 1

    @property
    def value(self) -> Fraction | None:
        """The exact value when rational, else None."""
        return self._lo if self.is_rational else None

    def as_fraction(self) -> Fraction:
        """The value if rational, else ValueError."""
        if not self.is_rational:
            raise ValueError(f"{self} is irrational")
        return self._lo

    @property
    def poly(self) -> Any:
        """The minimal polynomial as an ``fmpq_poly`` (monic)."""
        if self._minpoly is None:
            return flint.fmpq_poly(self._z) / self._z.leading_coefficient()
        return fmpq_poly_of(self._minpoly)

    @property
    def integer_poly(self) -> Any:
        """The minimal polynomial made primitive over Z (``fmpz_poly``, positive leading coefficient)."""
        return self._z if self._minpoly is None else _primitive(self.poly)

    @property
    def interval(self) -> tuple[Fraction, Fraction]:
        """The current isolating interval (``lo == hi`` for a rational)."""
        return self._lo, self._hi

    @property
    def lo(self) -> Fraction:
        return self._lo

    @property
    def hi(self) -> Fraction:
        return self._hi

    @property
    def index(self) -> int:
        if self._index is None:
            q = self.poly
            for i, (a, b) in enumerate(_isolate_all(self.minpoly)):
                lo, hi = max(a, self._lo), min(b, self._hi)
                if lo < hi and _sign_rational(q, lo) != _sign_rational(q, hi):
                    self._index = i
                    break
            else:  # pragma: no cover - would mean a wrong isolating interval
                raise AssertionError("root lost")
        return self._index

    # -- refinement and approximation -------------------------------------------------

    def bisect(self) -> None:
        """Halve the isolating interval (exactly; near the middle, at a short rational)."""
        if self.is_rational:
            return
        p = self.poly
        mid = near_midpoint(self._lo, self._hi)
        s = _sign_rational(p, mid)
        assert s != 0, "an irreducible polynomial of degree >= 2 has no rational root"
        if s == _sign_rational(p, self._lo):
            self._lo = mid
        else:
            self._hi = mid

    def refine(self, width: Fraction) -> None:
        """Bisect the isolating interval until it is shorter than ``width``."""
        if self.is_rational:
            return
        p = self.poly
        lo, hi = self._lo, self._hi
        slo = _sign_rational(p, lo)
        while hi - lo >= width:
            mid = near_midpoint(lo, hi)
            if _sign_rational(p, mid) == slo:
                lo = mid
            else:
                hi = mid
        self._lo, self._hi = lo, hi

    def enclosure(self, bits: int | None = None) -> Any:
        """An ``arb`` ball containing the number, about ``bits`` bits wide
        (default: the current flint precision)."""
        if self.is_rational:
            return flint.arb(fmpq_of(self._lo))
        bits = bits or flint.ctx.prec
        self.sign()  # the interval no longer contains 0: refine to relative precision
        self.refine(min(abs(self._lo), abs(self._hi)) / 2**bits)
        return _arb_interval(self._lo, self._hi)

    def approx(self, digits: int = 15) -> str:
        """A decimal string correct to ``digits`` significant digits (rounded)."""
        if self.is_rational and self._lo == 0:
            return "0"
        bits = int(digits * 3.33) + 16
        with working_precision(bits):
            x = self.enclosure(bits)
            return str(x.str(digits, radius=False))

    def rational_near(self, places: int) -> Fraction:
        """A rational within ``10**-places`` of this number (exact refinement)."""
        if self.is_rational:
            return self._lo
        self.refine(Fraction(1, 10**places))
        return (self._lo + self._hi) / 2

    def decimal(self, places: int = 12) -> str:
        """This number rounded to ``places`` decimal places (correctly rounded: error at most half a unit)."""
        if self.is_rational:
            scaled = round(self._lo * 10**places)
        else:  # correctly rounded: refine until both ends round alike (never at a tie: irrational)
            scale, half = 10**places, Fraction(1, 2)
            while math.floor(self._lo * scale + half) != math.floor(self._hi * scale + half):
                self.bisect()
            scaled = math.floor(self._lo * scale + half)
        minus = "-" if scaled < 0 else ""
        s = str(abs(scaled)).rjust(places + 1, "0")
        return f"{minus}{s[:-places]}.{s[-places:]}" if places else f"{minus}{s}"

    def __float__(self) -> float:
        if self.is_rational:
            return float(self._lo)
        self.refine(Fraction(1, 1 << 60) * max(Fraction(1), abs(self._lo)))
        return float((self._lo + self._hi) / 2)

    # -- exact sign and comparison --------------------------------------------------

    def sign(self) -> int:
        """-1, 0 or +1, exactly."""
        if self.is_rational:
            return sign(self._lo)
        # An irreducible polynomial of degree >= 2 does not vanish at 0; the
        # isolating interval shrinks until it does not contain 0.
        while self._lo <= 0 <= self._hi:
            self.bisect()
        return 1 if self._lo > 0 else -1

    def compare(self, other: Any) -> int:
        """-1, 0 or 1 as this number is below, equal to or above ``other`` (exact)."""
        if not isinstance(other, RealAlgebraic):
            x = Fraction(other)
            if self.is_rational:
                return sign(self._lo - x)
            if x <= self._lo:
                return 1
            if x >= self._hi:
                return -1
            p = self.poly
            s = _sign_rational(p, x)
            # the root lies where the sign changes: in (lo, x) if sign(x) != sign(lo)
            if s == _sign_rational(p, self._lo):
                self._lo = x
                return 1
            self._hi = x
            return -1
        if other.is_rational:
            return self.compare(other._lo)
        if self.is_rational:
            return -other.compare(self._lo)
        if self.minpoly == other.minpoly:
            if self._index is not None and other._index is not None:
                return sign(self._index - other._index)
            # each interval holds exactly one root of the polynomial, so they hold the same
            # root iff their common part does, i.e. the polynomial changes sign across it
            lo, hi = max(self._lo, other._lo), min(self._hi, other._hi)
            p = self.poly
            if lo < hi and _sign_rational(p, lo) != _sign_rational(p, hi):
                return 0
        while True:  # distinct numbers: separate the intervals
            if self._hi < other._lo:
                return -1
            if other._hi < self._lo:
                return 1
            if self._hi - self._lo >= other._hi - other._lo:
                self.bisect()
            else:
                other.bisect()

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (RealAlgebraic, int, Fraction)):
            return self.compare(other) == 0
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self._lo) if self.is_rational else hash(self.minpoly)

    def __lt__(self, other: Any) -> bool:
        return self.compare(other) < 0

    def __le__(self, other: Any) -> bool:
        return self.compare(other) <= 0

    def __gt__(self, other: Any) -> bool:
        return self.compare(other) > 0

    def __ge__(self, other: Any) -> bool:
        return self.compare(other) >= 0

    # -- arithmetic (exact, through algebraic_value) -----------------------------------

    def _binary(self, other: Any, fn: Callable[[Any, Any], Any]) -> RealAlgebraic:
        o = other if isinstance(other, RealAlgebraic) else RealAlgebraic(other)
        return algebraic_value(fn, [self, o])

    def __add__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: a + b)

    __radd__ = __add__

    def __sub__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: a - b)

    def __rsub__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: b - a)

    def __mul__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: a * b)

    __rmul__ = __mul__

    def __truediv__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: a / b)

    def __rtruediv__(self, other: Any) -> RealAlgebraic:
        return self._binary(other, lambda a, b: b / a)

    def __neg__(self) -> RealAlgebraic:
        return algebraic_value(lambda a: -a, [self])

    def __pow__(self, n: int) -> RealAlgebraic:
        return algebraic_value(lambda a: a**n, [self])

    # -- presentation ----------------------------------------------------------------

    def poly_str(self, var: str = "x", *, integer: bool = False) -> str:
        """The minimal polynomial in ``var``: monic, or primitive over Z with ``integer``."""
        import sympy  # sympy is heavy: only to print

        x = sympy.Symbol(var)
        if integer:
            return str(sympy.Poly([int(c) for c in reversed(self.integer_poly.coeffs())], x).as_expr())
        return str(
            sum((sympy.Rational(c.numerator, c.denominator) * x**k for k, c in enumerate(self.minpoly)))
        )

    def to_dict(self, places: int = 20) -> dict[str, Any]:
        """The number for a report: decimals, and the exact value or its polynomial and interval."""
        out: dict[str, Any] = {"decimal": self.decimal(places)}
        if self.is_rational:
            out["exact"] = str(self._lo)
        else:
            out["root_of"] = self.poly_str("t", integer=True)
            out["interval"] = [str(self._lo), str(self._hi)]
        return out

    def to_sympy(self) -> Any:
        """``Rational`` or ``CRootOf`` (same root index convention)."""
        import sympy  # sympy is heavy: only for sympy output

        if self.is_rational:
            v = self._lo
            return sympy.Rational(v.numerator, v.denominator)
        x = sympy.Symbol("x")
        den = math.lcm(*(c.denominator for c in self.minpoly))
        expr = sum(int(c * den) * x**k for k, c in enumerate(self.minpoly))
        return sympy.CRootOf(expr, self.index)

    def __repr__(self) -> str:
        if self.is_rational:
            return f"RealAlgebraic({self._lo})"
        return f"RealAlgebraic(root {self.index + 1} of {self.poly_str()}, ~{self.approx(12)})"

    def __str__(self) -> str:
        if self.is_rational:
            return str(self._lo)
        return f"{self.approx(15)} (root {self.index + 1} of {self.poly_str()})"


def rational_between(left: Any, right: Any) -> Fraction:
    """A short dyadic rational strictly between two numbers (rationals or :class:`RealAlgebraic`).

    Examples
    --------
    >>> x = rational_between(RealAlgebraic.sqrt(2), RealAlgebraic.sqrt(3))
    >>> RealAlgebraic.sqrt(2) < x < RealAlgebraic.sqrt(3), x.denominator & (x.denominator - 1) == 0
    (True, True)
    """
    if isinstance(left, RealAlgebraic) and left.is_rational:
        left = left.as_fraction()
    if isinstance(right, RealAlgebraic) and right.is_rational:
        right = right.as_fraction()
    if isinstance(left, RealAlgebraic):
        if isinstance(right, RealAlgebraic):
            while left.compare(right) < 0 and not left.hi < right.lo:
                (left if left.hi - left.lo >= right.hi - right.lo else right).bisect()
        else:
            while not left.hi < right:
                left.bisect()
        lo = left.hi
    else:
        lo = Fraction(left)
    if isinstance(right, RealAlgebraic):
        while not lo < right.lo:
            right.bisect()
        hi = right.lo
    else:
        hi = Fraction(right)
    return dyadic_between(lo, hi)


def sign_at(poly: Any, x: Any, ledger: Counter | None = None) -> int:
    """The exact sign of a polynomial over Q at a rational or real algebraic number.

    Zero exactly when the minimal polynomial of ``x`` divides ``poly``;
    otherwise an exact Taylor bound at the middle of the isolating interval
    decides, the interval being bisected (each time counted as an
    ``escalations`` in ``ledger``) until the bound excludes 0.

    Parameters
    ----------
    poly : fmpq_poly, fmpz_poly or sequence of rationals ``c0, c1, ...``
    x : Fraction, int or RealAlgebraic
    ledger : optional
        Where to count the refinements.

    Returns
    -------
    int
        -1, 0 or 1.

    Examples
    --------
    >>> from fractions import Fraction
    >>> r = algebraic_sqrt(Fraction(1, 10))
    >>> sign_at([Fraction(-1, 10), 0, 1], r), sign_at([Fraction(-1, 3), 1], r), sign_at([-1, 1], 2)
    (0, -1, 1)
    """
    g = flint.fmpq_poly(poly) if isinstance(poly, (flint.fmpq_poly, flint.fmpz_poly)) else fmpq_poly_of(poly)
    if g.is_zero():
        return 0
    if not isinstance(x, RealAlgebraic):
        return _sign_rational(g, Fraction(x))
    if x.is_rational:
        return _sign_rational(g, x.as_fraction())
    r = g % x.poly
    if r.is_zero():
        return 0
    if r.degree() == 0:
        return sign(fraction_of(r[0]))
    # g(x) != 0.  Taylor expansion at the midpoint m, exact in rationals:
    # g(m + s) = a0 + a1 s + ..., so |g(x) - a0| <= sum_{k>=1} |a_k| h^k with h the
    # half-width.  (Not done on the remainder r: reducing modulo the minimal polynomial
    # can put a root of r next to x; nor with interval Horner, which loses the
    # cancellation between large coefficients.)
    first = True
    while True:
        lo, hi = x.interval
        mid, h = (lo + hi) / 2, (hi - lo) / 2
        cs = g(flint.fmpq_poly([fmpq_of(mid), 1])).coeffs()
        a0 = fraction_of(cs[0]) if cs else Fraction(0)
        tail = fraction_of(flint.fmpq_poly([abs(c) for c in cs])(fmpq_of(h))) - abs(a0)
        if a0 != 0 and abs(a0) > tail:
            return sign(a0)
        if first and ledger is not None:
            ledger.add("escalations")
        first = False
        ratio = tail / abs(a0) if a0 != 0 else Fraction(256)
        steps = max(1, ratio.numerator.bit_length() - ratio.denominator.bit_length() + 2)
        for _ in range(steps):
            x.bisect()


# -- expressions ---------------------------------------------------------------------


def compile_expression(expr: Any, symbols: Sequence[Any]) -> Callable[..., Any]:
    """Compile a sympy rational expression into a function of its symbols that
    runs on any number type with ``+ - * /`` and integer powers.

    Rational constants are passed through ``const`` (the keyword argument of
    the returned function, default :class:`fractions.Fraction`), so the same
    compiled expression evaluates on Fractions, arb balls and matrices.
    """
    import sympy  # sympy is heavy: only for sympy input

    index = {s: i for i, s in enumerate(symbols)}

    def build(e: Any) -> Callable[[Sequence[Any], Callable[[Fraction], Any]], Any]:
        if e in index:
            i = index[e]
            return lambda v, c: v[i]
        if e.is_Rational:
            q = Fraction(int(e.p), int(e.q))
            return lambda v, c: c(q)
        if e.is_Add:
            parts = [build(a) for a in e.args]

            def add(v: Sequence[Any], c: Callable[[Fraction], Any]) -> Any:
                acc = parts[0](v, c)
                for p in parts[1:]:
                    acc = acc + p(v, c)
                return acc

            return add
        if e.is_Mul:
            parts = [build(a) for a in e.args]

            def mul(v: Sequence[Any], c: Callable[[Fraction], Any]) -> Any:
                acc = parts[0](v, c)
                for p in parts[1:]:
                    acc = acc * p(v, c)
                return acc

            return mul
        if e.is_Pow and e.exp.is_Integer:
            base = build(e.base)
            n = int(e.exp)
            if n >= 0:
                return lambda v, c: base(v, c) ** n
            return lambda v, c: c(Fraction(1)) / base(v, c) ** (-n)
        raise ValueError(f"not a rational expression in {symbols}: {e} ({sympy.srepr(e)[:60]})")

    if isinstance(expr, (str, bytes)):
        # Text is never evaluated (sympify would run it as Python): build the
        # expression with sympy, or read text with quadric_contact.exact.reading.
        raise EquationError(
            "compile_expression takes a sympy expression, not text "
            "(read text with quadric_contact.exact.reading)",
            expr,
        )
    fn = build(sympy.sympify(expr, strict=True))

    def run(*values: Any, const: Callable[[Fraction], Any] = Fraction) -> Any:
        return fn(values, const)

    run.takes_const = True  # type: ignore[attr-defined]
    return run


class _Elem:
    """An element of a finite-dimensional commutative Q-algebra, as its
    multiplication matrix (``fmpq_mat``)."""

    __slots__ = ("m",)

    def __init__(self, m: Any) -> None:
        self.m = m

    @staticmethod
    def scalar(q: Fraction, n: int) -> _Elem:
        entries = [(fmpq_of(q) if i == j else 0) for i in range(n) for j in range(n)]
        return _Elem(flint.fmpq_mat(n, n, entries))

    def _lift(self, o: Any) -> _Elem:
        if isinstance(o, _Elem):
            return o
        return _Elem.scalar(Fraction(o), self.m.nrows())

    def __add__(self, o: Any) -> _Elem:
        return _Elem(self.m + self._lift(o).m)

    __radd__ = __add__

    def __sub__(self, o: Any) -> _Elem:
        return _Elem(self.m - self._lift(o).m)

    def __rsub__(self, o: Any) -> _Elem:
        return _Elem(self._lift(o).m - self.m)

    def __mul__(self, o: Any) -> _Elem:
        return _Elem(self.m * self._lift(o).m)

    __rmul__ = __mul__

    def __truediv__(self, o: Any) -> _Elem:
        return _Elem(self.m * self._lift(o).m.inv())

    def __rtruediv__(self, o: Any) -> _Elem:
        return _Elem(self._lift(o).m * self.m.inv())

    def __neg__(self) -> _Elem:
        return _Elem(-self.m)

    def __pow__(self, n: int) -> _Elem:
        r = _Elem.scalar(Fraction(1), self.m.nrows())
        b = self
        while n:
            if n & 1:
                r = r * b
            b = b * b
            n >>= 1
        return r


class _Ball:
    """An arb ball that also accepts int and Fraction operands."""

    __slots__ = ("x",)

    def __init__(self, x: Any) -> None:
        self.x = x

    @staticmethod
    def _v(o: Any) -> Any:
        if isinstance(o, _Ball):
            return o.x
        if isinstance(o, (int, Fraction)):
            return flint.arb(fmpq_of(o))
        return o

    def __add__(self, o: Any) -> _Ball:
        return _Ball(self.x + self._v(o))

    __radd__ = __add__

    def __sub__(self, o: Any) -> _Ball:
        return _Ball(self.x - self._v(o))

    def __rsub__(self, o: Any) -> _Ball:
        return _Ball(self._v(o) - self.x)

    def __mul__(self, o: Any) -> _Ball:
        return _Ball(self.x * self._v(o))

    __rmul__ = __mul__

    def __truediv__(self, o: Any) -> _Ball:
        return _Ball(self.x / self._v(o))

    def __rtruediv__(self, o: Any) -> _Ball:
        return _Ball(self._v(o) / self.x)

    def __neg__(self) -> _Ball:
        return _Ball(-self.x)

    def __pow__(self, n: int) -> _Ball:
        # by squaring: arb's ``**`` is exp(n log x), NaN on a ball that holds 0
        r, b = flint.arb(1), self.x
        k = abs(n)
        while k:
            if k & 1:
                r = r * b
            b = b * b
            k >>= 1
        return _Ball(r if n >= 0 else 1 / r)


def _companion(key: tuple[Fraction, ...]) -> list[list[Fraction]]:
    """Multiplication by x on the basis 1, x, .., x^(d-1) of Q[x]/(p), p monic."""
    d = len(key) - 1
    m = [[Fraction(0)] * d for _ in range(d)]
    for i in range(1, d):
        m[i][i - 1] = Fraction(1)
    for i in range(d):
        m[i][d - 1] = -key[i]
    return m


def _kron_generators(keys: Sequence[tuple[Fraction, ...]]) -> list[Any]:
    """Multiplication matrices of the generators of the tensor product of the
    algebras Q[x_i]/(p_i)."""
    dims = [len(k) - 1 for k in keys]
    n = math.prod(dims)
    gens = []
    for j, key in enumerate(keys):
        comp = _companion(key)
        before = math.prod(dims[:j])
        after = math.prod(dims[j + 1 :])
        dj = dims[j]
        entries = [0] * (n * n)
        for b in range(before):
            for r in range(dj):
                for c in range(dj):
                    v = comp[r][c]
                    if v == 0:
                        continue
                    for a in range(after):
                        row = (b * dj + r) * after + a
                        col = (b * dj + c) * after + a
                        entries[row * n + col] = fmpq_of(v)
        gens.append(flint.fmpq_mat(n, n, entries))
    return gens


def algebraic_value(fn: Callable[..., Any], args: Sequence[Any]) -> RealAlgebraic:
    """The exact value of a rational function at real algebraic numbers.

    Parameters
    ----------
    fn : callable
        Built from ``+ - * /`` and integer powers only, with integer or
        Fraction constants (or a :func:`compile_expression`; its ``const``
        hook is used when present).
    args : sequence of RealAlgebraic (or rationals)

    Returns
    -------
    RealAlgebraic

    Raises
    ------
    ZeroDivisionError
        If a denominator vanishes at the given numbers.

    Notes
    -----
    ``fn`` is evaluated on the multiplication matrices of the tensor product
    of the fields ``Q(a_i)``; the minimal polynomial of that matrix has the
    value among its roots, and certified ball evaluation picks the root.
    A denominator must not vanish at any conjugate of the arguments (the
    matrix would be singular): ZeroDivisionError is raised then.
    """
    vals = [a if isinstance(a, RealAlgebraic) else RealAlgebraic(a) for a in args]
    takes_const = getattr(fn, "takes_const", False)
    if all(v.is_rational for v in vals):
        fr = [v.as_fraction() for v in vals]
        return RealAlgebraic(fn(*fr))
    # Distinct irrational numbers (same minpoly and index = same number).
    keys: list[tuple[tuple[Fraction, ...], int]] = []
    for v in vals:
        if not v.is_rational and (v.minpoly, v.index) not in keys:
            keys.append((v.minpoly, v.index))
    gens = _kron_generators([k for k, _ in keys])
    n = gens[0].nrows()
    elems: list[Any] = []
    for v in vals:
        if v.is_rational:
            elems.append(_Elem.scalar(v.as_fraction(), n))
        else:
            elems.append(_Elem(gens[keys.index((v.minpoly, v.index))]))

    def const_mat(q: Fraction) -> _Elem:
        return _Elem.scalar(q, n)

    try:
        M = fn(*elems, const=const_mat) if takes_const else fn(*elems)
    except ZeroDivisionError:
        M = None
    mp = M.m.minpoly() if isinstance(M, _Elem) else None

    def enclose(bits: int) -> Any:
        with working_precision(bits):
            ballargs = [v.enclosure(bits) for v in vals]

            def const_arb(q: Fraction) -> Any:
                return flint.arb(fmpq_of(q))

            try:
                if takes_const:
                    return fn(*ballargs, const=const_arb)
                out = fn(*(_Ball(b) for b in ballargs))
                return out.x if isinstance(out, _Ball) else flint.arb(fmpq_of(out))
            except ZeroDivisionError:
                return flint.arb("0 +/- inf")

    if mp is None:
        raise ZeroDivisionError("a denominator vanishes at a conjugate of the arguments")
    candidates = real_roots(mp)
    bits = 64
    while True:
        enc = enclose(bits)
        if not enc.is_finite():
            x = enc
            if bits > 4096:
                raise ZeroDivisionError("a denominator vanishes at the given algebraic numbers")
        else:
            x = enc
            hits = [c for c in candidates if _overlaps(c, x)]
            if len(hits) == 1:
                return hits[0]
            if not hits:  # pragma: no cover - would mean a wrong enclosure
                raise AssertionError("value lost during algebraic evaluation")
            _narrow(hits, bits)
            hits = [c for c in hits if _overlaps(c, x)]
            if len(hits) == 1:
                return hits[0]
        bits *= 2


def algebraic_sqrt(x: Any) -> RealAlgebraic:
    """The non-negative square root of a non-negative real algebraic number, exactly.

    It is a root of ``m(t^2)`` (``m`` the minimal polynomial of ``x``); the
    irreducible factor and the root are picked by certified evaluation.

    Parameters
    ----------
    x : RealAlgebraic or rational

    Returns
    -------
    RealAlgebraic

    Examples
    --------
    The bee's longest semi-axis in Example 17, ``sqrt(1/10)``:

    >>> from fractions import Fraction
    >>> algebraic_sqrt(Fraction(1, 10)).approx(6)
    '0.316228'
    """
    v = x if isinstance(x, RealAlgebraic) else RealAlgebraic(x)
    s = v.sign()
    if s < 0:
        raise ValueError(f"square root of a negative number {v}")
    if s == 0:
        return RealAlgebraic(0)
    if v.is_rational:
        return RealAlgebraic.sqrt(v.as_fraction())
    coeffs: list[Fraction] = []
    for c in v.minpoly:
        coeffs.extend([c, Fraction(0)])
    candidates = [r for r in real_roots(coeffs[:-1]) if r.sign() > 0]
    bits = 64
    while True:
        with working_precision(bits):
            enc = v.enclosure(bits).sqrt()
        hits = [c for c in candidates if _overlaps(c, enc)]
        if len(hits) == 1:
            return hits[0]
        _narrow(hits, bits)
        hits = [c for c in hits if _overlaps(c, enc)]
        if len(hits) == 1:
            return hits[0]
        bits *= 2


def _narrow(hits: list[RealAlgebraic], bits: int) -> None:
    """Narrow the candidate roots as far as an enclosure at ``bits`` bits is narrow (relative
    width about ``2^-bits``): two roots closer than their isolating intervals are wide are then
    told apart at this precision, instead of by doubling the precision while the intervals
    shrink by a constant factor (exponential in the roots' separation)."""
    for c in hits:
        if not c.is_rational:
            c.refine(max(abs(c.lo), abs(c.hi), Fraction(1)) / 2**bits)


def _overlaps(c: RealAlgebraic, ball: Any) -> bool:
    """The isolating interval of ``c`` meets the ball ``[mid - rad, mid + rad]``, read exactly.

    Not ``ball.lower()``/``ball.upper()``: they round to the precision in force when they are
    called, and a ball computed at thousands of bits read at 53 would be a 2^-52-wide interval
    (two close roots would then overlap it at every precision)."""
    mid = fraction_of(ball.mid())
    rad = fraction_of(ball.rad())
    return not (c._hi < mid - rad or mid + rad < c._lo)


def evaluate_arb(fn: Callable[..., Any], args: Sequence[RealAlgebraic], bits: int) -> Any:
    """A certified ball for ``fn(args)`` at ``bits`` bits (diagnostics, decimals)."""
    with working_precision(bits):
        balls = [a.enclosure(bits) for a in args]
        return fn(*balls, const=lambda q: flint.arb(fmpq_of(q)))


# -- Q(sqrt d) ------------------------------------------------------------------------


def _squarefree_part(n: int) -> tuple[int, int]:
    """``n = s * k^2`` with ``s`` squarefree: returns ``(s, k)`` (n > 0)."""
    s, k = 1, 1
    m = n
    p = 2
    while p * p <= m:
        while m % (p * p) == 0:
            m //= p * p
            k *= p
        if m % p == 0:
            m //= p
            s *= p
        p += 1
    return s * m, k


class QuadraticNumber:
    """``a + b*sqrt(d)`` with rational ``a, b`` and a squarefree integer ``d > 1``
    (``d = 1`` means the rationals); exact arithmetic and sign.

    Examples
    --------
    >>> r = QuadraticNumber.sqrt(Fraction(8, 9))
    >>> r, r * r, (r - 1).sign()
    (QuadraticNumber(0 + 2/3*sqrt(2)), QuadraticNumber(8/9), -1)
    """

    __slots__ = ("a", "b", "d")

    def __init__(self, a: Any = 0, b: Any = 0, d: int = 1) -> None:
        self.a = Fraction(a)
        self.b = Fraction(b) if d != 1 else Fraction(0)
        if d == 1:
            self.a += Fraction(b)
        self.d = d if self.b != 0 else 1

    @classmethod
    def sqrt(cls, q: Any) -> QuadraticNumber:
        """``sqrt(q)`` for a rational ``q >= 0``."""
        q = Fraction(q)
        if q < 0:
            raise ValueError("negative radicand")
        if q == 0:
            return cls(0)
        num = q.numerator * q.denominator  # sqrt(n/m) = sqrt(n*m)/m
        s, k = _squarefree_part(num)
        return cls(0, Fraction(k, q.denominator), s) if s != 1 else cls(Fraction(k, q.denominator))

    def _field(self, o: QuadraticNumber) -> int:
        if self.d == 1:
            return o.d
        if o.d == 1 or o.d == self.d:
            return self.d
        raise ValueError(f"mixing Q(sqrt {self.d}) and Q(sqrt {o.d})")

    @staticmethod
    def _of(o: Any) -> QuadraticNumber:
        return o if isinstance(o, QuadraticNumber) else QuadraticNumber(Fraction(o))

    def __add__(self, o: Any) -> QuadraticNumber:
        o = self._of(o)
        return QuadraticNumber(self.a + o.a, self.b + o.b, self._field(o))

    __radd__ = __add__

    def __neg__(self) -> QuadraticNumber:
        return QuadraticNumber(-self.a, -self.b, self.d)

    def __sub__(self, o: Any) -> QuadraticNumber:
        return self + (-self._of(o))

    def __rsub__(self, o: Any) -> QuadraticNumber:
        return self._of(o) - self

    def __mul__(self, o: Any) -> QuadraticNumber:
        o = self._of(o)
        d = self._field(o)
        return QuadraticNumber(self.a * o.a + self.b * o.b * d, self.a * o.b + self.b * o.a, d)

    __rmul__ = __mul__

    def conjugate(self) -> QuadraticNumber:
        return QuadraticNumber(self.a, -self.b, self.d)

    def norm(self) -> Fraction:
        return self.a * self.a - self.b * self.b * self.d

    def inverse(self) -> QuadraticNumber:
        n = self.norm()
        if n == 0:
            raise ZeroDivisionError("division by zero in Q(sqrt d)")
        c = self.conjugate()
        return QuadraticNumber(c.a / n, c.b / n, self.d)

    def __truediv__(self, o: Any) -> QuadraticNumber:
        return self * self._of(o).inverse()

    def __rtruediv__(self, o: Any) -> QuadraticNumber:
        return self._of(o) * self.inverse()

    def is_zero(self) -> bool:
        return self.a == 0 and self.b == 0

    def __bool__(self) -> bool:
        return not self.is_zero()

    def sign(self) -> int:
        """Exact sign (compare ``a^2`` with ``b^2 d`` when the signs differ)."""
        sa, sb = sign(self.a), sign(self.b)
        if sb == 0:
            return sa
        if sa == 0 or sa == sb:
            return sb
        return sa if self.a * self.a > self.b * self.b * self.d else sb

    def __eq__(self, o: object) -> bool:
        if isinstance(o, (QuadraticNumber, int, Fraction)):
            return (self - o).is_zero()
        return NotImplemented

    def __hash__(self) -> int:
        return hash((self.a, self.b, self.d))

    def __lt__(self, o: Any) -> bool:
        return (self - o).sign() < 0

    def __gt__(self, o: Any) -> bool:
        return (self - o).sign() > 0

    def __float__(self) -> float:
        return float(self.a) + float(self.b) * math.sqrt(self.d)

    def to_sympy(self) -> Any:
        import sympy  # sympy is heavy: only for sympy output

        return sympy.Rational(self.a.numerator, self.a.denominator) + sympy.Rational(
            self.b.numerator, self.b.denominator
        ) * sympy.sqrt(self.d)

    def __repr__(self) -> str:
        if self.d == 1:
            return f"QuadraticNumber({self.a})"
        return f"QuadraticNumber({self.a} + {self.b}*sqrt({self.d}))"


def as_real_algebraic(x: Any) -> RealAlgebraic:
    """A rational, a :class:`QuadraticNumber` or a :class:`RealAlgebraic` as a RealAlgebraic."""
    if isinstance(x, RealAlgebraic):
        return x
    if isinstance(x, QuadraticNumber):
        if x.d == 1:
            return RealAlgebraic(x.a)
        root = RealAlgebraic.sqrt(x.d)
        return algebraic_value(lambda r, a, b: a + b * r, [root, RealAlgebraic(x.a), RealAlgebraic(x.b)])
    return RealAlgebraic(x)


def values_in(mapping: Mapping[str, Any]) -> dict[str, str]:
    """Decimal strings of a mapping of algebraic numbers (for reports)."""
    return {k: (v.approx(15) if isinstance(v, RealAlgebraic) else str(v)) for k, v in mapping.items()}
