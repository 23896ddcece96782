"""Exact real algebraic numbers: isolation, comparison, arithmetic.

The invariants of Section 2.4 (eigenvalues of ``Q00``, the semi-axes and
curvatures built from them) and the critical values of the geometric
decision are real algebraic numbers.  They are compared here *exactly*:

* A :class:`RealAlgebraic` is the unique root of a monic polynomial
  irreducible over Q (its minimal polynomial) inside a rational isolating
  interval, together with its index among the real roots of that
  polynomial.  Two of them are equal exactly when they have the same minimal
  polynomial and the same index; otherwise their isolating intervals are
  refined (exact bisection on rational endpoints) until they are disjoint.
  No tolerance is involved anywhere.
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

Isolation uses FLINT's certified complex root finder (real roots are
returned with an exactly zero imaginary part, each ball isolating one root);
refinement is exact bisection.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator, Mapping, Sequence
from fractions import Fraction
from functools import lru_cache
from itertools import pairwise
from typing import Any

import flint

from .errors import EquationError

__all__ = [
    "QuadraticNumber",
    "RealAlgebraic",
    "algebraic_sqrt",
    "algebraic_value",
    "as_real_algebraic",
    "compile_expression",
    "real_roots",
    "sign_at",
    "workprec",
]


# -- flint helpers ---------------------------------------------------------------------


@contextlib.contextmanager
def workprec(bits: int) -> Iterator[None]:
    """Scoped working precision (bits) for flint ball arithmetic."""
    old = flint.ctx.prec
    flint.ctx.prec = bits
    try:
        yield
    finally:
        flint.ctx.prec = old


def _fmpq(x: Fraction | int) -> Any:
    x = Fraction(x)
    return flint.fmpq(x.numerator, x.denominator)


def _frac(x: Any) -> Fraction:
    """An exact flint number (fmpq, fmpz, or an exact arb/arf) as a Fraction."""
    if isinstance(x, flint.fmpq):
        return Fraction(int(x.p), int(x.q))
    if isinstance(x, flint.fmpz):
        return Fraction(int(x))
    man, exp = x.man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def _poly(coeffs: Sequence[Any]) -> Any:
    """``fmpq_poly`` from coefficients ``c0, c1, ...`` (ints, Fractions or fmpq)."""
    return flint.fmpq_poly([c if isinstance(c, (flint.fmpq, flint.fmpz)) else _fmpq(c) for c in coeffs])


def _monic(p: Any) -> Any:
    return p / p.leading_coefficient()


def _key(p: Any) -> tuple[Fraction, ...]:
    return tuple(_frac(c) for c in p.coeffs())


def _eval_frac(p: Any, x: Fraction) -> Fraction:
    return _frac(p(_fmpq(x)))


def _arb_interval(lo: Fraction, hi: Fraction) -> Any:
    """The ball ``[lo, hi]`` (exactly enclosing the interval at the current precision)."""
    mid = (lo + hi) / 2
    rad = (hi - lo) / 2
    # arb(mid, rad) rounds mid; widen the radius by the rounding error bound.
    m = flint.arb(_fmpq(mid))
    r = flint.arb(_fmpq(rad))
    return flint.arb(m.mid(), (r + m.rad()).upper())


def _arb_eval(p: Any, x: Any) -> Any:
    acc = flint.arb(0)
    for c in reversed(p.coeffs()):
        acc = acc * x + flint.arb(c)
    return acc


# -- isolation -------------------------------------------------------------------------


@lru_cache(maxsize=4096)
def _isolate(key: tuple[Fraction, ...]) -> tuple[tuple[Fraction, Fraction], ...]:
    """Disjoint rational isolating intervals of the real roots of the squarefree
    (here: irreducible) polynomial with coefficients ``key``, in increasing order.

    For degree 1 the interval is the root itself (``lo == hi``)."""
    p = _poly(key)
    if p.degree() == 1:
        c0, c1 = key
        r = -c0 / c1
        return ((r, r),)
    out: list[tuple[Fraction, Fraction]] = []
    for ball, mult in p.complex_roots():
        assert mult == 1
        if not ball.imag.is_zero():
            continue
        re = ball.real
        mid, rad = _frac(re.mid()), _frac(re.rad())
        out.append((mid - rad, mid + rad))
    out.sort()
    # Make the intervals pairwise disjoint with exact sign changes at the ends
    # (the root finder's balls isolate, but may touch after the conversion).
    fixed: list[tuple[Fraction, Fraction]] = []
    for lo, hi in out:
        lo, hi = _shrink(p, lo, hi)
        fixed.append((lo, hi))
    for (_, h1), (l2, _) in pairwise(fixed):
        assert h1 < l2
    return tuple(fixed)


def _shrink(p: Any, lo: Fraction, hi: Fraction) -> tuple[Fraction, Fraction]:
    """Bisect an isolating interval of a simple irrational root until it is
    short relative to its position (at most 1/4 of its width, three steps)."""
    slo = _sgn(_eval_frac(p, lo))
    shi = _sgn(_eval_frac(p, hi))
    assert slo * shi < 0, "isolating interval without a sign change"
    for _ in range(3):
        mid = (lo + hi) / 2
        s = _sgn(_eval_frac(p, mid))
        assert s != 0
        if s == slo:
            lo = mid
        else:
            hi = mid
    return lo, hi


def _sgn(x: Any) -> int:
    return (x > 0) - (x < 0)


def real_roots(poly: Any, *, multiplicities: bool = False) -> list[Any]:
    """The distinct real roots of a nonzero polynomial over Q, in increasing order.

    Parameters
    ----------
    poly : fmpq_poly, or a sequence of coefficients ``c0, c1, ...``
    multiplicities : bool
        Return ``(root, multiplicity)`` pairs.

    Returns
    -------
    list of RealAlgebraic (or of pairs)

    Examples
    --------
    >>> [str(r) for r in real_roots([-2, 0, 1])]
    ['-1.41421356237310 (root 1 of x**2 - 2)', '1.41421356237310 (root 2 of x**2 - 2)']
    >>> real_roots([6, -5, 1])
    [RealAlgebraic(2), RealAlgebraic(3)]
    """
    p = poly if isinstance(poly, flint.fmpq_poly) else _poly(poly)
    if p.is_zero():
        raise ValueError("the zero polynomial has every number as a root")
    found: list[tuple[RealAlgebraic, int]] = []
    _, factors = p.factor()
    for f, m in factors:
        f = _monic(flint.fmpq_poly(f))
        key = _key(f)
        for i in range(len(_isolate(key))):
            found.append((RealAlgebraic._make(key, i), m))
    found.sort(key=_SortKey)
    return found if multiplicities else [r for r, _ in found]


class _SortKey:
    __slots__ = ("r",)

    def __init__(self, pair: tuple[RealAlgebraic, int]) -> None:
        self.r = pair[0]

    def __lt__(self, other: _SortKey) -> bool:
        return self.r < other.r


# -- real algebraic numbers ------------------------------------------------------------


class RealAlgebraic:
    """A real algebraic number, exactly.

    Attributes
    ----------
    minpoly : tuple of Fraction
        Coefficients ``c0, c1, .., 1`` of the monic minimal polynomial over Q.
    index : int
        Position among the real roots of ``minpoly`` in increasing order
        (sympy's ``CRootOf`` index).

    Examples
    --------
    >>> r = RealAlgebraic.sqrt(2)
    >>> r * r == 2, r > Fraction(141, 100), r.approx(20)
    (True, True, '1.4142135623730950488')
    """

    __slots__ = ("_hi", "_lo", "index", "minpoly")
    minpoly: tuple[Fraction, ...]
    index: int
    _lo: Fraction
    _hi: Fraction

    def __init__(self, value: Any) -> None:
        if isinstance(value, RealAlgebraic):
            self.minpoly, self.index, self._lo, self._hi = value.minpoly, value.index, value._lo, value._hi
            return
        v = Fraction(value)
        self.minpoly = (-v, Fraction(1))
        self.index = 0
        self._lo = self._hi = v

    @classmethod
    def _make(cls, key: tuple[Fraction, ...], index: int) -> RealAlgebraic:
        obj = cls.__new__(cls)
        obj.minpoly = key
        obj.index = index
        obj._lo, obj._hi = _isolate(key)[index]
        return obj

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
        return len(self.minpoly) - 1

    @property
    def is_rational(self) -> bool:
        return self.degree == 1

    def as_fraction(self) -> Fraction:
        """The value if rational, else ValueError."""
        if not self.is_rational:
            raise ValueError(f"{self} is irrational")
        return self._lo

    @property
    def poly(self) -> Any:
        """The minimal polynomial as an ``fmpq_poly``."""
        return _poly(self.minpoly)

    @property
    def interval(self) -> tuple[Fraction, Fraction]:
        """The current isolating interval (``lo == hi`` for a rational)."""
        return self._lo, self._hi

    # -- refinement and approximation -------------------------------------------------

    def refine(self, width: Fraction) -> None:
        """Bisect the isolating interval until it is shorter than ``width``."""
        if self.is_rational:
            return
        p = self.poly
        lo, hi = self._lo, self._hi
        slo = _sgn(_eval_frac(p, lo))
        while hi - lo >= width:
            # Bisect at a short dyadic-ish point near the middle to keep sizes small.
            mid = _simple_between(lo, hi)
            s = _sgn(_eval_frac(p, mid))
            if s == slo:
                lo = mid
            else:
                hi = mid
        self._lo, self._hi = lo, hi

    def enclosure(self, bits: int | None = None) -> Any:
        """An ``arb`` ball containing the number, about ``bits`` bits wide
        (default: the current flint precision)."""
        if self.is_rational:
            return flint.arb(_fmpq(self._lo))
        bits = bits or flint.ctx.prec
        self.sign()  # the interval no longer contains 0: refine to relative precision
        self.refine(min(abs(self._lo), abs(self._hi)) / 2**bits)
        return _arb_interval(self._lo, self._hi)

    def approx(self, digits: int = 15) -> str:
        """A decimal string correct to ``digits`` significant digits (rounded)."""
        if self.is_rational and self._lo == 0:
            return "0"
        bits = int(digits * 3.33) + 16
        with workprec(bits):
            x = self.enclosure(bits)
            return x.str(digits, radius=False)

    def __float__(self) -> float:
        with workprec(64):
            return float(self.enclosure(64).mid())

    # -- exact sign and comparison --------------------------------------------------

    def sign(self) -> int:
        """-1, 0 or +1, exactly."""
        if self.is_rational:
            return _sgn(self._lo)
        # An irreducible polynomial of degree >= 2 does not vanish at 0; the
        # isolating interval shrinks until it does not contain 0.
        while self._lo <= 0 <= self._hi:
            self.refine((self._hi - self._lo) / 2)
        return 1 if self._lo > 0 else -1

    def _cmp(self, other: Any) -> int:
        o = other if isinstance(other, RealAlgebraic) else RealAlgebraic(other)
        if self.minpoly == o.minpoly:
            return _sgn(self.index - o.index)
        if self.is_rational and o.is_rational:
            return _sgn(self._lo - o._lo)
        # Different irreducible polynomials have no common root: refine until disjoint.
        while True:
            if self._hi < o._lo:
                return -1
            if o._hi < self._lo:
                return 1
            self.refine((self._hi - self._lo) / 2 if not self.is_rational else Fraction(1))
            o.refine((o._hi - o._lo) / 2 if not o.is_rational else Fraction(1))

    def __eq__(self, other: object) -> bool:
        if isinstance(other, (RealAlgebraic, int, Fraction)):
            return self._cmp(other) == 0
        return NotImplemented

    def __hash__(self) -> int:
        if self.is_rational:
            return hash(self._lo)
        return hash((self.minpoly, self.index))

    def __lt__(self, other: Any) -> bool:
        return self._cmp(other) < 0

    def __le__(self, other: Any) -> bool:
        return self._cmp(other) <= 0

    def __gt__(self, other: Any) -> bool:
        return self._cmp(other) > 0

    def __ge__(self, other: Any) -> bool:
        return self._cmp(other) >= 0

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

    def poly_str(self, var: str = "x") -> str:
        import sympy

        x = sympy.Symbol(var)
        return str(
            sum((sympy.Rational(c.numerator, c.denominator) * x**k for k, c in enumerate(self.minpoly)))
        )

    def to_sympy(self) -> Any:
        """``Rational`` or ``CRootOf`` (same root index convention)."""
        import sympy

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


def _simple_between(lo: Fraction, hi: Fraction) -> Fraction:
    """A rational with a small denominator strictly inside ``(lo, hi)``, near the middle."""
    w = hi - lo
    # a power-of-two grid finer than a quarter of the width (floor(log2 w) from the bit
    # lengths: w may be far below the smallest float)
    if w > 0:
        e = w.numerator.bit_length() - w.denominator.bit_length()
        if Fraction(2) ** e > w:
            e -= 1
        k = max(0, -e + 2)
    else:
        k = 0
    den = 2**k
    mid = (lo + hi) / 2
    cand = Fraction(round(mid * den), den)
    if lo < cand < hi:
        return cand
    return mid


def sign_at(poly: Any, alpha: RealAlgebraic) -> int:
    """The exact sign of a polynomial over Q at a real algebraic number.

    Zero exactly when the minimal polynomial divides ``poly``; otherwise the
    isolating interval is refined until a ball evaluation excludes 0.

    Parameters
    ----------
    poly : fmpq_poly or sequence of rationals ``c0, c1, ...``
    alpha : RealAlgebraic

    Returns
    -------
    int
        -1, 0 or 1.

    Examples
    --------
    >>> from fractions import Fraction
    >>> r = algebraic_sqrt(Fraction(1, 10))
    >>> sign_at([Fraction(-1, 10), 0, 1], r), sign_at([Fraction(-1, 3), 1], r)
    (0, -1)
    """
    p = poly if isinstance(poly, flint.fmpq_poly) else _poly(poly)
    if p.is_zero():
        return 0
    if alpha.is_rational:
        return _sgn(_eval_frac(p, alpha.as_fraction()))
    if (p % alpha.poly).is_zero():
        return 0
    bits = 64
    while True:
        with workprec(bits):
            v = _arb_eval(p, alpha.enclosure(bits))
            if v > 0:
                return 1
            if v < 0:
                return -1
        bits *= 2


# -- expressions ---------------------------------------------------------------------


def compile_expression(expr: Any, symbols: Sequence[Any]) -> Callable[..., Any]:
    """Compile a sympy rational expression into a function of its symbols that
    runs on any number type with ``+ - * /`` and integer powers.

    Rational constants are passed through ``const`` (the keyword argument of
    the returned function, default :class:`fractions.Fraction`), so the same
    compiled expression evaluates on Fractions, arb balls and matrices.
    """
    import sympy

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
        # expression with sympy, or read text with quadric_contact.parsing.
        raise EquationError(
            "compile_expression takes a sympy expression, not text (read text with quadric_contact.parsing)",
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
        return _Elem(flint.fmpq_mat(n, n, [(_fmpq(q) if i == j else 0) for i in range(n) for j in range(n)]))

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
            return flint.arb(_fmpq(o))
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
        return _Ball(self.x**n)


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
                        entries[row * n + col] = _fmpq(v)
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
        with workprec(bits):
            ballargs = [v.enclosure(bits) for v in vals]

            def const_arb(q: Fraction) -> Any:
                return flint.arb(_fmpq(q))

            try:
                if takes_const:
                    return fn(*ballargs, const=const_arb)
                out = fn(*(_Ball(b) for b in ballargs))
                return out.x if isinstance(out, _Ball) else flint.arb(_fmpq(out))
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
            for c in hits:
                c.refine((c._hi - c._lo) / 4 if not c.is_rational else Fraction(1))
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
        with workprec(bits):
            enc = v.enclosure(bits).sqrt()
        hits = [c for c in candidates if _overlaps(c, enc)]
        if len(hits) == 1:
            return hits[0]
        for c in hits:
            c.refine((c._hi - c._lo) / 4 if not c.is_rational else Fraction(1))
        bits *= 2


def _overlaps(c: RealAlgebraic, ball: Any) -> bool:
    lo = _frac(ball.lower())
    hi = _frac(ball.upper())
    return not (c._hi < lo or hi < c._lo)


def evaluate_arb(fn: Callable[..., Any], args: Sequence[RealAlgebraic], bits: int) -> Any:
    """A certified ball for ``fn(args)`` at ``bits`` bits (diagnostics, decimals)."""
    with workprec(bits):
        balls = [a.enclosure(bits) for a in args]
        return fn(*balls, const=lambda q: flint.arb(_fmpq(q)))


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
        sa, sb = _sgn(self.a), _sgn(self.b)
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
        import sympy

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
