"""Run a scene: plan from the requested effects, exact event timeline, work ledger.

For each moving ellipsoid and each object, each motion segment is processed
as Algorithms 1 and 2 prescribe, but in time (:mod:`quadric_contact.events`):

1. the pencil of the ellipsoid against the root plane of the object's tree
   is formed with polynomial coefficients in ``t``; the real roots of its
   critical polynomial are isolated exactly and the zone is classified on
   every interval between them and at every root;
2. a child of a plane (another plane, or a piece) is processed only if the
   zone reaches it somewhere in the segment; a piece's pencil (and its
   ``D2..D4``, and ``c1..c3`` if the relative position is wanted) is formed
   only then: "computed only if needed, depending on the zone" (Section 5.2);
3. all roots found are merged; on every interval between consecutive ones
   the state is constant and is decided at a rational sample time, and at
   every root exactly at the algebraic number; an event is reported where
   the state changes.

The plan follows the effects: ``zone`` alone never forms a piece's pencil;
``relative_position`` adds the coefficient polynomials; ``first_contact``
alone stops at the first contact; smallness is checked only for effects that
rely on Theorem 2.  The :class:`~quadric_contact.ledger.Ledger` counts
everything and compares it with a full evaluation of every effect for every
piece.

References
----------
Section 5.2, Algorithms 1 and 2, Corollaries 10 and 15, Theorem 13.
"""

from __future__ import annotations

import functools
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace
from fractions import Fraction
from typing import Any

from .algebraic import RealAlgebraic, rational_between
from .composite import Composite, Piece, Split
from .errors import SceneError
from .events import (
    PieceTrack,
    PieceValue,
    PlaneTrack,
    ZoneValue,
    _Track,
)
from .ledger import Ledger
from .quadric import Quadric
from .results import Region
from .scene import EFFECTS, MovingEllipsoid, Scene
from .trajectory import MotionSegment, poly_eval

__all__ = [
    "Episode",
    "Event",
    "ObjectState",
    "PairResult",
    "Plan",
    "SimulationResult",
    "simulate",
]

TimePoint = Any  # Fraction or RealAlgebraic


@dataclass(frozen=True)
class Plan:
    """What a run computes, derived from the requested effects.

    Attributes
    ----------
    effects : tuple of str
    pieces : bool
        Pieces are evaluated at all (contact, kind, region or first contact asked for).
    region, kind : bool
        Keep the coefficient polynomials / classify the contact kind.
    stop_at_first_contact : bool
        Only ``first_contact`` (with ``smallness``) is asked for: stop each
        (ellipsoid, object) at its first contact.
    full : bool
        Evaluate every effect for every piece on every segment (for comparison).
    """

    effects: tuple[str, ...]
    pieces: bool
    region: bool
    kind: bool
    stop_at_first_contact: bool
    full: bool = False

    @classmethod
    def from_effects(cls, effects: Iterable[str], *, full: bool = False) -> Plan:
        """The plan for a set of effects (:data:`~quadric_contact.scene.EFFECTS`).

        Raises
        ------
        SceneError
            An unknown effect, or none at all.

        Examples
        --------
        >>> Plan.from_effects(["zone"]).pieces, Plan.from_effects(["first_contact"]).stop_at_first_contact
        (False, True)
        """
        eff = tuple(dict.fromkeys(effects))
        bad = [e for e in eff if e not in EFFECTS]
        if bad:
            raise SceneError(f"unknown effect(s) {bad}; expected some of {list(EFFECTS)}", bad)
        if not eff:
            raise SceneError(f"no effect requested; expected some of {list(EFFECTS)}")
        pieces = bool({"contact", "contact_kind", "relative_position", "first_contact"} & set(eff))
        stop = "first_contact" in eff and not (
            {"zone", "contact", "contact_kind", "relative_position"} & set(eff)
        )
        return cls(
            eff,
            pieces or full,
            "relative_position" in eff or full,
            "contact_kind" in eff or full,
            stop and not full,
            full,
        )

    def restricted(self, effects: Iterable[str] | None) -> Plan:
        """The plan for one ellipsoid or one (ellipsoid, piece) pair that asks for
        ``effects`` only (None: no restriction): the effects both ask for.

        Examples
        --------
        >>> Plan.from_effects(["zone", "contact"]).restricted(["contact", "relative_position"]).effects
        ('contact',)
        >>> Plan.from_effects(["contact"]).restricted(["zone"]).pieces
        False
        """
        if effects is None or self.full:
            return self
        wanted = set(effects)
        kept = tuple(e for e in self.effects if e in wanted)
        if not kept:
            return Plan((), False, False, False, False)
        return Plan.from_effects(kept)

    def describe(self) -> str:
        """The plan in one sentence (printed with the timeline)."""
        steps = ["Algorithm 1 (zones) on every separating plane the descent reaches"]
        if self.pieces:
            what = "Algorithm 2 (Corollary 10) on the pieces of the zone only"
            if self.region:
                what += ", Table 4 root signs"
            if self.kind:
                what += ", contact kind (Table 3)"
            steps.append(what)
        if self.stop_at_first_contact:
            steps.append("stop at the first contact")
        if self.full:
            steps = ["every effect for every plane and piece on every segment (full evaluation)"]
        return "; ".join(steps)


@dataclass(frozen=True)
class ObjectState:
    """State of one ellipsoid against one object at a time point or on an interval.

    ``zones``: (plane name, :class:`ZoneValue`) for the planes Algorithm 1
    visited; ``pieces``: (piece name, :class:`PieceValue` or None when piece
    states were not requested) for the pieces of the zone.
    """

    zones: tuple[tuple[str, ZoneValue], ...]
    pieces: tuple[tuple[str, PieceValue | None], ...]

    @property
    def contact(self) -> bool | None:
        """Transversal contact with some piece (None: undecided for some, none found)."""
        vals = [v.contact for _, v in self.pieces if v is not None]
        if any(v is True for v in vals):
            return True
        if any(v is None for v in vals):
            return None
        return False

    @property
    def touching(self) -> list[str]:
        """Names of the pieces in transversal contact."""
        return [n for n, v in self.pieces if v is not None and v.contact]

    def summary(self, obj: Composite | None = None, *, with_zones: bool = True) -> str:
        """One line: the zones visited and each evaluated piece's state (``obj``
        glosses ``R-``/``R+`` as inside/outside)."""
        parts = []
        if with_zones and self.zones:
            parts.append("zone " + ", ".join(f"[{n}] {z}" for n, z in self.zones))
        evaluated = [(n, v) for n, v in self.pieces if v is not None]
        inside = {p.name: p.inside for p in obj.pieces} if obj is not None else {}
        if evaluated:
            parts.append("; ".join(f"{n}: {v.describe(inside.get(n))}" for n, v in evaluated))
        elif self.pieces:
            parts.append("pieces in zone: " + ", ".join(n for n, _ in self.pieces))
        else:
            parts.append("no piece in zone")
        return " | ".join(parts)

    def category(self, obj: Composite) -> str:
        """One word for plots: contact, inside, outside, undecided, or the zone."""
        c = self.contact
        evaluated = [(n, v) for n, v in self.pieces if v is not None]
        if not evaluated:
            return "zone " + "/".join(str(z.zone) for _, z in self.zones) if self.zones else "free"
        if c:
            return "contact"
        if c is None:
            return "undecided"
        pieces = {p.name: p for p in obj.pieces}
        regions = [v.region for n, v in evaluated if v.region is not None]
        if regions and len(regions) == len(evaluated):
            inside = [v.region == pieces[n].inside for n, v in evaluated]
            if all(inside):
                return "inside"
            if not any(inside):
                return "outside"
            return "mixed"
        return "no contact"

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        if self.zones:
            out["zones"] = {
                n: {"region": z.region.value, "zone": z.zone, "tangent": z.tangent} for n, z in self.zones
            }
        pieces: dict[str, Any] = {}
        for n, v in self.pieces:
            if v is None:
                pieces[n] = "in zone"
            else:
                d: dict[str, Any] = {"contact": v.contact, "decided_by": v.decided_by}
                if v.region is not None:
                    d["region"] = v.region.value
                if v.kind is not None:
                    d["kind"] = v.kind
                pieces[n] = d
        out["pieces"] = pieces
        return out


@dataclass
class Episode:
    """A maximal stretch of time with one state: ``[start, end]`` closed or open
    at each end (``closed_start``/``closed_end``); an instant has ``start == end``."""

    start: TimePoint
    end: TimePoint
    state: ObjectState
    closed_start: bool
    closed_end: bool
    sample: Fraction | None = None


@dataclass
class Event:
    """The state changes at an exact time: ``before`` (on the interval just
    before), ``at`` (at the instant), ``after`` (just after)."""

    time: RealAlgebraic
    before: ObjectState | None
    at: ObjectState
    after: ObjectState | None

    def changes(self, obj: Composite | None = None) -> list[str]:
        """Human-readable descriptions of what changed (``obj`` glosses R-/R+ as inside/outside)."""
        inside = {p.name: p.inside for p in obj.pieces} if obj is not None else {}
        out: list[str] = []
        b = self.before or self.at
        a = self.after or self.at

        def describe(kind: str, name: str, x: str, y: str, z: str) -> None:
            if x == y == z:
                return
            if x != z:
                tail = f" (at the instant: {y})" if y not in (x, z) else ""
                out.append(f"{kind}{name}: {x} -> {z}{tail}")
            else:
                out.append(f"{kind}{name}: {y} at the instant only (before and after: {x})")

        zb, zt, za = dict(b.zones), dict(self.at.zones), dict(a.zones)
        for name in dict.fromkeys([*zb, *zt, *za]):
            x, y, z = (str(d[name]) if name in d else "not visited" for d in (zb, zt, za))
            describe("zone of plane ", name, x, y, z)
        pb, pt, pa = dict(b.pieces), dict(self.at.pieces), dict(a.pieces)
        for name in dict.fromkeys([*pb, *pt, *pa]):
            x, y, z = (_piece_text(d, name, inside.get(name)) for d in (pb, pt, pa))
            describe("", name, x, y, z)
        return out

    def to_dict(self, places: int) -> dict[str, Any]:
        return {
            "time": self.time.to_dict(places),
            "changes": self.changes(),
            "before": None if self.before is None else self.before.to_dict(),
            "at": self.at.to_dict(),
            "after": None if self.after is None else self.after.to_dict(),
        }


@dataclass
class PairResult:
    """The timeline of one moving ellipsoid against one object."""

    ellipsoid: str
    object: Composite
    episodes: list[Episode]
    events: list[Event]
    first_contact: tuple[RealAlgebraic, list[str]] | None
    complete: bool = True
    segments_done: int = 0

    @property
    def initial(self) -> ObjectState:
        """The state at the start of the time span."""
        return self.episodes[0].state

    def state_at(self, t: Any) -> ObjectState:
        """The state at a rational time ``t`` of the span (from the exact timeline).

        Raises
        ------
        ValueError
            ``t`` is outside the computed part of the span.

        Examples
        --------
        Example 17's bee, inside the crown at ``t = 6``:

        >>> from quadric_contact.scene import builtin_scene
        >>> pair = simulate(builtin_scene()).pair("bee", "tree")
        >>> pair.state_at(6).summary(pair.object)
        'zone [z - 6] R+ | crown: no contact, R- (inside)'
        """
        t = Fraction(t)
        for ep in self.episodes:
            lo = _as_root(ep.start).compare(t)  # start vs t
            hi = _as_root(ep.end).compare(t)
            after_start = lo < 0 or (lo == 0 and ep.closed_start)
            before_end = hi > 0 or (hi == 0 and ep.closed_end)
            if after_start and before_end:
                return ep.state
        raise ValueError(f"t = {t} is not in the computed part of the time span")

    def to_dict(self, places: int, effects: Sequence[str]) -> dict[str, Any]:
        out: dict[str, Any] = {
            "ellipsoid": self.ellipsoid,
            "object": self.object.name,
            "complete": self.complete,
        }
        if self.complete:
            out["events"] = [e.to_dict(places) for e in self.events]
            out["episodes"] = [
                {
                    "start": _time_dict(ep.start, places),
                    "end": _time_dict(ep.end, places),
                    "closed": [ep.closed_start, ep.closed_end],
                    "sample_time": None if ep.sample is None else str(ep.sample),
                    "state": ep.state.to_dict(),
                }
                for ep in self.episodes
            ]
        if "first_contact" in effects:
            out["first_contact"] = (
                None
                if self.first_contact is None
                else {"time": self.first_contact[0].to_dict(places), "pieces": self.first_contact[1]}
            )
        return out


def _piece_text(d: dict[str, PieceValue | None], name: str, inside: Region | None = None) -> str:
    if name not in d:
        return "not in zone"
    v = d[name]
    return "in zone" if v is None else v.describe(inside)


def _as_root(t: TimePoint) -> RealAlgebraic:
    return t if isinstance(t, RealAlgebraic) else RealAlgebraic(Fraction(t))


def _time_dict(t: TimePoint, places: int) -> dict[str, Any]:
    return _as_root(t).to_dict(places)


def _fmt_time(t: TimePoint, places: int) -> str:
    r = _as_root(t)
    if r.is_rational:
        v = r.lo
        return str(v) if v.denominator == 1 else f"{r.decimal(places)} (= {v})"
    return r.decimal(places)


@dataclass
class SimulationResult:
    """Everything a run produced."""

    scene: Scene
    plan: Plan
    pairs: list[PairResult]
    ledger: Ledger
    seconds: float
    warnings: list[str] = field(default_factory=list)

    def pair(self, ellipsoid: str, obj: str) -> PairResult:
        """The timeline of one ellipsoid against one object (``KeyError`` if there is none)."""
        for p in self.pairs:
            if p.ellipsoid == ellipsoid and p.object.name == obj:
                return p
        raise KeyError((ellipsoid, obj))

    def to_dict(self, places: int | None = None) -> dict[str, Any]:
        """Everything as JSON-ready data (``quadric-contact simulate --json``); event
        times with ``places`` decimals, their polynomials and isolating intervals."""
        places = self.scene.places if places is None else places
        out: dict[str, Any] = {
            "scene": self.scene.name,
            "source": self.scene.source,
            "time_span": [str(self.scene.span[0]), str(self.scene.span[1])],
            "effects": list(self.plan.effects),
            "plan": self.plan.describe(),
            "events": sum(len(p.events) for p in self.pairs),
            "pairs": [p.to_dict(places, self.plan.effects) for p in self.pairs],
            "ledger": self.ledger.to_dict(),
            "seconds": round(self.seconds, 6),
            "warnings": self.warnings,
        }
        if "smallness" in self.plan.effects:
            out["smallness"] = [
                {
                    "ellipsoid": c.ellipsoid,
                    "object": c.object,
                    "piece": c.piece,
                    "small": c.small,
                    "report": None if c.report is None else str(c.report),
                    "note": c.note,
                }
                for c in self.scene.smallness.values()
            ]
        return out

    def format_text(self, places: int | None = None) -> str:
        """The timeline as printed by ``quadric-contact simulate`` (event times to ``places`` decimals)."""
        places = self.scene.places if places is None else places
        lines = [self.scene.describe(), f"plan: {self.plan.describe()}"]
        if "smallness" in self.plan.effects or any(c.small is False for c in self.scene.smallness.values()):
            lines.append("smallness (Tables 1, 2):")
            lines += [f"  {c}" for c in self.scene.smallness.values()]
        for w in self.warnings:
            lines.append(f"warning: {w}")
        lines.append(
            f"event times: exact real algebraic numbers, shown to {places} decimal places "
            "(--places N; --json gives each one's polynomial and isolating interval)"
        )
        for p in self.pairs:
            own = self.plan.restricted(self.scene.ellipsoid_effects.get(p.ellipsoid)).effects
            show_zones = "zone" in own
            show_timeline = bool({"zone", "contact", "contact_kind", "relative_position"} & set(own))
            lines.append("")
            lines.append(f"{p.ellipsoid} vs {p.object.name}")
            if p.complete and show_timeline:
                start = p.initial.summary(p.object, with_zones=show_zones)
                lines.append(f"  t = {_fmt_time(self.scene.span[0], places)}: start: {start}")
                for ev in p.events:
                    changes = ev.changes(p.object)
                    if not show_zones:
                        changes = [c for c in changes if not c.startswith("zone of plane")]
                        if not changes:
                            continue
                    head = f"  t = {_fmt_time(ev.time, places)}: "
                    lines.append(head + changes[0])
                    lines += [" " * len(head) + c for c in changes[1:]]
                end = p.episodes[-1].state.summary(p.object, with_zones=show_zones)
                lines.append(f"  t = {_fmt_time(self.scene.span[1], places)}: end: {end}")
            if "first_contact" in own:
                if p.first_contact is None:
                    lines.append("  first contact: none in the time span")
                else:
                    t, names = p.first_contact
                    extra = "" if p.complete else f" (stopped there, after {p.segments_done} segment(s))"
                    lines.append(
                        f"  first contact: t = {_fmt_time(t, places)} with {', '.join(names)}{extra}"
                    )
        lines.append("")
        events = sum(len(p.events) for p in self.pairs)
        touched = sum(1 for p in self.pairs if p.first_contact is not None)
        lines.append(
            f"events: {events} in {len(self.pairs)} (ellipsoid, object) pair(s); {touched} pair(s) in contact"
        )
        lines.append("work ledger (full = every effect for every piece on every segment):")
        lines += ["  " + line for line in self.ledger.format().splitlines()]
        lines.append(f"time: {self.seconds:.3f} s")
        return "\n".join(lines)


# -- the run -------------------------------------------------------------------------


def _plane_label(obj: Composite, s: Split) -> str:
    return f"{obj.name}: plane {s.name}"


def _piece_label(obj: Composite, p: Piece) -> str:
    return f"{obj.name}/{p.name}"


class _SegmentRun:
    """One ellipsoid against one object on one motion segment."""

    def __init__(
        self,
        scene: Scene,
        plan: Plan,
        ell: MovingEllipsoid,
        obj: Composite,
        seg: MotionSegment,
        ledger: Ledger,
    ) -> None:
        self.scene, self.ell, self.obj, self.seg, self.ledger = scene, ell, obj, seg, ledger
        # only what the scene asks for, per object: the ellipsoid's plan, then each piece's
        self.plan = plan.restricted(scene.ellipsoid_effects.get(ell.name))
        self.piece_plans = {
            p.name: self.plan.restricted(scene.piece_effects.get((obj.name, p.name))) for p in obj.pieces
        }
        self.E_upper = seg.moved_upper(ell.quadric, ell.center)
        self.positive = seg.norm_poly()  # |q(t)|^2 > 0: its powers carry no sign information
        self.targets: dict[str, Split | Piece] = {}
        for s in obj.splits():
            self.targets[_plane_label(obj, s)] = s
        for p in obj.pieces:
            self.targets[_piece_label(obj, p)] = p
        self.tracks: dict[str, Any] = {}
        self._samples: dict[tuple[Any, Any], Fraction] = {}

    def _sample(self, left: TimePoint, right: TimePoint) -> Fraction:
        """A rational time strictly between two points (cached across passes)."""
        key = (
            id(left) if isinstance(left, RealAlgebraic) else left,
            id(right) if isinstance(right, RealAlgebraic) else right,
        )
        if key not in self._samples:
            self._samples[key] = rational_between(left, right)
        return self._samples[key]

    def E_at(self, t: Fraction) -> Quadric:
        return Quadric._from_upper(tuple(poly_eval(p, t) for p in self.E_upper))

    def make_track(self, label: str) -> None:
        self.tracks[label] = self.build_track(label, self.seg.t0, self.seg.t1)

    def build_track(self, label: str, t0: Fraction, t1: Fraction) -> _Track:
        """The exact track of one target (plane or piece) on ``[t0, t1]`` of the segment."""
        target = self.targets[label]
        if isinstance(target, Split):
            return PlaneTrack(label, self.E_upper, target.plane, t0, t1, self.ledger, self.positive)
        return PieceTrack(
            label,
            self.E_upper,
            target.quadric,
            t0,
            t1,
            self.ledger,
            small=self.scene.small(self.ell.name, self.obj.name, target.name),
            table_4=self.scene.table_4_applies(self.ell.name, self.obj.name, target.name),
            region=self.piece_plans[target.name].region,
            kind=self.piece_plans[target.name].kind,
            E_at=self.E_at,
            positive=self.positive,
        )

    def descend(self, get: Callable[[str], Any]) -> ObjectState:
        obj = self.obj
        zones: list[tuple[str, ZoneValue]] = []
        active: list[Piece] = list(obj.extra_pieces) if not isinstance(obj.root, Piece) else []

        def visit(node: Split | Piece | None) -> None:
            if node is None:
                return
            if isinstance(node, Piece):
                if node not in active:
                    active.append(node)
                return
            z: ZoneValue | None = get(_plane_label(obj, node))
            if z is None:  # not computed yet: the next pass will have it
                return
            zones.append((node.name, z))
            if z.region in (Region.R_PLUS, Region.CONTACT):
                visit(node.plus)
            if z.region in (Region.R_MINUS, Region.CONTACT):
                visit(node.minus)

        visit(obj.root)
        pieces: list[tuple[str, PieceValue | None]] = []
        for p in active:
            pieces.append((p.name, get(_piece_label(obj, p)) if self.piece_plans[p.name].pieces else None))
        return ObjectState(tuple(zones), tuple(pieces))

    def run(self) -> list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]]:
        """Entries ``(kind, start, end, state, sample)`` in time order, kind 'instant' or 'interval'."""
        if self.plan.full:
            for label in self.targets:
                self.make_track(label)
        while True:
            # Each pass evaluates every time point with the tracks computed so far and
            # collects the targets the descent reached without a track; those are
            # computed (only they) and the pass is repeated: at most depth + 1 passes.
            self.missing: dict[str, None] = {}
            entries = self._evaluate()
            if not self.missing:
                return entries
            for label in self.missing:
                self.make_track(label)

    def _evaluate(self) -> list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]]:
        seg = self.seg
        # merge the roots of every track computed so far
        tagged = [(r, label, j) for label, tr in self.tracks.items() for j, r in enumerate(tr.roots)]

        def cmp(a: tuple[RealAlgebraic, str, int], b: tuple[RealAlgebraic, str, int]) -> int:
            return a[0].compare(b[0])

        tagged.sort(key=functools.cmp_to_key(cmp))
        merged: list[RealAlgebraic] = []
        owners: list[dict[str, int]] = []
        for r, label, j in tagged:
            if merged and merged[-1].compare(r) == 0:
                owners[-1][label] = j
            else:
                merged.append(r)
                owners.append({label: j})
        # prefix[label][i] = own roots strictly before merged interval i
        prefix: dict[str, list[int]] = {}
        for label in self.tracks:
            counts = [0]
            for own in owners:
                counts.append(counts[-1] + (1 if label in own else 0))
            prefix[label] = counts
        points: list[TimePoint] = [seg.t0, *merged, seg.t1]
        samples = [self._sample(points[i], points[i + 1]) for i in range(len(points) - 1)]

        entries: list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]] = []

        def at_rational(t: Fraction) -> Callable[[str], Any]:
            def get(label: str) -> Any:
                if label not in self.tracks:
                    self.missing[label] = None
                    return None
                return self.tracks[label].state_at_rational(t)

            return get

        def on_interval(i: int) -> Callable[[str], Any]:
            def get(label: str) -> Any:
                if label not in self.tracks:
                    self.missing[label] = None
                    return None
                return self.tracks[label].state_on_interval(prefix[label][i], samples[i])

            return get

        def at_root(k: int) -> Callable[[str], Any]:
            def get(label: str) -> Any:
                if label not in self.tracks:
                    self.missing[label] = None
                    return None
                tr = self.tracks[label]
                if label in owners[k]:
                    return tr.state_at_root(owners[k][label])
                return tr.state_on_interval(prefix[label][k], samples[k])

            return get

        entries.append(("instant", seg.t0, seg.t0, self.descend(at_rational(seg.t0)), None))
        for i in range(len(samples)):
            if i > 0:
                r = merged[i - 1]
                entries.append(("instant", r, r, self.descend(at_root(i - 1)), None))
            entries.append(("interval", points[i], points[i + 1], self.descend(on_interval(i)), samples[i]))
        entries.append(("instant", seg.t1, seg.t1, self.descend(at_rational(seg.t1)), None))
        return entries


def _first_contact(
    entries: Sequence[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]],
) -> tuple[RealAlgebraic, list[str]] | None:
    for _kind, start, _end, state, _ in entries:
        if state.contact:
            return _as_root(start), state.touching
    return None


def _tangent_boundaries(
    entries: list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]],
) -> None:
    """At an instant that bounds an interval of transversal contact with a piece and
    is not itself transversal, the surfaces touch without crossing (the contact set
    is closed, the transversal one open): an undetermined contact kind there is a
    tangency."""
    for i, (kind, start, end, state, sample) in enumerate(entries):
        if kind != "instant":
            continue
        changed = False
        pieces: list[tuple[str, PieceValue | None]] = []
        for name, v in state.pieces:
            if v is not None and v.contact is False and v.kind == "undetermined":
                near = [dict(entries[j][3].pieces).get(name) for j in (i - 1, i + 1) if 0 <= j < len(entries)]
                if any(n is not None and n.contact for n in near):
                    v = replace(v, kind="tangent", decided_by=v.decided_by + "; bounds a transversal contact")
                    changed = True
            pieces.append((name, v))
        if changed:
            entries[i] = (kind, start, end, ObjectState(state.zones, tuple(pieces)), sample)


def _episodes(
    entries: Sequence[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]],
) -> list[Episode]:
    eps: list[Episode] = []
    for kind, start, end, state, sample in entries:
        instant = kind == "instant"
        if eps and eps[-1].state == state:
            eps[-1].end = end
            eps[-1].closed_end = instant
            continue
        if eps and instant is False and eps[-1].closed_end is False:
            pass
        eps.append(Episode(start, end, state, instant, instant, sample))
    return eps


def _events(entries: Sequence[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]]) -> list[Event]:
    events: list[Event] = []
    for i, (kind, start, _end, state, _) in enumerate(entries):
        if kind != "instant":
            continue
        before = entries[i - 1][3] if i > 0 else None
        after = entries[i + 1][3] if i + 1 < len(entries) else None
        if before is None or after is None:
            continue  # the ends of the span are reported as start and end states
        if before == state == after:
            continue
        events.append(Event(_as_root(start), before, state, after))
    return events


def _progress(total: int, enabled: bool | None) -> Any:
    if enabled is None:
        enabled = total >= 20 and sys.stderr.isatty()
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=total, desc="simulating", unit="segment", file=sys.stderr, leave=False)


def _simulate_pair(
    scene: Scene,
    plan: Plan,
    e: MovingEllipsoid,
    obj: Composite,
    segs: Sequence[MotionSegment],
    ledger: Ledger,
    *,
    bar: Any = None,
    segment_run: Callable[..., _SegmentRun] | None = None,
) -> PairResult:
    """The timeline of one moving ellipsoid against one object, segment by segment."""
    make_run = segment_run or _SegmentRun
    own = plan.restricted(scene.ellipsoid_effects.get(e.name))
    entries: list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]] = []
    first: tuple[RealAlgebraic, list[str]] | None = None
    done = 0
    for seg in segs:
        part = make_run(scene, plan, e, obj, seg, ledger).run()
        done += 1
        if bar is not None:
            bar.update(1)
        if entries:
            part = part[1:]  # the joint instant was the previous segment's last entry
        entries.extend(part)
        if first is None:
            first = _first_contact(part)
        if own.stop_at_first_contact and first is not None:
            break
    if bar is not None and done < len(segs):
        bar.update(len(segs) - done)
    complete = done == len(segs)
    if own.kind:
        _tangent_boundaries(entries)
    return PairResult(
        e.name, obj, _episodes(entries), _events(entries) if complete else [], first, complete, done
    )


def simulate(
    scene: Scene,
    *,
    effects: Sequence[str] | None = None,
    full: bool = False,
    progress: bool | None = None,
    on_not_small: str | None = None,
    broad_phase: bool = False,
    workers: int = 1,
) -> SimulationResult:
    """Run a scene and return its exact event timelines and work ledger.

    Parameters
    ----------
    scene : Scene
    effects : sequence of str, optional
        Override the scene's effects (a subset of :data:`~quadric_contact.scene.EFFECTS`).
    full : bool
        Evaluate every effect for every piece on every segment instead of
        only what the effects need (to measure what the plan saves).
    progress : bool, optional
        Show a progress bar on stderr (default: for long runs on a terminal).
    on_not_small : {"refuse", "warn"}, optional
        Override the scene's smallness policy.
    broad_phase : bool
        Prune, with certified bounds of each ellipsoid's swept volume, the
        planes and pieces (and the stretches of time) where nothing can
        happen, before any pencil is formed (:mod:`quadric_contact.broadphase`);
        the timelines are the same.  A full evaluation (``full``) does without it.
    workers : int
        Processes to share the ellipsoids between (``0``: one per core).

    Returns
    -------
    SimulationResult

    Raises
    ------
    SceneError
        Unknown effects, or a pair that is not small under the ``"refuse"`` policy.

    References
    ----------
    Section 5.2, Algorithms 1 and 2, Corollaries 10 and 15, Theorem 13,
    Example 17.

    Examples
    --------
    >>> from quadric_contact.scene import builtin_scene
    >>> result = simulate(builtin_scene(), effects=["zone"])
    >>> result.ledger.cost("tree/crown"), result.ledger.cost("tree/trunk")
    (0, 0)
    """
    plan = Plan.from_effects(scene.effects if effects is None else effects, full=full)
    started = time.perf_counter()
    ledger = Ledger()
    if plan.full or scene.needs_smallness(plan.effects):
        scene.check_smallness(on_not_small=on_not_small)  # a no-op for the pairs checked at load time
        for key, n in scene.work.by_target.items():
            ledger.add("smallness_checks", n["smallness_checks"], target=key)
    # what a full evaluation would cost
    seg_lists = {
        e.name: e.trajectory.segments(scene.span[0], scene.span[1], e.center) for e in scene.ellipsoids
    }
    for e in scene.ellipsoids:
        nseg = len(seg_lists[e.name])
        for obj in scene.objects:
            for _s in obj.splits():
                ledger.add_full("characteristic_polynomials", nseg)
                ledger.add_full("discriminants", nseg)
            for p in obj.pieces:
                ledger.add_full("characteristic_polynomials", nseg)
                if p.is_plane:
                    ledger.add_full("discriminants", nseg)
                else:
                    ledger.add_full("discriminants", 3 * nseg)
                    ledger.add_full("coefficient_signs", 3 * nseg)
                    ledger.add_full("smallness_checks", 1)
    if full:
        broad_phase = False  # a full evaluation forms every pencil
    if broad_phase or workers != 1:
        from .manybody import run_pairs

        pairs = run_pairs(
            scene, plan, seg_lists, ledger, broad_phase=broad_phase, workers=workers, progress=progress
        )
    else:
        total = sum(len(seg_lists[e.name]) for e in scene.ellipsoids) * len(scene.objects)
        bar = _progress(total, progress)
        pairs = []
        try:
            for e in scene.ellipsoids:
                for obj in scene.objects:
                    pairs.append(_simulate_pair(scene, plan, e, obj, seg_lists[e.name], ledger, bar=bar))
        finally:
            if bar is not None:
                bar.close()
    return SimulationResult(scene, plan, pairs, ledger, time.perf_counter() - started, list(scene.warnings))
