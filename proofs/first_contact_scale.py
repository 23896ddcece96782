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
"""

from __future__ import annotations

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
