"""Pictures of a simulated scene (matplotlib, the optional ``plot`` extra).

:func:`plot_result` draws, for each moving ellipsoid and object, a 3D view
(the pieces, clipped to their zones; the separating planes; the path of the
centre coloured by state; the ellipsoid at the start and at each event) and a
timeline strip of the states with the exact event times.  Drawing uses floats:
the picture is an illustration, the timeline it shows is the exact one.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from fractions import Fraction
from typing import Any

from .composite import Composite, Piece, Split
from .errors import MissingDependencyError
from .quadric import Quadric

__all__ = ["STATE_COLOURS", "plot_result", "render_png"]

STATE_COLOURS: dict[str, str] = {
    "contact": "#d62728",
    "inside": "#2ca02c",
    "outside": "#1f77b4",
    "mixed": "#9467bd",
    "no contact": "#1f77b4",
    "undecided": "#7f7f7f",
    "zone 0": "#d62728",
    "zone 1": "#ff7f0e",
    "zone 2": "#1f77b4",
    "free": "#1f77b4",
}
"""Colour of each state category (:meth:`~quadric_contact.simulate.ObjectState.category`)."""


def _matplotlib() -> Any:
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise MissingDependencyError(
            "plots need matplotlib: pip install 'quadric-contact[plot]' (or pip install matplotlib)"
        ) from exc
    return plt


def _colour(category: str) -> str:
    if category.startswith("zone "):
        return STATE_COLOURS.get(category.split("/")[0], "#1f77b4")
    return STATE_COLOURS.get(category, "#7f7f7f")


def _constraints(obj: Composite) -> dict[str, list[tuple[Quadric, int]]]:
    """Piece name -> planes and sides (+1 for R+, -1 for R-) on the way from the root."""
    out: dict[str, list[tuple[Quadric, int]]] = {}

    def visit(node: Split | Piece | None, path: list[tuple[Quadric, int]]) -> None:
        if node is None:
            return
        if isinstance(node, Piece):
            out.setdefault(node.name, path)
            return
        visit(node.plus, [*path, (node.plane, 1)])
        visit(node.minus, [*path, (node.plane, -1)])

    visit(obj.root, [])
    for p in obj.pieces:
        out.setdefault(p.name, [])
    return out


def _surface_points(q: Quadric, box: Sequence[tuple[float, float]], n: int = 70) -> Any:
    """Points of the surface ``X^T Q X = 0`` in the box, found along grid lines in x, y and z."""
    import numpy as np

    M = q.to_numpy(float)
    pts = []
    for axis in range(3):
        others = [k for k in range(3) if k != axis]
        u = np.linspace(*box[others[0]], n)
        v = np.linspace(*box[others[1]], n)
        U, V = np.meshgrid(u, v)
        X = np.zeros((4, *U.shape))
        X[others[0]], X[others[1]], X[3] = U, V, 1.0
        # X(s) = X + s e_axis: a s^2 + b s + c = 0
        a = M[axis, axis]
        b = 2 * np.einsum("i,i...->...", M[axis], X)
        c = np.einsum("i...,ij,j...->...", X, M, X)
        with np.errstate(invalid="ignore", divide="ignore"):
            if abs(a) > 1e-14:
                disc = b * b - 4 * a * c
                ok = disc >= 0
                r = np.sqrt(np.where(ok, disc, 0.0))
                roots = [np.where(ok, (-b + r) / (2 * a), np.nan), np.where(ok, (-b - r) / (2 * a), np.nan)]
            else:
                roots = [np.where(np.abs(b) > 1e-14, -c / b, np.nan)]
        for s in roots:
            P = np.stack([U, V, s], axis=-1) if axis == 2 else None
            if axis == 0:
                P = np.stack([s, U, V], axis=-1)
            elif axis == 1:
                P = np.stack([U, s, V], axis=-1)
            assert P is not None
            P = P.reshape(-1, 3)
            P = P[np.isfinite(P).all(axis=1)]
            lo = np.array([b_[0] for b_ in box])
            hi = np.array([b_[1] for b_ in box])
            P = P[((lo <= P) & (hi >= P)).all(axis=1)]
            pts.append(P)
    return np.concatenate(pts) if pts else np.zeros((0, 3))


def _ellipsoid_mesh(E: Quadric, n: int = 14) -> tuple[Any, Any, Any]:
    """A (float) mesh of the surface of the ellipsoid ``E``."""
    import numpy as np

    M = E.to_numpy(float)
    A, b, c = M[:3, :3], M[:3, 3], M[3, 3]
    centre = -np.linalg.solve(A, b)
    k = b @ np.linalg.solve(A, b) - c
    w, V = np.linalg.eigh(A / k)
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n), np.linspace(0, np.pi, n))
    S = np.stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)], axis=-1) / np.sqrt(w)
    P = S @ V.T + centre
    return P[..., 0], P[..., 1], P[..., 2]


def _plane_value(plane: Quadric, P: Any) -> Any:
    import numpy as np

    M = plane.to_numpy(float)
    return 2 * P @ M[:3, 3] + M[3, 3] + np.zeros(len(P))


def _draw_pair(fig: Any, spec: Any, result: Any, pair: Any, samples: int) -> None:
    import numpy as np

    scene = result.scene
    t0, t1 = scene.span
    ell = next(e for e in scene.ellipsoids if e.name == pair.ellipsoid)
    segs = ell.trajectory.segments(t0, t1, ell.center)
    times = [t0 + (t1 - t0) * Fraction(i, samples) for i in range(samples + 1)]
    centres, cats = [], []
    for t in times:
        seg = next(s for s in segs if s.t0 <= t <= s.t1)
        centres.append([float(v) for v in seg.center_at(t)])
        try:
            cats.append(pair.state_at(t).category(pair.object))
        except ValueError:
            cats.append("undecided")
    C = np.array(centres)
    lo, hi = C.min(axis=0), C.max(axis=0)
    pad = np.maximum(2.0, 0.4 * (hi - lo).max())
    box = [(float(lo[k] - pad), float(hi[k] + pad)) for k in range(3)]

    ax = fig.add_subplot(spec[0], projection="3d")
    cons = _constraints(pair.object)
    palette = ["#8c564b", "#2ca02c", "#bcbd22", "#17becf", "#e377c2", "#7f7f7f"]
    for i, piece in enumerate(pair.object.pieces):
        P = _surface_points(piece.quadric, box)
        for plane, side in cons[piece.name]:
            if len(P):
                P = P[side * _plane_value(plane, P) >= 0]
        if len(P):
            ax.scatter(
                *P.T, s=1.2, alpha=0.3, color=palette[i % len(palette)], label=piece.name, linewidths=0
            )
    for split in pair.object.splits():
        n = split.plane.to_numpy(float)[:3, 3] * 2
        d = -split.plane.to_numpy(float)[3, 3]
        k = int(np.argmax(np.abs(n)))
        o = [j for j in range(3) if j != k]
        U, V = np.meshgrid(np.linspace(*box[o[0]], 8), np.linspace(*box[o[1]], 8))
        W = (d - n[o[0]] * U - n[o[1]] * V) / n[k]
        grid: list[Any] = [None, None, None]
        grid[k], grid[o[0]], grid[o[1]] = W, U, V
        ax.plot_surface(*grid, alpha=0.12, color="#999999")
    for i in range(len(C) - 1):
        ax.plot(*C[i : i + 2].T, color=_colour(cats[i]), linewidth=2.2, zorder=5)
    # the ellipsoid where it starts and where it first touches
    shown = [t0] + ([pair.first_contact[0].approx(8)] if pair.first_contact else [])
    for t in shown:
        X, Y, Z = _ellipsoid_mesh(ell.trajectory.placed(ell.quadric, t, t0, t1))
        ax.plot_wireframe(X, Y, Z, color="black", linewidth=0.3, alpha=0.6)
    for k, ev in enumerate(pair.events):
        t = ev.time.approx(6)
        seg = next((s for s in segs if s.t0 <= t <= s.t1), segs[-1])
        p = [float(v) for v in seg.center_at(t)]
        ax.scatter(*p, color="black", s=10, zorder=6)
        if len(pair.events) <= 12:
            ax.text(*p, f" {k + 1}", fontsize=6)
    ax.set_xlim(*box[0])
    ax.set_ylim(*box[1])
    ax.set_zlim(*box[2])
    extent = np.array([b_[1] - b_[0] for b_ in box])
    ax.set_box_aspect(tuple(np.maximum(extent / extent.max(), 0.25)))  # true proportions, within 1:4
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(f"{pair.ellipsoid} vs {pair.object.name}", fontsize=9)
    ax.legend(fontsize=6, loc="upper left", markerscale=10)

    tl = fig.add_subplot(spec[1])
    for ep in pair.episodes:
        a, b = float(ep.start), float(ep.end)
        cat = ep.state.category(pair.object)
        tl.barh(0, max(b - a, (float(t1) - float(t0)) / 400), left=a, color=_colour(cat), height=0.5)
    for k, ev in enumerate(pair.events):
        tl.axvline(float(ev.time), color="black", linewidth=0.5)
        if len(pair.events) <= 12:
            tl.text(float(ev.time), 0.3, f"{k + 1}", fontsize=6, ha="center", va="bottom")
    seen: dict[str, str] = {}
    for ep in pair.episodes:
        cat = ep.state.category(pair.object)
        seen.setdefault(cat, _colour(cat))
    for cat, col in seen.items():
        tl.barh(0, 0, color=col, label=cat)
    tl.set_yticks([])
    tl.set_xlim(float(t0), float(t1))
    tl.set_xlabel("t")
    tl.legend(fontsize=6, ncol=len(seen), loc="upper center", bbox_to_anchor=(0.5, 1.9), frameon=False)


def plot_result(result: Any, *, max_pairs: int = 6, samples: int = 240) -> Any:
    """A matplotlib figure of a :class:`~quadric_contact.simulate.SimulationResult`.

    One column per (ellipsoid, object) pair, up to ``max_pairs``: a 3D view
    above a timeline strip.

    Raises
    ------
    MissingDependencyError
        If matplotlib is not installed.
    """
    plt = _matplotlib()
    pairs = [p for p in result.pairs if p.complete][:max_pairs]
    if not pairs:
        pairs = result.pairs[:max_pairs]
    cols = max(1, len(pairs))
    fig = plt.figure(figsize=(5.2 * cols, 6.2))
    gs = fig.add_gridspec(2, cols, height_ratios=[6, 1], hspace=0.35)
    for j, pair in enumerate(pairs):
        _draw_pair(fig, (gs[0, j], gs[1, j]), result, pair, samples)
    fig.suptitle(result.scene.name, fontsize=10)
    return fig


def render_png(result: Any, **kwargs: Any) -> bytes:
    """The figure of :func:`plot_result` as PNG bytes (so that a caller can
    write the file only once everything has succeeded)."""
    plt = _matplotlib()
    fig = plot_result(result, **kwargs)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=130, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()
