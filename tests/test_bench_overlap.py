"""The overlap benchmark: its reimplementation of HOOMD-blue's ellipsoid test gives HOOMD's own
expected answers, its matrices are the package's, and the script runs."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import quadric_contact as qc

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def bench():
    spec = importlib.util.spec_from_file_location("bench_overlap", ROOT / "benchmarks" / "bench_overlap.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _params(axes, pos):
    n = len(pos)
    return {
        "axes": np.tile(np.asarray(axes, dtype=float), (n, 1)),
        "quat": np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)),
        "pos": np.asarray(pos, dtype=float),
    }


def test_hoomd_reimplementation_gives_hoomds_expected_answers(bench):
    """``overlap_ellipsoid_no_rot`` of HOOMD-blue's test_ellipsoid.cc: semi-axes (3, 1, 2) and
    (2, 3, 1), apart at 5.1 / 4.1 / 3.1 along x / y / z, overlapping at 4.9 / 3.9 / 2.9."""
    apart = [(5.1, 0, 0), (-5.1, 0, 0), (0, 4.1, 0), (0, -4.1, 0), (0, 0, 3.1), (0, 0, -3.1)]
    near = [(4.9, 0, 0), (-4.9, 0, 0), (0, 3.9, 0), (0, -3.9, 0), (0, 0, 2.9), (0, 0, -2.9)]
    a = _params((3, 1, 2), [(0, 0, 0)] * 6)
    got, err = bench.hoomd_overlap(a, _params((2, 3, 1), apart))
    assert not got.any() and not err.any()
    got, err = bench.hoomd_overlap(a, _params((2, 3, 1), near))
    assert got.all() and not err.any()
    # the matrices are the package's ellipsoids (inside negative)
    M = bench.matrices(_params((2, 3, 1), near[:1]))[0]
    exact = qc.Quadric.ellipsoid(2, 3, 1, center=(4.9, 0, 0))
    assert np.allclose(M, exact.to_numpy(), rtol=1e-15, atol=1e-15)
    packed = np.array([v[0] for v in bench.hoomd_matrices(_params((2, 3, 1), near[:1]))])
    assert np.allclose(
        packed, [M[0, 0], M[1, 0], M[1, 1], M[2, 0], M[2, 1], M[2, 2], M[3, 0], M[3, 1], M[3, 2], M[3, 3]]
    )


def test_the_script_runs(bench, capsys):
    pytest.importorskip("fcl")
    bench.main(["--pairs", "60", "--fcl-pairs", "10", "--repeat", "1"])
    out = capsys.readouterr().out
    assert "hard-case ladder" in out and "HOOMD-blue (numpy)" in out
    line = next(x for x in out.splitlines() if x.startswith("overlap exact input"))
    assert line.split()[3] == "0"  # the reference is never wrong
