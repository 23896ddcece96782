"""Layout of the ten independent entries of a symmetric 4x4 matrix.

Generated formulas take a symmetric matrix as these ten upper entries, in this
order: ``(m00, m01, m02, m03, m11, m12, m13, m22, m23, m33)``.
"""

from __future__ import annotations

ENTRY_INDICES: tuple[tuple[int, int], ...] = (
    (0, 0),
    (0, 1),
    (0, 2),
    (0, 3),
    (1, 1),
    (1, 2),
    (1, 3),
    (2, 2),
    (2, 3),
    (3, 3),
)
