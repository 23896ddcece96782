"""Table 2 reduces to Table 1 under rigid motions: a symbolic check (sympy).

1. The invariants Table 2 uses are invariant under the generators of the
   rigid motions (translations, rotations about each axis, rationally
   parametrised), symbolically: ``det Q``, the characteristic polynomial of
   ``Q00`` and ``J`` always; ``K`` when ``det Q00 = det Q = 0`` (the
   cylinders) and ``J'`` when ``Q00`` has rank 1 and ``K = 0`` (parallel
   planes), the only rows that use them (``K`` and ``J'`` are not invariant
   under translations in general).  Scaling ``Q`` by ``k > 0`` scales them by
   ``k^4, k, k^2, k^3, k^2`` and leaves every Table 2 quantity of Table 1
   (``a = a'd'``, ``a^2 = a'^2 L``, ...) unchanged.
2. On the standard forms of Table 1 (symbolic parameters) the printed
   formulas of Table 2 give back the Table 1 parameters and conditions,
   except where the paper is misprinted: the parabolic cylinder's
   ``d'^2 = 4 K a'^2`` (gives -1 instead of 1) and the hyperbolic cylinder's
   size condition (``M b'`` instead of ``M a'``).
"""

from __future__ import annotations

import pytest
import sympy as sp

from quadric_contact import QuadricKind, paper

K = QuadricKind
a, b, c, k = sp.symbols("a b c k", positive=True)
al, be, ga = sp.symbols("alpha beta gamma", positive=True)
s, t1, t2, t3 = sp.symbols("s t1 t2 t3", real=True)


def standard(kind):
    d = sp.diag
    if kind is K.ELLIPSOID:
        return d(1 / a**2, 1 / b**2, 1 / c**2, -1)
    if kind is K.HYPERBOLOID_ONE_SHEET:
        return d(1 / a**2, 1 / b**2, -1 / c**2, -1)
    if kind is K.HYPERBOLOID_TWO_SHEETS:
        return d(1 / a**2, 1 / b**2, -1 / c**2, 1)
    if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        m = d(1 / a**2, (1 if kind is K.ELLIPTIC_PARABOLOID else -1) / b**2, 0, 0)
        m[2, 3] = m[3, 2] = sp.Rational(-1, 2)
        return m
    if kind is K.ELLIPTIC_CYLINDER:
        return d(1 / a**2, 1 / b**2, 0, -1)
    if kind is K.HYPERBOLIC_CYLINDER:
        return d(1 / a**2, -1 / b**2, 0, -1)
    if kind is K.PARABOLIC_CYLINDER:
        m = d(1 / a**2, 0, 0, 0)
        m[2, 3] = m[3, 2] = sp.Rational(-1, 2)
        return m
    return d(1 / a**2, 0, 0, -1)  # parallel planes


def invariants(Q):
    A = Q[:3, :3]
    J = sum(A.extract([i, j], [i, j]).det() for i, j in ((0, 1), (0, 2), (1, 2)))
    Kv = sum(
        Q.extract([r for r in range(4) if r != i], [r for r in range(4) if r != i]).det() for i in range(3)
    )
    Jp = sum(Q.extract([i, 3], [i, 3]).det() for i in range(3))
    lam = sp.Symbol("lam")
    return {
        "det": sp.cancel(Q.det()),
        "charpoly": sp.Poly(sp.expand((A - lam * sp.eye(3)).det()), lam),
        "J": sp.cancel(J),
        "K": sp.cancel(Kv),
        "J'": sp.cancel(Jp),
        "det00": sp.cancel(A.det()),
        "rank00": A.rank(),
    }


def _motions():
    cs, sn = (1 - s**2) / (1 + s**2), 2 * s / (1 + s**2)
    rx = sp.Matrix([[1, 0, 0], [0, cs, -sn], [0, sn, cs]])
    ry = sp.Matrix([[cs, 0, sn], [0, 1, 0], [-sn, 0, cs]])
    rz = sp.Matrix([[cs, -sn, 0], [sn, cs, 0], [0, 0, 1]])
    out = []
    for R in (rx, ry, rz):
        H = sp.eye(4)
        H[:3, :3] = R
        out.append(H)
    T = sp.eye(4)
    T[:3, 3] = sp.Matrix([t1, t2, t3])
    out.append(T)
    return out


@pytest.mark.parametrize("kind", [kd for kd in K if kd.in_table_1])
def test_invariants_under_rigid_motions_and_scaling(kind):
    Q = standard(kind)
    base = invariants(Q)
    for H in _motions():
        Hi = H.inv()
        moved = (Hi.T * Q * Hi).applyfunc(sp.cancel)
        inv = invariants(moved)
        assert sp.simplify(inv["det"] - base["det"]) == 0
        assert (inv["charpoly"] - base["charpoly"]).is_zero
        assert sp.simplify(inv["J"] - base["J"]) == 0
        if base["det00"] == 0 and base["det"] == 0:  # cylinders: the rows that use K
            assert sp.simplify(inv["K"] - base["K"]) == 0
        if base["rank00"] == 1 and base["K"] == 0:  # parallel planes: the row that uses J'
            assert sp.simplify(inv["J'"] - base["J'"]) == 0
    scaled = invariants(k * Q)
    assert sp.simplify(scaled["det"] - k**4 * base["det"]) == 0
    assert sp.simplify(scaled["J"] - k**2 * base["J"]) == 0
    assert sp.simplify(scaled["K"] - k**3 * base["K"]) == 0
    assert sp.simplify(scaled["J'"] - k**2 * base["J'"]) == 0


def _printed_table_2(kind, inv, eig, scale=1):
    """The printed Table 2 row on given invariants (eigenvalues assigned as printed).

    Returns (Table 1 parameters squared as printed-formula expressions, printed
    condition sides squared)."""
    det, J, Kv, Jp = inv["det"], inv["J"], inv["K"], inv["J'"]
    kE2 = ga**2 / al**4  # standard E: alpha' = alpha, ..., delta' = 1 (checked below)
    if kind in (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS):
        ap2, bp2, cp2 = 1 / eig[0], 1 / eig[1], (1 if kind is K.ELLIPSOID else -1) / eig[2]
        sign = {K.ELLIPSOID: -1, K.HYPERBOLOID_ONE_SHEET: 1, K.HYPERBOLOID_TWO_SHEETS: -1}[kind]
        dp2 = sign * ap2 * bp2 * cp2 * det
        params = {"a": ap2 * dp2, "b": bp2 * dp2, "c": cp2 * dp2}
        if kind is K.ELLIPSOID:
            conds = [(dp2 * cp2, "size"), (ap2 / (dp2 * cp2**2), "curv")]
        elif kind is K.HYPERBOLOID_ONE_SHEET:
            conds = [(bp2 * dp2, "size"), (ap2 / (dp2 * cp2**2), "curv")]
        else:
            conds = [(cp2 * dp2, "size"), (cp2 / (dp2 * bp2**2), "curv")]
    elif kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
        ap2 = 1 / eig[0]
        bp2 = (1 if kind is K.ELLIPTIC_PARABOLOID else -1) / eig[1]
        L2 = -4 * det / J
        L = sp.sqrt(L2)
        params = {"a": ap2 * L, "b": bp2 * L}
        conds = [(4 / (L2 * bp2**2), "curv")]
    elif kind in (K.ELLIPTIC_CYLINDER, K.HYPERBOLIC_CYLINDER):
        ap2 = 1 / eig[0]
        bp2 = (1 if kind is K.ELLIPTIC_CYLINDER else -1) / eig[1]
        M2 = -Kv / J
        params = {"a": ap2 * M2, "b": bp2 * M2}
        conds = [(M2 * bp2, "size"), (ap2 / (M2 * bp2**2), "curv")]
    elif kind is K.PARABOLIC_CYLINDER:
        ap2 = 1 / eig[0]
        dp2 = 4 * Kv * ap2  # as printed
        params = {"a": ap2 * sp.sqrt(dp2)}
        conds = [(4 / (dp2 * ap2**2), "curv")]
    else:
        ap2 = 1 / eig[0]
        dp2 = -ap2 * Jp
        params = {"a": ap2 * dp2}
        conds = [(ap2 * dp2, "size")]
    return params, conds, kE2


TABLE_1 = {  # squared sides of Table 1 (size: X^2 >= alpha^2; curvature: kappa^2 <= gamma^2/alpha^4)
    K.ELLIPSOID: [c**2, a**2 / c**4],
    K.HYPERBOLOID_ONE_SHEET: [b**2, a**2 / c**4],
    K.HYPERBOLOID_TWO_SHEETS: [c**2, c**2 / b**4],
    K.ELLIPTIC_PARABOLOID: [4 / b**4],
    K.HYPERBOLIC_PARABOLOID: [4 / b**4],
    K.ELLIPTIC_CYLINDER: [b**2, a**2 / b**4],
    K.HYPERBOLIC_CYLINDER: [a**2, a**2 / b**4],
    K.PARABOLIC_CYLINDER: [4 / a**4],
    K.PARALLEL_PLANES: [a**2],
}

EIGEN = {  # the diagonal entries of the standard Q00, assigned as Table 2 prints them
    K.ELLIPSOID: (0, 1, 2),
    K.HYPERBOLOID_ONE_SHEET: (0, 1, 2),
    K.HYPERBOLOID_TWO_SHEETS: (0, 1, 2),
    K.ELLIPTIC_PARABOLOID: (0, 1),
    K.HYPERBOLIC_PARABOLOID: (0, 1),
    K.ELLIPTIC_CYLINDER: (0, 1),
    K.HYPERBOLIC_CYLINDER: (0, 1),
    K.PARABOLIC_CYLINDER: (0,),
    K.PARALLEL_PLANES: (0,),
}


@pytest.mark.parametrize("kind", [kd for kd in K if kd.in_table_1])
def test_table_2_reduces_to_table_1(kind):
    E = sp.diag(1 / al**2, 1 / be**2, 1 / ga**2, -1)
    # the ellipsoid row of Table 2 for E: alpha' = alpha, delta'^2 = -alpha^2 beta^2 gamma^2 det E = 1
    assert sp.simplify(-(al**2) * be**2 * ga**2 * E.det()) == 1
    Q = standard(kind)
    eig = [Q[i, i] for i in EIGEN[kind]]
    for scale in (1, k):  # the same on k*Q: Table 2 is scale invariant
        inv_s = invariants(scale * Q)
        eig_s = [scale * e for e in eig]
        params, conds, kE2 = _printed_table_2(kind, inv_s, eig_s)
        expected = TABLE_1[kind]
        misprinted = set()
        for (side, what), want in zip(conds, expected, strict=True):
            same = sp.simplify(side - want) == 0
            if not same:
                misprinted.add(what)
        if kind is K.PARABOLIC_CYLINDER:
            assert misprinted == {"curv"}  # d'^2 = 4 K a'^2 = -1
            assert sp.simplify(4 * inv_s["K"] / eig_s[0]) == -(scale**2)  # printed d'^2 < 0
            d_corrected = sp.sqrt(sp.simplify(-4 * inv_s["K"] / eig_s[0]))  # d'^2 = -4 K a'^2
            assert sp.simplify(d_corrected / eig_s[0] - a**2) == 0  # a^2 = a'^2 d'
            assert sp.simplify(4 / (d_corrected * (1 / eig_s[0])) ** 2 - TABLE_1[kind][0]) == 0
        elif kind is K.HYPERBOLIC_CYLINDER:
            assert misprinted == {"size"}  # M b' instead of M a'
            ap2, M2 = 1 / eig_s[0], -inv_s["K"] / inv_s["J"]
            assert sp.simplify(M2 * ap2 - a**2) == 0  # corrected: M a' >= delta' alpha'
        else:
            assert not misprinted, (kind, misprinted)
            for name, value in params.items():
                assert sp.simplify(value - {"a": a, "b": b, "c": c}[name] ** 2) == 0
    assert sp.simplify(TABLE_1[kind][-1] if kind is not K.PARALLEL_PLANES else 1) != 0
    assert any(e.key == "table-2-parabolic-cylinder-d" for e in paper.ERRATA)
