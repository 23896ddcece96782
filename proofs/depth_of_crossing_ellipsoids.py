"""Depth of crossing ellipsoids: the signed distance of two crossing ellipsoids enclosed between a
support bound at one direction and a covering of the sphere by cells, each certified by one point
of the Minkowski difference.

Not a result of the paper: the certificate of :mod:`quadric_contact.modes.distance.depth_kernel`, on which
:func:`quadric_contact.distance` answers the crossing ellipsoid pairs of float64 stacks.  ``E`` and
``K`` are ellipsoids (solids), ``D = E + (-K)``, ``phi(u) = h_E(u) + h_K(-u)`` its support
function and ``depth = min over unit u of phi(u)``: when the interiors meet, ``0`` is inside
``D``, the depth is the distance from ``0`` to the boundary of ``D`` and the signed distance is
``-depth``.

Claim.

1. ``depth <= phi(u) / |u|`` for every ``u != 0``.
2. Corner lemma.  Let ``S`` be a square of gnomonic coordinates on a face of the cube (the points
   ``w = s e_i + a e_j + b e_k``, ``(a, b)`` in ``S``, ``s = +-1``), ``w_1 .. w_4`` its corners,
   ``z`` a vector and ``r >= 0``.  If ``z . w_i >= r |w_i|`` at the four corners, then
   ``z . u >= r`` for every unit ``u`` in the cone of ``S``; in particular, where positive, the
   least ``z . u`` over the cell is at a corner.  Hence, if the six faces are cut into squares
   each with a point ``z_S`` of ``D`` passing the corner test for ``r``, then ``depth >= r``.
3. Cap bound.  For a unit ``v``, ``0 < rho <= pi / 2`` and ``z`` with ``A = z . v >= 0``,
   ``B = |z - A v|``, the least ``z . u`` over the cap of unit vectors within the angle ``rho`` of
   ``v`` is ``A cos rho - B sin rho``, attained at ``cos rho v - sin rho (z - A v) / B``.  (The
   cap circumscribing a cell contains the cell, so the corner test of 2 is never weaker.)
4. The farthest point of a gnomonic cell from the direction of its centre is a corner.
5. Bracketing.  For an ellipsoid given by a binary64 matrix, the float centre ``c``, float ``L``
   and radii ``sigma <= tau`` that the kernel computes have ``c + sigma L B`` inside the solid and
   the solid inside ``c + tau L B`` (``B`` the unit ball), and every point the kernel computes for
   a cell lies in the solid; the binary64 corner test passes only where the exact inequality of 2
   holds for the points computed.
6. The cap (one pair, many digits).  Let ``F(u, lambda) = (grad phi(u) + lambda u, (|u|^2 - 1) / 2)``,
   ``lo`` a lower bound of ``phi`` on the sphere, and ``X = U x L`` a box on which ``F`` has exactly
   one zero ``(u_c, lambda_c)``, with ``L`` holding ``[-r, -lo]`` and ``r >= -lambda_c``.  If
   ``phi >= r`` at every unit direction outside a cap ``C`` whose unit vectors lie in ``U``, then
   ``depth = -lambda_c``.  In binary64, corners ``w`` that pass the kernel's cap test
   ``w . c >= cos(0.8 a) |w|`` are within the angle ``0.9 a`` of ``c``.  For entries that are
   not binary64 numbers the kernel covers the pair rounded to binary64, whose support
   functions differ from the pair's by at most ``|c - c'| + ||M - M'||_F / (sqrt(m) + sqrt(m'))``
   (``M = r A^-1``, ``m = r / max_i sum_j |A_ij|``).

The argument.

1. ``phi`` is the support function of ``D``, positively homogeneous: ``phi(u / |u|) = phi(u) / |u|``.
2. Every ``w`` of the square is ``sum l_i w_i`` with ``l_i >= 0`` summing to 1, so
   ``z . w = sum l_i z . w_i >= r sum l_i |w_i| >= r |w|`` (the triangle inequality, ``r >= 0``),
   and ``u = w / |w|`` covers the cone.  Every direction ``u`` lies in the cone of a face (``i``
   the index of its largest coordinate) and of a cell of its cut; ``z_S`` in ``D`` gives
   ``phi(u) >= z_S . u >= r``.  With ``r`` the least corner value of ``z . u`` (positive), this is
   the statement that the least value over the cell is at a corner.
3. ``u = cos t v + sin t e`` with ``e`` a unit vector orthogonal to ``v`` and ``0 <= t <= rho``:
   ``z . u = A cos t + sin t (z . e) >= A cos t - B sin t``, which decreases in ``t`` on
   ``[0, pi / 2]`` (its derivative is ``-A sin t - B cos t <= 0``); equality at ``t = rho`` and
   ``e = -(z - A v) / B``.
4. 2 with ``z`` the centre's direction ``v`` and ``r`` the least ``v . w_i / |w_i|`` (positive on
   a cell of a face): every point of the cell is at least as close to ``v`` as the farthest
   corner.
5. The triangle inequality in the norm of ``A`` (the solid is ``||x - c_true||_A^2 <= r``), with
   the error bounds of binary64 arithmetic, as the module :mod:`quadric_contact.modes.distance.depth_kernel`
   states them.  With 1 and 2 the kernel's enclosure ``[-phi(u*) / |u*|, -r]`` (``phi(u*)``
   bounded through the outer ellipsoids, ``r`` through the inner points) holds the signed distance.
6. At a zero of ``F``, ``|u| = 1`` and ``phi(u) = u . grad phi(u) = -lambda`` (Euler, as in
   ``proofs/distance_of_separated_ellipsoids.py``), so ``depth <= -lambda_c``.  A global minimiser
   ``u_g`` is a critical point of ``phi`` on the sphere (``phi`` is smooth away from 0 for
   ellipsoids): ``(u_g, -phi(u_g))`` is a zero of ``F``.  If ``u_g`` is outside ``C``,
   ``depth = phi(u_g) >= r >= -lambda_c``.  If inside with ``phi(u_g) < r``, then
   ``-phi(u_g)`` lies in ``(-r, -lo]``, inside ``L``, and ``u_g`` in ``U``: the zero is the one of
   ``X``, and ``depth = -lambda_c``.  The rounding: ``cos x <= 1 - x^2 / 2 + x^4 / 24``, so an
   exact ``cos(w, c)`` at least that polynomial at ``x = 0.9 a`` puts ``w`` within ``0.9 a``.
   The rounding gap: ``h(u) = u . c + sqrt(u^T M u)``, ``|sqrt(a) - sqrt(b)| = |a - b| /
   (sqrt(a) + sqrt(b))``, ``|u^T (M - M') u| <= ||M - M'||_F`` for unit ``u``, and
   ``u^T M u >= r / lambda_max(A) >= m`` (a row sum bounds ``lambda_max``).

What is checked and how.  2 exactly on random rational cells (levels 0 to 6, every face): points
``z`` and targets ``r`` that pass the corner test, and a 9 x 9 grid of rational points of each
square (squares compared, no root taken); 4 the same way.  3 exactly on caps of rational rotations
(Pythagorean angles, so every cosine and sine is rational), against rational points of the cap.
5 exactly on random binary64 ellipsoids (round, elongated to 1:100, far from the origin): the
inner and outer ellipsoids through eigenvalue bounds of ``L^T A L`` found by rational bisection,
the points through the exact quadratic form; the corner test on random and near-threshold binary64
inputs against exact rational arithmetic.  6 by its rounding part, exactly, on binary64 corners
near the threshold of the cap test, and its gap bound against the support functions of rational
ellipsoids and their roundings in 200-bit balls at sampled directions; its logic is the argument
above, and a cross-check (full profile) holds the route of
:func:`quadric_contact.modes.distance.certified.crossing_ellipsoids` at 30 digits to the
brute-force minimiser at 40 and checks it declines pairs with two equal minima.
Cross-check (full profile): the kernel's enclosures
against a brute-force minimiser of ``phi`` (a grid, then Newton's method at 40 digits, on the exact
rational matrices) and against closed forms (two balls; a ball concentric with an ellipsoid).

Not proven here: the support-function form of the depth of convex solids and the triangle
inequality, standard facts of convex geometry not re-derived; the binary64 error bounds of the
kernel, argued in its module and checked on examples only.
"""

from __future__ import annotations

import math
import random
from fractions import Fraction as F
from typing import Any

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure
from quadric_contact.testing.samples import ellipsoid_matrix

from ._support_functions import centred_exact, least_support

proof = Proof(
    "Depth of crossing ellipsoids",
    "the signed distance of two crossing ellipsoids lies between minus a support bound at one "
    "direction and minus a target that every cell of a covering of the sphere certifies with one "
    "point of the Minkowski difference; for one pair, the value at the one zero of the support system "
    "in a box equals the depth when the covering holds outside the box's cap",
    not_proven=(
        "the support-function form of the depth of convex solids, a standard fact not re-derived; "
        "the binary64 error bounds of the kernel, argued in its module and checked on examples"
    ),
)

# -- exact helpers ----------------------------------------------------------------------------


def _dot(p: Any, q: Any) -> Any:
    return sum((x * y for x, y in zip(p, q, strict=True)), F(0))


def _face(axis: int, sign: int, a: F, b: F) -> tuple[F, F, F]:
    w = [F(0)] * 3
    w[axis] = F(sign)
    w[(axis + 1) % 3] = a
    w[(axis + 2) % 3] = b
    return (w[0], w[1], w[2])


def _random_cell(rng: random.Random) -> tuple[int, int, F, F, F]:
    """A cell of the quadtree of a face: axis, sign, centre ``(a, b)`` and half-width."""
    level = rng.randint(0, 6)
    h = F(1, 2**level)
    i, j = rng.randrange(2**level), rng.randrange(2**level)
    return rng.randrange(3), rng.choice((-1, 1)), -1 + (2 * i + 1) * h, -1 + (2 * j + 1) * h, h


def _corners(cell: tuple[int, int, F, F, F]) -> list[tuple[F, F, F]]:
    axis, sign, a, b, h = cell
    return [_face(axis, sign, a + p * h, b + q * h) for p in (-1, 1) for q in (-1, 1)]


def _grid(cell: tuple[int, int, F, F, F], n: int = 8) -> list[tuple[F, F, F]]:
    axis, sign, a, b, h = cell
    return [
        _face(axis, sign, a - h + 2 * h * p / n, b - h + 2 * h * q / n)
        for p in range(n + 1)
        for q in range(n + 1)
    ]


def _at_least(z: Any, w: Any, r: F) -> bool:
    """``z . w >= r |w|`` exactly (``r >= 0``)."""
    t = _dot(z, w)
    return t >= 0 and t * t >= r * r * _dot(w, w)


def _not_below(z: Any, w: Any, wm: Any) -> bool:
    """``z . w / |w| >= z . wm / |wm|`` exactly, both sides positive."""
    t, tm = _dot(z, w), _dot(z, wm)
    return t > 0 and tm > 0 and t * t * _dot(wm, wm) >= tm * tm * _dot(w, w)


def _rotation(rng: random.Random) -> list[list[F]]:
    """A rational rotation (of an integer quaternion), as columns."""
    while True:
        w, x, y, z = (rng.randint(-5, 5) for _ in range(4))
        n = w * w + x * x + y * y + z * z
        if n:
            break
    R = [
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z],
    ]
    return [[F(R[i][j], n) for i in range(3)] for j in range(3)]


def _circle(s: F) -> tuple[F, F]:
    """``(cos t, sin t)`` for ``tan(t / 2) = s``: rational points of the circle."""
    return (1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)


# -- 2: the corner lemma ----------------------------------------------------------------------


@proof.check(
    "corner lemma: z . w >= r |w| at the four corners of a gnomonic square implies it on the whole "
    "square, and the least positive z . u over a cell is at a corner (random rational cells, exactly)",
    method=Method.COMPUTATION,
)
def corner_lemma() -> Finding:
    rng = random.Random(20)
    cells = points = 0
    while cells < 150:
        cell = _random_cell(rng)
        corners = _corners(cell)
        axis, sign = cell[0], cell[1]
        z = [F(rng.randint(-40, 40), 16) for _ in range(3)]
        z[axis] = sign * F(rng.randint(20, 80), 16)  # mostly along the face: positive corner values
        values = [_dot(z, w) / math.sqrt(_dot(w, w)) for w in corners]
        if min(values) <= 0:
            continue
        # a rational target just below the least corner value, checked exactly
        r = F(min(values)).limit_denominator(10**9) * F(999_999, 1_000_000)
        if not all(_at_least(z, w, r) for w in corners):
            continue
        least = corners[values.index(min(values))]
        ensure(all(_not_below(z, w, least) for w in corners), "the least corner is least among corners")
        for w in _grid(cell):
            ensure(_at_least(z, w, r), f"z . w < r |w| inside the cell at {w}")
            ensure(_not_below(z, w, least), f"a point of the cell below the least corner at {w}")
            points += 1
        cells += 1
    return agrees(
        f"{cells} cells on every face at levels 0 to 6, {points} rational points: the corner test "
        "holds on the whole square, and no point is below the least corner"
    )


# -- 3: the cap bound ---------------------------------------------------------------------------


@proof.check(
    "cap bound: the least z . u over the cap of angle rho about v is A cos rho - B sin rho, "
    "attained at cos rho v - sin rho (z - A v) / B (rational rotations and angles, exactly)",
    method=Method.COMPUTATION,
)
def cap_bound() -> Finding:
    rng = random.Random(3)
    caps = points = 0
    for _ in range(60):
        e1, e2, v = _rotation(rng)
        A, B = F(rng.randint(0, 40), 8), F(rng.randint(0, 40), 8)
        z = [A * v[i] + B * e1[i] for i in range(3)]  # B = |z - A v|, rational
        s_rho = F(rng.randint(1, 16), 16)  # rho = 2 atan(s_rho), up to pi / 2
        cos_rho, sin_rho = _circle(s_rho)
        bound = A * cos_rho - B * sin_rho
        extreme = [cos_rho * v[i] - sin_rho * e1[i] for i in range(3)]
        ensure(_dot(extreme, extreme) == 1 and _dot(z, extreme) == bound, "attained at the extreme")
        for k in range(9):
            cos_t, sin_t = _circle(s_rho * k / 8)  # 0 <= t <= rho
            for m in range(-8, 9):
                cos_p, sin_p = _circle(F(m, 4))  # azimuths round the circle
                u = [cos_t * v[i] + sin_t * (cos_p * e1[i] + sin_p * e2[i]) for i in range(3)]
                ensure(_dot(u, u) == 1, "a unit vector")
                ensure(_dot(z, u) >= bound, f"z . u below the cap bound: A={A} B={B} rho={s_rho}")
                points += 1
        caps += 1
    return agrees(f"{caps} caps, {points} rational points of them: never below, equal at the extreme")


# -- 4: the farthest corner ---------------------------------------------------------------------


@proof.check(
    "the farthest point of a gnomonic cell from the direction of its centre is a corner (random "
    "rational cells, exactly)",
    method=Method.COMPUTATION,
)
def farthest_corner() -> Finding:
    rng = random.Random(4)
    checked = 0
    for _ in range(150):
        cell = _random_cell(rng)
        axis, sign, a, b, _h = cell
        v = _face(axis, sign, a, b)
        corners = _corners(cell)
        values = [_dot(v, w) / math.sqrt(_dot(w, w)) for w in corners]
        farthest = corners[values.index(min(values))]
        for w in corners + _grid(cell):
            ensure(_not_below(v, w, farthest), f"a point farther from the centre than every corner: {w}")
            checked += 1
    return agrees(f"150 cells, {checked} rational points: none farther from the centre than a corner")


# -- 5: the kernel's binary64 bracketing and corner test ----------------------------------------


def _sample_ellipsoids(n: int, seed: int) -> list[Any]:
    import numpy as np

    from quadric_contact.testing.samples import random_rotations

    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        if k % 3 == 0:
            axes = rng.uniform(0.3, 1.5, 3)
        elif k % 3 == 1:
            axes = np.array([1.0, 0.1, 0.01]) * rng.uniform(0.8, 1.2, 3)  # elongated to 1:100
        else:
            axes = rng.uniform(0.5, 1.0) * (1 + 1e-9 * rng.uniform(-1, 1, 3))  # nearly round
        centre = rng.uniform(-1, 1, 3) * (10.0 if k % 2 else 0.5)
        out.append(ellipsoid_matrix(axes, random_rotations(1, rng)[0], centre))
    return out


def _positive_definite(N: list[list[F]]) -> bool:
    d1 = N[0][0]
    d2 = N[0][0] * N[1][1] - N[0][1] * N[1][0]
    d3 = (
        N[0][0] * (N[1][1] * N[2][2] - N[1][2] * N[2][1])
        - N[0][1] * (N[1][0] * N[2][2] - N[1][2] * N[2][0])
        + N[0][2] * (N[1][0] * N[2][1] - N[1][1] * N[2][0])
    )
    return d1 > 0 and d2 > 0 and d3 > 0


def _eigen_bounds(N: list[list[F]]) -> tuple[F, F]:
    """Rationals ``mu <= lambda_min(N)`` and ``nu >= lambda_max(N)`` within ``1e-30`` relative,
    each proven by the leading minors of ``N - mu I`` and ``nu I - N``."""
    import mpmath

    with mpmath.workdps(60):
        ev = mpmath.eigsy(
            mpmath.matrix([[mpmath.mpf(x.numerator) / x.denominator for x in row] for row in N])
        )[0]
        lo, hi = F(str(min(ev))), F(str(max(ev)))
    mu, nu = lo * (1 - F(1, 10**30)), hi * (1 + F(1, 10**30))
    shifted = [[N[i][j] - (mu if i == j else 0) for j in range(3)] for i in range(3)]
    ensure(_positive_definite(shifted), "N - mu I positive definite")
    shifted = [[(nu if i == j else 0) - N[i][j] for j in range(3)] for i in range(3)]
    ensure(_positive_definite(shifted), "nu I - N positive definite")
    return mu, nu


def _sqrt_bounds(x: F) -> tuple[F, F]:
    """Rationals ``lo <= sqrt(x) <= hi``, proven by their squares."""
    import mpmath

    with mpmath.workdps(60):
        s = F(str(mpmath.sqrt(mpmath.mpf(x.numerator) / x.denominator)))
    lo, hi = s * (1 - F(1, 10**40)), s * (1 + F(1, 10**40))
    ensure(lo * lo <= x <= hi * hi, "square-root bounds")
    return lo, hi


@proof.check(
    "bracketing: for random binary64 ellipsoids (round, elongated to 1:100, far from the origin) the "
    "kernel's c + sigma L B lies in the solid, the solid in c + tau L B, and every point it computes "
    "for a cell lies in the solid (exactly)",
    method=Method.COMPUTATION,
)
def bracketing() -> Finding:
    import numpy as np

    from quadric_contact.modes.distance.depth_kernel import _bracket, _point
    from quadric_contact.modes.kernels._jit import plain

    bracket, point = plain(_bracket), plain(_point)
    rng = np.random.default_rng(5)
    ellipsoids = points = 0
    gaps = []
    for M0 in _sample_ellipsoids(12, 7):
        for sign in (1.0, -1.0):
            M = sign * M0
            adj, adja, c, L = np.empty((3, 3)), np.empty((3, 3)), np.empty(3), np.zeros((3, 3))
            sigma, tau = bracket(M, adj, adja, c, L)
            ensure(0.5 < sigma <= 1 <= tau < 2, f"radii {sigma}, {tau}")
            A, ct, r = centred_exact(M)
            Lq = [[F(float(L[i, j])) for j in range(3)] for i in range(3)]
            cq = [F(float(x)) for x in c]
            ALq = [[_dot(A[k], [Lq[m][j] for m in range(3)]) for j in range(3)] for k in range(3)]
            N = [
                [_dot([Lq[k][i] for k in range(3)], [ALq[k][j] for k in range(3)]) for j in range(3)]
                for i in range(3)
            ]
            mu, nu = _eigen_bounds(N)
            # ||c - c_true||_A and |L^-1 (c_true - c)|, bounded above
            dc = [cq[i] - ct[i] for i in range(3)]
            rho = _sqrt_bounds(_dot(dc, [_dot(A[i], dc) for i in range(3)]))[1]
            Li = np.linalg.inv(L)  # only to find a candidate; checked exactly below
            s0 = [F(x) for x in Li @ np.array([float(-x) for x in dc])]
            res = [_dot(Lq[i], s0) + dc[i] for i in range(3)]  # L s0 - (c_true - c), exact
            ensure(max(abs(x) for x in res) < F(1, 10**10), "s0 solves L s0 = c_true - c nearly")
            sqrt_r_lo, sqrt_r_hi = _sqrt_bounds(r)
            # inner: ||c + L s - c_true||_A <= sigma sqrt(nu) + rho <= sqrt(r) for |s| <= sigma
            s_nu = _sqrt_bounds(nu)[1]
            ensure(F(sigma) * s_nu + rho <= sqrt_r_lo, "c + sigma L B inside the solid")
            # outer: |L^-1 (x - c)| <= sqrt(r / mu) + |s0| for x in the solid, with |s0| bounded
            # through the exact residual of s0 (|L^-1 res| <= |res| / sqrt(mu'), mu' of L^T L)
            M2 = [
                [_dot([Lq[k][i] for k in range(3)], [Lq[k][j] for k in range(3)]) for j in range(3)]
                for i in range(3)
            ]
            mu2 = _eigen_bounds(M2)[0]
            s0_hi = _sqrt_bounds(_dot(s0, s0))[1] + _sqrt_bounds(_dot(res, res) / mu2)[1]
            outer = _sqrt_bounds(r / mu)[1] + s0_hi
            ensure(outer <= F(tau), f"the solid inside c + tau L B: {float(outer)} > {tau}")
            gaps.append(float(F(tau) - F(sigma)))
            # the points of the cells: directions round the sphere, both signs, as the kernel
            sig = sigma * (1.0 - 16 * 2.0**-53)
            sig2 = float(np.nextafter(sigma * sigma, -np.inf))
            Q = [[F(float(M[i, j])) for j in range(4)] for i in range(4)]
            for w in list(rng.normal(size=(40, 3))) + [np.eye(3)[k] * s for k in range(3) for s in (1, -1)]:
                for sgn in (1.0, -1.0):
                    x0, x1, x2, ok = point(c, L, sig, sig2, sgn, float(w[0]), float(w[1]), float(w[2]))
                    ensure(ok, "the radius check of a point passes")
                    X = [F(float(x0)), F(float(x1)), F(float(x2)), F(1)]
                    ensure(_dot(X, [_dot(Q[i], X) for i in range(4)]) < 0, "a computed point inside")
                    points += 1
            ellipsoids += 1
    return agrees(
        f"{ellipsoids} ellipsoids (both signs of the matrix), {points} computed points inside; "
        f"tau - sigma from {min(gaps):.1e} to {max(gaps):.1e}"
    )


@proof.check(
    "the kernel's binary64 corner test passes only where (x~ - y~) . w >= r |w| holds exactly "
    "(random and near-threshold binary64 points, exactly)",
    method=Method.COMPUTATION,
)
def corner_rounding() -> Finding:
    import numpy as np

    from quadric_contact.modes.distance.depth_kernel import _corner
    from quadric_contact.modes.kernels._jit import plain

    corner = plain(_corner)
    rng = np.random.default_rng(6)
    passed = failed = 0
    for _ in range(1500):
        axis, sign = int(rng.integers(3)), float(rng.choice((-1.0, 1.0)))
        level = int(rng.integers(0, 25))
        a = float(rng.integers(-(2**level), 2**level + 1)) / 2**level
        b = float(rng.integers(-(2**level), 2**level + 1)) / 2**level
        x = rng.uniform(-10, 10, 3)
        y = x - rng.normal(size=3) * 10.0 ** rng.uniform(-3, 1)
        d = x - y  # as the kernel: binary64 differences
        dn, da, db = sign * d[axis], d[(axis + 1) % 3], d[(axis + 2) % 3]
        w = _face(axis, int(sign), F(a), F(b))
        T = _dot([F(float(p)) - F(float(q)) for p, q in zip(x, y, strict=True)], w)
        if T <= 0:
            ensure(not corner(float(dn), float(da), float(db), a, b, 1e-300), "passed with T <= 0")
            continue
        r = float(T) / math.sqrt(float(_dot(w, w)))
        for k in range(-12, 13):
            R2 = float(np.nextafter((r * (1 + k * 2.0**-52)) ** 2, np.inf))
            if corner(float(dn), float(da), float(db), a, b, R2):
                ensure(F(R2) * _dot(w, w) <= T * T, f"passed where T^2 < R2 |w|^2: {x}, {y}, {a}, {b}")
                passed += 1
            else:
                failed += 1
    ensure(passed > 1000 and failed > 1000, "both outcomes near the threshold")
    return agrees(f"{passed} passes, all exact; {failed} refusals near the threshold")


# -- cross-check: the kernel against a brute-force minimiser -------------------------------------


@proof.check(
    "the kernel's enclosures hold the brute-force depth (random binary64 pairs read as exact rationals: "
    "general, nearly round, elongated, two equal minima) and the closed forms of two balls and of a "
    "ball concentric with an ellipsoid",
    method=Method.CROSS_CHECK,
    full=True,
    size="48 random pairs and 3 closed forms",
)
def enclosures_hold() -> Finding:
    import mpmath
    import numpy as np

    from quadric_contact.modes.distance.depth_kernel import crossing_ellipsoids
    from quadric_contact.testing.samples import random_rotations

    rng = np.random.default_rng(8)
    pairs = []
    for k in range(48):
        R1, R2 = random_rotations(2, rng)
        if k % 4 == 0:
            axes1, axes2 = rng.uniform(0.3, 1.5, (2, 3))
        elif k % 4 == 1:
            axes1, axes2 = rng.uniform(0.5, 1.5, 2)[:, None] * (1 + 1e-6 * rng.uniform(-1, 1, (2, 3)))
        elif k % 4 == 2:
            axes1, axes2 = np.array([[1.0, 0.2, 0.05]]) * rng.uniform(0.8, 1.2, (2, 3))
        else:  # identical ellipsoids shifted along their longest axis: two equal minima
            axes1 = axes2 = np.array([3.0, 1.0, 0.5])
            R2 = R1
        if k % 4 == 3:
            c1, c2 = np.zeros(3), R1 @ np.array([rng.uniform(0.2, 1.0), 0, 0])
        else:  # plates crossing near their middles
            c1, c2 = rng.uniform(-0.3, 0.3, (2, 3)) * (0.1 if k % 4 == 2 else 1.0)
        pairs.append((ellipsoid_matrix(axes1, R1, c1), ellipsoid_matrix(axes2, R2, c2)))
    Es = np.array([p[0] for p in pairs])
    Ks = np.array([p[1] for p in pairs])
    enc, rest = crossing_ellipsoids(Es, Ks)
    ensure((~rest).sum() >= 44, f"only {(~rest).sum()} of 48 answered")
    for k in np.flatnonzero(~rest):
        value = -least_support(Es[k], Ks[k])
        ensure(mpmath.mpf(enc[k, 0]) <= value <= mpmath.mpf(enc[k, 1]), f"pair {k}: {value} not in {enc[k]}")
        ensure(enc[k, 1] - enc[k, 0] <= 1e-12 * abs(enc[k, 1]), "at most 1e-12 relative wide")
    # closed forms: |c1 - c2| = 5/8 and 13/16; a ball of radius 1/4 concentric with axes (2, 1, 1/2)
    eye = np.eye(3)
    ball, ball_2, ball_4 = ([1.0] * 3, [0.5] * 3, [0.25] * 3)
    centre = np.array([1.0, 2, 3])
    closed = [
        (
            (
                ellipsoid_matrix(ball, eye, np.zeros(3)),
                ellipsoid_matrix(ball_2, eye, np.array([0.375, 0.5, 0])),
            ),
            F(7, 8),
        ),
        (
            (
                ellipsoid_matrix(ball, eye, np.zeros(3)),
                ellipsoid_matrix(ball_2, eye, np.array([0.3125, 0, 0.75])),
            ),
            F(11, 16),
        ),
        ((ellipsoid_matrix([2.0, 1.0, 0.5], eye, centre), ellipsoid_matrix(ball_4, eye, centre)), F(3, 4)),
    ]
    Es = np.array([p[0][0] for p in closed])
    Ks = np.array([p[0][1] for p in closed])
    enc2, rest2 = crossing_ellipsoids(Es, Ks)
    ensure(not rest2.any(), "the closed forms answered")
    for k, (_pair, depth) in enumerate(closed):
        ensure(
            F(float(enc2[k, 0])) <= -depth <= F(float(enc2[k, 1])),
            f"closed form {k}: {-depth} not in {enc2[k]}",
        )
    return agrees(
        f"{(~rest).sum()} of 48 random pairs answered, each enclosure holding the 40-digit brute-force "
        "depth; the three closed forms inside their enclosures"
    )


# -- 6: the cap ----------------------------------------------------------------------------------


@proof.check(
    "the kernel's binary64 cap test w . c >= cos(0.8 a) |w| passes only for corners within the "
    "angle 0.9 a of c (random and near-threshold binary64 corners and centres, exactly)",
    method=Method.COMPUTATION,
)
def cap_rounding() -> Finding:
    import numpy as np

    rng = np.random.default_rng(16)
    passed = failed = 0
    for _ in range(400):
        a = float(10.0 ** rng.uniform(-6, -3))
        c = rng.normal(size=3)
        c /= np.linalg.norm(c)
        axis = int(np.argmax(np.abs(c)))
        sign = 1.0 if c[axis] > 0 else -1.0
        # a direction at an angle near 0.8 a from c, snapped to dyadic gnomonic coordinates
        e = np.cross(c, rng.normal(size=3))
        e /= np.linalg.norm(e)
        t = 0.8 * a * (1 + rng.uniform(-1e-6, 1e-6))
        d = math.cos(t) * c + math.sin(t) * e
        level = int(rng.integers(30, 53))
        ca = round(d[(axis + 1) % 3] / abs(d[axis]) * 2**level) / 2**level
        cb = round(d[(axis + 2) % 3] / abs(d[axis]) * 2**level) / 2**level
        w = _face(axis, int(sign), F(ca), F(cb))
        # the kernel's test, in binary64: its _on_face vector (exact) against c, and sqrt(1 + a^2 + b^2)
        wf = [float(x) for x in w]
        nq = math.sqrt((1.0 + ca * ca) + cb * cb)
        if wf[0] * c[0] + wf[1] * c[1] + wf[2] * c[2] >= math.cos(0.8 * a) * nq:
            x = F(0.9 * a)
            P = 1 - x * x / 2 + x**4 / 24  # at least cos x
            cf = [F(float(v)) for v in c]
            wc = _dot(w, cf)
            ensure(
                wc > 0 and wc * wc >= P * P * _dot(w, w) * _dot(cf, cf),
                f"a corner beyond 0.9 a: {w}, {c}, {a}",
            )
            passed += 1
        else:
            failed += 1
    ensure(passed > 100 and failed > 100, "both outcomes near the threshold")
    return agrees(f"{passed} passes, each within 0.9 a exactly; {failed} refusals near the threshold")


@proof.check(
    "the rounding gap bounds |h_Q(u) - h_Q'(u)| for rational ellipsoids Q and their binary64 "
    "roundings Q' (200-bit balls at 300 directions each), and is within a factor 100 of the largest "
    "difference seen",
    method=Method.EVIDENCE,
    size="8 ellipsoids, 2400 directions",
)
def rounding_gap() -> Finding:
    import flint
    import numpy as np

    from quadric_contact.exact.precision import working_precision
    from quadric_contact.model.motions import RigidMotion
    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.distance.certified import _inverse3, _rounding_gap
    from quadric_contact.theory.contact_scale import centred_form
    from quadric_contact.theory.overlap import solid_of

    def support(q: Any, u: Any) -> Any:
        A, c, r = centred_form(q)
        B = _inverse3(A)
        quad = sum(u[i] * _ball(B[i][j]) * u[j] for i in range(3) for j in range(3))
        return sum(u[i] * _ball(c[i]) for i in range(3)) + (_ball(r) * quad).sqrt()

    def _ball(x: F) -> Any:
        return flint.arb(x.numerator) / x.denominator

    rng = np.random.default_rng(12)
    turn = RigidMotion.from_quaternion(3, 1, -2, 1)
    ratios = []
    for _ in range(8):
        axes = [F(int(x), 97) for x in rng.integers(20, 150, 3)]
        centre = [F(int(x), 89) for x in rng.integers(-60, 60, 3)]
        q = solid_of(Quadric.ellipsoid(*axes, center=centre).moved(turn))
        rounded = Quadric.from_matrix([[F(float(x)) for x in row] for row in q.to_numpy()])
        gap = _rounding_gap(q, q.to_numpy())
        ensure(gap is not None and gap > 0, "a rational ellipsoid rounds to another one")
        with working_precision(200):
            worst = flint.arb(0)
            for u in rng.normal(size=(300, 3)):
                ub = [flint.arb(float(x)) for x in u / np.linalg.norm(u)]
                d = abs(support(q, ub) - support(rounded, ub))
                ensure(d < _ball(gap), f"a difference {d} above the gap {float(gap)}")
                worst = max(worst, d.upper())
            ratios.append(float(_ball(gap) / worst))
    ensure(max(ratios) <= 100, f"the gap is {max(ratios):.0f} times the largest difference seen")
    return agrees(
        f"8 ellipsoids, 2400 directions: never above the gap; gap / largest seen "
        f"{min(ratios):.1f} to {max(ratios):.1f}"
    )


@proof.check(
    "the certified route for one crossing pair (kernel bound, one isolated root, covering outside "
    "its cap) holds the brute-force depth at 30 digits, and declines pairs with two equal minima",
    method=Method.CROSS_CHECK,
    full=True,
    size="12 random pairs and 4 pairs with two equal minima",
)
def cap_route_holds() -> Finding:
    import mpmath
    import numpy as np

    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.distance.certified import crossing_ellipsoids
    from quadric_contact.testing.samples import random_rotations
    from quadric_contact.theory.overlap import solid_of

    rng = np.random.default_rng(61)
    answered = 0
    for _ in range(12):
        R1, R2 = random_rotations(2, rng)
        E, K = (ellipsoid_matrix(rng.uniform(0.3, 1.5, 3), R, rng.uniform(-0.5, 0.5, 3)) for R in (R1, R2))
        r = crossing_ellipsoids(Quadric.from_matrix(E).as_ellipsoid(), solid_of(Quadric.from_matrix(K)), 30)
        if r is None:
            continue
        answered += 1
        with mpmath.workdps(60):
            value = -least_support(E, K)
            mid, rad = (mpmath.mpf(x.str(60, radius=False)) for x in (r.distance.mid(), r.distance.rad()))
            ensure(mid - rad <= value <= mid + rad, f"{value} outside {r.distance}")
            ensure(rad <= abs(mid) * mpmath.mpf(10) ** -30, "30 digits")
    ensure(answered >= 10, f"only {answered} of 12 answered")
    declined = 0
    for _ in range(4):
        axes = np.array([3.0, 1.0, 0.5]) * rng.uniform(0.8, 1.2)
        (R,) = random_rotations(1, rng)
        E = ellipsoid_matrix(axes, R, np.zeros(3))
        K = ellipsoid_matrix(axes, R, R @ np.array([rng.uniform(0.2, 1.0), 0.0, 0.0]))
        r = crossing_ellipsoids(Quadric.from_matrix(E).as_ellipsoid(), solid_of(Quadric.from_matrix(K)), 15)
        declined += r is None
    ensure(declined == 4, f"{4 - declined} pairs with two equal minima answered by one root")
    return agrees(f"{answered} of 12 enclosures hold the 40-digit depth; 4 of 4 symmetric pairs declined")
