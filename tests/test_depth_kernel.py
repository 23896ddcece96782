"""The compiled depth of crossing ellipsoids on stacks: every enclosure it gives holds the
value of the independent brute-force minimiser (:mod:`tests.brute_distance`) and is at most
``tol`` relative wide; the compiled kernel and its Python twin give the same bits; pairs that
are not two crossing ellipsoids are left to the scalar path; and most crossing pairs are
answered."""

from __future__ import annotations

import flint
import mpmath
import numpy as np
import pytest
from tests.brute_distance import _centred, minimise_on_sphere

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.exact.precision import working_precision
from quadric_contact.modes.distance.apart_kernel import separated_ellipsoids
from quadric_contact.modes.distance.depth_kernel import (
    _kernel,
    crossing_ellipsoids,
    crossing_ellipsoids_cells,
)
from quadric_contact.modes.kernels._jit import plain
from quadric_contact.modes.kernels.threads import single_threaded
from quadric_contact.testing.samples import ellipsoid_matrix as _ellipsoid
from quadric_contact.testing.samples import float_depth as _float_depth
from quadric_contact.testing.samples import random_rotations

# -- pairs ----------------------------------------------------------------------------------


def _rotation(rng):
    return random_rotations(1, rng)[0]


def _random(rng, spread=0.5, lo=0.3, hi=1.5):
    return tuple(
        _ellipsoid(rng.uniform(lo, hi, 3), _rotation(rng), rng.uniform(-spread, spread, 3)) for _ in "EK"
    )


def _deep(rng):
    return _random(rng, spread=0.05)


def _nearly_spherical(rng, flat=1e-3):
    r1, r2 = rng.uniform(0.5, 1.5, 2)
    return tuple(
        _ellipsoid(r * (1 + flat * rng.uniform(-1, 1, 3)), _rotation(rng), rng.uniform(-0.4, 0.4, 3) * r)
        for r in (r1, r2)
    )


def _elongated(rng, ratio=20.0):
    """Needles or plates crossing at their middles (``ratio``: longest over shortest axis)."""
    axes = np.array([1.0, ratio**-0.5, 1 / ratio])
    return tuple(
        _ellipsoid(axes * rng.uniform(0.8, 1.2, 3), _rotation(rng), rng.uniform(-0.02, 0.02, 3)) for _ in "EK"
    )


def _two_minima(rng, tilt=0.0):
    """Identical ellipsoids shifted along the longest axis: ``phi(u) = phi(R diag(1, 1, -1) R^T u)``,
    two equal minima; ``tilt`` perturbs the shift out of the symmetry plane, the two minima
    then differ a little."""
    axes = np.array([3.0, 1.0, 0.5]) * rng.uniform(0.8, 1.2)
    R = _rotation(rng)
    shift = R @ np.array([rng.uniform(0.2, 1.0), 0.0, tilt])
    return _ellipsoid(axes, R, np.zeros(3)), _ellipsoid(axes, R, shift)


def _mirrored(rng):
    """``K`` the mirror image of ``E`` in the plane ``x = 0``: two equal minima in general."""
    axes = rng.uniform(0.4, 1.5, 3)
    R = _rotation(rng)
    c = np.array([rng.uniform(0.1, 0.4), rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)])
    S = np.diag([-1.0, 1.0, 1.0])
    return _ellipsoid(axes, R, c), _ellipsoid(axes, S @ R @ S, S @ c)


def _shallow(rng, depth):
    """A crossing pair of depth about ``depth`` times the smallest semi-axis: a random pair
    moved along its minimiser ``u`` (moving ``K`` by ``t u`` lowers ``phi`` by ``t u . v``,
    at most ``t``, and by ``t`` at ``u``)."""
    while True:
        axes = rng.uniform(0.3, 1.5, (2, 3))
        E = _ellipsoid(axes[0], _rotation(rng), np.zeros(3))
        R2, c2 = _rotation(rng), rng.uniform(-0.5, 0.5, 3)
        d, u = _float_depth(E, _ellipsoid(axes[1], R2, c2))
        if d > 0:
            return E, _ellipsoid(axes[1], R2, c2 + (d - depth * axes.min()) * u)


def _stack(pairs):
    return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])


# -- the reference --------------------------------------------------------------------------


def _brute_depth(E, K, digits=25):
    """``min phi`` over the unit sphere by the tests' brute-force minimiser, at ``digits``
    digits, from the exact rational matrices."""
    with working_precision(dps=digits + 10):
        A1, c1, r1 = _centred(Quadric.from_matrix(E))
        A2, c2, r2 = _centred(Quadric.from_matrix(K))
        M1, M2, cd = r1 * A1**-1, r2 * A2**-1, c1 - c2

    def phi(u):
        return (u.T * cd)[0] + mpmath.sqrt((u.T * M1 * u)[0]) + mpmath.sqrt((u.T * M2 * u)[0])

    return minimise_on_sphere(phi, digits=digits, grid=24, polish=4)


def _check_against_brute(Es, Ks, tol, *, least=1):
    """Every accepted enclosure holds ``-min phi`` and is at most ``tol`` relative wide; at least
    ``least`` pairs are accepted.  Returns the number accepted."""
    enc, rest = crossing_ellipsoids(Es, Ks, tol)
    done = np.flatnonzero(~rest)
    assert len(done) >= least, (len(done), len(Es))
    lo, hi = enc[done, 0], enc[done, 1]
    assert np.all(lo <= hi) and np.all(hi < 0)
    assert np.all(hi - lo <= tol * np.abs(hi)), np.max((hi - lo) / np.abs(hi))
    for k in done:
        value = -_brute_depth(Es[k], Ks[k])
        assert mpmath.mpf(enc[k, 0]) <= value <= mpmath.mpf(enc[k, 1]), (k, enc[k], value)
    return len(done)


# -- (a) the enclosures hold the brute-force value ------------------------------------------


@pytest.mark.parametrize(
    ("make", "count", "least"),
    [
        (_random, 8, 8),
        (_deep, 4, 4),
        (_nearly_spherical, 4, 4),
        (lambda rng: _nearly_spherical(rng, 1e-9), 3, 3),
        (_elongated, 4, 3),
        (_two_minima, 4, 4),
        (lambda rng: _two_minima(rng, tilt=1e-9), 3, 3),
        (_mirrored, 4, 3),
    ],
    ids=[
        "random",
        "deep",
        "nearly-spherical",
        "spheres-to-1e-9",
        "elongated",
        "two-minima",
        "near-two-minima",
        "mirrored",
    ],
)
def test_enclosures_hold_the_brute_force_depth(make, count, least):
    rng = np.random.default_rng(count * 7 + least)
    Es, Ks = _stack([make(rng) for _ in range(count)])
    _check_against_brute(Es, Ks, 1e-12, least=least)


@pytest.mark.parametrize(("depth", "tol"), [(1e-3, 1e-9), (1e-5, 1e-7), (1e-8, 1e-4)])
def test_shallow_pairs_at_a_tolerance_they_allow(depth, tol):
    """A shallow pair's enclosure cannot be narrower than a few units in the last place of the
    ellipsoids' size: at ``1e-12`` relative such pairs go to the scalar path (never a wrong
    answer), at a coarser tolerance the kernel answers them."""
    rng = np.random.default_rng(int(-np.log10(depth)))
    Es, Ks = _stack([_shallow(rng, depth) for _ in range(3)])
    _check_against_brute(Es, Ks, tol, least=2)
    enc, rest = crossing_ellipsoids(Es, Ks)  # 1e-12: flagged, or right
    for k in np.flatnonzero(~rest):
        assert enc[k, 0] <= -_brute_depth(Es[k], Ks[k]) <= enc[k, 1]


def test_the_scalar_certified_path_agrees():
    rng = np.random.default_rng(11)
    Es, Ks = _stack([_random(rng) for _ in range(2)])
    enc, rest = crossing_ellipsoids(Es, Ks)
    assert not rest.any()
    for k in range(2):
        r = qc.distance(Quadric.from_matrix(Es[k]), Quadric.from_matrix(Ks[k]), digits=20)
        assert r.distance.overlaps(flint.arb(enc[k, 0]).union(flint.arb(enc[k, 1])))


@pytest.mark.slow
@pytest.mark.parametrize(
    "make", [_random, _deep, _nearly_spherical, _elongated, _two_minima, _mirrored], ids=lambda f: f.__name__
)
def test_enclosures_hold_the_brute_force_depth_exhaustively(make):
    rng = np.random.default_rng(2026)
    Es, Ks = _stack([make(rng) for _ in range(100)])
    _check_against_brute(Es, Ks, 1e-12, least=85)


# A pair (from the random pairs of benchmarks/bench_depth.py) whose two best starting directions
# lead Newton's method to a local minimum of phi about 0.7% above the least: the cells find the
# deeper one (a cell across the edge of the region below the target has a corner below it).
_MISSED = (
    np.array(
        [
            [4.138183158261705, -0.40294057831968744, 0.25723158047676853, 1.721690470456592],
            [-0.40294057831968744, 1.495736449549515, 1.1885504137318939, -0.7109886681249736],
            [0.25723158047676853, 1.1885504137318939, 2.9029070262629237, -0.6533153612857807],
            [1.721690470456592, -0.7109886681249736, -0.6533153612857807, -0.030551339057743654],
        ]
    ),
    np.array(
        [
            [7.7839234536758684e-01, -1.3632768112544205e-03, 7.5034861441887358e-03, 5.3343082258093803e-02],
            [-1.3632768112544205e-03, 2.0766417198808527e00, -2.1176507731822443e00, -6.6185733689949822e-01],
            [7.5034861441887358e-03, -2.1176507731822443e00, 3.5177346893632704e00, 6.6676549830834309e-01],
            [
                5.3343082258093803e-02,
                -6.6185733689949822e-01,
                6.6676549830834309e-01,
                -7.8540553238770228e-01,
            ],
        ]
    ),
)


def test_a_minimum_newtons_method_missed_is_found_by_the_cells():
    Es, Ks = _stack([_MISSED])
    _check_against_brute(Es, Ks, 1e-12, least=1)


# -- (b) the twin -----------------------------------------------------------------------------


def test_the_compiled_kernel_and_its_python_twin_give_the_same_bits():
    rng = np.random.default_rng(5)
    pairs = [
        _random(rng),
        _deep(rng),
        _nearly_spherical(rng),
        _elongated(rng),
        _two_minima(rng),
        _mirrored(rng),
        _MISSED,
    ]
    unit = _ellipsoid([1.0, 1.0, 1.0], np.eye(3), [0.0, 0.0, 0.0])
    pairs.append((unit, _ellipsoid([1.0, 1.0, 1.0], np.eye(3), [1.0, 0.0, 0.0])))  # covered only, below
    ball = _ellipsoid([1.0, 1.0, 1.0], np.eye(3), [0.1, 0.2, 0.3])
    pairs.append((ball, ball))  # phi constant: the budget runs out, the pair is left
    Es, Ks = _stack(pairs)
    n = len(Es)
    got = [
        (np.empty((n, 2)), np.empty(n, dtype=np.uint8), np.empty(n, dtype=np.int64), np.empty((n, 3)))
        for _ in range(2)
    ]
    cover = np.zeros((n, 5))
    cover[-2] = [1.0, 1.0, 0.0, 0.0, np.cos(0.1)]  # phi = 2 - u_x >= 1: a target and a cap
    _kernel(Es, Ks, 1e-12, cover, *got[0], 0, n)
    plain(_kernel)(Es, Ks, 1e-12, cover, *got[1], 0, n)
    for compiled, twin in zip(*got, strict=True):
        assert np.array_equal(compiled, twin, equal_nan=True)
    assert not got[0][1][:-1].any() and got[0][1][-1]
    assert np.array_equal(got[0][0][-2], [-1.0, -1.0])


# -- (c) what is left to the scalar path -------------------------------------------------------


def _ball(r, c):
    return _ellipsoid([r, r, r], np.eye(3), c)


def test_pairs_that_are_not_two_crossing_ellipsoids_are_left():
    unit = _ball(1.0, [0, 0, 0])
    hyperboloid = np.diag([1.0, 1.0, -1.0, -1.0])
    cylinder = np.diag([1.0, 1.0, 0.0, -1.0])
    imaginary = np.diag([1.0, 1.0, 1.0, 1.0])
    point = np.diag([1.0, 1.0, 1.0, 0.0])
    nan = unit.copy()
    nan[0, 3] = nan[3, 0] = np.nan
    inf = unit.copy()
    inf[1, 1] = np.inf
    huge = unit * 1e120
    others = [
        (unit, _ball(1.0, [3, 0, 0])),  # apart
        (unit, _ball(1.0, [2, 0, 0])),  # touching
        (unit, _ball(1.0, [2 - 2.0**-45, 0, 0])),  # crossing, too shallow for 1e-12
        (unit, unit),  # the same ball: phi constant, no cell small enough
        (unit, hyperboloid),
        (hyperboloid, unit),
        (unit, cylinder),
        (unit, imaginary),
        (unit, point),
        (unit, nan),
        (inf, unit),
        (huge, huge),
    ]
    Es, Ks = _stack(others)
    enc, rest = crossing_ellipsoids(Es, Ks)
    assert rest.all()
    assert np.all(enc[:, 0] == -np.inf) and np.all(enc[:, 1] == np.inf)


def test_either_sign_of_the_matrices():
    rng = np.random.default_rng(8)
    Es, Ks = _stack([_random(rng) for _ in range(6)])
    a, ra = crossing_ellipsoids(Es, Ks)
    b, rb = crossing_ellipsoids(-Es, -Ks)
    assert np.array_equal(ra, rb) and np.array_equal(a[~ra], b[~rb])


def test_closed_forms():
    """Two balls (depth ``r1 + r2 - |c1 - c2|``) and a ball concentric with an ellipsoid (depth
    ``r + c``, ``c`` the least semi-axis: two antipodal minima)."""
    Es, Ks = _stack(
        [
            (_ball(1.0, [0, 0, 0]), _ball(0.5, [0.375, 0.5, 0])),  # |c1 - c2| = 5/8
            (_ellipsoid([2.0, 1.0, 0.5], np.eye(3), [1, 2, 3]), _ball(0.25, [1, 2, 3])),
        ]
    )
    enc, rest = crossing_ellipsoids(Es, Ks)
    assert not rest.any()
    for k, depth in enumerate((1.5 - 0.625, 0.75)):
        assert enc[k, 0] <= -depth <= enc[k, 1]


# -- (d) most crossing pairs are answered ------------------------------------------------------


def test_most_random_crossing_pairs_are_answered():
    rng = np.random.default_rng(2)
    Es, Ks = _stack([_random(rng) for _ in range(400)])
    _, apart = separated_ellipsoids(Es, Ks)
    crossing = np.array([_float_depth(E, K)[0] > 0 for E, K in zip(Es, Ks, strict=True)]) & apart
    enc, rest, cells = crossing_ellipsoids_cells(Es, Ks)
    with single_threaded():  # the stack split between threads or not: the same answers
        alone = crossing_ellipsoids_cells(Es, Ks)
    assert all(np.array_equal(x, y) for x, y in zip((enc, rest, cells), alone, strict=True))
    assert crossing.sum() > 350
    assert (~rest[crossing]).mean() > 0.95
    assert np.all(rest[~crossing])  # apart or touching: never answered here
    assert np.median(cells[crossing]) < 1000


def test_the_stack_distance_uses_both_kernels():
    """A stack of separated, crossing and touching pairs: the kernels answer the first two, the
    scalar path the touching one, in the stack's shape."""
    rng = np.random.default_rng(4)
    crossing = _stack([_random(rng) for _ in range(3)])
    Es = np.concatenate([crossing[0], [_ball(1.0, [0, 0, 0]), _ball(1.0, [0, 0, 0])]])
    Ks = np.concatenate([crossing[1], [_ball(1.0, [4, 0, 0]), _ball(1.0, [2, 0, 0])]])
    got = qc.distance(Es.reshape(5, 1, 4, 4), Ks.reshape(5, 1, 4, 4))
    assert got.shape == (5, 1, 2)
    enc, _ = crossing_ellipsoids(*crossing)
    assert np.array_equal(got[:3, 0], enc)
    assert got[3, 0, 0] <= 2.0 <= got[3, 0, 1]
    assert got[4, 0, 0] <= 0.0 <= got[4, 0, 1]


def test_a_single_pair_in_float_mode_is_the_stack_of_one():
    """One meaning for both forms: ``mode="float"`` on one pair of binary64 ellipsoids answers
    with the enclosure the stack of one gives (the kernels'), crossing or apart: its value and
    error bound cover that enclosure and are no wider than its rounding needs."""
    rng = np.random.default_rng(12)
    Es, Ks = _stack([_random(rng) for _ in range(2)])
    Es = np.concatenate([Es, [_ellipsoid([1.0, 0.8, 0.6], np.eye(3), [0, 0, 0])]])
    Ks = np.concatenate([Ks, [_ball(0.5, [3, 0, 0])]])
    for k in range(3):
        f = qc.distance(Es[k], Ks[k], mode="float")
        ((lo, hi),) = qc.distance(Es[k][None], Ks[k][None], mode="float")
        assert not f.uncertain
        assert f.bounds[0] <= lo <= hi <= f.bounds[1]
        assert f.bounds[1] - f.bounds[0] <= (hi - lo) * (1 + 1e-12) + 4e-16 * abs(hi)
        c = qc.distance(Es[k], Ks[k], digits=20).distance
        assert c.overlaps(flint.arb(lo).union(flint.arb(hi)))
    assert qc.distance(Es[2], Ks[2], mode="float").distance == pytest.approx(1.5, rel=1e-12)
