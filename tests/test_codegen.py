"""The generated formulas are derived, verified and reproducible."""

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
