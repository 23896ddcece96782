"""Surface meshes of single quadrics (plotting.quadric_mesh / plot_quadric)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from quadric_contact import Quadric, QuadricKind
from quadric_contact.exact.errors import ShapeError
from quadric_contact.interfaces.plotting import plot_quadric, quadric_mesh

BOX = [(-3, 3), (-2, 4), (-3, 3)]

# (quadric, patches in the parametric method) for every type with a real surface
CASES = {
    "ellipsoid": (Quadric.ellipsoid(2, Fraction(3, 2), 1, center=(0, 1, 0), rotation=(1, 2, 3, 4)), 1),
    "one sheet": (Quadric.hyperboloid_one_sheet(1, 2, 1).rotated((1, 1, 0, 0)), 1),
    "two sheets": (Quadric.hyperboloid_two_sheets(1, 2, 1).rotated((3, 0, 1, 2)), 2),
    "elliptic paraboloid": (Quadric.elliptic_paraboloid(1, 2).translated((0, 1, -2)), 1),
    "hyperbolic paraboloid": (Quadric.hyperbolic_paraboloid(1, 1).rotated((3, 1, 0, 1)), 1),
    "elliptic cylinder": (Quadric.elliptic_cylinder(2, 1).rotated((2, 0, 1, 0)), 1),
    "hyperbolic cylinder": (Quadric.hyperbolic_cylinder(1, 2).rotated((1, 1, 1, 1)), 2),
    "parabolic cylinder": (Quadric.parabolic_cylinder(1).rotated((1, 1, 1, 0)), 1),
    "parallel planes": (Quadric.parallel_planes(1).rotated((2, 1, 0, 0)), 2),
    "plane": (Quadric.plane((1, 2, 2), 1), 1),
    "cone": (Quadric.from_equation("x**2 + 2*y**2 - (z - 1)**2"), 1),
    "intersecting planes": (Quadric.from_equation("x**2 - 4*y**2 + 2*x"), 2),
    "coincident planes": (Quadric.from_equation("(x + y - 1)**2"), 1),
}


def _residuals(q: Quadric, mesh):
    M = q.to_numpy(float)
    scale = np.abs(M).max()
    out = []
    for X, Y, Z in mesh:
        P = np.stack([X.ravel(), Y.ravel(), Z.ravel(), np.ones(X.size)])
        P = P[:, np.isfinite(P).all(axis=0)]
        out.append(np.abs(np.einsum("in,ij,jn->n", P, M, P)) / (scale * (P * P).sum(axis=0)))
    return np.concatenate(out)


def _surface_samples(q: Quadric, box, n=25):
    """Points of the surface in the box, found independently: roots of the equation
    along lines parallel to each axis (numpy's polynomial roots)."""
    M = q.to_numpy(float)
    lo, hi = np.array(box, dtype=float).T
    pts = []
    for axis in range(3):
        others = [k for k in range(3) if k != axis]
        for u in np.linspace(lo[others[0]], hi[others[0]], n):
            for v in np.linspace(lo[others[1]], hi[others[1]], n):
                X = np.zeros(4)
                X[others[0]], X[others[1]], X[3] = u, v, 1.0
                e = np.zeros(4)
                e[axis] = 1.0
                coeffs = [e @ M @ e, 2 * e @ M @ X, X @ M @ X]
                while coeffs and abs(coeffs[0]) < 1e-12:
                    coeffs = coeffs[1:]
                if len(coeffs) < 2:
                    continue
                for s in np.roots(coeffs):
                    if abs(s.imag) < 1e-12:
                        p = X[:3] + s.real * e[:3]
                        if (p >= lo).all() and (p <= hi).all():
                            pts.append(p)
    return np.array(pts)


@pytest.mark.parametrize("method", ["parametric", "graph"])
@pytest.mark.parametrize("name", list(CASES))
def test_mesh_points_lie_on_the_surface_inside_the_box(name, method):
    q, patches = CASES[name]
    mesh = quadric_mesh(q, BOX, n=30, method=method)
    assert mesh
    if method == "parametric":
        assert len(mesh) == patches
    assert _residuals(q, mesh).max() < 1e-9
    lo, hi = np.array(BOX, dtype=float).T
    for X, Y, Z in mesh:
        pts = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
        pts = pts[np.isfinite(pts).all(axis=1)]
        assert ((pts >= lo) & (pts <= hi)).all()


def _coverage(q: Quadric, box, mesh):
    """(largest distance from an independently found surface point to the nearest mesh
    vertex, largest mesh cell diagonal, number of surface points checked)."""
    vertices, cell = [], 0.0
    for X, Y, Z in mesh:
        P = np.stack([X, Y, Z], axis=-1)
        d1 = np.linalg.norm(P[1:, 1:] - P[:-1, :-1], axis=-1)
        d2 = np.linalg.norm(P[1:, :-1] - P[:-1, 1:], axis=-1)
        cell = max(cell, np.nanmax(d1), np.nanmax(d2))
        vertices.append(P.reshape(-1, 3))
    V = np.concatenate(vertices)
    V = V[np.isfinite(V).all(axis=1)]
    samples = _surface_samples(q, box)
    lo, hi = np.array(box, dtype=float).T
    margin = 0.05 * (hi - lo).min()  # cells cut by the box may leave a gap at its faces
    inner = samples[((samples >= lo + margin) & (samples <= hi - margin)).all(axis=1)]
    nearest = np.sqrt(((inner[:, None, :] - V[None, :, :]) ** 2).sum(axis=-1)).min(axis=1)
    return nearest.max(), cell, len(inner)


@pytest.mark.parametrize("name", list(CASES))
def test_parametric_mesh_covers_the_surface_in_the_box(name):
    """Every surface point found independently lies within one mesh cell of a vertex."""
    q, _ = CASES[name]
    worst, cell, checked = _coverage(q, BOX, quadric_mesh(q, BOX, n=50))
    assert checked > 20
    assert worst <= cell, (worst, cell)


def test_a_whole_ellipsoid_needs_no_box():
    q = Quadric.ellipsoid(3, 2, 1, center=(1, 2, 3), rotation=(1, 2, 3, 4))
    ((X, Y, Z),) = quadric_mesh(q, n=16)
    assert np.isfinite(X).all() and X.shape == (9, 16)
    assert _residuals(q, [(X, Y, Z)]).max() < 1e-12
    centre = np.array([float(c) for c in q.center()])
    assert np.allclose(np.stack([X, Y, Z], axis=-1).reshape(-1, 3).mean(axis=0), centre, atol=0.5)


@pytest.mark.parametrize(
    "equation",
    ["x**2 + y**2 + z**2 + 1", "x**2 + y**2 + z**2", "x**2 + y**2 + 1", "x**2 + y**2", "x**2 + 1", "1"],
)
def test_no_real_surface_gives_no_patch(equation):
    q = Quadric.from_equation(equation)
    assert q.kind not in (QuadricKind.PLANE, QuadricKind.ELLIPSOID)
    assert quadric_mesh(q, BOX) == []


def test_unbounded_surfaces_need_a_box_and_bad_input_is_refused():
    with pytest.raises(ShapeError, match="unbounded"):
        quadric_mesh("x**2 + y**2 - z**2 - 1")
    with pytest.raises(ShapeError, match="box"):
        quadric_mesh("x**2 + y**2 - z**2 - 1", [(0, 1), (0, 1)])
    with pytest.raises(ShapeError, match="min < max"):
        quadric_mesh("x**2 + y**2 - z**2 - 1", [(0, 1), (1, 0), (0, 1)])
    with pytest.raises(ValueError, match="method"):
        quadric_mesh("x**2 + y**2 + z**2 - 1", method="marching cubes")


def test_graph_method_draws_a_nearly_degenerate_hyperboloid():
    """The hyperboloid of Example 6 (an eigenvalue 1.7e-7): the graph along its
    nearly null direction lands on the surface."""
    from quadric_contact.paper import PRINTED

    rows = [[Fraction(v) for v in row.split()] for row in PRINTED["Example 6 Q"].split(";")]
    q = Quadric(rows)
    assert q.kind is QuadricKind.HYPERBOLOID_ONE_SHEET
    box = [(-8, -4), (-7, -3), (-5, -1)]  # around the ellipsoid of Example 6, near the saddle
    mesh = quadric_mesh(q, box, n=40, method="graph")
    assert _residuals(q, mesh).max() < 1e-9
    worst, cell, checked = _coverage(q, box, mesh)
    assert checked > 20
    assert worst <= cell, (worst, cell)


def test_plot_quadric_draws_one_colour_and_one_label():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure()
    ax = fig.add_subplot(projection="3d")
    artists = plot_quadric(ax, "x**2 + y**2 - z**2 + 1", BOX, label="two sheets")
    assert len(artists) == 2
    assert artists[0].get_label() == "two sheets"
    colours = {tuple(np.round(a.get_facecolor()[0][:3], 6)) for a in artists}
    assert len(colours) == 1
    plt.close(fig)


def test_plot_result_keeps_the_backend_of_a_session_that_uses_pyplot():
    """A notebook's inline backend must survive drawing a scene (the command line,
    which has not imported pyplot, draws off-screen)."""
    matplotlib = pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from quadric_contact.interfaces.plotting import plot_result
    from quadric_contact.scenes.scene_toml import builtin_scene
    from quadric_contact.scenes.simulate import simulate

    before = matplotlib.get_backend()
    plt.switch_backend("svg")
    try:
        fig = plot_result(simulate(builtin_scene(), effects=["zone"]), samples=20)
        assert matplotlib.get_backend() == "svg"
        plt.close(fig)
    finally:
        plt.switch_backend(before)
