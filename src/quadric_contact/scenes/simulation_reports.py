"""What a run of a scene reports: the plan, states, episodes, events, per-pair and
whole-scene results (:func:`quadric_contact.scenes.simulate.simulate` builds them).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.errors import SceneError
from quadric_contact.exact.printing import safe_text
from quadric_contact.scenes.composite import Composite
from quadric_contact.scenes.events import (
    PieceValue,
    ZoneValue,
)
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_distance import PieceDistance
from quadric_contact.scenes.scene_model import EFFECTS, Scene
from quadric_contact.theory.results import Region

__all__ = [
    "Episode",
    "Event",
    "ObjectState",
    "PairResult",
    "Plan",
    "SimulationResult",
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
        Only ``first_contact`` (with ``smallness`` or ``distance``) is asked for: stop each
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
        """The plan for a set of effects (:data:`~quadric_contact.scenes.scene_model.EFFECTS`).

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

    @property
    def distance(self) -> bool:
        """The least signed distance along the path is asked for (the ``distance`` effect)."""
        return "distance" in self.effects

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
        if self.distance:
            steps.append("the least signed distance along the path, certified by a Lipschitz bound")
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
                out.append(f"{kind}{safe_text(name)}: {x} -> {z}{tail}")
            else:
                out.append(f"{kind}{safe_text(name)}: {y} at the instant only (before and after: {x})")

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
    distances: list[PieceDistance] = field(default_factory=list)
    """The ``distance`` effect: one entry per piece of the object that asks for it."""

    def beyond_cut(self) -> list[str]:
        """The pieces the ellipsoid crosses only beyond their cut at some time: where
        the geometric reading and the paper's (whole quadrics) differ."""
        names: dict[str, None] = {}
        for ep in self.episodes:
            for name, v in ep.state.pieces:
                if v is not None and v.beyond_cut:
                    names[name] = None
        return list(names)

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

        >>> from quadric_contact.scenes.scene_toml import builtin_scene
        >>> from quadric_contact.scenes.simulate import simulate
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
        if "distance" in effects:
            out["distance"] = [d.to_dict(places) for d in self.distances]
        return out


EVENTS_SHOWN = 24
"""Events listed per pair in a summarised report (two thirds from the start, the rest from the end)."""

LINES_SHOWN = 80
"""Lines of pair timelines in a summarised report before the remaining pairs are summed up."""


def _shown_changes(ev: Event, obj: Composite, show_zones: bool) -> list[str]:
    changes = ev.changes(obj)
    if not show_zones:
        changes = [c for c in changes if not c.startswith("zone of plane")]
    return changes


def _reading_text(reading: str) -> str:
    if reading == "paper":
        return "reading: the paper's (Algorithm 1): a piece whose zone is reached counts as its whole quadric"
    return "reading: pieces as cut by the planes of their object (--reading paper: as whole quadrics)"


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
    mutual: list[Any] | None = None
    """The pairs of moving ellipsoids that meet (:mod:`quadric_contact.scenes.mutual`),
    when the scene asks for mutual contacts."""

    def pair(self, ellipsoid: str, obj: str) -> PairResult:
        """The timeline of one ellipsoid against one object (``KeyError`` if there is none)."""
        for p in self.pairs:
            if p.ellipsoid == ellipsoid and p.object.name == obj:
                return p
        raise KeyError((ellipsoid, obj))

    def distance(self, ellipsoid: str, obj: str, piece: str) -> PieceDistance:
        """The ``distance`` effect's answer for one ellipsoid and one piece (``KeyError`` if
        it was not asked for)."""
        for d in self.pair(ellipsoid, obj).distances:
            if d.piece == piece:
                return d
        raise KeyError((ellipsoid, obj, piece))

    def to_dict(self, places: int | None = None) -> dict[str, Any]:
        """Everything as JSON-ready data (``quadric-contact simulate --json``); event
        times with ``places`` decimals, their polynomials and isolating intervals."""
        places = self.scene.places if places is None else places
        out: dict[str, Any] = {
            "scene": self.scene.name,
            "source": self.scene.source,
            "time_span": [str(self.scene.span[0]), str(self.scene.span[1])],
            "effects": list(self.plan.effects),
            "reading": self.scene.reading,
            "plan": self.plan.describe(),
            "events": sum(len(p.events) for p in self.pairs),
            "pairs": [p.to_dict(places, self.plan.effects) for p in self.pairs],
            "mutual": None if self.mutual is None else [m.to_dict(places) for m in self.mutual],
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

    def _mutual_lines(self, places: int, events: str) -> list[str]:
        assert self.mutual is not None
        lines = [
            "",
            f"mutual contacts among {len(self.scene.mutual)} moving ellipsoids: "
            f"{len(self.mutual)} pair(s) meet",
        ]
        shown = self.mutual if events == "all" else self.mutual[:12]
        for m in shown:
            lines.append(f"  {m.a} and {m.b}: start {m.start}")
            listed = m.events if events == "all" else m.events[:EVENTS_SHOWN]
            for ev in listed:
                lines.append(f"    t = {_fmt_time(ev.time, places)}: {ev.describe()}")
            if len(listed) < len(m.events):
                lines.append(
                    f"    ... {len(m.events) - len(listed)} more events (--events all lists every one)"
                )
        if len(shown) < len(self.mutual):
            lines.append(f"  ... {len(self.mutual) - len(shown)} more pairs (--events all lists every one)")
        return lines

    def _listed(self, p: PairResult) -> int:
        """The events a pair's timeline reports (what its ellipsoid asks to see)."""
        own = self.plan.restricted(self.scene.ellipsoid_effects.get(p.ellipsoid)).effects
        if not (p.complete and {"zone", "contact", "contact_kind", "relative_position"} & set(own)):
            return 0
        return sum(1 for ev in p.events if _shown_changes(ev, p.object, "zone" in own))

    def format_text(self, places: int | None = None, *, events: str = "summary") -> str:
        """The timeline as printed by ``quadric-contact simulate`` (event times to ``places`` decimals).

        ``events="summary"`` (the default) bounds the output: each pair lists at
        most :data:`EVENTS_SHOWN` events (the first ones and the last ones), and
        once :data:`LINES_SHOWN` lines of timelines are printed the remaining pairs
        are summed up in one line; ``events="all"`` lists every event of every pair.
        """
        if events not in ("summary", "all"):
            raise SceneError(f"events: expected 'summary' or 'all', got {events!r}", events)
        places = self.scene.places if places is None else places
        lines = [self.scene.describe(), f"plan: {self.plan.describe()}", _reading_text(self.scene.reading)]
        if "smallness" in self.plan.effects or any(c.small is False for c in self.scene.smallness.values()):
            lines.append("smallness (Tables 1, 2):")
            lines += [f"  {c}" for c in self.scene.smallness.values()]
        for w in self.warnings:
            lines.append(f"warning: {w}")
        lines.append(
            f"event times: exact real algebraic numbers, shown to {places} decimal places "
            "(--places N; --json gives each one's polynomial and isolating interval)"
        )
        shown_lines = listed_events = 0
        hidden: list[PairResult] = []
        for p in self.pairs:
            if events == "summary" and shown_lines >= LINES_SHOWN:
                hidden.append(p)
                continue
            before = len(lines)
            own = self.plan.restricted(self.scene.ellipsoid_effects.get(p.ellipsoid)).effects
            show_zones = "zone" in own
            show_timeline = bool({"zone", "contact", "contact_kind", "relative_position"} & set(own))
            lines.append("")
            lines.append(f"{safe_text(p.ellipsoid)} vs {safe_text(p.object.name)}")
            if p.complete and show_timeline:
                start = p.initial.summary(p.object, with_zones=show_zones)
                lines.append(f"  t = {_fmt_time(self.scene.span[0], places)}: start: {start}")
                listed = [
                    (ev, changes) for ev in p.events if (changes := _shown_changes(ev, p.object, show_zones))
                ]
                skip = (0, 0)
                if events == "summary" and len(listed) > EVENTS_SHOWN:
                    head_n = EVENTS_SHOWN - EVENTS_SHOWN // 3
                    skip = (head_n, len(listed) - EVENTS_SHOWN // 3)
                for k, (ev, changes) in enumerate(listed):
                    if skip[0] <= k < skip[1]:
                        if k == skip[0]:
                            lines.append(
                                f"  ... {skip[1] - skip[0]} more events (--events all lists every one)"
                            )
                        continue
                    head = f"  t = {_fmt_time(ev.time, places)}: "
                    lines.append(head + changes[0])
                    lines += [" " * len(head) + c for c in changes[1:]]
                listed_events += len(listed)
                end = p.episodes[-1].state.summary(p.object, with_zones=show_zones)
                lines.append(f"  t = {_fmt_time(self.scene.span[1], places)}: end: {end}")
            beyond = p.beyond_cut()
            if beyond:
                lines.append(
                    f"  readings differ: as whole quadrics (--reading paper) the crossings of "
                    f"{', '.join(beyond)} beyond the cut count as contact"
                )
            if "first_contact" in own:
                if p.first_contact is None:
                    lines.append("  first contact: none in the time span")
                else:
                    t, names = p.first_contact
                    extra = "" if p.complete else f" (stopped there, after {p.segments_done} segment(s))"
                    who = ", ".join(map(safe_text, names))
                    lines.append(f"  first contact: t = {_fmt_time(t, places)} with {who}{extra}")
            lines += [f"  {d.describe(places)}" for d in p.distances]
            shown_lines += len(lines) - before
        if hidden:
            n_events = sum(self._listed(p) for p in hidden)
            listed_events += n_events
            n_touched = sum(1 for p in hidden if p.first_contact is not None)
            lines.append("")
            lines.append(
                f"... {len(hidden)} more (ellipsoid, object) pairs, {n_touched} of them in contact, "
                f"{n_events} events (--events all lists every one; --json gives everything)"
            )
        if self.mutual is not None:
            lines += self._mutual_lines(places, events)
        lines.append("")
        touched = sum(1 for p in self.pairs if p.first_contact is not None)
        lines.append(
            f"events: {listed_events} in {len(self.pairs)} (ellipsoid, object) pair(s); "
            f"{touched} pair(s) in contact"
        )
        lines.append("work ledger (full = every effect for every piece on every segment):")
        lines += ["  " + line for line in self.ledger.format().splitlines()]
        lines.append(f"time: {self.seconds:.3f} s")
        # Names reach the other lines too (the scene's description, warnings, smallness
        # reports): each name with a control or format character (a line break, an
        # escape sequence, a bidi override) is replaced by its escaped form first, then
        # no such character is printed raw, so a name can neither forge a line nor
        # rewrite the terminal.
        text = "\n".join(lines)
        for name in sorted(_user_names(self.scene), key=len, reverse=True):
            text = text.replace(name, safe_text(name))
        return safe_text(text, keep_newlines=True)


def _user_names(scene: Any) -> set[str]:
    """The names in ``scene`` given by its user that a terminal would not print as
    themselves (see :func:`~quadric_contact.exact.printing.safe_text`)."""
    names = {scene.name}
    for e in scene.ellipsoids:
        names.add(e.name)
    for obj in scene.objects:
        names.add(obj.name)
        names.update(p.name for p in obj.pieces)
        names.update(sp.name for sp in obj.splits())
    return {n for n in names if isinstance(n, str) and n and safe_text(n) != n}
