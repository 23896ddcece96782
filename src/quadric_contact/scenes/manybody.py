"""Many bodies: the scene engine with a certified broad phase, on several processes.

:func:`~quadric_contact.scenes.simulate.simulate` with ``broad_phase=True`` runs each
(ellipsoid, object, motion segment) through :func:`~quadric_contact.scenes.broadphase.cover`
first.  A plane or a piece that the broad phase certifies for the whole segment
gets no pencil in time at all (*pruned*); one certified on some stretches gets
its exact track (:mod:`quadric_contact.scenes.events`) on the other stretches only,
and a :class:`PiecewiseTrack` joins the two.  The state of a certified stretch
is the one the pencil in time would give there: for a plane, ``R+`` or ``R-``
without tangency (Corollary 15 on an ellipsoid strictly on one side); for a
piece, the same decision as the exact track, taken once on a frozen placement
inside the stretch (:data:`~quadric_contact.scenes.ledger.ITEMS` ``static_pencils``).
The narrow phase is the exact machinery, so the event timelines are those of
the run without the broad phase; ``workers`` shares the ellipsoids between
processes.

:func:`many_body_scene` generates the benchmark scene: ``bodies`` small
ellipsoids on straight paths around and through a totem of ``pieces``
quadric pieces (spheres and one-sheet hyperboloids stacked along ``z``,
separated by the planes ``z = 2k`` in a balanced tree).

References
----------
Section 5.2, Algorithms 1 and 2, Theorem 14, Corollaries 10 and 15.
"""

from __future__ import annotations

import multiprocessing
import random
from collections.abc import Sequence
from fractions import Fraction
from typing import Any, ClassVar

import flint

from quadric_contact.exact.errors import SceneError
from quadric_contact.exact.rational import fmpq_of
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.broadphase import (
    Coverage,
    Part,
    cover,
    ellipsoid_extents,
    zone_of_sign,
)
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.scenes.events import PieceTrack, ZoneValue
from quadric_contact.scenes.ledger import Ledger
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.scene_pairs import _progress, _SegmentRun, _simulate_pair
from quadric_contact.scenes.simulation_reports import PairResult, Plan
from quadric_contact.scenes.trajectory import MotionSegment, PolynomialMotion, poly_eval

__all__ = ["GENERATED_SCENES", "PiecewiseTrack", "many_body_scene", "run_pairs", "totem"]


class PiecewiseTrack:
    """A target's track on a segment cut into parts: exact tracks on the tracked
    parts, a constant state on the certified ones.

    It answers the questions the simulator asks of a track (its sorted
    ``roots``, the state between two of them, at one of them, at a rational
    time).  At a boundary between a certified and a tracked part the certified
    state holds (the broad phase's intervals are closed).
    """

    def __init__(self, label: str, parts: Sequence[tuple[Part, Any]]) -> None:
        self.label = label
        self.parts = list(parts)
        self.roots: list[Any] = []
        self.offsets: list[int] = []
        for part, track in self.parts:
            self.offsets.append(len(self.roots))
            if part.tracked:
                self.roots.extend(track.roots)

    def _locate(self, t: Fraction) -> int:
        found = None
        for k, (part, _) in enumerate(self.parts):
            if part.start <= t <= part.end:
                if not part.tracked:
                    return k
                if found is None:
                    found = k
        if found is None:  # pragma: no cover - the parts cover the segment
            raise ValueError(f"{self.label}: t = {t} is outside the segment")
        return found

    def _certified(self, k: int) -> Any:
        value = self.parts[k][1]
        if value is None:  # pragma: no cover - would be a broad-phase bug
            raise AssertionError(f"{self.label}: the broad phase found this target out of reach here")
        return value

    def state_on_interval(self, index: int, sample: Fraction) -> Any:
        k = self._locate(sample)
        part, track = self.parts[k]
        if not part.tracked:
            return self._certified(k)
        if sample in (part.start, part.end):
            return track.state_at_rational(sample)
        return track.state_on_interval(index - self.offsets[k], sample)

    def state_at_root(self, index: int) -> Any:
        for k, (part, track) in enumerate(self.parts):
            if part.tracked and self.offsets[k] <= index < self.offsets[k] + len(track.roots):
                return track.state_at_root(index - self.offsets[k])
        raise IndexError(index)  # pragma: no cover

    def state_at_rational(self, t: Fraction) -> Any:
        k = self._locate(t)
        part, track = self.parts[k]
        return self._certified(k) if not part.tracked else track.state_at_rational(t)


class _BroadSegmentRun(_SegmentRun):
    """One ellipsoid against one object on one segment, after the broad phase."""

    extents: ClassVar[dict[str, Any]] = {}
    max_depth: ClassVar[int] = 2

    def __init__(self, *args: Any) -> None:
        super().__init__(*args)
        half, rho = self.extents[self.ell.name]
        self.coverage: Coverage = cover(
            self.obj, self.seg, half, rho, max_depth=self.max_depth, ledger=self.ledger
        )
        for label in self.coverage.pruned:
            self.ledger.add("pruned_pairs", target=label)
        self._static: dict[tuple[str, int], Any] = {}

    def _certified_state(self, label: str, part: Part) -> Any:
        if part.sign == 0:
            return None  # out of reach on this part: never asked about
        target = self.targets[label]
        if isinstance(target, Split):
            return ZoneValue(zone_of_sign(part.sign))
        assert isinstance(target, Piece), "the broad phase covers planes and pieces only"
        key = (label, part.sign)  # one state per side: the ellipsoid never touches the target
        if key not in self._static:
            # the exact track's decision, on the placement at a time where it was certified
            t = part.witness
            assert t is not None
            frozen = tuple(flint.fmpq_poly([fmpq_of(poly_eval(p, t))]) for p in self.E_upper)
            scratch = Ledger()
            track = PieceTrack(
                label,
                frozen,
                target.quadric,
                part.start,
                part.end,
                scratch,
                small=self.scene.small(self.ell.name, self.obj.name, target.name),
                table_4=self.scene.table_4_applies(self.ell.name, self.obj.name, target.name),
                region=self.piece_plans[target.name].region,
                kind=self.piece_plans[target.name].kind,
                E_at=self.E_at,
                positive=None,
            )
            self.ledger.add("static_pencils", target=label)
            self._static[key] = track.state_at_rational(t)
        return self._static[key]

    def make_track(self, label: str) -> None:
        if label not in self.coverage.parts:  # a plane section of a piece as cut: exact on the segment
            super().make_track(label)
            return
        parts = self.coverage.parts[label]
        if len(parts) == 1 and parts[0].tracked:
            super().make_track(label)
            return
        built: list[tuple[Part, Any]] = []
        for part in parts:
            if part.tracked:
                built.append((part, self.build_track(label, part.start, part.end)))
            else:
                if any(p.tracked for p in parts):
                    self.ledger.add("pruned_stretches", target=label)
                built.append((part, self._certified_state(label, part)))
        self.tracks[label] = PiecewiseTrack(label, built)


# -- running many pairs, on several processes -------------------------------------------

_JOB: dict[str, Any] = {}


def _segment_run_factory(scene: Scene, broad_phase: bool, max_depth: int) -> Any:
    if not broad_phase:
        return None
    by_shape: dict[tuple[Fraction, ...], Any] = {}
    extents = {}
    for e in scene.ellipsoids:  # congruent translates share their extents
        shape = e.quadric.translated(tuple(-v for v in e.center)).upper
        if shape not in by_shape:
            by_shape[shape] = ellipsoid_extents(e.quadric)
        extents[e.name] = by_shape[shape]
    return type("_Run", (_BroadSegmentRun,), {"extents": extents, "max_depth": max_depth})


def _run_chunk(indices: Sequence[int]) -> tuple[list[tuple[int, int, PairResult]], Ledger]:
    scene: Scene = _JOB["scene"]
    plan: Plan = _JOB["plan"]
    factory = _JOB["factory"]
    ledger = Ledger()
    out = []
    for i in indices:
        e = scene.ellipsoids[i]
        segs = e.trajectory.segments(scene.span[0], scene.span[1], e.center)
        for j, obj in enumerate(scene.objects):
            pair = _simulate_pair(scene, plan, e, obj, segs, ledger, segment_run=factory)
            out.append((i, j, pair))
    return out, ledger


def _run_chunk_detached(indices: Sequence[int]) -> tuple[list[tuple[int, int, PairResult]], Ledger]:
    """As :func:`_run_chunk`, with the objects left out of the results (the parent
    has them; they need not travel back)."""
    out, ledger = _run_chunk(indices)
    for _, _, pair in out:
        pair.object = None  # type: ignore[assignment]
    return out, ledger


def run_pairs(
    scene: Scene,
    plan: Plan,
    seg_lists: dict[str, list[MotionSegment]],
    ledger: Ledger,
    *,
    broad_phase: bool = True,
    workers: int = 1,
    progress: bool | None = None,
    max_depth: int = 2,
) -> list[PairResult]:
    """The timelines of every (ellipsoid, object) pair, in scene order.

    Parameters
    ----------
    scene, plan, seg_lists, ledger
        As prepared by :func:`~quadric_contact.scenes.simulate.simulate` (the work is
        added to ``ledger``).
    broad_phase : bool
        Run the certified broad phase first.
    workers : int
        Processes (``0``: one per core; ``1``: this one).
    progress : bool, optional
        A progress bar on stderr (default: for long runs on a terminal).
    max_depth : int
        Bisections of a time interval in the broad phase.

    Returns
    -------
    list of PairResult
    """
    if workers < 0:
        raise SceneError(f"workers: expected a number of processes >= 0, got {workers}", workers)
    if workers == 0:
        workers = multiprocessing.cpu_count()
    factory = _segment_run_factory(scene, broad_phase, max_depth)
    n = len(scene.ellipsoids)
    if workers > 1 and "fork" not in multiprocessing.get_all_start_methods():  # pragma: no cover
        workers = 1
    total = sum(len(seg_lists[e.name]) for e in scene.ellipsoids) * len(scene.objects)
    results: dict[tuple[int, int], PairResult] = {}
    if workers <= 1 or n <= 1:
        bar = _progress(total, progress)
        try:
            for i, e in enumerate(scene.ellipsoids):
                for j, obj in enumerate(scene.objects):
                    results[i, j] = _simulate_pair(
                        scene, plan, e, obj, seg_lists[e.name], ledger, bar=bar, segment_run=factory
                    )
        finally:
            if bar is not None:
                bar.close()
        return [results[i, j] for i in range(n) for j in range(len(scene.objects))]
    size = max(1, n // (workers * 8))
    chunks = [list(range(k, min(n, k + size))) for k in range(0, n, size)]
    _JOB.update(scene=scene, plan=plan, factory=factory)
    bar = _progress(n, progress)
    if bar is not None:
        bar.unit = "ellipsoid"
    try:
        with multiprocessing.get_context("fork").Pool(workers) as pool:
            for out, part_ledger in pool.imap_unordered(_run_chunk_detached, chunks):
                ledger.merge(part_ledger)
                for i, j, pair in out:
                    pair.object = scene.objects[j]
                    results[i, j] = pair
                if bar is not None:
                    bar.update(len({i for i, _, _ in out}))
    finally:
        _JOB.clear()
        if bar is not None:
            bar.close()
    return [results[i, j] for i in range(n) for j in range(len(scene.objects))]


# -- the generated many-body scene --------------------------------------------------------


def totem(pieces: int = 16) -> Composite:
    """A stack of ``pieces`` quadric pieces along ``z``: piece ``k`` occupies
    ``2k <= z <= 2k + 2`` and is a sphere of radius 3/2 centred at height
    ``2k + 1`` (even ``k``) or the one-sheet hyperboloid
    ``x^2 + y^2 - (z - 2k - 1)^2 / 4 = 1`` (odd ``k``); the planes ``z = 2k``
    separate them in a balanced tree.

    Examples
    --------
    >>> t = totem(4)
    >>> sorted((p.name, p.quadric.kind.value) for p in t.pieces)[:2], [s.name for s in t.splits()]
    ([('p0', 'ellipsoid'), ('p1', 'hyperboloid of one sheet')], ['z = 4', 'z = 6', 'z = 2'])
    """
    if pieces < 1:
        raise SceneError(f"a totem needs at least one piece, got {pieces}", pieces)
    made = []
    for k in range(pieces):
        c = 2 * k + 1
        if k % 2 == 0:
            q = Quadric.sphere(Fraction(3, 2), (0, 0, c))
        else:
            q = Quadric.hyperboloid_one_sheet(1, 1, 2).translated((0, 0, c))
        made.append(Piece(f"p{k}", q))

    def tree(lo: int, hi: int) -> Split | Piece:
        if hi - lo == 1:
            return made[lo]
        mid = (lo + hi) // 2
        plane = Quadric.plane((0, 0, 1), 2 * mid)
        return Split(plane, tree(mid, hi), tree(lo, mid), name=f"z = {2 * mid}")

    return Composite("totem", tree(0, pieces))


_SHAPES = (
    (Fraction(1, 5), Fraction(3, 20), Fraction(1, 10)),
    (Fraction(1, 4), Fraction(1, 8), Fraction(1, 8)),
    (Fraction(3, 20), Fraction(3, 20), Fraction(3, 20)),
    (Fraction(1, 5), Fraction(1, 10), Fraction(3, 40)),
)
# rational unit directions in the plane (Pythagorean triples)
_DIRS = tuple(
    (Fraction(sx * a, c), Fraction(sy * b, c))
    for a, b, c in ((1, 0, 1), (0, 1, 1), (3, 4, 5), (4, 3, 5), (5, 12, 13), (12, 5, 13), (8, 15, 17))
    for sx in (1, -1)
    for sy in (1, -1)
)


def many_body_scene(
    bodies: int = 1000,
    pieces: int = 16,
    *,
    seed: int = 0,
    duration: int = 4,
    effects: Sequence[str] = ("zone", "contact", "first_contact"),
    check_smallness: bool = True,
    mutual: bool = False,
) -> Scene:
    """``bodies`` small ellipsoids flying straight through and around a :func:`totem`.

    Each body has one of four shapes (semi-axes 1/5 .. 3/40), starts at a random
    rational point at distance 3 to 6 from the totem's axis and height 0 to
    ``2 pieces``, and flies at constant velocity to a random point at distance
    at most 3 from the axis on the other side, over ``duration``; about one in
    ten also turns (a quaternion linear in ``t``).  The same ``seed`` gives the
    same scene.  With ``mutual`` the bodies' contacts with each other are wanted too.

    Examples
    --------
    >>> s = many_body_scene(12, 4, seed=1, check_smallness=False)
    >>> len(s.ellipsoids), len(s.objects[0].pieces), s.span
    (12, 4, (Fraction(0, 1), Fraction(4, 1)))
    """
    rng = random.Random(seed)
    height = 2 * pieces
    ells = []
    for i in range(bodies):
        a, b, c = _SHAPES[rng.randrange(len(_SHAPES))]
        dx, dy = _DIRS[rng.randrange(len(_DIRS))]
        r0 = Fraction(rng.randrange(24, 49), 8)
        z0 = Fraction(rng.randrange(0, 8 * height + 1), 8)
        start = (r0 * dx, r0 * dy, z0)
        ex, ey = _DIRS[rng.randrange(len(_DIRS))]
        r1 = Fraction(rng.randrange(0, 25), 8)
        z1 = min(Fraction(height), max(Fraction(0), z0 + Fraction(rng.randrange(-16, 17), 8)))
        end = (-r1 * ex, -r1 * ey, z1)
        velocity = tuple((end[k] - start[k]) / duration for k in range(3))
        E = Quadric.ellipsoid(a, b, c, center=start)
        translation = tuple((Fraction(0), velocity[k]) for k in range(3))
        quaternion = None
        if rng.randrange(10) == 0:
            axis = rng.randrange(3)
            quaternion = ((1,), *(((0, Fraction(1, 2)) if k == axis else (0,)) for k in range(3)))
        motion = PolynomialMotion(translation, quaternion)
        ells.append(MovingEllipsoid(f"e{i}", E.as_ellipsoid(), motion))
    scene = Scene(
        f"Many bodies: {bodies} ellipsoids around a totem of {pieces} pieces",
        (totem(pieces),),
        tuple(ells),
        (Fraction(0), Fraction(duration)),
        tuple(effects),
        description=f"generated (seed {seed}): straight paths, four shapes, one in ten turning",
        source=f"<generated many_bodies {bodies} {pieces} seed {seed}>",
        on_not_small="refuse",
        places=10,
        mutual=tuple(e.name for e in ells) if mutual else (),
    )
    if check_smallness and scene.needs_smallness():
        scene.check_smallness()
    return scene


GENERATED_SCENES: dict[str, str] = {
    "many_bodies": "1000 ellipsoids on straight paths around a totem of 16 quadric pieces (generated)",
}
"""Scenes made by a generator rather than read from a file (``quadric-contact simulate NAME``)."""
