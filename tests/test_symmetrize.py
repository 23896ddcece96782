"""An asymmetric matrix is refused with the way to symmetrise in the message, and is
symmetrised only when asked: ``Quadric.from_matrix(M, symmetrize=True)`` for one matrix,
``qc.symmetrize(M)`` for a stack, both giving the exact symmetric part (M + M^T)/2."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import quadric_contact as qc

# a sphere of radius 1 whose x-y entry differs in the last bit between the two triangles,
# as numpy's R @ D @ R.T often leaves it
A = 0.1
B = float(np.nextafter(A, 1.0))
LOPSIDED = np.array([[1.0, A, 0.0, 0.0], [B, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, -1.0]])
MEAN = (Fraction(A) + Fraction(B)) / 2
BALL = np.diag([1.0, 1.0, 1.0, -16.0])  # radius 4: holds the ellipsoid above


def test_the_error_says_how_to_symmetrise_for_one_matrix_and_for_a_stack():
    with pytest.raises(qc.NotSymmetricError) as one:
        qc.Quadric.from_matrix(LOPSIDED)
    with pytest.raises(qc.NotSymmetricError) as stack:
        qc.transversal_contact(LOPSIDED[None], BALL, mode="exact")
    for err in (one.value, stack.value):
        assert "symmetrize=True" in str(err) and "quadric_contact.symmetrize(M)" in str(err)
        assert err.details["entry"] == (0, 1)
    with pytest.raises(qc.NotSymmetricError, match="symmetrize"):
        qc.pack(LOPSIDED[None])


def test_from_matrix_symmetrises_only_when_asked_and_exactly():
    q = qc.Quadric.from_matrix(LOPSIDED, symmetrize=True)
    assert q[0, 1] == q[1, 0] == MEAN
    # the exact mean of two neighbouring binary64 numbers is not binary64
    assert Fraction(float(MEAN)) != MEAN


def test_symmetrize_of_a_stack_is_the_exact_symmetric_part():
    S = qc.symmetrize(np.stack([LOPSIDED, BALL]))
    assert S.shape == (2, 4, 4) and S.dtype == object
    assert S[0, 0, 1] == S[0, 1, 0] == MEAN
    assert all(S[1, i, j] == BALL[i, j] for i in range(4) for j in range(4))
    # a symmetric binary64 stack, or one whose means are binary64, stays binary64 as it is
    assert qc.symmetrize(BALL).dtype == np.float64
    assert (qc.symmetrize(BALL) == BALL).all()
    halves = np.array(LOPSIDED)
    halves[1, 0] = 0.3  # (0.1 + 0.3) / 2 is not binary64 either; 0.5 and 1.5 average to 1.0
    halves[0, 1], halves[1, 0] = 0.5, 1.5
    T = qc.symmetrize(halves)
    assert T.dtype == np.float64 and T[0, 1] == T[1, 0] == 1.0
    # exact input: Fractions and decimal strings
    F = qc.symmetrize([[1, "0.1", 0, 0], [Fraction(3, 10), 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]])
    assert F[0, 1] == F[1, 0] == Fraction(1, 5)


def test_symmetrised_answers_agree_for_one_matrix_and_a_stack_of_one():
    one = qc.transversal_contact(qc.Quadric.from_matrix(LOPSIDED, symmetrize=True), BALL)
    stack = qc.transversal_contact(qc.symmetrize(LOPSIDED[None]), BALL)
    assert bool(one) is False
    assert stack.tolist() == [int(qc.ContactCode.NO_CONTACT)]


def test_symmetrize_refuses_what_is_not_a_stack_of_4x4_matrices():
    with pytest.raises(qc.ShapeError):
        qc.symmetrize(np.eye(3))
