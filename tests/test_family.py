"""Parametric families: the reader, the exact quantities against the pair API, the paper's
conditions over a family, the numeric lambdas against exact values, the certified signs,
and the contact maps against the scalar predicates."""

from __future__ import annotations

import ast
import math
from fractions import Fraction

import flint
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from mpmath.libmp import to_rational
from tests.untrusted import HOSTILE, untrusted

import quadric_contact as qc
from quadric_contact import Quadric, Region, family
from quadric_contact.exact.errors import (
    ChoiceError,
    EquationError,
    NotAnEllipsoidError,
    QuadricContactError,
    ShapeError,
)
from quadric_contact.exact.straight_line import _functions, rounding_counts
from quadric_contact.families.family import MAX_PARAMETERS, RationalFunction
from quadric_contact.families.family_emit import emit_program
from quadric_contact.families.family_maps import MapAnswer
from quadric_contact.families.family_numeric import UNCERTAIN, compile_quantity
from quadric_contact.theory.pencil import characteristic_polynomial
from quadric_contact.theory.smallness import smallness

TRUNK = "x^2 + y^2 - 0.25*(z - 3)^2 - 1"
CROWN = "x^2 + y^2 + 3*(z - 8.36291)^2 - 20"
BEE = "(x - u)^2 + y^2 + 3*(z - w)^2 - 0.1"

BEE_TRUNK = family(BEE, TRUNK, "u w")
# a semi-axis s and a position v: entries are quotients of polynomials in s
SEMI = family("x^2/s^2 + 4*(y - v)^2 + 9*z^2 - 1", "x^2 + y^2 - z^2/4 - 1", "s v")
# a plane through the origin and a sphere of radius 1/2 centred at (u, 0, w)
PLANE = family("(x - u)^2 + y^2 + (z - w)^2 - 1/4", "z - x/2", "u w")
# an ellipsoid turned by the rational rotation of angle 2 atan(t) about z, centred at (1, 0, 0)
_t = sp.Symbol("r")  # a parameter may not be named t (the smallness conditions use it)
_c, _s = (1 - _t**2) / (1 + _t**2), 2 * _t / (1 + _t**2)
_R = sp.Matrix([[_c, -_s, 0, 0], [_s, _c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
_T = sp.Matrix([[1, 0, 0, -1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
_M = _T * _R.T  # X -> R^T (X - c)
_E0 = sp.diag(sp.Rational(1, 4), 1, 4, -1)
ROTATING = family(sp.simplify(_M.T * _E0 * _M), "x^2 + 2*y^2 - z^2 - 4", [_t])

FAMILIES = {"bee-trunk": BEE_TRUNK, "semi-axis": SEMI, "plane": PLANE, "rotating": ROTATING}

fractions = st.fractions(min_value=-6, max_value=6, max_denominator=64)


def _point(fam, draw_values):
    return dict(zip(fam.parameters, draw_values, strict=True))


def _valid(fam, point) -> bool:
    try:
        E, _ = fam.at(**point)
    except ZeroDivisionError:
        return False
    return E.kind is qc.QuadricKind.ELLIPSOID


# -- reading -------------------------------------------------------------------------------------


def test_every_input_form_gives_the_same_family():
    u, w = sp.symbols("u w")
    x, y, z = sp.symbols("x y z")
    expr = (x - u) ** 2 + y**2 + 3 * (z - w) ** 2 - sp.Rational(1, 10)
    matrix = sp.Matrix(
        [
            [1, 0, 0, -u],
            [0, 1, 0, 0],
            [0, 0, 3, -3 * w],
            [-u, 0, -3 * w, u**2 + 3 * w**2 - sp.Rational(1, 10)],
        ]
    )
    text_matrix = [
        ["1", 0, 0, "-u"],
        [0, 1, 0, 0],
        [0, 0, 3, "-3*w"],
        ["-u", 0, "-3*w", "u^2 + 3*w^2 - 0.1"],
    ]
    trunk = Quadric.from_equation(TRUNK)
    forms = [
        family(expr, trunk, [u, w]),
        family(sp.Eq(expr, 0), TRUNK, "u, w"),
        family(matrix, trunk.to_sympy(), ("u", "w")),
        family(text_matrix, trunk, "u w"),
    ]
    for fam in forms:
        assert fam.E == BEE_TRUNK.E and fam.Q == BEE_TRUNK.Q
        assert fam.coefficients == BEE_TRUNK.coefficients


def test_parameters_are_declared_names():
    with pytest.raises(EquationError, match=r"unknown name 'v' at position 6"):
        family("(x - v)^2 + y^2 + z^2 - 1", "z", "u")
    with pytest.raises(EquationError, match="not declared parameters"):
        family(sp.Matrix(4, 4, lambda i, j: sp.Symbol("v") if i == j == 3 else int(i == j)), "z", "u")
    with pytest.raises(EquationError, match="in x, y, z"):
        family("x^2/(u - x) + y^2 + z^2 - 1", "z", "u")
    for bad in ("x", "u u", "2u", "u;w", "u.w"):
        with pytest.raises(EquationError):
            family("x^2 + y^2 + z^2 - 1", "z", bad)
    with pytest.raises(EquationError, match="MAX_PARAMETERS"):
        family("x^2 + y^2 + z^2 - 1", "z", [f"p{i}" for i in range(MAX_PARAMETERS + 1)])
    with pytest.raises(EquationError, match="degree 3"):
        family("x^3 + u", "z", "u")
    with pytest.raises(EquationError, match="not a quotient of polynomials"):
        family((sp.Symbol("x") - sp.sqrt(2)) ** 2 + sp.Symbol("y") ** 2 + sp.Symbol("z") ** 2 - 1, "z", [])


def test_the_reader_is_bounded():
    with pytest.raises(EquationError, match="MAX_DEGREE"):
        family("x^2 + y^2 + z^2 - (u + 1)^1000", "z", "u")
    with pytest.raises(EquationError, match=r"MAX_FAMILY_WORK|MAX_DEGREE|MAX_PARAMETERS"):
        family(
            "x^2 + y^2 + z^2 - (" + " + ".join(f"a{i}" for i in range(8)) + ")^8",
            "z",
            [f"a{i}" for i in range(8)],
        )


def test_no_point_where_e_is_an_ellipsoid():
    with pytest.raises(NotAnEllipsoidError):
        family("x^2 + y^2 + z^2 + u^2 + 1", "z", "u")
    with pytest.raises(NotAnEllipsoidError):
        family("x^2 + y^2 + z^2 - u", "z", "u", at={"u": -1})


def test_hostile_text_never_runs():
    bee = BEE_TRUNK  # warm up: nothing is imported or compiled for the first time below
    assert bee.parameters == ("u", "w")
    with pytest.raises(EquationError):
        family("x2 + u", TRUNK, "u")
    refused = []
    with untrusted():
        for text in HOSTILE:
            for args in ((text, TRUNK, "u"), (BEE, text, "u w"), (BEE, TRUNK, text)):
                try:
                    family(*args)
                except QuadricContactError as exc:
                    assert str(exc)
                    refused.append(text)
                else:
                    raise AssertionError(f"accepted {args!r:.200}")
    assert len(refused) == 3 * len(HOSTILE)


# -- exact quantities against the pair API ------------------------------------------------------------


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
def test_a_family_at_a_point_is_the_pair(name, data):
    fam = FAMILIES[name]
    point = _point(fam, [data.draw(fractions) for _ in fam.parameters])
    assume(_valid(fam, point))
    E, Q = fam.at(**point)
    P = characteristic_polynomial(E, Q)
    assert tuple(fam.evaluate(f"c{k}", **point) for k in range(5)) == P.coefficients
    assert tuple(fam.evaluate(f"Delta{j}", **point) for j in (2, 3, 4)) == P.deltas()
    # fixing one parameter first gives the same numbers
    first, rest = fam.parameters[0], fam.parameters[1:]
    sub = fam.fix(**{first: point[first]})
    assert sub.parameters == rest
    for q in ("c2", "Delta4"):
        assert sub.evaluate(q, **{p: point[p] for p in rest}) == fam.evaluate(q, **point)


def test_all_parameters_fixed_is_the_pair_api():
    pair = BEE_TRUNK.fix(u=3, w=Fraction(11, 2))
    assert pair.parameters == ()
    P = characteristic_polynomial("(x-3)^2 + y^2 + 3*(z-5.5)^2 - 0.1", TRUNK)
    assert tuple(Fraction(str(c)) for c in pair.coefficients) == P.coefficients


def test_the_deltas_are_those_of_the_coefficients():
    from quadric_contact.exact.discriminants import paper_deltas

    for fam in FAMILIES.values():
        assert all(
            sp.cancel(a - b) == 0 for a, b in zip(paper_deltas(fam.coefficients), fam.deltas, strict=True)
        )


def test_polynomial_or_rational():
    assert all(BEE_TRUNK.quantity(n).is_polynomial for n in ("c0", "c1", "c2", "c3", "c4", "Delta4"))
    assert not SEMI.quantity("c4").is_polynomial and not ROTATING.quantity("c3").is_polynomial
    # the bee's Delta_4 has degree 12 in (u, w): each c_k has degree <= 2 under a translation
    assert BEE_TRUNK.quantity("Delta4").value.degree == 12


# -- the paper's conditions over a family ------------------------------------------------------------


@given(u=fractions, w=fractions)
def test_table_4_rules_say_what_relative_position_says(u, w):
    fam = BEE_TRUNK
    point = {"u": u, "w": w}
    assume(fam.evaluate("Delta4", **point) > 0)  # all roots real and distinct
    signs = [(c > 0) - (c < 0) for c in (fam.evaluate(f"c{k}", **point) for k in range(5))]
    held = [r for r, rule in fam.table_4.items() if rule.holds(signs)]
    E, Q = fam.at(**point)
    assert held == [qc.relative_position(E, Q).region]  # the bee is small: Theorem 13 applies
    cond = fam.table_4_condition(held[0]).subs(
        dict(zip(fam.symbols, (sp.Rational(u), sp.Rational(w)), strict=True))
    )
    assert cond is sp.true


@pytest.mark.parametrize(
    "fam", [BEE_TRUNK, family(BEE, CROWN, "u w"), PLANE, SEMI], ids=lambda f: f.q_kind.value
)
def test_table_4_rules_are_the_sign_vectors_of_real_rooted_quartics(fam):
    """Every quartic -(l - r1)..(l - r4) with roots in a small set and the rule's root-sign
    pattern has a sign vector of the rule, and every vector of the rule occurs."""
    import itertools

    roots = [Fraction(k, 2) for k in range(-6, 7)]
    for rule in fam.table_4.values():
        seen = set()
        for rs in itertools.combinations_with_replacement(roots, 4):
            pattern = "".join(sorted(("-" if r < 0 else "0" if r == 0 else "+") for r in rs))
            if pattern != "".join(sorted(rule.pattern)):
                continue
            poly = sp.Poly(-sp.prod([sp.Symbol("l") - sp.Rational(r) for r in rs]), sp.Symbol("l"))
            coeffs = [poly.coeff_monomial(sp.Symbol("l") ** k) for k in range(5)]
            v = tuple(int(sp.sign(c)) for c in coeffs)
            assert rule.holds(v), (rule, rs)
            seen.add(v)
        assert seen == set(rule.vectors), rule
    if fam is BEE_TRUNK:  # a one-sheet hyperboloid: the corrected count of Table 4 (erratum)
        assert fam.table_4[Region.R_MINUS].changes == 1 and "c4 < 0, c0 > 0" in str(
            fam.table_4[Region.R_PLUS]
        )


@given(u=fractions, w=fractions)
def test_corollary_15_over_a_plane_family(u, w):
    point = {"u": u, "w": w}
    E, P = PLANE.at(**point)
    side = qc.plane_side(E, P)
    disc = PLANE.evaluate("plane discriminant", **point)
    assert (disc < 0) == (side.zone is Region.CONTACT)
    assert side.tangent == (disc == 0)
    if disc >= 0:
        c3 = PLANE.evaluate("c3", **point)
        assert side.zone is (Region.R_PLUS if c3 > 0 else Region.R_MINUS)
    assert PLANE.corollary_15 is not None and BEE_TRUNK.corollary_15 is None


@pytest.mark.parametrize("fam", [BEE_TRUNK, ROTATING], ids=["centre moves", "rotates"])
@given(data=st.data())
def test_smallness_is_constant_when_only_the_position_changes(fam, data):
    s = fam.smallness
    assert s.status == "constant" and not s.conditions
    point = _point(fam, [data.draw(fractions) for _ in fam.parameters])
    assume(_valid(fam, point))
    assert smallness(*fam.at(**point)).small == s.report.small


@given(s=st.fractions(min_value=Fraction(1, 10), max_value=3, max_denominator=32), v=fractions)
def test_smallness_conditions_over_a_semi_axis(s, v):
    sm = SEMI.smallness
    assert sm.status == "rational" and sm.not_polynomial  # the curvature conditions have s in a denominator
    point = {"s": s, "v": v}
    subs = {sp.Symbol("s"): sp.Rational(s), sp.Symbol("v"): sp.Rational(v)}
    assume(
        all(bool(a.subs(subs)) for a in sm.assumptions)
    )  # the order of the eigenvalues fixed at the reference
    report = smallness(*SEMI.at(**point))
    by_name = {c.name: c.holds for c in report.conditions}
    for cond in sm.conditions:
        assert cond.holds_at([s, v]) == by_name[cond.name], cond.name


def test_smallness_that_is_not_rational_says_so():
    fam = family("x^2 + u*x*y + 2*y^2 + z^2 - 1", "x^2 + y^2 - z^2 - 1", "u")
    assert fam.smallness.status == "algebraic" and "irreducible" in fam.smallness.explanation
    assert family(BEE, "(x - y)*(x + y)", "u w").smallness.status == "excluded"


def test_boundaries_are_the_factors_of_the_discriminant():
    (b,) = [b for b in BEE_TRUNK.boundaries if b.name == "Delta4"]
    d4 = BEE_TRUNK.quantity("Delta4").numerator
    product = d4.context().constant(1)
    for f in b.factors:
        k = 0
        while (d4 / product) != 0 and _divides(f ** (k + 1), d4):
            k += 1
        assert k >= 1
        product *= f**k
    assert (d4 / product).is_constant()  # the factors, with their multiplicities, make up Delta_4
    assert {b.name for b in family(BEE, CROWN, "u w").boundaries} == {"Delta3"}  # Delta4 = 0 identically
    assert {b.name for b in SEMI.boundaries} == {"Delta4", "pole"}  # c4 = -36/s^2 never vanishes


def _divides(f, g) -> bool:
    _, r = divmod(g, f)
    return r == 0


# -- the numeric lambdas -----------------------------------------------------------------------------

floats = st.floats(min_value=-8, max_value=8, allow_nan=False).filter(lambda x: x == 0 or abs(x) > 1e-6)


def _quantities(fam):
    return [n for n in fam.quantities if n != "plane discriminant" or fam.q_is_plane]


@pytest.mark.parametrize("name", list(FAMILIES))
@given(data=st.data())
@settings(max_examples=25)
def test_lambdified_values_are_the_exact_values(name, data):
    fam = FAMILIES[name]
    xs = [data.draw(floats) for _ in fam.parameters]
    point = dict(zip(fam.parameters, xs, strict=True))
    for q in _quantities(fam):
        try:
            exact = fam.evaluate(q, **point)
        except ZeroDivisionError:
            continue
        value = fam.quantity(q).value
        den = value.den(*[flint.fmpq(*x.as_integer_ratio()) for x in xs]) if xs else 1
        # the float value is num/den: far from a pole, within a small relative error of the
        # exact value, measured against the magnitude of the numerator's terms
        cq = fam.lambdify(q).compiled
        mag = float(cq.scale) * abs(cq.functions["quantity_magnitude"](*[abs(x) for x in xs])[0])
        if cq.has_denominator:
            dmag = abs(cq.functions["quantity_magnitude"](*[abs(x) for x in xs])[1])
            assume(abs(float(den)) > 1e-6 * dmag * float(abs(den) / max(abs(den), 1)))
            mag = mag / abs(cq.functions["quantity"](*xs)[1])
        got = float(fam.lambdify(q)(*xs))
        assert abs(got - float(exact)) <= 1e-12 * mag + 1e-300, (q, point)
        mp = Fraction(*to_rational(fam.lambdify(q, "mpmath", dps=40)(*xs)._mpf_))
        assert abs(mp - exact) <= Fraction(1, 10**30) * (abs(exact) + Fraction(mag)), (q, point)


@given(u=floats, w=floats)
@settings(max_examples=40)
def test_numba_and_numpy_agree(u, w):
    for q in ("c1", "c3", "Delta3", "Delta4"):
        a = BEE_TRUNK.lambdify(q, "numba")(np.array([u]), np.array([w]))
        b = BEE_TRUNK.lambdify(q, "numpy")(np.array([u]), np.array([w]))
        assert np.allclose(a, b, rtol=1e-12, atol=1e-300)


def _exact_sign(fam, name, xs):
    try:
        v = fam.quantity(name).value.evaluate([Fraction(x) for x in xs])
    except ZeroDivisionError:
        return None
    return (v > 0) - (v < 0)


def _check_signs(fam, name, U, W):
    signs = fam.lambdify(name, "certified")(U, W)
    for x, y, s in zip(U.reshape(-1), W.reshape(-1), signs.reshape(-1), strict=True):
        e = _exact_sign(fam, name, [float(x), float(y)])
        assert s in (UNCERTAIN, e), (name, x, y, s, e)
    return signs


@pytest.mark.parametrize("name", ["bee-trunk", "semi-axis", "plane"])
@given(data=st.data())
@settings(max_examples=30)
def test_the_certified_sign_is_never_wrong(name, data):
    fam = FAMILIES[name]
    U = np.array(data.draw(st.lists(floats, min_size=8, max_size=8)))
    W = np.array(data.draw(st.lists(floats, min_size=8, max_size=8)))
    for q in _quantities(fam):
        _check_signs(fam, q, U, W)


def test_the_certified_sign_near_and_on_the_boundary():
    """Points on the curve Delta_4 = 0 (its real roots in w along lines u = const, rounded
    to binary64, their neighbours and points a little further) and on the axis u = 0, where
    Delta_4 = 0 exactly."""
    fam = BEE_TRUNK
    d4 = fam.quantity("Delta4").numerator
    us, ws = [], []
    for u in np.linspace(-3.9, 3.9, 23):
        tq = flint.fmpq(*float(u).as_integer_ratio())
        coeffs: dict[int, object] = {}
        for mono, c in d4.to_dict().items():
            coeffs[int(mono[1])] = coeffs.get(int(mono[1]), flint.fmpq(0)) + c * tq ** int(mono[0])
        g = flint.fmpq_poly([coeffs.get(k, 0) for k in range(max(coeffs) + 1)])
        for root, _ in g.complex_roots():
            if root.imag == 0:
                w0 = float(root.real.mid())
                near = [math.nextafter(w0, -math.inf), w0, math.nextafter(w0, math.inf)]
                for w in [*near, *(w0 * (1 + e) for e in (-1e-5, -1e-9, 1e-9, 1e-5))]:
                    us.append(float(u))
                    ws.append(w)
    U, W = np.array(us), np.array(ws)
    assert len(U) > 50
    signs = _check_signs(fam, "Delta4", U, W)
    assert np.any(signs == UNCERTAIN) and np.any(signs != UNCERTAIN)
    on_axis = fam.lambdify("Delta4", "certified")(np.zeros(5), np.linspace(-1, 9, 5))
    assert set(on_axis.tolist()) <= {0, UNCERTAIN}
    assert np.all(on_axis == 0)  # the magnitude companion is zero too: an exact zero


def test_the_certified_checks():
    """Underflow, overflow and non-finite inputs make a point uncertain, in numba and numpy."""
    from quadric_contact.families.family_numeric import _numpy_signs

    sign = BEE_TRUNK.lambdify("Delta4", "certified")
    u = np.array([1e-300, np.nan, 3.0, 1e200, 3.0, 1e-200])
    w = np.array([1.0, 1.0, np.inf, 1.0, 5.5, 1e-200])
    expected = [_exact_sign(BEE_TRUNK, "Delta4", [1e-300, 1.0]), 2, 2, 2, 1, 2]
    got = sign(u, w).tolist()
    assert got[1:] == expected[1:] and got[0] in (expected[0], UNCERTAIN)
    assert _numpy_signs(sign.compiled, [u, w]).tolist() == got
    # a tiny first parameter: u^2 underflows, the sign of Delta4 is that of its constant part
    tiny = sign(np.array([1e-170]), np.array([5.5]))
    assert tiny.tolist() == [UNCERTAIN]
    # products that do not underflow: certain even for small inputs (the static guard is not needed)
    small = sign(np.array([1e-30]), np.array([5.5]))
    assert small.tolist() == [_exact_sign(BEE_TRUNK, "Delta4", [1e-30, 5.5])]


def test_lambdify_arguments():
    f = BEE_TRUNK.lambdify("c3")
    assert f(u=3.0, w=5.5) == f(3.0, 5.5) == float(BEE_TRUNK.evaluate("c3", u=3, w=5.5))
    assert f(np.zeros((2, 3)), 1.0).shape == (2, 3)
    with pytest.raises(TypeError):
        f(1.0)
    with pytest.raises(ChoiceError, match="no quantity"):
        BEE_TRUNK.lambdify("c5")
    with pytest.raises(ValueError, match="backend"):
        BEE_TRUNK.lambdify("c3", "fortran")
    exact = BEE_TRUNK.lambdify("c3", "exact")(np.array([3.0]), np.array([5.5]))
    assert exact[0] == BEE_TRUNK.evaluate("c3", u=3, w=5.5)


# -- the generated programs ----------------------------------------------------------------------------


class _Tracked:
    """Counts the rounded operations on the worst path (as tests/test_codegen.py does), with
    integer constants beyond 2^53 counted as rounded operands."""

    def __init__(self, n, degree):
        self.n, self.degree = n, degree

    @staticmethod
    def _lift(x):
        return x if isinstance(x, _Tracked) else _Tracked(int(abs(x) > 2**53), 0)

    def __add__(self, other):
        o = self._lift(other)
        return _Tracked(max(self.n, o.n) + 1, max(self.degree, o.degree))

    __radd__ = __sub__ = __rsub__ = __add__

    def __mul__(self, other):
        o = self._lift(other)
        return _Tracked(self.n + o.n + 1, self.degree + o.degree)

    __rmul__ = __mul__

    def __neg__(self):
        return self


@given(
    st.lists(
        st.tuples(st.tuples(st.integers(0, 4), st.integers(0, 4)), st.integers(-(2**70), 2**70)),
        min_size=1,
        max_size=12,
    )
)
def test_emitted_programs_are_exact_with_honest_counts(terms):
    poly = dict(terms)
    prog = emit_program("f", ("a", "b"), [("n", poly), ("m", {(1, 1): 3})])
    fns = _functions(prog.source)
    ns: dict = {}
    exec(compile(ast.Module(body=list(fns.values()), type_ignores=[]), "<test>", "exec"), ns)
    a, b = sp.symbols("a b")
    expected = sum((c * a**i * b**j for (i, j), c in poly.items()), sp.Integer(0))
    assert sp.expand(ns["f"](a, b)[0] - expected) == 0
    tracked = [_Tracked._lift(t) for t in ns["f"](_Tracked(0, 1), _Tracked(0, 1))]
    assert tuple(t.n for t in tracked) == prog.value_counts
    assert tuple(t.degree for t in tracked) == prog.degree
    assert rounding_counts(fns["f"]) == list(zip(prog.value_counts, prog.degree, strict=True))
    mag = sp.Poly(sp.expand(ns["f_magnitude"](a, b)[0]), a, b) if poly and any(poly.values()) else None
    if mag is not None:
        cm = dict(mag.terms())
        for mono, c in sp.Poly(expected, a, b).terms():
            assert cm.get(mono, 0) >= abs(c)


def test_compiled_programs_refuse_anything_but_the_grammar():
    from quadric_contact.families.family_numeric import _checked

    _checked("def f(a):\n    x = a*a - 3\n    return (x,)\n")
    with pytest.raises(AssertionError):
        _checked("def f(a):\n    x = a.__class__\n    return (x,)\n")
    with pytest.raises(AssertionError):
        _checked("def f(a):\n    x = g(a)\n    return (x,)\n")


def test_rational_functions():
    ctx = flint.fmpq_mpoly_ctx.get(("s",), "lex")
    (s,) = ctx.gens()
    r = RationalFunction(s * s - 1, s - 1)
    assert r.is_polynomial and r == RationalFunction(s + 1)
    assert (r / RationalFunction(s)).evaluate([Fraction(1, 2)]) == Fraction(3)
    with pytest.raises(ZeroDivisionError):
        RationalFunction(ctx.constant(1), s).evaluate([0])
    cq = compile_quantity("r", RationalFunction(ctx.constant(3), s * s + 1), 1)
    assert cq.has_denominator and cq.scale == 3


# -- contact maps --------------------------------------------------------------------------------------


def _scalar_answer(fam, names, u, w, fixed=None):
    point = {names[0]: Fraction(float(u)), names[1]: Fraction(float(w)), **(fixed or {})}
    try:
        E, Q = fam.at(**point)
    except ZeroDivisionError:
        return MapAnswer.UNDEFINED
    if E.kind is not qc.QuadricKind.ELLIPSOID:
        return MapAnswer.UNDEFINED
    kind = qc.contact_kind(E, Q, mode="exact")
    if kind.name in ("TANGENT_POINT", "TWO_TANGENT_POINTS", "TANGENT_CURVE"):
        return MapAnswer.TOUCHING
    region = qc.relative_position(E, Q, mode="exact").region
    return {
        Region.R_MINUS: MapAnswer.R_MINUS,
        Region.CONTACT: MapAnswer.CONTACT,
        Region.R_PLUS: MapAnswer.R_PLUS,
    }[region]


def _check_map(m, fam, subcells=25, seed=0):
    for i, u in enumerate(m.u):
        for j, w in enumerate(m.w):
            assert m.codes[i, j] == _scalar_answer(fam, m.names, u, w, m.fixed), (i, j, u, w)
    fu, fw = m.subcell_centres()
    k = 2**m.refine
    rng = np.random.default_rng(seed)
    cells = np.argwhere(m.refined)
    for c in rng.permutation(len(cells))[:subcells]:
        i, j = cells[c]
        a, b = i * k + rng.integers(k), j * k + rng.integers(k)
        assert m.fine[a, b] == _scalar_answer(fam, m.names, fu[a], fw[b], m.fixed), (a, b)


def test_map_cells_are_the_predicates_answers_at_their_centres():
    m = BEE_TRUNK.contact_map(u=(-3, 3), w=(-1, 8), resolution=(9, 7), refine=1)
    assert set(m.counts()) == {"R_MINUS", "CONTACT", "R_PLUS"}
    assert m.refined.any() and not m.refined.all()
    _check_map(m, BEE_TRUNK)


def test_a_map_finds_the_touching_cells():
    # the sphere of radius 1/2 touches the plane z = 0 when w = +-1/2 (cell centres -1, -1/2, 0, 1/2, 1)
    fam = family("(x - u)^2 + y^2 + (z - w)^2 - 1/4", "z", "u w")
    m = fam.contact_map(u=(-1, 1), w=(-1.25, 1.25), resolution=(2, 5), refine=0)
    assert m.codes[0].tolist() == [-1, 3, 0, 3, 1]
    _check_map(m, fam)
    # a sphere inside a cylinder of radius 1 touching it along a circle when |u| = 1/2
    fam = family("(x - u)^2 + y^2 + (z - w)^2 - 1/4", "x^2 + y^2 - 1", "u w")
    m = fam.contact_map(u=(-1.25, 1.25), w=(0, 1), resolution=(5, 1), refine=0)
    assert m.codes[:, 0].tolist() == [0, 3, -1, 3, 0]
    _check_map(m, fam)


def test_undefined_cells_where_e_is_not_an_ellipsoid():
    m = SEMI.contact_map(s=(-0.5, 1.5), v=(-2, 2), resolution=(4, 4), refine=0)
    assert (m.codes[0] != MapAnswer.UNDEFINED).all()  # s = -1/4: s^2 > 0
    m = family("x^2 + y^2 + (z - w)^2 - s", "x^2 + y^2 - z^2 - 4", "s w").contact_map(
        s=(-1, 1), w=(0, 1), resolution=(4, 1), refine=0
    )
    assert m.codes[:, 0].tolist()[:2] == [MapAnswer.UNDEFINED, MapAnswer.UNDEFINED]
    _check_map(m, family("x^2 + y^2 + (z - w)^2 - s", "x^2 + y^2 - z^2 - 4", "s w"))
    _check_map(SEMI.contact_map(s=(0.2, 2), v=(-2, 2), resolution=(5, 4), refine=0), SEMI)


def test_a_map_over_a_family_that_is_not_small():
    # a flat disc in the throat of a hyperboloid: all roots real, yet crossing (Remark 9)
    fam = family("(x - u)^2/a^2 + y^2 + z^2 - 1", "x^2 + y^2 - z^2/100 - 1", "u a")
    m = fam.contact_map(u=(0.5, 1.0), a=(0.05, 0.3), resolution=(5, 4), refine=0)
    assert MapAnswer.CONTACT in m.codes
    _check_map(m, fam)


def test_map_with_a_fixed_parameter_and_argument_errors(tmp_path):
    fam = family("(x - u)^2 + (y - v)^2 + 3*(z - w)^2 - 0.1", TRUNK, "u v w")
    m = fam.contact_map(u=(-2, 2), w=(0, 6), v=0, resolution=6, refine=1)
    ref = BEE_TRUNK.contact_map(u=(-2, 2), w=(0, 6), resolution=6, refine=1)
    assert (m.codes == ref.codes).all() and (m.fine == ref.fine).all()
    assert m.fixed == {"v": 0}
    swapped = BEE_TRUNK.contact_map(w=(0, 6), u=(-2, 2), resolution=6, refine=0)
    assert (swapped.codes == ref.codes.T).all() and swapped.names == ("w", "u")
    with pytest.raises(ShapeError, match="exactly two"):
        fam.contact_map(u=(-1, 1), v=0, w=0)
    with pytest.raises(ShapeError, match="missing"):
        fam.contact_map(u=(-1, 1), w=(0, 1))
    with pytest.raises(ShapeError, match="low < high"):
        BEE_TRUNK.contact_map(u=(1, -1), w=(0, 1))
    fig = m.plot(tmp_path / "map.png")
    assert (tmp_path / "map.png").stat().st_size > 1000 and fig.axes


def test_family_is_exported():
    assert qc.family is family and "family" in qc.__all__ and "Family" in qc.__all__
