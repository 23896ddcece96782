"""Depth into non-convex solids: the penetration depth of an ellipsoid into the solid of a
hyperboloid, a hyperbolic paraboloid or cylinder lies between the depth into an inscribed
ellipsoid and the length of a translation checked free exactly.

Not a result of the paper: the route by which :func:`quadric_contact.distance` (``certified``
and ``float`` modes) answers an ellipsoid ``E`` crossing a solid ``K = {X^T Q X <= 0}`` that is
not convex (:mod:`quadric_contact.modes.distance.nonconvex`).  The depth is
``depth(E, K) = min { |v| : E + v and K have disjoint interiors }``.

Claim.

1. Inclusion.  For linear forms ``l_i`` and ``s_i >= 0``, ``C = {X^T Q X + sum s_i (l_i . X)^2 <=
   0}`` lies in ``K``.
2. Tangency.  If every ``l_i`` vanishes at ``Y = (y, 1)`` with ``y`` on the surface of ``K``, then
   ``y`` is on the surface of ``C`` and the two gradients there are equal: ``C`` is tangent to
   ``K`` at ``y``.
3. Monotonicity.  ``C`` inside ``K`` gives ``depth(E, C) <= depth(E, K)``.
4. Upper bound.  If the interiors of ``E + v`` and ``K`` are disjoint, ``depth(E, K) <= |v|``.

Hence ``-|v| <= -depth(E, K) <= -depth(E, C)``: the certified route encloses ``-depth(E, C)``
to ``digits + 2`` digits (two ellipsoids, :mod:`quadric_contact.modes.distance.certified`),
lengthens ``C``'s nearest free translation by ``10^-(digits + 1)``, decides exactly that
``E + v`` does not overlap ``K`` (:func:`quadric_contact.theory.overlap.overlap_exact`), and
answers only where the two ends agree to the digits asked.

The argument.

1. On ``C``, ``X^T Q X <= -sum s_i (l_i . X)^2 <= 0``.
2. ``sum s_i (l_i . X)^2`` vanishes at ``Y`` with its gradient ``2 sum s_i (l_i . Y) l_i``.
3. A translation ``v`` that frees ``E`` from ``K`` frees it from ``C``: the interior of ``C`` is in
   that of ``K``.  The least ``|v|`` over a larger set of translations is not larger.
4. The definition.

What is checked and how.  1 and 2 as symbolic identities on generic symbols (``Q`` symmetric,
two forms), and 1 exactly at rational points of the package's inscribed ellipsoids for every
type, tangency point and width.  The cross-check (full profile) holds the route's enclosures to
an independent brute force (``proofs/_brute_depth.py``: the least first free ``t`` along rays,
freedom read from the minimum of ``Q`` over the ellipsoid, a trust-region subproblem, in
binary64), for every non-convex type.

Not proven here: nothing beyond the four statements is needed.  The route's reach (where the
two ends meet) is measured, not claimed: a nearest free position touching ``K`` at two points
(a ball in the waist of a hyperboloid) is left undecided.
"""

from __future__ import annotations

import random
from fractions import Fraction as F
from typing import Any

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure

from ._brute_depth import depth as brute_depth

proof = Proof(
    "Depth into non-convex solids",
    "the penetration depth of an ellipsoid into a solid that is not convex lies between the depth "
    "into an inscribed ellipsoid tangent to it and the length of a translation checked free exactly",
)


@proof.check(
    "inclusion and tangency: X^T Q' X - X^T Q X = sum s_i (l_i . X)^2, and where every l_i . Y = 0 "
    "the two forms and their gradients agree at Y (generic symmetric Q, two forms)",
    method=Method.IDENTITY,
)
def inclusion_and_tangency() -> Finding:
    import sympy as sp

    X = sp.Matrix([*sp.symbols("x1:4", real=True), 1])
    Q = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"q{min(i, j)}{max(i, j)}", real=True))
    s = sp.symbols("s1:3", nonnegative=True)
    y = sp.Matrix([*sp.symbols("y1:4", real=True), 1])
    # forms that vanish at Y: l = (m, -m . y) for free m
    ms = [sp.Matrix(sp.symbols(f"m{k}_1:4", real=True)) for k in (1, 2)]
    ls = [sp.Matrix([*m, -(m.T * y[:3, 0])[0]]) for m in ms]
    added = sum((s[k] * ls[k] * ls[k].T for k in range(2)), sp.zeros(4, 4))
    Qp = Q + added
    form = (X.T * Q * X)[0]
    formp = (X.T * Qp * X)[0]
    diff = sp.expand(formp - form - sum(s[k] * (ls[k].T * X)[0] ** 2 for k in range(2)))
    ensure(diff == 0, "Q' - Q is the sum of the squares")
    at_y = {X[i]: y[i] for i in range(3)}
    ensure(sp.expand(formp.subs(at_y) - form.subs(at_y)) == 0, "the forms agree at Y")
    xs = list(X[:3, 0])
    for x in xs:
        g = sp.expand((sp.diff(formp, x) - sp.diff(form, x)).subs(at_y))
        ensure(g == 0, f"the gradients agree at Y ({x})")
    return agrees("Q' - Q = sum s_i (l_i . X)^2; at Y the values and the three derivatives agree")


@proof.check(
    "inclusion, exactly: rational points of the package's inscribed ellipsoids lie in the solid "
    "(one sheet inside, two sheets, hyperbolic paraboloid and cylinder; three widths each)",
    method=Method.COMPUTATION,
)
def inscribed_points() -> Finding:
    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.distance.nonconvex import inscribed_ellipsoid
    from quadric_contact.theory.overlap import solid_of

    rng = random.Random(5)
    points = 0
    for q, y in (
        ("x^2 + y^2 - z^2 - 1", (1, 0, 0)),
        ("x^2 + y^2 - z^2 - 1", (F(5, 4), 0, F(3, 4))),
        ("x^2 + y^2 - z^2 + 1", (0, 0, 1)),
        ("z - x^2 + y^2", (F(1, 2), F(1, 2), 0)),
        ("x^2 - y^2 - 1", (1, 0, 5)),
    ):
        K = solid_of(Quadric.from_equation(q))
        for width in (F(1, 64), F(1, 8), F(1)):
            C = inscribed_ellipsoid(K, y, width)
            ensure(C is not None, f"an ellipsoid inscribed in {q} at {y}")
            assert C is not None
            c = C.center()
            assert c is not None
            for _ in range(30):
                d = [F(rng.randint(-50, 50), 50) for _ in range(3)]
                for t in (F(k, 6) for k in range(1, 7)):
                    p = [c[i] + t * d[i] for i in range(3)]
                    if C.value_at(p) <= 0:
                        ensure(K.value_at(p) <= 0, f"a point of C outside K: {p}")
                        points += 1
    return agrees(f"{points} rational points of 15 inscribed ellipsoids, every one in its solid")


CASES = (
    ("(x - 4/5)^2 + y^2 + (z - 1/2)^2 - 9/100", "x^2 + y^2 - z^2 - 1"),
    ("(x - 13/10)^2 + y^2 + (z - 1/2)^2 - 9/100", "x^2 + y^2 - z^2 - 1"),
    ("x^2 + y^2 + (z - 11/10)^2 - 1/25", "x^2 + y^2 - z^2 + 1"),
    ("(x - 1/5)^2/(1/25) + y^2/(9/100) + (z - 1/20)^2/(1/100) - 1", "z - x^2 + y^2"),
    ("(x - 6/5)^2/(1/25) + (y - 1/5)^2/(1/16) + z^2/(1/9) - 1", "x^2 - y^2 - 1"),
)


@proof.check(
    "the route's enclosures hold the brute-force depth (rays, the least of Q over the ellipsoid) "
    "on a pair of every non-convex type",
    method=Method.CROSS_CHECK,
    full=True,
    size="5 pairs",
)
def enclosures_hold() -> Finding:
    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.distance.certified import distance_certified
    from quadric_contact.theory.overlap import solid_of

    worst = 0.0
    for e, q in CASES:
        E, K = Quadric.from_equation(e).as_ellipsoid(), solid_of(Quadric.from_equation(q))
        r = distance_certified(E, K)
        ensure(r.method == "inscribed ellipsoid", f"{e} against {q}: {r.method}")
        want = -brute_depth(E.to_numpy(), K.to_numpy(), 2.0)
        got = float(r.distance.mid())
        gap: Any = abs(got - want) / abs(want)
        ensure(gap <= 1e-8, f"{e} against {q}: {got} against the brute force {want}")
        worst = max(worst, gap)
    return agrees(f"5 of 5 enclosures within {worst:.1e} relative of the brute force (its accuracy)")
