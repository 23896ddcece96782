"""The work ledger of a scene run: what was computed, against what a full evaluation would cost.

Section 5.2 of the paper insists that a piece's characteristic polynomial
"shall be computed only if needed, depending on the zone the ellipsoid is
placed".  The ledger makes that measurable: every unit of work done by
:mod:`quadric_contact.scenes.composite`, :mod:`quadric_contact.scenes.events` and
:mod:`quadric_contact.scenes.simulate` is counted here, and the simulator adds,
for comparison, what evaluating every effect for every piece would have
cost (:meth:`Ledger.add_full`).

Counted items
-------------
``characteristic_polynomials``
    Pencils ``det(lambda E + Q)`` formed: one per (ellipsoid, motion segment,
    plane or piece) when the coefficients are polynomials in time, one per
    pair for a static query.
``discriminants``
    Members of the discrimination system formed (``D2, D3, D4`` of a piece's
    pencil, ``c3^2 - 4 c4 c2`` of a plane's, which has the sign of the
    paper's ``Delta_3``).
``coefficient_signs``
    Coefficient polynomials ``c1, c2, c3`` kept for the root-sign pattern of
    Table 4 (only when the relative position is asked for).
``root_isolations``
    Exact real-root isolations: one per distinct irreducible factor of a
    critical polynomial in time.
``escalations``
    Ball evaluations that could not decide a sign at an algebraic event time
    and had to refine the isolating interval (and double the precision).
``samples``, ``instants``
    State decisions at rational sample times between events and at the
    exact (algebraic) event times.
``smallness_checks``
    Smallness of a moving ellipsoid with respect to a piece (Tables 1, 2).
``broad_phase_tests``
    Certified box tests of the broad phase (:mod:`quadric_contact.scenes.broadphase`):
    a plane or a piece against the box swept by an ellipsoid on a time interval.
``pruned_pairs``
    (Ellipsoid, motion segment, plane or piece) pairs whose pencil in time the
    broad phase proved unnecessary: the target is out of reach or certified
    on one side for the whole segment.
``pruned_stretches``
    Stretches of a segment certified by the broad phase for a target whose
    pencil in time is still formed, on the other stretches only.
``static_pencils``
    Pencils of one frozen placement, formed to state a certified stretch
    exactly as the pencil in time would (one per target and side).
``section_pencils``
    Geometric reading: pencils of the conics cut by a plane from the moving
    ellipsoid and a piece's quadric, with its discriminant in ``t`` and the
    discriminant of the piece's pencil (one per piece, plane and segment).
``section_samples``
    Does the curve ``E ∩ Q`` meet a cutting plane at a sample time (a cubic's
    roots and one inertia per gap).
``mutual_pencils``
    Pencils ``det(λ A(t) + B(t))`` of two moving ellipsoids (one per pair the
    broad phase keeps and window of time).
``separated_windows``
    (Pair of moving ellipsoids, window of time) that the broad phase keeps but
    that are certified apart without a pencil: their centres stay farther apart
    than the sum of their radii (an exact polynomial in ``t`` without roots).
``level_sweeps``
    Does the curve ``E ∩ Q`` lie on the kept side, decided by sweeping the
    levels of the cutting plane (at a sample time where it does not meet it).
``distance_evaluations``
    Signed distances of a moving ellipsoid from a piece's solid, evaluated at one
    time each for the ``distance`` effect (:mod:`quadric_contact.scenes.scene_distance`).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import Any

__all__ = ["ITEMS", "Ledger"]

ITEMS: tuple[str, ...] = (
    "characteristic_polynomials",
    "discriminants",
    "coefficient_signs",
    "root_isolations",
    "escalations",
    "samples",
    "instants",
    "smallness_checks",
    "broad_phase_tests",
    "pruned_pairs",
    "pruned_stretches",
    "static_pencils",
    "section_pencils",
    "section_samples",
    "level_sweeps",
    "mutual_pencils",
    "separated_windows",
    "distance_evaluations",
)
"""The counted items, in report order."""

OPTIONAL_ITEMS: frozenset[str] = frozenset(
    {
        "broad_phase_tests",
        "pruned_pairs",
        "pruned_stretches",
        "static_pencils",
        "section_pencils",
        "section_samples",
        "level_sweeps",
        "mutual_pencils",
        "separated_windows",
        "distance_evaluations",
    }
)
"""Items printed only when something was counted (the broad phase's, the geometric
reading's, the mutual contacts', the distance's)."""

FULL_ITEMS: tuple[str, ...] = (
    "characteristic_polynomials",
    "discriminants",
    "coefficient_signs",
    "smallness_checks",
)
"""Items whose full-evaluation cost is known without doing the work (the
others depend on roots that a full evaluation would have to find first)."""


@dataclass
class Ledger:
    """Counts of the work done, by item and by target.

    Attributes
    ----------
    done : Counter
        Item -> count of work actually done.
    full : Counter
        Item -> count that evaluating every effect for every piece on every
        motion segment would have cost (filled by the simulator for the items
        of :data:`FULL_ITEMS`).
    by_target : dict
        Target label -> Counter of the work done for it, so that a test can
        assert that a piece the ellipsoid never approached cost nothing.

    Examples
    --------
    >>> led = Ledger()
    >>> led.add("characteristic_polynomials", target="tree/trunk")
    >>> led.cost("tree/trunk"), led.cost("tree/crown")
    (1, 0)
    """

    done: Counter[str] = field(default_factory=Counter)
    full: Counter[str] = field(default_factory=Counter)
    by_target: dict[str, Counter[str]] = field(default_factory=dict)

    def add(self, item: str, count: int = 1, target: str | None = None) -> None:
        """Record ``count`` units of ``item`` (optionally for ``target``)."""
        if item not in ITEMS:
            raise KeyError(f"unknown ledger item {item!r}; known: {ITEMS}")
        if count == 0:
            return
        self.done[item] += count
        if target is not None:
            self.by_target.setdefault(target, Counter())[item] += count

    def add_full(self, item: str, count: int = 1) -> None:
        """Record what a full evaluation would cost for ``item``."""
        if item not in FULL_ITEMS:
            raise KeyError(f"the full cost of {item!r} is not estimated; estimated: {FULL_ITEMS}")
        self.full[item] += count

    def cost(self, target: str) -> int:
        """Total units of work done for ``target`` (0 if never touched)."""
        return sum(self.by_target.get(target, Counter()).values())

    def merge(self, other: Ledger) -> None:
        """Add the counts of ``other`` to these."""
        self.done.update(other.done)
        self.full.update(other.full)
        for k, v in other.by_target.items():
            self.by_target.setdefault(k, Counter()).update(v)

    def to_dict(self) -> dict[str, Any]:
        """The counts as JSON-ready data."""
        return {
            "done": {k: self.done.get(k, 0) for k in ITEMS},
            "full_evaluation": {k: self.full.get(k, 0) for k in FULL_ITEMS},
            "by_target": {t: dict(c) for t, c in sorted(self.by_target.items())},
        }

    def format(self) -> str:
        """A small table: item, done, full evaluation (where known), saving."""
        width = max(len(k) for k in ITEMS)
        lines = [f"{'work item':<{width}}  {'done':>8}  {'full':>8}  saved"]
        for k in ITEMS:
            done = self.done.get(k, 0)
            if k in OPTIONAL_ITEMS and not done:
                continue
            if k in FULL_ITEMS and self.full.get(k, 0):
                full = self.full[k]
                saved = f"{100 * (full - done) / full:5.1f}%" if full else ""
                lines.append(f"{k:<{width}}  {done:>8}  {full:>8}  {saved}".rstrip())
            else:
                lines.append(f"{k:<{width}}  {done:>8}")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.format()
