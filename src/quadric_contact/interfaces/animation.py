"""Animations of a simulated scene, for teaching (matplotlib's animation, pillow writer).

:func:`animate_result` shows the bodies moving through the scene, each
coloured by its state (:data:`~quadric_contact.interfaces.plotting.STATE_COLOURS`: in
contact, inside, outside, the zone of a plane), above the timeline with a
cursor at the current time.  A few bodies are drawn whole (their surfaces at
each frame); many bodies are drawn as points at their centres, and the
timeline then counts the bodies in each state.  :func:`render_gif` writes it
as an animated GIF (``quadric-contact simulate --animate out.gif``).

The frames are drawn with floats at rational frame times; the states come
from the exact timeline (:meth:`~quadric_contact.scenes.simulation_reports.PairResult.state_at`).
"""

from __future__ import annotations

import os
import sys
import tempfile
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from quadric_contact.exact.optional import pyplot, require
from quadric_contact.interfaces.plotting import (
    _colour,
    _constraints,
    _ellipsoid_mesh,
    _plane_value,
    _surface_points,
)

__all__ = ["animate_result", "body_states", "render_gif"]

_ORDER = ("contact", "undecided", "mixed", "inside", "outside", "no contact")


def body_states(result: Any, t: Fraction) -> dict[str, str]:
    """Ellipsoid name -> one state word at the rational time ``t``: ``contact`` if it
    crosses any object or meets another body (mutual contacts), else its state
    against the first object in scene order
    (:meth:`~quadric_contact.scenes.simulation_reports.ObjectState.category`)."""
    out: dict[str, str] = {}
    for pair in result.pairs:
        try:
            cat = pair.state_at(t).category(pair.object)
        except ValueError:  # after an early stop at the first contact
            cat = "contact" if pair.first_contact is not None else "undecided"
        if pair.ellipsoid not in out or cat == "contact":
            out[pair.ellipsoid] = cat
    for m in getattr(result, "mutual", None) or ():  # bodies touching or overlapping each other
        if m.state_at(t) in ("touching", "overlapping"):
            out[m.a] = out[m.b] = "contact"
    return out


def _centres(result: Any, times: list[Fraction]) -> dict[str, Any]:
    scene = result.scene
    t0, t1 = scene.span
    out = {}
    for ell in scene.ellipsoids:
        segs = ell.trajectory.segments(t0, t1, ell.center)
        pts = []
        for t in times:
            seg = next(s for s in segs if s.t0 <= t <= s.t1)
            pts.append([float(v) for v in seg.center_at(t)])
        out[ell.name] = np.array(pts)
    return out


def animate_result(result: Any, *, frames: int = 40, fps: int = 10, whole: int = 12) -> Any:
    """A matplotlib animation of a :class:`~quadric_contact.scenes.simulation_reports.SimulationResult`.

    Parameters
    ----------
    result : SimulationResult
    frames : int
        Frames over the time span (evenly spaced rational times).
    fps : int
        Frames per second (kept on the animation for :func:`render_gif`).
    whole : int
        Up to this many ellipsoids are drawn whole; more are drawn as points.

    Returns
    -------
    matplotlib.animation.FuncAnimation

    Raises
    ------
    MissingDependencyError
        If matplotlib is not installed.
    """
    plt = pyplot("animations")
    animation = require("matplotlib.animation", extra="plot", purpose="animations")
    if frames < 2:
        raise ValueError(f"an animation needs at least 2 frames, got {frames}")
    scene = result.scene
    t0, t1 = scene.span
    times = [t0 + (t1 - t0) * Fraction(i, frames - 1) for i in range(frames)]
    centres = _centres(result, times)
    states = [body_states(result, t) for t in times]
    allpts = np.concatenate(list(centres.values()))
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    pad = np.maximum(1.5, 0.15 * (hi - lo).max())
    box = [(float(lo[k] - pad), float(hi[k] + pad)) for k in range(3)]

    fig = plt.figure(figsize=(7.0, 7.2))
    gs = fig.add_gridspec(2, 1, height_ratios=[5, 1.3], hspace=0.35)
    ax = fig.add_subplot(gs[0], projection="3d")
    palette = ["#8c564b", "#2ca02c", "#bcbd22", "#17becf", "#e377c2", "#7f7f7f"]
    k = 0
    for obj in scene.objects:
        cons = _constraints(obj)
        for piece in obj.pieces:
            P = _surface_points(piece.quadric, box, n=50)
            for plane, side in cons[piece.name]:
                if len(P):
                    P = P[side * _plane_value(plane, P) >= 0]
            if len(P):
                ax.scatter(
                    *P.T, s=1.5, alpha=0.3, color=palette[k % len(palette)], linewidths=0, label=piece.name
                )
            k += 1
    ax.set_xlim(*box[0])
    ax.set_ylim(*box[1])
    ax.set_zlim(*box[2])
    extent = np.array([b[1] - b[0] for b in box])
    ax.set_box_aspect(tuple(np.maximum(extent / extent.max(), 0.25)))
    ax.set_xlabel("x", fontsize=10)
    ax.set_ylabel("y", fontsize=10)
    ax.set_zlabel("z", fontsize=10)
    ax.tick_params(labelsize=9)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(plt.MaxNLocator(4))
    if len(scene.ellipsoids) <= whole:  # the whole path of each body, faint, from the start
        for ell in scene.ellipsoids:
            ax.plot(*centres[ell.name].T, color="#555555", linewidth=0.8, linestyle=(0, (3, 2)), alpha=0.6)
    if k <= 8:
        ax.legend(fontsize=9, loc="upper left", markerscale=6)

    tl = fig.add_subplot(gs[1])
    names = [e.name for e in scene.ellipsoids]
    many = len(names) > whole
    tf = [float(t) for t in times]
    if many:
        cats = sorted({c for st in states for c in st.values()}, key=lambda c: (c not in _ORDER, c))
        counts = np.array([[sum(1 for v in st.values() if v == c) for st in states] for c in cats])
        tl.stackplot(tf, counts, colors=[_colour(c) for c in cats], labels=cats, alpha=0.85)
        tl.set_ylabel("bodies", fontsize=10)
        tl.legend(fontsize=9, ncol=len(cats), loc="upper center", bbox_to_anchor=(0.5, 1.45), frameon=False)
    else:
        for row, pair in enumerate(result.pairs):
            for ep in pair.episodes:
                a, b = float(ep.start), float(ep.end)
                width = max(b - a, float(t1 - t0) / 400)
                tl.barh(row, width, left=a, color=_colour(ep.state.category(pair.object)), height=0.6)
        tl.set_yticks(range(len(result.pairs)))
        tl.set_yticklabels([f"{p.ellipsoid} / {p.object.name}" for p in result.pairs], fontsize=9)
        tl.invert_yaxis()
        seen = dict.fromkeys(ep.state.category(p.object) for p in result.pairs for ep in p.episodes)
        for cat in seen:
            tl.barh(0, 0, color=_colour(cat), label=cat)
        tl.legend(fontsize=9, ncol=len(seen), loc="upper center", bbox_to_anchor=(0.5, 1.45), frameon=False)
    tl.set_xlim(float(t0), float(t1))
    tl.set_xlabel("t", fontsize=10)
    tl.tick_params(labelsize=9)
    cursor = tl.axvline(tf[0], color="black", linewidth=1.2)
    title = ax.set_title("", fontsize=12)
    drawn: list[Any] = []
    trail: dict[str, Any] = {}

    def draw(i: int) -> list[Any]:
        for artist in drawn:
            artist.remove()
        drawn.clear()
        st = states[i]
        if many:
            P = np.array([centres[n][i] for n in names])
            drawn.append(
                ax.scatter(*P.T, s=6, c=[_colour(st.get(n, "free")) for n in names], depthshade=False)
            )
        else:
            for ell in scene.ellipsoids:
                X, Y, Z = _ellipsoid_mesh(ell.trajectory.placed(ell.quadric, times[i], t0, t1), n=12)
                drawn.append(ax.plot_surface(X, Y, Z, color=_colour(st.get(ell.name, "free")), alpha=0.9))
                path = centres[ell.name][: i + 1]
                if ell.name in trail:
                    trail[ell.name].remove()
                (trail[ell.name],) = ax.plot(*path.T, color="black", linewidth=1.6, alpha=0.8)
        cursor.set_xdata([tf[i], tf[i]])
        title.set_text(f"{scene.name}   t = {tf[i]:.3f}")
        return [*drawn, cursor, title]

    anim = animation.FuncAnimation(fig, draw, frames=frames, interval=1000 / fps, blit=False)
    anim._quadric_contact_fps = fps
    return anim


def render_gif(result: Any, *, dpi: int = 80, progress: bool | None = None, **kwargs: Any) -> bytes:
    """The animation of :func:`animate_result` as GIF bytes (pillow writer), so that a
    caller can write the file only once everything has succeeded.

    Parameters
    ----------
    result : SimulationResult
    dpi : int
        Resolution of the frames (the figure is 7 x 7.2 inches).
    progress : bool, optional
        A progress bar of the frames written, on stderr (default: on a terminal).
    **kwargs
        As for :func:`animate_result` (``frames``, ``fps``, ``whole``).

    Returns
    -------
    bytes
    """
    plt = pyplot("animations")
    require("PIL", extra="plot", purpose="GIF animations", package="pillow")
    PillowWriter = require("matplotlib.animation", extra="plot", purpose="animations").PillowWriter
    fps = int(kwargs.get("fps", 10))
    anim = animate_result(result, **kwargs)
    fd, tmp = tempfile.mkstemp(suffix=".gif")
    os.close(fd)
    bar = _frames_bar(int(kwargs.get("frames", 40)), progress)
    try:
        callback = None if bar is None else (lambda i, n: bar.update(1))
        anim.save(tmp, writer=PillowWriter(fps=fps), dpi=dpi, progress_callback=callback)
        return Path(tmp).read_bytes()
    finally:
        if bar is not None:
            bar.close()
        plt.close(anim._fig)
        Path(tmp).unlink(missing_ok=True)


def _frames_bar(total: int, enabled: bool | None) -> Any:
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    from tqdm import tqdm  # tqdm takes tens of ms to import: only when a progress bar is shown

    # every frame is drawn: a frame takes tenths of a second, and a bar that skips
    # updates by time may never show the last one before it is cleared
    return tqdm(
        total=total, desc="animating", unit="frame", file=sys.stderr, leave=False, miniters=1, mininterval=0
    )
