"""The decision kernel (quadric_contact.modes.kernels.decision) and the lane of the pipeline that
runs it: its codes against the exact decision, the lane against the general steps on the same
pairs, its compiled and Python forms, and the pairs it must leave to the general steps."""

from __future__ import annotations

import numpy as np
import pytest

from quadric_contact.modes.codes import RegionCode
from quadric_contact.modes.decision import separation as sep
from quadric_contact.modes.kernels import decision as kd
from quadric_contact.modes.numbers.binary64 import FilterMode, FloatMode
from quadric_contact.modes.numbers.certified import CertifiedMode
from quadric_contact.modes.predicates import contact_kind, overlap, relative_position, transversal_contact
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_ellipsoids, random_pairs
from quadric_contact.theory import decision as dec


def _pairs(E, Q):
    return make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))[0]


def _populations():
    rng = np.random.default_rng(53)
    E1, Q1, _ = random_pairs(200, rng)
    E2, _ = random_ellipsoids(200, rng, axes=(0.5, 2.0), box=3.0)
    Q2, _ = random_ellipsoids(200, rng, axes=(2.0, 5.0), box=0.0)
    E3, _ = random_ellipsoids(200, rng, axes=(0.05, 0.2), box=4.0)
    env, _ = random_ellipsoids(1, rng, axes=(3.0, 5.0), box=0.0)
    cases = [c for c in hard_cases() if not c.exact_input]
    E4 = np.stack([c.matrices()[0] for c in cases])
    Q4 = np.stack([c.matrices()[1] for c in cases])
    # one quadric against a stack (the kernel's own layout: the quadric read once), and the
    # same pairs as a stack of pairs
    return [(E1, Q1), (E2, Q2), (E3, np.repeat(env, 200, axis=0)), (E3, env[0]), (E2, Q2[7]), (E4, Q4)]


def test_codes_are_the_exact_decision():
    """Every code the kernel gives is the exact answer: the criterion's region reading where it
    settles (a crossing, or E in the closed R+ of Q), the signature's separation code elsewhere."""
    lane = settled = 0
    for E, Q in _populations():
        crit, code, qsign, *_ = kd.decide_ellipsoids(_pairs(E, Q), outside_too=True)
        for i in range(E.shape[0]):
            if qsign[i] == 0:
                assert crit[i] == kd.OUT and code[i] == kd.NOT_RUN
                continue
            lane += 1
            exact = dec.decide_exact(E[i], Q if Q.ndim == 2 else Q[i])
            if crit[i] == int(RegionCode.CONTACT):
                assert exact.contact == dec.CONTACT, i
                settled += 1
            elif abs(int(crit[i])) == 1 and crit[i] * qsign[i] == 1:
                assert exact.contact == dec.NO_CONTACT, i  # touching or apart, never crossing
            if code[i] not in (kd.NOT_RUN, sep.UNCERTAIN):
                assert code[i] == exact.region, (i, code[i], exact.region)
                settled += 1
    assert lane > 800 and settled > 600


def test_left_out_pairs_are_those_without_two_certain_ellipsoids():
    """A quadric that is not an ellipsoid, a non-symmetric or non-finite matrix: out of the lane."""
    rng = np.random.default_rng(59)
    E, _ = random_ellipsoids(4, rng, axes=(0.5, 1.0), box=1.0)
    Q = np.stack(
        [np.diag([1.0, 1.0, 1.0, -9.0]), np.diag([1.0, 1.0, 0.0, -1.0]), np.diag([1.0, 1, 1, -9]), np.eye(4)]
    )
    Q[2, 0, 1] = 1e-3  # not symmetric
    Q[3, 3, 3] = np.nan
    crit, _, qsign, *_ = kd.decide_ellipsoids(_pairs(E, Q), outside_too=False)
    assert qsign[0] != 0
    assert (qsign[1:] == 0).all() and (crit[1:] == kd.OUT).all()


def test_the_compiled_kernel_is_the_python_one():
    from quadric_contact.modes.decision import pipeline

    rng = np.random.default_rng(61)
    E, _ = random_ellipsoids(70, rng, axes=(0.5, 2.0), box=3.0)
    Q, _ = random_ellipsoids(70, rng, axes=(2.0, 5.0), box=0.0)
    # quadrics of every type too: their pairs leave the lane (OUT = 7), and the table's key of
    # such a pair exceeds 127 (the Python form once wrapped it in int8 arithmetic, and answered)
    E1, Q1, _ = random_pairs(70, rng)
    tables = [
        (False, None),
        (False, pipeline._lane_table("contact")),
        (True, pipeline._lane_table("overlap")),
    ]
    # a stack of pairs; one quadric against a stack; every type
    for pairs in (_pairs(E, Q), _pairs(E, Q[3]), _pairs(E1, Q1)):
        for outside_too, table in tables:
            a = kd.decide_ellipsoids(pairs, outside_too=outside_too, table=table)
            b = kd.decide_ellipsoids(pairs, outside_too=outside_too, table=table, backend="numpy")
            for x, y in zip(a, b, strict=True):
                assert (x == y).all()


@pytest.mark.parametrize("question", ["contact", "region", "kind", "overlap"])
def test_the_kernel_reads_its_codes_as_the_table_does(question):
    """The kernel reads every pair's codes through the lane table as it goes, slice by slice
    on two threads: the answers, the pairs left and the counts are what reading its codes
    afterwards (:func:`~quadric_contact.modes.kernels.decision.read_codes`) gives."""
    from quadric_contact.modes.decision import pipeline

    rng = np.random.default_rng(71)
    n = 40_000  # several slices on each thread
    E, _ = random_ellipsoids(n, rng, axes=(0.3, 2.0), box=3.0)
    Q, _ = random_ellipsoids(n, rng, axes=(1.0, 4.0), box=1.0)
    Q[::97] = np.diag([1.0, 1.0, 0.0, -1.0])  # cylinders: left to the general steps
    table = pipeline._lane_table(question)
    for pairs, stacked in ((_pairs(E, Q), True), (_pairs(E, Q[5]), False)):
        crit, sep_, qsign, out, left, by_step = kd.decide_ellipsoids(
            pairs, outside_too=question == "overlap", table=table, threads=2
        )
        want, want_left, want_steps = kd.read_codes(crit, sep_, qsign, *table)
        assert (out == want).all()
        assert left.tolist() == want_left.tolist()
        assert by_step.tolist() == want_steps.tolist()
        assert by_step[0] > 0 and by_step[1] > 0
        if stacked:
            assert set(range(0, n, 97)) <= set(left.tolist())


def _without_lane(mode):
    """The same mode with the lane switched off: the general steps decide every pair."""
    for m in (mode, *getattr(mode, "stages", ())):
        if hasattr(m, "decide_ellipsoids"):
            m.decide_ellipsoids = lambda pairs, outside_too, table: None
    return mode


QUESTIONS = {
    "contact": transversal_contact,
    "region": relative_position,
    "overlap": overlap,
    "kind": contact_kind,
}


@pytest.mark.parametrize("question", list(QUESTIONS))
@pytest.mark.parametrize("mode", [CertifiedMode, FilterMode, FloatMode])
def test_the_lane_answers_as_the_steps_do(question, mode):
    """The lane is a faster road to the same answers: certified modes give the same codes with
    and without it; the plain float mode gives the certified answer wherever the lane settled a
    pair (it reads certified facts), which the general steps also give on these pairs."""
    fn = QUESTIONS[question]
    for E, Q in _populations():
        with_lane = fn(E, Q, mode=mode())
        steps = fn(E, Q, mode=_without_lane(mode()))
        if mode is FloatMode:
            truth = fn(E, Q, mode="certified")
            assert (with_lane == truth).sum() >= (steps == truth).sum()
        else:
            assert (with_lane == steps).all()


def test_the_lane_counts_its_stages():
    rng = np.random.default_rng(67)
    E, _ = random_ellipsoids(300, rng, axes=(0.5, 2.0), box=3.0)
    Q, _ = random_ellipsoids(300, rng, axes=(2.0, 5.0), box=0.0)
    mode = CertifiedMode()
    transversal_contact(E, Q, mode=mode)
    decided = mode.last.decided
    assert decided.get("criterion (filter)", 0) > 0 and decided.get("separation (filter)", 0) > 0
    assert mode.last.total == 300


def test_invalid_input_still_raises_through_the_lane():
    from quadric_contact.exact.errors import NonFiniteError, NotSymmetricError

    rng = np.random.default_rng(71)
    E, _ = random_ellipsoids(40, rng, axes=(0.5, 2.0), box=3.0)
    Q, _ = random_ellipsoids(40, rng, axes=(2.0, 5.0), box=0.0)
    bad = Q.copy()
    bad[17, 0, 2] += 1e-9
    with pytest.raises(NotSymmetricError):
        transversal_contact(E, bad)
    bad = E.copy()
    bad[5, 1, 1] = np.inf
    with pytest.raises(NonFiniteError):
        overlap(bad, Q)


def test_the_codes_are_read_through_the_rules_table():
    """The lane reads the kernel's three codes through a table built by the steps' own rules:
    the compiled reading gives, pair by pair, the rules' answer and step."""
    from quadric_contact.modes.decision import pipeline

    rng = np.random.default_rng(67)
    n = 5000
    crit = rng.choice(np.array([-1, 0, 1, 6, 7], dtype=np.int8), n)
    code = rng.integers(-1, 4, n).astype(np.int8)
    qsign = rng.integers(-1, 2, n).astype(np.int8)
    for question in ("contact", "region", "kind", "overlap"):
        if question == "overlap":
            want, step = pipeline._overlap_lane_rules(crit, code, qsign)
        else:
            want, step = pipeline._lane_rules(crit, code, qsign, question)
        out, left, by_step = kd.read_codes(crit, code, qsign, *pipeline._lane_table(question))
        assert (out == want).all(), question
        assert (left == np.flatnonzero(step == 2)).all()
        assert by_step.tolist() == np.bincount(step, minlength=3).tolist()
        assert (step[qsign == 0] == 2).all()  # a pair left out of the lane goes on to the steps
