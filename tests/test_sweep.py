"""Sweeps: perturbations are reproducible, a sweep on a dask.distributed LocalCluster
gives exactly the serial results, and the command line runs one."""

from __future__ import annotations

import json
from fractions import Fraction as F
from importlib import resources

import pytest

from quadric_contact.exact.errors import SceneError
from quadric_contact.interfaces.cli import main
from quadric_contact.scenes.scene_toml import builtin_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.sweep import perturbed, run_sweep, summarize

BEE = resources.files("quadric_contact").joinpath("scenes", "bee_and_tree.toml").read_text()


def test_perturbations_are_small_reproducible_and_keep_smallness():
    bee = builtin_scene()
    a = perturbed(bee, 3, seed=4, amplitude=F(1, 10))
    assert a.smallness.keys() == bee.smallness.keys()
    for k0, k1 in zip(bee.ellipsoids[0].trajectory.keys, a.ellipsoids[0].trajectory.keys, strict=True):
        assert all(abs(u - v) <= F(1, 10) for u, v in zip(k0.position, k1.position, strict=True))

    def keys(scene):
        return scene.ellipsoids[0].trajectory.keys

    assert keys(perturbed(bee, 3, seed=4, amplitude=F(1, 10))) == keys(a)
    assert keys(perturbed(bee, 3, seed=5, amplitude=F(1, 10))) != keys(a)
    drone = builtin_scene("drone_cooling_tower")
    moved = perturbed(drone, 1)
    assert moved.ellipsoids[0].quadric != drone.ellipsoids[0].quadric  # initial place moved
    assert moved.ellipsoids[0].trajectory is drone.ellipsoids[0].trajectory


def test_a_run_summary_is_the_exact_timeline():
    result = simulate(perturbed(builtin_scene(), 2), effects=["contact", "first_contact"])
    (pair,) = summarize(result, 15)
    assert pair["events"] == [e.time.decimal(15) for e in result.pairs[0].events]
    assert pair["first_contact"]["pieces"] == ["trunk"]


def test_local_cluster_gives_the_serial_results():
    pytest.importorskip("dask.distributed")
    serial = run_sweep(BEE, "bee", 9, seed=1, serial=True)
    cluster = run_sweep(BEE, "bee", 9, seed=1, workers=1, threads=2, processes=False, chunk=2)
    assert cluster.runs == serial.runs
    assert "LocalCluster" in cluster.where and serial.where == "serial"
    firsts = serial.first_contacts("bee", "tree")
    assert len(set(firsts)) > 1
    unperturbed = simulate(builtin_scene(), effects=["first_contact"]).pairs[0].first_contact[0]
    assert firsts[0] == unperturbed.decimal(12)
    # and the same seed on an explicit client
    from dask.distributed import Client

    with Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=None) as client:
        again = run_sweep(BEE, "bee", 9, seed=1, client=client, chunk=4)
    assert again.runs == serial.runs


def test_sweep_from_the_command_line(tmp_path, capsys):
    target = tmp_path / "sweep.json"
    assert main(["sweep", "-n", "5", "--serial", "--amplitude", "0.02", "-o", str(target)]) == 0
    out = capsys.readouterr().out
    assert "5 runs" in out and "bee vs tree: first contact in 5 of 5 runs" in out
    data = json.loads(target.read_text())
    assert data["amplitude"] == "1/50" and len(data["results"]) == 5
    assert main(["sweep", "-n", "2", "--serial", "--amplitude", "a lot"]) == 2
    assert main(["sweep", "-n", "0", "--serial"]) == 2
    assert main(["sweep", "nowhere.toml", "--serial"]) == 2
    with pytest.raises(SceneError):
        run_sweep(BEE, "bee", 0, serial=True)
