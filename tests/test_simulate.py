"""The simulator: plans from effects, the work ledger, early stops, and every built-in scene
checked against the static Algorithms 1-2 by dense sampling."""

from __future__ import annotations

import json
from fractions import Fraction as F

import pytest

from quadric_contact.exact.errors import ChoiceError, SceneError
from quadric_contact.scenes.composite import algorithm_2
from quadric_contact.scenes.ledger import FULL_ITEMS, Ledger
from quadric_contact.scenes.scene_model import READINGS
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names, parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.simulation_reports import Plan


@pytest.fixture
def stays_in_zone_2(bee_and_tree):
    """The bee flying low, below the tree's plane (zone 2: only the trunk matters)."""
    return bee_and_tree(
        name="low bee",
        time="[0, 4]",
        effects='["contact", "relative_position"]',
        motion='{ type = "linear", velocity = [-0.5, -0.6, -0.2] }',
    )


def test_zone_only_never_touches_a_piece():
    r = simulate(builtin_scene(), effects=["zone"])
    assert r.ledger.cost("tree/crown") == 0 and r.ledger.cost("tree/trunk") == 0
    assert r.ledger.done["smallness_checks"] == 0 and r.ledger.done["coefficient_signs"] == 0
    assert r.ledger.cost("tree: plane z - 6") > 0
    pair = r.pair("bee", "tree")
    assert all(v is None for ep in pair.episodes for _, v in ep.state.pieces)


def test_a_piece_outside_the_zone_costs_nothing(stays_in_zone_2):
    r = simulate(parse_scene(stays_in_zone_2, "low.toml"))
    # the crown's smallness is checked when the scene is loaded; nothing else is done for it
    assert dict(r.ledger.by_target["tree/crown"]) == {"smallness_checks": 1}
    assert r.ledger.cost("tree/trunk") > 0
    assert r.ledger.full["characteristic_polynomials"] == 3  # plane, crown, trunk on one segment
    assert r.ledger.done["characteristic_polynomials"] == 2


def test_contact_without_relative_position_keeps_no_coefficient_polynomials():
    r = simulate(builtin_scene(), effects=["contact"])
    assert r.ledger.done["coefficient_signs"] == 0
    assert all(v.region is None for p in r.pairs for ep in p.episodes for _, v in ep.state.pieces if v)
    r2 = simulate(builtin_scene(), effects=["contact", "relative_position"])
    assert r2.ledger.done["coefficient_signs"] > 0
    # the contact timeline is the same with or without the regions
    assert [e.time.decimal(30) for e in r.pairs[0].events] == [
        e.time.decimal(30) for e in r2.pairs[0].events if any("contact" in c for c in e.changes())
    ]


def test_first_contact_alone_stops_early():
    scene = builtin_scene()
    early = simulate(scene, effects=["first_contact"])
    whole = simulate(scene, effects=["contact", "first_contact"])
    pe, pw = early.pair("bee", "tree"), whole.pair("bee", "tree")
    assert not pe.complete and pe.segments_done < pw.segments_done
    assert pe.first_contact[0].compare(pw.first_contact[0]) == 0 and pe.first_contact[1] == ["trunk"]
    assert early.ledger.done["characteristic_polynomials"] < whole.ledger.done["characteristic_polynomials"]
    assert "stopped there" in early.format_text()


def test_full_evaluation_matches_the_structural_estimate():
    """The ledger's 'full' column is what the full plan actually computes."""
    for name in ("bee_and_tree", "capsule_pipe"):
        scene = builtin_scene(name)
        lazy = simulate(scene)
        full = simulate(scene, full=True)
        for item in FULL_ITEMS:
            if item == "smallness_checks":
                continue
            assert full.ledger.done[item] == lazy.ledger.full[item], (name, item)
            assert lazy.ledger.done[item] <= lazy.ledger.full[item]
        # and the timelines agree
        assert [e.time.decimal(25) for e in lazy.pairs[0].events] == [
            e.time.decimal(25) for e in full.pairs[0].events
        ]


def piece_plan(result, pair, piece):
    """What was asked for on one (ellipsoid, piece) pair (per-object effects)."""
    scene = result.scene
    own = result.plan.restricted(scene.ellipsoid_effects.get(pair.ellipsoid))
    return own.restricted(scene.piece_effects.get((pair.object.name, piece)))


def check_against_static(result, samples=80):
    scene = result.scene
    t0, t1 = scene.span
    for pair in result.pairs:
        if not pair.complete:
            continue
        ell = next(e for e in scene.ellipsoids if e.name == pair.ellipsoid)
        obj = pair.object
        for i in range(samples + 1):
            t = t0 + (t1 - t0) * F(i, samples)
            state = pair.state_at(t)
            E = ell.trajectory.placed(ell.quadric, t, t0, t1)
            small = {p.name: scene.small(ell.name, obj.name, p.name) for p in obj.pieces}
            static = algorithm_2(E, obj, small=small, region=result.plan.region)
            assert {k: v.region for k, v in state.zones} == {
                k: v.zone for k, v in static.zone.sides.items()
            }, t
            assert sorted(n for n, _ in state.pieces) == sorted(p.name for p in static.zone.pieces), t
            for name, value in state.pieces:
                if value is None:
                    continue
                assert value.contact == static.contacts[name].transversal, (pair.ellipsoid, t, name)
                if piece_plan(result, pair, name).region:
                    assert value.region == static.regions[name].region, (pair.ellipsoid, t, name)


@pytest.mark.parametrize("name", builtin_scene_names())
def test_builtin_scenes_agree_with_static_algorithms(name):
    """In the paper's reading the timeline is Algorithms 1 and 2 at every instant."""
    scene = builtin_scene(name)
    effects = [e for e in scene.effects if e != "first_contact"] or ["contact"]
    if "contact" not in effects:
        effects.append("contact")
    result = simulate(scene, effects=effects, reading="paper")
    check_against_static(result, samples=60 if name != "swarm_around_tree" else 16)


def test_bee_and_tree_timeline_has_the_promised_story():
    r = simulate(builtin_scene())
    pair = r.pair("bee", "tree")
    text = "\n".join(c for e in pair.events for c in e.changes())
    assert "trunk: no contact, R+ -> contact" in text
    assert "zone of plane z - 6: R- -> contact" in text
    assert "zone of plane z - 6: contact -> R+" in text
    assert "crown: no contact, R+ -> contact" in text
    assert "crown: contact -> no contact, R-" in text  # inside the crown
    assert pair.first_contact[1] == ["trunk"]
    # events are in increasing order and exact
    for a, b in zip(pair.events, pair.events[1:], strict=False):
        assert a.time.compare(b.time) < 0


def test_json_is_complete_and_exact():
    r = simulate(builtin_scene())
    data = json.loads(json.dumps(r.to_dict(30)))
    pair = data["pairs"][0]
    ev = pair["events"][0]
    assert len(ev["time"]["decimal"].split(".")[1]) == 30
    assert "root_of" in ev["time"] and len(ev["time"]["interval"]) == 2
    assert data["ledger"]["done"]["characteristic_polynomials"] > 0
    assert pair["first_contact"]["pieces"] == ["trunk"]
    assert {s["piece"] for s in data["smallness"]} == {"crown", "trunk"}
    assert pair["episodes"][0]["state"]["zones"]["z - 6"]["zone"] == 2


def test_plan_validation():
    with pytest.raises(SceneError, match="unknown effect"):
        Plan.from_effects(["zone", "collision"])
    with pytest.raises(SceneError, match="no effect"):
        Plan.from_effects([])
    p = Plan.from_effects(["first_contact", "smallness"])
    assert p.stop_at_first_contact and p.pieces and not p.region
    assert not Plan.from_effects(["first_contact", "zone"]).stop_at_first_contact


def test_an_unknown_smallness_policy_is_a_choice_error_naming_the_choices():
    scene = builtin_scene(check_smallness=False)
    for bogus in ("bogus", "", "Warn", 1):
        with pytest.raises(ChoiceError, match="'refuse', 'warn' or None") as info:
            simulate(scene, effects=["zone"], on_not_small=bogus)
        assert info.value.details["choices"] == ("refuse", "warn", None)
    with pytest.raises(ChoiceError, match="got 'bogus'"):
        scene.check_smallness(on_not_small="bogus")
    assert simulate(scene, effects=["zone"], on_not_small=None).ledger is not None


def test_an_unknown_reading_is_a_choice_error_naming_the_choices():
    scene = builtin_scene(check_smallness=False)
    for bogus in ("bogus", "", "Paper", 1, ["paper"]):
        with pytest.raises(ChoiceError, match="'geometry', 'paper'") as info:
            simulate(scene, effects=["zone"], reading=bogus)
        assert info.value.details["choices"] == READINGS


def test_progress_bar_on_request(capsys):
    simulate(builtin_scene("swarm_around_tree"), effects=["contact"], progress=True)
    err = capsys.readouterr().err
    assert "simulating" in err and "segment" in err
    simulate(builtin_scene("swarm_around_tree"), effects=["contact"], progress=False)
    assert capsys.readouterr().err == ""


def test_ledger_rejects_unknown_items():
    led = Ledger()
    with pytest.raises(KeyError):
        led.add("coffee")
    with pytest.raises(KeyError):
        led.add_full("samples")
    led.add("samples", 0, target="x")
    assert led.cost("x") == 0 and "samples" in led.format()


def test_contact_kind_between_events_uses_the_segre_analysis():
    """A unit sphere sliding along the axis inside a cylinder of radius 1 touches it along
    a circle all the time (Table 3: curve of tangency), with all roots real and a
    persistent multiple root; the kind needs the singular members of the pencil."""
    text = """
[scene]
name = "piston"
time = [0, 1]
effects = ["contact", "contact_kind"]
[[object]]
name = "bore"
[[object.piece]]
name = "bore"
standard = "elliptic cylinder"
a = 1
b = 1
[[ellipsoid]]
name = "piston"
standard = "sphere"
radius = 1
motion = { type = "linear", velocity = [0, 0, 1] }
"""
    r = simulate(parse_scene(text, "piston.toml"))
    pair = r.pairs[0]
    assert pair.events == []
    value = dict(pair.initial.pieces)["bore"]
    assert value.contact is False and value.kind == "tangent_curve"


def _without_per_object_effects(scene):
    from dataclasses import replace

    return replace(scene, ellipsoid_effects={}, piece_effects={}, smallness=dict(scene.smallness))


def test_per_object_effects_compute_only_what_each_asks_for():
    scene = builtin_scene("bees_with_interests")
    assert scene.ellipsoid_effects["worker"] == ("first_contact",)
    assert scene.piece_effects["tree", "crown"] == ("zone", "contact", "first_contact")
    r = simulate(scene)
    everything = simulate(_without_per_object_effects(scene))
    # the worker stops at its first contact; the drone keeps no regions; nobody has the crown's region
    worker, drone, scout = r.pair("worker", "tree"), r.pair("drone", "tree"), r.pair("scout", "tree")
    assert not worker.complete and worker.first_contact is not None
    assert worker.first_contact[0].compare(everything.pair("worker", "tree").first_contact[0]) == 0
    assert all(v.region is None for ep in drone.episodes for _, v in ep.state.pieces if v is not None)
    for ep in scout.episodes:
        pieces = dict(ep.state.pieces)
        if pieces.get("crown") is not None:
            assert pieces["crown"].region is None
        trunk = pieces.get("trunk")
        if trunk is not None and trunk.contact is False and not trunk.beyond_cut:
            # (crossing the whole quadric beyond the cut, the ellipsoid is on neither side)
            assert trunk.region is not None

    # the contact timelines are the ones of the run that computes everything
    def contact_changes(pair):
        def flags(state):
            return {n: v.contact for n, v in state.pieces if v is not None}

        return [e.time.decimal(20) for e in pair.events if flags(e.before) != flags(e.after)]

    for name in ("scout", "drone"):
        mine = contact_changes(r.pair(name, "tree"))
        assert mine and mine == contact_changes(everything.pair(name, "tree"))
    # and the ledger shows the work saved against every effect everywhere
    for item in ("characteristic_polynomials", "coefficient_signs"):
        assert r.ledger.done[item] < everything.ledger.done[item] <= r.ledger.full[item]
    text = r.format_text()
    assert "effects asked for by ellipsoid worker: first_contact" in text
    assert "worker vs tree\n  first contact:" in text


def test_per_object_effects_are_validated(stays_in_zone_2):
    bad = stays_in_zone_2 + '\n[effects]\nellipsoids = { wasp = ["zone"] }\n'
    with pytest.raises(SceneError, match=r"effects\.ellipsoids\.wasp"):
        parse_scene(bad, "bad.toml")
    bad = stays_in_zone_2 + '\n[effects]\npieces = { "tree/crown" = ["colour"] }\n'
    with pytest.raises(SceneError, match=r"effects\.pieces\.tree/crown\[0\]"):
        parse_scene(bad, "bad.toml")
    ok = parse_scene(stays_in_zone_2 + '\n[effects]\npieces = { "tree/trunk" = [] }\n', "ok.toml")
    r = simulate(ok)
    assert r.ledger.cost("tree/trunk") == dict(r.ledger.by_target["tree/trunk"]).get("smallness_checks", 0)
