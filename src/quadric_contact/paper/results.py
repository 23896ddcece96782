"""The results the package proves: the paper's numbered results and the further ones it relies on.

``proofs/`` holds one module per result, in this order
(:mod:`quadric_contact.paper.proving` runs them, and the report lists them so).
"""

from __future__ import annotations

__all__ = ["FURTHER_RESULTS", "NUMBERED_RESULTS"]

NUMBERED_RESULTS: tuple[str, ...] = (
    "eq. (1)",
    "Theorem 2",
    "Lemma 3",
    "Lemma 4",
    "Theorem 5",
    "Example 6",
    "Lemma 7",
    "Lemma 8",
    "Remark 9",
    "Section 3.2",
    "Corollary 10",
    "Example 11",
    "Lemma 12",
    "Theorem 13",
    "Theorem 14",
    "Corollary 15",
    "Remark 16",
    "Example 17",
)
"""The paper's numbered results in the paper's order (Definition 1 is a
definition; the formulas of Section 3.2 are unnumbered but proved too).
Tables 1-4 and the numbered equations belong to the results that state them."""

FURTHER_RESULTS: tuple[str, ...] = (
    "Wang-Wang-Kim 2001",
    "Tu-Wang-Mourrain-Wang 2009",
    "Pieces as cut",
    "First-contact scale",
    "Mutual contact events",
    "Distance along a path",
    "Depth of crossing ellipsoids",
    "Distance of separated ellipsoids",
    "Distance to cut pieces",
    "Depth into non-convex solids",
)
"""Results from outside the paper that the package relies on and proves in ``proofs/``
alongside the paper's (after them, in this order): the separation condition of two
ellipsoids of Wang, Wang and Kim (CAGD 18, 2001), on which
:func:`quadric_contact.overlap` decides two ellipsoids; the decision of contact,
region and overlap of an ellipsoid and any quadric from the signature sequence of the pencil
(after Tu, Wang, Mourrain and Wang, CAGD 26, 2009), which needs no smallness: beyond the
paper; the package's own reduction of contact with a piece as cut by a plane to the plane
section's pencil (:mod:`quadric_contact.theory.sections`), on which the geometric reading of
scenes rests; the choice of the root that :func:`quadric_contact.contact_scale` returns; the
reduction of the contacts of two moving ellipsoids with each other to the real roots of a
discriminant in time (:mod:`quadric_contact.scenes.mutual`); the bound on the displacement of
a rigidly moving ellipsoid's points by which the least distance along a path is enclosed
(:mod:`quadric_contact.scenes.path_distance`); the certificate by which the depth of two
crossing ellipsoids is enclosed on stacks (:mod:`quadric_contact.modes.distance.depth_kernel`); the
isolated root by which the distance of two separated ellipsoids and its witnesses are enclosed
in the ``certified`` mode (:mod:`quadric_contact.modes.distance.certified`); the duality
bounds by which the distance of an ellipsoid from a convex piece cut by planes is enclosed
(:mod:`quadric_contact.modes.distance.pieces`); and the bracket of the depth into a solid that is
not convex between an inscribed ellipsoid and a free translation
(:mod:`quadric_contact.modes.distance.nonconvex`)."""
