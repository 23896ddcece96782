import pytest

import quadric_contact as qc
from quadric_contact.exact import errors


def test_hierarchy_subclasses_builtin_types():
    for cls in (errors.NotANumberError,):
        assert issubclass(cls, TypeError)
    for cls in (
        errors.NonFiniteError,
        errors.NotRationalError,
        errors.ShapeError,
        errors.NotSymmetricError,
        errors.EquationError,
        errors.NotAnEllipsoidError,
        errors.NotAPlaneError,
        errors.ExcludedQuadricError,
        errors.DegeneratePencilError,
        errors.UndecidedError,
        errors.SceneError,
    ):
        assert issubclass(cls, ValueError)
        assert issubclass(cls, errors.QuadricContactError)


def test_every_error_of_the_package_is_exported():
    """Every error class the package raises can be caught by its name on the package."""
    import inspect

    names = [
        name
        for name, cls in inspect.getmembers(errors, inspect.isclass)
        if issubclass(cls, errors.QuadricContactError) and cls.__module__ == errors.__name__
    ]
    assert "WorkLimitError" in names and "ChoiceError" in names
    for name in names:
        assert getattr(qc, name) is getattr(errors, name) and name in qc.__all__
    assert issubclass(qc.WorkLimitError, errors.QuadricContactError)
    assert issubclass(qc.WorkLimitError, ValueError)


def test_not_an_ellipsoid_carries_object_and_kind():
    q = qc.Quadric.from_equation("x**2 + y**2 - z**2 - 1")
    with pytest.raises(qc.NotAnEllipsoidError) as info:
        qc.characteristic_polynomial(q, "x + y")
    assert info.value.value is q
    assert info.value.details["kind"] is qc.QuadricKind.HYPERBOLOID_ONE_SHEET
    assert "hyperboloid of one sheet" in str(info.value)


@pytest.mark.parametrize(
    "eq", ["x**2 + y**2 + z**2 + 1", "x**2 + y**2 + z**2", "x**2 + y**2 - 1", "x + y", "0"]
)
def test_things_that_are_not_real_ellipsoids(eq):
    with pytest.raises(qc.NotAnEllipsoidError):
        qc.transversal_contact(eq, "z")


def test_not_a_plane():
    with pytest.raises(qc.NotAPlaneError) as info:
        qc.plane_side("x**2 + y**2 + z**2 - 1", "x**2 - 4")
    assert info.value.details["kind"] is qc.QuadricKind.PARALLEL_PLANES


@pytest.mark.parametrize("eq", ["x**2 + y**2 - z**2", "x**2 - y**2", "x**2"])
def test_excluded_types_with_real_roots(eq):
    # A tiny sphere far away: every root real, and the theory excludes the type.
    E = qc.Quadric.sphere(1, center=(50, 60, 70))
    with pytest.raises(qc.ExcludedQuadricError) as info:
        qc.transversal_contact(E, eq, method="theory")
    assert info.value.details["kind"] in (
        qc.QuadricKind.CONE,
        qc.QuadricKind.INTERSECTING_PLANES,
        qc.QuadricKind.COINCIDENT_PLANES,
    )


def test_excluded_type_still_decided_by_remark_9_when_roots_are_not_real():
    # A unit sphere centred on the cone, away from the vertex: one crossing curve, non-real roots.
    E = qc.Quadric.sphere(1, center=(2, 0, 2))
    r = qc.transversal_contact(E, "x**2 + y**2 - z**2", method="theory")
    assert bool(r) and r.decided_by == "Remark 9"


def test_undecided_refuses_bool():
    E = qc.Quadric.sphere(1)
    r = qc.transversal_contact(E, "x**2 + y**2 - 4", small=False, method="theory")
    assert not r.decided
    with pytest.raises(qc.UndecidedError):
        bool(r)
