"""``quadric-contact check`` says whether the surfaces touch, and where, for every type of Q,
as ``contact_kind`` (Table 3) does.  Each pair is built so that the tangency and its points
follow from the geometry alone (a unit sphere against a surface placed to meet it there)."""

from __future__ import annotations

import json

import pytest

import quadric_contact as qc
from quadric_contact.interfaces.cli import main

SPHERE = "x**2 + y**2 + z**2 - 1"
BALL_AT_3 = "(x-3)**2 + y**2 + z**2 - 1"

CASES = [
    # (E, Q, kind, tangent points as the report prints them)
    (SPHERE, "(x-2)**2 + y**2 + z**2 - 1", "tangent_point", ["(1, 0, 0)"]),  # two unit spheres
    (SPHERE, "x - 1", "tangent_point", ["(1, 0, 0)"]),  # a plane
    (SPHERE, "x**2 - 1", "two_tangent_points", ["(1, 0, 0)", "(-1, 0, 0)"]),  # parallel planes
    (SPHERE, "z + 1 + x**2 + y**2", "tangent_point", ["(0, 0, -1)"]),  # a paraboloid's vertex
    # the two-sheet hyperboloid's vertex (2, 0, 0), radius of curvature 2 > 1
    (BALL_AT_3, "x**2 - y**2 - z**2 - 4", "tangent_point", ["(2, 0, 0)"]),
    (BALL_AT_3, "y**2 - 2*(x-2)", "tangent_point", ["(2, 0, 0)"]),  # a parabolic cylinder
    (SPHERE, "x**2 + y**2 - z**2/4 - 1", "tangent_curve", []),  # a throat of radius 1
    (SPHERE, "x**2 + y**2 - 1", "tangent_curve", []),  # a cylinder of radius 1
    (SPHERE, "x**2 + y**2 + z**2 - 4", "none", []),  # inside a sphere of radius 2
    (SPHERE, "x**2 + y**2 + z**2 - 2*x", "transversal", []),
]


@pytest.mark.parametrize(("E", "Q", "kind", "points"), CASES, ids=[c[1] for c in CASES])
def test_check_reports_touching_with_the_tangent_points(capsys, E, Q, kind, points):
    assert main(["check", E, Q]) == 0
    line = [t for t in capsys.readouterr().out.splitlines() if t.startswith("touching:")]
    assert len(line) == 1, "one touching line in every report"
    assert f"Table 3: {kind}," in line[0]
    for point in points:
        assert point in line[0]
    assert line[0].startswith("touching: yes") == (kind not in ("none", "transversal"))
    # the report agrees with the public predicate
    assert str(qc.contact_kind(E, Q)) == kind


def test_check_json_carries_the_contact_kind(capsys):
    assert main(["check", "--json", SPHERE, "(x-2)**2 + y**2 + z**2 - 1"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["contact_kind"]["kind"] == "tangent_point"
    points = [p for m in data["contact_kind"]["members"] for p in m["points"]]
    assert points == [["1", "0", "0"]]
