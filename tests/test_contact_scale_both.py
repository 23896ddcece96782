"""The compiled first-contact scale of two ellipsoids scaled together (``scale="both"``) on
stacks: every enclosure holds the exact scale of the scalar path, two spheres give their closed
form, the pairs the kernel leaves are answered exactly, bad input is refused."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.exact.errors import NonFiniteError, NotAnEllipsoidError, NotSymmetricError
from quadric_contact.modes.distance.scale_both import WIDTH, _flags, scale_both_stack
from quadric_contact.testing.samples import random_ellipsoids


def _exact(e, q):
    return qc.contact_scale(Quadric(e.tolist()), Quadric(q.tolist()), scale="both").scale


def _holds(enc, e, q):
    """``enc[0] <= s* <= enc[1]``, compared as exact numbers."""
    s = _exact(e, q)
    return s.compare(Fraction(enc[0])) >= 0 and s.compare(Fraction(enc[1])) <= 0


def _ellipsoid(axes, centre, seed):
    """An ellipsoid with the given semi-axes and centre, turned by a random rotation."""
    from quadric_contact.testing.samples import ellipsoid_matrix, random_rotations

    return ellipsoid_matrix(axes, random_rotations(1, np.random.default_rng(seed))[0], centre)


def _sphere(r, c):
    """The sphere ``|x - c|^2 - r^2`` (entries exact in binary64 for short dyadic ``r``, ``c``)."""
    M = np.eye(4)
    M[:3, 3] = M[3, :3] = -np.asarray(c, dtype=float)
    M[3, 3] = float(sum(Fraction(x) ** 2 for x in c) - Fraction(r) ** 2)
    assert Fraction(M[3, 3]) == sum(Fraction(x) ** 2 for x in c) - Fraction(r) ** 2
    return M


CASES = {
    "apart": ((1.0, 0.5, 0.3), (0, 0, 0), (0.4, 0.9, 0.2), (2.5, -1.0, 0.7)),
    "overlapping": ((1.0, 0.5, 0.3), (0, 0, 0), (0.4, 0.9, 0.2), (0.6, 0.2, -0.1)),
    "nearly concentric": ((1.0, 0.5, 0.3), (0.25, 0, 0), (0.4, 0.9, 0.2), (0.25, 1e-6, -2e-6)),
    "very different sizes": ((50.0, 30.0, 20.0), (1, 2, 3), (0.01, 0.02, 0.015), (60.0, 2.0, 3.0)),
    "one inside the other": ((3.0, 2.0, 2.5), (0, 0, 0), (0.1, 0.2, 0.3), (0.5, 0.3, -0.2)),
    "far apart": ((0.2, 0.3, 0.4), (-40, 10, 5), (0.5, 0.1, 0.3), (30, -20, 8)),
}


@pytest.mark.parametrize("name", list(CASES))
def test_enclosure_holds_the_exact_scale(name):
    ax1, c1, ax2, c2 = CASES[name]
    E, Q = _ellipsoid(ax1, c1, 1), _ellipsoid(ax2, c2, 2)
    enc = qc.contact_scale(E[None], Q[None], scale="both")
    assert enc.shape == (1, 2) and enc[0, 0] <= enc[0, 1]
    assert _holds(enc[0], E, Q)
    # the same pair given with the other sign and in the other order: the same scale
    enc2 = qc.contact_scale(-Q[None], -E[None], scale="both")
    assert _holds(enc2[0], Q, E)


def test_random_pairs_hold_the_exact_scale():
    rng = np.random.default_rng(11)
    Es, _ = random_ellipsoids(8, rng)
    Qs, _ = random_ellipsoids(8, rng)
    enc, rest = scale_both_stack(Es, Qs)
    assert not rest.any()
    assert ((enc[:, 1] - enc[:, 0]) <= WIDTH * enc[:, 1]).all()
    assert all(_holds(enc[k], Es[k], Qs[k]) for k in range(8))


def test_two_spheres_have_the_closed_form():
    """Radii ``r1``, ``r2`` at distance ``d``: ``s* = d / (r1 + r2)``; compared squared, as
    exact rationals (``d^2`` is rational for dyadic centres)."""
    rng = np.random.default_rng(5)
    n = 400
    cases = []
    for _ in range(n):
        r1, r2 = (float(x) for x in rng.integers(1, 64, 2) / 16)
        c1 = rng.integers(-256, 256, 3) / 32
        c2 = rng.integers(-256, 256, 3) / 32
        if (c1 == c2).all():
            c2[0] += 1
        cases.append((r1, c1, r2, c2))
    Es = np.array([_sphere(r1, c1) for r1, c1, _, _ in cases])
    Qs = np.array([_sphere(r2, c2) for _, _, r2, c2 in cases])
    enc, rest = scale_both_stack(Es, Qs)
    assert not rest.any()
    for (r1, c1, r2, c2), (lo, hi) in zip(cases, enc, strict=True):
        d2 = sum((Fraction(a) - Fraction(b)) ** 2 for a, b in zip(c1, c2, strict=True))
        t = d2 / (Fraction(r1) + Fraction(r2)) ** 2
        assert Fraction(lo) ** 2 <= t <= Fraction(hi) ** 2
    # one pair through the public function and the exact path: 1 and 2 at distance 6, s* = 2
    E, Q = _sphere(1, (0, 0, 0)), _sphere(2, (6, 0, 0))
    lo, hi = qc.contact_scale(E[None], Q[None], scale="both")[0]
    assert lo <= 2 <= hi and hi - lo < 1e-12
    assert _exact(E, Q) == 2


def test_a_stack_of_one_holds_the_scalar_answer():
    E = _ellipsoid((1.0, 0.7, 0.4), (0.5, -0.2, 1.0), 3)
    Q = _ellipsoid((0.3, 0.8, 0.5), (2.0, 1.0, -0.5), 4)
    scalar = qc.contact_scale(Quadric(E.tolist()), Quadric(Q.tolist()), scale="both")
    for enc in (
        qc.contact_scale(E[None], Q[None], scale="both")[0],
        qc.contact_scale(E[None], Q, scale="both")[0],  # one side broadcast
        qc.contact_scale(np.stack([E, E]), Q, scale="both")[1],
    ):
        assert scalar.scale.compare(Fraction(enc[0])) >= 0 and scalar.scale.compare(Fraction(enc[1])) <= 0


def test_pairs_left_to_the_exact_path_get_the_exact_answer():
    E = _ellipsoid((1.0, 0.5, 0.3), (0.5, 0.25, 0), 6)
    same_centre = _ellipsoid((0.4, 0.9, 0.2), (0.5, 0.25, 0), 7)
    near = _ellipsoid((0.4, 0.9, 0.2), (0.5, 0.25, 1e-13), 7)
    concentric = E.copy()
    concentric[:3, :3] *= 4.0  # the same centre exactly: a * 4, A * 4
    concentric[:3, 3] *= 4.0
    concentric[3, :3] *= 4.0
    concentric[3, 3] = 4.0 * E[3, 3] + 3.0
    Es, Qs = np.stack([E, E, E]), np.stack([concentric, same_centre, near])
    _, rest = scale_both_stack(Es, Qs)
    assert rest.all()  # one centre, or centres too close for binary64 bounds this narrow
    enc = qc.contact_scale(Es, Qs, scale="both")
    assert tuple(enc[0]) == (0.0, 0.0)
    assert _exact(E, concentric) == 0
    for k in (1, 2):
        assert _holds(enc[k], E, Qs[k]) and enc[k, 1] - enc[k, 0] <= 1e-15 * enc[k, 1]


@pytest.mark.parametrize("hard", [False, True], ids=["random", "needles"])
def test_blocks_agree_with_the_scalar_kernel(hard):
    """A pair the blocks leave to the exact path is one the scalar kernel leaves too, and the
    two enclosures of every other pair meet.  On random pairs the blocks certify nearly every
    pair; needles (axes down to 0.01, centres up to 6 from the origin) cancel so much in the
    corner entries that the bounds of about a third of them are too wide, and those go to the
    exact path (only agreement is asserted there)."""
    rng = np.random.default_rng(8)
    Es, _ = random_ellipsoids(20000, rng)
    Qs, _ = (
        random_ellipsoids(20000, rng, axes=(0.01, 3.0), box=6.0) if hard else random_ellipsoids(20000, rng)
    )
    enc, flag = _flags(Es, Qs)
    ref, rflag = _flags(Es, Qs, blocks=False)
    assert set(np.unique(rflag)) <= {0, 1}
    assert not (flag == 1)[rflag == 0].any()
    both = (flag != 1) & (rflag == 0)
    assert (enc[both, 0] <= ref[both, 1]).all() and (ref[both, 0] <= enc[both, 1]).all()
    assert (enc[flag == 1] == [-np.inf, np.inf]).all()
    width = (enc[flag != 1, 1] - enc[flag != 1, 0]) / enc[flag != 1, 1]
    assert (width <= WIDTH).all()
    if not hard:
        assert (flag == 0).mean() > 0.99 and np.median(width) < 1e-10
    for k in np.flatnonzero(flag != 1)[:3]:
        assert _holds(enc[k], Es[k], Qs[k])


def test_bad_input_is_refused():
    rng = np.random.default_rng(9)
    Es, _ = random_ellipsoids(2, rng)
    bad = Es.copy()
    bad[1, 0, 1] += 1e-9
    with pytest.raises(NotSymmetricError):
        qc.contact_scale(bad, Es[0], scale="both")
    bad = Es.copy()
    bad[0, 2, 2] = np.inf
    with pytest.raises(NonFiniteError):
        qc.contact_scale(Es[1], bad, scale="both")
    hyperboloid = np.array(Quadric.from_equation("x**2 + y**2 - z**2 - 1").matrix, dtype=float)
    with pytest.raises(NotAnEllipsoidError):
        qc.contact_scale(Es, hyperboloid, scale="both")
    imaginary = np.diag([1.0, 1.0, 1.0, 1.0])
    with pytest.raises(NotAnEllipsoidError):
        qc.contact_scale(imaginary[None], Es[0], scale="both")
    with pytest.raises(ValueError, match="scale must be one of"):
        qc.contact_scale(Es, Es, scale="Q")
