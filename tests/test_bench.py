"""``quadric-contact bench`` runs, reports every target and writes its files (smoke
profile: seconds; the timings themselves are not asserted)."""

import json

import pytest

from quadric_contact.interfaces import benchmark
from quadric_contact.interfaces.cli import main


def test_bench_smoke_profile_writes_table_json_and_reports_targets(tmp_path, capsys):
    assert main(["bench", "--profile", "smoke", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    for needle in (
        "Time per test",
        "certified",
        "numpy eigvals",
        "Near-tangent ladder",
        "Targets",
        "pairs/s",
    ):
        assert needle in out
    data = json.loads((tmp_path / "bench_smoke.json").read_text())
    names = {t["name"] for t in data["targets"]}
    assert {
        "certified vs numpy batch eigvals",
        "certified vs plain float kernel",
        "exact mode per pair (float input)",
        "float kernel vs reading its inputs",
        "escalated past the float stage",
        # the kernel targets: the criterion alone at the memory limit, first use
        "certified criterion, distinct (N, 4, 4) pairs",
        "certified criterion, one matrix against a stack",
        "certified criterion vs numpy batch eigvals, one matrix against a stack",
        "filter vs float, distinct pairs",
        "certified criterion vs reading its inputs (distinct)",
        "first array call after install (empty cache)",
    } <= names
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
    assert (tmp_path / "bench_smoke.md").exists()


def test_peers_agree_with_exact_far_from_tangency():
    import numpy as np

    from quadric_contact.interfaces.benchmark import criterion_stack as transversal_contact_batch
    from quadric_contact.testing.samples import random_pairs

    E, Q, _ = random_pairs(30, np.random.default_rng(4), kinds=benchmark.GENERIC_KINDS)
    truth = transversal_contact_batch(E, Q, mode="exact")
    assert (benchmark.peer_sympy(E[:3], Q[:3]) == truth[:3]).all()
    assert (benchmark.peer_numpy_eigvals(E, Q) == truth).all()
    assert (benchmark.peer_numpy_roots(E, Q) == truth).all()


def test_fcl_peer_when_installed():
    pytest.importorskip("fcl")
    import numpy as np

    from quadric_contact.interfaces.benchmark import criterion_stack as transversal_contact_batch
    from quadric_contact.model.classification import QuadricKind
    from quadric_contact.testing.samples import random_pairs

    E, Q, _, ge, gq = random_pairs(
        40, np.random.default_rng(8), kinds=(QuadricKind.ELLIPSOID,), with_geometry=True
    )
    keep = np.flatnonzero(gq["sign"] > 0)
    E, Q = E[keep], Q[keep]
    ge = {k: v[keep] for k, v in ge.items()}
    gq = {k: v[keep] for k, v in gq.items()}
    truth = benchmark.exact_overlap(E, Q, transversal_contact_batch(E, Q, mode="exact"))
    assert (benchmark.peer_fcl(ge, gq, range(len(E))) == truth).all()


@pytest.mark.slow
def test_first_use_compiles_once_and_says_so():
    # minutes: every kernel of the complete decision is compiled into an empty cache directory
    c = benchmark.cold_start()
    assert c["fresh"]["notice"]
    assert not c["warm"]["notice"]
    assert c["warm"]["first"] < c["fresh"]["first"]
