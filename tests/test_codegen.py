"""The generated formulas are derived, verified and reproducible."""

import numpy as np
import pytest
import sympy as sp

from quadric_contact import codegen
from quadric_contact._generated import formulas


def test_regenerating_reproduces_the_committed_file_byte_for_byte():
    assert codegen.GENERATED_PATH.read_text() == codegen.emit_formulas()


def test_pencil_program_equals_sympy_determinant():
    codegen.verify_pencil()  # raises on any difference


def test_generated_functions_evaluate_to_the_symbolic_determinant():
    E, es = codegen.symmetric_matrix("e")
    Q, qs = codegen.symmetric_matrix("q")
    reference = codegen.charpoly_by_determinant(E, Q)
    got = formulas.pencil_coefficients(*es, *qs)
    assert [sp.expand(g - r) for g, r in zip(got, reference, strict=True)] == [0] * 5
    assert sp.expand(formulas.det_symmetric_4(*qs) - Q.det(method="berkowitz")) == 0


def test_discrimination_sequences_match_yang_definition():
    for n in range(1, 5):
        c = codegen.coefficient_symbols(n)
        M = codegen.discrimination_matrix(list(reversed(c)))
        fn = getattr(formulas, f"discrimination_sequence_{n}")
        got = fn(*c)
        for k in range(1, n + 1):
            assert sp.expand(got[k - 1] - M[: 2 * k, : 2 * k].det()) == 0


def test_last_discrimination_minor_is_leading_coefficient_times_discriminant():
    x = sp.Symbol("x")
    for n in range(2, 5):
        c = codegen.coefficient_symbols(n)
        f = sum(ci * x**i for i, ci in enumerate(c))
        Dn = getattr(formulas, f"discrimination_sequence_{n}")(*c)[-1]
        assert sp.expand(Dn - c[n] ** 2 * sp.discriminant(f, x)) == 0


def test_paper_deltas_are_positive_multiples_of_yang_minors():
    c = codegen.coefficient_symbols(4)
    D = formulas.discrimination_sequence_4(*c)
    d2, d3, d4 = formulas.paper_deltas(*c)
    assert sp.expand(D[1] - c[4] ** 2 * d2) == 0
    assert sp.expand(D[2] - 2 * c[4] ** 2 * d3) == 0
    assert sp.expand(D[3] - c[4] ** 2 * d4) == 0


def test_quartic_sign_forms_are_positive_multiples_of_the_deltas():
    c = codegen.coefficient_symbols(4)
    d2, d3, d4 = formulas.paper_deltas(*c)
    s2, s3, s27 = formulas.quartic_sign_forms(*c)
    assert sp.expand(s2 - d2) == 0 and sp.expand(s3 - d3) == 0 and sp.expand(s27 - 27 * d4) == 0


# -- the number-mode companions (_generated/kernels.py) ---------------------------------------

from quadric_contact._generated import kernels  # noqa: E402


def test_regenerating_reproduces_the_kernels_byte_for_byte():
    assert codegen.KERNELS_PATH.read_text() == codegen.emit_kernels()


def test_check_command_covers_every_generated_file(capsys):
    assert codegen.main(["--check"]) == 0
    out = capsys.readouterr().out
    generated = sorted(p.name for p in codegen.GENERATED_PATH.parent.glob("*.py") if p.name != "__init__.py")
    assert generated == ["blocks.py", "dd_programs.py", "formulas.py", "kernels.py"]
    for name in generated:
        assert f"{name}: current" in out


def test_regenerating_reproduces_the_blocks_byte_for_byte():
    assert codegen.BLOCKS_PATH.read_text() == codegen.emit_blocks()


def test_blocks_compute_the_same_bits_as_the_formulas():
    from quadric_contact._generated import blocks

    rng = np.random.default_rng(3)
    e = tuple(rng.normal(size=50) for _ in range(10))
    q = tuple(rng.normal(size=50) for _ in range(10))
    ref = formulas.pencil_coefficients(*e, *q)
    for got in (
        blocks.pencil(e, q),
        blocks.pencil_with_q_part(e, q, blocks.pencil_q_part(q)),
        blocks.pencil_with_e_part(e, q, blocks.pencil_e_part(e)),
    ):
        for g, r in zip(got, ref, strict=True):
            assert np.array_equal(g, r)


def _wide_floats(rng, n):
    """Signed binary64 numbers over a wide range of exponents, with zeros and signed zeros."""
    x = rng.uniform(1, 2, size=n) * np.exp2(rng.integers(-60, 60, size=n)) * rng.choice([-1.0, 1.0], size=n)
    x[rng.random(n) < 0.05] = 0.0
    x[rng.random(n) < 0.05] = -0.0
    return x


def test_value_and_magnitude_program_has_the_bits_of_the_two_programs():
    """The fused Delta program (products shared between the value and its magnitude companion)
    gives bit for bit what the value program and the companion at the absolute values give, with
    numpy and compiled; so the error bounds derived for the two programs hold for it unchanged."""
    from quadric_contact._generated import blocks
    from quadric_contact.modes.kernels._jit import njit

    rng = np.random.default_rng(5)
    c = tuple(_wide_floats(rng, 20000) for _ in range(5))
    values = kernels.paper_deltas_compact(*c)
    mags = blocks.paper_deltas_compact_magnitude(*(np.abs(x) for x in c))
    fused = blocks.paper_deltas_compact_and_magnitude(*c)
    for g, r in zip(fused, (*values, *mags), strict=True):
        assert np.array_equal(g.view(np.int64), np.asarray(r).view(np.int64))
    both = njit(blocks.paper_deltas_compact_and_magnitude)
    for i in range(0, 20000, 97):
        got = both(*(float(x[i]) for x in c))
        want = (*(v[i] for v in values), *(m[i] for m in mags))
        assert np.array_equal(np.array(got).view(np.int64), np.array(want).view(np.int64))


def test_fused_program_reuses_only_products_of_exact_magnitudes():
    """A product whose operand is a sum has a magnitude other than the absolute value of its
    value: the fused program must compute that one (here ``(a - b) * c``)."""
    import ast

    from quadric_contact.exact.straight_line import _interpret, emit_value_and_magnitude_function

    fdef = ast.parse("def f(a, b, c):\n    s = a - b\n    return s*c\n").body[0]
    fused = ast.parse("\n".join(emit_value_and_magnitude_function(fdef))).body[0]
    _, (value, mag) = _interpret(fused, [1.0, 3.0, -2.0])
    assert value == 4.0 and mag == 8.0  # |a - b| |c| = 4, the companion (|a| + |b|) |c| = 8


def test_invariants_are_the_characteristic_polynomial_coefficients():
    codegen.verify_invariants()  # raises on any difference
    Q, qs = codegen.symmetric_matrix("q")
    t = sp.Symbol("t")
    got = kernels.quadric_invariants(*qs)
    ref = sp.Poly((t * sp.eye(4) + Q).det(), t).all_coeffs()[1:]
    assert [sp.expand(g - r) for g, r in zip(got[3:], ref, strict=True)] == [0] * 4
    A = Q[:3, :3]
    ref_a = sp.Poly((t * sp.eye(3) + A).det(), t).all_coeffs()[1:]
    assert [sp.expand(g - r) for g, r in zip(got[:3], ref_a, strict=True)] == [0] * 3
    a = [sp.Symbol(f"a{i}{j}") for i, j in codegen.QUADRATIC_PART_INDICES]
    M = sp.Matrix(3, 3, lambda i, j: a[codegen.QUADRATIC_PART_INDICES.index((min(i, j), max(i, j)))])
    m2, m3 = kernels.leading_minors_3(*a)
    assert sp.expand(m2 - M[:2, :2].det()) == 0 and sp.expand(m3 - M.det()) == 0


def _value_and_magnitude(name):
    module = formulas if kernels.ROUNDING_COUNTS[name]["module"] == ("formulas",) else kernels
    return getattr(module, name), getattr(kernels, f"{name}_magnitude")


@pytest.mark.parametrize("name", [f for _, f, _ in codegen.FILTERED_FUNCTIONS])
def test_magnitude_companion_dominates_every_product(name):
    """Expanded, the companion has non-negative coefficients, each at least the absolute
    value of the value program's coefficient of the same monomial (it sums |products|)."""
    value, magnitude = _value_and_magnitude(name)
    nargs = value.__code__.co_argcount
    xs = sp.symbols(f"x0:{nargs}")
    for v, m in zip(value(*xs), magnitude(*xs), strict=True):
        pv, pm = sp.Poly(sp.expand(v), *xs), sp.Poly(sp.expand(m), *xs)
        cm = dict(pm.terms())
        assert all(c > 0 for c in cm.values())
        for mono, c in pv.terms():
            assert cm.get(mono, 0) >= abs(c)


class _Tracked:
    """A number that counts the rounded operations on its worst path and its degree —
    an independent re-derivation of ROUNDING_COUNTS by running the generated code."""

    def __init__(self, n, degree):
        self.n, self.degree = n, degree

    @staticmethod
    def _lift(x):
        return x if isinstance(x, _Tracked) else _Tracked(0, 0)

    def __add__(self, other):
        o = self._lift(other)
        return _Tracked(max(self.n, o.n) + 1, max(self.degree, o.degree))

    __radd__ = __add__
    __sub__ = __add__
    __rsub__ = __add__

    def __mul__(self, other):
        o = self._lift(other)
        return _Tracked(self.n + o.n + 1, self.degree + o.degree)

    __rmul__ = __mul__

    def __neg__(self):
        return self


@pytest.mark.parametrize("name", [f for _, f, _ in codegen.FILTERED_FUNCTIONS])
def test_rounding_counts_agree_with_an_instrumented_run(name):
    value, magnitude = _value_and_magnitude(name)
    rc = kernels.ROUNDING_COUNTS[name]
    nargs = value.__code__.co_argcount
    runs = (("value", value, 0), ("value_rounded_inputs", value, 1), ("magnitude", magnitude, 0))
    for key, fn, leaf in runs:
        out = fn(*[_Tracked(leaf, 1) for _ in range(nargs)])
        assert tuple(t.n for t in out) == rc[key], key
        assert tuple(t.degree for t in out) == rc["degree"]
