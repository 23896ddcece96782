"""Contract tests of the array predicates, parametrized over every mode and both
predicates at once: shapes and broadcasting, dtypes, bad input, codes, counts."""

import pickle
from fractions import Fraction
from itertools import product

import numpy as np
import pytest
from tests.oracles import criterion_contact as transversal_contact_batch
from tests.oracles import criterion_region as relative_position_batch

import quadric_contact as qc
from quadric_contact import (
    NonFiniteError,
    NotAnEllipsoidError,
    NotANumberError,
    NotSymmetricError,
    Quadric,
    QuadricKind,
    ShapeError,
    UndecidedError,
    characteristic_polynomial,
)
from quadric_contact.exact.discriminants import root_structure
from quadric_contact.exact.errors import QuadricContactError
from quadric_contact.model.classification import TABLE_1_KINDS, classify
from quadric_contact.modes import (
    MODES,
    CertifiedMode,
    ContactCode,
    ExactMode,
    FilterMode,
    FloatMode,
    RegionCode,
    Sign,
    StageCounts,
    get_mode,
)
from quadric_contact.modes.decision.answers import (
    CONTACT_TABLE,
    ELLIPSOID_TABLE,
    KINDS,
    kind_from_invariant_signs,
    masks_from_invariant_signs,
    rows_from_masks,
    sign_index,
)
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import random_pairs
from quadric_contact.theory.results import Region

ALL_MODES = list(MODES)
PREDICATES = [transversal_contact_batch, relative_position_batch]
CODE_TYPES = {transversal_contact_batch: ContactCode, relative_position_batch: RegionCode}


@pytest.fixture(scope="module")
def sample():
    E, Q, _ = random_pairs(24, np.random.default_rng(3))
    return E, Q


@pytest.fixture(scope="module")
def exact_answers(sample):
    E, Q = sample
    return {p: p(E, Q, mode="exact") for p in PREDICATES}


# -- shapes and broadcasting ----------------------------------------------------------


@pytest.mark.parametrize("mode", ALL_MODES)
@pytest.mark.parametrize("predicate", PREDICATES)
def test_shapes_broadcast_like_numpy(mode, predicate, sample):
    E, Q = sample
    E4, Q5 = E[:4], Q[:5]
    grid = predicate(E4[:, None], Q5[None, :], mode=mode)
    assert grid.shape == (4, 5) and grid.dtype == np.int8
    for i, j in product(range(4), range(5)):
        assert grid[i, j] == predicate(E4[i], Q5[j], mode=mode)
    one_e = predicate(E[0], Q5, mode=mode)
    assert one_e.shape == (5,) and (one_e == grid[0]).all()
    one_q = predicate(E4, Q5[0], mode=mode)
    assert one_q.shape == (4,) and (one_q == grid[:, 0]).all()
    assert predicate(E4[:, None, None], Q5[None, :2, None], mode=mode).shape == (4, 2, 1)
    assert predicate(E[:0], Q[:0], mode=mode).shape == (0,)


@pytest.mark.parametrize("predicate", PREDICATES)
def test_single_pair_gives_one_code(predicate, sample):
    E, Q = sample
    code = predicate(E[0], Q[0])
    assert isinstance(code, CODE_TYPES[predicate])
    assert code == predicate(E[:1], Q[:1])[0]


@pytest.mark.parametrize("predicate", PREDICATES)
@pytest.mark.parametrize(
    "e_shape, q_shape",
    [
        ((3, 4, 4), (2, 4, 4)),
        ((4, 3), (4, 4)),
        ((2, 4, 5), (4, 4)),
        ((4,), (4, 4)),
        ((2, 3, 4, 4), (2, 4, 4)),
    ],
)
def test_bad_shapes_raise_shape_error(predicate, e_shape, q_shape):
    with pytest.raises(ShapeError):
        predicate(np.zeros(e_shape), np.zeros(q_shape))


# -- dtypes ---------------------------------------------------------------------------------


@pytest.mark.parametrize("predicate", PREDICATES)
def test_every_input_type_gives_the_same_answers(predicate, sample, exact_answers):
    E, Q = sample
    ref = exact_answers[predicate]
    frac = lambda M: np.vectorize(Fraction, otypes=[object])(M)  # noqa: E731
    assert (predicate(frac(E), frac(Q)) == ref).all()  # dyadic Fractions are float input
    assert (predicate(E.tolist(), Q.tolist()) == ref).all()
    quadrics_e = [Quadric.from_matrix(m) for m in E]
    assert (predicate(quadrics_e, Q) == ref).all()
    centers = np.array([[1, 0, 0], [0, 2, -1], [3, 3, 3]])
    A = np.diag([2, 2, 3])
    ints = np.zeros((3, 4, 4), dtype=np.int64)
    ints[:, :3, :3] = A
    ints[:, :3, 3] = ints[:, 3, :3] = -centers @ A
    ints[:, 3, 3] = np.einsum("ni,ij,nj->n", centers, A, centers) - 1
    assert (predicate(ints, Q[0]) == predicate(ints.astype(float), Q[0])).all()
    big = ints.astype(object) * 2**70  # beyond binary64: exact input
    assert (predicate(big, Q[0]) == predicate(ints.astype(float), Q[0])).all()
    assert (predicate(E.astype(np.float32), Q) == predicate(E.astype(np.float32).astype(np.float64), Q)).all()


def test_equations_and_quadrics_work_for_single_pairs():
    code = transversal_contact_batch("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z", mode="float")
    assert code is ContactCode.CONTACT
    assert relative_position_batch(Quadric.sphere(1), "z - 6") is RegionCode.R_MINUS


# -- bad input ------------------------------------------------------------------------------


def _bad_inputs(E, Q):
    nan = E.copy()
    nan[3, 1, 2] = nan[3, 2, 1] = np.nan
    inf = Q.copy()
    inf[2, 3, 3] = np.inf
    asym = E.copy()
    asym[5, 0, 3] += 1.0
    hyperboloid = E.copy()
    hyperboloid[4] = np.diag([1.0, 1.0, -1.0, -1.0])
    return [
        (nan, Q, NonFiniteError, "E[3]"),
        (E, inf, NonFiniteError, "Q[2]"),
        (asym, Q, NotSymmetricError, "E[5]"),
        (hyperboloid, Q, NotAnEllipsoidError, "E[4]"),
        (E.astype(bool), Q, NotANumberError, None),
        (E.astype(complex), Q, NotANumberError, None),
    ]


@pytest.mark.parametrize("mode", ALL_MODES)
@pytest.mark.parametrize("predicate", PREDICATES)
def test_bad_input_raises_the_package_errors(mode, predicate, sample):
    E, Q = (np.array(x) for x in sample)
    for bad_e, bad_q, error, where in _bad_inputs(E, Q):
        with pytest.raises(error) as info:
            predicate(bad_e, bad_q, mode=mode)
        if where:
            assert where in str(info.value)


def test_exact_input_that_is_not_symmetric_or_not_a_number():
    M = np.array([[Fraction(1), 2, 0, 0], [3, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]], dtype=object)
    with pytest.raises(NotSymmetricError):
        transversal_contact_batch(M[None], M)
    with pytest.raises(NotANumberError):
        transversal_contact_batch(np.full((1, 4, 4), "x", dtype=object), M)


# -- codes ---------------------------------------------------------------------------------


def test_region_codes_are_the_sign_of_q_over_e_and_map_to_regions():
    assert RegionCode.from_region(Region.R_MINUS) == -1 and RegionCode.R_MINUS.region is Region.R_MINUS
    assert RegionCode.from_region("R+") == 1 and RegionCode.from_region("contact") == 0
    assert RegionCode.from_region(None) is RegionCode.NO_ROW and RegionCode.EXCLUDED.region is None
    assert ContactCode.CONTACT.transversal is True and ContactCode.UNCERTAIN.transversal is None


def test_uncertain_is_never_read_as_false():
    with pytest.raises(UndecidedError):
        bool(Sign.UNCERTAIN)
    assert bool(Sign.NEGATIVE) and not bool(Sign.ZERO)
    assert bool(np.int8(ContactCode.UNCERTAIN)) and bool(np.int8(RegionCode.UNCERTAIN))
    assert bool(ContactCode.UNCERTAIN)


@pytest.mark.parametrize("mode", ["certified", "exact", "float", "mpmath"])
@pytest.mark.parametrize("predicate", PREDICATES)
def test_modes_that_always_answer_never_say_uncertain(mode, predicate, sample):
    E, Q = sample
    assert not (predicate(E, Q, mode=mode) == 2).any()


@pytest.mark.parametrize("mode", ["certified", "filter", "ball"])
@pytest.mark.parametrize("predicate", PREDICATES)
def test_certified_modes_agree_with_exact_wherever_they_answer(mode, predicate, sample, exact_answers):
    E, Q = sample
    got = predicate(E, Q, mode=mode)
    decided = got != 2
    assert (got[decided] == exact_answers[predicate][decided]).all()


@pytest.mark.parametrize("predicate", PREDICATES)
def test_numba_and_numpy_backends_give_identical_codes(predicate):
    cases = [c for c in hard_cases(["ladder", "dyadic-tangent", "delta4-zero"]) if not c.exact_input]
    E = np.stack([c.matrices()[0] for c in cases])
    Q = np.stack([c.matrices()[1] for c in cases])
    for cls in (FloatMode, FilterMode):
        a = predicate(E, Q, mode=cls(backend="numba"))
        b = predicate(E, Q, mode=cls(backend="numpy"))
        assert (a == b).all(), cls


@pytest.mark.parametrize("stage", ["screen", "filter"])
def test_each_float_stage_is_the_same_in_both_backends(stage):
    from quadric_contact.modes.numbers.binary64 import stage_codes

    E, Q, _ = random_pairs(3000, np.random.default_rng(21))
    cases = [
        c for c in hard_cases(["ladder", "dyadic-tangent", "delta4-zero", "huge-offset"]) if not c.exact_input
    ]
    E = np.concatenate([E, np.stack([c.matrices()[0] for c in cases])])
    Q = np.concatenate([Q, np.stack([c.matrices()[1] for c in cases])])
    a = stage_codes(E, Q, stage, backend="numba")
    b = stage_codes(E, Q, stage, backend="numpy")
    assert (a == b).all()
    assert 0 < (a == 2).sum() < len(a)


def test_exact_backends_agree(sample, exact_answers):
    E, Q = sample
    assert (
        transversal_contact_batch(E, Q, mode=ExactMode("fmpz")) == exact_answers[transversal_contact_batch]
    ).all()


# -- modes as objects -------------------------------------------------------------------------


def test_certified_mode_exposes_who_decided_what(sample):
    E, Q = sample
    mode = CertifiedMode()
    transversal_contact_batch(E, Q, mode=mode)
    assert mode.last.total == len(E) and mode.last.undecided == 0
    assert list(mode.last.decided) == ["filter", "ball", "exact"]
    relative_position_batch(E, Q, mode=mode)
    assert mode.counts.total == 2 * len(E)
    mode.reset_counts()
    assert mode.counts.total == 0
    hard = [c for c in hard_cases(["dyadic-tangent"])]
    He = np.stack([c.matrices()[0] for c in hard])
    Hq = np.stack([c.matrices()[1] for c in hard])
    transversal_contact_batch(He, Hq, mode=mode)
    assert mode.last.escalated > 0 and mode.last.decided["filter"] + mode.last.escalated == len(hard)
    assert "filter" in str(mode.last)


def test_binary64_criterion_goes_from_the_filter_to_the_exact_stage(monkeypatch):
    """On binary64 input the exact stage decides what the filter leaves (it costs less than
    the balls there); on rounded exact input the ball stage still takes its turn.  Either way
    the answers are the exact ones."""
    from fractions import Fraction

    from quadric_contact.modes.numbers.objects import BallMode

    asked = []
    ball = BallMode.criterion_contact

    def spy(self, pairs):
        asked.append(pairs.n)
        return ball(self, pairs)

    monkeypatch.setattr(BallMode, "criterion_contact", spy)
    hard = [c for c in hard_cases(["dyadic-tangent"]) if not c.exact_input]
    He = np.stack([c.matrices()[0] for c in hard])
    Hq = np.stack([c.matrices()[1] for c in hard])
    mode = CertifiedMode()
    got = transversal_contact_batch(He, Hq, mode=mode)
    assert mode.last.escalated > 0
    assert mode.last.decided["ball"] == 0 and mode.last.decided["exact"] == mode.last.escalated
    assert asked == []
    assert (got == transversal_contact_batch(He, Hq, mode="exact")).all()
    third = np.vectorize(lambda x: Fraction(x) / 3, otypes=[object])
    Fe, Fq = third(He), third(Hq)
    got = transversal_contact_batch(Fe, Fq, mode=mode)
    assert mode.last.escalated > 0 and asked == [mode.last.escalated]
    assert (got == transversal_contact_batch(Fe, Fq, mode="exact")).all()


def test_binary64_types_go_from_the_filter_to_the_exact_stage(monkeypatch):
    """The type of a quadric the filter cannot tell (an invariant that is exactly zero although
    its products are not: integer matrices ``P^T D P`` of rank 3) is read by the exact stage on
    binary64 input, not by the balls first; a rotated cylinder, whose det Q is a rounding's
    worth from 0, is certified by the filter's double-double reading and never asks the exact
    stage; the types are the exact ones, and the exact invariants are computed once per
    quadric and stack."""
    from quadric_contact.modes import facts
    from quadric_contact.modes.decision.answers import rows_from_masks
    from quadric_contact.modes.numbers import objects
    from quadric_contact.modes.stacks.batch import as_stack

    asked = []
    ball = objects.BallMode.classify
    computed = []
    exact = facts.integer_invariant_signs

    def spy(self, Q, rows=None):
        asked.append(len(rows))
        return ball(self, Q, rows)

    def count(Q, rows):
        computed.append(len(rows))
        return exact(Q, rows)

    monkeypatch.setattr(objects.BallMode, "classify", spy)
    monkeypatch.setattr(facts, "integer_invariant_signs", count)
    _, Q, _ = random_pairs(60, np.random.default_rng(43))
    CertifiedMode().classify(as_stack(Q, "Q"))
    assert computed == []  # rotated cylinders, cones, paraboloids ... : all certified in floats
    P = np.array([[1.0, 2, -1, 3], [0, 1, 1, -2], [0, 0, 1, 1], [0, 0, 0, 1]])
    zeros = np.stack([P.T @ np.diag(d) @ P for d in ([1.0, 2, 0, -1], [1.0, -3, 0, 2], [2.0, 0, 0, -1])])
    stack = as_stack(np.concatenate([Q, zeros]), "Q")
    mode = CertifiedMode()
    got = rows_from_masks(mode.classify(stack))
    assert asked == []
    before = sum(computed)
    assert 0 < before <= len(zeros)  # the filter left the exact zeros to the exact stage
    mode.classify(stack)  # the same stack again: the exact signs are kept with it
    assert sum(computed) == before
    want = rows_from_masks(objects.ExactMode().classify(as_stack(np.concatenate([Q, zeros]), "Q")))
    assert (got == want).all()


def test_stage_counts_merge():
    a = StageCounts({"filter": 3}, 1)
    a.merge(StageCounts({"filter": 2, "exact": 1}))
    assert a.decided == {"filter": 5, "exact": 1} and a.total == 7 and a.escalated == 2


def test_get_mode():
    assert isinstance(get_mode(), CertifiedMode)
    assert get_mode("ball", prec=256).prec == 256  # type: ignore[attr-defined]
    m = FloatMode()
    assert get_mode(m) is m
    with pytest.raises(ValueError):
        get_mode("interval")
    with pytest.raises(ValueError):
        get_mode(m, backend="numpy")
    with pytest.raises(ValueError):
        CertifiedMode(stages=(FloatMode(),))


def test_modes_pickle_without_their_lock(sample):
    E, Q = sample
    mode = pickle.loads(pickle.dumps(CertifiedMode()))
    assert (transversal_contact_batch(E, Q, mode=mode) == transversal_contact_batch(E, Q)).all()


# -- the decision tables, against independent computations ----------------------------------------


def test_contact_table_agrees_with_root_structure_of_random_quartics():
    rng = np.random.default_rng(5)
    from quadric_contact.exact.discriminants import paper_deltas

    seen = set()
    for _ in range(3000):
        roots = [int(r) for r in rng.integers(-3, 4, size=rng.integers(0, 3) * 2)]
        # quartics with a chosen number of real roots, plus random ones
        c = [int(v) for v in rng.integers(-5, 6, size=5)]
        if roots:
            p = np.poly1d([1.0])
            for r in roots:
                p *= np.poly1d([1.0, -r])
            while p.order < 4:
                p *= np.poly1d([1.0, 0.0, int(rng.integers(1, 4))])
            c = [round(v) for v in p.coeffs[::-1]]
        if c[4] == 0:
            continue
        d2, d3, d4 = paper_deltas(c)
        signs = tuple(int(np.sign(v)) for v in (d2, d3, d4))
        seen.add(signs)
        code = CONTACT_TABLE[sign_index(signs[0]) + 4 * sign_index(signs[1]) + 16 * sign_index(signs[2])]
        assert code == (0 if root_structure(c).all_real else 1), c
    assert len(seen) >= 8


def test_uncertain_contact_entries_are_resolved_only_when_every_completion_agrees():
    assert CONTACT_TABLE[sign_index(2) + 4 * sign_index(2) + 16 * sign_index(-1)] == 1  # Delta4 < 0
    assert CONTACT_TABLE[sign_index(2) + 4 * sign_index(2) + 16 * sign_index(1)] == 2
    assert ELLIPSOID_TABLE[2, sign_index(-1), sign_index(2), sign_index(2)] == 0  # m2 < 0 decides


def _degenerate_quadrics():
    return [
        Quadric.diagonal(1, 1, -1, 0),  # cone
        Quadric.diagonal(1, -1, 0, 0),  # intersecting planes
        Quadric.diagonal(1, 0, 0, 0),  # coincident planes
        Quadric.diagonal(1, 1, 1, 1),  # imaginary ellipsoid
        Quadric.diagonal(1, 1, 0, 1),  # imaginary elliptic cylinder
        Quadric.diagonal(1, 0, 0, 1),  # imaginary parallel planes
        Quadric.diagonal(0, 0, 0, 1),  # empty
        Quadric.diagonal(0, 0, 0, -1),
        Quadric.diagonal(0, 0, 0, 0),
        Quadric.diagonal(1, 1, 1, 0),  # imaginary cone
        Quadric.diagonal(1, 1, 0, 0),  # imaginary intersecting planes
    ]


def test_kind_from_invariant_signs_is_classify():
    from quadric_contact._generated import kernels

    qs = _degenerate_quadrics()
    E, Q, _ = random_pairs(60, np.random.default_rng(6))
    qs += [Quadric.from_matrix(m) for m in Q[:60]]
    qs += [-q for q in qs]
    for kind in TABLE_1_KINDS:  # the kinds with a standard form (the others are refused)
        params = dict(zip(Quadric.standard_parameters(kind), (3, 2, 1), strict=False))
        qs.append(Quadric.standard(kind, **params))
    for kind in set(QuadricKind) - set(TABLE_1_KINDS):
        with pytest.raises(QuadricContactError, match="no standard form"):
            Quadric.standard(kind, a=3)
    for q in qs:
        inv = kernels.quadric_invariants(*q.upper)
        signs = (*tuple(int(np.sign(v)) for v in inv), int(np.sign(q.upper[9])))
        assert kind_from_invariant_signs(signs) == classify(q.upper), q
        mask = masks_from_invariant_signs(np.array([signs]))
        assert KINDS[int(rows_from_masks(mask)[0]) // 2] is q.kind


def test_every_kind_is_handled_by_the_region_predicate():
    e = Quadric.sphere(Fraction(1, 4), center=(5, 5, 5))
    for q in _degenerate_quadrics()[:-1]:
        P = characteristic_polynomial(e, q)
        code = relative_position_batch(e, q)
        if not P.structure.all_real:
            assert code is RegionCode.CONTACT
        else:
            assert code is RegionCode.EXCLUDED, q


@pytest.mark.slow
@pytest.mark.parametrize("predicate", PREDICATES)
def test_certified_equals_exact_on_many_random_pairs(predicate):
    E, Q, _ = random_pairs(200_000, np.random.default_rng(99))
    mode = CertifiedMode()
    assert (predicate(E, Q, mode=mode) == predicate(E, Q, mode="exact")).all()
    assert mode.last.escalated > 0  # the rounded cylinders and parallel planes


def test_input_binary64_cannot_hold_is_decided_exactly_in_every_mode():
    """Exact input beyond binary64's range or below its normal numbers: its rounding is no
    longer the same quadric (a ball of radius ``1e-200`` rounds to a point), so the filters
    leave it and the plain modes decide it exactly; every mode and form gives the exact answer."""
    unit = "x**2 + y**2 + z**2 - 1"
    tiny_r2 = "1e-400"  # squared radius of a ball at the origin
    tiny_ball = f"x**2 + y**2 + z**2 - {tiny_r2}"
    huge_a = "1e309"  # the ellipsoid huge_a x^2 + y^2 + z^2 = 1 at the origin
    huge = f"{huge_a}*x**2 + y**2 + z**2 - 1"
    S2 = np.diag([1.0, 1.0, 1.0, -4.0])  # the ball of squared radius 4 at the origin
    # the geometry, from the numbers above: both ellipsoids are centred at the origin, so each
    # lies strictly inside the ball when its largest semi-axis is shorter than the ball's radius
    assert Fraction(tiny_r2) < 1 and max(1 / Fraction(huge_a), Fraction(1)) < 4  # squared lengths
    overlapping, inside = qc.OverlapCode.OVERLAPPING, qc.Region.R_MINUS
    for mode in ("certified", "float", "mpmath", "exact"):
        assert qc.overlap(unit, [tiny_ball], mode=mode).tolist() == [int(overlapping)], mode
        assert qc.overlap(unit, tiny_ball, mode=mode).code is overlapping, mode
        assert qc.transversal_contact(huge, S2, mode=mode).transversal is False, mode
        no_contact = int(qc.ContactCode.NO_CONTACT)
        assert qc.transversal_contact([huge], S2, mode=mode).tolist() == [no_contact], mode
        assert qc.relative_position(huge, S2, mode=mode).region is inside, mode


def test_matrices_of_wide_range_are_classified_without_a_crash():
    """Signs of invariants that no quadric has together (a completion of uncertain signs with
    ``rank A = 0`` and ``rank Q = 4``) are skipped, not looked up: a quadric whose entries span
    a wide range of magnitudes is answered, as the exact mode answers it."""
    S = np.diag([1.0, 1.0, 1.0, -1.0])
    for Q in (np.diag([1.0, 1.0, 1.0, -4.0]) * 1e60, np.diag([1.0, 1.0, 1e-300, -1.0])):
        want = qc.transversal_contact(S[None], Q[None], mode="exact").tolist()
        for mode in ("certified", "float"):
            assert qc.transversal_contact(S[None], Q[None], mode=mode).tolist() == want, mode
            assert (
                qc.relative_position(S[None], Q[None], mode=mode).tolist()
                == qc.relative_position(S[None], Q[None], mode="exact").tolist()
            ), mode
