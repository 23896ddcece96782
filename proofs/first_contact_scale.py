"""The first-contact scale: the root of the scaled pencil's discriminant that
:func:`quadric_contact.contact_scale` returns is the scale at which ``E`` first touches ``Q``.

Not a result of the paper.  ``E: (x - c)^T A (x - c) = r`` scaled about its centre by ``s``
is ``E_t`` (``t = s^2``), the matrix of ``E`` with the corner ``c^T A c - t r``; ``Q`` is a
quadric of Table 1 or a plane (no finite singular point); ``P(l, t) = det(l E_t + Q)``.

Claim.  ``t* = inf {t > 0 : the solid of E_t meets the surface of Q}`` (for ``c`` not on the
surface) is a root of ``R(t) = D(t) Res_l(G*, P~)(t)``, where ``P = G(l) P~(l, t)`` with
``G = gcd`` of the coefficients of ``P`` in ``t`` (in ``Q[l]``), ``D`` the last member of
Yang's discrimination sequence of ``P~`` in ``l`` and ``G*`` = ``G`` without its factors
``l``.  The package returns the least positive root ``t_k`` of ``R`` such that the predicate
holds at a rational between ``t_k`` and the next root, having checked that it fails at a
rational between ``t_{k-1}`` and ``t_k``: by monotonicity and ``t*`` being a root of ``R``,
that root is ``t*``.

The argument.

1. ``P`` is affine in ``t``: ``t`` sits in the corner entry only, and the determinant is
   affine in one entry with the cofactor as slope: ``P = P_0(l) - t r l det(l A + Q_00)``
   (check ``affine_in_the_scale``).  So ``G`` is the common factor of the two coefficients.
2. Monotone: the solids ``(x - c)^T A (x - c) <= t r`` are nested and increasing in ``t``, so
   the predicate is false below ``t*`` and true above; it is true at ``t*`` (a compact solid
   and a closed surface: the infimum is attained).
3. At ``t*`` the solid touches the surface at a point ``p`` of the boundary of ``E_t*`` (an
   interior point would allow a smaller ``t``), where the surface of ``Q`` is tangent to
   ``E_t*``: ``grad q(p) = -l0 grad e(p)`` for a real ``l0`` (``grad e(p) != 0`` as ``p != c``;
   ``grad q(p) != 0`` as the accepted types have no finite singular point).  Then ``X = (p, 1)``
   spans a kernel vector of ``l0 E_t* + Q``: the first three entries of ``(l0 E + Q) X`` are
   the gradients' combination, zero, and the last is ``X^T (l0 E + Q) X = 0`` (check
   ``tangency_is_a_kernel_vector``).
4. A kernel vector ``X`` with ``X^T E X = 0`` makes ``l0`` a multiple root of ``P(., t*)``
   (Jacobi: ``P' = tr(adj(l E + Q) E)``; the adjugate of a symmetric matrix of rank 3 is
   ``k X X^T``, of rank <= 2 zero; check ``jacobi_multiple_root``).
5. A multiple root ``l0`` of ``P = G P~``: if ``G(l0) != 0`` it is a multiple root of ``P~``,
   so ``D(t*) = 0`` (``D`` is the discriminant times the square of the leading coefficient,
   which is ``c t`` with ``c != 0``); if ``G(l0) = 0`` and ``P~(l0, t*) = 0``, the resultant
   vanishes; ``l0 = 0`` is excluded by step 3 (``QX = 0`` would make ``p`` a singular point).
   The remaining case, ``l0`` a multiple root of ``G`` with ``P~(l0, t*) != 0``, is not
   excluded by an argument here: the searches below find no pair where it decides.

What is checked and how.  Steps 1, 3, 4 symbolically; step 5's resultant and discriminant
on exact constructions (two spheres, concentric and homothetic ellipsoids, a sphere on the
axis of a cylinder: the symmetric pencils with a structural multiple root); the whole claim
against the predicate itself at rationals a relative ``1e-12`` on either side of the answer,
on random exact pairs of every type (evidence: a missed candidate below the answer would
make the predicate true below it); and ``scale="both"`` against the Perram-Wertheim contact
function computed by its own maximum formula (a cross-check).

Not proven here: step 5's last case, a tangency at a multiple root of the structural factor
``G`` at which ``P~`` does not vanish; the bracketing search supports the claim there.

The certificate of the compiled kernel for ``scale="both"``
(:mod:`quadric_contact.modes.distance.scale_both`).  With ``f = 1 + E(x) / r_E`` and
``g = 1 + Q(x) / r_Q`` (``r_E = -det E / det A``, ``r_Q = -det Q / det B``; the scaled solids are
``f <= s^2`` and ``g <= s^2``), ``s*^2 = min_x max(f(x), g(x))``: the solids scaled by ``s``
meet iff some ``x`` has ``max(f, g) <= s^2``, and the minimum is attained (``max(f, g)`` is
continuous and tends to infinity).  The two bounds:

Upper: any point ``x`` gives ``s*^2 <= max(f(x), g(x))`` (it lies in both solids scaled by
``sqrt(max(f, g))``); the kernel takes ``x(mu) = Y[:3] / Y_4``, ``Y = adj(E + mu Q) e_4``,
where ``E(x) = Y^T E Y / Y_4^2`` (check ``both_bounds_identities``).
Lower: for ``mu >= 0`` and every ``x``, with the weights ``r_E > 0`` and ``mu r_Q >= 0``,
``max(f, g) >= (r_E f + mu r_Q g) / (r_E + mu r_Q) = 1 + (E(x) + mu Q(x)) / (r_E + mu r_Q)``
(a weighted mean is at most the larger value).  So ``s*^2 = max(f, g)`` at its minimiser is at
least the least value over ``x`` of the right side, which is
``1 + det M / (det M_00 (r_E + mu r_Q))`` for ``M = E + mu Q`` (``M_00 = A + mu B`` is positive
definite: ``X^T M X`` is convex in ``x``, stationary at ``x(mu)`` as the first three entries of
``M Y`` vanish, and its value there is ``det M / Y_4``), that is
``L(mu) = 1 - det M det A det B / (Y_4 (det E det B + mu det Q det A))``.

Neither bound assumes anything of ``mu`` but ``mu >= 0``, so a multiplier found by a float
search certifies ``L(mu) <= s*^2 <= max(f, g)(x(mu))`` whatever its accuracy; at the
Perram-Wertheim multiplier (``f = g`` at ``x(mu)``) the two meet, and for two spheres that
multiplier is ``r_1 / r_2`` (check ``both_bounds_meet_for_spheres``).  The checks: the
identities symbolically, the closed form for two spheres, and the enclosure against the exact
scale on random exact pairs at multipliers near and far from the optimum (evidence).
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import sympy as sp

from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure, search_settings

from ._plane_pencil import LAM, ellipsoid_matrix

proof = Proof(
    "First-contact scale",
    "the first touch of E scaled about its centre is the root of the scaled pencil's discriminant chosen",
    not_proven=(
        "step 5's last case (a tangency at a multiple root of the structural factor G that the "
        "scale leaves unchanged) is not excluded by an argument; the searches find no pair where "
        "it decides"
    ),
)


def _sym(name: str, n: int) -> sp.Matrix:
    return sp.Matrix(n, n, lambda i, j: sp.Symbol(f"{name}{min(i, j)}{max(i, j)}", real=True))


@proof.check(
    "det(l E_t + Q) = det(l E_0 + Q) - t r l det(l A + Q_00): affine in t = s^2",
    method=Method.IDENTITY,
)
def affine_in_the_scale() -> Finding:
    A = _sym("a", 3)
    c = sp.Matrix(sp.symbols("c0:3", real=True))
    r, t = sp.symbols("r t", positive=True)
    Q = _sym("q", 4)
    E1 = ellipsoid_matrix(A, c)  # (x - c)^T A (x - c) - 1
    Et = E1.copy()
    Et[3, 3] = (c.T * A * c)[0, 0] - t * r
    # E_t is the scaled ellipsoid: (x - c)^T A (x - c) - t r
    x = sp.Matrix(sp.symbols("x0:3", real=True))
    X = x.col_join(sp.Matrix([1]))
    ensure(
        sp.expand((X.T * Et * X)[0, 0] - (((x - c).T * A * (x - c))[0, 0] - t * r)) == 0,
        "E_t is (x - c)^T A (x - c) - t r",
    )
    E0 = Et.subs(t, 0)
    lhs = (LAM * Et + Q).det(method="berkowitz")
    rhs = (LAM * E0 + Q).det(method="berkowitz") - t * r * LAM * (LAM * A + Q[:3, :3]).det(method="berkowitz")
    ensure(sp.expand(lhs - rhs) == 0, "affine in t with the cofactor as slope")
    return agrees("P(l, t) = P_0(l) + t B(l) with B(l) = -r l det(l A + Q_00), for every symmetric Q")


@proof.check(
    "parallel gradients at a common point make X = (p, 1) a kernel vector of l0 E + Q",
    method=Method.IDENTITY,
)
def tangency_is_a_kernel_vector() -> Finding:
    E, Q = _sym("e", 4), _sym("q", 4)
    p = sp.Matrix(sp.symbols("p0:3", real=True))
    X = p.col_join(sp.Matrix([1]))
    l0 = sp.Symbol("l0", real=True)
    v = (l0 * E + Q) * X
    # the first three entries are (l0 grad e + grad q) / 2
    grad = [sp.diff((X.T * M * X)[0, 0], pi) for M in (E, Q) for pi in p]
    for i in range(3):
        ensure(sp.expand(2 * v[i] - (l0 * grad[i] + grad[3 + i])) == 0, f"entry {i} is half the gradient sum")
    # and X^T v = l0 e(p) + q(p) = v[3] + sum p_i v[i]
    ensure(sp.expand((X.T * v)[0, 0] - v[3] - sum(p[i] * v[i] for i in range(3))) == 0, "last entry")
    return agrees(
        "(l0 E + Q) X = ((l0 grad e + grad q) / 2, w) and X^T (l0 E + Q) X = w + p . 0: with parallel "
        "gradients (l0 grad e + grad q = 0) and p on both surfaces, w = 0, so X is a kernel vector"
    )


@proof.check(
    "Jacobi: P'(l) = tr(adj(l E + Q) E); at a kernel vector X of rank 3 with X^T E X = 0, P'(l0) = 0",
    method=Method.IDENTITY,
)
def jacobi_multiple_root() -> Finding:
    E, Q = _sym("e", 4), _sym("q", 4)
    M = LAM * E + Q
    P = M.det(method="berkowitz")
    ensure(sp.expand(sp.diff(P, LAM) - (M.adjugate(method="berkowitz") * E).trace()) == 0, "Jacobi's formula")
    # a symmetric matrix of rank 3 with kernel X: adj = k X X^T.  Built exactly: B diag(d, 0) B^T
    # with B invertible, whose kernel is spanned by the last column of B^-T.
    d = sp.symbols("d0:3", nonzero=True)
    B = sp.Matrix([[1, 2, 0, 1], [0, 1, 3, 0], [1, 0, 1, 2], [0, 1, 1, 1]])
    S = B * sp.diag(*d, 0) * B.T
    X = B.T.inv()[:, 3]
    ensure(sp.simplify(S * X) == sp.zeros(4, 1), "X spans the kernel")
    adj = S.adjugate()
    k = sp.simplify(adj[0, 0] / X[0] ** 2)
    ensure(sp.simplify(adj - k * X * X.T) == sp.zeros(4, 4), "adj = k X X^T")
    return agrees(
        "P' = tr(adj(l E + Q) E) (Jacobi), and a symmetric matrix of rank 3 with kernel X has "
        "adj = k X X^T (rank <= 2: adj = 0): P'(l0) = k X^T E X = 0, so l0 is a multiple root"
    )


@proof.check(
    "symmetric pencils with a structural multiple root: the resultant factor holds the first touch",
    method=Method.CONSTRUCTION,
)
def structural_roots() -> Finding:
    from quadric_contact import Quadric
    from quadric_contact.theory.contact_scale import contact_scale_exact

    cases: list[tuple[str, Any, Any, Fraction]] = [
        # name, E, Q, the first-contact scale by elementary geometry
        ("two unit spheres 4 apart", Quadric.sphere(1), Quadric.sphere(1, (4, 0, 0)), Fraction(3)),
        (
            "a unit sphere at the centre of a sphere of radius 3",
            Quadric.sphere(1),
            Quadric.sphere(3),
            Fraction(3),
        ),
        (
            "homothetic ellipsoids with one centre",
            Quadric.ellipsoid(1, 2, 3, (1, 1, 1)),
            Quadric.ellipsoid(Fraction(1, 2), 1, Fraction(3, 2), (1, 1, 1)),
            Fraction(1, 2),
        ),
        (
            "a unit sphere on the axis of a cylinder of radius 2",
            Quadric.sphere(1),
            Quadric.elliptic_cylinder(2, 2),
            2,
        ),
        ("a unit sphere 5 from a plane", Quadric.sphere(1), Quadric.plane((0, 0, 1), 5), Fraction(5)),
        (
            "coaxial spheroids",
            Quadric.ellipsoid(1, 1, 2),
            Quadric.ellipsoid(2, 2, 1, (0, 0, 7)),
            Fraction(3),  # the axis: E's pole at s*2 meets Q's pole at 7 - 1
        ),
    ]
    for name, e, q, want in cases:
        got = contact_scale_exact(e, q)
        ensure(got.scale == want, f"{name}: {got.scale} != {want}")
    return agrees("; ".join(f"{n}: s* = {w}" for n, _, _, w in cases))


def _predicate_around(e: Any, q: Any) -> str:
    from quadric_contact.theory.contact_scale import contact_scale_exact, reached_at

    got = contact_scale_exact(e, q)
    if got.scale.sign() == 0:
        return "zero"
    eps = Fraction(1, 10**12)
    t = got.squared
    t.refine(t.hi * eps / 16)
    lo, hi = t.lo * (1 - eps), t.hi * (1 + eps)
    ensure(not reached_at(e, q, lo, "E"), f"{e} / {q}: the solid reaches the surface below s*")
    ensure(reached_at(e, q, hi, "E"), f"{e} / {q}: the solid does not reach the surface above s*")
    return q.kind.name


@proof.search(
    "random exact pairs of every type: the predicate is false 1e-12 below t* and true 1e-12 above",
    examples=12,
    large=150,
    detail="ellipsoids moved by rational motions against quadrics of every type with a solid",
)
def predicate_brackets_the_answer(examples: int) -> Finding:
    from hypothesis import given
    from hypothesis import strategies as st

    from quadric_contact.testing.strategies import ellipsoids, quadrics

    seen: dict[str, int] = {}

    @search_settings(examples)
    @given(e=ellipsoids(max_axis=2), q=quadrics(max_param=4) | quadrics("plane"), sym=st.booleans())
    def search(e: Any, q: Any, sym: bool) -> None:
        if sym:  # a sphere: the symmetric pencils
            from quadric_contact import Quadric

            centre = e.center()
            e = Quadric.sphere(Fraction(1, 2), centre)
        kind = _predicate_around(e, q)
        seen[kind] = seen.get(kind, 0) + 1

    search()
    return agrees(", ".join(f"{v} {k.lower()}" for k, v in sorted(seen.items())) + ": bracketed")


PW_EXAMPLES = 80


@proof.check(
    "two ellipsoids scaled together: s*^2 equals the Perram-Wertheim function by its maximum formula",
    method=Method.CROSS_CHECK,
    full=True,
    size=f"{PW_EXAMPLES} hypothesis examples, F = max over l in [0, 1] of "
    "l (1 - l) d^T ((1 - l) A^-1 + l B^-1)^-1 d, golden section",
    requires=("hypothesis",),
)
def perram_wertheim() -> Finding:
    examples = PW_EXAMPLES
    import mpmath
    from hypothesis import given

    from quadric_contact.exact.precision import working_precision
    from quadric_contact.testing.strategies import ellipsoids
    from quadric_contact.theory.contact_scale import contact_scale_exact

    worst = [mpmath.mpf(0)]

    def mat(q: Any) -> Any:
        return mpmath.matrix([[mpmath.mpf(x.numerator) / x.denominator for x in row] for row in q.matrix])

    def shape(q: Any) -> tuple[Any, Any]:
        M = mat(q)
        A, b = M[:3, :3], M[:3, 3]
        c = -(A**-1) * b
        r = (c.T * A * c)[0] - M[3, 3]
        return A / r, c

    @search_settings(examples)
    @given(e=ellipsoids(max_axis=2), q=ellipsoids(max_axis=2))
    def search(e: Any, q: Any) -> None:
        got = contact_scale_exact(e, q, scale="both")
        with working_precision(dps=50):
            A, ca = shape(e)
            B, cb = shape(q)
            Ai, Bi, d = A**-1, B**-1, cb - ca

            def F(lam: Any) -> Any:
                return lam * (1 - lam) * (d.T * ((1 - lam) * Ai + lam * Bi) ** -1 * d)[0]

            lo, hi, phi = mpmath.mpf(0), mpmath.mpf(1), (mpmath.sqrt(5) - 1) / 2
            while hi - lo > mpmath.mpf(10) ** -24:
                m1, m2 = hi - phi * (hi - lo), lo + phi * (hi - lo)
                lo, hi = (m1, hi) if F(m1) < F(m2) else (lo, m2)
            want = F((lo + hi) / 2)
            err = abs(mpmath.mpf(got.squared.decimal(45)) - want) / max(1, want)
            ensure(err < mpmath.mpf(10) ** -35, f"{e} / {q}: {got.squared} against {want}")
            worst[0] = max(worst[0], err)

    search()
    return agrees(f"agree to a relative {mpmath.nstr(worst[0], 3)} or better (40 digits asked)")


@proof.check(
    "scale both: M adj(M) e_4 = det(M) e_4 and det E = -r det A, so x(mu) = Y[:3] / Y_4 is "
    "stationary, X^T M X = det M / Y_4 there, and the kernel's formulas of f, g and L(mu) hold",
    method=Method.IDENTITY,
)
def both_bounds_identities() -> Finding:
    M = _sym("m", 4)
    Y = M.adjugate(method="berkowitz")[:, 3]
    e4 = sp.Matrix([0, 0, 0, 1])
    ensure(sp.expand(M * Y - M.det(method="berkowitz") * e4) == sp.zeros(4, 1), "M Y = det M e_4")
    # hence the first three entries of M X vanish at X = Y / Y_4 (the gradient of X^T M X in x
    # is twice them) and X^T M X = X^T (det M / Y_4) e_4 = det M / Y_4
    A = _sym("a", 3)
    c = sp.Matrix(sp.symbols("c0:3", real=True))
    r = sp.Symbol("r", positive=True)
    E = ellipsoid_matrix(A, c)
    E[3, 3] = (c.T * A * c)[0, 0] - r  # (x - c)^T A (x - c) - r
    ensure(sp.expand(E.det(method="berkowitz") + r * A.det(method="berkowitz")) == 0, "det E = -r det A")
    # f(x(mu)) = 1 + E(x) / r_E with E(x) = Y^T E Y / Y_4^2 and r_E = -det E / det A
    TE, Y4, dE, dA, dB, dQ, dM, mu, EQ = sp.symbols("T_E Y_4 dE dA dB dQ dM mu EQ", real=True)
    f = 1 + (TE / Y4**2) / (-dE / dA)
    ensure(sp.simplify(f - (1 - TE * dA / (Y4**2 * dE))) == 0, "f(x(mu))")
    # the weighted mean: (r_E f + mu r_Q g) / (r_E + mu r_Q) = 1 + (E(x) + mu Q(x)) / (r_E + mu r_Q)
    rE, rQ, Ex, Qx = sp.symbols("r_E r_Q E_x Q_x", positive=True)
    mean = (rE * (1 + Ex / rE) + mu * rQ * (1 + Qx / rQ)) / (rE + mu * rQ)
    ensure(sp.simplify(mean - (1 + (Ex + mu * Qx) / (rE + mu * rQ))) == 0, "the weighted mean")
    L = 1 + (dM / Y4) / (-dE / dA - mu * dQ / dB)
    ensure(sp.simplify(L - (1 - dM * dA * dB / (Y4 * (dE * dB + mu * dQ * dA)))) == 0, "L(mu)")
    return agrees(
        "M adj(M) = det(M) I gives the stationary point and the Schur complement det M / Y_4; "
        "det E = -r det A; f(x(mu)) = 1 - (Y^T E Y) det A / (Y_4^2 det E); the weighted mean is "
        "1 + (E + mu Q) / (r_E + mu r_Q); "
        "L(mu) = 1 - det M det A det B / (Y_4 (det E det B + mu det Q det A))"
    )


@proof.check(
    "scale both, two spheres (radii r1, r2, centres d apart): at mu = r1 / r2 the lower and the "
    "upper bound both equal (d / (r1 + r2))^2",
    method=Method.IDENTITY,
)
def both_bounds_meet_for_spheres() -> Finding:
    r1, r2, d = sp.symbols("r1 r2 d", positive=True)
    x = sp.Matrix(sp.symbols("x0:3", real=True))
    X = x.col_join(sp.Matrix([1]))
    E = sp.diag(1, 1, 1, -(r1**2))
    Q = sp.diag(1, 1, 1, d**2 - r2**2)
    Q[0, 3] = Q[3, 0] = -d
    mu = r1 / r2
    M = E + mu * Q
    Y = M.adjugate(method="berkowitz")[:, 3]
    want = (d / (r1 + r2)) ** 2
    detA = detB = sp.Integer(1)
    detE, detQ = E.det(), Q.det()
    L = 1 - M.det() * detA * detB / (Y[3] * (detE * detB + mu * detQ * detA))
    f = 1 - (Y.T * E * Y)[0] * detA / (Y[3] ** 2 * detE)
    g = 1 - (Y.T * Q * Y)[0] * detB / (Y[3] ** 2 * detQ)
    for name, v in (("L", L), ("f", f), ("g", g)):
        ensure(sp.simplify(v - want) == 0, f"{name} = (d / (r1 + r2))^2")
    # and f, g are the scaled forms: the sphere E scaled by s is |x|^2 <= s^2 r1^2
    ensure(sp.expand((X.T * E * X)[0] + r1**2 - r1**2 * (1 + (X.T * E * X)[0] / r1**2)) == 0, "f")
    return agrees("L(r1 / r2) = f(x) = g(x) = d^2 / (r1 + r2)^2: the bounds meet, s* = d / (r1 + r2)")


def _both_bounds(e: Any, q: Any, mu: Fraction) -> tuple[Fraction, Fraction]:
    """``L(mu)`` and ``max(f, g)`` at ``x(mu)``, exactly."""
    E, Q = sp.Matrix(e.matrix), sp.Matrix(q.matrix)
    if E[0, 0] < 0:
        E = -E
    if Q[0, 0] < 0:
        Q = -Q
    m = sp.Rational(mu.numerator, mu.denominator)
    M = E + m * Q
    Y = M.adjugate()[:, 3]
    dA, dB, dE, dQ = E[:3, :3].det(), Q[:3, :3].det(), E.det(), Q.det()
    L = 1 - M.det() * dA * dB / (Y[3] * (dE * dB + m * dQ * dA))
    f = 1 - (Y.T * E * Y)[0] * dA / (Y[3] ** 2 * dE)
    g = 1 - (Y.T * Q * Y)[0] * dB / (Y[3] ** 2 * dQ)
    return Fraction(str(L)), Fraction(str(max(f, g)))


def _float_multiplier(e: Any, q: Any) -> Fraction:
    """The multiplier with ``f = g`` at ``x(mu)``, by bisection in ``log mu`` in binary64 (a
    search: nothing relies on its accuracy)."""
    import numpy as np

    E, Q = (np.array(m.matrix, dtype=float) for m in (e, q))
    E, Q = (E if E[0, 0] > 0 else -E), (Q if Q[0, 0] > 0 else -Q)
    rE = -np.linalg.det(E) / np.linalg.det(E[:3, :3])
    rQ = -np.linalg.det(Q) / np.linalg.det(Q[:3, :3])

    def f_minus_g(mu: float) -> float:
        M = E + mu * Q
        X = np.append(np.linalg.solve(M[:3, :3], -M[:3, 3]), 1.0)
        return float((X @ E @ X) / rE - (X @ Q @ X) / rQ)

    lo, hi = -60.0, 60.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f_minus_g(math.exp(mid)) < 0 else (lo, mid)
    return Fraction(math.exp(0.5 * (lo + hi)))


@proof.search(
    "scale both: the exact s*^2 of random exact pairs lies between L(mu) and max(f, g) at x(mu), "
    "at multipliers near and far from the optimum",
    examples=6,
    large=40,
    detail="ellipsoids moved by rational motions; mu the optimum in binary64, and 1/3 and 3 times it",
)
def both_bounds_enclose(examples: int) -> Finding:
    from hypothesis import given

    from quadric_contact.testing.strategies import ellipsoids
    from quadric_contact.theory.contact_scale import contact_scale_exact

    gaps: list[float] = []

    @search_settings(examples)
    @given(e=ellipsoids(max_axis=2), q=ellipsoids(max_axis=2))
    def search(e: Any, q: Any) -> None:
        got = contact_scale_exact(e, q, scale="both")
        if got.squared.sign() == 0:
            return
        mu = _float_multiplier(e, q)
        lo, hi = _both_bounds(e, q, mu)
        best = hi - lo
        for m in (mu, mu / 3, mu * 3):
            lo, hi = _both_bounds(e, q, m)
            ensure(got.squared.compare(lo) >= 0, f"{e} / {q}: L({m}) = {lo} above s*^2")
            ensure(got.squared.compare(hi) <= 0, f"{e} / {q}: max(f, g) at x({m}) = {hi} below s*^2")
        gaps.append(float(best / hi))

    search()
    return agrees(
        f"{len(gaps)} pairs enclosed at three multipliers each; the bounds at the binary64 optimum "
        f"apart by at most {max(gaps, default=0.0):.1e} relative"
    )
