"""Small ellipsoids placed near a quadric, for the evidence of Theorem 2 and Lemma 4.

A seeded search (no hypothesis: it runs with the package's own dependencies):
each example is a Table 1 quadric in standard form with rational parameters
in [2, 6] (ordered as Table 1 orders them), and an ellipsoid with rational
semi-axes in [1/10, 1/2], rotated by a rational rotation and centred near the
surface of the quadric (a float Newton step from a random point towards the
surface, a random offset of the ellipsoid's size, rounded to a rational: only
where to look is chosen in floating point).  Only pairs that the package's
exact :func:`~quadric_contact.theory.smallness.smallness` finds small (Table 1,
corrected) are kept; everything about them is then decided exactly, by the
characteristic polynomial and by :func:`~quadric_contact.theory.geometric.decide_geometrically`,
the package's exact decision of how the surfaces meet (Lagrange conditions and
Morse theory, without the pencil).
"""

from __future__ import annotations

import random
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from quadric_contact import Quadric, QuadricKind, characteristic_polynomial
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.model.motions import rotation_from_quaternion
from quadric_contact.theory.geometric import GeometricDecision, decide_geometrically
from quadric_contact.theory.smallness import smallness


@dataclass(frozen=True)
class SmallPair:
    kind: QuadricKind
    E: Quadric
    Q: Quadric
    nonreal: bool  # P has a non-real root
    decision: GeometricDecision


def _rational(v: float, den: int = 64) -> Fraction:
    return Fraction(round(v * den), den)


def small_pairs(count: int, *, seed: int = 0) -> Iterator[SmallPair]:
    """``count`` small pairs, the same on every run (seeded)."""
    rng = random.Random(seed)
    made = 0
    tries = 0
    while made < count:
        tries += 1
        if tries > 20 * count + 100:
            raise RuntimeError("too few small pairs drawn")  # pragma: no cover
        kind = TABLE_1_KINDS[tries % len(TABLE_1_KINDS)]
        names = Quadric.standard_parameters(kind)
        params = [Fraction(rng.randint(8, 24), 4) for _ in names]
        if kind is not QuadricKind.HYPERBOLIC_CYLINDER:
            params.sort(reverse=True)
        Q = Quadric.standard(kind, **dict(zip(names, params, strict=True)))
        axes = sorted((Fraction(rng.randint(2, 10), 20) for _ in range(3)), reverse=True)
        quaternion = [rng.randint(-3, 3) for _ in range(4)]
        if not any(quaternion):
            quaternion[0] = 1
        rotation = rotation_from_quaternion(*quaternion)
        # Towards the surface: one Newton step for f(x) = X^T Q X from a random point.
        M = np.array([[float(v) for v in row] for row in Q.matrix])
        x = np.array([rng.uniform(-4, 4) for _ in range(3)])
        for _ in range(3):
            X = np.append(x, 1.0)
            f = X @ M @ X
            g = 2 * (M @ X)[:3]
            if float(g @ g) > 1e-12:
                x = x - f * g / float(g @ g)
        offset = np.array([rng.uniform(-1, 1) for _ in range(3)]) * float(axes[0])
        centre = tuple(_rational(v) for v in x + offset)
        E = Quadric.ellipsoid(*axes, center=centre, rotation=rotation)
        if not smallness(E, Q).small:
            continue
        nonreal = not characteristic_polynomial(E, Q).structure.all_real
        made += 1
        yield SmallPair(kind, E, Q, nonreal, decide_geometrically(E, Q))
