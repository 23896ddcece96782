"""Exact event times for an ellipsoid under polynomial motion.

Under a polynomial (or rational-rotation) motion the moving ellipsoid's
matrix is, up to a positive factor, a matrix of polynomials in the time
``t`` (:meth:`~quadric_contact.trajectory.MotionSegment.moved_upper`).  The
generated formulas of :mod:`quadric_contact._generated.formulas` are
straight-line ``+ - *`` code, so running them on ``flint.fmpq_poly`` values
gives the exact polynomials in ``t``:

* ``c_k(t)``: the coefficients of ``P(lambda; t) = det(lambda E(t) + Q)``;
* ``D_2(t), D_3(t), D_4(t)``: Yang's discrimination sequence of ``P``
  (``D_4 = c4^2 Delta_4``, ``D_3 = 2 c4^2 Delta_3``: the signs of the
  paper's ``Delta_4`` and ``Delta_3``);
* for a plane, ``c3(t)^2 - 4 c4(t) c2(t)`` (the paper's ``Delta_3`` of the
  plane's pencil is ``c2^2`` times it).

Every decision of the paper (Corollary 10 and the complete discrimination
system for contact, Table 4 for the region, Corollary 15 for the zone of a
plane) is a function of the *signs* of these polynomials.  Those signs are
constant between consecutive real roots, so a state can change only at a
real root: a *candidate* event time.  A candidate is not necessarily a
change (a root of ``Delta_4`` where a double root appears and disappears
again, the persistent zeros of a sphere against a cylinder, ...), so each
open interval between candidates is classified exactly at a rational sample
time, each candidate itself exactly at the algebraic number it is, and an
*event* is reported only where the classification changes.

Event times are :class:`RealRoot` s: an irreducible integer polynomial and an
isolating interval with rational ends, refined on request to any number of
decimal places by exact bisection; the comparisons and the signs of other
polynomials at an event time are exact (a divisibility test, then ball
arithmetic on a shrinking interval; each refinement is counted as an
*escalation* in the ledger).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint

from ._generated.formulas import paper_deltas, pencil_coefficients
from .classification import QuadricKind
from .descartes import sign_variations
from .discriminants import revised_sign_list
from .ledger import Ledger
from .quadric import Quadric
from .regions import ROOT_SIGN_TABLE
from .results import Region

__all__ = [
    "PieceTrack",
    "PieceValue",
    "PlaneTrack",
    "RealRoot",
    "ZoneValue",
    "real_roots",
    "simplest_between",
    "table_4_patterns",
]

TimePoint = Any  # Fraction or RealRoot


def _sign(x: Any) -> int:
    return (x > 0) - (x < 0)


def _fmpq(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def _frac(q: Any) -> Fraction:
    return Fraction(int(q.p), int(q.q))


def _eval_sign(p: Any, t: Fraction) -> int:
    """Exact sign of an ``fmpq_poly`` at a rational ``t``."""
    if p.is_zero():
        return 0
    v = p(_fmpq(t))
    return _sign(_frac(v))


def _dyadic(x: Fraction, bits: int, up: bool) -> tuple[int, int]:
    """``(m, -bits)`` with ``m 2^-bits`` the dyadic just below (or above) ``x``."""
    scaled = x * (1 << bits)
    m = math.ceil(scaled) if up else math.floor(scaled)
    return (m, -bits)


# -- real algebraic numbers ------------------------------------------------------


class RealRoot:
    """A real algebraic number: the only root of ``poly`` in the interval ``[lo, hi]``.

    ``poly`` is an irreducible, primitive integer polynomial with positive
    leading coefficient (``flint.fmpz_poly``).  A rational root (``poly`` of
    degree 1) is held exactly with ``lo == hi``.  Otherwise ``lo < root < hi``
    and ``poly`` has opposite signs at ``lo`` and ``hi``.

    Examples
    --------
    >>> import flint
    >>> r = real_roots(flint.fmpq_poly([-14, 0, 1]), Fraction(0), Fraction(10))[0]
    >>> r.decimal(20)
    '3.74165738677394138558'
    >>> r.compare(Fraction(374, 100)), r.sign_of(flint.fmpq_poly([-14, 0, 1]))
    (1, 0)
    """

    __slots__ = ("_qpoly", "hi", "lo", "poly")

    def __init__(self, poly: Any, lo: Fraction, hi: Fraction) -> None:
        self.poly = poly
        self._qpoly = flint.fmpq_poly(poly)
        self.lo = lo
        self.hi = hi

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickle as the integer coefficients and the isolating interval (for worker processes)."""
        return (_rebuild_root, (tuple(int(c) for c in self.poly.coeffs()), self.lo, self.hi))

    @classmethod
    def rational(cls, value: Fraction) -> RealRoot:
        poly = flint.fmpz_poly([-value.numerator, value.denominator])
        return cls(poly, value, value)

    # -- exact facts --------------------------------------------------------------

    @property
    def is_rational(self) -> bool:
        return self.lo == self.hi

    @property
    def value(self) -> Fraction | None:
        """The exact value when rational, else None."""
        return self.lo if self.is_rational else None

    def _sign_lo(self) -> int:
        return _eval_sign(self._qpoly, self.lo)

    def bisect(self) -> None:
        """Halve the isolating interval (exactly)."""
        if self.is_rational:
            return
        mid = (self.lo + self.hi) / 2
        s = _eval_sign(self._qpoly, mid)
        assert s != 0, "an irreducible polynomial of degree >= 2 has no rational root"
        if s == self._sign_lo():
            self.lo = mid
        else:
            self.hi = mid

    def refine(self, width: Fraction) -> None:
        """Bisect until the interval is narrower than ``width``."""
        while self.hi - self.lo >= width and not self.is_rational:
            self.bisect()

    def compare(self, other: Fraction | RealRoot) -> int:
        """-1, 0 or 1 as this number is below, equal to or above ``other`` (exact)."""
        if isinstance(other, RealRoot):
            if other.is_rational:
                return self.compare(other.lo)
            if self.is_rational:
                return -other.compare(self.lo)
            if self.poly == other.poly:
                # same irreducible polynomial: each interval holds exactly one of its roots, so
                # they are the same root iff the common part of the intervals holds a root,
                # i.e. the polynomial changes sign across it (its ends are rational: no roots)
                lo, hi = max(self.lo, other.lo), min(self.hi, other.hi)
                if lo < hi and _eval_sign(self._qpoly, lo) != _eval_sign(self._qpoly, hi):
                    return 0
            while True:  # distinct algebraic numbers: separate the intervals
                if self.hi < other.lo:
                    return -1
                if other.hi < self.lo:
                    return 1
                if self.hi - self.lo >= other.hi - other.lo:
                    self.bisect()
                else:
                    other.bisect()
        x = Fraction(other)
        if self.is_rational:
            return _sign(self.lo - x)
        if x <= self.lo:
            return 1
        if x >= self.hi:
            return -1
        s = _eval_sign(self._qpoly, x)
        assert s != 0
        # the root lies where the sign changes: in (lo, x) if sign(x) != sign(lo)
        if s == self._sign_lo():  # no sign change on (lo, x]: the root is above x
            self.lo = x
            return 1
        self.hi = x
        return -1

    def __lt__(self, other: Fraction | RealRoot) -> bool:
        return self.compare(other) < 0

    def __gt__(self, other: Fraction | RealRoot) -> bool:
        return self.compare(other) > 0

    def __eq__(self, other: object) -> bool:
        if isinstance(other, int):
            other = Fraction(other)
        if isinstance(other, (RealRoot, Fraction)):
            return self.compare(other) == 0
        return NotImplemented

    def __hash__(self) -> int:
        return hash(self.value) if self.is_rational else hash(tuple(int(c) for c in self.poly.coeffs()))

    def sign_of(self, g: Any, ledger: Ledger | None = None) -> int:
        """Exact sign of the polynomial ``g`` (fmpq_poly or fmpz_poly) at this number.

        ``g`` vanishes here exactly when ``poly`` divides it (``poly`` is
        irreducible); otherwise ball arithmetic on the isolating interval
        decides, refining it (an *escalation*) until the ball excludes 0.
        """
        g = flint.fmpq_poly(g)
        if g.is_zero():
            return 0
        if self.is_rational:
            return _eval_sign(g, self.lo)
        r = g % self._qpoly
        if r.is_zero():
            return 0
        if r.degree() == 0:
            return _sign(_frac(r[0]))
        # g(root) != 0.  Taylor expansion at the midpoint m, exact in rationals:
        # g(m + s) = a0 + a1 s + ..., so |g(root) - a0| <= sum_{k>=1} |a_k| h^k with h
        # the half-width.  (Not done on the remainder r: reducing modulo poly can put a
        # root of r next to this one; nor with interval Horner, which loses the
        # cancellation between large coefficients.)
        first = True
        while True:
            mid = (self.lo + self.hi) / 2
            h = (self.hi - self.lo) / 2
            shifted = g(flint.fmpq_poly([_fmpq(mid), 1]))
            cs = shifted.coeffs()
            a0 = _frac(cs[0]) if cs else Fraction(0)
            tail = _frac(flint.fmpq_poly([abs(c) for c in cs])(_fmpq(h))) - abs(a0)
            if a0 != 0 and abs(a0) > tail:
                return _sign(a0)
            if first and ledger is not None:
                ledger.add("escalations")
            first = False
            ratio = tail / abs(a0) if a0 != 0 else Fraction(256)
            steps = max(1, ratio.numerator.bit_length() - ratio.denominator.bit_length() + 2)
            for _ in range(steps):
                self.bisect()

    # -- presentation -------------------------------------------------------------

    def approx(self, places: int) -> Fraction:
        """A rational within ``10**-places`` of this number (exact refinement)."""
        if self.is_rational:
            return self.lo
        self.refine(Fraction(1, 10**places))
        return (self.lo + self.hi) / 2

    def decimal(self, places: int = 12) -> str:
        """This number to ``places`` decimal places, with error below ``10**-places``."""
        if self.is_rational and (self.lo * 10**places).denominator == 1:
            v = self.lo
        else:
            self.refine(Fraction(1, 2 * 10**places))
            v = (self.lo + self.hi) / 2
        scaled = round(v * 10**places)
        sign = "-" if scaled < 0 else ""
        s = str(abs(scaled)).rjust(places + 1, "0")
        return f"{sign}{s[:-places]}.{s[-places:]}" if places else f"{sign}{s}"

    def __float__(self) -> float:
        if self.is_rational:
            return float(self.lo)
        self.refine(Fraction(1, 1 << 60) * max(Fraction(1), abs(self.lo)))
        return float((self.lo + self.hi) / 2)

    def polynomial_str(self, var: str = "t") -> str:
        import sympy

        t = sympy.Symbol(var)
        return str(sympy.Poly([int(c) for c in reversed(self.poly.coeffs())], t).as_expr())

    def to_dict(self, places: int = 20) -> dict[str, Any]:
        out: dict[str, Any] = {"decimal": self.decimal(places)}
        if self.is_rational:
            out["exact"] = str(self.lo)
        else:
            out["root_of"] = self.polynomial_str()
            out["interval"] = [str(self.lo), str(self.hi)]
        return out

    def __repr__(self) -> str:
        if self.is_rational:
            return f"RealRoot({self.lo})"
        return f"RealRoot(root of {self.polynomial_str()} in [{self.lo}, {self.hi}])"

    def __str__(self) -> str:
        return str(self.lo) if self.is_rational else self.decimal(12)


def _rebuild_root(coeffs: tuple[int, ...], lo: Fraction, hi: Fraction) -> RealRoot:
    return RealRoot(flint.fmpz_poly(list(coeffs)), lo, hi)


def _ball_interval(ball: Any) -> tuple[Fraction, Fraction]:
    m, e = ball.mid().man_exp()
    rm, re = ball.rad().man_exp()
    mid = Fraction(int(m)) * Fraction(2) ** int(e)
    rad = Fraction(int(rm)) * Fraction(2) ** int(re)
    return mid - rad, mid + rad


def _isolate_irreducible(coeffs: tuple[int, ...]) -> tuple[tuple[Fraction, Fraction], ...]:
    """Isolating intervals of all real roots of an irreducible integer polynomial."""
    f = flint.fmpz_poly(list(coeffs))
    if f.degree() == 1:
        r = Fraction(-coeffs[0], coeffs[1])
        return ((r, r),)
    q = flint.fmpq_poly(f)
    out = []
    for root, mult in f.complex_roots():
        assert mult == 1
        if not (root.imag.is_exact() and root.imag == 0):
            continue
        lo, hi = _ball_interval(root.real)
        s_lo, s_hi = _eval_sign(q, lo), _eval_sign(q, hi)
        assert s_lo * s_hi < 0, "certified isolation must bracket the root"
        out.append((lo, hi))
    out.sort()
    return tuple(out)


def _descartes_bound(f: Any, a: Fraction, b: Fraction) -> int:
    """An upper bound (exact parity) on the number of roots of ``f`` in ``(a, b)``:
    the sign variations of ``(1 + u)^n f((a + b u) / (1 + u))`` (Descartes' rule
    after the Moebius map of ``(0, oo)`` onto ``(a, b)``).  0 means no root."""
    h = flint.fmpq_poly(f)(flint.fmpq_poly([_fmpq(a), _fmpq(b - a)]))  # roots of f in (a, b) <-> h in (0, 1)
    coeffs = h.coeffs()
    rev = flint.fmpq_poly(list(reversed(coeffs)))  # y^n h(1/y)
    g = rev(flint.fmpq_poly([1, 1]))  # roots of h in (0, 1) <-> positive roots of g
    signs = [1 if c > 0 else -1 for c in g.coeffs() if c != 0]
    return sum(1 for x, y in pairwise(signs) if x != y)


def _isolate_between(f: Any, a: Fraction, b: Fraction) -> list[RealRoot]:
    """The real roots in ``(a, b)`` of an irreducible integer polynomial of degree > 1,
    isolated by bisection with Descartes' rule (the Vincent-Collins-Akritas method):
    a piece with no sign variation holds no root, one with one variation exactly one
    (then ``f`` changes sign across it).  Roots are simple, none is rational, so every
    bisection point is a non-root and the bisection ends."""
    out: list[RealRoot] = []
    todo = [(a, b)]
    while todo:
        lo, hi = todo.pop()
        v = _descartes_bound(f, lo, hi)
        if v == 0:
            continue
        if v == 1:
            out.append(RealRoot(f, lo, hi))
            continue
        mid = (lo + hi) / 2
        todo += [(mid, hi), (lo, mid)]
    return out


def _primitive(p: Any) -> Any:
    """The primitive integer polynomial with positive leading coefficient of an fmpq_poly/fmpz_poly."""
    z = flint.fmpz_poly(flint.fmpq_poly(p).numer())
    c = z.content()
    if c != 1 and c != 0:
        z = flint.fmpz_poly([int(a) // int(c) for a in z.coeffs()])
    if z.degree() >= 0 and z.leading_coefficient() < 0:
        z = -z
    return z


def irreducible_factors(p: Any) -> list[Any]:
    """Distinct irreducible factors (of positive degree) of a non-zero polynomial."""
    z = _primitive(p)
    if z.degree() <= 0:
        return []
    _, facs = z.factor()
    out = []
    for f, _m in facs:
        if f.degree() >= 1:
            out.append(-f if f.leading_coefficient() < 0 else f)
    return out


def real_roots(
    p: Any,
    a: Fraction,
    b: Fraction,
    *,
    closed: bool = False,
    ledger: Ledger | None = None,
    target: str | None = None,
) -> list[RealRoot]:
    """The distinct real roots of ``p`` in ``(a, b)`` (or ``[a, b]``), sorted, exactly.

    Parameters
    ----------
    p : fmpq_poly or fmpz_poly, not identically zero
    a, b : Fraction
    closed : bool
        Include roots equal to ``a`` or ``b``.
    ledger, target
        Where to count the isolations (one per irreducible factor).

    Returns
    -------
    list of RealRoot
        Each held by an irreducible integer polynomial and an isolating
        interval with rational ends; a rational root exactly.

    Examples
    --------
    >>> import flint
    >>> [r.decimal(6) for r in real_roots(flint.fmpq_poly([-2, 0, 1]), Fraction(-10), Fraction(10))]
    ['-1.414214', '1.414214']
    """
    roots: list[RealRoot] = []
    for f in irreducible_factors(p):
        if ledger is not None:
            ledger.add("root_isolations", target=target)
        if f.degree() > 1 and a < b:
            # an irreducible f of degree > 1 has simple roots and none at the rational a, b:
            # bisect (a, b) with Descartes' rule until each piece holds at most one root
            roots.extend(_isolate_between(f, a, b))
            continue
        for lo, hi in _isolate_irreducible(tuple(int(c) for c in f.coeffs())):
            r = RealRoot(f, lo, hi)
            ca, cb = r.compare(a), r.compare(b)
            if (ca > 0 and cb < 0) or (closed and ca >= 0 and cb <= 0):
                roots.append(r)
    return sort_roots(roots)


def sort_roots(roots: Sequence[RealRoot]) -> list[RealRoot]:
    """Sort exactly, dropping duplicates."""

    def cmp(u: RealRoot, v: RealRoot) -> int:
        return u.compare(v)

    ordered = sorted(roots, key=functools.cmp_to_key(cmp))
    out: list[RealRoot] = []
    for r in ordered:
        if not out or out[-1].compare(r) != 0:
            out.append(r)
    return out


def simplest_between(a: Fraction, b: Fraction) -> Fraction:
    """The rational with the smallest denominator in the open interval ``(a, b)``.

    Examples
    --------
    >>> simplest_between(Fraction(31, 10), Fraction(33, 10)), simplest_between(Fraction(1, 3), Fraction(1, 2))
    (Fraction(13, 4), Fraction(2, 5))
    """
    if not a < b:
        raise ValueError(f"empty interval ({a}, {b})")
    if a < 0 < b:
        return Fraction(0)
    if b <= 0:
        return -simplest_between(-b, -a)
    n = math.floor(a) + 1  # smallest integer > a
    if n < b:
        return Fraction(n)
    fl = n - 1
    lo, hi = a - fl, b - fl  # 0 <= lo < hi <= 1
    if lo == 0:
        return fl + Fraction(1, math.floor(1 / hi) + 1)
    return fl + 1 / simplest_between(1 / hi, 1 / lo)


def dyadic_between(lo: Fraction, hi: Fraction) -> Fraction:
    """A short dyadic rational ``m / 2^k`` (smallest ``k``) in the open interval ``(lo, hi)``.

    Examples
    --------
    >>> dyadic_between(Fraction(31, 10), Fraction(33, 10)), dyadic_between(Fraction(1, 3), Fraction(2))
    (Fraction(13, 4), Fraction(1, 1))
    """
    if not lo < hi:
        raise ValueError(f"empty interval ({lo}, {hi})")
    w = hi - lo
    k = max(0, w.denominator.bit_length() - w.numerator.bit_length() + 1)  # 2^-k < w
    best = None
    while k >= 0:
        m = math.floor(lo * (1 << k)) + 1
        x = Fraction(m, 1 << k)
        if not x < hi:
            break
        best = x
        k -= 1
    assert best is not None
    return best


def sample_between(left: TimePoint, right: TimePoint) -> Fraction:
    """A simple rational strictly between two time points (rationals or roots)."""
    if isinstance(left, RealRoot):
        if isinstance(right, RealRoot):
            while left.compare(right) < 0 and not left.hi < right.lo:
                (left if left.hi - left.lo >= right.hi - right.lo else right).bisect()
        else:
            while not left.hi < right:
                left.bisect()
        lo = left.hi
    else:
        lo = left
    if isinstance(right, RealRoot):
        while not lo < right.lo:
            right.bisect()
        hi = right.lo
    else:
        hi = right
    if isinstance(left, RealRoot) and left.is_rational:
        lo = left.lo
    if isinstance(right, RealRoot) and right.is_rational:
        hi = right.lo
    return dyadic_between(lo, hi)


def sign_at(p: Any, t: TimePoint, ledger: Ledger | None = None) -> int:
    """Exact sign of a polynomial in ``t`` at a rational or algebraic time."""
    if isinstance(t, RealRoot):
        return t.sign_of(p, ledger)
    return _eval_sign(p, t)


# -- states ---------------------------------------------------------------------------


@dataclass(frozen=True)
class ZoneValue:
    """Where the ellipsoid is with respect to a separating plane (Algorithm 1).

    ``region`` is ``R+`` (Zone 1), ``R-`` (Zone 2) or ``contact`` (Zone 0,
    transversal contact with the plane); ``tangent`` marks the instants where
    the plane touches the ellipsoid (``c3^2 = 4 c4 c2``).
    """

    region: Region
    tangent: bool = False

    @property
    def zone(self) -> int:
        return {Region.R_PLUS: 1, Region.R_MINUS: 2, Region.CONTACT: 0}[self.region]

    def __str__(self) -> str:
        return f"{self.region.value}{' (tangent)' if self.tangent else ''}"


@dataclass(frozen=True)
class PieceValue:
    """State of the ellipsoid against one quadric piece.

    Attributes
    ----------
    contact : bool or None
        Transversal contact (None: undecided, the ellipsoid is not known to be small).
    region : Region or None
        ``R-``, ``R+`` or ``contact`` (only when the relative position is asked for).
    kind : str or None
        Contact kind (Table 3) when asked for.
    decided_by : str
        The result that decided the contact.
    """

    contact: bool | None
    region: Region | None = None
    kind: str | None = None
    decided_by: str = ""
    region_asked: bool = False

    def __str__(self) -> str:
        return self.describe()

    def describe(self, inside: Region | None = None) -> str:
        """One line; with ``inside`` (the piece's inside region) ``R-``/``R+`` are
        glossed as inside/outside."""
        parts = [{True: "contact", False: "no contact", None: "contact undecided"}[self.contact]]
        if self.region is not None and self.region is not Region.CONTACT:
            gloss = "" if inside is None else (" (inside)" if self.region is inside else " (outside)")
            parts.append(self.region.value + gloss)
        elif self.region is None and self.region_asked and self.contact is not True:
            parts.append("region undecided")
        redundant = (("transversal", True), ("none", False))
        if self.kind is not None and (self.kind, self.contact) not in redundant:
            parts.append(self.kind)
        return ", ".join(parts)


def table_4_patterns(Q: Quadric) -> dict[Region, str]:
    """Root-sign pattern of each region for ``Q`` *as given*.

    Parameters
    ----------
    Q : Quadric

    Returns
    -------
    dict
        ``Region -> pattern``: Table 4, with ``R-``/``R+`` swapped and the
        roots negated when ``Q`` has the opposite sign of its standard form
        (:attr:`~quadric_contact.quadric.Quadric.canonical_sign`).

    References
    ----------
    Theorem 13, Table 4.

    Examples
    --------
    The unit sphere, and the same sphere written with its inside positive:

    >>> q = Quadric.sphere(1)
    >>> table_4_patterns(q)[Region.R_MINUS], table_4_patterns(-q)[Region.R_PLUS]
    ('----', '++++')
    """
    kind = Q.kind
    table = ROOT_SIGN_TABLE.get(kind, {})
    if Q.canonical_sign > 0:
        return dict(table)
    flip = str.maketrans("-+", "+-")
    return {r.swapped(): "".join(sorted(p.translate(flip), key="-0+".index)) for r, p in table.items()}


def _descartes_pattern(signs: Sequence[int]) -> str:
    """Root-sign pattern of a real-rooted polynomial from its coefficient signs ``c0..cn``."""
    c = list(signs)
    while c and c[-1] == 0:
        c.pop()
    zero = next(i for i, v in enumerate(c) if v != 0)
    positive = sign_variations(c)
    negative = sign_variations([v if k % 2 == 0 else -v for k, v in enumerate(c)])
    return "-" * negative + "0" * zero + "+" * positive


def reduce_positive(g: Any, positive: Any = None) -> Any:
    """``g`` divided by its (positive) content and by every power of ``positive`` (a
    polynomial without real roots and positive leading coefficient, such as
    ``|q(t)|^2``) that divides it: same sign everywhere, lower degree."""
    if g.is_zero():
        return g
    num = flint.fmpz_poly(g.numer())
    content = abs(int(num.content()))
    g = flint.fmpq_poly(num) / content if content > 1 else flint.fmpq_poly(num)
    if positive is not None and positive.degree() >= 1:
        while True:
            q, r = divmod(g, positive)
            if not r.is_zero():
                break
            g = q
    return g


class _Track:
    """Shared machinery: critical polynomials, their roots in a segment, cached states."""

    label: str
    critical: list[Any]

    def __init__(self, label: str, t0: Fraction, t1: Fraction, ledger: Ledger, positive: Any = None) -> None:
        self.label = label
        self.t0 = t0
        self.t1 = t1
        self.ledger = ledger
        self.positive = positive
        self.roots: list[RealRoot] = []
        self._interval_cache: dict[int, Any] = {}
        self._root_cache: dict[int, Any] = {}
        self._rational_cache: dict[Fraction, Any] = {}

    def _find_roots(self) -> None:
        polys = [p for p in self.critical if p.degree() >= 1]
        found: list[RealRoot] = []
        seen: set[tuple[int, ...]] = set()
        for p in polys:
            for f in irreducible_factors(p):
                key = tuple(int(c) for c in f.coeffs())
                if key in seen:
                    continue
                seen.add(key)
                found.extend(real_roots(f, self.t0, self.t1, ledger=self.ledger, target=self.label))
        self.roots = sort_roots(found)

    def decide(self, sign: Callable[[Any], int], t: TimePoint) -> Any:  # pragma: no cover - abstract
        raise NotImplementedError

    def state_on_interval(self, index: int, sample: Fraction) -> Any:
        """State on the open interval between own roots ``index-1`` and ``index``
        (``sample`` must lie in it)."""
        if index not in self._interval_cache:
            self.ledger.add("samples", target=self.label)
            self._interval_cache[index] = self.decide(lambda p: _eval_sign(p, sample), sample)
        return self._interval_cache[index]

    def state_at_root(self, index: int) -> Any:
        if index not in self._root_cache:
            r = self.roots[index]
            self.ledger.add("instants", target=self.label)
            self._root_cache[index] = self.decide(lambda p: r.sign_of(p, self.ledger), r)
        return self._root_cache[index]

    def state_at_rational(self, t: Fraction) -> Any:
        if t not in self._rational_cache:
            self.ledger.add("instants", target=self.label)
            self._rational_cache[t] = self.decide(lambda p: _eval_sign(p, t), t)
        return self._rational_cache[t]


def _upper_polys(Q: Quadric) -> list[Any]:
    return [flint.fmpq_poly([_fmpq(v)]) for v in Q.upper]


class PlaneTrack(_Track):
    """The zone of a moving ellipsoid with respect to a plane (Theorem 14, Corollary 15).

    ``P0(lambda; t) = lambda^2 (c4 lambda^2 + c3 lambda + c2)``; transversal
    contact iff ``c3^2 - 4 c4 c2 < 0``, else ``R+`` iff ``c3 > 0``.  The only
    critical polynomial is ``c3^2 - 4 c4 c2``: where it is positive ``c3``
    cannot vanish (``c4 < 0`` and ``c2 < 0``, eq. (12)), so the zone is
    constant between its roots.
    """

    def __init__(
        self,
        label: str,
        E_upper: Sequence[Any],
        plane: Quadric,
        t0: Fraction,
        t1: Fraction,
        ledger: Ledger,
        positive: Any = None,
    ) -> None:
        super().__init__(label, t0, t1, ledger, positive)
        c = pencil_coefficients(*E_upper, *_upper_polys(plane))
        ledger.add("characteristic_polynomials", target=label)
        assert c[0].is_zero() and c[1].is_zero(), "a plane gives c0 = c1 = 0 (eq. (12))"
        self.c2, self.c4 = c[2], c[4]
        self.c3 = reduce_positive(c[3], positive)
        self.disc = reduce_positive(c[3] * c[3] - 4 * c[4] * c[2], positive)
        ledger.add("discriminants", target=label)
        self.critical = [self.disc]
        self._find_roots()

    def decide(self, sign: Callable[[Any], int], t: TimePoint) -> ZoneValue:
        d = sign(self.disc)
        if d < 0:
            return ZoneValue(Region.CONTACT)
        s3 = sign(self.c3)
        assert s3 != 0, "c3 = 0 forces c3^2 - 4 c4 c2 < 0"
        return ZoneValue(Region.R_PLUS if s3 > 0 else Region.R_MINUS, tangent=d == 0)


NO_REAL_POINTS = frozenset(
    {
        QuadricKind.IMAGINARY_ELLIPSOID,
        QuadricKind.IMAGINARY_ELLIPTIC_CYLINDER,
        QuadricKind.IMAGINARY_PARALLEL_PLANES,
        QuadricKind.EMPTY,
    }
)


def _external_contact_kind() -> Callable[..., Any] | None:
    """``contact_kind(E, Q, small=...)`` (Table 3 via the Segre characteristic) when the
    package provides it (module :mod:`quadric_contact.contact_kind`)."""
    import importlib

    try:
        module = importlib.import_module(f"{__package__ or 'quadric_contact'}.contact_kind")
    except ImportError:
        return None
    fn = getattr(module, "contact_kind_exact", None)
    return fn if callable(fn) else None


class PieceTrack(_Track):
    """Contact, region and contact kind of a moving ellipsoid against one quadric piece.

    Contact is Corollary 10 read on ``D4`` and ``D3`` (the signs of
    ``Delta_4`` and ``Delta_3``); where both vanish the complete
    discrimination system (Yang's revised sign list of ``D1..D4``) decides,
    which also covers Remark 9 (non-real roots mean transversal contact for
    any pair).  With all roots real, "no contact" needs the ellipsoid to be
    small (Theorem 2); otherwise the contact is undecided.  The region is
    read from the coefficient signs by Descartes' rule (exact: all roots are
    real when there is no transversal contact) against Table 4.

    A piece that is a plane is handled by Theorem 14 / Corollary 15.
    """

    def __init__(
        self,
        label: str,
        E_upper: Sequence[Any],
        Q: Quadric,
        t0: Fraction,
        t1: Fraction,
        ledger: Ledger,
        *,
        small: bool | None,
        region: bool,
        kind: bool,
        E_at: Callable[[Fraction], Quadric] | None = None,
        table_4: bool = True,
        positive: Any = None,
    ) -> None:
        super().__init__(label, t0, t1, ledger, positive)
        self.Q = Q
        self.small = small
        self.table_4 = table_4
        self.want_region = region
        self.want_kind = kind
        self.E_at = E_at
        self.is_plane = Q.kind is QuadricKind.PLANE
        self.patterns = table_4_patterns(Q)
        raw = pencil_coefficients(*E_upper, *_upper_polys(Q))
        ledger.add("characteristic_polynomials", target=label)
        # signs only matter: drop positive factors (content, powers of |q(t)|^2)
        c = tuple(reduce_positive(ck, positive) for ck in raw)
        self.c = c
        if self.is_plane:
            self.D: tuple[Any, ...] = (reduce_positive(raw[3] * raw[3] - 4 * raw[4] * raw[2], positive),)
            ledger.add("discriminants", target=label)
            self.critical = [self.D[0]]
        else:
            # (1, Delta_2, Delta_3, Delta_4) have the signs of Yang's (D1, .., D4):
            # D1 = 4 c4^2 > 0, D2 = c4^2 Delta_2, D3 = 2 c4^2 Delta_3, D4 = c4^2 Delta_4
            deltas = paper_deltas(*raw)
            self.D = (flint.fmpq_poly([1]), *(reduce_positive(d, positive) for d in deltas))
            ledger.add("discriminants", 3, target=label)
            self.critical = list(self.D[1:])
            if region or kind:
                # c0 = det Q is constant and c4 = det E(t) < 0: only c1..c3 can change sign
                ledger.add("coefficient_signs", 3, target=label)
                self.critical += [c[1], c[2], c[3]]
        self._kind_fn = _external_contact_kind() if kind else None
        self._find_roots()

    def decide(self, sign: Callable[[Any], int], t: TimePoint) -> PieceValue:
        if self.is_plane:
            d = sign(self.D[0])
            if d < 0:
                return PieceValue(
                    True,
                    Region.CONTACT if self.want_region else None,
                    "transversal" if self.want_kind else None,
                    "Corollary 15",
                )
            s3 = sign(self.c[3])
            reg = Region.R_PLUS if s3 > 0 else Region.R_MINUS
            plane_kind = ("tangent_point" if d == 0 else "none") if self.want_kind else None
            return PieceValue(False, reg if self.want_region else None, plane_kind, "Corollary 15")
        s = [1] + [sign(d) for d in self.D[1:]]  # D1 = 4 c4^2 > 0
        s3, s4 = s[2], s[3]
        if s4 < 0 or (s4 == 0 and s3 < 0):
            transversal, by = True, "Corollary 10"
        elif s4 > 0 or (s4 == 0 and s3 > 0):
            rev = revised_sign_list(s)
            nonzero = [v for v in rev if v]
            pairs = sum(1 for a, b in pairwise(nonzero) if a != b)
            transversal, by = pairs > 0, "Corollary 10"
            if pairs:
                by = "Remark 9 (two pairs of non-real roots)"
        else:  # D4 = D3 = 0: the complete discrimination system decides
            rev = revised_sign_list(s)
            nonzero = [v for v in rev if v]
            pairs = sum(1 for a, b in pairwise(nonzero) if a != b)
            transversal, by = pairs > 0, "complete discrimination system"
        if self.Q.kind in NO_REAL_POINTS:
            return PieceValue(False, None, "none" if self.want_kind else None, "no real points")
        contact: bool | None
        if transversal:
            contact = True
            if by == "Corollary 10" and self.small is not True:
                by = "Remark 9"
        elif self.small:
            contact = False
        else:
            contact, by = None, "all roots real but E is not known to be small (Remark 9)"
        region: Region | None = None
        if self.want_region:
            if contact:
                region = Region.CONTACT
            elif contact is False and self.table_4:
                pattern = _descartes_pattern([sign(ck) for ck in self.c])
                for reg, pat in self.patterns.items():
                    if pat == pattern:
                        region = reg
        kind: str | None = None
        if self.want_kind:
            kind = self._kind(contact, s4, t)
        if self.want_region and region is None and contact is False:
            by += "; region undecided: " + (
                "Table 4 does not apply (E is small only in the enclosing sense)"
                if not self.table_4
                else "the root signs match no row of Table 4"
            )
        return PieceValue(contact, region, kind, by, self.want_region)

    def _kind(self, contact: bool | None, s4: int, t: TimePoint) -> str:
        if contact:
            return "transversal"
        if contact is None:
            return "undecided"
        if s4 != 0:
            return "none"  # all roots real and simple: Segre type [1111], no contact (Table 3)
        if self._kind_fn is not None and isinstance(t, Fraction) and self.E_at is not None:
            result = self._kind_fn(self.E_at(t), self.Q, small=self.small)
            return str(getattr(result, "value", result))
        return "undetermined"
