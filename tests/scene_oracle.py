"""An independent check of a simulated timeline: the static Algorithms 1-2 on the
exactly moved ellipsoid (no polynomial in time, no root isolation) at dense
rational sample times and on both sides of every reported event.

Used by the gallery tests and the broad-phase tests: every scene's event times
are checked against it.
"""

from __future__ import annotations

from fractions import Fraction as F
from typing import Any

from quadric_contact.scenes.composite import Piece, Split, algorithm_2
from quadric_contact.theory.results import Region
from quadric_contact.theory.sections import curve_meets_half_space


def static_state(result: Any, pair: Any, t: F, *, region: bool) -> tuple[Any, Any]:
    """(zones, pieces) decided by the static Algorithm 2 at the rational time ``t``:
    ``zones`` maps plane name -> Region, ``pieces`` piece name -> (contact, region)."""
    scene = result.scene
    ell = next(e for e in scene.ellipsoids if e.name == pair.ellipsoid)
    obj = pair.object
    E = ell.trajectory.placed(ell.quadric, t, *scene.span)
    small = {p.name: scene.smallness.get((ell.name, obj.name, p.name)) for p in obj.pieces}
    given = {
        k: (v.report if v is not None and v.report is not None else bool(v and v.small))
        for k, v in small.items()
    }
    static = algorithm_2(E, obj, small=given, region=region)
    zones = {k: v.zone for k, v in static.zone.sides.items()}
    pieces = {
        name: (c.transversal, static.regions[name].region if region else None)
        for name, c in static.contacts.items()
    }
    if result.scene.reading == "geometry":
        for name, crossed in _crossed_paths(obj, zones).items():
            if pieces.get(name, (None,))[0] is not True or not crossed or not all(crossed):
                continue
            piece = next(p for p in obj.pieces if p.name == name)
            answers = []
            for path in crossed:
                assert len(path) == 1, "a piece cut by two planes the ellipsoid crosses at once"
                plane, side = path[0]
                answers.append(curve_meets_half_space(E, piece.quadric, plane, side))
            if not any(answers):
                assert all(a is False for a in answers)
                pieces[name] = (False, None)
    return zones, pieces


def _crossed_paths(obj: Any, zones: dict[str, Any]) -> dict[str, list[list[tuple[Any, int]]]]:
    """Piece name -> for every path of the tree that reaches it, the planes on the path
    that the ellipsoid crosses (Zone 0) and the side kept."""
    out: dict[str, list[list[tuple[Any, int]]]] = {}

    def visit(node: Any, crossed: list[tuple[Any, int]]) -> None:
        if node is None:
            return
        if isinstance(node, Piece):
            out.setdefault(node.name, []).append(crossed)
            return
        assert isinstance(node, Split)
        z = zones[node.name]
        if z in (Region.R_PLUS, Region.CONTACT):
            visit(node.plus, crossed + ([(node.plane, 1)] if z is Region.CONTACT else []))
        if z in (Region.R_MINUS, Region.CONTACT):
            visit(node.minus, crossed + ([(node.plane, -1)] if z is Region.CONTACT else []))

    if isinstance(obj.root, Split):
        visit(obj.root, [])
    return out


def _asked_region(result: Any, pair: Any, piece: str) -> bool:
    """The relative position was asked for on this pair (per-object effects)."""
    scene = result.scene
    own = result.plan.restricted(scene.ellipsoid_effects.get(pair.ellipsoid))
    return bool(own.restricted(scene.piece_effects.get((pair.object.name, piece))).region)


def timeline_state(state: Any, *, region: bool) -> tuple[Any, Any]:
    zones = {k: v.region for k, v in state.zones}
    pieces = {n: (v.contact, v.region if region else None) for n, v in state.pieces if v is not None}
    return zones, pieces


def _comparable(result: Any, pair: Any, got: tuple[Any, Any], static: tuple[Any, Any]) -> tuple[Any, Any]:
    """The static state restricted to what the timeline evaluated (pieces whose state was
    asked for; regions where the relative position was asked for)."""
    zones, pieces = static
    kept = {}
    for name, (contact, region) in pieces.items():
        if name in got[1]:
            kept[name] = (contact, region if _asked_region(result, pair, name) else None)
    return zones, kept


def check_timeline(result: Any, *, samples: int = 60, bracket: F = F(1, 10**9)) -> int:
    """Assert that every complete timeline of ``result`` agrees with the static
    algorithms at ``samples + 1`` evenly spaced times and on both sides of each
    event (within ``bracket`` of it); return the number of events checked."""
    region = result.plan.region
    t0, t1 = result.scene.span
    checked = 0
    for pair in result.pairs:
        if not pair.complete:
            continue
        for i in range(samples + 1):
            t = t0 + (t1 - t0) * F(i, samples)
            got = timeline_state(pair.state_at(t), region=region)
            static = _comparable(result, pair, got, static_state(result, pair, t, region=region))
            assert got == static, (pair.ellipsoid, pair.object.name, t)
            assert set(got[1]) == set(static_state(result, pair, t, region=region)[1]) or not got[1]
        for k, ev in enumerate(pair.events):
            if ev.time.is_rational:
                t = ev.time.value
                got = timeline_state(ev.at, region=region)
                assert got == _comparable(result, pair, got, static_state(result, pair, t, region=region)), t
            ev.time.refine(bracket / 4)
            lo, hi = ev.time.lo - bracket, ev.time.hi + bracket
            neighbours = [e.time for j, e in enumerate(pair.events) if j != k]
            assert all(n.compare(lo) < 0 or n.compare(hi) > 0 for n in neighbours), "events too close"
            for side, when, state in ((lo > t0, lo, ev.before), (hi < t1, hi, ev.after)):
                if side and state is not None:
                    got = timeline_state(state, region=region)
                    static = _comparable(result, pair, got, static_state(result, pair, when, region=region))
                    assert got == static, (pair.ellipsoid, float(ev.time))
            checked += 1
    return checked
