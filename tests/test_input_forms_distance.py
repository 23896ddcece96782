"""``qc.distance`` and ``qc.contact_scale`` take every stack form the other array predicates
take, with one meaning: an object array of Fractions or Python ints is exact input, each pair
answered as the pair itself is (its enclosure in binary64); a packed stack is its unpacked
float64 matrices; batch shapes that do not broadcast are a ``ShapeError`` naming both."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact.modes.distances import FloatDistance, enclosure

F = Fraction


def _matrix(equation: str) -> np.ndarray:
    """The exact matrix of an equation, an object array of Fractions."""
    return qc.Quadric.from_equation(equation).to_numpy(dtype=object)


# every entry a binary64 number: the float64 and packed forms hold the same pairs
APART = ("x**2 + 4*y**2 + 16*z**2 - 1", "(x - 4)**2 + y**2 + z**2 - 1")  # an ellipsoid, a sphere
PLANE = ("x**2 + 4*y**2 + 16*z**2 - 1", "x - 3")  # the ellipsoid inside the half-space x <= 3
CROSSING = ("(x - 1/2)**2 + y**2 + z**2 - 1/4", "x**2 + 4*y**2 + 16*z**2 - 1")  # a ball crossing
ELLIPSOIDS = ("x**2 + 4*y**2 + 16*z**2 - 1", "(x - 3/2)**2/4 + 4*y**2 + 4*z**2 - 1")  # crossing
THIRDS = ("9*(x - 1/3)**2 + 9*y**2 + 9*z**2 - 1", "x - 1")  # not binary64: exact input only

DYADIC = [APART, PLANE, CROSSING, ELLIPSOIDS]


def _fractions(pairs):
    E = np.array([_matrix(e) for e, _ in pairs], dtype=object)
    Q = np.array([_matrix(q) for _, q in pairs], dtype=object)
    assert E.dtype == object and E.shape == (len(pairs), 4, 4)
    assert all(isinstance(v, Fraction) for v in E.reshape(-1))
    return E, Q


def _ints(pairs):
    """The same quadrics as integer matrices (each matrix times the lcm of its denominators),
    an object array of Python ints."""

    def scaled(m):
        d = int(np.lcm.reduce([v.denominator for v in m.reshape(-1)]))
        return np.array([[int(v * d) for v in row] for row in m], dtype=object)

    E, Q = _fractions(pairs)
    Ei = np.array([scaled(m) for m in E], dtype=object)
    Qi = np.array([scaled(m) for m in Q], dtype=object)
    assert all(type(v) is int for v in Ei.reshape(-1))
    return Ei, Qi


def _packed(pairs):
    E, Q = _fractions(pairs)
    Ef, Qf = E.astype(np.float64), Q.astype(np.float64)
    assert all(F(float(v)) == v for v in E.reshape(-1)) and all(F(float(v)) == v for v in Q.reshape(-1))
    return qc.Packed(qc.pack(Ef)), qc.Packed(qc.pack(Qf))


def _scalar(function, e, q, **options):
    """The scalar answer for one pair as a value and bounds: ``(value or None, lo, hi)`` with
    ``lo <= true value <= hi`` as Fractions; or the error class it raised."""
    try:
        r = function(e, q, **options)
    except qc.QuadricContactError as exc:
        return type(exc)
    if isinstance(r, qc.ContactScaleResult):
        return r.scale, *(F(v) for v in enclosure(r.scale))
    if isinstance(r, qc.DistanceResult):
        return r.distance, *(F(v) for v in enclosure(r.distance))
    if isinstance(r, FloatDistance):
        assert not r.uncertain
        return r, *(F(v) for v in r.bounds)
    lo, hi = r.bounds  # a DistanceEnclosure: arb balls
    return r, F(lo), F(hi)


def _check_stack(function, form, pairs, **options):
    """The stack of ``pairs`` in ``form`` answers each pair as the scalar call does: the same
    error, or an enclosure overlapping the scalar one and holding the exact value where there
    is one, narrow; for exact input in the exact and float modes, the scalar call's own
    binary64 bounds."""
    E, Q = form(pairs)
    one_by_one = zip(*(qc.unpack(v.array) if isinstance(v, qc.Packed) else v for v in (E, Q)), strict=True)
    answers = [_scalar(function, e, q, **options) for e, q in one_by_one]
    errors = [a for a in answers if isinstance(a, type)]
    if errors:
        with pytest.raises(errors[0]):
            function(E, Q, **options)
        return
    got = function(E, Q, **options)
    assert got.shape == (len(pairs), 2) and got.dtype == np.float64
    for (lo, hi), (value, slo, shi) in zip(got, answers, strict=True):
        assert lo <= hi and hi - lo <= 1e-9 * max(1.0, abs(hi)), (lo, hi)
        assert F(lo) <= shi and slo <= F(hi), ((lo, hi), (slo, shi))  # both hold the value
        if isinstance(value, qc.RealAlgebraic):
            assert value.compare(F(lo)) >= 0 and value.compare(F(hi)) <= 0
        exact_input = form is not _packed
        if exact_input and (isinstance(value, qc.RealAlgebraic) or options.get("mode") == "float"):
            assert (F(lo), F(hi)) == (slo, shi)  # the scalar path, pair by pair


def _exact_values(function, pairs, **options):
    """The exact value of each pair (the ``exact`` mode), where the exact path gives one."""
    out = []
    for e, q in pairs:
        try:
            r = function(e, q, mode="exact", **options)
        except qc.UndecidedError:
            out.append(None)
            continue
        out.append(r.scale if isinstance(r, qc.ContactScaleResult) else r.distance)
    return out


@pytest.mark.parametrize("form", [_fractions, _ints, _packed], ids=["fractions", "ints", "packed"])
@pytest.mark.parametrize("mode", ["certified", "exact", "float"])
def test_distance_of_every_stack_form_is_the_scalar_answer(form, mode):
    pairs = [*DYADIC, THIRDS] if form is not _packed else DYADIC
    _check_stack(qc.distance, form, pairs, mode=mode)


@pytest.mark.parametrize("form", [_fractions, _ints, _packed], ids=["fractions", "ints", "packed"])
@pytest.mark.parametrize("mode", ["certified", "exact"])
def test_contact_scale_of_every_stack_form_is_the_scalar_answer(form, mode):
    pairs = [*DYADIC, THIRDS] if form is not _packed else DYADIC
    _check_stack(qc.contact_scale, form, pairs, mode=mode)


def test_the_exact_pairs_hold_their_exact_values_in_every_form():
    """Where the exact path answers, every form's enclosure holds that exact value (the ball
    crossing the ellipsoid, the ellipsoid against the plane, the sphere of radius 1/3)."""
    values = _exact_values(qc.distance, [PLANE, CROSSING, THIRDS])
    assert values[1].sign() < 0 and values[0] == -4 and values[2] == -1
    for form, pairs, vals in (
        (_fractions, [PLANE, CROSSING, THIRDS], values),
        (_ints, [PLANE, CROSSING, THIRDS], values),
        (_packed, [PLANE, CROSSING], values[:2]),
    ):
        E, Q = form(pairs)
        for mode in ("certified", "exact", "float"):
            for (lo, hi), v in zip(qc.distance(E, Q, mode=mode), vals, strict=True):
                assert v.compare(F(lo)) >= 0 and v.compare(F(hi)) <= 0, (form, mode)


def test_packed_stacks_broadcast_against_one_matrix_and_both_scales():
    E, Q = _packed([APART, ELLIPSOIDS])
    one = _fractions([APART])[1][0].astype(np.float64)
    got = qc.distance(E, one)
    want = qc.distance(qc.unpack(E.array), one)
    assert got.shape == (2, 2) and (got == want).all()
    both = qc.contact_scale(E, Q, scale="both")
    assert (both == qc.contact_scale(qc.unpack(E.array), qc.unpack(Q.array), scale="both")).all()
    s = qc.contact_scale(APART[0], APART[1], scale="both").scale
    assert s.compare(F(both[0, 0])) >= 0 and s.compare(F(both[0, 1])) <= 0


def test_exact_stacks_broadcast_as_numpy_does():
    """Two spheres (exact input) against a plane and an ellipsoid: ``(2, 1)`` against
    ``(1, 2)`` stacks give the ``(2, 2)`` grid of the scalar answers."""
    E, Q = _fractions([CROSSING, THIRDS])
    _, Q = _fractions([PLANE, CROSSING])
    grid = qc.distance(E[:, None], Q[None, :], mode="exact")
    assert grid.shape == (2, 2, 2)
    for i in range(2):
        for j in range(2):
            want = qc.distance(E[i], Q[j], mode="exact").distance
            assert (grid[i, j] == enclosure(want)).all()
    scales = qc.contact_scale(E[:, None], list(Q))  # a list of exact matrices: batch (2,)
    assert scales.shape == (2, 2, 2)
    assert (scales[1, 0] == enclosure(qc.contact_scale(E[1], Q[0]).scale)).all()


@pytest.mark.parametrize("function", [qc.distance, qc.contact_scale])
@pytest.mark.parametrize(
    "form",
    [
        lambda m: m,
        lambda m: m.astype(object),
        lambda m: qc.Packed(qc.pack(m)),
        lambda m: list(m),
    ],
    ids=["float64", "object", "packed", "list"],
)
def test_stacks_that_do_not_broadcast_are_a_shape_error_naming_both(function, form):
    E = np.repeat(np.diag([1.0, 1.0, 1.0, -1.0])[None], 3, axis=0)
    Q = np.repeat(np.diag([1.0, 1.0, 1.0, -1.0])[None], 2, axis=0)
    Q[:, 0, 3] = Q[:, 3, 0] = -4.0
    Q[:, 3, 3] = 15.0
    with pytest.raises(qc.ShapeError, match=r"\(3,\) of E and \(2,\) of Q") as info:
        function(form(E), form(Q), mode="exact")
    with pytest.raises(qc.ShapeError, match=r"\(3,\) of E and \(2,\) of Q"):
        qc.transversal_contact(form(E), form(Q))  # the same error as the other predicates
    assert info.value.value == ((3,), (2,))


def test_a_stack_that_is_not_of_4x4_matrices_is_a_shape_error():
    bad = np.zeros((2, 3, 3), dtype=object)
    with pytest.raises(qc.ShapeError, match="E must have shape"):
        qc.distance(bad, "x - 3", mode="exact")
    with pytest.raises(qc.ShapeError, match="Q must have shape"):
        qc.contact_scale("x**2 + y**2 + z**2 - 1", np.zeros((2, 4, 5)))


def test_a_dask_stack_is_read_as_its_array():
    da = pytest.importorskip("dask.array")
    E, Q = _fractions([APART, PLANE])
    Ef, Qf = E.astype(np.float64), Q.astype(np.float64)
    lazy = da.from_array(Ef, chunks=(1, 4, 4))
    assert (qc.distance(lazy, Qf) == qc.distance(Ef, Qf)).all()
    assert (qc.contact_scale(lazy, Qf[1]) == qc.contact_scale(Ef, Qf[1])).all()


HYPERBOLOID = "x**2 + y**2 - z**2 - 1"


@pytest.mark.parametrize("form", ["float64", "fractions", "equations"])
@pytest.mark.parametrize("mode", ["certified", "exact", "float"])
def test_a_pair_the_scalar_path_refuses_is_named_by_its_place_in_the_stack(form, mode):
    """The pairs a stack answers one by one raise what the pair raises alone (the same class,
    value and details), naming where it sits in the stack: ``index`` is its flat position."""
    es = [APART[1], HYPERBOLOID, PLANE[0]]  # a sphere, then a hyperboloid, then an ellipsoid
    qs = [APART[0], APART[0], PLANE[1]]
    if form == "equations":
        E, Q = es, qs
    else:
        E = np.array([_matrix(e) for e in es], dtype=object)
        Q = np.array([_matrix(q) for q in qs], dtype=object)
        if form == "float64":
            E, Q = E.astype(float), Q.astype(float)
    with pytest.raises(qc.NotAnEllipsoidError) as alone:
        qc.distance(HYPERBOLOID, APART[0], mode=mode)
    with pytest.raises(qc.NotAnEllipsoidError, match=r"^the pair at \[1\]: ") as info:
        qc.distance(E, Q, mode=mode)
    assert str(info.value).endswith(str(alone.value))
    assert info.value.details == {**alone.value.details, "index": 1}
    if mode != "float":
        with pytest.raises(qc.NotAnEllipsoidError, match=r"^the pair at \[1\]: ") as info:
            qc.contact_scale(E, Q, mode=mode)
        assert info.value.details["index"] == 1


def test_the_place_of_a_pair_in_a_stack_of_two_axes_is_its_multi_index():
    E = np.array([[_matrix(APART[0]), _matrix(HYPERBOLOID)]] * 2, dtype=object).astype(float)
    with pytest.raises(qc.NotAnEllipsoidError, match=r"^the pair at \[0, 1\]: ") as info:
        qc.distance(E, _matrix(APART[1]).astype(float))
    assert info.value.details["index"] == 1
