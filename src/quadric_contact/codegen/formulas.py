"""Derive the closed forms of ``_generated/formulas.py`` and write the file.

The coefficients of the pencil ``det(lambda*E + Q)`` (paper eq. (1)) by a Laplace
expansion checked against sympy's determinant (:func:`derive_pencil`,
:func:`verify_pencil`), Yang's discrimination sequences of degrees 1 to 4
(:func:`derive_discrimination_sequence`), the paper's normalisation of them
(:func:`derive_paper_deltas`) and the invariants ``I``, ``J`` of the quartic
(:func:`derive_quartic_invariants`); :func:`emit_formulas` prints them as straight-line
code and :func:`regenerate` writes (or checks) the file.  The symbolic building blocks
(:func:`symmetric_matrix`, :func:`coefficient_symbols`) serve the other generated files too.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import sympy as sp

from quadric_contact.codegen.emission import emit_expression, emit_polynomial, power_temps
from quadric_contact.exact.entries import ENTRY_INDICES

__all__ = [
    "GENERATED_PATH",
    "charpoly_by_determinant",
    "coefficient_symbols",
    "derive_discrimination_sequence",
    "derive_paper_deltas",
    "derive_pencil",
    "derive_quartic_invariants",
    "discrimination_matrix",
    "emit_formulas",
    "regenerate",
    "substitute_program",
    "symmetric_matrix",
    "verify_pencil",
]

GENERATED_PATH = Path(__file__).parents[1] / "_generated" / "formulas.py"


def symmetric_matrix(prefix: str) -> tuple[sp.Matrix, list[sp.Symbol]]:
    """A symbolic symmetric 4x4 matrix with entries ``{prefix}ij`` (i <= j)."""
    syms = {ij: sp.Symbol(f"{prefix}{ij[0]}{ij[1]}") for ij in ENTRY_INDICES}
    m = sp.Matrix(4, 4, lambda i, j: syms[(min(i, j), max(i, j))])
    return m, [syms[ij] for ij in ENTRY_INDICES]


def coefficient_symbols(n: int = 4) -> list[sp.Symbol]:
    """``c0 .. cn`` (``c_k`` multiplies ``lambda**k``)."""
    return list(sp.symbols(f"c0:{n + 1}"))


def charpoly_by_determinant(E: sp.Matrix, Q: sp.Matrix) -> list[sp.Expr]:
    """``[c0, .., c4]`` of det(lambda*E + Q), straight from sympy's determinant."""
    lam = sp.Symbol("lambda")
    poly = sp.Poly(sp.expand((lam * E + Q).det(method="berkowitz")), lam)
    return [sp.expand(poly.coeff_monomial(lam**k)) for k in range(5)]


_PAIRS = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))


def _pair_sign(cols: tuple[int, int]) -> int:
    """Sign of the Laplace term for rows (0, 1) and columns ``cols``."""
    return -1 if (cols[0] + cols[1] + 0 + 1) % 2 else 1


def derive_pencil() -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[sp.Expr], list[sp.Symbol]]:
    """Straight-line program for the coefficients of det(lambda*E + Q).

    Returns ``(assignments, outputs, arguments)``: ``assignments`` is a list
    of ``(temporary, expression)`` in evaluation order, ``outputs`` the
    expressions for ``c0 .. c4`` in terms of arguments and temporaries.
    """
    E, es = symmetric_matrix("e")
    Q, qs = symmetric_matrix("q")
    assignments: list[tuple[sp.Symbol, sp.Expr]] = []

    def minors(rows: tuple[int, int], cols: tuple[int, int], tag: str) -> tuple[sp.Symbol, ...]:
        (r0, r1), (a, b) = rows, cols
        ee = E[r0, a] * E[r1, b] - E[r0, b] * E[r1, a]
        qq = Q[r0, a] * Q[r1, b] - Q[r0, b] * Q[r1, a]
        mm = E[r0, a] * Q[r1, b] + Q[r0, a] * E[r1, b] - E[r0, b] * Q[r1, a] - Q[r0, b] * E[r1, a]
        out = []
        for kind, expr in (("E", ee), ("M", mm), ("Q", qq)):
            s = sp.Symbol(f"{kind}{tag}{a}{b}")
            assignments.append((s, expr))
            out.append(s)
        return tuple(out)

    c = [sp.Integer(0)] * 5
    for cols in _PAIRS:
        rest = tuple(sorted(set(range(4)) - set(cols)))
        top_e, top_m, top_q = minors((0, 1), cols, "t")
        bot_e, bot_m, bot_q = minors((2, 3), rest, "b")  # type: ignore[arg-type]
        s = _pair_sign(cols)
        # (top_e L^2 + top_m L + top_q) * (bot_e L^2 + bot_m L + bot_q)
        c[4] += s * top_e * bot_e
        c[3] += s * (top_e * bot_m + top_m * bot_e)
        c[2] += s * (top_e * bot_q + top_m * bot_m + top_q * bot_e)
        c[1] += s * (top_m * bot_q + top_q * bot_m)
        c[0] += s * top_q * bot_q
    return assignments, c, es + qs


def substitute_program(
    assignments: Sequence[tuple[sp.Symbol, sp.Expr]], outputs: Sequence[sp.Expr]
) -> list[sp.Expr]:
    """Inline the temporaries of a straight-line program (for verification)."""
    env: dict[sp.Symbol, sp.Expr] = {}
    for sym, expr in assignments:
        env[sym] = expr.xreplace(env)
    return [sp.expand(o.xreplace(env)) for o in outputs]


def verify_pencil() -> None:
    """Raise AssertionError unless the generated program equals sympy's determinant."""
    assignments, outputs, _ = derive_pencil()
    E, _ = symmetric_matrix("e")
    Q, _ = symmetric_matrix("q")
    derived = substitute_program(assignments, outputs)
    reference = charpoly_by_determinant(E, Q)
    for k, (d, r) in enumerate(zip(derived, reference, strict=True)):
        if sp.expand(d - r) != 0:
            raise AssertionError(f"pencil coefficient c{k} differs from sympy's determinant")


def discrimination_matrix(coeffs_high_first: Sequence[sp.Expr]) -> sp.Matrix:
    """Yang's discrimination matrix Discr(f) of f and f' (2n x 2n).

    ``coeffs_high_first`` are ``a0 .. an`` with ``f = a0 x^n + ... + an``.
    Rows alternate between shifted copies of ``f`` and of ``f'``.
    """
    a = list(coeffs_high_first)
    n = len(a) - 1
    da = [(n - i) * a[i] for i in range(n)]
    M = sp.zeros(2 * n, 2 * n)
    for i in range(n):
        for j, coef in enumerate(a):
            M[2 * i, i + j] = coef
        for j, coef in enumerate(da):
            M[2 * i + 1, i + 1 + j] = coef
    return M


def derive_discrimination_sequence(n: int) -> list[sp.Expr]:
    """``[D_1, .., D_n]`` for ``f = c_n x^n + ... + c_0`` (Yang 1999, Definition 1)."""
    c = coefficient_symbols(n)
    M = discrimination_matrix(list(reversed(c)))
    return [sp.expand(M[: 2 * k, : 2 * k].det(method="berkowitz")) for k in range(1, n + 1)]


def derive_paper_deltas() -> list[sp.Expr]:
    """``[Delta_2, Delta_3, Delta_4]``: Yang's D_k divided by their positive
    factors ``c4**2``, ``2*c4**2``, ``c4**2`` (exact polynomial division)."""
    c = coefficient_symbols(4)
    D = derive_discrimination_sequence(4)
    out = []
    for Dk, factor in ((D[1], c[4] ** 2), (D[2], 2 * c[4] ** 2), (D[3], c[4] ** 2)):
        q, r = sp.div(sp.Poly(Dk, *c), sp.Poly(factor, *c))
        if not r.is_zero:
            raise AssertionError("the paper's normalisation is not an exact division")
        out.append(q.as_expr())
    return out


def derive_quartic_invariants() -> tuple[sp.Expr, sp.Expr]:
    """The invariants ``I``, ``J`` of the binary quartic with
    ``4 I^3 - J^2 = 27 Delta_4`` (checked here, not assumed)."""
    c0, c1, c2, c3, c4 = coefficient_symbols(4)
    # a x^4 + b x^3 + c x^2 + d x + e with a = c4, ..., e = c0
    a, b, c, d, e = c4, c3, c2, c1, c0
    Iv = 12 * a * e - 3 * b * d + c**2
    Jv = 72 * a * c * e + 9 * b * c * d - 27 * a * d**2 - 27 * b**2 * e - 2 * c**3
    delta4 = derive_paper_deltas()[2]
    if sp.expand(4 * Iv**3 - Jv**2 - 27 * delta4) != 0:
        raise AssertionError("4 I^3 - J^2 != 27 Delta_4")
    return Iv, Jv


def emit_formulas() -> str:
    """The full text of ``_generated/formulas.py``."""
    out: list[str] = [
        '"""Closed forms of quadric-contact, generated by ``quadric_contact.codegen``.',
        "",
        "Do not edit: regenerate with ``python -m quadric_contact.codegen``.  Every",
        "function is straight-line code over ``+ - *`` with integer literals, so it runs",
        "on int, Fraction, float, numpy arrays, mpmath and flint arb alike.",
        '"""',
        "",
        "# ruff: noqa",
        "",
    ]
    # Pencil coefficients.
    assignments, outputs, args = derive_pencil()
    arg_names = ", ".join(str(a) for a in args)
    out += [
        f"def pencil_coefficients({arg_names}):",
        '    """(c0, c1, c2, c3, c4) of det(lambda*E + Q) from the upper entries eij of E and qij of Q',
        '    (Laplace expansion along rows 0, 1; each 2x2 minor split into E, mixed and Q parts)."""',
    ]
    for sym, expr in assignments:
        out.append(f"    {sym} = {emit_expression(expr)}")
    for k, o in enumerate(outputs):
        out.append(f"    c{k} = {emit_expression(o)}")
    out += ["    return (c0, c1, c2, c3, c4)", "", ""]
    # The determinant of one symmetric matrix: the Q-only part of the same program.
    q_only = [(sym, expr) for sym, expr in assignments if str(sym).startswith("Q")]
    q_args = ", ".join(str(a) for a in args[10:])
    out += [
        f"def det_symmetric_4({q_args}):",
        '    """det(Q) for the symmetric Q with upper entries qij (the c0 part of pencil_coefficients)."""',
    ]
    for sym, expr in q_only:
        out.append(f"    {sym} = {emit_expression(expr)}")
    out += [f"    return {emit_expression(outputs[0])}", "", ""]
    # Discrimination sequences.
    for n in range(1, 5):
        c = coefficient_symbols(n)
        D = derive_discrimination_sequence(n)
        lines, temps = power_temps(D, c)
        out += [
            f"def discrimination_sequence_{n}({', '.join(str(s) for s in c)}):",
            f'    """Yang\'s (D_1, .., D_{n}) for c{n}*x^{n} + ... + c0: the even-order principal',
            '    minors of the discrimination matrix of f and f\'."""',
            *lines,
        ]
        for k, Dk in enumerate(D, 1):
            out.append(f"    D{k} = {emit_polynomial(Dk, c, temps)}")
        out += [f"    return ({', '.join(f'D{k}' for k in range(1, n + 1))}{',' if n == 1 else ''})", "", ""]
    # Paper deltas.
    c = coefficient_symbols(4)
    deltas = derive_paper_deltas()
    lines, temps = power_temps(deltas, c)
    out += [
        "def paper_deltas(c0, c1, c2, c3, c4):",
        '    """(Delta_2, Delta_3, Delta_4) of Section 3.2: D_2/c4^2, D_3/(2 c4^2), D_4/c4^2."""',
        *lines,
    ]
    for name, d in zip(("Delta2", "Delta3", "Delta4"), deltas, strict=True):
        out.append(f"    {name} = {emit_polynomial(d, c, temps)}")
    out += ["    return (Delta2, Delta3, Delta4)", "", ""]
    # Sign forms: the same signs with far fewer operations.
    Iv, Jv = derive_quartic_invariants()
    out += [
        "def quartic_sign_forms(c0, c1, c2, c3, c4):",
        '    """(Delta_2, Delta_3, 27*Delta_4) with 27*Delta_4 = 4*I^3 - J^2 from the invariants I, J',
        '    of the quartic: the signs of paper_deltas at a fraction of the cost."""',
        f"    I = {emit_expression(Iv)}",
        f"    J = {emit_expression(Jv)}",
        f"    Delta2 = {emit_expression(deltas[0])}",
        f"    Delta3 = {emit_expression(deltas[1])}",
        "    return (Delta2, Delta3, 4*I*I*I - J*J)",
        "",
    ]
    return "\n".join(out)


def regenerate(path: Path = GENERATED_PATH, check: bool = False) -> bool:
    """Write (or with ``check=True`` only compare) the generated module.

    Returns True when the file on disk equals the freshly generated text.
    """
    verify_pencil()
    text = emit_formulas()
    current = path.read_text() if path.exists() else None
    if check:
        return current == text
    path.parent.mkdir(parents=True, exist_ok=True)
    init = path.parent / "__init__.py"
    if not init.exists():
        init.write_text('"""Generated code; see :mod:`quadric_contact.codegen`."""\n')
    path.write_text(text)
    return current == text
