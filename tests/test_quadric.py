from fractions import Fraction

import numpy as np
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

from quadric_contact import Quadric, QuadricKind, RigidMotion, rotation_from_quaternion
from quadric_contact.exact.errors import EquationError, NotANumberError, NotSymmetricError, ShapeError
from quadric_contact.model.classification import TABLE_1_KINDS
from quadric_contact.testing.strategies import ellipsoids, quadrics, rigid_motions

K = QuadricKind

KIND_EXAMPLES = {
    "x**2/4 + y**2 + z**2/9 - 1": K.ELLIPSOID,
    "x**2 + y**2 - z**2 - 1": K.HYPERBOLOID_ONE_SHEET,
    "x**2 + y**2 - z**2 + 1": K.HYPERBOLOID_TWO_SHEETS,
    "x**2 + 2*y**2 - z": K.ELLIPTIC_PARABOLOID,
    "x**2 - 2*y**2 - z": K.HYPERBOLIC_PARABOLOID,
    "x**2 + 2*y**2 - 3": K.ELLIPTIC_CYLINDER,
    "x**2 - 2*y**2 - 3": K.HYPERBOLIC_CYLINDER,
    "x**2 - 2*y**2 + 3": K.HYPERBOLIC_CYLINDER,
    "x**2 - z": K.PARABOLIC_CYLINDER,
    "x**2 - 4": K.PARALLEL_PLANES,
    "(x + y - 1)*(x + y + 3)": K.PARALLEL_PLANES,
    "x + 2*y - z + 5": K.PLANE,
    "x**2 + y**2 - z**2": K.CONE,
    "x**2 - y**2": K.INTERSECTING_PLANES,
    "(x - 1)*(y + 2)": K.INTERSECTING_PLANES,
    "(x - y + 1)**2": K.COINCIDENT_PLANES,
    "x**2 + y**2 + z**2 + 1": K.IMAGINARY_ELLIPSOID,
    "x**2 + y**2 + (z-1)**2": K.IMAGINARY_CONE,
    "x**2 + y**2 + 1": K.IMAGINARY_ELLIPTIC_CYLINDER,
    "x**2 + y**2": K.IMAGINARY_INTERSECTING_PLANES,
    "x**2 + 1": K.IMAGINARY_PARALLEL_PLANES,
    "7": K.EMPTY,
    "0": K.ZERO,
}


@pytest.mark.parametrize("eq, kind", KIND_EXAMPLES.items())
def test_kind_of_every_type(eq, kind):
    q = Quadric.from_equation(eq)
    assert q.kind is kind
    assert (-q).kind is kind


@pytest.mark.parametrize("eq, kind", KIND_EXAMPLES.items())
@given(motion=rigid_motions())
def test_kind_is_invariant_under_rigid_motions(eq, kind, motion):
    assert Quadric.from_equation(eq).moved(motion).kind is kind


@given(q=quadrics(flip_sign=False, moved=False), motion=rigid_motions(), scale=st.fractions(1, 50))
def test_standard_forms_have_canonical_sign_one(q, motion, scale):
    assert q.canonical_sign == 1
    moved = q.moved(motion).scaled(scale)
    assert moved.kind is q.kind and moved.canonical_sign == 1
    if q.kind not in (K.HYPERBOLIC_PARABOLOID,):
        assert (-moved).canonical_sign == -1


@pytest.mark.parametrize("kind", TABLE_1_KINDS)
def test_standard_constructors(kind):
    params = {"a": 3, "b": 2, "c": 1}
    n = {K.PARABOLIC_CYLINDER: 1, K.PARALLEL_PLANES: 1}.get(
        kind, 3 if kind in (K.ELLIPSOID, K.HYPERBOLOID_ONE_SHEET, K.HYPERBOLOID_TWO_SHEETS) else 2
    )
    q = Quadric.standard(kind, **dict(list(params.items())[:n]))
    assert q.kind is kind


def test_standard_form_equations():
    assert Quadric.ellipsoid(2, 1, Fraction(1, 2)).equation() == "x**2/4 + y**2 + 4*z**2 - 1"
    assert Quadric.hyperboloid_two_sheets(1, 1, 2).equation() == "x**2 + y**2 - z**2/4 + 1"
    assert Quadric.elliptic_paraboloid(1, Fraction(1, 2)).equation() == "x**2 + 4*y**2 - z"
    assert Quadric.parabolic_cylinder(2).equation() == "x**2/4 - z"
    assert Quadric.plane((1, 2, 3), 4).equation() == "x + 2*y + 3*z - 4"
    # Irrational semi-axes with rational squares (Example 17: c1 = 1/sqrt(3)).
    assert Quadric.ellipsoid(1, 1, 1 / sympy.sqrt(3)).equation() == "x**2 + y**2 + 3*z**2 - 1"


def test_from_matrix_inputs_agree():
    rows = [[1, 0, 0, 0], [0, 2, 0, 0], [0, 0, 3, "1/2"], [0, 0, "1/2", "-8.5"]]
    a = Quadric.from_matrix(rows)
    assert Quadric.from_matrix(np.array([[1, 0, 0, 0], [0, 2, 0, 0], [0, 0, 3, 0.5], [0, 0, 0.5, -8.5]])) == a
    assert (
        Quadric.from_matrix(
            sympy.Matrix(
                [
                    [1, 0, 0, 0],
                    [0, 2, 0, 0],
                    [0, 0, 3, sympy.Rational(1, 2)],
                    [0, 0, sympy.Rational(1, 2), sympy.Rational(-17, 2)],
                ]
            )
        )
        == a
    )
    assert Quadric(rows) == a
    assert a[3, 3] == Fraction(-17, 2)
    assert Quadric.from_equation(a.equation()) == a


def test_not_symmetric_names_entry_and_can_symmetrize():
    m = np.eye(4)
    m[0, 1] = 1e-17
    with pytest.raises(NotSymmetricError) as info:
        Quadric.from_matrix(m)
    assert info.value.details["entry"] == (0, 1)
    q = Quadric.from_matrix(m, symmetrize=True)
    assert q[0, 1] == q[1, 0] == Fraction(1e-17) / 2


def test_from_coefficients_eq_6():
    q = Quadric.from_coefficients(
        [[1, 0, 0], [0, 1, 0], [0, 0, 3]], [-3, -3, Fraction(-33, 2)], Fraction(2173, 20)
    )
    assert q == Quadric.from_equation("(x - 3)**2 + (y - 3)**2 + 3*(z - 5.5)**2 - 0.1")


@pytest.mark.parametrize(
    "text",
    ["3*(z-5.5)^2 + x^2 + y^2 - 0.1", "x**2 + y**2 + 3*(z - 5.5)**2 = 0.1", "x^2+y^2+3 *(z-5.5)^2-1/10"],
)
def test_equation_syntaxes(text):
    assert Quadric.from_equation(text) == Quadric.from_equation("x**2 + y**2 + 3*(z-5.5)**2 - 0.1")


@pytest.mark.parametrize(
    "text",
    [
        "x**3 + y",
        "x*y*z",
        "x**2 + w",
        "sin(x)",
        "1/x + y**2",
        "x = y = z",
        "x**2 + sqrt(2)*y",
        "",
        "x**2 +",
        "__import__('os')",
        "3(z-5.5)^2 + x^2 + y^2 - 0.1",
        "x^2+y^2+3 (z-5.5)^2-1/10",
        "x2 + y2 + z2 - 1",
    ],
)
def test_bad_equations(text):
    with pytest.raises(EquationError):
        Quadric.from_equation(text)


def test_sympy_expression_input():
    x, y, z = sympy.symbols("x y z")
    assert Quadric.from_equation(sympy.Eq(x**2 + y**2, z)).kind is K.ELLIPTIC_PARABOLOID
    with pytest.raises(EquationError):
        Quadric.from_equation(42)


def test_quaternion_rotation_is_exact_rotation():
    R = rotation_from_quaternion(1, 2, 3, 4)
    M = sympy.Matrix(R)
    assert sympy.eye(3) == M.T * M and M.det() == 1


@given(e=ellipsoids(), m1=rigid_motions(), m2=rigid_motions())
def test_motions_compose_and_invert(e, m1, m2):
    assert e.moved(m2).moved(m1) == e.moved(m1 @ m2)
    assert e.moved(m1).moved(m1.inverse()) == e


@given(q=quadrics(), m=rigid_motions(), p=st.tuples(*[st.fractions(-5, 5)] * 3))
def test_moving_moves_the_zero_set(q, m, p):
    # value of the moved quadric at the moved point equals the value at the point
    assert q.moved(m).value_at(m.apply(p)) == q.value_at(p)


def test_rotated_about_point_and_translated():
    s = Quadric.sphere(1, center=(1, 0, 0))
    assert s.rotated((1, 0, 0, 1), about=(0, 0, 0)) == Quadric.sphere(1, center=(0, 1, 0))
    assert s.translated((0, 0, 2)) == Quadric.sphere(1, center=(1, 0, 2))
    with pytest.raises(ShapeError):
        RigidMotion.from_matrix([[1, 1, 0], [0, 1, 0], [0, 0, 1]])


def test_immutability_hash_and_center():
    q = Quadric.ellipsoid(3, 2, 1, center=(1, 2, 3), rotation=(1, 1, 0, 0))
    with pytest.raises(AttributeError):
        q.foo = 1  # type: ignore[attr-defined]
    assert hash(q) == hash(Quadric.from_matrix(q.matrix))
    assert q.center() == (1, 2, 3)
    assert Quadric.from_equation("x**2 - z").center() is None
    assert q.scaled(-2).is_proportional_to(q) and not q.is_proportional_to(Quadric.sphere(1))


def test_as_ellipsoid_normalises_sign():
    e = Quadric.from_equation("1 - x**2 - y**2/4 - z**2/9")
    n = e.as_ellipsoid()
    assert n == -e and n.as_ellipsoid() is n


@given(q=st.tuples(*[st.fractions(-3, 3)] * 3).filter(any), d1=st.fractions(-5, 5), d2=st.fractions(-5, 5))
def test_two_parallel_planes(q, d1, d2):
    if d1 == d2:
        with pytest.raises(NotANumberError):
            Quadric.two_parallel_planes(q, d1, d2)
        return
    pp = Quadric.two_parallel_planes(q, d1, d2)
    assert pp.kind is K.PARALLEL_PLANES and pp.canonical_sign == 1
    n2 = sum(v * v for v in q)
    # A point on each plane is on the quadric; the midpoint is in R- (the slab).
    for d in (d1, d2):
        assert pp.value_at([v * d / n2 for v in q]) == 0
    assert pp.value_at([v * (d1 + d2) / 2 / n2 for v in q]) < 0


@given(e=ellipsoids())
def test_center_is_the_exact_critical_point(e):
    import sympy

    c = e.center()
    A = sympy.Matrix(e.quadratic_part)
    b = sympy.Matrix(e.linear_part)
    assert sympy.Matrix(c) == -A.LUsolve(b)


def test_a_binary64_array_keeps_its_exact_entries_whatever_their_size():
    """The fast path for float64 arrays (the integer form first, the Fractions when read) gives
    the entries exactly, also when their sum overflows, and still refuses non-finite ones."""
    import numpy as np

    from quadric_contact.exact.errors import NonFiniteError

    for big in (1.0, 1e308):
        m = np.diag([big, big, 1.0, -0.1])
        m[0, 1] = m[1, 0] = big / 3
        q = Quadric.from_matrix(m)
        want = Quadric.from_matrix([[Fraction(v) for v in row] for row in m.tolist()])
        assert q == want and hash(q) == hash(want)
        assert q.integer_form() == want.integer_form() and q[0, 1] == Fraction(big / 3)
    for bad in (float("nan"), float("inf")):
        m = np.diag([1.0, 1.0, 1.0, -1.0])
        m[2, 3] = m[3, 2] = bad
        with pytest.raises(NonFiniteError):
            Quadric.from_matrix(m)
