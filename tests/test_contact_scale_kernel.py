"""The compiled first-contact scale on stacks: every enclosure holds the exact scale of the
scalar path, the pairs the kernel leaves are answered exactly, bad input is refused."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.exact.errors import NonFiniteError, NotSymmetricError
from quadric_contact.modes.distance.scale_blocks import scale_stack


def _ellipsoids(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        A = R @ np.diag(1 / rng.uniform(0.2, 1.5, 3) ** 2) @ R.T
        A = (A + A.T) / 2
        c = rng.uniform(-3, 3, 3)
        M = np.zeros((4, 4))
        M[:3, :3] = A
        M[:3, 3] = M[3, :3] = -A @ c
        M[3, 3] = c @ A @ c - 1
        out.append(M)
    return np.array(out)


def _holds(enc, e, q):
    s = qc.contact_scale(Quadric(e.tolist()), Quadric(q.tolist())).scale
    return s.compare(Fraction(enc[0])) >= 0 and s.compare(Fraction(enc[1])) <= 0


OTHERS = {
    "hyperboloid": "x**2 + y**2 - z**2/4 - 1",
    "two sheets": "z**2 - x**2 - y**2/4 - 1",
    "paraboloid": "x**2 + 2*y**2 - z",
    "saddle": "x**2 - y**2 - z",
    "plane": "x + 2*y - 2*z - 1",
    "cylinder": "x**2 + y**2/4 - 1",  # degenerate: the exact path
}


def test_two_ellipsoids_hold_the_exact_scale():
    Es, Qs = _ellipsoids(12, 1), _ellipsoids(12, 2)
    enc = qc.contact_scale(Es, Qs)
    assert enc.shape == (12, 2)
    assert all(_holds(enc[k], Es[k], Qs[k]) for k in range(12))
    assert np.median((enc[:, 1] - enc[:, 0]) / enc[:, 1]) < 1e-9


@pytest.mark.parametrize("name", list(OTHERS))
def test_other_types_hold_the_exact_scale(name):
    Q = np.array(Quadric.from_equation(OTHERS[name]).matrix, dtype=float)
    Es = _ellipsoids(4, 3)
    enc = qc.contact_scale(Es, Q)
    assert all(_holds(enc[k], Es[k], Q) for k in range(4))


def test_degenerate_pairs_are_left_to_the_exact_path():
    Q = np.array(Quadric.from_equation(OTHERS["cylinder"]).matrix, dtype=float)
    _, rest = scale_stack(_ellipsoids(3, 4), np.broadcast_to(Q, (3, 4, 4)))
    assert rest.all()
    centre_on_surface = np.array(Quadric.sphere(1, (1, 0, 0)).matrix, dtype=float)
    sphere = np.array(Quadric.sphere(1).matrix, dtype=float)
    enc, rest = scale_stack(centre_on_surface[None], sphere[None])
    assert rest[0]
    assert tuple(qc.contact_scale(centre_on_surface[None], sphere)[0]) == (0.0, 0.0)


def test_bad_input_is_refused():
    Es = _ellipsoids(2, 5)
    bad = Es.copy()
    bad[1, 0, 1] += 1e-9
    with pytest.raises(NotSymmetricError):
        qc.contact_scale(bad, Es[0])
    bad = Es.copy()
    bad[0, 2, 2] = np.nan
    with pytest.raises(NonFiniteError):
        qc.contact_scale(bad, Es[1])


def test_the_kernel_identities_in_exact_arithmetic():
    """``adj(E + mu Q) e_4 = det(A_mu) (x(mu), 1)``, ``f det(A_mu)^2 = Y^T Q Y``, the formula of
    ``s(mu)^2``, and ``f' = -2 g^T A_mu^-1 g``, derived with sympy on rational pairs."""
    import sympy as sp

    mu = sp.Symbol("mu")
    E = sp.Matrix(Quadric.ellipsoid(2, 1, Fraction(1, 2), center=(1, -2, Fraction(1, 3))).matrix)
    Q = sp.Matrix(Quadric.from_equation("x**2 - 2*y**2 + z**2/3 + x*y - z + 5").matrix)
    A, a = E[:3, :3], E[:3, 3]
    Am = A + mu * Q[:3, :3]
    x = -Am.inv() * (a + mu * Q[:3, 3])
    X = x.col_join(sp.Matrix([1]))
    Y = (E + mu * Q).adjugate()[:, 3]
    assert sp.simplify(Y - Am.det() * X) == sp.zeros(4, 1)
    f = sp.simplify((X.T * Q * X)[0])
    assert sp.simplify(f * Am.det() ** 2 - (Y.T * Q * Y)[0]) == 0
    c = -A.inv() * a
    r = (c.T * A * c)[0] - E[3, 3]
    s2 = ((x - c).T * A * (x - c))[0] / r
    formula = (Y[3] ** 2 * E.det() - (Y.T * E * Y)[0] * A.det()) / (Y[3] ** 2 * E.det())
    assert sp.simplify(s2 - formula) == 0
    g = Q[:3, :3] * x + Q[:3, 3]
    assert sp.simplify(sp.diff(f, mu) + 2 * (g.T * Am.inv() * g)[0]) == 0


# -- the block kernel against the scalar kernel ----------------------------------------------------


def _random_pairs(n, seed):
    from quadric_contact.testing.samples import random_ellipsoids

    rng = np.random.default_rng(seed)
    Es, _ = random_ellipsoids(n, rng)
    Qs, _ = random_ellipsoids(n, rng)
    return Es, Qs


def _agree(Es, Qs):
    """Blocks and the scalar kernel on the same pairs: a pair the blocks leave to the exact path
    is one the scalar kernel leaves too, and the two enclosures of every other pair meet."""
    from quadric_contact.modes.distance.scale_blocks import _scale_flags

    enc, flag = _scale_flags(Es, Qs)
    ref, rflag = _scale_flags(Es, Qs, blocks=False)
    assert set(np.unique(rflag)) <= {0, 1}
    assert not (flag == 1)[rflag == 0].any()
    both = (flag != 1) & (rflag == 0)
    assert (enc[both, 0] <= ref[both, 1]).all() and (ref[both, 0] <= enc[both, 1]).all()
    assert (enc[flag == 1] == [-np.inf, np.inf]).all()
    assert (enc[flag != 1, 0] >= 0).all() and (enc[flag != 1, 0] <= enc[flag != 1, 1]).all()
    return enc, flag, ref


def test_blocks_agree_with_the_scalar_kernel():
    Es, Qs = _random_pairs(20000, 7)
    enc, flag, ref = _agree(Es, Qs)
    ok = flag == 0
    assert ok.mean() > 0.99  # the blocks certify nearly every pair themselves
    width = (enc[ok, 1] - enc[ok, 0]) / enc[ok, 1]
    rwidth = (ref[ok, 1] - ref[ok, 0]) / ref[ok, 1]
    assert np.median(width) < 1e-9 and np.median(width) < 4 * np.median(rwidth)
    for k in np.flatnonzero(ok)[:6]:
        assert _holds(enc[k], Es[k], Qs[k])


@pytest.mark.parametrize("name", ["hyperboloid", "two sheets", "paraboloid", "saddle", "plane", "cylinder"])
def test_blocks_agree_on_other_types(name):
    Q = np.array(Quadric.from_equation(OTHERS[name]).matrix, dtype=float)
    Es, _ = _random_pairs(300, 8)
    Qs = np.broadcast_to(Q, Es.shape).copy()
    enc, flag, _ = _agree(Es, Qs)
    if name == "cylinder":
        assert (flag == 1).all()
    for k in range(3):
        if flag[k] != 1:
            assert _holds(enc[k], Es[k], Q)


def _scaled(E, t):
    """``E`` scaled by ``t`` about its centre."""
    A, a = E[:3, :3], E[:3, 3]
    c = -np.linalg.solve(A, a)
    r = c @ A @ c - E[3, 3]
    out = E.copy()
    out[3, 3] = E[3, 3] - (t * t - 1) * r
    return out


@pytest.mark.parametrize("delta", [1e-12, -1e-12, 1e-8, -1e-8, 1e-4])
def test_blocks_on_near_touching_pairs(delta):
    """``E`` grown until it all but touches ``Q`` (scale ``1 / (1 + delta)``)."""
    Es, Qs = _random_pairs(2000, 9)
    enc, rest = scale_stack(Es, Qs)
    keep = ~rest & (enc[:, 0] > 0.5)
    s = 0.5 * (enc[keep, 0] + enc[keep, 1])
    near = np.array([_scaled(e, t * (1 + delta)) for e, t in zip(Es[keep], s, strict=True)])
    enc2, flag, _ = _agree(near, Qs[keep])
    done = flag != 1
    assert done.mean() > 0.95
    target = 1 / (1 + delta)
    assert np.median(np.abs(0.5 * (enc2[done, 0] + enc2[done, 1]) - target)) < 1e-9
    for k in np.flatnonzero(done)[:2]:
        assert _holds(enc2[k], near[k], Qs[keep][k])


def test_a_pair_the_blocks_leave_goes_to_the_scalar_kernel():
    """``E``'s centre inside a long ``Q``: the root is far along the negative side, past the
    steps the blocks take; the scalar kernel answers, exactly as alone."""
    from quadric_contact.modes.distance.scale_blocks import _scale_flags

    E = np.array(Quadric.ellipsoid(0.1, 0.2, 0.3, center=(0.5, 0.3, 0.1)).matrix, dtype=float)
    Q = np.array(Quadric.ellipsoid(40, 1, 1).matrix, dtype=float)
    enc, flag = _scale_flags(E[None], Q[None])
    ref, rflag = _scale_flags(E[None], Q[None], blocks=False)
    assert flag[0] == 2 and rflag[0] == 0
    assert (enc == ref).all()
    assert _holds(enc[0], E, Q)
