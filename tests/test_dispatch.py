"""The public predicates' one dispatch: the provenance of a decision as data, and the counts of a
call returned with the call (right when one mode instance serves several threads)."""

from __future__ import annotations

import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact.exact.errors import ChoiceError
from quadric_contact.modes import CertifiedMode, FilterMode, FloatMode, StageCounts
from quadric_contact.modes.codes import Provenance, Step
from quadric_contact.modes.dispatch import replace
from quadric_contact.modes.numbers.number_mode import QUESTIONS, Decided
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.testing.samples import random_ellipsoids

EX11 = ("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")  # non-real roots: the criterion
DISC = ("100*(x - 17/20)**2 + y**2 + z**2 - 1", "x**2 + y**2 - z**2/100 - 1")  # the separation
IMAGINARY = ("x**2 + y**2 + z**2 - 1", "x**2 + y**2 + z**2 + 1")  # no real points
TOUCHING = ("x**2 + y**2 + z**2 - 1", "(x - 2)**2 + y**2 + z**2 - 1")  # the filter cannot tell

PAIRS = (EX11, DISC, IMAGINARY, TOUCHING)


def _answer(pair, mode):
    r = qc.transversal_contact(*pair, mode=mode)
    return r.decided_by, r.reason


@pytest.fixture(scope="module")
def filter_answers():
    """The answer of each pair in the filter mode, each from a sequential call on an instance of
    its own; each pair is settled by a different step (or by none), so that a result that took
    another caller's counts would name the wrong one."""
    answers = {pair: _answer(pair, FilterMode()) for pair in PAIRS}
    assert len({by for by, _ in answers.values()}) == len(PAIRS)
    assert answers[TOUCHING][0] is None
    return answers


def _pairs(E, Q):
    return make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))[0]


# -- provenance as data ---------------------------------------------------------------------------


def test_a_provenance_prints_as_the_stage_counts_name_it():
    assert str(Provenance(Step.CRITERION, "filter")) == "criterion (filter)"
    assert str(Provenance(Step.SEPARATION, "exact")) == "separation (exact)"
    assert str(Provenance(Step.SMALLNESS, "ball")) == "smallness (ball)"
    assert str(Provenance(Step.NO_REAL_POINTS, "type")) == "no real points (type)"
    assert str(Provenance(Step.EXACT_PAIR)) == "exact pair"
    assert (
        str(Provenance(Step.EXACT_PAIR, "outside binary64's range"))
        == "exact pair (outside binary64's range)"
    )
    assert Provenance(Step.CRITERION, "filter") == Provenance(Step.CRITERION, "filter")
    with pytest.raises(AttributeError):
        Provenance(Step.CRITERION).step = Step.SEPARATION  # type: ignore[misc]


def test_stage_counts_keep_the_provenance_behind_each_name():
    counts = StageCounts()
    counts.add(Provenance(Step.CRITERION, "filter"), 0)
    counts.add(Provenance(Step.SEPARATION, "ball"), 2)
    counts.add("by hand", 1)
    assert counts.decided == {"criterion (filter)": 0, "separation (ball)": 2, "by hand": 1}
    assert counts.deciding() == Provenance(Step.SEPARATION, "ball")
    merged = StageCounts()
    merged.merge(counts)
    merged.merge(counts)
    assert merged.decided["separation (ball)"] == 4
    assert merged.provenance["separation (ball)"] == Provenance(Step.SEPARATION, "ball")
    assert "by hand" not in merged.provenance
    assert StageCounts().deciding() is None
    assert StageCounts({"exact pair": 1}) == StageCounts({"exact pair": 1})


@pytest.mark.parametrize("mode", [CertifiedMode, FilterMode, FloatMode])
@pytest.mark.parametrize("question", ["contact", "region", "kind", "overlap", "criterion", "smallness"])
def test_every_count_of_a_call_has_its_provenance(mode, question):
    rng = np.random.default_rng(5)
    E, _ = random_ellipsoids(40, rng, axes=(0.5, 2.0), box=3.0)
    Q, _ = random_ellipsoids(40, rng, axes=(1.0, 4.0), box=1.0)
    codes, counts = mode().decide(question, _pairs(E, Q))
    assert codes.shape == (40,) and counts.total == 40
    assert counts.decided and set(counts.provenance) == set(counts.decided)
    for name, provenance in counts.provenance.items():
        assert isinstance(provenance.step, Step) and str(provenance) == name


def test_the_documented_stage_name_still_keys_the_counts():
    mode = CertifiedMode()
    E = np.diag([2.0, 2.0, 3.0, -1.0])
    Q = np.array([[1.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 4], [0, 0, 4, 0]])
    qc.transversal_contact(np.stack([E, E]), Q, mode=mode)
    assert mode.last.decided["criterion (filter)"] == 2
    assert mode.last.provenance["criterion (filter)"] == Provenance(Step.CRITERION, "filter")


def test_the_exact_path_counts_an_exact_pair_in_the_callers_instance():
    mode = CertifiedMode()
    qc.transversal_contact(*EX11, mode=mode)
    assert mode.last.decided == {"exact pair": 1}
    assert mode.last.deciding() == Provenance(Step.EXACT_PAIR)


class _Told(FilterMode):
    """A mode whose every answer is ``code``, said to come from ``provenance``."""

    def __init__(self, code: int, provenance: Provenance | None) -> None:
        super().__init__()
        self.told = (code, provenance)

    def decide(self, question, pairs):
        code, provenance = self.told
        counts = StageCounts()
        if provenance is None:
            counts.undecided = pairs.n
        else:
            counts.add(provenance, pairs.n)
        self._record(counts)
        return Decided(np.full(pairs.n, code, dtype=np.int8), counts)


@pytest.mark.parametrize(
    ("provenance", "contact", "region"),
    [
        (Provenance(Step.CRITERION, "filter"), "Remark 9", "Remark 9"),
        (Provenance(Step.SMALLNESS, "filter"), "Corollary 10", "Theorem 13 / Table 4"),
        # the step decides, not the name: a stage whose numbers are called "criterion"
        (Provenance(Step.SEPARATION, "criterion"), "separation certificate", "separation certificate"),
        (Provenance(Step.NO_REAL_POINTS, "smallness"), "no real points", "no real points"),
        (Provenance(Step.EXACT_PAIR, "criterion"), "exact pair (criterion)", "exact pair (criterion)"),
    ],
)
def test_the_result_a_stage_stands_for_is_read_from_its_provenance(provenance, contact, region):
    mode = _Told(1, provenance)  # ContactCode.CONTACT
    r = qc.transversal_contact(*EX11, mode=mode)
    assert (r.transversal, r.decided_by) == (True, contact)
    assert r.reason == f"transversal contact, decided in filter mode by {provenance}"
    mode.told = (0, provenance)  # RegionCode.CONTACT
    r = qc.relative_position(*EX11, mode=mode)
    assert (r.region, r.decided_by) == (qc.Region.CONTACT, region)
    mode.told = (2, None)
    r = qc.transversal_contact(*EX11, mode=mode)
    assert (r.transversal, r.decided_by, r.reason) == (None, None, "filter mode cannot tell (undecided)")


def test_a_plane_cleared_by_the_criterion_is_theorem_14():
    mode = _Told(0, Provenance(Step.CRITERION, "filter"))  # ContactCode.NO_CONTACT
    assert qc.transversal_contact("x**2 + y**2 + z**2 - 1", "z - 3", mode=mode).decided_by == "Theorem 14"
    assert qc.transversal_contact(*DISC, mode=mode).decided_by == "Remark 9"


def test_a_mode_is_asked_a_question_by_its_name():
    assert set(QUESTIONS) == {"contact", "region", "kind", "overlap", "criterion", "smallness"}
    with pytest.raises(ChoiceError):
        FilterMode().decide("contacts", _pairs(*EX11))


def test_one_replace_for_the_frozen_results():
    r = qc.transversal_contact(*EX11, mode="exact")
    assert replace(r, mode="exact") is r
    copy = replace(r, mode="certified")
    assert copy is not r and copy.mode == "certified" and r.mode == "exact"
    assert (copy.transversal, copy.decided_by, copy.reason) == (r.transversal, r.decided_by, r.reason)
    o = qc.overlap(*TOUCHING, mode="exact")
    o2 = replace(o, code=qc.OverlapCode.SEPARATE, convention="separate")
    assert (o2.code, o2.convention, o2.touching, o.code) == (
        qc.OverlapCode.SEPARATE,
        "separate",
        True,
        qc.OverlapCode.TOUCHING,
    )


# -- counts returned with the call, one instance shared by threads --------------------------------


class _Interleaved(FilterMode):
    """A filter mode whose calls, two at a time, both record their counts before either returns:
    the interleaving that makes ``last`` the other call's counts for one of them."""

    def __init__(self) -> None:
        super().__init__()
        self.barrier = threading.Barrier(2, timeout=60)

    def _record(self, counts):
        super()._record(counts)
        self.barrier.wait()


@pytest.mark.parametrize("second", [DISC, IMAGINARY, TOUCHING])
def test_a_shared_instance_explains_each_callers_pair(second, filter_answers):
    """Two threads ask one instance about different pairs, and both calls record their counts
    before either builds its result: each result still names its own deciding stage."""
    mode = _Interleaved()
    with ThreadPoolExecutor(2) as pool:
        for _ in range(3):
            a, b = pool.map(lambda pair: qc.transversal_contact(*pair, mode=mode), [EX11, second])
            assert (a.decided_by, a.reason) == filter_answers[EX11]
            assert (b.decided_by, b.reason) == filter_answers[second]
    assert mode.counts.total == 6


def test_each_call_gets_its_own_counts_from_a_shared_instance():
    """Many threads, one instance: every call's counts are its own, and the instance adds them
    all up."""
    mode = CertifiedMode()
    rng = np.random.default_rng(11)
    sizes = [1, 3, 7, 20, 50] * 6
    stacks = []
    for n in sizes:
        E, _ = random_ellipsoids(n, rng, axes=(0.5, 2.0), box=3.0)
        Q, _ = random_ellipsoids(n, rng, axes=(1.0, 4.0), box=1.0)
        stacks.append(_pairs(E, Q))
    want = [CertifiedMode().decide("contact", p) for p in stacks]

    def ask(k):
        return mode.decide("contact", stacks[k])

    with ThreadPoolExecutor(6) as pool:
        got = list(pool.map(ask, range(len(stacks))))
    for n, w, g in zip(sizes, want, got, strict=True):
        assert (g.codes == w.codes).all()
        assert g.counts.total == n and g.counts.decided == w.counts.decided
    assert mode.counts.total == sum(sizes) and mode.counts.undecided == 0


def test_single_pairs_from_many_threads_on_one_instance(filter_answers):
    mode = FilterMode()
    pairs = list(PAIRS) * 8
    with ThreadPoolExecutor(4) as pool:
        got = list(pool.map(lambda pair: _answer(pair, mode), pairs))
    assert got == [filter_answers[p] for p in pairs]
    assert mode.counts.total == len(pairs)
