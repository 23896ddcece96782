"""Pieces as cut: the plane-section decisions and the scenes' timelines in both readings,
against computations that do not use the pencil: dense sampling of the ellipsoid's
surface in floating point, and closed forms of the event times where the geometry
gives one."""

from __future__ import annotations

import json
import random
from fractions import Fraction as F

import numpy as np
import pytest
import sympy as sp

from quadric_contact import Quadric
from quadric_contact.exact.algebraic import sign_at
from quadric_contact.exact.errors import ChoiceError, SceneError
from quadric_contact.exact.rational import fmpq_poly_of
from quadric_contact.scenes.composite import Piece, Split
from quadric_contact.scenes.scene_toml import builtin_scene, builtin_scene_names, parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.theory.sections import (
    conic_pencil_coefficients,
    conics_meet,
    cubic_discriminant,
    curve_meets_half_space,
    plane_form,
    section_matrix,
)

# -- independent float sampling ------------------------------------------------------------


def _matrix(q: Quadric) -> np.ndarray:
    return np.array([[float(v) for v in row] for row in q.matrix])


def _sphere_directions(n: int) -> np.ndarray:
    """``n`` nearly uniform unit vectors (a Fibonacci lattice)."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    phi = np.pi * (1 + 5**0.5) * k
    r = np.sqrt(1 - z * z)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def _surface_points(E: Quadric, n: int = 40000) -> np.ndarray:
    """Points of the ellipsoid's surface, in homogeneous coordinates."""
    M = _matrix(E)
    A, b, d = M[:3, :3], M[:3, 3], M[3, 3]
    if np.linalg.det(A) < 0:  # the inside positive: negate
        A, b, d = -A, -b, -d
    c = -np.linalg.solve(A, b)
    k = float(c @ A @ c) - d  # (x - c)^T A (x - c) = k
    w, V = np.linalg.eigh(A)
    x = c + (_sphere_directions(n) * np.sqrt(k / w)) @ V.T
    return np.hstack([x, np.ones((n, 1))])


def _values(Q: Quadric, X: np.ndarray) -> np.ndarray:
    return np.einsum("ni,ij,nj->n", X, _matrix(Q), X)


def _crosses(values: np.ndarray, scale: float) -> bool | None:
    """Both signs clearly present: True; one sign only, clearly: False; else None."""
    if values.size == 0:
        return False
    lo, hi = values.min(), values.max()
    tol = 1e-9 * scale
    if lo < -tol and hi > tol:
        return True
    if lo > tol or hi < -tol:
        return False
    return None


# -- the static decisions --------------------------------------------------------------------


def _random_ellipse(rng: random.Random) -> Quadric:
    a, b = (F(rng.randint(2, 12), rng.randint(2, 6)) for _ in range(2))
    center = (F(rng.randint(-8, 8), 4), F(rng.randint(-8, 8), 4), 0)
    return Quadric.ellipsoid(a, b, 1, center=center)


def test_section_matrix_is_the_restriction_to_the_plane():
    rng = random.Random(3)
    for _ in range(20):
        Q = Quadric._from_upper(tuple(F(rng.randint(-9, 9), rng.randint(1, 4)) for _ in range(10)))
        n = [F(rng.randint(-3, 3)) for _ in range(3)]
        if not any(n):
            n[2] = F(1)
        plane = Quadric.plane(tuple(n), F(rng.randint(-5, 5)))
        S = section_matrix(Q.upper, plane)
        nn, d = plane_form(plane)
        # points of the plane from the frame, and the quadric's value there
        for _ in range(5):
            u, v = F(rng.randint(-9, 9), 3), F(rng.randint(-9, 9), 3)
            X = [u, v, F(1)]
            conic = sum(X[i] * S[i][j] * X[j] for i in range(3) for j in range(3))
            # solve for the point: find it by evaluating Q on the same point
            from quadric_contact.theory.sections import section_frame

            dirs, origin, _step = section_frame(plane)
            P = [u * dirs[0][k] + v * dirs[1][k] + origin[k] for k in range(4)]
            assert sum(nn[k] * P[k] for k in range(3)) + d == 0
            assert conic == sum(P[i] * Q.matrix[i][j] * P[j] for i in range(4) for j in range(4))


def test_cubic_formulas_are_sympy_s():
    a = sp.symbols("a0:9")
    b = sp.symbols("b0:9")
    A = sp.Matrix(3, 3, lambda i, j: a[3 * min(i, j) + max(i, j)])
    B = sp.Matrix(3, 3, lambda i, j: b[3 * min(i, j) + max(i, j)])
    lam = sp.Symbol("lam")
    c = conic_pencil_coefficients(A.tolist(), B.tolist())
    poly = sp.Poly((lam * A + B).det(method="berkowitz"), lam)
    assert all(sp.expand(c[k] - poly.coeff_monomial(lam**k)) == 0 for k in range(4))
    k = sp.symbols("k0:4")
    generic = sp.Poly(sum(k[i] * lam**i for i in range(4)), lam)
    assert sp.expand(cubic_discriminant(*k) - sp.discriminant(generic)) == 0


def test_conics_meet_agrees_with_sampling_the_ellipse():
    rng = random.Random(11)
    theta = np.linspace(0, 2 * np.pi, 20001)
    checked = 0
    for _ in range(80):
        E = _random_ellipse(rng)
        Q = Quadric._from_upper(tuple(F(rng.randint(-6, 6), rng.randint(1, 3)) for _ in range(10)))
        z0 = Quadric.plane((0, 0, 1), 0)
        A, B = section_matrix(E.upper, z0), section_matrix(Q.upper, z0)
        Af = np.array([[float(v) for v in row] for row in A])
        Bf = np.array([[float(v) for v in row] for row in B])
        c = -np.linalg.solve(Af[:2, :2], Af[:2, 2])
        k = float(c @ Af[:2, :2] @ c) - Af[2, 2]
        w, V = np.linalg.eigh(Af[:2, :2])
        pts = c + (np.stack([np.cos(theta), np.sin(theta)], 1) * np.sqrt(k / w)) @ V.T
        X = np.hstack([pts, np.ones((len(theta), 1))])
        vals = np.einsum("ni,ij,nj->n", X, Bf, X)
        expected = _crosses(vals, float(np.abs(Bf).max()))
        if expected is None:
            continue
        assert conics_meet(A, B) == expected
        checked += 1
    assert checked >= 60


def test_curve_meets_half_space_agrees_with_sampling_the_cap():
    """E ∩ H is a connected cap: the crossing curve meets it iff Q changes sign on it."""
    rng = random.Random(5)
    checked = {True: 0, False: 0}
    for _ in range(240):
        E = Quadric.ellipsoid(
            F(rng.randint(2, 8), 4), F(rng.randint(2, 8), 4), F(rng.randint(2, 8), 4),
            center=tuple(F(rng.randint(-4, 4), 4) for _ in range(3)),
        )  # fmt: skip
        kind = rng.choice(["sphere", "hyperboloid", "cylinder"])
        if kind == "sphere":
            centre = tuple(F(rng.randint(-8, 8), 4) for _ in range(3))
            Q = Quadric.sphere(F(rng.randint(4, 10), 4), center=centre)
        elif kind == "hyperboloid":
            Q = Quadric.hyperboloid_one_sheet(1, F(3, 2), 2).translated(
                tuple(F(rng.randint(-8, 8), 8) for _ in range(3))
            )
        else:
            Q = Quadric.from_equation(f"x^2 + 2*y^2 - {F(rng.randint(1, 9), 4)}")
        n = tuple(F(rng.randint(-3, 3)) for _ in range(3))
        if not any(n):
            continue
        plane = Quadric.plane(n, F(rng.randint(-4, 4), 4))
        side = rng.choice([1, -1])
        X = _surface_points(E)
        q = _values(Q, X)
        if _crosses(q, 1.0) is not True:
            continue
        nn, d = plane_form(plane)
        pi = X[:, :3] @ np.array([float(v) for v in nn]) + float(d)
        expected = _crosses(q[side * pi >= 0], 1.0)
        if expected is None:
            continue
        got = curve_meets_half_space(E, Q, plane, side)
        assert got == expected, (E, Q, plane, side)
        checked[expected] += 1
    assert checked[True] >= 5 and checked[False] >= 5, checked


# -- the scenes, in both readings --------------------------------------------------------------


def _paths(node, kept=()):
    """(piece, [(plane, side), ...]) for every leaf of an object's tree."""
    if node is None:
        return []
    if isinstance(node, Piece):
        return [(node, list(kept))]
    assert isinstance(node, Split)
    return _paths(node.plus, (*kept, (node.plane, 1))) + _paths(node.minus, (*kept, (node.plane, -1)))


def _expected(obj, E, reading, points=12000):
    """Piece name -> contact, from the ellipsoid's sampled surface (None: too close to call)."""
    X = _surface_points(E, points)
    out: dict[str, bool | None] = {}
    leaves = _paths(obj.root) if not isinstance(obj.root, Piece) else [(obj.root, [])]
    leaves += [(p, []) for p in obj.extra_pieces]
    for piece, kept in leaves:
        q = _values(piece.quadric, X)
        mask = np.ones(len(X), dtype=bool)
        reached = True
        for plane, side in kept:
            nn, d = plane_form(plane)
            pi = side * (X[:, :3] @ np.array([float(v) for v in nn]) + float(d))
            if np.max(pi) < 0:
                reached = False
            elif -1e-9 < np.max(pi) < 1e-6:
                out[piece.name] = None
            mask &= pi >= 0
        if reached is False:
            value: bool | None = False
        elif reading == "paper":
            value = _crosses(q, 1.0)
        else:
            value = _crosses(q[mask], 1.0)
        if out.get(piece.name, False) is None:
            continue
        out[piece.name] = value if piece.name not in out or out[piece.name] is False else out[piece.name]
    return out


@pytest.mark.parametrize("reading", ["geometry", "paper"])
@pytest.mark.parametrize("name", builtin_scene_names())
def test_builtin_scene_contacts_agree_with_sampling(name, reading):
    """Every piece's contact at many times, against the surface sampled in floats: in the
    geometric reading only the kept part of the ellipsoid's surface counts."""
    _compare_with_sampling(name, reading, steps=48, points=8000)


@pytest.mark.slow
@pytest.mark.parametrize("reading", ["geometry", "paper"])
@pytest.mark.parametrize("name", builtin_scene_names())
def test_builtin_scene_contacts_agree_with_dense_sampling(name, reading):
    _compare_with_sampling(name, reading, steps=400, points=60000)


def _compare_with_sampling(name, reading, *, steps, points):
    scene = builtin_scene(name)
    result = simulate(scene, effects=["contact"], reading=reading)
    t0, t1 = scene.span
    steps = steps if len(scene.ellipsoids) < 4 else steps // 4
    compared = 0
    for pair in result.pairs:
        if not pair.complete:
            continue
        own = result.plan.restricted(scene.ellipsoid_effects.get(pair.ellipsoid))
        asked = {
            p.name
            for p in pair.object.pieces
            if own.restricted(scene.piece_effects.get((pair.object.name, p.name))).pieces
        }
        ell = next(e for e in scene.ellipsoids if e.name == pair.ellipsoid)
        events = [float(ev.time) for ev in pair.events]
        margin = float(t1 - t0) / 400
        for i in range(steps + 1):
            t = t0 + (t1 - t0) * F(2 * i + 1, 2 * steps + 2)
            if any(abs(float(t) - e) < margin for e in events):
                continue
            state = pair.state_at(t)
            got = {n: v.contact for n, v in state.pieces if v is not None}
            E = ell.trajectory.placed(ell.quadric, t, t0, t1)
            for piece, expected in _expected(pair.object, E, reading, points).items():
                if expected is None or piece not in asked:
                    continue
                assert got.get(piece, False) == expected, (pair.ellipsoid, piece, t, reading)
                compared += 1
    assert compared > 0


def test_the_readings_differ_only_where_a_piece_is_crossed_beyond_its_cut():
    for name in builtin_scene_names():
        geo = simulate(builtin_scene(name), effects=["contact"])
        paper = simulate(builtin_scene(name), effects=["contact"], reading="paper")
        for g, p in zip(geo.pairs, paper.pairs, strict=True):
            same = [e.time.decimal(12) for e in g.events] == [e.time.decimal(12) for e in p.events]
            assert same or g.beyond_cut(), (name, g.ellipsoid, g.object.name)


def _starts(pair, piece):
    """Times where contact with ``piece`` starts (events where it becomes true)."""
    out = []
    for ev in pair.events:
        before = dict((ev.before or ev.at).pieces).get(piece)
        after = dict((ev.after or ev.at).pieces).get(piece)
        if (before is None or not before.contact) and after is not None and after.contact:
            out.append(ev.time)
    return out


def _ends(pair, piece):
    out = []
    for ev in pair.events:
        before = dict((ev.before or ev.at).pieces).get(piece)
        after = dict((ev.after or ev.at).pieces).get(piece)
        if before is not None and before.contact and (after is None or not after.contact):
            out.append(ev.time)
    return out


def _scout_centre(t):
    """The scout's centre on its second keyframe segment, 2 <= t <= 4."""
    s = (t - 2) / 2
    return (sp.Rational(5, 4) + s * sp.Rational(5, 4), sp.Rational(1, 2) - s / 2, 5 + s * sp.Rational(5, 2))


def test_scout_meets_the_crown_as_cut_at_a_closed_form_root():
    """The scout and the crown are homothetic (both ``x^2 + y^2 + 3 z^2 + ...``): their
    intersection is the scout's section by the radical plane ``E - Q = 0``.  It first
    reaches the crown's side of ``z = 6`` where the line ``{E - Q = 0, z = 6}`` touches
    the scout's circle at ``z = 6``: a closed form written here with sympy, without pencils."""
    t, x, y, z = sp.symbols("t x y z")
    cx, cy, cz = _scout_centre(t)
    scout = (x - cx) ** 2 + (y - cy) ** 2 + 3 * (z - cz) ** 2 - sp.Rational(1, 10)
    crown = x**2 + y**2 + 3 * (z - sp.Rational(836291, 100000)) ** 2 - 20
    radical = sp.expand(scout - crown).subs(z, 6)  # a x + b y - e, linear in x, y
    a, b = radical.coeff(x), radical.coeff(y)
    e = -radical.subs({x: 0, y: 0})
    radius2 = sp.Rational(1, 10) - 3 * (6 - cz) ** 2
    h = sp.Poly(sp.expand((a * cx + b * cy - e) ** 2 - (a**2 + b**2) * radius2), t)
    closed = fmpq_poly_of([F(int(c.p), int(c.q)) for c in reversed(h.all_coeffs())])

    geo = simulate(builtin_scene("bees_with_interests")).pair("scout", "tree")
    paper = simulate(builtin_scene("bees_with_interests"), reading="paper").pair("scout", "tree")
    start = _starts(geo, "crown")[0]
    assert start.decimal(10) == "2.6623162741"
    assert not start.is_rational and start.degree >= 2  # an algebraic number, exactly
    assert sign_at(closed, start) == 0
    # in the paper's reading the crown counts from the instant the scout reaches z = 6:
    # the top of the scout, cz + sqrt(1/30), is 6
    paper_start = _starts(paper, "crown")[0]
    assert paper_start.decimal(10) == "2.6539406513"
    top = sp.Poly(sp.expand((6 - cz) ** 2 - sp.Rational(1, 30)), t)
    assert sign_at([F(int(c.p), int(c.q)) for c in reversed(top.all_coeffs())], paper_start) == 0
    # the trunk: its contact ends before the scout leaves z = 6 in the geometric reading
    assert [r.decimal(10) for r in _ends(geo, "trunk")] == ["2.9437570943"]
    assert [r.decimal(10) for r in _ends(paper, "trunk")] == ["2.9460593487"]


def test_example_17_is_the_same_in_both_readings():
    """The bee of Example 17 crosses the plane z = 6 without touching either quadric beyond it."""
    geo = simulate(builtin_scene("bee_and_tree")).pair("bee", "tree")
    paper = simulate(builtin_scene("bee_and_tree"), reading="paper").pair("bee", "tree")
    assert [e.time.decimal(12) for e in geo.events] == [e.time.decimal(12) for e in paper.events]
    assert [e.changes() for e in geo.events] == [e.changes() for e in paper.events]
    assert not geo.beyond_cut()


def test_reading_in_a_scene_file_and_its_errors():
    text = """
[scene]
name = "r"
time = [0, 1]
reading = "paper"
[[object]]
name = "o"
[[object.piece]]
name = "s"
equation = "x^2 + y^2 + z^2 = 1"
[[ellipsoid]]
name = "e"
standard = "sphere"
radius = 0.1
center = [0, 0, 5]
"""
    assert parse_scene(text, "r.toml").reading == "paper"
    assert parse_scene(text.replace('reading = "paper"\n', ""), "r.toml").reading == "geometry"
    with pytest.raises(SceneError, match=r"scene\.reading"):
        parse_scene(text.replace('"paper"', '"whole"'), "r.toml")
    with pytest.raises(ChoiceError, match="reading"):
        simulate(parse_scene(text, "r.toml"), reading="whole")


def test_report_says_where_the_readings_differ(capsys):
    from quadric_contact.interfaces.cli import main

    assert main(["simulate", "bees_with_interests", "--places", "10"]) == 0
    out = capsys.readouterr().out
    assert "reading: pieces as cut" in out
    assert "2.6623162741: crown: no contact (crosses the quadric beyond the cut only) -> contact" in out
    assert sum("readings differ" in line for line in out.splitlines()) == 1
    assert main(["simulate", "bees_with_interests", "--reading", "paper", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["reading"] == "paper"
    scout = next(p for p in data["pairs"] if p["ellipsoid"] == "scout")
    assert [e["time"]["decimal"][:12] for e in scout["events"]][1] == "2.6539406513"


def test_events_are_changes_and_the_count_is_the_timeline():
    """An event is reported only where the decided state changes: every event says what
    changed, and the summary's count is the number of events the timelines list."""
    for name in builtin_scene_names():
        result = simulate(builtin_scene(name))
        for pair in result.pairs:
            for ev in pair.events:
                assert ev.changes(pair.object), (name, pair.ellipsoid, ev.time)
        text = result.format_text(events="all")
        listed = sum(
            1
            for line in text.splitlines()
            if line.startswith("  t = ") and ": start: " not in line and ": end: " not in line
        )
        assert f"events: {listed} in {len(result.pairs)} (ellipsoid, object) pair(s)" in text, name


def test_long_reports_are_summarised_unless_all_events_are_asked_for():
    from quadric_contact.scenes.manybody import many_body_scene
    from quadric_contact.scenes.simulation_reports import EVENTS_SHOWN, LINES_SHOWN

    scene = many_body_scene(60, 4, seed=1, check_smallness=False)
    result = simulate(scene, broad_phase=True)
    short, full = result.format_text(), result.format_text(events="all")
    events = sum(len(p.events) for p in result.pairs)
    assert events > 40
    assert len(short.splitlines()) < LINES_SHOWN + 3 * EVENTS_SHOWN + 60 < len(full.splitlines())
    assert "more (ellipsoid, object) pairs" in short and "--events all" in short
    assert "more (ellipsoid, object) pairs" not in full
    tail = [line for line in short.splitlines() if line.startswith("events: ")]
    assert tail == [line for line in full.splitlines() if line.startswith("events: ")]
    with pytest.raises(SceneError, match="events"):
        result.format_text(events="some")


def test_probe_two_sheets_has_no_event_at_3_plus_sqrt10_over_2():
    pair = simulate(builtin_scene("probe_two_sheets")).pair("probe", "hyperboloid")
    phantom = 3 + 10**0.5 / 2
    assert all(abs(float(e.time) - phantom) > 1e-9 for e in pair.events)
    assert len(pair.events) == 4


def test_contact_kinds_in_scenes_are_analyze_contact_s():
    from quadric_contact import analyze_contact
    from quadric_contact.theory.contact_kind import ContactKind

    scene = builtin_scene("parallel_walls")
    result = simulate(scene)
    ell = scene.ellipsoids[0]
    walls = next(p for p in scene.objects[0].pieces if p.name == "walls")
    words = {k.value for k in ContactKind} | {"undetermined", "undecided"}
    seen = 0
    for pair in result.pairs:
        for ev in pair.events:
            v = dict(ev.at.pieces).get("walls")
            assert v is not None and v.kind in words
            if ev.time.is_rational:
                t = ev.time.as_fraction()
                E = ell.trajectory.placed(ell.quadric, t, *scene.span)
                assert v.kind == analyze_contact(E, walls.quadric).kind.value
                seen += 1
    assert seen == 4
