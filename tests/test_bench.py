"""``quadric-contact bench`` runs, writes its table, JSON and plot to ``--out`` (by default the
user cache directory, never the current one) and says where; the table speaks of what it
measured (smoke profile: seconds; the timings themselves are not asserted).  The command is
run as the user runs it (the command line, or a fresh process); the peers it measures are
checked against the exact answers."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from quadric_contact.interfaces.cli import main
from quadric_contact.interfaces.cli.arguments import user_cache_dir
from quadric_contact.model.classification import QuadricKind
from quadric_contact.modes.kernels._jit import kernel_cache_dir
from quadric_contact.modes.predicates import corollary_10
from quadric_contact.testing.peers import peer_fcl, peer_numpy_eigvals, peer_numpy_roots, peer_sympy
from quadric_contact.testing.references import exact_overlap
from quadric_contact.testing.samples import GENERIC_KINDS, random_pairs

ROOT = Path(__file__).resolve().parents[1]


def _bench(cwd: Path, extra: dict[str, str], *args: str) -> subprocess.CompletedProcess[str]:
    """``quadric-contact bench`` in a fresh process, run from ``cwd``, this checkout's sources
    first on the path and the kernels compiled into this process's cache (also where ``extra``
    moves the user's cache directory)."""
    env = {
        **os.environ,
        "QUADRIC_CONTACT_CACHE_DIR": kernel_cache_dir(),
        **extra,
        "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")]),
    }
    return subprocess.run(
        [sys.executable, "-m", "quadric_contact", "bench", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )


def _assert_speaks_of_measurements(table):
    """No pass/fail rows, no row of an unmeasured figure."""
    assert not re.search(r"\bnan\b", table, re.IGNORECASE)
    assert not re.search(r"target|\bgoal\b|\| met \|", table, re.IGNORECASE)
    assert not re.search(r"\|\s*(yes|no)\b", table, re.IGNORECASE)


def test_bench_smoke_profile_writes_to_out_and_nothing_to_the_current_directory(
    tmp_path, capsys, monkeypatch
):
    cwd, out_dir = tmp_path / "cwd", tmp_path / "out"
    cwd.mkdir()
    monkeypatch.chdir(cwd)
    assert main(["bench", "--profile", "smoke", "--out", str(out_dir)]) == 0
    out = capsys.readouterr().out
    assert list(cwd.iterdir()) == []
    assert f"to {out_dir.resolve()}" in out.splitlines()[-1]
    _assert_speaks_of_measurements(out)
    table = (out_dir / "bench_smoke.md").read_text()
    _assert_speaks_of_measurements(table)
    assert table in out
    for needle in (
        "Time per test",
        "certified",
        "numpy eigvals",
        "Near-tangent ladder",
        "## Summary",
        "pairs/s",
        "read bandwidth",
    ):
        assert needle in out
    # a figure the smoke profile does not measure is named with its reason, not shown as a value
    assert "Not measured: the first array call with an empty numba cache" in out
    data = json.loads((out_dir / "bench_smoke.json").read_text())
    assert "targets" not in data
    figures = {(f["name"], f["against"]) for f in data["summary"]}
    assert {
        ("certified criterion, pairs per second", "numpy batch eigvals"),
        ("certified criterion, pairs per second", "the plain float kernel"),
        ("float kernel, time", "reading its inputs once (read bandwidth)"),
        ("exact mode, time per pair (binary64 input)", "python-flint fmpz backend, sympy"),
        ("pairs escalated past the float stage (certified)", ""),
        # the kernels: the criterion alone at the memory limit
        ("certified criterion, distinct (N, 4, 4) pairs", ""),
        ("certified criterion, one matrix against a stack", ""),
        (
            "certified criterion, one matrix against a stack, pairs per second",
            "numpy batch eigvals, same pairs",
        ),
        ("filter, time, distinct pairs", "the plain float kernel"),
        ("certified criterion, distinct pairs, pairs per second", "reading its inputs once (read bandwidth)"),
    } <= figures
    assert all(f["measured"] == f["measured"] for f in data["summary"])  # no NaN
    assert "Kernels at the memory limit" in out
    # the complete decision, as a fraction of the criterion kernel, per population and question
    assert "The complete decision against the certified criterion kernel" in out
    methods = {(r["population"], r["method"]) for r in data["complete"]}
    for population in ("environment", "similar sizes", "every type"):
        for question in ("contact", "region", "overlap"):
            assert (population, f"{question}, certified") in methods
            assert (population, f"{question}, float") in methods
    assert "The exact scalar decision" in out and len(data["exact_scalar"]) == 2
    # the float mode on symmetric placements and near-tangent ladders: no wrong answer
    assert [f["float wrong"] for f in data["float_families"]] == [0, 0]
    wrong = {(m["population"], m["method"]): m["wrong"] for m in data["measurements"]}
    assert all(
        wrong[(pop, method)] == 0 for pop, method in wrong if method in ("certified", "exact", "filter")
    )


def test_bench_writes_to_the_user_cache_directory_by_default(tmp_path):
    cwd, cache = tmp_path / "cwd", tmp_path / "cache"
    cwd.mkdir()
    out = _bench(cwd, {"XDG_CACHE_HOME": str(cache)}, "--profile", "smoke", "--no-plot").stdout
    where = cache / "quadric-contact" / "bench"
    assert list(cwd.iterdir()) == []
    assert sorted(p.name for p in where.iterdir()) == ["bench_smoke.json", "bench_smoke.md"]
    assert f"to {where}" in out


def test_user_cache_directory(tmp_path, monkeypatch):
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr("sys.platform", "linux")
    assert user_cache_dir("bench") == tmp_path / "quadric-contact" / "bench"
    # a relative XDG_CACHE_HOME is ignored (the XDG specification), so never the current directory
    monkeypatch.setenv("XDG_CACHE_HOME", "cache")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert user_cache_dir() == tmp_path / "home" / ".cache" / "quadric-contact"
    monkeypatch.delenv("XDG_CACHE_HOME")
    assert user_cache_dir("hypothesis") == tmp_path / "home" / ".cache" / "quadric-contact" / "hypothesis"


def test_peers_agree_with_exact_far_from_tangency():
    E, Q, _ = random_pairs(30, np.random.default_rng(4), kinds=GENERIC_KINDS)
    truth = corollary_10(E, Q, mode="exact")
    assert (peer_sympy(E[:3], Q[:3]) == truth[:3]).all()
    assert (peer_numpy_eigvals(E, Q) == truth).all()
    assert (peer_numpy_roots(E, Q) == truth).all()


def test_fcl_peer_when_installed():
    pytest.importorskip("fcl")
    E, Q, _, ge, gq = random_pairs(
        40, np.random.default_rng(8), kinds=(QuadricKind.ELLIPSOID,), with_geometry=True
    )
    keep = np.flatnonzero(gq["sign"] > 0)
    E, Q = E[keep], Q[keep]
    ge = {k: v[keep] for k, v in ge.items()}
    gq = {k: v[keep] for k, v in gq.items()}
    truth = exact_overlap(E, Q, corollary_10(E, Q, mode="exact"))
    assert (peer_fcl(ge, gq, range(len(E))) == truth).all()


@pytest.mark.slow
def test_first_use_compiles_once_and_says_so(tmp_path):
    # minutes: the quick profile measures the first use in fresh processes, every kernel of the
    # complete decision compiled into an empty cache directory
    _bench(tmp_path, {}, "--profile", "quick", "--no-plot", "--out", str(tmp_path / "out"))
    c = json.loads((tmp_path / "out" / "bench_quick.json").read_text())["cold_start"]
    assert not c["native"]["notice"] and not c["native"]["twins"]  # the native kernels answer
    assert c["fresh"]["twins"] and not c["fresh"]["notice"]  # answered by the twins, said once
    assert c["compiling"]["notice"] and not c["compiling"]["twins"]
    assert not c["warm"]["notice"] and not c["warm"]["twins"]
    assert c["warm"]["first"] < c["compiling"]["first"]
