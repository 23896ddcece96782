"""Smallness on stacks (Tables 1-2 as corrected) in every number mode: one meaning, the
exact scalar decision's, for every input form; the filter's bounds checked against exact
values."""

from __future__ import annotations

import ast
import inspect
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.oracles import smallness_codes
from tests.test_table_verification import ORDERED, max_scale

from quadric_contact import NotAnEllipsoidError, Quadric, QuadricKind, RigidMotion
from quadric_contact.exact.errors import ExcludedQuadricError
from quadric_contact.exact.quantity import Quantity, compare_quantities
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.model.invariants import invariants
from quadric_contact.modes import (
    CertifiedMode,
    FilterMode,
    FloatMode,
    get_mode,
)
from quadric_contact.modes.codes import SmallnessCode
from quadric_contact.modes.facts import table_kinds
from quadric_contact.modes.smallness import binary64 as sf
from quadric_contact.modes.smallness.tables import (
    E_SIDES,
    NPRIM,
    Q_SIDES,
    TABLE_CONDITIONS,
    evaluate,
    kind_signs,
)
from quadric_contact.modes.stacks.batch import as_stack, make_pairs
from quadric_contact.testing.strategies import ellipsoids, quadrics
from quadric_contact.theory.smallness import smallness

K = QuadricKind
C = SmallnessCode
UNC = int(C.UNCERTAIN)
ALL_MODES = ("certified", "exact", "filter", "ball", "float", "mpmath")
NONDEGENERATE = (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS)
"""Types whose quadratic part is invertible: plain binary64 sees them after a rotation in floating
point (a degenerate type rounded off its exact zero eigenvalue is a nearly degenerate other type,
where plain numbers may be wrong)."""
CERTAIN_MODES = ("certified", "exact")


def scalar_code(E, Q) -> int:
    """What the exact scalar decision says of one pair, as a code."""
    try:
        r = smallness(E, Q)
    except ExcludedQuadricError:
        return int(C.EXCLUDED)
    return int(C.SMALL if r.table_4_applies else (C.SMALL_ENCLOSING if r.small else C.NOT_SMALL))


def scalar_codes(Es, Qs) -> np.ndarray:
    return np.array([[scalar_code(e, q) for q in Qs] for e in Es], dtype=np.int8)


def margin(E, Q) -> float:
    """The smallest relative gap between the two sides of any condition (0 on a boundary)."""
    try:
        r = smallness(E, Q)
    except ExcludedQuadricError:
        return np.inf
    gaps = []
    for c in (*r.conditions, *r.alternative):
        lhs, rhs = (float(x.ball(64).mid()) for x in (c.lhs_squared, c.rhs_squared))
        gaps.append(abs(lhs - rhs) / max(abs(lhs), abs(rhs)))
    return min(gaps)


def check_modes(Es, Qs) -> np.ndarray:
    """Every mode on the pairs ``Es x Qs``: certified and exact equal the scalar decision,
    filter and ball where certain, float and mpmath away from the boundary."""
    ref = scalar_codes(Es, Qs)
    for name in ALL_MODES:
        got = np.stack([smallness_codes(Es[i], list(Qs), mode=name) for i in range(len(Es))])
        if name in CERTAIN_MODES:
            assert np.array_equal(got, ref), (name, got, ref)
        elif name in ("filter", "ball"):
            sure = got != UNC
            assert np.array_equal(got[sure], ref[sure]), (name, got, ref)
        else:
            # plain numbers: an answer everywhere, the right one away from the boundary of a
            # condition, for quadrics whose type they see (a degenerate type rounded off its
            # exact zero is another type for them)
            assert (got != UNC).all()
            for j, q in enumerate(Qs):
                if not sees_type(name, q):
                    continue
                for i, e in enumerate(Es):
                    if got[i, j] != ref[i, j]:
                        assert margin(e, q) < 1e-9, (name, i, j, got[i, j], ref[i, j])
    return ref


def sees_type(mode, q) -> bool:
    """Does the (plain) mode classify ``q`` as its exact type?"""
    kinds, _ = table_kinds(get_mode(mode).classify(as_stack(q, "Q"), np.zeros(1, dtype=np.intp)))
    exact = TABLE_1_KINDS.index(q.kind) if q.kind in TABLE_1_KINDS else -1
    return int(kinds[0]) == exact


# -- one meaning: the exact scalar decision --------------------------------------------------


@st.composite
def signed_ellipsoids(draw):
    e = draw(ellipsoids(max_axis=3))
    return e.scaled(draw(st.sampled_from([1, -1, Fraction(-5, 2), 3])))


@settings(max_examples=25)
@given(st.sampled_from(TABLE_1_KINDS), st.data())
def test_every_mode_on_exact_input(kind, data):
    Es = [data.draw(signed_ellipsoids()) for _ in range(2)]
    Qs = [data.draw(quadrics(kind)), data.draw(quadrics(kind, max_param=3))]
    check_modes(Es, Qs)


@settings(max_examples=25)
@given(st.sampled_from(TABLE_1_KINDS), st.data())
def test_float_input_is_the_dyadic_rational_it_stores(kind, data):
    """A float matrix is decided as the exact dyadic rational matrix it holds (whose type may
    differ from the construction's once rounded: then that type's row, or EXCLUDED)."""
    Es = [data.draw(signed_ellipsoids()).to_numpy(float) for _ in range(2)]
    Qs = [data.draw(quadrics(kind)).to_numpy(float) for _ in range(2)]
    ref = np.array([[scalar_code(Quadric.from_matrix(e), Quadric.from_matrix(q)) for q in Qs] for e in Es])
    for name in ALL_MODES:
        got = smallness_codes(np.stack(Es)[:, None], np.stack(Qs), mode=name)
        assert got.shape == (2, 2) and got.dtype == np.int8
        sure = got != UNC
        if name in CERTAIN_MODES:
            assert sure.all()
        if name in (*CERTAIN_MODES, "filter", "ball"):
            assert np.array_equal(got[sure], ref[sure]), (name, got, ref)


def test_random_small_ellipsoids_against_one_environment():
    """The paper's use case in floating point: many distinct ellipsoids, one quadric of each
    kind; the filter decides nearly all, the cascade equals the scalar decision."""
    rng = np.random.default_rng(7)
    n = 60
    Es = random_ellipsoids(rng, n, 0.5, 2, 3)
    for kind in TABLE_1_KINDS:
        q = rng_quadric(rng, kind)
        mode = CertifiedMode()
        got = smallness_codes(Es, q, mode=mode)
        ref = np.array([scalar_code(Quadric.from_matrix(e), Quadric.from_matrix(q)) for e in Es])
        assert np.array_equal(got, ref), kind
        assert mode.last.decided["smallness (filter)"] >= n - 2, (kind, mode.last)
        filt = smallness_codes(Es, q, mode="filter")
        sure = filt != UNC
        assert np.array_equal(filt[sure], ref[sure])
        if kind in NONDEGENERATE:
            # plain floats see the type, and random pairs are far from the boundary
            assert np.array_equal(smallness_codes(Es, q, mode="float"), ref), kind


def random_ellipsoids(rng, n, lo, hi, centre):
    """``n`` random ellipsoids (semi-axes in ``[lo, hi]``, random rotations, centres in
    ``[-centre, centre]^3``), as binary64 matrices."""
    axes = rng.uniform(lo, hi, size=(n, 3))
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    R = np.stack([quaternion_matrix(v) for v in q])
    A = np.einsum("nij,nj,nkj->nik", R, 1 / axes**2, R)
    A = (A + np.swapaxes(A, 1, 2)) / 2
    c = rng.uniform(-centre, centre, size=(n, 3))
    M = np.zeros((n, 4, 4))
    M[:, :3, :3] = A
    b = -np.einsum("nij,nj->ni", A, c)
    M[:, :3, 3] = b
    M[:, 3, :3] = b
    M[:, 3, 3] = np.einsum("ni,ni->n", c, np.einsum("nij,nj->ni", A, c)) - 1
    return M


def quaternion_matrix(q):
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def rng_quadric(rng, kind):
    """A quadric of ``kind`` with parameters in ``[2, 5]``, moved by a random float motion."""
    n = len(Quadric.standard_parameters(kind))
    params = sorted(rng.uniform(2, 5, size=n), reverse=True)
    S = Quadric.standard(kind, **dict(zip("abc", (Fraction(float(p)) for p in params), strict=False)))
    M = S.to_numpy(float)
    R = np.eye(4)
    R[:3, :3] = quaternion_matrix(_unit(rng.normal(size=4)))
    R[:3, 3] = rng.uniform(-1, 1, size=3)
    T = np.linalg.inv(R)
    out = T.T @ M @ T
    return (out + out.T) / 2


def _unit(v):
    return v / np.linalg.norm(v)


# -- input forms and shapes -------------------------------------------------------------------


def test_input_forms_give_one_answer():
    bee = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
    crown = "x**2 + y**2 + 3*(z - 8.36291)**2 - 20"
    trunk = "x**2 + y**2 - 0.25*(z-3)**2 - 1"
    e, q1, q2 = (Quadric.from_equation(s) for s in (bee, crown, trunk))
    expected = [scalar_code(e, q) for q in (q1, q2)]
    assert expected == [C.SMALL, C.SMALL]
    forms = [
        (bee, [q1, q2]),
        (e, [q1, q2]),
        ([e], [q1, q2]),
        (np.array(e.matrix, dtype=object), np.array([q1.matrix, q2.matrix], dtype=object)),
        ([list(r) for r in e.matrix], [[list(r) for r in q.matrix] for q in (q1, q2)]),
        (e.to_numpy(float), np.stack([q1.to_numpy(float), q2.to_numpy(float)])),
    ]
    for E, Q in forms:
        for mode in ALL_MODES:
            got = np.asarray(smallness_codes(E, Q, mode=mode)).reshape(-1)
            assert list(got) == expected, (mode, type(E))
    one = smallness_codes(bee, crown)
    assert isinstance(one, SmallnessCode) and one is C.SMALL and one.small and one.table_4_applies


def test_broadcasting_shapes_and_empty_stacks():
    rng = np.random.default_rng(3)
    Es = random_ellipsoids(rng, 6, 0.5, 2, 3).reshape(2, 3, 4, 4)
    Qs = np.stack([rng_quadric(rng, k) for k in NONDEGENERATE])
    got = smallness_codes(Es[:, :, None], Qs[None, None], mode="certified")
    assert got.shape == (2, 3, 3)
    for idx in np.ndindex(2, 3, 3):
        i, j, k = idx
        assert got[idx] == scalar_code(Quadric.from_matrix(Es[i, j]), Quadric.from_matrix(Qs[k]))
    # one quadric against many ellipsoids, and many against one, through every path
    for mode in ("float", "filter", FilterMode(backend="numpy"), FloatMode(backend="numpy")):
        assert np.array_equal(smallness_codes(Es, Qs[1], mode=mode), got[:, :, 1])
        assert np.array_equal(smallness_codes(Es[0, 0], Qs, mode=mode), got[0, 0])
    assert smallness_codes(np.zeros((0, 4, 4)), Qs[0]).shape == (0,)


def test_numba_and_numpy_backends_agree():
    rng = np.random.default_rng(5)
    Es = random_ellipsoids(rng, 300, 0.3, 3, 4)
    Es[::7] *= -1  # the other sign of the matrix
    for kind in TABLE_1_KINDS:
        q = rng_quadric(rng, kind)
        for cls in (FloatMode, FilterMode):
            a = smallness_codes(Es, q, mode=cls(backend="numba"))
            b = smallness_codes(Es, q, mode=cls(backend="numpy"))
            assert np.array_equal(a, b), (cls, kind)
        # the per-row route (ellipsoids repeated) and the fused one (all distinct) agree
        idx = rng.integers(0, 300, size=500)
        a = smallness_codes(Es[idx], q, mode="filter")
        pairs, _ = make_pairs(as_stack(Es, "E"), as_stack(q, "Q"))
        b = FilterMode().smallness(pairs.take(idx))
        assert np.array_equal(a, b)


def test_dask_input():
    da = pytest.importorskip("dask.array")  # the [dask] extra

    rng = np.random.default_rng(11)
    Es = random_ellipsoids(rng, 40, 0.5, 2, 3)
    q = rng_quadric(rng, K.HYPERBOLOID_ONE_SHEET)
    expected = smallness_codes(Es, q)
    got = smallness_codes(da.from_array(Es, chunks=(16, 4, 4)), q)
    assert np.array_equal(got, expected)
    lazy = smallness_codes(da.from_array(Es, chunks=(16, 4, 4)), q, compute=False)
    assert np.array_equal(np.asarray(lazy.compute()), expected)


# -- boundaries and errata -------------------------------------------------------------------


@pytest.mark.parametrize("exact", [False, True])
def test_two_equal_spheres(exact):
    """c = alpha and a/c^2 = gamma/alpha^2 hold with equality: small (Table 4 applies); the
    filter cannot separate equal sides and leaves the pair to the later stages."""
    r = Fraction(3, 2) if exact else Fraction(2)
    e = Quadric.sphere(r, center=(-5, 0, 7))
    q = Quadric.sphere(r, center=(1, 2, 3)).rotated((1, 2, 3, 4))
    E, Q = (m if exact else m.to_numpy(float) for m in (e, q))
    assert scalar_code(e, q) == C.SMALL
    assert smallness_codes(E, Q, mode="filter") is C.UNCERTAIN
    mode = CertifiedMode()
    assert smallness_codes(E, Q, mode=mode) is C.SMALL
    assert mode.last.decided["smallness (filter)"] == 0
    for name in ("exact", "ball"):
        assert smallness_codes(E, Q, mode=name) in (C.SMALL, C.UNCERTAIN)


def boundary_pair(kind, u, seed):
    """E at ``u`` times the largest scale Table 1 (corrected) allows for Q (``u = 1``: on the
    boundary), both standard, moved by one rational motion (as benchmarks/bench_smallness.py)."""
    rng = np.random.default_rng(seed)
    ps = [Fraction(int(rng.integers(4, 40)), 8) for _ in Quadric.standard_parameters(kind)]
    n = ORDERED.get(kind, 0)
    ps = sorted(ps[:n], reverse=True) + ps[n:]
    p = dict(zip("abc", ps, strict=False))
    shape = tuple(sorted((Fraction(int(rng.integers(2, 24)), 8) for _ in range(3)), reverse=True))
    s = max_scale(kind, p, shape) * u
    m = RigidMotion.from_quaternion(1, 2, 0, 1, (1, 0, -2))
    return Quadric.ellipsoid(*(s * v for v in shape)).moved(m), Quadric.standard(kind, **p).moved(m)


@pytest.mark.parametrize("kind", TABLE_1_KINDS)
def test_table_1_boundary(kind):
    """On the boundary u = 1 a condition holds with equality: small; just beyond it, not
    small; inside, small.  Only the exact stages may decide the first two."""
    for seed in range(2):
        pairs = [boundary_pair(kind, u, seed) for u in (Fraction(1), 1 + Fraction(1, 10**12), Fraction(1, 2))]
        Es = [e for e, _ in pairs]
        Qs = [q for _, q in pairs]
        ref = [scalar_code(e, q) for e, q in pairs]
        assert ref[0] == C.SMALL and ref[2] == C.SMALL and ref[1] != C.SMALL
        for name in ALL_MODES:
            got = [int(smallness_codes(e, q, mode=name)) for e, q in zip(Es, Qs, strict=True)]
            for g, r in zip(got, ref, strict=True):
                if name in CERTAIN_MODES:
                    assert g == r, (name, kind, got, ref)
                elif name in ("filter", "ball"):
                    assert g in (r, UNC), (name, kind, got, ref)
            if name == "filter":
                assert got[0] == UNC and got[1] == UNC and got[2] == ref[2]


def test_erratum_counterexamples():
    m = RigidMotion.from_quaternion(1, 2, 0, 1, (1, 0, -2))
    cases = [
        # one-sheet hyperboloid: the throat's curvature (the printed Table 1 says small)
        (
            Quadric.ellipsoid(Fraction(1, 10), 1, 1, center=(Fraction(17, 20), 0, 0)),
            Quadric.hyperboloid_one_sheet(1, 1, 10),
            C.NOT_SMALL,
        ),
        # an ellipsoid around a smaller one: small only the other way round (no Table 4)
        (Quadric.sphere(2), Quadric.sphere(1), C.SMALL_ENCLOSING),
        # hyperbolic cylinder: the transverse semi-axis is a (printed: M b')
        (
            Quadric.sphere(Fraction(3, 2)),
            Quadric.hyperbolic_cylinder(1, 10).rotated((1, 1, 0, 2)),
            C.NOT_SMALL,
        ),
        # parabolic cylinder: d'^2 = -4 K a'^2 (printed 4 K a'^2 < 0)
        (Quadric.sphere(Fraction(1, 10)), Quadric.parabolic_cylinder(3).moved(m), C.SMALL),
    ]
    for e, q, code in cases:
        assert scalar_code(e, q) == code
        for E, Q in ((e, q), (-e, -q), (e.to_numpy(float), q.to_numpy(float))):
            ref = (
                code
                if isinstance(E, Quadric)
                else scalar_code(Quadric.from_matrix(E), Quadric.from_matrix(Q))
            )
            for name in ALL_MODES:
                got = smallness_codes(E, Q, mode=name)
                exact_q = Q if isinstance(Q, Quadric) else Quadric.from_matrix(Q)
                if name in ("float", "mpmath") and not sees_type(name, exact_q):
                    continue
                assert got == ref or (name in ("filter", "ball") and got is C.UNCERTAIN), (name, code, got)
    assert smallness_codes(Quadric.sphere(1), Quadric.sphere(2)) is C.SMALL


@pytest.mark.parametrize(
    "q",
    [
        "x**2 + y**2 - z**2",  # cone
        "x**2 - y**2",  # intersecting planes
        "(x - 1)**2",  # coincident planes
        "z - 1",  # a plane
        "x**2 + y**2 + z**2 + 1",  # imaginary ellipsoid
        "x**2 + 1",  # imaginary parallel planes
    ],
)
def test_excluded_quadrics(q):
    with pytest.raises(ExcludedQuadricError):
        smallness("x**2 + y**2 + z**2 - 1", q)
    Q = Quadric.from_equation(q)
    for name in ALL_MODES:
        for E, QQ in (("x**2 + y**2 + z**2 - 1", Q), (np.diag([1.0, 1, 1, -1]), Q.to_numpy(float))):
            assert smallness_codes(E, QQ, mode=name) is C.EXCLUDED, (name, q)


def test_not_an_ellipsoid():
    good = np.diag([1.0, 1, 1, -1])
    bad = np.diag([1.0, 1, -1, -1])  # a one-sheet hyperboloid
    Q = np.diag([1.0, 1, 1, -9])
    for name in ALL_MODES:
        with pytest.raises(NotAnEllipsoidError, match=r"E\[1\]"):
            smallness_codes(np.stack([good, bad]), Q, mode=name)
        with pytest.raises(NotAnEllipsoidError):
            smallness_codes(bad, "z - 1", mode=name)  # checked before Q is looked at


def test_bad_input_is_diagnosed():
    from quadric_contact.exact.errors import NonFiniteError, NotSymmetricError

    E = np.diag([1.0, 1, 1, -1])
    Q = np.diag([1.0, 1, 1, -9])
    nan = E.copy()
    nan[0, 3] = nan[3, 0] = np.nan
    asym = E.copy()
    asym[0, 1] = 0.5
    for name in ("certified", "float", "filter"):
        with pytest.raises(NonFiniteError):
            smallness_codes(np.stack([E, nan]), Q, mode=name)
        with pytest.raises(NotSymmetricError):
            smallness_codes(asym, Q, mode=name)
        with pytest.raises(NotSymmetricError):
            smallness_codes(E, asym * 9, mode=name)


def test_exact_entries_that_round_to_zero():
    """An exact entry below the binary64 range rounds to 0: its rounding is no relative
    perturbation, so the filter leaves the matrix to the exact stages."""
    tiny = Fraction(1, 10**400)
    e = Quadric.sphere(1)
    q = Quadric.from_coefficients([[1, 0, 0], [0, 1, 0], [0, 0, tiny]], [0, 0, 0], -4)  # an ellipsoid
    assert q.kind is K.ELLIPSOID
    code = scalar_code(e, q)
    assert code == C.NOT_SMALL  # its third semi-axis is 2 * 10^200
    assert smallness_codes(e, q, mode="filter") in (C.UNCERTAIN, code)
    assert smallness_codes(e, q) == code


def test_stage_counts_add_up():
    rng = np.random.default_rng(2)
    Es = random_ellipsoids(rng, 50, 0.5, 2, 3)
    sphere = Quadric.sphere(2)
    Es[:3] = sphere.to_numpy(float)  # three ties: left to the later stages
    mode = CertifiedMode()
    smallness_codes(Es, sphere.to_numpy(float), mode=mode)
    assert mode.last.total == 50 and mode.last.undecided == 0
    assert mode.last.decided["smallness (filter)"] <= 47 and mode.last.escalated >= 3
    smallness_codes(Es[:10], sphere.to_numpy(float), mode=mode)
    assert mode.counts.total == 60
    for name in ("filter", "ball", "float", "mpmath", "exact"):
        m = get_mode(name)
        codes = smallness_codes(Es[:8], sphere.to_numpy(float), mode=m)
        assert m.last.total == 8
        assert m.last.undecided == int(np.count_nonzero(codes == UNC))


# -- the filter's bounds against exact values ---------------------------------------------------


def exact_primitives(M, kind):
    """The primitives of smallness_tables of a matrix with its canonical sign, exactly (as
    quantity.Quantity: eigenvalues are real algebraic numbers)."""
    q = Quadric.from_matrix(M) if isinstance(M, np.ndarray) else M
    if kind is K.ELLIPSOID and q.kind is K.ELLIPSOID:
        q = q if q.canonical_sign > 0 else -q
    inv = invariants(q)
    from quadric_contact.model.classification import principal_minor_sums_4

    _, E2, E3, E4 = principal_minor_sums_4(q.upper)
    values = [E4, inv.det00, inv.J, E3, E2, inv.trace]
    signs = kind_signs(kind)
    out = [Quantity.of(abs(Fraction(v))) for v in values]
    for i, m in enumerate(inv.eigenvalues):
        out.append(Quantity.of(m) * signs[6 + i] if signs[6 + i] else Quantity.of(1))
    return out


def inside(lo, hi, x: Quantity) -> bool:
    below = compare_quantities(Quantity.of(Fraction(lo)), x)
    return below <= 0 <= compare_quantities(Quantity.of(Fraction(hi)), x)


@pytest.mark.parametrize("seed", range(3))
def test_ellipsoid_sides_enclose_the_exact_values(seed):
    rng = np.random.default_rng(seed)
    Es = random_ellipsoids(rng, 8, 0.2, 3, 5)
    Es[0] = Quadric.sphere(Fraction(3, 4), center=(1, 2, 3)).to_numpy(float)
    Es[1] = Quadric.ellipsoid(2, 2, Fraction(1, 2)).rotated((1, 2, 3, 4)).to_numpy(float)  # a spheroid
    Es[2] *= -1
    status, values = sf.e_row_quantities(as_stack(Es, "E"), None, certify=True)
    assert (status == 0).all()
    for k, M in enumerate(Es):
        prim = exact_primitives(M, K.ELLIPSOID)
        for slot, mono in enumerate(E_SIDES):
            lo, hi = values[2 * slot, k], values[2 * slot + 1, k]
            assert lo <= hi and inside(lo, hi, evaluate(prim, mono)), (k, slot)
            assert hi - lo <= 1e-4 * hi  # and narrow


@pytest.mark.parametrize("kind", TABLE_1_KINDS)
def test_quadric_sides_enclose_the_exact_values(kind):
    """Binary64 input of each type (axis-aligned, a dyadic translation and a signed permutation:
    the type survives) and exact input (a rational rotation, rounded for the filter: the
    enclosures of the rounded matrix widened by Weyl's inequality)."""
    from quadric_contact.modes.facts import exact_facts

    params = dict(zip("abc", (Fraction(5, 2), Fraction(7, 4), Fraction(3, 4)), strict=False))
    std = Quadric.standard(kind, **{k: params[k] for k in Quadric.standard_parameters(kind)})
    flip = RigidMotion.from_quaternion(1, 1, 1, 1, (Fraction(1, 2), Fraction(-3, 4), 2))
    exact = [
        std.moved(RigidMotion.from_quaternion(*q, (Fraction(1, 3), 0, -1)))
        for q in ((1, 2, 0, 1), (3, 1, 1, 2))
    ]
    for stack in (as_stack([std.moved(flip), -std.moved(flip)], "Q"), as_stack([exact[0], -exact[1]], "Q")):
        rows = np.arange(2)
        kinds, signs = table_kinds(exact_facts(stack, rows)[1])
        assert (kinds == TABLE_1_KINDS.index(kind)).all()
        status, values = sf.q_row_quantities(stack, rows, kinds, signs, certify=True)
        assert (status == 0).all(), status
        for k in rows:
            q = (
                Quadric._from_upper(tuple(stack.exact[k]))
                if stack.exact is not None
                else Quadric.from_matrix(stack.floats[k])
            )
            prim = exact_primitives(q if q.canonical_sign > 0 else -q, kind)
            for slot, mono in enumerate(Q_SIDES[kind]):
                lo, hi = values[2 * slot, k], values[2 * slot + 1, k]
                assert inside(lo, hi, evaluate(prim, mono)), (kind, k, slot)
                assert hi - lo <= 1e-4 * hi


@settings(max_examples=20)
@given(st.sampled_from(TABLE_1_KINDS), st.data())
def test_tables_are_the_scalar_conditions(kind, data):
    """The monomials of smallness_tables, evaluated exactly, are the squared sides the scalar
    decision compares, condition by condition (Table 2 after a rigid motion, either sign)."""
    e = data.draw(signed_ellipsoids())
    q = data.draw(quadrics(kind))
    r = smallness(e, q)
    ep = exact_primitives(e.as_ellipsoid(), K.ELLIPSOID)
    qq = q if q.canonical_sign > 0 else -q
    qp = exact_primitives(qq, kind)
    inner, outer = TABLE_CONDITIONS[kind]
    if kind is K.HYPERBOLIC_PARABOLOID:
        # one printed condition on max|mu| (the smaller of a, b), two conjuncts in the table
        (c,) = r.conditions
        (q0, e0, rel0), (q1, e1, rel1) = inner
        assert e0 == e1 and rel0 == rel1 == 1 and c.relation == "<="
        v0, v1 = (evaluate(qp, Q_SIDES[kind][s]) for s in (q0, q1))
        assert compare_quantities(v0 if compare_quantities(v0, v1) >= 0 else v1, c.lhs_squared) == 0
        assert compare_quantities(evaluate(ep, E_SIDES[e0]), c.rhs_squared) == 0
        return
    for conds, reported in ((inner, r.conditions), (outer, r.alternative)):
        assert len(conds) == len(reported)
        for (qs, es, rel), c in zip(conds, reported, strict=True):
            qv, ev = evaluate(qp, Q_SIDES[kind][qs]), evaluate(ep, E_SIDES[es])
            sides = (qv, ev) if c.source != "enclosing" else (ev, qv)
            assert compare_quantities(sides[0], c.lhs_squared) == 0
            assert compare_quantities(sides[1], c.rhs_squared) == 0
            assert (rel == 0) == (c.relation == (">=" if c.source != "enclosing" else "<="))
    assert len(qp) == NPRIM


def test_shift_program_and_its_magnitude_companion():
    """The eigenvalue counts' program: its magnitude companion is what codegen emits for it,
    and its values are the trace, J and determinant (checked with sympy)."""
    import sympy

    from quadric_contact.exact.straight_line import emit_magnitude_function

    fdef = ast.parse(inspect.getsource(sf.shift_invariants)).body[0]
    emitted = ast.parse("\n".join(emit_magnitude_function(fdef))).body[0]
    mine = ast.parse(inspect.getsource(sf.shift_invariants_magnitude)).body[0]
    strip = lambda f: [ast.dump(s) for s in f.body[1:]]  # noqa: E731 - without the docstrings
    assert strip(emitted) == strip(mine)
    b = sympy.symbols("b00 b01 b02 b11 b12 b22")
    B = sympy.Matrix([[b[0], b[1], b[2]], [b[1], b[3], b[4]], [b[2], b[4], b[5]]])
    t = sympy.Symbol("t")
    cp = sympy.Poly((t * sympy.eye(3) - B).det(), t).all_coeffs()
    tr, J, det = sf.shift_invariants(*b)
    assert sympy.expand(tr + cp[1]) == 0 and sympy.expand(J - cp[2]) == 0 and sympy.expand(det + cp[3]) == 0
    assert all(k > 0 for k in sf.SHIFT_ERRBOUND)


def test_eigenvalue_approximations():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(2000, 3, 3))
    A = A + np.swapaxes(A, 1, 2)
    A[:5] = np.diag([2.0, 2.0, 2.0])  # a sphere
    A[5:10] = np.diag([1.0, 3.0, 3.0])  # spheroids
    ref = np.linalg.eigvalsh(A)
    got = np.stack(
        sf.eigen_approx(A[:, 0, 0], A[:, 0, 1], A[:, 0, 2], A[:, 1, 1], A[:, 1, 2], A[:, 2, 2]), axis=1
    )
    scale = np.abs(ref).max(axis=1, keepdims=True)
    assert (np.abs(got - ref) <= 1e-9 * scale).all()
    x = np.linspace(0, 0.5, 1001)
    assert np.abs(sf._horner(sf.H_COEFFS, 4 * x - 1) - sf._h(x)).max() < 1e-11
    assert np.abs(sf._horner(sf.G_COEFFS, 4 * x - 1) - sf._g(x)).max() < 1e-11


def test_chain_constants():
    u = Fraction(1, 2**53)
    for k in range(len(sf.CHAIN_DOWN)):
        assert Fraction(sf.CHAIN_DOWN[k]) * (1 + u) <= (1 - u) ** (2 * k) and sf.CHAIN_DOWN[k] < 1
        assert Fraction(sf.CHAIN_UP[k]) >= (1 - u) ** -(2 * k + 1) and sf.CHAIN_UP[k] > 1


@pytest.mark.parametrize("kind", TABLE_1_KINDS)
def test_filter_is_never_wrong_near_the_boundary(kind):
    """Binary64 pairs with the ellipsoid at ``1 + d`` times the largest scale Table 1 allows
    (``d`` from 1e-4 down to 0, plus the rounding of the scale), rotated and moved in floating
    point (smallness depends on its semi-axes only) against the standard quadric: the filter
    answers only where it is right, the cascade always right."""
    rng = np.random.default_rng(100 + TABLE_1_KINDS.index(kind))
    Es, Qs, distinct = [], [], []
    for d in (1e-4, -1e-4, 1e-7, -1e-7, 1e-10, -1e-10, 1e-13, 0.0):
        ps = [Fraction(int(rng.integers(4, 40)), 8) for _ in Quadric.standard_parameters(kind)]
        n = ORDERED.get(kind, 0)
        p = dict(zip("abc", sorted(ps[:n], reverse=True) + ps[n:], strict=False))
        shape = tuple(sorted((Fraction(int(rng.integers(2, 24)), 8) for _ in range(3)), reverse=True))
        distinct.append(len(set(shape)) == 3)
        s = max_scale(kind, p, shape)
        axes = np.array([float(s * v) for v in shape]) * (1 + d)
        R = quaternion_matrix(_unit(rng.normal(size=4)))
        A = R @ np.diag(1 / axes**2) @ R.T
        A = (A + A.T) / 2
        c = rng.uniform(-3, 3, size=3)
        M = np.zeros((4, 4))
        M[:3, :3] = A
        M[:3, 3] = M[3, :3] = -A @ c
        M[3, 3] = c @ A @ c - 1
        Es.append(M)
        Qs.append(Quadric.standard(kind, **p).to_numpy(float))  # dyadic: exactly of its kind
    Es, Qs = np.stack(Es), np.stack(Qs)
    ref = np.array(
        [scalar_code(Quadric.from_matrix(e), Quadric.from_matrix(q)) for e, q in zip(Es, Qs, strict=True)]
    )
    got = smallness_codes(Es, Qs, mode="filter")
    sure = got != UNC
    assert np.array_equal(got[sure], ref[sure]), (got, ref)
    assert np.array_equal(smallness_codes(Es, Qs), ref)
    assert sure[:2].all()  # 1e-4 is far from the boundary for the filter
    # 1e-7 is within the first enclosures' width; the second, tight try separates it when the
    # ellipsoid's eigenvalues are simple
    assert all(sure[k] for k in (2, 3) if distinct[k])


def test_shifted_signs_are_exact_where_certain():
    """The certified signs of ``(tr, J, det)`` of ``A - t I`` at points ``t`` next to the
    eigenvalues (where they cancel most), against exact rational arithmetic."""
    rng = np.random.default_rng(4)
    checked = 0
    for k in range(300):
        lam = rng.uniform(0.2, 5, size=3)
        if k % 3 == 0:
            lam[1] = lam[0]  # spheroids
        if k % 7 == 0:
            lam[:] = lam[0]  # spheres
        R = quaternion_matrix(_unit(rng.normal(size=4)))
        A = R @ np.diag(lam) @ R.T
        A = (A + A.T) / 2
        a = [A[0, 0], A[0, 1], A[0, 2], A[1, 1], A[1, 2], A[2, 2]]
        fa = [Fraction(v) for v in a]
        for target in lam:
            for rel in (0.0, 1e-15, -1e-15, 1e-12, -1e-9, 1e-6):
                t = float(target * (1 + rel))
                signs = sf._shift_signs(*a, t)
                ft = Fraction(t)
                b = (fa[0] - ft, fa[1], fa[2], fa[3] - ft, fa[4], fa[5] - ft)
                exact = [(v > 0) - (v < 0) for v in sf.shift_invariants(*b)]
                for s, x in zip(signs, exact, strict=True):
                    if s != UNC:
                        assert s == x, (k, rel, signs, exact)
                        checked += 1
    assert checked > 1000


def test_a_pairs_filter_code_does_not_depend_on_its_place_in_the_stack():
    """Rounded cylinders, cones and paraboloids (their exact zero eigenvalue rounded off), each
    distinct: the filter refines every one the binary64 stage leaves, so a pair's code in a
    long stack is its code alone (it used to give up after the 64th), and never wrong."""
    from quadric_contact import smallness
    from quadric_contact.testing.samples import SAMPLE_KINDS, random_pairs

    kinds = tuple(k for k in SAMPLE_KINDS if k.name.endswith(("CYLINDER", "PARABOLOID", "CONE")))
    E, Q, _ = random_pairs(100, np.random.default_rng(3), kinds=kinds)
    stack = smallness(E, Q, mode="filter")
    alone = np.array([smallness(E[i : i + 1], Q[i : i + 1], mode="filter")[0] for i in range(len(E))])
    exact = smallness(E, Q, mode="exact")
    assert (stack == alone).all()
    certain = stack != int(SmallnessCode.UNCERTAIN)
    assert (stack[certain] == exact[certain]).all()
    assert certain.sum() >= 0.9 * len(E)
