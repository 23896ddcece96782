"""Exact event times for an ellipsoid under polynomial motion.

Under a polynomial (or rational-rotation) motion the moving ellipsoid's
matrix is, up to a positive factor, a matrix of polynomials in the time
``t`` (:meth:`~quadric_contact.scenes.trajectory.MotionSegment.moved_upper`).  The
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

Event times are :class:`~quadric_contact.exact.algebraic.RealAlgebraic` numbers: the
root of an irreducible polynomial in an isolating interval with rational ends,
refined on request to any number of decimal places by exact bisection; the
comparisons and the signs of other polynomials at an event time are exact
(:func:`~quadric_contact.exact.algebraic.sign_at`: a divisibility test, then an exact
Taylor bound on a shrinking interval; each refinement is counted as an
*escalation* in the ledger).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint

from quadric_contact._generated.formulas import paper_deltas, pencil_coefficients
from quadric_contact.exact.algebraic import (
    RealAlgebraic,
    irreducible_factors,
    real_roots,
    sign_at,
    sort_roots,
)
from quadric_contact.exact.descartes import sign_variations
from quadric_contact.exact.discriminants import revised_sign_list
from quadric_contact.exact.rational import fmpq_poly_of
from quadric_contact.model.classification import NO_REAL_POINTS, QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.theory.contact_kind import contact_kind_exact
from quadric_contact.theory.regions import ROOT_SIGN_TABLE
from quadric_contact.theory.results import Region

__all__ = [
    "PieceTrack",
    "PieceValue",
    "PlaneTrack",
    "ZoneValue",
    "table_4_patterns",
]

TimePoint = Any  # Fraction or RealAlgebraic


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
    beyond_cut : bool
        The ellipsoid crosses the piece's whole quadric, but only beyond the
        plane(s) that cut the piece (the geometric reading says no contact, the
        paper's reading says contact).
    """

    contact: bool | None
    region: Region | None = None
    kind: str | None = None
    decided_by: str = field(default="", compare=False)
    region_asked: bool = False
    beyond_cut: bool = False

    def __str__(self) -> str:
        return self.describe()

    def describe(self, inside: Region | None = None) -> str:
        """One line; with ``inside`` (the piece's inside region) ``R-``/``R+`` are
        glossed as inside/outside."""
        parts = [{True: "contact", False: "no contact", None: "contact undecided"}[self.contact]]
        if self.beyond_cut:
            parts[0] += " (crosses the quadric beyond the cut only)"
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
        (:attr:`~quadric_contact.model.quadric.Quadric.canonical_sign`).

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
        self.roots: list[RealAlgebraic] = []
        self._interval_cache: dict[int, Any] = {}
        self._root_cache: dict[int, Any] = {}
        self._rational_cache: dict[Fraction, Any] = {}

    def _find_roots(self) -> None:
        polys = [p for p in self.critical if p.degree() >= 1]
        found: list[RealAlgebraic] = []
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
            self._interval_cache[index] = self.decide(lambda p: sign_at(p, sample), sample)
        return self._interval_cache[index]

    def state_at_root(self, index: int) -> Any:
        if index not in self._root_cache:
            r = self.roots[index]
            self.ledger.add("instants", target=self.label)
            self._root_cache[index] = self.decide(lambda p: sign_at(p, r, self.ledger), r)
        return self._root_cache[index]

    def state_at_rational(self, t: Fraction) -> Any:
        if t not in self._rational_cache:
            self.ledger.add("instants", target=self.label)
            self._rational_cache[t] = self.decide(lambda p: sign_at(p, t), t)
        return self._rational_cache[t]


def _upper_polys(Q: Quadric) -> list[Any]:
    return [fmpq_poly_of([v]) for v in Q.upper]


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
        self._kind_fn: Callable[..., Any] | None = contact_kind_exact if kind else None
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
        if isinstance(t, RealAlgebraic) and t.is_rational:
            t = t.as_fraction()  # a rational event time: the kind is classified exactly there
        if self._kind_fn is not None and isinstance(t, Fraction) and self.E_at is not None:
            result = self._kind_fn(self.E_at(t), self.Q, small=self.small)
            return str(getattr(result, "value", result))
        return "undetermined"
