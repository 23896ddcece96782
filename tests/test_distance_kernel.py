"""The compiled distance of separated ellipsoids on stacks: every enclosure holds the scalar
certified distance, is at most 1e-12 relative wide, and the other pairs are left to the scalar
path."""

from __future__ import annotations

import flint
import numpy as np

import quadric_contact as qc
from quadric_contact import Quadric
from quadric_contact.modes.distance.apart_kernel import separated_ellipsoids


def _stack(m, seed, spread=4.0):
    rng = np.random.default_rng(seed)
    out = np.zeros((m, 4, 4))
    for k in range(m):
        R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        A = R @ np.diag(1 / rng.uniform(0.3, 1.5, 3) ** 2) @ R.T
        A = (A + A.T) / 2
        c = rng.uniform(-spread, spread, 3)
        out[k, :3, :3] = A
        out[k, :3, 3] = out[k, 3, :3] = -A @ c
        out[k, 3, 3] = c @ A @ c - 1
    return out


def test_separated_pairs_hold_the_scalar_value():
    Es, Ks = _stack(60, 1), _stack(60, 2)
    enc, rest = separated_ellipsoids(Es, Ks)
    done = np.flatnonzero(~rest)
    assert len(done) > 20
    assert np.all((enc[done, 1] - enc[done, 0]) <= 1e-12 * enc[done, 0])
    for k in done[:6]:
        r = qc.distance(Quadric.from_matrix(Es[k]), Quadric.from_matrix(Ks[k]), digits=20)
        assert r.distance.overlaps(flint.arb(enc[k, 0]).union(flint.arb(enc[k, 1])))


def test_crossing_pairs_are_left_and_the_stack_still_answers():
    Es, Ks = _stack(3, 3, spread=0.2), _stack(3, 4, spread=0.2)  # centres close: crossing
    _, rest = separated_ellipsoids(Es, Ks)
    assert rest.all()
    enc = qc.distance(Es[:1], Ks[:1])
    r = qc.distance(Quadric.from_matrix(Es[0]), Quadric.from_matrix(Ks[0]), digits=20)
    assert enc[0, 0] < 0 and r.distance.overlaps(flint.arb(enc[0, 0]).union(flint.arb(enc[0, 1])))


def test_either_sign_of_the_matrices():
    Es, Ks = _stack(8, 5), _stack(8, 6)
    a, ra = separated_ellipsoids(Es, Ks)
    b, rb = separated_ellipsoids(-Es, -Ks)
    assert np.array_equal(ra, rb) and np.array_equal(a[~ra], b[~rb])
