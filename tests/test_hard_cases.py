"""The hard-case suite (tests/fixtures, built by tests/fixtures/make_hard_cases.py):
certified always equals exact; where and how the other modes fail is recorded."""

import collections
import importlib.util
import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from tests.oracles import criterion_contact as transversal_contact_batch
from tests.oracles import criterion_region as relative_position_batch

from quadric_contact import Quadric
from quadric_contact.modes import CertifiedMode, ContactCode, RegionCode, get_mode
from quadric_contact.testing.hardcases import FAMILIES, hard_cases

FIXTURES = Path(__file__).parent / "fixtures"


def _load_script():
    spec = importlib.util.spec_from_file_location("make_hard_cases", FIXTURES / "make_hard_cases.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def records():
    return json.loads((FIXTURES / "hard_cases.json").read_text())["cases"]


@pytest.fixture(scope="module")
def cases():
    return hard_cases()


def _run(cases, predicate, mode):
    """Answers of ``mode`` on every case (binary64 and exact inputs batched separately)."""
    out = np.empty(len(cases), dtype=np.int8)
    for exact in (False, True):
        idx = [k for k, c in enumerate(cases) if c.exact_input == exact]
        if not idx:
            continue
        E = np.stack([cases[k].matrices()[0] for k in idx])
        Q = np.stack([cases[k].matrices()[1] for k in idx])
        out[idx] = predicate(E, Q, mode=mode)
    return out


@pytest.fixture(scope="module")
def expected(records):
    contact = np.array([int(ContactCode[r["exact_contact"]]) for r in records], dtype=np.int8)
    region = np.array([int(RegionCode[r["exact_region"]]) for r in records], dtype=np.int8)
    return contact, region


def test_fixture_file_is_what_the_script_generates(records, cases):
    assert [r["id"] for r in records] == [c.id for c in cases]
    assert (FIXTURES / "hard_cases.json").read_text() == _load_script().build()


def test_every_family_is_present_and_ladders_cover_every_type(records):
    families = collections.Counter(r["family"] for r in records)
    assert set(families) == set(FAMILIES)
    kinds = {r["kind"] for r in records if r["family"] == "ladder"}
    assert len(kinds) == 10
    distances = {r["distance"] for r in records if r["family"] == "ladder"}
    assert {f"1e-{k}" for k in range(2, 17)} <= distances
    assert {r["side"] for r in records if r["family"] == "ladder"} == {"R-", "R+"}


def test_every_construction_means_what_it_says(records):
    """The intended answers hold for the exact rational matrices (exact scalar path)."""
    script = _load_script()
    from quadric_contact.testing.hardcases import HardCase

    for r in records:
        if r["intended_contact"] is None:
            continue
        exact = HardCase(
            r["id"],
            r["family"],
            r["description"],
            tuple(Fraction(v) for v in r["E"]),
            tuple(Fraction(v) for v in r["Q"]),
            True,
            r["intended_contact"],
            r["intended_region"],
            r["kind"],
        )
        contact, region = script.exact_answers(exact)
        assert (contact == "CONTACT") == r["intended_contact"], r["id"]
        assert RegionCode[region].region.value == r["intended_region"], r["id"]


def test_dyadic_cases_are_held_exactly_by_binary64(cases):
    dyadic = [c for c in cases if c.family in ("dyadic-tangent", "example-11")]
    assert dyadic and all(c.rounding_is_exact for c in dyadic)
    assert any(Quadric._from_upper(c.Q).kind.is_degenerate for c in dyadic)


@pytest.mark.parametrize("what", ["contact", "region"])
def test_certified_equals_exact_on_every_case(cases, expected, what):
    predicate = transversal_contact_batch if what == "contact" else relative_position_batch
    mode = CertifiedMode()
    got = _run(cases, predicate, mode)
    want = expected[0] if what == "contact" else expected[1]
    assert (got == want).all(), [c.id for c, g, w in zip(cases, got, want, strict=True) if g != w][:10]
    assert mode.counts.undecided == 0 and mode.counts.escalated > 0
    assert (_run(cases, predicate, "exact") == want).all()


@pytest.mark.parametrize("mode", ["filter", "ball"])
def test_bounded_modes_are_never_wrong_where_they_answer(cases, expected, mode):
    for predicate, want in zip((transversal_contact_batch, relative_position_batch), expected, strict=True):
        got = _run(cases, predicate, mode)
        decided = got != 2
        assert (got[decided] == want[decided]).all()
        assert (~decided).any()  # and they do leave something to the next stage


def _failures(cases, expected, mode):
    out = collections.Counter()
    for predicate, want in zip((transversal_contact_batch, relative_position_batch), expected, strict=True):
        got = _run(cases, predicate, mode)
        for c, g, w in zip(cases, got, want, strict=True):
            if g != 2 and g != w:
                out[c.family] += 1
    return out


def test_float_fails_near_tangency_but_reads_structural_zeros(cases, expected):
    wrong = _failures(cases, expected, "float")
    # Rounding left to itself: near tangency, huge offsets, thin ellipsoids ...
    assert wrong["ladder"] > 0 and wrong["huge-offset"] > 0 and wrong["thin"] > 0
    # ... but not the structural zeros, which plain float reads exactly as the filter does:
    # c0 = 0 / c1 = c0 = 0 of the exactly held cylinders, parallel planes and planes, and
    # Delta_4 = 0 for proportional quadratic parts (wrong only within rounding of tangency).
    assert wrong["dyadic-tangent"] == 0
    got = _run(cases, transversal_contact_batch, "float")
    for c, g, w in zip(cases, got, expected[0], strict=True):
        if c.family == "delta4-zero" and g != w:
            assert c.distance in ("1e-15", "1e-16"), c.id
    assert _failures(cases, expected, "certified") == collections.Counter()


def test_float_is_right_far_from_tangency(cases, expected):
    far = [k for k, c in enumerate(cases) if c.family == "ladder" and c.distance in ("1e-2", "1e-3", "1e-4")]
    got = _run([cases[k] for k in far], transversal_contact_batch, "float")
    assert (got == expected[0][far]).all()


def test_mpmath_at_fifty_digits_fails_only_near_tangency(cases, expected):
    wrong = _failures(cases, expected, get_mode("mpmath", dps=50))
    # exact tangencies (Delta_4 = 0 by geometry, not structure) read as rounding noise;
    # the structural zeros are read exactly
    assert sum(wrong.values()) > 0
    assert set(wrong) <= {"ladder", "ladder-exact", "thin", "nearly-spherical", "huge-offset"}
