"""The certified distance of an ellipsoid from a convex solid cut by planes
(:mod:`quadric_contact.modes.distance.pieces`): closed forms derived here, an independent
brute-force minimiser at 40 digits on random pairs of every convex type with 1 to 3 planes, the
support functions against points of the solids, and the refusals."""

from __future__ import annotations

import itertools
import math
from fractions import Fraction as F

import mpmath
import numpy as np
import pytest
from proofs._cut_pieces import brute, diag, moved, rotation, standard

from quadric_contact.exact.errors import (
    ExcludedQuadricError,
    NotAnEllipsoidError,
    NotAPlaneError,
    QuadricContactError,
    UndecidedError,
    WorkLimitError,
)
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.quadric import Quadric
from quadric_contact.modes.distance.pieces import (
    MAX_DIGITS,
    ConvexSolid,
    CutPieceDistance,
    HalfSpace,
    cut_piece_distance,
    half_space,
    union_distance,
)
from quadric_contact.theory.overlap import solid_of

BALL2 = "x^2 + y^2 + z^2 - 4"


def _contains(r, value, slack=0.0):
    lo, hi = r.bounds
    return float(lo) - slack <= value <= float(hi) + slack


# -- closed forms ------------------------------------------------------------------------------


def test_nearest_point_on_the_rim_of_the_cut_disc():
    # The unit ball at c = (0, 0, 4) and the ball of radius 2 cut to x >= 1.  The projection
    # (1, 0, 4) of c on the plane x = 1 is outside the face's disc y^2 + z^2 <= 3, so the nearest
    # point of the piece is on the rim: p = (1, 0, sqrt 3), where c - p = (-1, 0, 4 - sqrt 3)
    # = a (1, 0, sqrt 3) + b (-1, 0, 0) (the sphere's outward normal and the face's) with
    # a = (4 - sqrt 3) / sqrt 3 > 0 and b = a + 1 > 0: in the normal cone, so d = |c - p| - 1.
    r = cut_piece_distance("x^2 + y^2 + (z - 4)^2 - 1", BALL2, [("x - 1", "R+")], digits=30)
    lo, hi = r.bounds
    with mpmath.workdps(60):
        expected = mpmath.sqrt(1 + (4 - mpmath.sqrt(3)) ** 2) - 1
        assert (
            mpmath.mpf(lo.numerator) / lo.denominator <= expected <= mpmath.mpf(hi.numerator) / hi.denominator
        )
    assert (hi - lo) <= lo / 10**30 and r.method == "cut piece" and isinstance(r, CutPieceDistance)
    # the two exact points of the upper bound are in the solids
    x, y = r.near_E, r.near_P
    assert x[0] ** 2 + x[1] ** 2 + (x[2] - 4) ** 2 <= 1 and sum(v * v for v in y) <= 4 and y[0] >= 1
    assert sum((a - b) ** 2 for a, b in zip(x, y, strict=True)) <= hi**2


def test_nearest_point_on_the_flat_face():
    # The unit ball centred at (1/2, 0, 3) and the half ball z <= 0 of radius 2: the centre
    # projects onto the plane at (1/2, 0, 0), inside the disc, with c - p along the face's
    # normal (0, 0, 1): d = 3 - 1 = 2.
    r = cut_piece_distance("(x - 1/2)^2 + y^2 + (z - 3)^2 - 1", BALL2, [("z", "R-")])
    assert _contains(r, 2.0)
    lo, hi = r.bounds
    assert lo <= 2 <= hi and hi - lo <= lo / 10**15


def test_nearest_point_on_the_curved_surface():
    # The unit ball at (0, 0, -5) below the half ball z <= 0 of radius 2: the nearest point
    # (0, 0, -2) of the whole ball is in the kept half, so d = 5 - 2 - 1 = 2; the other half
    # (z >= 0) is nearest at its flat face's centre, d = 5 - 1 = 4.
    below = cut_piece_distance("x^2 + y^2 + (z + 5)^2 - 1", BALL2, [("z", "R-")])
    above = cut_piece_distance("x^2 + y^2 + (z + 5)^2 - 1", BALL2, [("z", "R+")])
    assert below.bounds[0] <= 2 <= below.bounds[1] and above.bounds[0] <= 4 <= above.bounds[1]


def test_a_half_space_cut_by_a_plane_is_a_wedge():
    # The solid z <= 0 cut by x <= 0 (a wedge with edge the y axis) and the unit ball at
    # (3, 0, 4): the nearest point of the wedge to the centre is on the edge, (0, 0, 0)
    # (c - 0 = (3, 0, 4) = 3 (1, 0, 0) + 4 (0, 0, 1), both normals with positive weights),
    # so d = 5 - 1 = 4.
    r = cut_piece_distance("(x - 3)^2 + y^2 + (z - 4)^2 - 1", "z", [("x", "R-")])
    assert r.bounds[0] <= 4 <= r.bounds[1]


def test_the_union_of_two_parts_is_the_nearer():
    # the ball of radius 2 cut to x >= 1 (rim distance sqrt(1 + (4 - sqrt 3)^2) - 1, above) and
    # to z <= -1 (its face's centre (0, 0, -1), d = 5 - 1 = 4): the union is the nearer
    E = "x^2 + y^2 + (z - 4)^2 - 1"
    u = union_distance(E, BALL2, [[("z + 1", "R-")], [("x - 1", "R+")]])
    assert _contains(u, math.sqrt(1 + (4 - math.sqrt(3)) ** 2) - 1, 1e-15)
    # a part with no plane is the whole solid: the whole ball's distance 4 - 2 - 1
    w = union_distance(E, BALL2, [[("x - 1", "R+")], []])
    assert w.distance.contains(1)


def test_no_plane_is_the_whole_solid():
    r = cut_piece_distance("x^2 + y^2 + (z - 4)^2 - 1", BALL2, [])
    assert r.distance.contains(1)


# -- the sides of a plane ----------------------------------------------------------------------


def test_the_sides_of_a_plane_follow_the_sign_of_its_matrix():
    # R- is {X^T P X <= 0} for the matrix as given: for P = 2 z - 3, the point z = 0 is in R-
    for plane in ("2*z - 3", "3 - 2*z"):
        P = Quadric.from_equation(plane)
        at_origin = P[3, 3]  # X^T P X at X = (0, 0, 0, 1)
        inside = half_space(plane, "R-" if at_origin < 0 else "R+")
        outside = half_space(plane, "R+" if at_origin < 0 else "R-")
        origin = (F(0), F(0), F(0))
        assert inside.value(origin) < 0 < outside.value(origin)


# -- support functions against points of the solids --------------------------------------------

KINDS = {
    "ellipsoid": "x^2 + y^2/4 + z^2/9 - 1",
    "elliptic paraboloid": "x^2 + y^2/4 - z",
    "elliptic cylinder": "x^2 + y^2/4 - 1",
    "parabolic cylinder": "x^2 - z",
    "parallel planes": "z^2 - 1",
    "plane": "z - 1",
}


FREE = {"elliptic cylinder": (2,), "parabolic cylinder": (1,), "parallel planes": (0, 1), "plane": (0, 1)}
"""The coordinates along which the standard solids of ``KINDS`` are unbounded lines (their
maximisers of ``w . y`` are then not unique; those coordinates are pinned at 0)."""


def _exact(h):
    """The support value as a Fraction (an arb ball's midpoint, exactly)."""
    if isinstance(h, F):
        return h
    m, e = h.mid().man_exp()
    m, e = int(m), int(e)
    return F(m * 2**e) if e >= 0 else F(m, 2**-e)


@pytest.mark.parametrize("kind", list(KINDS))
def test_the_support_function_bounds_every_point_and_is_reached(kind):
    K = ConvexSolid(Quadric.from_equation(KINDS[kind]))
    assert K.kind.value == kind
    rng = np.random.default_rng(5)
    points = rng.uniform(-6, 6, (4000, 3))
    inside = [p for p in points if float(K.value([F(v) for v in p])) <= 0]
    assert inside
    tested = 0
    for _ in range(20):
        w = K.project([F(int(v)) for v in rng.integers(-4, 5, 3)])
        if not any(w):
            continue
        assert all(w[i] == 0 for i in FREE.get(kind, ()))  # finite only across the free lines
        with working_precision(200):  # (the sqrt of the curved kinds, enclosed tightly)
            h = _exact(K.support(w))
        # h(w) >= w . y for every sampled y of K ...
        assert max(float(np.dot([float(v) for v in w], p)) for p in inside) <= float(h) + 1e-9
        # ... and is reached: maximise w . y over K by Lagrange at 30 digits (a point of the
        # boundary where the gradient of the form is a positive multiple of w)
        assert _reached(K, w, h, FREE.get(kind, ()))
        tested += 1
    assert tested >= 5


def _reached(K, w, h, free):
    """Some point of ``K`` (its ``free`` coordinates 0) has ``w . y`` within ``1e-20`` of ``h``:
    Newton's method (mpmath's ``findroot``) on ``w = lambda grad Q_K(y)``, ``Q_K(y) = 0`` in the
    other coordinates, from a few starts, ``lambda > 0``."""
    live = [i for i in range(3) if i not in free]
    with mpmath.workdps(30):
        m = lambda v: mpmath.mpf(v.numerator) / v.denominator  # noqa: E731
        M = [[m(v) for v in row] for row in K.M]
        b = [m(v) for v in K.b]
        q = m(K.q)
        wv = [m(v) for v in w]
        hm = m(h)

        def point(z):
            y = [mpmath.mpf(0)] * 3
            for k, i in enumerate(live):
                y[i] = z[k]
            return y

        def system(*z):
            y, lam = point(z), z[-1]
            g = [2 * (sum(M[i][j] * y[j] for j in range(3)) + b[i]) for i in range(3)]
            form = sum(M[i][j] * y[i] * y[j] for i in range(3) for j in range(3)) + 2 * sum(
                b[i] * y[i] for i in range(3)
            )
            return [*(wv[i] - lam * g[i] for i in live), form + q]

        for start in itertools.product((-1.5, 0.5, 2.0), repeat=len(live)):
            try:
                sol = mpmath.findroot(system, (*start, 1.0))
            except (ZeroDivisionError, ValueError, TypeError):  # (a singular system; NaN pivots)
                continue
            y = point(list(sol)[:-1])
            if sol[len(live)] > 0 and abs(sum(wv[i] * y[i] for i in range(3)) - hm) < 1e-20 * (1 + abs(hm)):
                return True
    return False


# -- an independent brute force on random pairs ----------------------------------------------


def _instance(kind, planes, rng):
    """A random pair: K of the kind, rotated and moved exactly; ``planes`` planes through points
    near a point inside K (so the cut piece has interior points); an ellipsoid placed around."""
    S, p = standard(kind, rng)
    R, t = rotation(rng), [F(int(v), 4) for v in rng.integers(-4, 5, 3)]
    Kmat = moved(S, R, t)
    inner = [sum(R[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]
    hs = []
    for _ in range(planes):
        n = [F(int(v)) for v in rng.integers(-3, 4, 3)]
        if not any(n):
            n = [F(1), F(0), F(0)]
        offset = F(int(rng.integers(0, 4)), 8)
        hs.append(HalfSpace(tuple(n), sum(n[i] * inner[i] for i in range(3)) + offset))
    axes = [F(int(v), 10) for v in rng.integers(3, 13, 3)]
    ER, Ec = rotation(rng), [inner[i] + F(int(v), 2) for i, v in enumerate(rng.integers(-8, 9, 3))]
    Emat = moved(diag(1 / axes[0] ** 2, 1 / axes[1] ** 2, 1 / axes[2] ** 2, const=-1), ER, Ec)
    return Quadric.from_matrix(Emat), Quadric.from_matrix(Kmat), hs, [float(v) for v in inner]


def _in_solid(Q, p):
    S = solid_of(Q)
    X = (*p, F(1))
    return sum(S[i, j] * X[i] * X[j] for i in range(4) for j in range(4)) <= 0


def _check_random(kind, planes, seed, count):
    rng = np.random.default_rng(seed)
    done = 0
    tries = 0
    while done < count:
        tries += 1
        assert tries < 10 * count, "too few separated instances"
        E, K, hs, inner = _instance(kind, planes, rng)
        reference = brute(E, K, hs, inner)
        if reference is None:
            continue
        try:
            r = cut_piece_distance(E, K, hs, digits=20)
        except UndecidedError as exc:
            # refused as crossing or touching: its upper bound is the distance of two exact points
            # of the solids, checked here; below the sampling's 0.05 the pair was not apart
            x, y = exc.details["points"]
            assert _in_solid(E, x) and _in_solid(K, y) and all(h.value(y) <= 0 for h in hs)
            assert sum((a - b) ** 2 for a, b in zip(x, y, strict=True)) < F(1, 400), (str(exc), reference)
            continue
        lo, hi = r.bounds
        with mpmath.workdps(50):
            lo_m, hi_m = (mpmath.mpf(v.numerator) / v.denominator for v in (lo, hi))
            assert lo_m <= reference <= hi_m, (kind, planes, seed, float(lo), float(reference), float(hi))
        assert hi - lo <= lo / 10**20
        done += 1


@pytest.mark.parametrize("kind", list(KINDS))
def test_random_pairs_against_the_brute_force(kind):
    _check_random(kind, 1 + len(kind) % 3, seed=len(kind), count=1)


@pytest.mark.slow
@pytest.mark.parametrize("planes", [1, 2, 3])
@pytest.mark.parametrize("kind", list(KINDS))
def test_many_random_pairs_against_the_brute_force(kind, planes):
    _check_random(kind, planes, seed=100 * planes + len(kind), count=4)


# -- refusals ----------------------------------------------------------------------------------


def test_a_crossing_pair_is_refused():
    # the unit ball at (0, 0, 1) crosses the half ball z <= 0 of radius 2 (they share (0, 0, 0.5))
    with pytest.raises(UndecidedError, match=r"cross or touch.*depth into a cut piece is not computed"):
        cut_piece_distance("x^2 + y^2 + (z - 1)^2 - 1", BALL2, [("z", "R-")])
    # touching: the unit ball at (0, 0, 1) and the half-space z <= 0 cut by x <= 0
    with pytest.raises(UndecidedError, match="cross or touch"):
        cut_piece_distance("x^2 + y^2 + (z - 1)^2 - 1", "z", [("x", "R-")])


def test_a_solid_that_is_not_convex_is_refused():
    with pytest.raises(UndecidedError, match="not convex"):
        cut_piece_distance("x^2 + y^2 + (z - 9)^2 - 1", "x^2 + y^2 - z^2 - 1", [("z - 5", "R-")])
    with pytest.raises(UndecidedError, match="not convex"):
        cut_piece_distance("x^2 + y^2 + (z - 9)^2 - 1", "x^2 - y^2 - z", [("z - 5", "R-")])


def test_an_empty_or_flat_piece_is_refused():
    # z <= -3 misses the ball of radius 2; z <= 0 and z >= 0 leave a flat disc
    E = "x^2 + y^2 + (z - 9)^2 - 1"
    with pytest.raises(UndecidedError, match="no interior point"):
        cut_piece_distance(E, BALL2, [("z + 3", "R-")])
    with pytest.raises(UndecidedError, match="no interior point"):
        cut_piece_distance(E, BALL2, [("z", "R-"), ("z", "R+")])


def test_bad_input_raises_the_package_errors():
    E = "x^2 + y^2 + (z - 9)^2 - 1"
    with pytest.raises(NotAnEllipsoidError):
        cut_piece_distance("x^2 + y^2 - z^2 - 1", BALL2, [("z", "R-")])
    with pytest.raises(NotAPlaneError):
        cut_piece_distance(E, BALL2, [("z^2 - 1", "R-")])
    with pytest.raises(QuadricContactError, match="R- or R\\+"):
        cut_piece_distance(E, BALL2, [("z", "inside")])
    with pytest.raises(QuadricContactError, match="R- or R\\+"):
        cut_piece_distance(E, BALL2, [("z", "contact")])
    with pytest.raises(QuadricContactError, match="pair"):
        cut_piece_distance(E, BALL2, ["z"])
    with pytest.raises(QuadricContactError, match="n != 0"):
        cut_piece_distance(E, BALL2, [HalfSpace((F(0), F(0), F(0)), F(1))])
    with pytest.raises(QuadricContactError, match="digits"):
        cut_piece_distance(E, BALL2, [("z", "R-")], digits=0)
    with pytest.raises(WorkLimitError, match="MAX_DIGITS") as refused:
        cut_piece_distance(E, BALL2, [("z", "R-")], digits=MAX_DIGITS + 1)
    assert refused.value.details["limit"] == MAX_DIGITS
    assert cut_piece_distance(E, BALL2, [("z", "R-")], digits=MAX_DIGITS).distance > 0  # the bound is reached
    with pytest.raises(ExcludedQuadricError):
        cut_piece_distance(E, "x^2 + y^2 - z^2", [("z", "R-")])  # a cone has no solid
    with pytest.raises(QuadricContactError, match="at least one part"):
        union_distance(E, BALL2, [])
