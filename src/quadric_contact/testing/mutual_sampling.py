"""Mutual contacts against dense exact sampling: no contact interval missed.

The exact timelines of :func:`~quadric_contact.scenes.mutual.mutual_contacts` are
compared, on a subset of pairs of moving ellipsoids, with the state that the static
exact decision (:func:`~quadric_contact.theory.overlap.overlap_exact`, on the placements
built by :meth:`~quadric_contact.scenes.trajectory.Trajectory.placed`, independently of
the pencil in time) gives at many evenly spaced rational times.  Every sample must agree
with the timeline; a *missed* contact interval is a maximal run of samples where the
sampled pair touches or overlaps and the timeline says apart throughout it.

:func:`near_pairs` picks the subset: pairs that meet in the timelines, and pairs whose
centres come close (within twice the sum of the largest semi-axes, on a float grid of
times) without meeting, the cases a wrong event time or a wrong pruning would show.

Examples
--------
>>> from quadric_contact.scenes.manybody import many_body_scene
>>> from quadric_contact.scenes.mutual import mutual_contacts
>>> scene = many_body_scene(40, 2, seed=1, check_smallness=False, mutual=True)
>>> found = mutual_contacts(scene)
>>> check = dense_check(scene, found, near_pairs(scene, found, meeting=2, near=1), samples=16)
>>> check.disagreements, check.missed
([], 0)
"""

from __future__ import annotations

import multiprocessing
import random
from collections.abc import Sequence
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import numpy as np

from quadric_contact.scenes.broadphase import ellipsoid_extents
from quadric_contact.scenes.mutual import OVERLAPPING, SEPARATE, TOUCHING, MutualResult
from quadric_contact.scenes.scene_model import Scene
from quadric_contact.theory.overlap import overlap_exact

__all__ = ["DenseCheck", "dense_check", "near_pairs"]

_STATE = {"SEPARATE": SEPARATE, "TOUCHING": TOUCHING, "OVERLAPPING": OVERLAPPING}


@dataclass
class DenseCheck:
    """The comparison of exact timelines with dense exact sampling.

    Attributes
    ----------
    pairs, samples : int
        Pairs compared and sample times per pair (evenly spaced over the span, ends included).
    disagreements : list of (str, str, Fraction, str, str)
        ``(a, b, t, sampled, timeline)`` wherever the two states differ (none expected).
    sampled_intervals : int
        Maximal runs of samples where a pair touches or overlaps.
    missed : int
        Of those, the runs where the timeline says apart at every sample.
    exact_intervals : int
        Contact intervals of the timelines of the pairs compared.
    unseen : int
        Of those, the ones no sample falls in (shorter than the step): sampling's blind spot,
        not a disagreement.
    """

    pairs: int = 0
    samples: int = 0
    disagreements: list[tuple[str, str, Fraction, str, str]] = field(default_factory=list)
    sampled_intervals: int = 0
    missed: int = 0
    exact_intervals: int = 0
    unseen: int = 0

    def merge(self, other: DenseCheck) -> None:
        self.pairs += other.pairs
        self.disagreements += other.disagreements
        self.sampled_intervals += other.sampled_intervals
        self.missed += other.missed
        self.exact_intervals += other.exact_intervals
        self.unseen += other.unseen


def _contact_intervals(result: MutualResult | None, t0: Fraction, t1: Fraction) -> list[tuple[Any, Any]]:
    """Maximal stretches ``(start, end)`` where the timeline touches or overlaps."""
    if result is None:
        return []
    meet = (TOUCHING, OVERLAPPING)
    out: list[tuple[Any, Any]] = []
    start: Any = t0 if result.start in meet else None
    for e in result.events:
        if start is None and (e.at in meet or e.after in meet):
            start = e.time
        if start is not None and e.after not in meet:
            out.append((start, e.time))
            start = None
    if start is not None:
        out.append((start, t1))
    return out


def near_pairs(
    scene: Scene, results: Sequence[MutualResult], *, meeting: int = 20, near: int = 10, seed: int = 0
) -> list[tuple[str, str]]:
    """Up to ``meeting`` pairs that meet in ``results`` and up to ``near`` pairs whose centres
    come within twice the sum of their largest semi-axes (on 257 float times) without
    meeting, chosen at random with ``seed``."""
    rng = random.Random(seed)
    met = sorted((r.a, r.b) for r in results)
    chosen = rng.sample(met, min(meeting, len(met)))
    bodies = [e for e in scene.ellipsoids if not scene.mutual or e.name in scene.mutual]
    names = [e.name for e in bodies]
    rho = np.array([float(ellipsoid_extents(e.quadric)[1]) for e in bodies])
    t0, t1 = scene.span
    closest = np.full((len(bodies), len(bodies)), np.inf)
    for k in range(257):
        t = t0 + (t1 - t0) * Fraction(k, 256)
        c = np.array(
            [[float(v) for v in e.trajectory.segment_at(t, t0, t1, e.center).center_at(t)] for e in bodies]
        )
        d = np.linalg.norm(c[:, None, :] - c[None, :, :], axis=2)
        np.minimum(closest, d, out=closest)
    i, j = np.nonzero(np.triu(closest <= 2 * (rho[:, None] + rho[None, :]), 1))
    meets = set(met)
    misses = sorted({(names[a], names[b]) for a, b in zip(i, j, strict=True)} - meets)
    return chosen + rng.sample(misses, min(near, len(misses)))


_JOB: dict[str, Any] = {}


def _check_pairs(pairs: Sequence[tuple[str, str]]) -> DenseCheck:
    scene: Scene = _JOB["scene"]
    by_pair: dict[tuple[str, str], MutualResult] = _JOB["by_pair"]
    samples: int = _JOB["samples"]
    bodies = {e.name: e for e in scene.ellipsoids}
    t0, t1 = scene.span
    times = [t0 + (t1 - t0) * Fraction(k, samples) for k in range(samples + 1)]
    out = DenseCheck(samples=samples)
    for a, b in pairs:
        ea, eb = bodies[a], bodies[b]
        result = by_pair.get((a, b)) or by_pair.get((b, a))
        exact = _contact_intervals(result, t0, t1)
        out.pairs += 1
        out.exact_intervals += len(exact)
        seen = [False] * len(exact)
        run: list[str] | None = None  # the timeline's states along a sampled contact run
        for t in times:
            A = ea.trajectory.placed(ea.quadric, t, t0, t1)
            B = eb.trajectory.placed(eb.quadric, t, t0, t1)
            sampled = _STATE[overlap_exact(A, B).code.name]
            timeline = SEPARATE if result is None else result.state_at(t)
            if sampled != timeline:
                out.disagreements.append((a, b, t, sampled, timeline))
            for k, (lo, hi) in enumerate(exact):
                if _le(lo, t) and _le(t, hi):
                    seen[k] = True
            if sampled != SEPARATE:
                run = (run or []) + [timeline]
            elif run is not None:
                out.sampled_intervals += 1
                out.missed += all(s == SEPARATE for s in run)
                run = None
        if run is not None:
            out.sampled_intervals += 1
            out.missed += all(s == SEPARATE for s in run)
        out.unseen += seen.count(False)
    return out


def _le(x: Any, y: Any) -> bool:
    if isinstance(x, Fraction):
        return x <= y if isinstance(y, Fraction) else y.compare(x) >= 0
    return x.compare(y) <= 0


def dense_check(
    scene: Scene,
    results: Sequence[MutualResult],
    pairs: Sequence[tuple[str, str]],
    *,
    samples: int = 256,
    workers: int = 1,
) -> DenseCheck:
    """Compare the timelines ``results`` with the exact state at ``samples + 1`` evenly
    spaced rational times, for each of ``pairs`` (names of moving ellipsoids of ``scene``).

    Parameters
    ----------
    scene : Scene
    results : sequence of MutualResult
        The exact timelines (pairs apart throughout are absent: apart at every time).
    pairs : sequence of (str, str)
    samples : int
    workers : int
        Processes to share the pairs between.

    Returns
    -------
    DenseCheck
    """
    _JOB.update(scene=scene, by_pair={(r.a, r.b): r for r in results}, samples=samples)
    try:
        if workers <= 1 or len(pairs) < 2 or "fork" not in multiprocessing.get_all_start_methods():
            return _check_pairs(pairs)
        chunks = [list(pairs[k :: workers * 4]) for k in range(workers * 4)]
        total = DenseCheck(samples=samples)
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            for part in pool.imap_unordered(_check_pairs, [c for c in chunks if c]):
                total.merge(part)
        return total
    finally:
        _JOB.clear()
