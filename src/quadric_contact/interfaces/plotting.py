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

import numpy as np

from quadric_contact.exact.errors import ShapeError
from quadric_contact.exact.optional import pyplot
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.theory.pencil import as_quadric

__all__ = [
    "STATE_COLOURS",
    "label_rows",
    "merge_close_labels",
    "plot_quadric",
    "plot_result",
    "quadric_mesh",
    "render_png",
]

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
"""Colour of each state category (:meth:`~quadric_contact.scenes.simulation_reports.ObjectState.category`)."""


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
    M = plane.to_numpy(float)
    return 2 * P @ M[:3, 3] + M[3, 3] + np.zeros(len(P))


def _draw_pair(fig: Any, spec: Any, result: Any, pair: Any, samples: int) -> None:
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
    shown = [t0] + ([pair.first_contact[0].rational_near(8)] if pair.first_contact else [])
    for t in shown:
        X, Y, Z = _ellipsoid_mesh(ell.trajectory.placed(ell.quadric, t, t0, t1))
        ax.plot_wireframe(X, Y, Z, color="black", linewidth=0.3, alpha=0.6)
    spots = []
    for ev in pair.events:
        t = ev.time.rational_near(6)
        seg = next((s for s in segs if s.t0 <= t <= s.t1), segs[-1])
        p = [float(v) for v in seg.center_at(t)]
        ax.scatter(*p, color="black", s=10, zorder=6)
        spots.append(p)
    if len(pair.events) <= 12:
        size = max(b_[1] - b_[0] for b_ in box)
        for members, p in merge_close_labels(spots, 0.04 * size):
            ax.text(*p, " " + ",".join(str(k + 1) for k in members), fontsize=8)
    ax.set_xlim(*box[0])
    ax.set_ylim(*box[1])
    ax.set_zlim(*box[2])
    extent = np.array([b_[1] - b_[0] for b_ in box])
    ax.set_box_aspect(tuple(np.maximum(extent / extent.max(), 0.25)))  # true proportions, within 1:4
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(f"{pair.ellipsoid} vs {pair.object.name}", fontsize=11)
    ax.legend(fontsize=8, loc="upper left", markerscale=10)

    tl = fig.add_subplot(spec[1])
    for ep in pair.episodes:
        a, b = float(ep.start), float(ep.end)
        cat = ep.state.category(pair.object)
        tl.barh(0, max(b - a, (float(t1) - float(t0)) / 400), left=a, color=_colour(cat), height=0.5)
    times = [float(ev.time) for ev in pair.events]
    for x in times:
        tl.axvline(x, color="black", linewidth=0.5)
    rows = label_rows(times, 0.045 * (float(t1) - float(t0)))
    if len(pair.events) <= 12:
        for k, (x, row) in enumerate(zip(times, rows, strict=True)):
            tl.text(x, 0.3 + 0.45 * row, f"{k + 1}", fontsize=8, ha="center", va="bottom")
        tl.set_ylim(-0.4, 0.8 + 0.45 * max(rows, default=0))
    seen: dict[str, str] = {}
    for ep in pair.episodes:
        cat = ep.state.category(pair.object)
        seen.setdefault(cat, _colour(cat))
    for cat, col in seen.items():
        tl.barh(0, 0, color=col, label=cat)
    tl.set_yticks([])
    tl.set_xlim(float(t0), float(t1))
    tl.set_xlabel("t")
    tl.legend(fontsize=8, ncol=len(seen), loc="upper center", bbox_to_anchor=(0.5, 1.9), frameon=False)


def label_rows(xs: list[float], gap: float) -> list[int]:
    """A row for each label at ``xs`` (in increasing order) so that two labels of one row
    are at least ``gap`` apart: labels that would collide are stacked.

    Examples
    --------
    >>> label_rows([1.0, 1.01, 1.02, 2.0, 2.5], 0.1)
    [0, 1, 2, 0, 0]
    """
    last: list[float] = []  # the right-most label of each row
    rows = []
    for x in xs:
        row = next((r for r, right in enumerate(last) if x - right >= gap), len(last))
        if row == len(last):
            last.append(x)
        else:
            last[row] = x
        rows.append(row)
    return rows


def merge_close_labels(points: list[list[float]], radius: float) -> list[tuple[list[int], list[float]]]:
    """Indices of points closer than ``radius`` to the first of a group share one label,
    placed at that first point: ``[(members, position), ...]``.

    Examples
    --------
    >>> merge_close_labels([[0, 0, 0], [0, 0, 0.01], [1, 0, 0]], 0.1)
    [([0, 1], [0, 0, 0]), ([2], [1, 0, 0])]
    """
    groups: list[tuple[list[int], list[float]]] = []
    for k, p in enumerate(points):
        for members, q in groups:
            if sum((a - b) ** 2 for a, b in zip(p, q, strict=True)) < radius * radius:
                members.append(k)
                break
        else:
            groups.append(([k], p))
    return groups


def plot_result(result: Any, *, max_pairs: int = 6, samples: int = 240) -> Any:
    """A matplotlib figure of a :class:`~quadric_contact.scenes.simulation_reports.SimulationResult`.

    One column per (ellipsoid, object) pair, up to ``max_pairs``: a 3D view
    above a timeline strip.

    Parameters
    ----------
    result : SimulationResult
    max_pairs : int
        At most this many pairs are drawn (complete timelines first).
    samples : int
        Sample times along each path, for the coloured path only (the states
        come from the exact timeline).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    MissingDependencyError
        If matplotlib is not installed.
    """
    plt = pyplot()
    pairs = [p for p in result.pairs if p.complete][:max_pairs]
    if not pairs:
        pairs = result.pairs[:max_pairs]
    cols = max(1, len(pairs))
    fig = plt.figure(figsize=(5.2 * cols, 6.2))
    gs = fig.add_gridspec(2, cols, height_ratios=[6, 1], hspace=0.35)
    for j, pair in enumerate(pairs):
        _draw_pair(fig, (gs[0, j], gs[1, j]), result, pair, samples)
    fig.suptitle(result.scene.name, fontsize=12)
    return fig


def render_png(result: Any, **kwargs: Any) -> bytes:
    """The figure of :func:`plot_result` as PNG bytes (so that a caller can
    write the file only once everything has succeeded).

    Parameters
    ----------
    result : SimulationResult
    **kwargs
        As for :func:`plot_result`.

    Returns
    -------
    bytes
    """
    plt = pyplot()
    fig = plot_result(result, **kwargs)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=130, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


# -- surface meshes of one quadric ---------------------------------------------------

K = QuadricKind

_ZERO_EIGENVALUES: dict[QuadricKind, int] = {
    K.ELLIPSOID: 0,
    K.HYPERBOLOID_ONE_SHEET: 0,
    K.HYPERBOLOID_TWO_SHEETS: 0,
    K.CONE: 0,
    K.ELLIPTIC_PARABOLOID: 1,
    K.HYPERBOLIC_PARABOLOID: 1,
    K.ELLIPTIC_CYLINDER: 1,
    K.HYPERBOLIC_CYLINDER: 1,
    K.INTERSECTING_PLANES: 1,
    K.PARABOLIC_CYLINDER: 2,
    K.PARALLEL_PLANES: 2,
    K.COINCIDENT_PLANES: 2,
    K.PLANE: 3,
}
"""How many eigenvalues of the quadratic part vanish, for each type with a real surface."""

# Cylinders: the surface contains lines along the null directions of the quadratic part.
_CYLINDERS = frozenset(
    {
        K.ELLIPTIC_CYLINDER,
        K.HYPERBOLIC_CYLINDER,
        K.INTERSECTING_PLANES,
        K.PARABOLIC_CYLINDER,
        K.PARALLEL_PLANES,
        K.COINCIDENT_PLANES,
    }
)

Mesh = tuple[Any, Any, Any]


def _as_box(box: Any) -> Any:
    if box is None:
        return None
    try:
        B = np.array(box, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ShapeError("box must be ((xmin, xmax), (ymin, ymax), (zmin, zmax))", box) from exc
    if B.shape != (3, 2) or not np.isfinite(B).all() or not (B[:, 0] < B[:, 1]).all():
        raise ShapeError("box must be ((xmin, xmax), (ymin, ymax), (zmin, zmax)) with min < max", box)
    return B


def _grid(a: tuple[float, float], b: tuple[float, float], n: int) -> tuple[Any, Any]:
    return np.meshgrid(np.linspace(*a, n), np.linspace(*b, n))


def _parametric(kind: QuadricKind, w: Any, bt: Any, c: float, yB: Any, h: float, n: int) -> list[Any]:
    """Patches ``(3, n, m)`` in the eigenframe ``y`` of the quadratic part, where the
    equation reads ``sum w_i y_i^2 + 2 bt . y + c = 0`` (``w[:nz] = 0``)."""
    nz = _ZERO_EIGENVALUES[kind]
    s = np.zeros(3)  # centre along the non-null directions
    k = -c
    for i in range(nz, 3):
        s[i] = -bt[i] / w[i]
        k += bt[i] * bt[i] / w[i]
    # now: sum_{i >= nz} w_i (y_i - s_i)^2 + 2 sum_{i < nz} bt_i y_i = k
    out: list[Any] = []
    y: list[Any]

    def patch(y0: Any, y1: Any, y2: Any) -> None:
        out.append(np.stack([y0, y1, y2]))

    def reach(idx: list[int]) -> float:
        """Distance from the centre to the far side of the box, in the directions idx."""
        return float(np.linalg.norm([yB[i] - s[i] for i in idx])) + h

    full = np.linspace(0, 2 * np.pi, n)
    if nz == 0:
        if kind is K.ELLIPSOID:
            r = np.sqrt(k / w)
            th, ph = np.meshgrid(full, np.linspace(0, np.pi, max(3, n // 2 + 1)))
            patch(
                s[0] + r[0] * np.cos(th) * np.sin(ph),
                s[1] + r[1] * np.sin(th) * np.sin(ph),
                s[2] + r[2] * np.cos(ph),
            )
            return out
        if kind is K.CONE:
            j = next(
                i
                for i in range(3)
                if np.sign(w[i]) != np.sign(w[(i + 1) % 3]) and np.sign(w[i]) != np.sign(w[(i + 2) % 3])
            )
            i1, i2 = (i for i in range(3) if i != j)
            R = reach([j])
            th, t = np.meshgrid(full, np.linspace(-R, R, n))
            y = [None, None, None]
            y[j] = s[j] + t
            y[i1] = s[i1] + t * np.sqrt(-w[j] / w[i1]) * np.cos(th)
            y[i2] = s[i2] + t * np.sqrt(-w[j] / w[i2]) * np.sin(th)
            patch(*y)
            return out
        # hyperboloids: j is the axis whose eigenvalue has the odd sign out
        same = [i for i in range(3) if np.sign(w[i]) == np.sign(k)]
        other = [i for i in range(3) if i not in same]
        if kind is K.HYPERBOLOID_ONE_SHEET:
            (j,), (i1, i2) = other, same
            r1, r2, rj = np.sqrt(k / w[i1]), np.sqrt(k / w[i2]), np.sqrt(-k / w[j])
            vmax = np.arcsinh(reach([j]) / rj)
            th, v = np.meshgrid(full, np.linspace(-vmax, vmax, n))
            y = [None, None, None]
            y[i1] = s[i1] + r1 * np.cosh(v) * np.cos(th)
            y[i2] = s[i2] + r2 * np.cosh(v) * np.sin(th)
            y[j] = s[j] + rj * np.sinh(v)
            patch(*y)
            return out
        (j,), (i1, i2) = same, other
        r1, r2, rj = np.sqrt(-k / w[i1]), np.sqrt(-k / w[i2]), np.sqrt(k / w[j])
        vmax = np.arcsinh(reach([i1, i2]) / min(r1, r2))
        th, v = np.meshgrid(full, np.linspace(0, vmax, n))
        for sheet in (1, -1):
            y = [None, None, None]
            y[i1] = s[i1] + r1 * np.sinh(v) * np.cos(th)
            y[i2] = s[i2] + r2 * np.sinh(v) * np.sin(th)
            y[j] = s[j] + sheet * rj * np.cosh(v)
            patch(*y)
        return out
    if nz == 1:
        R = reach([1, 2])
        if kind in (K.ELLIPTIC_PARABOLOID, K.HYPERBOLIC_PARABOLOID):
            th, rho = np.meshgrid(full, np.linspace(0, R, n))
            u1, u2 = rho * np.cos(th), rho * np.sin(th)
            patch((k - w[1] * u1 * u1 - w[2] * u2 * u2) / (2 * bt[0]), s[1] + u1, s[2] + u2)
            return out
        along = np.linspace(yB[0] - h, yB[0] + h, n)
        if kind is K.ELLIPTIC_CYLINDER:
            th, t = np.meshgrid(full, along)
            patch(t, s[1] + np.sqrt(k / w[1]) * np.cos(th), s[2] + np.sqrt(k / w[2]) * np.sin(th))
            return out
        if kind is K.HYPERBOLIC_CYLINDER:
            j = 1 if np.sign(w[1]) != np.sign(k) else 2
            i = 3 - j
            ri, rj = np.sqrt(k / w[i]), np.sqrt(-k / w[j])
            vmax = np.arcsinh(reach([j]) / rj)
            v, t = np.meshgrid(np.linspace(-vmax, vmax, n), along)
            for branch in (1, -1):
                y = [t, None, None]
                y[i] = s[i] + branch * ri * np.cosh(v)
                y[j] = s[j] + rj * np.sinh(v)
                patch(*y)
            return out
        # intersecting planes: w1 u1^2 + w2 u2^2 = 0
        u2, t = np.meshgrid(np.linspace(-R, R, n), along)
        for branch in (1, -1):
            patch(t, s[1] + branch * np.sqrt(-w[2] / w[1]) * u2, s[2] + u2)
        return out
    if nz == 2:
        if kind is K.PARABOLIC_CYLINDER:
            e = float(np.hypot(bt[0], bt[1]))
            d = np.array([bt[0], bt[1]]) / e
            p = np.array([-d[1], d[0]])
            tB = float(p @ yB[:2])
            u, tau = _grid((yB[2] - s[2] - h, yB[2] - s[2] + h), (tB - h, tB + h), n)
            sigma = (k - w[2] * u * u) / (2 * e)
            patch(sigma * d[0] + tau * p[0], sigma * d[1] + tau * p[1], s[2] + u)
            return out
        a, b = _grid((yB[0] - h, yB[0] + h), (yB[1] - h, yB[1] + h), n)
        offsets = [0.0] if kind is K.COINCIDENT_PLANES else [np.sqrt(k / w[2]), -np.sqrt(k / w[2])]
        for off in offsets:
            patch(a, b, s[2] + off + 0 * a)
        return out
    # a plane: 2 bt . y + c = 0
    e = float(np.linalg.norm(bt))
    nrm = bt / e
    p1 = np.cross(nrm, [1.0, 0, 0] if abs(nrm[0]) < 0.9 else [0, 1.0, 0])
    p1 /= np.linalg.norm(p1)
    p2 = np.cross(nrm, p1)
    a, b = _grid((p1 @ yB - h, p1 @ yB + h), (p2 @ yB - h, p2 @ yB + h), n)
    base = -c / (2 * e) * nrm
    patch(*(base[i] + a * p1[i] + b * p2[i] for i in range(3)))
    return out


def _graph(kind: QuadricKind, w: Any, bt: Any, c: float, yB: Any, h: float, n: int) -> list[Any]:
    """Patches as graphs along one eigen-direction ``g``: on a grid of the other two
    coordinates, the (stable) roots of the quadratic ``w_g s^2 + 2 bt_g s + G = 0``."""
    if kind is K.PLANE:
        g = int(np.argmax(np.abs(bt)))
    elif kind in _CYLINDERS:
        g = 2  # a non-null direction: the generators lie along the null ones
    else:
        g = 0  # the direction of the eigenvalue smallest in magnitude
    i, j = (m for m in range(3) if m != g)
    ui, uj = _grid((yB[i] - h, yB[i] + h), (yB[j] - h, yB[j] + h), n)
    G = w[i] * ui * ui + w[j] * uj * uj + 2 * bt[i] * ui + 2 * bt[j] * uj + c
    a, beta = w[g], bt[g]
    roots: list[Any]
    with np.errstate(invalid="ignore", divide="ignore"):
        if a == 0:
            roots = [-G / (2 * beta)]
        else:
            disc = beta * beta - a * G
            if kind is K.COINCIDENT_PLANES:
                disc = 0 * disc  # a double root everywhere (rounding would scatter its sign)
            sq = np.sqrt(np.where(disc >= 0, disc, np.nan))
            q = -(beta + np.copysign(sq, beta))
            small = np.where(q != 0, G / q, sq / abs(a))
            roots = [q / a, small]
    out = []
    for r in roots:
        y: list[Any] = [None, None, None]
        y[g], y[i], y[j] = r, ui, uj
        out.append(np.stack(y))
    return out


def quadric_mesh(q: Any, box: Any = None, *, n: int = 40, method: str = "parametric") -> list[Mesh]:
    """Surface patches of a quadric, as float grids for matplotlib's ``plot_surface``.

    The type of ``q`` is decided exactly (:attr:`Quadric.kind`); only the
    geometry of the picture (the principal frame, the semi-axes) is computed
    in floating point.  An illustration, not a computation.

    Parameters
    ----------
    q : Quadric, matrix-like or equation
    box : ((xmin, xmax), (ymin, ymax), (zmin, zmax)), optional
        The part of space to draw; points outside are NaN (matplotlib leaves
        those cells out).  Required for every type but the ellipsoid.
    n : int
        Grid points along each parameter of a patch.
    method : {"parametric", "graph"}
        ``"parametric"`` uses the standard parametrisation of the type in its
        principal frame (trigonometric and hyperbolic functions); ``"graph"``
        solves the equation along one principal direction over a grid of the
        other two (robust for nearly degenerate quadrics such as the
        hyperboloid of Example 6, which looks like a hyperbolic paraboloid
        in any reasonable box; silhouettes come out ragged).

    Returns
    -------
    list of (X, Y, Z)
        One patch per sheet, branch or plane (two for a hyperboloid of two
        sheets, a hyperbolic cylinder, parallel or intersecting planes in the
        parametric method); empty for the types without a real surface
        (imaginary quadrics, a point, a line, the empty set, the zero matrix).

    Raises
    ------
    ShapeError
        A malformed box, or no box for an unbounded surface.

    Examples
    --------
    >>> from quadric_contact import Quadric
    >>> [X.shape for X, Y, Z in quadric_mesh(Quadric.sphere(1), n=12)]
    [(7, 12)]
    >>> len(quadric_mesh("x**2 + y**2 - z**2 + 1", box=[(-3, 3)] * 3))   # two sheets
    2
    """
    if method not in ("parametric", "graph"):
        raise ValueError(f"method must be 'parametric' or 'graph', got {method!r}")
    q = as_quadric(q, "q")
    kind = q.kind
    if kind not in _ZERO_EIGENVALUES:
        return []
    B = _as_box(box)
    if B is None and (kind is not K.ELLIPSOID or method == "graph"):
        raise ShapeError(
            f"a {kind.value} is unbounded: give box=((xmin, xmax), (ymin, ymax), (zmin, zmax))", box
        )
    M = q.to_numpy(float)
    A, b, c = M[:3, :3], M[:3, 3], float(M[3, 3])
    w, V = np.linalg.eigh(A)
    order = np.argsort(np.abs(w), kind="stable")
    w, V = w[order].copy(), V[:, order]
    w[: _ZERO_EIGENVALUES[kind]] = 0.0  # exactly zero (the exact type says how many)
    bt = V.T @ b
    if B is not None:
        centre = B.mean(axis=1)
        yB, h = V.T @ centre, 0.5 * float(np.linalg.norm(B[:, 1] - B[:, 0]))
    else:
        yB, h = np.zeros(3), 0.0
    make = _parametric if method == "parametric" else _graph
    out: list[Mesh] = []
    for patch in make(kind, w, bt, c, yB, h, n):
        pts = np.einsum("ij,j...->i...", V, patch)
        if B is not None:
            lo, hi = B[:, :1, None], B[:, 1:, None]
            with np.errstate(invalid="ignore"):
                outside = ((pts < lo) | (pts > hi)).any(axis=0)
            pts = np.where(outside | ~np.isfinite(pts).all(axis=0), np.nan, pts)
            if np.isnan(pts).all():
                continue
        out.append((pts[0], pts[1], pts[2]))
    return out


def plot_quadric(
    ax: Any, q: Any, box: Any = None, *, n: int = 40, method: str = "parametric", **kwargs: Any
) -> list[Any]:
    """Draw a quadric on a matplotlib 3D axes (:func:`quadric_mesh`, then ``plot_surface``).

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.Axes3D
    q, box, n, method
        As for :func:`quadric_mesh`.
    **kwargs
        Passed to ``plot_surface`` (default ``alpha=0.35``, no edges, and one
        colour for all the patches); a ``label`` goes to the first patch only.

    Returns
    -------
    list
        The ``Poly3DCollection`` of each patch.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> ax = plt.figure().add_subplot(projection="3d")
    >>> len(plot_quadric(ax, "x**2 + y**2 - z**2 - 1", box=[(-2, 2)] * 3, color="tab:green"))
    1
    """
    options = {"alpha": 0.35, "linewidth": 0, "rstride": 1, "cstride": 1, **kwargs}
    label = options.pop("label", None)
    if not {"color", "facecolors", "cmap"} & set(options):
        # one colour for every patch of this quadric: the next one of the axes' cycle
        get_next = getattr(getattr(ax, "_get_lines", None), "get_next_color", None)
        if get_next is not None:
            options["color"] = get_next()
    artists = []
    for k, (X, Y, Z) in enumerate(quadric_mesh(q, box, n=n, method=method)):
        extra = {"label": label} if (k == 0 and label is not None) else {}
        artists.append(ax.plot_surface(X, Y, Z, **options, **extra))
    return artists
