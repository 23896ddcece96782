"""Run a scene: plan from the requested effects, exact event timeline, work ledger.

For each moving ellipsoid and each object, each motion segment is processed
as Algorithms 1 and 2 prescribe, but in time (:mod:`quadric_contact.scenes.events`):

1. the pencil of the ellipsoid against the root plane of the object's tree
   is formed with polynomial coefficients in ``t``; the real roots of its
   critical polynomial are isolated exactly and the zone is classified on
   every interval between them and at every root;
2. a child of a plane (another plane, or a piece) is processed only if the
   zone reaches it somewhere in the segment; a piece's pencil (and its
   ``D2..D4``, and ``c1..c3`` if the relative position is wanted) is formed
   only then: "computed only if needed, depending on the zone" (Section 5.2);
3. all roots found are merged; on every interval between consecutive ones
   the state is constant and is decided at a rational sample time, and at
   every root exactly at the algebraic number; an event is reported where
   the state changes.

The plan follows the effects: ``zone`` alone never forms a piece's pencil;
``relative_position`` adds the coefficient polynomials; ``first_contact``
alone stops at the first contact; smallness is checked only for effects that
rely on Theorem 2; ``distance`` encloses, after the timelines, the least signed
distance from each piece that asks for it
(:mod:`quadric_contact.scenes.scene_distance`).  The
:class:`~quadric_contact.scenes.ledger.Ledger` counts everything and compares it
with a full evaluation of every effect for every piece.

References
----------
Section 5.2, Algorithms 1 and 2, Corollaries 10 and 15, Theorem 13.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace

from quadric_contact.scenes.composite import Composite, Piece
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.manybody import run_pairs
from quadric_contact.scenes.mutual import mutual_contacts
from quadric_contact.scenes.scene_distance import PieceDistance, piece_distances
from quadric_contact.scenes.scene_model import (
    READINGS,
    MovingEllipsoid,
    Scene,
    check_choice,
    check_on_not_small,
)
from quadric_contact.scenes.scene_pairs import _progress, _simulate_pair
from quadric_contact.scenes.simulation_reports import Plan, SimulationResult

__all__ = ["simulate"]


def simulate(
    scene: Scene,
    *,
    effects: Sequence[str] | None = None,
    full: bool = False,
    progress: bool | None = None,
    on_not_small: str | None = None,
    broad_phase: bool = False,
    workers: int = 1,
    reading: str | None = None,
) -> SimulationResult:
    """Run a scene and return its exact event timelines and work ledger.

    Parameters
    ----------
    scene : Scene
    effects : sequence of str, optional
        Override the scene's effects (a subset of :data:`~quadric_contact.scenes.scene_model.EFFECTS`).
    full : bool
        Evaluate every effect for every piece on every segment instead of
        only what the effects need (to measure what the plan saves).
    progress : bool, optional
        Show a progress bar on stderr (default: for long runs on a terminal).
    on_not_small : {"refuse", "warn"}, optional
        Override the scene's smallness policy (None: the scene's own).
    broad_phase : bool
        Prune, with certified bounds of each ellipsoid's swept volume, the
        planes and pieces (and the stretches of time) where nothing can
        happen, before any pencil is formed (:mod:`quadric_contact.scenes.broadphase`);
        the timelines are the same.  A full evaluation (``full``) does without it.
    workers : int
        Processes to share the ellipsoids between, and the pairs of bodies whose
        mutual contacts are wanted (``0``: one per core).
    reading : {"geometry", "paper"}, optional
        Override the scene's reading of its pieces: as cut by the planes on
        their paths (``"geometry"``), or as whole quadrics (``"paper"``,
        Algorithm 1).

    Returns
    -------
    SimulationResult

    Raises
    ------
    SceneError
        Unknown effects, or a pair that is not small under the ``"refuse"`` policy.
    ChoiceError
        ``reading`` is not ``"geometry"`` or ``"paper"``, or ``on_not_small`` is not
        ``"refuse"``, ``"warn"`` or None.

    References
    ----------
    Section 5.2, Algorithms 1 and 2, Corollaries 10 and 15, Theorem 13,
    Example 17.

    Examples
    --------
    >>> from quadric_contact.scenes.scene_toml import builtin_scene
    >>> result = simulate(builtin_scene(), effects=["zone"])
    >>> result.ledger.cost("tree/crown"), result.ledger.cost("tree/trunk")
    (0, 0)
    """
    check_on_not_small(on_not_small)
    if reading is not None and reading != scene.reading:
        check_choice("reading", reading, READINGS)
        scene = replace(scene, reading=reading)
    plan = Plan.from_effects(scene.effects if effects is None else effects, full=full)
    started = time.perf_counter()
    ledger = Ledger()
    if plan.full or scene.needs_smallness(plan.effects):
        scene.check_smallness(on_not_small=on_not_small)  # a no-op for the pairs checked at load time
        for key, n in scene.work.by_target.items():
            ledger.add("smallness_checks", n["smallness_checks"], target=key)
    # what a full evaluation would cost
    seg_lists = {
        e.name: e.trajectory.segments(scene.span[0], scene.span[1], e.center) for e in scene.ellipsoids
    }
    for e in scene.ellipsoids:
        nseg = len(seg_lists[e.name])
        for obj in scene.objects:
            for _s in obj.splits():
                ledger.add_full("characteristic_polynomials", nseg)
                ledger.add_full("discriminants", nseg)
            for p in obj.pieces:
                ledger.add_full("characteristic_polynomials", nseg)
                if p.is_plane:
                    ledger.add_full("discriminants", nseg)
                else:
                    ledger.add_full("discriminants", 3 * nseg)
                    ledger.add_full("coefficient_signs", 3 * nseg)
                    ledger.add_full("smallness_checks", 1)
    if full:
        broad_phase = False  # a full evaluation forms every pencil
    if broad_phase or workers != 1:
        pairs = run_pairs(
            scene, plan, seg_lists, ledger, broad_phase=broad_phase, workers=workers, progress=progress
        )
    else:
        total = sum(len(seg_lists[e.name]) for e in scene.ellipsoids) * len(scene.objects)
        bar = _progress(total, progress)
        pairs = []
        try:
            for e in scene.ellipsoids:
                for obj in scene.objects:
                    pairs.append(_simulate_pair(scene, plan, e, obj, seg_lists[e.name], ledger, bar=bar))
        finally:
            if bar is not None:
                bar.close()
    if plan.distance:
        ells = {e.name: e for e in scene.ellipsoids}
        for pair in pairs:
            pair.distances = _distances(scene, plan, ells[pair.ellipsoid], pair.object, ledger)
    mutual = None
    if len(scene.mutual) >= 2:
        mutual = mutual_contacts(scene, scene.mutual, ledger=ledger, workers=workers)
    return SimulationResult(
        scene, plan, pairs, ledger, time.perf_counter() - started, list(scene.warnings), mutual=mutual
    )


def _distances(
    scene: Scene,
    plan: Plan,
    ell: MovingEllipsoid,
    obj: Composite,
    ledger: Ledger,
) -> list[PieceDistance]:
    """The ``distance`` effect for one (ellipsoid, object): the pieces for which the scene,
    the ellipsoid and the piece all ask for it."""
    own = plan.restricted(scene.ellipsoid_effects.get(ell.name))

    def wanted(piece: Piece) -> bool:
        return own.restricted(scene.piece_effects.get((obj.name, piece.name))).distance

    return piece_distances(scene, ell, obj, ledger, wanted)
