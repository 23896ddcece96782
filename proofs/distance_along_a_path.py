"""Distance along a path: the least signed distance of a moving ellipsoid from a solid, enclosed by
a bound on how far the ellipsoid's points move.

Not a result of the paper: the bound on which :func:`quadric_contact.scenes.path_distance.
path_distance` (and the scenes' ``distance`` effect) bisects.  The ellipsoid ``E0`` (centre
``c0``, every point within ``rho`` of it) moves rigidly on a segment: ``x(t) = p(t) + R(t) y``
for its point ``c0 + y``, with ``p`` polynomial and ``R(t) = M(q(t)) / n(t)`` the rotation of a
polynomial quaternion (``n = |q|^2 > 0``; ``R = I`` without rotation).  ``d(t)`` is the signed
distance of the moved ellipsoid from the solid ``K`` (:func:`quadric_contact.distance`: the
distance of the sets when the interiors are disjoint, minus the translation depth when they
meet, which is computed for convex ``K`` only).

Claim.  On ``[a, b]`` inside one segment, with ``V >= |p'|``, ``W >= 2 |q'| / |q|`` there and
``f(s) = V s + rho min(W s, 2)``, every ``t`` in ``[a, b]`` has
``d(t) >= (d(a) + d(b)) / 2 - f((b - a) / 2)``.

The argument.

1. Points move little: ``|x(t) - x(a)| <= |p(t) - p(a)| + |(R(t) - R(a)) y|``; the first term is
   at most ``V (t - a)``; the second is a chord of the circle of radius ``|y| <= rho`` through
   the angle of ``R(t) R(a)^T``, at most ``2 rho`` and at most ``rho`` times the angle, which is
   at most ``W (t - a)`` (the angle is at most the integral of the angular speed).  So every
   point moves by at most ``f(t - a)`` (check ``displacements_are_bounded``).
2. The angular speed of ``R = M(q) / |q|^2``: ``|omega|^2 = 4 (|q'|^2 |q|^2 - (q . q')^2) /
   |q|^4 <= 4 |q'|^2 / |q|^2`` (Cauchy-Schwarz; check ``angular_speed``), so ``W`` may be any
   upper bound of ``2 |q'| / |q|``: the package takes ``sqrt(4 S / N)`` rounded up, ``S`` the
   sum of the squared enclosures of the ``|q_i'|``, ``N`` a positive lower enclosure of ``|q|^2``.
3. The distance moves by at most the displacement: if every point moves by at most ``delta``,
   the new solid ``A'`` lies in ``A + B(delta)`` (``B`` a ball) and the old in ``A' + B(delta)``.
   For disjoint interiors the distance of the sets is at least ``dist(A, K) - delta``.  For
   convex ``K``, ``d(A) = -min_u (h_A(u) + h_K(-u))`` over unit ``u`` for both signs (the
   support-function form of :mod:`quadric_contact.theory.distance_critical`), ``h`` grows with
   the set and ``h_{A + B(delta)} = h_A + delta``, so ``d(A') >= d(A) - delta``; symmetrically
   ``d(A) >= d(A') - delta`` (check ``widening_by_a_ball``, on exact sphere pairs).
4. From ``a`` and from ``b``: ``d(t) >= d(a) - f(t - a)`` and ``d(t) >= d(b) - f(b - t)``;
   their mean is at least ``(d(a) + d(b)) / 2 - (f(t - a) + f(b - t)) / 2``, and ``f`` is
   concave (a linear term plus the minimum of two linear ones), so the last mean is at most
   ``f((b - a) / 2)`` (check ``midpoint_bound``).

What is checked and how.  Step 2 as a symbolic identity over a generic quaternion and its
derivative (eight symbols).  Step 1 exactly, on random rational quaternion and centre paths: the
displacement of points of the boundary of a random ellipsoid, against the bound the package
computes for the interval (``_reach_bound`` at half the interval).  Step 3 on exact pairs where
the distance is known in closed form (balls, and a ball against a half-space).  Step 4 exactly on
a grid of rational parameters.  Cross-check: a turning ellipsoid above a plane, whose least
distance is known in closed form, and the enclosure against exact distances sampled along the
path.

Not proven here: the support-function form of the signed distance of convex solids and the
chord-arc inequality, standard facts of convex geometry not re-derived; step 1 and step 3 are
checked on examples, not in general.
"""

from __future__ import annotations

import random
from fractions import Fraction as F

import sympy as sp

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure

from .mutual_contact_events import _rotation_times_n

proof = Proof(
    "Distance along a path",
    "the least signed distance of a rigidly moving ellipsoid from a solid is enclosed by the mean of "
    "the end values minus a bound of the points' displacement",
    not_proven=(
        "the support-function form of the signed distance of convex solids and the chord-arc "
        "inequality, standard facts not re-derived; the displacement and widening steps on examples"
    ),
)


@proof.check(
    "the angular speed of R = M(q) / |q|^2: |omega|^2 = 4 (|q'|^2 |q|^2 - (q . q')^2) / |q|^4",
    method=Method.IDENTITY,
)
def angular_speed() -> Finding:
    q = sp.symbols("w x y z", real=True)
    dq = sp.symbols("dw dx dy dz", real=True)
    n = sum(v * v for v in q)
    M = sp.Matrix(_rotation_times_n(*q))
    # R' along the path: the derivative of M / n in the direction dq
    dM = sum((M.diff(v) * dv for v, dv in zip(q, dq, strict=True)), sp.zeros(3, 3))
    dn = sum(2 * v * dv for v, dv in zip(q, dq, strict=True))
    R = M / n
    dR = dM / n - M * dn / n**2
    Omega = dR * R.T  # skew: R' R^T
    ensure(sp.simplify(Omega + Omega.T) == sp.zeros(3, 3), "R' R^T is skew")
    omega2 = Omega[2, 1] ** 2 + Omega[0, 2] ** 2 + Omega[1, 0] ** 2
    dot = sum(v * dv for v, dv in zip(q, dq, strict=True))
    dd = sum(dv * dv for dv in dq)
    ensure(
        sp.simplify(omega2 * n**2 - 4 * (dd * n - dot**2)) == 0,
        "|omega|^2 |q|^4 = 4 (|q'|^2 |q|^2 - (q.q')^2)",
    )
    return agrees(
        "with eight independent symbols for q and q': R' R^T is skew and its axial vector has "
        "|omega|^2 = 4 (|q'|^2 |q|^2 - (q . q')^2) / |q|^4, at most 4 |q'|^2 / |q|^2"
    )


@proof.check(
    "f(s) = V s + rho min(W s, 2) is concave: (f(x) + f(L - x)) / 2 <= f(L / 2) on a rational grid",
    method=Method.COMPUTATION,
)
def midpoint_bound() -> Finding:
    grid = [F(0), F(1, 3), F(1, 2), F(1), F(3, 2), F(4)]
    count = 0
    for V in grid:
        for W in grid:
            for rho in (F(1, 2), F(2)):
                for L in (F(1, 4), F(1), F(3)):

                    def f(s: F, V: F = V, W: F = W, rho: F = rho) -> F:
                        return V * s + rho * min(W * s, F(2))

                    for k in range(9):
                        x = L * k / 8
                        ensure((f(x) + f(L - x)) / 2 <= f(L / 2), f"V={V} W={W} rho={rho} L={L} x={x}")
                        count += 1
    return agrees(f"{count} points: the mean of the two one-sided bounds never exceeds f at the midpoint")


def _random_segment(rng: random.Random):  # type: ignore[no-untyped-def]
    from quadric_contact.scenes.trajectory import PolynomialMotion

    translation = [[F(rng.randint(-4, 4), 4) for _ in range(rng.randint(1, 3))] for _ in range(3)]
    quaternion = [[F(rng.randint(-3, 3), 2) for _ in range(rng.randint(1, 3))] for _ in range(4)]
    quaternion[0][0] = F(3)  # |q| >= 3 - (the rest) stays away from zero on small times
    return PolynomialMotion(translation, quaternion)


@proof.check(
    "every boundary point of a turning, moving ellipsoid moves by at most the package's bound "
    "f(t - a) on random rational segments (exactly)",
    method=Method.COMPUTATION,
)
def displacements_are_bounded() -> Finding:
    from quadric_contact import Quadric
    from quadric_contact.scenes.broadphase import ellipsoid_extents
    from quadric_contact.scenes.path_distance import _reach_bound

    rng = random.Random(7)
    checked = 0
    for _ in range(12):
        axes = [F(rng.randint(1, 8), 4) for _ in range(3)]
        centre = tuple(F(rng.randint(-4, 4), 2) for _ in range(3))
        E = Quadric.ellipsoid(*axes, center=centre)
        rho = ellipsoid_extents(E)[1]
        motion = _random_segment(rng)
        (seg,) = motion.segments(F(0), F(1), centre)
        a = F(rng.randint(0, 4), 8)
        t = a + F(rng.randint(1, 4), 64)
        # the bound of f(t - a) is the package's f((b - a) / 2) on [a, b] with b = 2 t - a
        bound = _reach_bound(seg, a, 2 * t - a, rho)
        Ma, Mt = seg.rigid_motion(a, centre), seg.rigid_motion(t, centre)
        for sx in (-1, 1):
            for k in range(3):
                y = [F(0)] * 3
                y[k] = sx * axes[k]
                point = tuple(centre[i] + y[i] for i in range(3))
                pa, pt = Ma.apply(point), Mt.apply(point)
                d2 = sum((pt[i] - pa[i]) ** 2 for i in range(3))
                ensure(d2 <= bound**2, f"displacement^2 {float(d2)} > bound^2 {float(bound**2)}")
                checked += 1
    return agrees(f"{checked} points of 12 ellipsoids on random segments: |x(t) - x(a)| <= f(t - a)")


@proof.check(
    "widening by a ball lowers the signed distance by its radius: balls against a ball and against a "
    "half-space, apart and crossing (exact distances)",
    method=Method.COMPUTATION,
)
def widening_by_a_ball() -> Finding:
    from quadric_contact import Quadric, distance

    checked = 0
    for r, delta, gap in ((F(1), F(1, 2), F(3)), (F(1, 2), F(1, 4), F(1, 8)), (F(2), F(1), F(-1, 2))):
        for target in ("x**2 + y**2 + z**2 - 1", "z"):
            # a ball of radius r centred at height h: distance from the unit ball h - r - 1, from z <= 0 h - r
            h = gap + r + (1 if target != "z" else 0)
            small = distance(Quadric.sphere(r, center=(0, 0, h)), target, mode="exact").distance
            wide = distance(Quadric.sphere(r + delta, center=(0, 0, h)), target, mode="exact").distance
            ensure(small == gap, f"d = {gap} for r = {r}, got {small}")
            ensure(wide == gap - delta, f"d - delta for r + delta = {r + delta}, got {wide}")
            checked += 1
    return agrees(f"{checked} pairs: d(A + B(delta)) = d(A) - delta, on both sides of touching")


@proof.check(
    "a turning ellipsoid above a plane (semi-axes 2, 1/2, 1/2 at height 3 and 3/2, turned about y by "
    "2 atan t): the enclosure holds the closed-form minimum 1 (and -1/2) and every sampled distance",
    method=Method.CROSS_CHECK,
    full=True,
    size="2 paths, 17 sampled times each",
)
def turning_ellipsoid() -> Finding:
    from quadric_contact import Quadric, distance
    from quadric_contact.scenes.path_distance import path_distance
    from quadric_contact.scenes.trajectory import PolynomialMotion

    for h, least in ((F(3), F(1)), (F(3, 2), F(-1, 2))):
        E0 = Quadric.ellipsoid(2, F(1, 2), F(1, 2), center=(0, 0, h))
        path = PolynomialMotion([[0], [0], [0]], [[1], [0], [0, 1], [0]])
        r = path_distance(E0, "z", path, 0, 2, tolerance=F(1, 1000))
        lo, hi = r.minimum
        ensure(lo <= least <= hi, f"{least} in [{float(lo)}, {float(hi)}]")
        ensure(any(a <= 1 <= b for a, b in r.times), "t = 1 among the times")
        (seg,) = path.segments(F(0), F(2), (0, 0, h))
        for k in range(0, 17):
            t = F(k, 8)
            dt = distance(E0.moved(seg.rigid_motion(t, (0, 0, h))), "z", mode="exact").distance
            ensure(dt >= lo, f"d({t}) below the enclosure")
    return agrees("both heights: the closed-form minimum inside the enclosure, t = 1 inside the times")
