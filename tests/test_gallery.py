"""The gallery of built-in scenes: together they cover every quadric type of Table 1
and the plane, and every scene's event times are checked against an independent
computation (the static Algorithms 1-2 at dense rational times and on both sides
of each event), and against closed forms where the geometry gives them."""

from __future__ import annotations

from fractions import Fraction as F
from itertools import pairwise

import pytest
from tests.scene_oracle import check_timeline

from quadric_contact.model.classification import QuadricKind
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names
from quadric_contact.scenes.simulate import simulate

NEW_SCENES = ("probe_two_sheets", "parallel_walls", "trough_and_channel")


def test_the_gallery_covers_table_1_and_the_plane():
    kinds = set()
    for name in builtin_scene_names():
        for obj in builtin_scene(name, check_smallness=False).objects:
            kinds |= {p.quadric.kind for p in obj.pieces}
    wanted = {k for k in QuadricKind if k.in_table_1} | {QuadricKind.PLANE}
    assert wanted <= kinds, wanted - kinds
    assert set(NEW_SCENES) <= set(builtin_scene_names())


@pytest.mark.parametrize("reading", ["geometry", "paper"])
@pytest.mark.parametrize("name", builtin_scene_names())
def test_every_scene_event_time_agrees_with_the_static_algorithms(name, reading):
    """Algorithms 1-2 at rational times (the paper's reading); in the geometric reading,
    where the ellipsoid crosses a cutting plane, the static section decision too."""
    scene = builtin_scene(name)
    effects = [e for e in scene.effects if e not in ("first_contact", "contact_kind")]
    if "contact" not in effects:
        effects.append("contact")
    result = simulate(scene, effects=effects, reading=reading)
    samples = 16 if name == "swarm_around_tree" else 60
    checked = check_timeline(result, samples=samples)
    assert checked == sum(len(p.events) for p in result.pairs)
    assert checked > 0


def _contact_intervals(pair, piece):
    """(start, end) of every maximal interval of transversal contact with ``piece``."""
    out = []
    for ep in pair.episodes:
        value = dict(ep.state.pieces).get(piece)
        if value is not None and value.contact and ep.start != ep.end:
            out.append((ep.start, ep.end))
    return out


def _keyframe_crossing(keys, coord, level):
    """Times at which the piecewise-linear path of the keyframes has ``coord == level``
    strictly inside a leg (the closed forms of the scene files)."""
    out = []
    for (ta, pa), (tb, pb) in pairwise(keys):
        a, b = F(pa[coord]), F(pb[coord])
        if a != b and min(a, b) < level < max(a, b):
            out.append(F(ta) + (F(tb) - F(ta)) * (level - a) / (b - a))
    return out


def _keys(scene):
    (ell,) = scene.ellipsoids
    return [(k.time, k.position) for k in ell.trajectory.keys]


def test_probe_enters_the_upper_sheet_on_its_axis_at_the_closed_form_times():
    """On the axis, the distance from (0, 0, z) to the sheet z = sqrt(1 + x^2 + y^2) is
    |z - 1| while z <= 2: contact exactly while |z - 1| < 1/2."""
    scene = builtin_scene("probe_two_sheets")
    pair = simulate(scene).pair("probe", "hyperboloid")
    (ell,) = scene.ellipsoids
    r = F(1, 2)
    assert ell.quadric == type(ell.quadric).sphere(r, (-6, 0, 0))
    enter = _keyframe_crossing(_keys(scene), 2, 1 - r)
    inside = _keyframe_crossing(_keys(scene), 2, 1 + r)
    assert enter == [F(7, 2)] and inside == [F(9, 2)]
    first = _contact_intervals(pair, "sheets")[0]
    assert (first[0].value, first[1].value) == (enter[0], inside[0])
    assert pair.first_contact[0].value == enter[0]
    # and the probe ends inside its wall's far side: it left through the wall
    assert len(_contact_intervals(pair, "sheets")) == 2


def test_ball_between_parallel_walls_crosses_them_at_the_closed_form_times():
    """Walls x = +-1, ball of radius 1/4: contact exactly while |x| > 3/4; the floor is
    touched (never crossed) all the time."""
    scene = builtin_scene("parallel_walls")
    pair = simulate(scene).pair("ball", "corridor")
    keys = _keys(scene)
    crossings = sorted(_keyframe_crossing(keys, 0, F(3, 4)) + _keyframe_crossing(keys, 0, F(-3, 4)))
    assert crossings == [F(5, 3), F(13, 6), F(23, 6), F(59, 14)]
    got = [t for iv in _contact_intervals(pair, "walls") for t in iv]
    assert [t.value for t in got] == crossings
    assert [e.time.value for e in pair.events] == crossings
    for ep in pair.episodes:
        floor = dict(ep.state.pieces)["floor"]
        assert floor.contact is False and floor.kind == "tangent_point"


def test_body_skims_the_trough_and_the_channel_at_the_closed_form_times():
    """Trough x^2 = 4z: on its axis the distance is |z| (z <= 2), contact while z < 1/2.
    Channel x^2 - (y - 14)^2 = 1: at the throat the distance is 1 - x, contact while
    x > 1/2."""
    scene = builtin_scene("trough_and_channel")
    result = simulate(scene)
    keys = _keys(scene)
    trough = _contact_intervals(result.pair("body", "trough"), "trough")
    assert [(a.value, b.value) for a, b in trough] == [tuple(_keyframe_crossing(keys, 2, F(1, 2)))]
    assert trough == [(F(8, 5), F(12, 5))]
    channel = _contact_intervals(result.pair("body", "channel"), "walls")
    throat = _keyframe_crossing(keys, 0, F(1, 2))
    assert [(a.value, b.value) for a, b in channel] == [tuple(throat)] == [(F(61, 8), F(67, 8))]
