"""The signed distance along a path: its least value and the times of closest approach,
certified.

An ellipsoid ``E0`` moves rigidly: its centre follows polynomial pieces ``p(t)`` and, on a
piece that turns it, its orientation is the rotation of a polynomial quaternion ``q(t)``
(:mod:`quadric_contact.scenes.trajectory`); the solid of ``Q`` stays.  ``d(t)``, the signed
distance of :func:`quadric_contact.distance` between the moved ellipsoid and ``Q``, moves by at
most the largest displacement of a point of the ellipsoid: if every point moves by at most
``delta``, the new solid lies in the old one widened by a ball of radius ``delta``, and the
distance of two sets, like the translation distance of convex solids (minus the least value of
the sum of their support functions, which widening by a ball raises by ``delta``), moves by at
most ``delta`` (``proofs/distance_along_a_path.py``).  A point at ``y`` from the centre,
``|y| <= rho`` (a rational bound of the largest semi-axis), moves from time ``a`` to ``t`` by at
most ``f(t - a) = V (t - a) + rho min(W (t - a), 2)``, with ``V`` a bound of ``|p'|`` and ``W`` of
the angular speed ``|omega| <= 2 |q'| / |q|`` on the piece (rational upper bounds: the
derivatives enclosed on the interval, ``|q|^2`` enclosed from below; without a positive lower
bound, ``W`` is dropped and the chord bound ``2 rho`` is used).  ``f`` is concave, so on
``[a, b]``::

    min d >= (d(a) + d(b)) / 2 - f((b - a) / 2),

with the certified enclosures of ``d(a)`` and ``d(b)`` (for a translation, ``V (b - a) / 2``).
Subdividing the intervals whose bound does not exceed the least enclosed value seen gives an
enclosure of ``min d`` and a union of time intervals holding every time at which the minimum
is reached.  The bound is first order: near a minimum passed at a steady speed the intervals
must shrink like the tolerance, so a tolerance of about ``10^-3`` of the path's scale is within
a few hundred evaluations.  The number of evaluations is bounded (``max_evaluations``): when the
budget runs out first, the enclosure reached is returned, wider than the tolerance.

In place of ``Q``, a function may give the distance at each time (the moved ellipsoid, a
:class:`~quadric_contact.model.quadric.Quadric`, to an enclosure ``(lo, hi)``): the distance of
the ellipsoid from any fixed set moves by at most ``delta`` too, so the same bound holds for a
piece cut by planes (:func:`quadric_contact.modes.distance.pieces.cut_piece_distance`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from quadric_contact.exact.errors import UndecidedError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.model.quadric import Quadric, as_quadric
from quadric_contact.modes.distances import distance
from quadric_contact.scenes.broadphase import _sqrt_up, ellipsoid_extents, poly_range
from quadric_contact.scenes.trajectory import MotionSegment, Trajectory

__all__ = ["PathDistance", "path_distance"]

_Item = tuple[Fraction, Fraction, MotionSegment, Fraction]
"""A work item of :func:`path_distance`: ``(a, b, segment, f((b - a) / 2))``."""


@dataclass(frozen=True)
class PathDistance:
    """The least signed distance along a path.

    Attributes
    ----------
    minimum : tuple of two Fraction
        ``lo <= min_t d(t) <= hi``.
    times : tuple of (Fraction, Fraction)
        Intervals whose union holds every time at which ``d`` reaches its minimum.
    samples : tuple of (Fraction, Fraction, Fraction)
        ``(t, lo, hi)``: the enclosures of ``d`` computed on the way, in time order.
    """

    minimum: tuple[Fraction, Fraction]
    times: tuple[tuple[Fraction, Fraction], ...]
    samples: tuple[tuple[Fraction, Fraction, Fraction], ...]


def _derivative_bound(polys: Any, a: Fraction, b: Fraction) -> Fraction:
    """``sum_i max |p_i'|^2`` over ``[a, b]``, rounded up: each derivative enclosed by
    :func:`~quadric_contact.scenes.broadphase.poly_range`."""
    total = Fraction(0)
    for p in polys:
        lo, hi = poly_range(p.derivative(), a, b)
        total += max(abs(lo), abs(hi)) ** 2
    return total


def _turn_speed(segment: MotionSegment, a: Fraction, b: Fraction) -> Fraction | None:
    """A rational upper bound ``W`` of the angular speed on ``[a, b]`` (0 without rotation), or
    None where ``|q|^2`` is not bounded away from zero by its enclosure there.

    With ``u = q / |q|``, ``|omega| = 2 |u'|`` and ``|u'|^2 = (|q'|^2 |q|^2 - (q . q')^2) / |q|^4
    <= |q'|^2 / |q|^2``; so ``W^2 = 4 S / N`` with ``S`` the sum of the squared bounds of the
    ``|q_i'|`` and ``N`` a positive lower bound of ``|q|^2`` on the interval."""
    if segment.quaternion is None:
        return Fraction(0)
    norm_low = poly_range(segment.norm_poly(), a, b)[0]
    if norm_low <= 0:
        return None
    return _sqrt_up(4 * _derivative_bound(segment.quaternion, a, b) / norm_low, 30)


def _reach_bound(segment: MotionSegment, a: Fraction, b: Fraction, rho: Fraction) -> Fraction:
    """``f((b - a) / 2)``: a rational upper bound of how far a point of the ellipsoid (within
    ``rho`` of its centre) moves in half the interval: ``V h + rho min(W h, 2)``."""
    h = (b - a) / 2
    w = _turn_speed(segment, a, b)
    turn = 2 * rho if w is None else rho * min(w * h, Fraction(2))
    return _sqrt_up(_derivative_bound(segment.center, a, b), 30) * h + turn


def path_distance(
    E0: Any,
    Q: Any,
    trajectory: Trajectory,
    t0: Any,
    t1: Any,
    *,
    tolerance: Any = Fraction(1, 10**6),
    max_evaluations: int = 400,
) -> PathDistance:
    """Enclose ``min over [t0, t1]`` of the signed distance of the moving ellipsoid from ``Q``.

    Parameters
    ----------
    E0 : the ellipsoid in its initial placement
    Q : a quadric with a solid (as :func:`quadric_contact.distance`), or a function
        From the moved ellipsoid (a :class:`~quadric_contact.model.quadric.Quadric`) to a
        rational enclosure ``(lo, hi)`` of its distance from a fixed set (raising
        :class:`~quadric_contact.exact.errors.UndecidedError` where it does not decide).
    trajectory : Trajectory
        Translations and rotations (a polynomial quaternion per segment).
    t0, t1 : numbers, ``t0 < t1``
    tolerance : number
        Stop when the enclosure of the minimum is this narrow (absolutely).
    max_evaluations : int
        Distances evaluated at most (the ends of the trajectory's segments are evaluated
        first, whatever their number); then the enclosure reached is returned.  Where the
        budget does not allow bisecting every interval still in question, those with the
        lowest bounds are bisected first.

    Raises
    ------
    UndecidedError
        A distance the modes do not decide (its time is named).

    Examples
    --------
    A unit ball flying over the half-space ``z <= 0``, its centre at height ``2 + (t - 1)^2``
    (the distance ``1 + (t - 1)^2``, least at ``t = 1``):

    >>> from quadric_contact import Quadric
    >>> from quadric_contact.scenes.trajectory import PolynomialMotion
    >>> path = PolynomialMotion([[0], [0], [3, -2, 1]])
    >>> r = path_distance(Quadric.sphere(1), "z", path, 0, 2, tolerance="1/1000")
    >>> float(r.minimum[0]) <= 1 <= float(r.minimum[1]), r.minimum[1] - r.minimum[0] <= Fraction(1, 1000)
    (True, True)
    >>> any(a <= 1 <= b for a, b in r.times)
    True

    The same flight over the ball of radius 2 cut to ``z <= 0``, through a distance function: the
    nearest point is the centre of the flat face, at ``2 + (t - 1)^2 - 1`` from the ball:

    >>> from quadric_contact.modes.distance.pieces import cut_piece_distance
    >>> half = lambda placed: cut_piece_distance(placed, Quadric.sphere(2), [("z", "R-")], digits=8).bounds
    >>> r = path_distance(Quadric.sphere(1), half, path, 0, 2, tolerance="1/100")
    >>> float(r.minimum[0]) <= 1 <= float(r.minimum[1])
    True
    """
    e = as_quadric(E0, "E").as_ellipsoid()
    if callable(Q) and not isinstance(Q, Quadric):
        given: Callable[[Quadric], Any] = Q
    else:
        q = as_quadric(Q, "Q")

        def given(placed: Quadric) -> Any:
            return distance([placed], q)[0]

    t0, t1 = to_fraction(t0), to_fraction(t1)
    tol = to_fraction(tolerance)
    if not t0 < t1:
        raise ValueError(f"the time interval must have t0 < t1, got [{t0}, {t1}]")
    c = e.center()
    assert c is not None
    segments = trajectory.segments(t0, t1, c)
    rho = ellipsoid_extents(e)[1]
    cache: dict[Fraction, tuple[Fraction, Fraction]] = {}

    def d(t: Fraction) -> tuple[Fraction, Fraction]:
        if t not in cache:
            placed = trajectory.placed(e, t, t0, t1)
            try:
                lo, hi = given(placed)
            except UndecidedError as exc:
                raise UndecidedError(f"at t = {t}: {exc}", placed, time=t, evaluations=len(cache)) from exc
            cache[t] = (Fraction(lo), Fraction(hi))
        return cache[t]

    def item(
        a: Fraction, b: Fraction, seg: MotionSegment
    ) -> tuple[Fraction, Fraction, MotionSegment, Fraction]:
        """An interval inside one segment, with its displacement bound (computed once)."""
        return a, b, seg, _reach_bound(seg, a, b, rho)

    work = []
    for s in segments:
        a, b = max(s.t0, t0), min(s.t1, t1)
        if a < b:
            work.append(item(a, b, s))
    while True:
        best = min(hi for lo, hi in (d(a) for a, _, _, _ in work))
        best = min(best, min(d(b)[1] for _, b, _, _ in work))
        bounds = [((d(w[0])[0] + d(w[1])[0]) / 2 - w[3], w) for w in work]
        live = [x for x in bounds if x[0] <= best]
        low = min(x[0] for x in live)
        budget = max_evaluations - len(cache)  # one evaluation per bisection (the midpoint)
        if best - low <= tol or budget <= 0:
            break
        wide = sorted((x for x in live if best - x[0] > tol), key=lambda x: x[0])
        split = {w[:2] for _, w in wide[:budget]}
        work = []
        for _, w in live:
            a, b, seg, _ = w
            if (a, b) in split:
                m = (a + b) / 2
                work += [item(a, m, seg), item(m, b, seg)]
            else:
                work.append(w)
    minimum = (min(low, best), best)
    times = tuple(w[:2] for _, w in live)
    samples = tuple(sorted((t, lo, hi) for t, (lo, hi) in cache.items()))
    return PathDistance(minimum, times, samples)
