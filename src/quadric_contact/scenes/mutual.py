"""Mutual contacts between moving ellipsoids, at exact times.

Two ellipsoids ``A(t)`` and ``B(t)``, each under the scene's motion
(polynomial translations, rational rotations), have matrices that are
positive multiples of matrices of polynomials in ``t``
(:meth:`~quadric_contact.scenes.trajectory.MotionSegment.moved_upper`).  The
pencil is taken time-dependent on both sides, ``P(λ; t) = det(λ A(t) + B(t))``,
both matrices negative inside: its coefficients are polynomials in ``t``
(rather than moving to the frame of one body, which makes the other's motion
rational with the first rotation's inverse; both give the same roots, the
pencil needs no division).  By the condition of Wang, Wang and Kim (proved in
``proofs/wwk_2001_ellipsoid_separation.py``) the solids are apart iff ``P``
has two distinct positive roots, touch iff it has a double positive root,
and overlap iff it has none.

In time the number of positive roots changes only where two roots meet (a
real root of the discriminant ``Δ4(t)``) or where a root passes through 0 or
infinity, which never happens: ``c0 = det B(t)`` and ``c4 = det A(t)`` are a
positive power of ``|q(t)|^2`` times the fixed negative determinants.  So the
state is decided at one rational time between consecutive real roots of
``Δ4`` and, at each root, by the sign of the double root ``-s0/s1`` of the
first subresultant ``s1 λ + s0`` of ``P`` and ``P'``: touching iff it is
positive.  Similar bodies in the same orientation (congruent ones that only translate,
spheres whatever their rotations) have the structural double root
``λ = -k(t) < 0`` where the quadratic part vanishes, ``k = p / q`` a ratio of
polynomials: ``P = (q λ + p)^2 R(λ)``, and the discriminant of the quadratic
``R`` takes the place of ``Δ4`` (identically zero then).  Any other pencil
whose ``Δ4`` vanishes identically (coaxial spheroids moving along their axis)
is split into its irreducible factors, whose roots meet only at roots of
their discriminants and resultants.  At a rational time between
roots the state needs no root isolation: the sign of ``Δ4`` tells two real
roots (the two negative ones: overlapping) from four, where Descartes' rule of
signs is exact (two sign changes: apart).  The reduction is proved in
``proofs/mutual_contact_events.py``; the formulas are checked in
``tests/test_mutual.py``.

A *broad phase* among bodies keeps N bodies from costing N² pencils: over each
window of time every body's swept volume is enclosed in a rational box
(:func:`~quadric_contact.scenes.broadphase.swept_box`); boxes are sorted and
swept along ``x`` and only pairs whose boxes meet get a pencil on that window.
A box contains every placement, so a pruned pair cannot touch there: the
pruning never loses a contact (the tests compare with the unpruned run).  A
kept pair whose centres stay farther apart than the sum of the bodies' largest
semi-axes on a window (an exact polynomial in ``t`` without roots there) is
apart on it too, without a pencil (``separated_windows`` in the ledger).
``workers`` shares the kept pairs between processes.
"""

from __future__ import annotations

import functools
import math
import multiprocessing
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import pairwise
from typing import Any

import flint
import numpy as np

from quadric_contact._generated.formulas import paper_deltas, pencil_coefficients
from quadric_contact.exact.algebraic import (
    RealAlgebraic,
    compile_expression,
    rational_between,
    real_roots,
    sign_at,
    sort_roots,
)
from quadric_contact.exact.rational import fmpq_of, fraction_of
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.broadphase import _swept_box_q, ellipsoid_extents
from quadric_contact.scenes.events import reduce_positive
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.trajectory import MotionSegment

__all__ = ["OVERLAPPING", "SEPARATE", "TOUCHING", "MutualEvent", "MutualResult", "mutual_contacts"]

SEPARATE, TOUCHING, OVERLAPPING, UNDECIDED = "apart", "touching", "overlapping", "undecided"


@functools.cache
def _subresultant_1() -> tuple[Any, Any]:
    """``(s1, s0)``: the first subresultant of a quartic and its derivative, as
    functions of ``c0..c4`` (derived with sympy once)."""
    import sympy as sp  # sympy is heavy: only for this one derivation

    c = sp.symbols("c0:5")
    lam = sp.Symbol("lam")
    P = sp.Poly(sum(c[i] * lam**i for i in range(5)), lam)
    S1 = sp.Poly(sp.subresultants(P, P.diff(lam))[3], lam)
    assert S1.degree() == 1
    return (
        compile_expression(sp.expand(S1.coeff_monomial(lam)), c),
        compile_expression(sp.expand(S1.coeff_monomial(1)), c),
    )


def _negative_inside(q: Quadric) -> Quadric:
    return -q if q.canonical_sign < 0 else q


_QUADRATIC = (0, 1, 2, 4, 5, 7)  # q00 q01 q02 q11 q12 q22 among the ten upper entries


def _homothety(A: Sequence[Any], B: Sequence[Any]) -> tuple[Any, Any] | None:
    """``(p, q)``, polynomials in ``t`` without a common factor, with the quadratic part of
    ``q B(t)`` equal to that of ``p A(t)`` at every time (similar bodies in the same
    orientation, such as congruent translates or two spheres, whatever their rotations),
    else None.  ``k = p / q > 0``: the ratio of the entries ``00`` of positive definite
    blocks (``q`` never vanishes; constant ``q = 1`` for bodies that only translate)."""
    a, b = A[0], B[0]
    g = a.gcd(b)
    p, q = b / g, a / g
    if all((q * B[j] - p * A[j]).is_zero() for j in _QUADRATIC):
        return p, q
    return None


@dataclass(frozen=True)
class MutualEvent:
    """The state of a pair of bodies changes at an exact time: ``before``, ``at``, ``after``."""

    time: RealAlgebraic
    before: str
    at: str
    after: str

    def describe(self) -> str:
        if self.before == self.after:
            return f"{self.at} at the instant only (before and after: {self.before})"
        tail = f" (at the instant: {self.at})" if self.at not in (self.before, self.after) else ""
        return f"{self.before} -> {self.after}{tail}"


@dataclass
class MutualResult:
    """The timeline of one pair of bodies: its state at the start, its events, and
    the first time the solids meet (touch or overlap)."""

    a: str
    b: str
    start: str
    events: list[MutualEvent] = field(default_factory=list)
    first_contact: RealAlgebraic | None = None

    def state_at(self, t: Any) -> str:
        """The pair's state at a rational time of the span.

        Examples
        --------
        >>> from quadric_contact.scenes.scene_toml import builtin_scene
        >>> from quadric_contact.scenes.simulate import simulate
        >>> pair = simulate(builtin_scene("bees_meeting")).mutual[0]
        >>> pair.a, pair.b, pair.state_at(0), pair.state_at(2)
        ('north', 'south', 'apart', 'overlapping')
        """
        t = Fraction(t)
        state = self.start
        for e in self.events:
            c = e.time.compare(t)
            if c > 0:
                break
            state = e.at if c == 0 else e.after
        return state

    def to_dict(self, places: int) -> dict[str, Any]:
        return {
            "bodies": [self.a, self.b],
            "start": self.start,
            "events": [
                {"time": e.time.to_dict(places), "before": e.before, "at": e.at, "after": e.after}
                for e in self.events
            ],
            "first_contact": None if self.first_contact is None else self.first_contact.to_dict(places),
        }


class _PairWindow:
    """The exact track of a pair on a window ``[t0, t1]`` where both motions are one segment."""

    def __init__(
        self, A: Sequence[Any], B: Sequence[Any], t0: Fraction, t1: Fraction, ledger: Ledger
    ) -> None:
        self.t0, self.t1 = t0, t1
        self.c = pencil_coefficients(*A, *B)
        ledger.add("mutual_pencils")
        k = _homothety(A, B)
        self.similar = k is not None
        if k is not None:
            # λ = -p/q < 0 makes the quadratic part vanish: P = (q λ + p)^2 (r2 λ^2 + r1 λ + r0)
            # over Q[t] (Gauss: q λ + p is primitive), and the positive roots are those of the
            # quadratic factor
            p, q = k
            c0, c1, c2, c3, c4 = self.c
            q2 = q * q
            r2 = _exact_quotient(c4, q2)
            r1 = _exact_quotient(c3 - 2 * p * q * r2, q2)
            r0 = _exact_quotient(c2 - 2 * p * q * r1 - p * p * r2, q2)
            assert (c1 - (2 * p * q * r0 + p * p * r1)).is_zero() and (c0 - p * p * r0).is_zero()
            self.r = (r0, r1, r2)
            disc = r1 * r1 - 4 * r2 * r0
            self.D4 = reduce_positive(disc) if not disc.is_zero() else disc
        else:
            d4 = paper_deltas(*self.c)[2]
            self.D4 = reduce_positive(d4) if not d4.is_zero() else d4
            s1, s0 = _subresultant_1()
            self.s1, self.s0 = s1(*self.c, const=fmpq_of), s0(*self.c, const=fmpq_of)
        self.meetings: list[tuple[Any, Any, Any]] = []
        if self.D4.is_zero() and not self.similar:
            # a multiple root at every time without a constant ratio (coaxial spheroids moving
            # along their axis, ...): the roots of the distinct irreducible factors meet only
            # at roots of their discriminants and of their resultants
            self.meetings = _factor_meetings(self.c)
            found = [r for _, _, g in self.meetings for r in real_roots(g, t0, t1, ledger=ledger)]
            self.roots = sort_roots(found)
        else:
            self.roots = [] if self.D4.is_zero() else real_roots(self.D4, t0, t1, ledger=ledger)

    def at_rational(self, t: Fraction) -> str:
        """The state at a rational time: by the sign of the discriminant and, where all four
        roots are real, Descartes' rule (exact then); by isolating the roots of ``P`` where
        the discriminant vanishes."""
        q = fmpq_of(t)
        if not self.D4.is_zero():
            d = self.D4(q)
            if d < 0:  # two real roots (the two negative ones of Wang-Wang-Kim), two non-real
                return OVERLAPPING
            if d > 0 and self.similar:  # two real roots of r2 l^2 + r1 l + r0, product r0 / r2 > 0
                r1, r2 = self.r[1](q), self.r[2](q)
                return SEPARATE if r1 * r2 < 0 else OVERLAPPING  # their sum -r1 / r2 > 0
            if d > 0:  # four distinct real roots, none zero: Descartes' count is exact
                cs = [ck(q) for ck in self.c]
                signs = [c > 0 for c in cs if c != 0]
                changes = sum(1 for u, v in pairwise(signs) if u != v)
                assert changes in (0, 2), "two ellipsoids: 0 or 2 positive roots (Wang-Wang-Kim)"
                return SEPARATE if changes == 2 else OVERLAPPING
        return self.at_rational_by_roots(t)

    def at_rational_by_roots(self, t: Fraction) -> str:
        """The state at a rational time from the isolated positive roots of ``P``."""
        P = flint.fmpq_poly([ck(fmpq_of(t)) for ck in self.c])
        lead = abs(fraction_of(P[P.degree()]))
        bound = 1 + max(abs(fraction_of(P[k])) for k in range(P.degree())) / lead  # Cauchy's bound
        positive = real_roots(P, Fraction(0), bound, multiplicities=True)
        if any(m >= 2 for _, m in positive):
            return TOUCHING
        assert len(positive) in (0, 2), "two ellipsoids: 0 or 2 positive roots (Wang-Wang-Kim)"
        return SEPARATE if positive else OVERLAPPING

    def at_root(self, r: RealAlgebraic, left: str, right: str) -> str:
        """At a root of Δ4: touching iff the double root is positive."""
        if r.is_rational:
            return self.at_rational(r.as_fraction())
        if left != right:
            return TOUCHING  # the apart and overlapping sets are open: their common boundary touches
        if self.similar:  # the double root of the quadratic factor is -r1 / (2 r2)
            r0, r1, r2 = self.r
            return TOUCHING if -sign_at(r1, r) * sign_at(r2, r) > 0 else left
        if self.meetings:  # the common root -s0 / s1 of the factors that meet here
            for s1p, s0p, g in self.meetings:
                if sign_at(g, r) != 0:
                    continue
                s1 = sign_at(s1p, r)
                if s1 == 0:
                    return UNDECIDED
                if -sign_at(s0p, r) * s1 > 0:
                    return TOUCHING
            return left
        s1 = sign_at(self.s1, r)
        if s1 == 0:  # the gcd of P and P' has degree 2 or more here
            return UNDECIDED
        return TOUCHING if -sign_at(self.s0, r) * s1 > 0 else left


def _exact_quotient(a: Any, b: Any) -> Any:
    q, r = divmod(a, b)
    assert r.is_zero(), "an exact division"
    return q


def _factor_meetings(c: Sequence[Any]) -> list[tuple[Any, Any, Any]]:
    """For ``P = Σ c_k(t) l^k`` whose discriminant in ``l`` vanishes identically: for each
    irreducible factor ``f`` of ``P`` over Q (of degree >= 2 in ``l``) with ``f' = ∂f/∂l``,
    and each pair of distinct factors ``f, g``: ``(s1, s0, R)`` with ``R(t)`` the resultant
    in ``l`` (the discriminant of ``f`` up to a factor) and ``s1 l + s0`` the first
    subresultant, whose root ``-s0 / s1`` is the common root where ``R`` vanishes and
    ``s1`` does not (``s1 = s0 = 0`` when the pair has no subresultant of degree 1).
    Exact, with sympy: the path of a rare structural case."""
    import sympy as sp  # sympy is heavy: only in this rare case

    lam, t = sp.symbols("lam t")

    def expr(p: Any) -> Any:
        return sum(sp.Rational(int(v.p), int(v.q)) * t**i for i, v in enumerate(p.coeffs()))

    def poly_t(e: Any) -> Any:
        q = sp.Poly(sp.expand(e), t)
        return flint.fmpq_poly([fmpq_of(Fraction(int(v.p), int(v.q))) for v in reversed(q.all_coeffs())])

    P = sp.expand(sum(expr(ck) * lam**k for k, ck in enumerate(c)))
    _, factors = sp.factor_list(P, lam, t)
    fs = [sp.Poly(f, lam) for f, _ in factors if sp.degree(f, lam) >= 1]
    pairs = [(f, f.diff(lam)) for f in fs if f.degree() >= 2]
    pairs += [(fs[i], fs[j]) for i in range(len(fs)) for j in range(i + 1, len(fs))]
    out = []
    for f, g in pairs:
        res = sp.resultant(f, g)
        linear = [sp.Poly(q, lam) for q in sp.subresultants(f, g) if sp.Poly(q, lam).degree() == 1]
        s1 = poly_t(linear[0].coeff_monomial(lam)) if linear else flint.fmpq_poly([])
        s0 = poly_t(linear[0].coeff_monomial(1)) if linear else flint.fmpq_poly([])
        R = poly_t(res)
        assert not R.is_zero(), "distinct irreducible factors: a resultant that is not zero"
        out.append((s1, s0, reduce_positive(R)))
    return out


def _far_apart(x: MotionSegment, y: MotionSegment, a: Fraction, b: Fraction, reach: Any) -> bool:
    """The centres stay farther apart than ``reach`` (an upper bound of the sum of the two
    largest semi-axes) on ``[a, b]``: ``|p_x(t) - p_y(t)|^2 - reach^2 > 0`` at ``a`` and has
    no real root in ``[a, b]``, decided exactly.  Each body lies within its largest
    semi-axis of its centre, so the solids are apart there."""
    if reach is None:
        return False
    g = flint.fmpq_poly([-reach * reach])
    for k in range(3):
        d = x.center[k] - y.center[k]
        g += d * d
    return bool(g(fmpq_of(a)) > 0) and not real_roots(g, a, b, closed=True)


def _windows(
    sa: Sequence[MotionSegment], sb: Sequence[MotionSegment]
) -> list[tuple[MotionSegment, MotionSegment, Fraction, Fraction]]:
    out = []
    for x in sa:
        for y in sb:
            a, b = max(x.t0, y.t0), min(x.t1, y.t1)
            if a < b:
                out.append((x, y, a, b))
    return out


def _pair_timeline(
    ea: MovingEllipsoid,
    eb: MovingEllipsoid,
    sa: Sequence[MotionSegment],
    sb: Sequence[MotionSegment],
    live: Any,
    ledger: Ledger,
    moved: dict[tuple[str, Fraction], tuple[Any, ...]] | None = None,
    reach: Any = None,
) -> MutualResult:
    """The timeline of one pair; ``live(a, b)`` says whether the broad phase kept the
    pair on ``[a, b]`` (elsewhere the solids are certified apart)."""
    A0, B0 = _negative_inside(ea.quadric), _negative_inside(eb.quadric)
    moved = moved if moved is not None else {}

    def upper(e: MovingEllipsoid, E0: Quadric, seg: MotionSegment) -> tuple[Any, ...]:
        key = (e.name, seg.t0)  # a body's segments start at distinct times
        if key not in moved:
            moved[key] = seg.moved_upper(E0, e.center)
        return moved[key]

    entries: list[tuple[str, Any, str]] = []  # ("instant" | "interval", time or sample, state)
    for x, y, a, b in _windows(sa, sb):
        if not live(a, b) or _far_apart(x, y, a, b, reach):
            if live(a, b):
                ledger.add("separated_windows")
            if not entries:
                entries.append(("instant", a, SEPARATE))
            entries += [("interval", a, SEPARATE), ("instant", b, SEPARATE)]
            continue
        w = _PairWindow(upper(ea, A0, x), upper(eb, B0, y), a, b, ledger)
        points: list[Any] = [a, *w.roots, b]
        states = [w.at_rational(rational_between(points[i], points[i + 1])) for i in range(len(points) - 1)]
        ledger.add("samples", len(states))
        if not entries:
            entries.append(("instant", a, w.at_rational(a)))
        for i, s in enumerate(states):
            entries.append(("interval", points[i], s))
            if i + 1 < len(states):
                entries.append(("instant", points[i + 1], w.at_root(points[i + 1], s, states[i + 1])))
        entries.append(("instant", b, w.at_rational(b)))
    # joints between windows: an instant between two intervals, decided where it was computed
    result = MutualResult(ea.name, eb.name, entries[0][2])
    for i in range(1, len(entries) - 1):
        kind, t, at = entries[i]
        if kind != "instant":
            continue
        before, after = entries[i - 1][2], entries[i + 1][2]
        if before == at == after:
            continue
        time = t if isinstance(t, RealAlgebraic) else RealAlgebraic(Fraction(t))
        if result.events and result.events[-1].time.compare(time) == 0:
            continue
        result.events.append(MutualEvent(time, before, at, after))
    for _kind, t, state in entries:
        if state in (TOUCHING, OVERLAPPING):
            result.first_contact = t if isinstance(t, RealAlgebraic) else RealAlgebraic(Fraction(t))
            break
    return result


def _outward(lo: Any, hi: Any) -> tuple[float, float]:
    """Floats around the rational interval ``[lo, hi]`` (``fmpq``): each end correctly rounded
    (integer division), then moved one step outwards."""
    return (
        math.nextafter(int(lo.p) / int(lo.q), -math.inf),
        math.nextafter(int(hi.p) / int(hi.q), math.inf),
    )


def _boxes(
    bodies: Sequence[MovingEllipsoid],
    segs: Mapping[str, Sequence[MotionSegment]],
    radii: Mapping[str, Any],
    a: Fraction,
    b: Fraction,
) -> np.ndarray:
    """The swept boxes of the bodies on ``[a, b]`` as floats rounded outwards, shape
    ``(bodies, 3, 2)``: each contains the exact rational box
    (:func:`~quadric_contact.scenes.broadphase.swept_box`), so no meeting is lost."""
    out = np.empty((len(bodies), 3, 2))
    for n, e in enumerate(bodies):
        first = True
        for s in segs[e.name]:
            lo, hi = max(a, s.t0), min(b, s.t1)
            if lo > hi:
                continue
            half, rho = radii[e.name]
            part = _swept_box_q(s, rho if s.quaternion is not None else half, fmpq_of(lo), fmpq_of(hi))
            for k in range(3):
                flo, fhi = _outward(*part[k])
                if first or flo < out[n, k, 0]:
                    out[n, k, 0] = flo
                if first or fhi > out[n, k, 1]:
                    out[n, k, 1] = fhi
            first = False
    return out


def _sweep(boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs ``(i, j)``, ``i < j``, of the boxes that meet (closed boxes): sorted by
    their low ``x``, box ``i`` meets along ``x`` exactly the next ones whose low ``x`` is at
    most its high ``x`` (sort and sweep, vectorised); those are tested along ``y`` and ``z``."""
    order = np.argsort(boxes[:, 0, 0], kind="stable")
    lo, hi = boxes[order, 0, 0], boxes[order, 0, 1]
    n = len(order)
    end = np.searchsorted(lo, hi, side="right")
    counts = np.maximum(end - np.arange(1, n + 1), 0)
    first = np.repeat(np.arange(n), counts)
    starts = np.cumsum(counts) - counts
    second = first + 1 + (np.arange(int(counts.sum())) - np.repeat(starts, counts))
    i, j = order[first], order[second]
    meet = np.ones(len(i), dtype=bool)
    for k in (1, 2):
        meet &= (boxes[i, k, 0] <= boxes[j, k, 1]) & (boxes[j, k, 0] <= boxes[i, k, 1])
    i, j = i[meet], j[meet]
    return np.minimum(i, j), np.maximum(i, j)


def mutual_contacts(
    scene: Scene,
    names: Sequence[str] | None = None,
    *,
    broad_phase: bool = True,
    windows: int = 16,
    ledger: Ledger | None = None,
    workers: int = 1,
) -> list[MutualResult]:
    """Exact timelines of every pair of the named moving ellipsoids (all by default).

    Parameters
    ----------
    scene : Scene
    names : sequence of str, optional
        The bodies whose mutual contacts are wanted.
    broad_phase : bool
        Prune pairs by certified swept boxes over ``windows`` equal windows of
        the span (never a real contact); without it every pair gets its pencil
        on every window.
    windows : int
    ledger : Ledger, optional
    workers : int
        Processes to share the pairs between (``0``: one per core; ``1``: this one).

    Returns
    -------
    list of MutualResult
        One per pair that is not apart at some time (pairs apart throughout are
        left out), in the order of the bodies.
    """
    ledger = ledger if ledger is not None else Ledger()
    bodies = [e for e in scene.ellipsoids if names is None or e.name in set(names)]
    t0, t1 = scene.span
    segs = {e.name: e.trajectory.segments(t0, t1, e.center) for e in bodies}
    cuts = [t0 + (t1 - t0) * Fraction(k, windows) for k in range(windows + 1)]
    keep: dict[tuple[int, int], list[tuple[Fraction, Fraction]]] = {}
    radii: dict[str, Any] = {}  # per body: half-extents along the axes, largest semi-axis (fmpq)
    if broad_phase:
        by_shape: dict[tuple[Fraction, ...], Any] = {}
        for e in bodies:  # congruent translates share their extents
            u = e.quadric.upper
            shape = (*(u[k] for k in _QUADRATIC), e.quadric.value_at(e.center))
            if shape not in by_shape:
                half, rho = ellipsoid_extents(e.quadric)
                by_shape[shape] = ([fmpq_of(v) for v in half], [fmpq_of(rho)] * 3)
            radii[e.name] = by_shape[shape]
        for a, b in pairwise(cuts):
            for i, j in zip(*_sweep(_boxes(bodies, segs, radii, a, b)), strict=True):
                keep.setdefault((int(i), int(j)), []).append((a, b))
            ledger.add("broad_phase_tests", len(bodies))
        candidates = sorted(keep)
        ledger.add("pruned_pairs", len(bodies) * (len(bodies) - 1) // 2 - len(candidates))
    else:
        candidates = [(i, j) for i in range(len(bodies)) for j in range(i + 1, len(bodies))]
    if workers == 0:
        workers = multiprocessing.cpu_count()
    if workers > 1 and len(candidates) > 1 and "fork" in multiprocessing.get_all_start_methods():
        size = max(1, len(candidates) // (workers * 8))
        chunks = [candidates[k : k + size] for k in range(0, len(candidates), size)]
        _JOB.update(bodies=bodies, segs=segs, keep=keep, radii=radii if broad_phase else None)
        found: dict[tuple[int, int], MutualResult] = {}
        try:
            with multiprocessing.get_context("fork").Pool(workers) as pool:
                for part, part_ledger in pool.imap_unordered(_run_chunk, chunks):
                    ledger.merge(part_ledger)
                    found.update(part)
        finally:
            _JOB.clear()
        return [found[k] for k in sorted(found)]
    _JOB.update(bodies=bodies, segs=segs, keep=keep, radii=radii if broad_phase else None)
    try:
        part, _ = _run_chunk(candidates, ledger)
    finally:
        _JOB.clear()
    return [part[k] for k in sorted(part)]


_JOB: dict[str, Any] = {}


def _run_chunk(
    candidates: Sequence[tuple[int, int]], ledger: Ledger | None = None
) -> tuple[dict[tuple[int, int], MutualResult], Ledger]:
    """The timelines of the pairs ``candidates`` (indices into the job's bodies) that meet."""
    ledger = ledger if ledger is not None else Ledger()
    bodies, segs, keep, radii = (_JOB[k] for k in ("bodies", "segs", "keep", "radii"))
    broad_phase = radii is not None
    moved: dict[tuple[str, Fraction], tuple[Any, ...]] = {}  # each body's matrix in t, once per segment
    out = {}
    for i, j in candidates:
        ea, eb = bodies[i], bodies[j]
        spans = keep.get((i, j), [])

        def live(a: Fraction, b: Fraction, spans: list[tuple[Fraction, Fraction]] = spans) -> bool:
            return not broad_phase or any(lo < b and a < hi for lo, hi in spans)

        reach = (radii[ea.name][1][0] + radii[eb.name][1][0]) if broad_phase else None
        r = _pair_timeline(ea, eb, segs[ea.name], segs[eb.name], live, ledger, moved, reach)
        if r.first_contact is not None:
            out[i, j] = r
    return out, ledger
