"""``quadric-contact simulate``: the default scene, JSON, plots, and no half-written output."""

from __future__ import annotations

import json
from fractions import Fraction as F

import pytest

from quadric_contact.interfaces.cli import main

BROKEN = """
[scene]
name = "broken"
time = [0, 1]
[[object]]
name = "o"
[[object.piece]]
name = "p"
equation = "x^2 + y^2 + z^2 = 1"
[[ellipsoid]]
name = "e"
equation = "x^2 + y^2 + z^2 = 1"
motion = { type = "linear", velocity = [1, 0, "fast"] }
"""


def test_default_runs_the_bee_and_the_tree(capsys):
    assert main(["simulate"]) == 0
    out = capsys.readouterr().out
    assert "The bee and the tree (Example 17)" in out
    assert "bee vs tree" in out and "first contact: t = " in out
    assert "work ledger" in out and "characteristic_polynomials" in out and "time:" in out


def test_json_and_output_file(capsys, tmp_path):
    target = tmp_path / "run.json"
    assert main(["simulate", "capsule_pipe", "--json", "--places", "25", "-o", str(target)]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert json.loads(target.read_text()) == printed | {"seconds": json.loads(target.read_text())["seconds"]}
    ev = printed["pairs"][0]["events"][0]
    assert len(ev["time"]["decimal"].split(".")[1]) == 25


def test_effects_override_and_list(capsys):
    assert main(["simulate", "--effects", "zone", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["effects"] == ["zone"]
    assert data["ledger"]["by_target"].get("tree/crown") is None
    assert main(["simulate", "--list"]) == 0
    out = capsys.readouterr().out
    assert "bee_and_tree" in out and "drone_cooling_tower" in out


def test_plot_writes_a_png(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    target = tmp_path / "bee.png"
    assert main(["simulate", "--plot", str(target)]) == 0
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "plot written" in capsys.readouterr().out
    assert [p.name for p in tmp_path.iterdir()] == ["bee.png"]  # no temporary files left


def test_bad_scene_exits_2_and_writes_nothing(tmp_path, capsys):
    scene = tmp_path / "broken.toml"
    scene.write_text(BROKEN)
    out = tmp_path / "out.json"
    png = tmp_path / "out.png"
    assert main(["simulate", str(scene), "-o", str(out), "--plot", str(png)]) == 2
    err = capsys.readouterr().err
    assert (
        str(scene) in err and "ellipsoid[0].motion.velocity[2]" in err and "expected a finite number" in err
    )
    assert not out.exists() and not png.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["broken.toml"]


def test_bad_options_exit_2(tmp_path, capsys):
    assert main(["simulate", "--effects", "zone,teleport"]) == 2
    assert "--effects" in capsys.readouterr().err
    assert main(["simulate", "--plot", str(tmp_path / "no" / "such" / "dir.png")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert main(["simulate", str(tmp_path / "missing.toml")]) == 2
    assert "no such file" in capsys.readouterr().err


def test_not_small_is_refused_with_the_failing_condition(tmp_path, capsys):
    scene = tmp_path / "throat.toml"
    scene.write_text(
        BROKEN.replace('velocity = [1, 0, "fast"]', "velocity = [0.2, 0, 0]")
        .replace(
            'equation = "x^2 + y^2 + z^2 = 1"\n[[ellipsoid]]',
            'equation = "x^2 + y^2 - z^2/100 = 1"\n[[ellipsoid]]',
        )
        .replace(
            'name = "e"\nequation = "x^2 + y^2 + z^2 = 1"', 'name = "e"\nequation = "100*x^2 + y^2 + z^2 = 1"'
        )
    )
    assert main(["simulate", str(scene), "--effects", "contact"]) == 2
    err = capsys.readouterr().err
    assert "not small with respect to piece 'p'" in err and "FAILS" in err and "on_not_small" in err
    assert main(["simulate", str(scene), "--effects", "contact", "--on-not-small", "warn"]) == 0
    out = capsys.readouterr().out
    assert "NOT small" in out and "contact undecided" in out


def test_animate_writes_a_gif(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    from PIL import Image

    target = tmp_path / "walls.gif"
    assert main(["simulate", "parallel_walls", "--animate", str(target), "--frames", "6"]) == 0
    assert target.read_bytes()[:6] in (b"GIF87a", b"GIF89a")
    assert Image.open(target).n_frames == 6
    assert "animation written" in capsys.readouterr().out
    assert [p.name for p in tmp_path.iterdir()] == ["walls.gif"]
    assert main(["simulate", "parallel_walls", "--animate", str(target), "--frames", "1"]) == 2


def test_many_bodies_from_the_command_line(capsys):
    assert main(["simulate", "--list"]) == 0
    assert "many_bodies" in capsys.readouterr().out
    args = ["simulate", "many_bodies", "--bodies", "12", "--pieces", "4", "--seed", "2", "--json"]
    assert main(args) == 0
    broad = json.loads(capsys.readouterr().out)
    assert len(broad["pairs"]) == 12 and broad["ledger"]["done"]["broad_phase_tests"] > 0
    assert broad["events"] == sum(len(p["events"]) for p in broad["pairs"])
    assert main([*args, "--workers", "2"]) == 0
    two = json.loads(capsys.readouterr().out)
    assert _same_events(two, broad)
    assert main(["simulate", "many_bodies", "--bodies", "0"]) == 2


def test_broad_phase_option_keeps_the_timeline(capsys):
    assert main(["simulate", "drone_cooling_tower", "--json"]) == 0
    plain = json.loads(capsys.readouterr().out)
    assert main(["simulate", "drone_cooling_tower", "--json", "--broad-phase"]) == 0
    broad = json.loads(capsys.readouterr().out)
    assert _same_events(plain, broad)
    assert "broad_phase_tests" in broad["ledger"]["done"]


def _same_events(a, b):
    """The same events: same changes, the same polynomial (or rational) and overlapping
    isolating intervals for each time (the intervals themselves may differ)."""
    for pa, pb in zip(a["pairs"], b["pairs"], strict=True):
        assert len(pa["events"]) == len(pb["events"])
        for ea, eb in zip(pa["events"], pb["events"], strict=True):
            assert ea["changes"] == eb["changes"]
            ta, tb = ea["time"], eb["time"]
            assert ta.get("exact") == tb.get("exact") and ta.get("root_of") == tb.get("root_of")
            if "interval" in ta:
                lo = max(F(ta["interval"][0]), F(tb["interval"][0]))
                hi = min(F(ta["interval"][1]), F(tb["interval"][1]))
                assert lo < hi
    return True


def test_animate_many_bodies_as_points(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    target = tmp_path / "many.gif"
    args = [
        "simulate",
        "many_bodies",
        "--bodies",
        "14",
        "--pieces",
        "4",
        "--animate",
        str(target),
        "--frames",
        "3",
    ]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "events: " in out and "14 (ellipsoid, object) pair(s)" in out
    assert target.read_bytes()[:3] == b"GIF"


def test_animate_shows_progress_and_draws_the_path(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    pytest.importorskip("PIL")
    from quadric_contact.interfaces.animation import animate_result
    from quadric_contact.scenes.scene_toml import builtin_scene
    from quadric_contact.scenes.simulate import simulate

    target = tmp_path / "walls.gif"
    assert main(["simulate", "parallel_walls", "--animate", str(target), "--frames", "5", "--progress"]) == 0
    err = capsys.readouterr().err
    assert "animating" in err and "5/5" in err
    anim = animate_result(simulate(builtin_scene("parallel_walls")), frames=4)
    ax = anim._fig.axes[0]
    dashed = [ln for ln in ax.get_lines() if ln.get_linestyle() not in ("-", "None")]
    assert len(dashed) == 1 and len(dashed[0].get_data_3d()[0]) == 4  # the whole path, from the start
    assert min(t.get_fontsize() for t in ax.get_xticklabels() + ax.get_yticklabels()) >= 9
    anim._draw_was_started = True  # inspected, not rendered: no warning when it is dropped
    import matplotlib.pyplot as plt

    plt.close(anim._fig)


def test_event_labels_do_not_collide():
    from quadric_contact.interfaces.plotting import label_rows, merge_close_labels

    xs = [0.0, 2.6539, 2.6623, 2.9437, 2.9460, 2.9781, 8.0]
    rows = label_rows(xs, 0.045 * 8)
    for i in range(len(xs)):
        for j in range(i + 1, len(xs)):
            if rows[i] == rows[j]:
                assert xs[j] - xs[i] >= 0.045 * 8
    groups = merge_close_labels([[0, 0, 0], [0.01, 0, 0], [5, 0, 0]], 0.1)
    assert [m for m, _ in groups] == [[0, 1], [2]]


def test_mutual_contacts_and_full_event_lists_on_the_command_line(capsys):
    assert main(["simulate", "bees_meeting", "--events", "all"]) == 0
    out = capsys.readouterr().out
    assert "mutual contacts among 6 moving ellipsoids: 2 pair(s) meet" in out
    assert "north and south: start apart" in out
    assert main(["simulate", "bees_meeting", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert [m["bodies"] for m in data["mutual"]] == [["north", "south"], ["east", "west"]]
    assert main(["simulate", "bee_and_tree", "--mutual", "--places", "4"]) == 0  # one body: nothing to meet
    assert "mutual contacts" not in capsys.readouterr().out
