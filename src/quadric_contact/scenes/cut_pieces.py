"""Pieces as cut: contact with ``Q ∩ H`` for a moving ellipsoid, exactly.

The geometric reading of a scene (the default; ``reading = "paper"`` keeps
Algorithm 1's reading, where a piece reached by the descent counts as its
whole quadric).  A piece is the part of its quadric ``Q`` on the kept side
``H`` of every plane on its path in the object's tree.  While the ellipsoid
lies on the kept side of all of them, the piece and its quadric give the same
answer.  Where it crosses one plane ``Π`` of the path (Algorithm 1's Zone 0),
it crosses the piece iff the curve ``C(t) = E(t) ∩ Q`` of a transversal
contact has a point in ``H``.

In time, that answer can change only where the whole-quadric state or the
zone changes, or where ``C(t)`` meets ``Π`` anew: where the section conics
``E(t) ∩ Π`` and ``Q ∩ Π`` become tangent, a real root of the discriminant
``G(t)`` of ``det(λ E_Π(t) + Q_Π)`` (:class:`SectionTrack`).  Between such
times it is decided at a rational sample time by
:func:`~quadric_contact.theory.sections.curve_meets_half_space`; at each of
them from the neighbouring intervals and the exact signs there
(:func:`resolve_cut`).  The reduction is proved in
``proofs/pieces_as_cut.py``.

What is not decided is said so (contact undecided, with the reason): an
ellipsoid crossing two cutting planes of one piece at once, section conics
tangent at every instant, and, for pieces whose pencil with the ellipsoid
has a multiple root at every instant (other than a quadric homothetic to
the ellipsoid, or a plane), an intersection curve that may have several
components.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from fractions import Fraction
from typing import Any

import flint

from quadric_contact._generated.formulas import paper_deltas, pencil_coefficients
from quadric_contact.exact.algebraic import RealAlgebraic, sign_at
from quadric_contact.exact.rational import fmpq_of, fraction_of
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.events import PieceValue, _Track, reduce_positive
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.theory.sections import (
    conic_pencil_coefficients,
    conics_meet,
    cubic_discriminant,
    curve_meets_half_space,
    section_matrix,
)

__all__ = ["SectionTrack", "resolve_cut"]

TimePoint = Any


def _const(v: Fraction) -> Any:
    return flint.fmpq_poly([fmpq_of(v)])


class SectionTrack(_Track):
    """The section by a cutting plane of a moving ellipsoid and a piece's quadric.

    Its only critical polynomial is ``G(t)``, the discriminant in ``λ`` of
    ``det(λ E_Π(t) + Q_Π)``: where it does not vanish the section conics
    meet in four distinct points (over C), so the number of real common
    points, and whether ``C(t)`` meets the plane, is constant.  Its state at a
    time is the sign of ``G``; :meth:`meets` and :meth:`double_point_real` answer
    the questions :func:`resolve_cut` asks.

    Attributes
    ----------
    degenerate : bool
        ``G`` vanishes identically (the conics are tangent at every instant).
    smooth : bool
        Between the roots of the pencil's discriminant ``Δ4(t)`` the real curve
        ``E(t) ∩ Q`` is smooth: ``Δ4`` is not identically zero, or ``Q`` is a
        plane or has a quadratic part proportional to ``E``'s (then the curve
        is one plane section of ``E``).
    """

    def __init__(
        self,
        label: str,
        E_upper: Sequence[Any],
        Q: Quadric,
        plane: Quadric,
        side: int,
        t0: Fraction,
        t1: Fraction,
        ledger: Ledger,
        positive: Any = None,
    ) -> None:
        super().__init__(label, t0, t1, ledger, positive)
        self.Q, self.plane, self.side = Q, plane, side
        one = flint.fmpq_poly([1])
        self.A = section_matrix(E_upper, plane, one=one)
        self.B = section_matrix(Q.upper, plane)
        Bp = [[_const(v) for v in row] for row in self.B]
        self.c = tuple(conic_pencil_coefficients(self.A, Bp))
        ledger.add("section_pencils", target=label)
        G = cubic_discriminant(*self.c)
        self.degenerate = G.is_zero()
        self.G = G if self.degenerate else reduce_positive(G, positive)
        raw = pencil_coefficients(*E_upper, *(_const(v) for v in Q.upper))
        d4 = paper_deltas(*raw)[2]
        self.D4 = d4 if d4.is_zero() else reduce_positive(d4, positive)
        self.smooth = not self.D4.is_zero() or Q.kind is QuadricKind.PLANE or _homothetic(E_upper, Q)
        self.critical = [] if self.degenerate else [self.G]
        self._find_roots()

    def decide(self, sign: Callable[[Any], int], t: TimePoint) -> int:
        return 0 if self.degenerate else sign(self.G)

    def sign_G(self, t: TimePoint) -> int:
        return 0 if self.degenerate else sign_at(self.G, t, self.ledger)

    def sign_D4(self, t: TimePoint) -> int:
        return 0 if self.D4.is_zero() else sign_at(self.D4, t, self.ledger)

    def section_at(self, t: Fraction) -> list[list[Fraction]]:
        return [[fraction_of(p(fmpq_of(t))) for p in row] for row in self.A]

    def meets(self, t: Fraction) -> bool:
        """At a rational time where ``E`` crosses the plane: does ``C(t)`` meet it?"""
        self.ledger.add("section_samples", target=self.label)
        return conics_meet(self.section_at(t), self.B)

    def double_point_real(self, r: TimePoint) -> bool | None:
        """At a root of ``G``: the section conics are tangent at one real point
        (True), at two points only (None: a double member of rank 1), or the
        cubic has a triple root (None)."""
        c0, c1, c2, c3 = self.c
        den = c2 * c2 - 3 * c3 * c1  # (p - q)^2 for a double root p and a simple root q
        if sign_at(den, r, self.ledger) == 0:
            return None
        num = 9 * c3 * c0 - c2 * c1  # 2 p (p - q)^2: the double root is num / (2 den)
        M = [[num * self.A[i][j] + 2 * den * _const(self.B[i][j]) for j in range(3)] for i in range(3)]
        for i, j in ((0, 1), (0, 2), (1, 2)):
            for k, m in ((0, 1), (0, 2), (1, 2)):
                minor = M[i][k] * M[j][m] - M[i][m] * M[j][k]
                if sign_at(minor, r, self.ledger) != 0:
                    return True
        return None


def _homothetic(E_upper: Sequence[Any], Q: Quadric) -> bool:
    """``Q``'s quadratic part is a constant multiple of ``E(t)``'s (or zero) for every ``t``."""
    quad = (0, 1, 2, 4, 5, 7)  # q00 q01 q02 q11 q12 q22
    qs = [Q.upper[k] for k in quad]
    es = [E_upper[k] for k in quad]
    if all(v == 0 for v in qs):
        return True
    k = next(i for i in range(6) if qs[i] != 0)
    # q_i E_k - q_k E_i = 0 for all i (as polynomials in t)
    return all((fmpq_of(qs[i]) * es[k] - fmpq_of(qs[k]) * es[i]).is_zero() for i in range(6))


def resolve_cut(
    track: SectionTrack,
    whole: PieceValue,
    t: TimePoint,
    E_at: Callable[[Fraction], Quadric],
    *,
    interval: bool,
    left: tuple[bool | None, bool | None] | None = None,
    right: tuple[bool | None, bool | None] | None = None,
) -> tuple[bool | None, bool | None, str]:
    """Contact with the piece as cut by ``track.plane`` at one time point, where
    the ellipsoid crosses that plane.

    Parameters
    ----------
    track : SectionTrack
    whole : PieceValue
        The state against the whole quadric at ``t``.
    t : Fraction or RealAlgebraic
        A rational sample time of an interval (``interval``), or an instant.
    E_at : callable
        The ellipsoid at a rational time.
    left, right : (contact, meets) pairs, optional
        At an instant: the answers on the neighbouring intervals, and whether
        ``C`` met the plane there.

    Returns
    -------
    (contact, meets, reason)
        Contact with the piece as cut (None: undecided); whether ``C(t)`` meets
        the plane (None: not known or not needed); what decided.
    """
    if whole.contact is not True:
        return whole.contact, None, "no transversal contact with the whole quadric"
    if track.degenerate:
        return None, None, "the section conics are tangent at every instant"
    rational = isinstance(t, Fraction) or (isinstance(t, RealAlgebraic) and t.is_rational)
    tq = t if isinstance(t, Fraction) else (t.as_fraction() if rational else None)
    static = tq is not None and track.sign_G(tq) != 0 and (track.sign_D4(tq) != 0 or _plane_curve(track))
    if interval or static:
        assert tq is not None
        if track.meets(tq):
            return True, True, "the curve E ∩ Q crosses the cutting plane"
        if not track.smooth:
            return None, False, "the intersection curve may have several components"
        track.ledger.add("level_sweeps", target=track.label)
        inside = curve_meets_half_space(E_at(tq), track.Q, track.plane, track.side)
        if inside is None:
            return None, False, "the level sections are tangent at every level"
        return (
            inside,
            False,
            ("the curve E ∩ Q lies on the kept side" if inside else "the curve E ∩ Q lies beyond the cut"),
        )
    near = [n for n in (left, right) if n is not None]
    g0 = track.sign_G(t) == 0
    d0 = track.sign_D4(t) == 0 and not _plane_curve(track)
    if not g0:
        if any(m for _, m in near):
            return True, True, "the curve E ∩ Q crosses the cutting plane"
        values = {c for c, _ in near}
        if d0:
            if False in values:
                return False, False, "a crossing in the piece would persist on both sides of this instant"
            return None, False, "the surfaces touch at this instant, away from the cutting plane"
        if len(values) == 1:
            return values.pop(), False, "as on both sides (nothing meets the plane here)"
        return None, False, "the neighbouring intervals disagree"
    if d0:
        return None, None, "the section conics are tangent where the surfaces touch"
    if any(m for _, m in near):
        return True, True, "the curve E ∩ Q meets the cutting plane"
    real = track.double_point_real(t)
    if real:
        return True, True, "the curve E ∩ Q touches the cutting plane"
    return None, None, "the section conics are tangent at two points"


def _plane_curve(track: SectionTrack) -> bool:
    """The curve is a plane section of ``E`` (smooth wherever it is a crossing)."""
    return track.smooth and track.D4.is_zero()


def cut_value(whole: PieceValue, contact: bool | None, reason: str, split_name: str) -> PieceValue:
    """The piece's state as cut, from its whole-quadric state."""
    if contact is True and whole.contact is True:
        return replace(whole, decided_by=f"{whole.decided_by}; as cut by {split_name}: {reason}")
    if contact is False and whole.contact is True:
        return replace(
            whole,
            contact=False,
            region=None,
            kind="none" if whole.kind is not None else None,
            decided_by=f"{whole.decided_by}; as cut by {split_name}: {reason}",
            region_asked=False,
            beyond_cut=True,
        )
    if contact is None and whole.contact is True:
        return replace(
            whole,
            contact=None,
            region=None,
            kind="undecided" if whole.kind is not None else None,
            decided_by=f"as cut by {split_name}: undecided: {reason}",
            region_asked=False,
        )
    return whole
