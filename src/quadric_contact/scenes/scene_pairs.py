"""One ellipsoid against one object over its motion segments: the engine of a simulation.

:func:`_simulate_pair` runs Algorithms 1 and 2 in time for one pair (see
:mod:`quadric_contact.scenes.simulate` for the steps); :class:`_SegmentRun` is one motion
segment of it.  Both the single-process loop of :func:`~quadric_contact.scenes.simulate.simulate`
and the broad-phase and multi-process runner of :mod:`quadric_contact.scenes.manybody`
(which specialises :class:`_SegmentRun`) call them, so they live here, below both.

References
----------
Section 5.2, Algorithms 1 and 2, Corollaries 10 and 15, Theorem 13.
"""

from __future__ import annotations

import functools
import sys
from collections.abc import Callable, Sequence
from dataclasses import replace
from fractions import Fraction
from typing import Any

from quadric_contact.exact.algebraic import RealAlgebraic, rational_between
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.scenes.cut_pieces import SectionTrack, cut_value, resolve_cut
from quadric_contact.scenes.events import (
    PieceTrack,
    PieceValue,
    PlaneTrack,
    ZoneValue,
    _Track,
)
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.simulation_reports import (
    Episode,
    Event,
    ObjectState,
    PairResult,
    Plan,
    TimePoint,
    _as_root,
)
from quadric_contact.scenes.trajectory import MotionSegment, poly_eval
from quadric_contact.theory.results import Region


def _plane_label(obj: Composite, s: Split) -> str:
    return f"{obj.name}: plane {s.name}"


def _piece_label(obj: Composite, p: Piece) -> str:
    return f"{obj.name}/{p.name}"


def _section_label(obj: Composite, p: Piece, s: Split, side: int) -> str:
    return f"{obj.name}/{p.name} cut by {s.name} ({'R+' if side > 0 else 'R-'} kept)"


Crossing = tuple[Split, int]  # a cutting plane the ellipsoid crosses, and the kept side


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
        self.geometric = scene.reading == "geometry"
        self.targets: dict[str, Split | Piece | tuple[Piece, Split, int]] = {}
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
        if isinstance(target, tuple):
            piece, split, side = target
            return SectionTrack(
                label, self.E_upper, piece.quadric, split.plane, side, t0, t1, self.ledger, self.positive
            )
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
        # per piece, the cutting planes the ellipsoid crosses on each path that reaches it
        paths: dict[str, list[tuple[Crossing, ...]]] = {p.name: [()] for p in active}

        def visit(node: Split | Piece | None, crossed: tuple[Crossing, ...]) -> None:
            if node is None:
                return
            if isinstance(node, Piece):
                if node not in active:
                    active.append(node)
                paths.setdefault(node.name, []).append(crossed)
                return
            z: ZoneValue | None = get(_plane_label(obj, node))
            if z is None:  # not computed yet: the next pass will have it
                return
            zones.append((node.name, z))
            through = z.region is Region.CONTACT
            if z.region in (Region.R_PLUS, Region.CONTACT):
                visit(node.plus, (*crossed, (node, 1)) if through else crossed)
            if z.region in (Region.R_MINUS, Region.CONTACT):
                visit(node.minus, (*crossed, (node, -1)) if through else crossed)

        visit(obj.root, ())
        pieces: list[tuple[str, PieceValue | None]] = []
        cuts: dict[str, list[tuple[Crossing, ...]]] = {}
        for p in active:
            wanted = self.piece_plans[p.name].pieces
            pieces.append((p.name, get(_piece_label(obj, p)) if wanted else None))
            if self.geometric and wanted and all(paths[p.name]):  # cut on every path that reaches it
                cuts[p.name] = paths[p.name]
                for crossed in paths[p.name]:
                    if len(crossed) == 1:
                        split, side = crossed[0]
                        label = _section_label(obj, p, split, side)
                        self.targets.setdefault(label, (p, split, side))
                        get(label)
        self._cut_log.append(cuts)
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
            self._cut_log: list[dict[str, list[tuple[Crossing, ...]]]] = []
            entries = self._evaluate()
            if not self.missing:
                if self.geometric and any(self._cut_log):
                    self._cut(entries)
                return entries
            for label in self.missing:
                self.make_track(label)

    def _cut(self, entries: list[tuple[str, TimePoint, TimePoint, ObjectState, Fraction | None]]) -> None:
        """The geometric reading: every piece the ellipsoid reaches only across a
        cutting plane gets its state as cut (:mod:`quadric_contact.scenes.cut_pieces`):
        the intervals at their sample times first, then each instant from its
        neighbours."""
        log = self._cut_log
        assert len(log) == len(entries)
        found: dict[tuple[int, str], tuple[bool | None, bool | None, str]] = {}

        def one(i: int, name: str, crossed: tuple[Crossing, ...], whole: PieceValue) -> Any:
            if len(crossed) != 1:
                return None, None, "the ellipsoid crosses two cutting planes of the piece at once"
            split, side = crossed[0]
            label = _section_label(self.obj, self._piece(name), split, side)
            key = (i, label)
            if key in found:
                return found[key]
            kind, start, _end, _state, sample = entries[i]
            track = self.tracks[label]
            if kind == "interval":
                out = resolve_cut(track, whole, sample, self.E_at, interval=True)
            else:
                near = []
                for j in (i - 1, i + 1):
                    if 0 <= j < len(entries) and entries[j][0] == "interval" and name in log[j]:
                        pv = dict(entries[j][3].pieces).get(name)
                        near.append(one(j, name, crossed, pv)[:2] if pv is not None else None)
                    else:
                        near.append(None)
                out = resolve_cut(track, whole, start, self.E_at, interval=False, left=near[0], right=near[1])
            found[key] = out
            return out

        for order in ("interval", "instant"):
            for i, (kind, start, end, state, sample) in enumerate(entries):
                if kind != order or not log[i]:
                    continue
                pieces = []
                for name, v in state.pieces:
                    if v is not None and name in log[i]:
                        answers = [one(i, name, crossed, v) for crossed in log[i][name]]
                        values = [a[0] for a in answers]
                        contact = True if True in values else (None if None in values else False)
                        reason = next(a[2] for a in answers if a[0] is contact)
                        planes = ", ".join(dict.fromkeys(c[0].name for cr in log[i][name] for c in cr))
                        v = cut_value(v, contact, reason, planes)
                    pieces.append((name, v))
                entries[i] = (kind, start, end, ObjectState(state.zones, tuple(pieces)), sample)

    def _piece(self, name: str) -> Piece:
        return next(p for p in self.obj.pieces if p.name == name)

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
    is closed, the transversal one open).  The contact kind is a word of Table 3's
    vocabulary (:class:`~quadric_contact.theory.contact_kind.ContactKind`, the one of
    :func:`~quadric_contact.analyze_contact`); at an irrational instant, where the
    row is not classified, it stays ``undetermined`` and the reason says that the
    surfaces touch there."""
    for i, (kind, start, end, state, sample) in enumerate(entries):
        if kind != "instant":
            continue
        changed = False
        pieces: list[tuple[str, PieceValue | None]] = []
        for name, v in state.pieces:
            if v is not None and v.contact is False and v.kind == "undetermined":
                near = [dict(entries[j][3].pieces).get(name) for j in (i - 1, i + 1) if 0 <= j < len(entries)]
                if any(n is not None and n.contact for n in near):
                    v = replace(
                        v,
                        decided_by=v.decided_by
                        + "; bounds a transversal contact: the surfaces touch without crossing "
                        "(the row of Table 3 is not classified at an irrational instant)",
                    )
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
    from tqdm import tqdm  # tqdm takes tens of ms to import: only when a progress bar is shown

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
