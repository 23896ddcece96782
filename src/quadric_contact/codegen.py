"""Derive the package's closed forms with sympy and emit them as straight-line code.

Nothing in :mod:`quadric_contact._generated.formulas` is typed in by hand: this
module derives every formula symbolically, checks it against an independent
sympy computation, and writes it out as plain Python that uses only ``+``,
``-``, ``*`` and integer literals.  Such code runs unchanged on every number
type the package uses (``int``, ``Fraction``, ``float``, numpy arrays, mpmath
numbers, flint ``arb`` balls), which is what "one formula, many number modes"
means in practice.

Derivations
-----------
``pencil_coefficients``
    The coefficients ``c0 .. c4`` of ``P(lambda) = det(lambda*E + Q)``
    (paper eq. (1)) for symmetric ``E`` and ``Q`` given by their ten upper
    entries.  Derived by the Laplace expansion of the 4x4 determinant along
    rows (0, 1) against rows (2, 3): each 2x2 minor of ``lambda*E + Q`` is a
    quadratic in lambda (an E-minor, a Q-minor and a mixed term), and the
    coefficients are sums of products of those.  Checked against sympy's
    determinant expanded in lambda.
``discrimination_sequence_n`` (n = 1 .. 4)
    The principal minors ``D_1 .. D_n`` of even order of the discrimination
    matrix of a degree-n polynomial and its derivative (Yang 1999, the
    subresultant-based "complete discrimination system").
``paper_deltas``
    The paper's normalisation (Section 3.2) of Yang's minors for the quartic:
    ``Delta_2 = D_2 / c4**2``, ``Delta_3 = D_3 / (2*c4**2)``,
    ``Delta_4 = D_4 / c4**2``; the divisions are exact polynomial divisions
    done by sympy, and the positive factors are what make the signs agree.

Companions for the number modes (``_generated/kernels.py``)
------------------------------------------------------------
``leading_minors_3``, ``quadric_invariants``
    The leading principal minors of a quadratic part (Sylvester's test that
    ``E`` is an ellipsoid) and the invariants that fix the affine type of
    ``Q`` (trace, ``J`` and determinant of the quadratic part; the sums of
    the principal minors of each order of the whole matrix), expanded by
    sympy and checked against its determinants.
``*_magnitude``
    For every straight-line function of either generated module, the same
    program with every ``-`` turned into ``+`` and every input read as its
    absolute value (an AST transformation of the emitted text, so the
    operations, their order and their association are those of the value
    program).  Its value bounds the sum of the absolute values of all the
    products the value program adds up: the quantity a rounding-error bound
    is proportional to.
``ROUNDING_COUNTS``
    For every output of every straight-line function, the largest number of
    rounded operations on any path from the inputs (an AST walk of the
    emitted text: a sum counts ``max + 1``, a product ``sum + 1``) and the
    degree.  :mod:`quadric_contact.modes.errorbounds` turns them into the
    error-bound constants.

Regenerate with ``python -m quadric_contact.codegen`` (or
``quadric-contact codegen``); the test suite checks that regenerating
reproduces both committed files byte for byte.
"""

from __future__ import annotations

import argparse
import ast
import itertools
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import sympy as sp

from .entries import ENTRY_INDICES

GENERATED_PATH = Path(__file__).with_name("_generated") / "formulas.py"
KERNELS_PATH = Path(__file__).with_name("_generated") / "kernels.py"


# -- symbolic building blocks ---------------------------------------------------


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


# -- emission -------------------------------------------------------------------


def _monomial_code(
    powers: Sequence[int], names: Sequence[str], temps: dict[tuple[int, int], str]
) -> list[str]:
    factors: list[str] = []
    for idx, p in enumerate(powers):
        if p == 0:
            continue
        if p == 1:
            factors.append(names[idx])
        elif (idx, p) in temps:
            factors.append(temps[(idx, p)])
        else:
            factors.extend([names[idx]] * p)
    return factors


def _emit_polynomial(expr: sp.Expr, variables: Sequence[sp.Symbol], temps: dict[tuple[int, int], str]) -> str:
    """Emit an integer polynomial as a sum of monomials; powers use shared temporaries."""
    poly = sp.Poly(expr, *variables)
    names = [str(v) for v in variables]
    parts: list[str] = []
    for powers, coef in poly.terms():  # deterministic (lex) order
        if not coef.is_Integer:
            raise AssertionError(f"non-integer coefficient {coef} in generated formula")
        factors = _monomial_code(powers, names, temps)
        k = int(coef)
        body = "*".join(factors) if factors else "1"
        if abs(k) != 1:
            body = f"{abs(k)}*{body}" if factors else str(abs(k))
        parts.append(("- " if k < 0 else "+ ") + body)
    if not parts:
        return "0"
    text = " ".join(parts)
    return text[2:] if text.startswith("+ ") else "-" + text[2:]


def _power_temps(
    exprs: Sequence[sp.Expr], variables: Sequence[sp.Symbol]
) -> tuple[list[str], dict[tuple[int, int], str]]:
    needed: set[tuple[int, int]] = set()
    for e in exprs:
        for powers, _ in sp.Poly(e, *variables).terms():
            needed.update((i, p) for i, p in enumerate(powers) if p > 1)
    lines: list[str] = []
    temps: dict[tuple[int, int], str] = {}
    for i, p in sorted(needed):
        name = f"{variables[i]}_{p}"
        temps[(i, p)] = name
    for i, p in sorted(needed):
        base = str(variables[i])
        prev = temps.get((i, p - 1), base if p - 1 == 1 else None)
        rhs = f"{prev}*{base}" if prev is not None else "*".join([base] * p)
        lines.append(f"    {temps[(i, p)]} = {rhs}")
    return lines, temps


def _emit_expression(expr: sp.Expr) -> str:
    """Print an integer polynomial in its free symbols; powers become products."""
    expr = sp.expand(expr)
    variables = sorted(expr.free_symbols, key=str)
    return _emit_polynomial(expr, variables, {}) if variables else str(int(expr))


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
        out.append(f"    {sym} = {_emit_expression(expr)}")
    for k, o in enumerate(outputs):
        out.append(f"    c{k} = {_emit_expression(o)}")
    out += ["    return (c0, c1, c2, c3, c4)", "", ""]
    # The determinant of one symmetric matrix: the Q-only part of the same program.
    q_only = [(sym, expr) for sym, expr in assignments if str(sym).startswith("Q")]
    q_args = ", ".join(str(a) for a in args[10:])
    out += [
        f"def det_symmetric_4({q_args}):",
        '    """det(Q) for the symmetric Q with upper entries qij (the c0 part of pencil_coefficients)."""',
    ]
    for sym, expr in q_only:
        out.append(f"    {sym} = {_emit_expression(expr)}")
    out += [f"    return {_emit_expression(outputs[0])}", "", ""]
    # Discrimination sequences.
    for n in range(1, 5):
        c = coefficient_symbols(n)
        D = derive_discrimination_sequence(n)
        lines, temps = _power_temps(D, c)
        out += [
            f"def discrimination_sequence_{n}({', '.join(str(s) for s in c)}):",
            f'    """Yang\'s (D_1, .., D_{n}) for c{n}*x^{n} + ... + c0: the even-order principal',
            '    minors of the discrimination matrix of f and f\'."""',
            *lines,
        ]
        for k, Dk in enumerate(D, 1):
            out.append(f"    D{k} = {_emit_polynomial(Dk, c, temps)}")
        out += [f"    return ({', '.join(f'D{k}' for k in range(1, n + 1))}{',' if n == 1 else ''})", "", ""]
    # Paper deltas.
    c = coefficient_symbols(4)
    deltas = derive_paper_deltas()
    lines, temps = _power_temps(deltas, c)
    out += [
        "def paper_deltas(c0, c1, c2, c3, c4):",
        '    """(Delta_2, Delta_3, Delta_4) of Section 3.2: D_2/c4^2, D_3/(2 c4^2), D_4/c4^2."""',
        *lines,
    ]
    for name, d in zip(("Delta2", "Delta3", "Delta4"), deltas, strict=True):
        out.append(f"    {name} = {_emit_polynomial(d, c, temps)}")
    out += ["    return (Delta2, Delta3, Delta4)", "", ""]
    # Sign forms: the same signs with far fewer operations.
    Iv, Jv = derive_quartic_invariants()
    out += [
        "def quartic_sign_forms(c0, c1, c2, c3, c4):",
        '    """(Delta_2, Delta_3, 27*Delta_4) with 27*Delta_4 = 4*I^3 - J^2 from the invariants I, J',
        '    of the quartic: the signs of paper_deltas at a fraction of the cost."""',
        f"    I = {_emit_expression(Iv)}",
        f"    J = {_emit_expression(Jv)}",
        f"    Delta2 = {_emit_expression(deltas[0])}",
        f"    Delta3 = {_emit_expression(deltas[1])}",
        "    return (Delta2, Delta3, 4*I*I*I - J*J)",
        "",
    ]
    return "\n".join(out)


# -- number-mode companions (``_generated/kernels.py``) -------------------------------

QUADRATIC_PART_INDICES: tuple[tuple[int, int], ...] = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
"""The six independent entries of a symmetric 3x3 quadratic part, in argument order."""


def _principal_minor_sum(M: sp.Matrix, order: int) -> sp.Expr:
    from itertools import combinations

    n = M.shape[0]
    return sp.expand(
        sum(
            (
                M.extract(list(rows), list(rows)).det(method="berkowitz")
                for rows in combinations(range(n), order)
            ),
            sp.Integer(0),
        )
    )


def derive_leading_minors_3() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """Leading principal minors of orders 2 and 3 of a symmetric 3x3 matrix ``a``
    (Sylvester's criterion; the order-1 minor is the entry ``a00`` itself)."""
    syms = {ij: sp.Symbol(f"a{ij[0]}{ij[1]}") for ij in QUADRATIC_PART_INDICES}
    A = sp.Matrix(3, 3, lambda i, j: syms[(min(i, j), max(i, j))])
    args = [syms[ij] for ij in QUADRATIC_PART_INDICES]
    return args, [
        ("m2", sp.expand(A[:2, :2].det(method="berkowitz"))),
        ("m3", sp.expand(A.det(method="berkowitz"))),
    ]


def derive_quadric_invariants() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """The invariants that fix the affine type of ``Q`` (see
    :mod:`quadric_contact.classification`): trace, ``J`` and determinant of the
    quadratic part, and the sums ``E1 .. E4`` of the principal minors of each
    order of the whole matrix (``det(t I + Q) = t^4 + E1 t^3 + E2 t^2 + E3 t + E4``)."""
    Q, qs = symmetric_matrix("q")
    A = Q[:3, :3]
    outputs = [
        ("trA", _principal_minor_sum(A, 1)),
        ("JA", _principal_minor_sum(A, 2)),
        ("detA", _principal_minor_sum(A, 3)),
    ]
    outputs += [(f"E{k}", _principal_minor_sum(Q, k)) for k in range(1, 5)]
    return qs, outputs


def verify_invariants() -> None:
    """Raise AssertionError unless the invariants are the coefficients sympy's
    characteristic polynomials give (an independent computation)."""
    t = sp.Symbol("t")
    args, outputs = derive_quadric_invariants()
    Q, _ = symmetric_matrix("q")
    got = dict(outputs)
    cq = sp.Poly((t * sp.eye(4) + Q).det(method="berkowitz"), t)
    for k in range(1, 5):
        if sp.expand(got[f"E{k}"] - cq.coeff_monomial(t ** (4 - k))) != 0:
            raise AssertionError(f"E{k} differs from the characteristic polynomial of Q")
    ca = sp.Poly((t * sp.eye(3) + Q[:3, :3]).det(method="berkowitz"), t)
    for name, k in (("trA", 1), ("JA", 2), ("detA", 3)):
        if sp.expand(got[name] - ca.coeff_monomial(t ** (3 - k))) != 0:
            raise AssertionError(f"{name} differs from the characteristic polynomial of the quadratic part")
    _, minors = derive_leading_minors_3()
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{min(i, j)}{max(i, j)}"))
    if sp.expand(dict(minors)["m3"] - A.det()) != 0 or sp.expand(dict(minors)["m2"] - A[:2, :2].det()) != 0:
        raise AssertionError("leading minors differ from sympy's determinants")


def derive_compact_deltas() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """A short straight-line program with the signs of ``(Delta_2, Delta_3, Delta_4)``,
    for exact arithmetic (about 60 operations instead of 160): ``Delta_3`` grouped by
    ``c3`` and ``c4``, and ``27 Delta_4 = 4 I^3 - J^2`` with the invariants ``I, J`` of
    the quartic (the discriminant identity).  Checked against :func:`derive_paper_deltas`
    by :func:`verify_compact_deltas`.  Not for floating point: ``4 I^3 - J^2`` cancels far
    more than the expanded form, so its rounding bound is much weaker."""
    c0, c1, c2, c3, c4 = coefficient_symbols(4)
    I, J, u, v, w = sp.symbols("I J u v w")  # noqa: E741 - the classical names
    program = [
        ("I", 12 * c0 * c4 - 3 * c1 * c3 + c2 * c2),
        (
            "J",
            72 * c0 * c2 * c4 - 27 * c0 * c3 * c3 - 27 * c1 * c1 * c4 + 9 * c1 * c2 * c3 - 2 * c2 * c2 * c2,
        ),
        ("u", c2 * c2 - 3 * c1 * c3),
        ("v", 8 * c0 * c2 - 9 * c1 * c1),
        ("w", 7 * c1 * c2 - 3 * c0 * c3),
        ("Delta2", 3 * c3 * c3 - 8 * c2 * c4),
        ("Delta3", c3 * c3 * u + 2 * c4 * c4 * v + 2 * c3 * c4 * w - 4 * c2 * c2 * c2 * c4),
        ("Delta4_27", 4 * I * I * I - J * J),
    ]
    return [c0, c1, c2, c3, c4], [(name, sp.expand(expr)) for name, expr in program]


def verify_compact_deltas() -> None:
    """Raise AssertionError unless the compact program gives ``Delta_2, Delta_3, 27 Delta_4``."""
    _, program = derive_compact_deltas()
    env: dict[sp.Symbol, sp.Expr] = {}
    for name, expr in program:
        env[sp.Symbol(name)] = sp.expand(expr.xreplace(env))
    d2, d3, d4 = derive_paper_deltas()
    for name, ref in (("Delta2", d2), ("Delta3", d3), ("Delta4_27", 27 * d4)):
        if sp.expand(env[sp.Symbol(name)] - ref) != 0:
            raise AssertionError(f"compact {name} differs from the derived one")


def _emit_function(
    name: str, args: Sequence[sp.Symbol], outputs: Sequence[tuple[str, sp.Expr]], doc: str
) -> list[str]:
    lines = [f"def {name}({', '.join(str(a) for a in args)}):", f'    """{doc}"""']
    for out_name, expr in outputs:
        lines.append(f"    {out_name} = {_emit_expression(expr)}")
    lines.append(f"    return ({', '.join(n for n, _ in outputs)}{',' if len(outputs) == 1 else ''})")
    return lines


# The straight-line functions have a tiny grammar: assignments of expressions built
# from names, integer constants, binary + - * and unary minus, and a tuple return.
# The printer below covers exactly that grammar (ast.unparse would do, but its
# spacing is not promised to stay the same across Python versions, and the
# generated file must reproduce byte for byte).

_PRECEDENCE = {ast.Add: 1, ast.Sub: 1, ast.Mult: 2}
_SYMBOL = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*"}


def _print_expr(node: ast.expr, parent_prec: int = 0, right: bool = False) -> str:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
        return str(node.value)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        text = "-" + _print_expr(node.operand, 3)
        return f"({text})" if parent_prec >= 2 else text
    if isinstance(node, ast.BinOp) and type(node.op) in _PRECEDENCE:
        prec = _PRECEDENCE[type(node.op)]
        left, right_text = _print_expr(node.left, prec), _print_expr(node.right, prec, True)
        op = _SYMBOL[type(node.op)]
        text = f"{left} {op} {right_text}" if prec == 1 else f"{left}{op}{right_text}"
        needs = prec < parent_prec or (right and prec == parent_prec)
        return f"({text})" if needs else text
    raise AssertionError(f"unexpected syntax in a generated straight-line function: {ast.dump(node)}")


class _MagnitudeTransformer(ast.NodeTransformer):
    """``x - y`` becomes ``x + y`` and ``-x`` becomes ``x``; everything else stays."""

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        if isinstance(node.op, ast.Sub):
            node.op = ast.Add()
        return node

    def visit_UnaryOp(self, node: ast.UnaryOp) -> ast.AST:
        self.generic_visit(node)
        if isinstance(node.op, ast.USub):
            return node.operand
        return node

    def visit_Constant(self, node: ast.Constant) -> ast.AST:
        if isinstance(node.value, int) and not isinstance(node.value, bool):
            return ast.Constant(abs(node.value))
        return node


def _functions(text: str) -> dict[str, ast.FunctionDef]:
    return {n.name: n for n in ast.parse(text).body if isinstance(n, ast.FunctionDef)}


def _straight_line(fdef: ast.FunctionDef) -> tuple[list[str], list[tuple[str, ast.expr]], list[str]]:
    """(arguments, assignments, returned names) of a generated straight-line function."""
    args = [a.arg for a in fdef.args.args]
    assignments: list[tuple[str, ast.expr]] = []
    returned: list[str] = []
    for stmt in fdef.body:
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant):
            continue  # docstring
        if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
            assignments.append((stmt.targets[0].id, stmt.value))
        elif isinstance(stmt, ast.Return) and stmt.value is not None:
            value = stmt.value
            if isinstance(value, ast.Tuple) and all(isinstance(e, ast.Name) for e in value.elts):
                returned = [e.id for e in value.elts]  # type: ignore[attr-defined]
            else:
                assignments.append(("__result__", value))
                returned = ["__result__"]
        else:
            raise AssertionError(f"unexpected statement in {fdef.name}: {ast.dump(stmt)}")
    return args, assignments, returned


def emit_magnitude_function(fdef: ast.FunctionDef) -> list[str]:
    """The magnitude companion of a generated straight-line function (see the module docstring)."""
    import copy

    args, assignments, returned = _straight_line(fdef)
    out = [
        f"def {fdef.name}_magnitude({', '.join(args)}):",
        f'    """Magnitude companion of ``{fdef.name}``: call it with the absolute values of the',
        '    arguments; same operations in the same order, with every minus turned into a plus."""',
    ]
    for target, expr in assignments:
        mag = _MagnitudeTransformer().visit(copy.deepcopy(expr))
        name = "result" if target == "__result__" else target
        out.append(f"    {name} = {_print_expr(mag)}")
    names = ["result" if r == "__result__" else r for r in returned]
    if len(names) == 1 and returned == ["__result__"]:
        out.append("    return result")
    else:
        out.append(f"    return ({', '.join(names)}{',' if len(names) == 1 else ''})")
    return out


EXACT_INTEGER_MAX = 2**53
"""Integers up to this magnitude are binary64 numbers; a larger literal may be rounded."""


def rounding_counts(fdef: ast.FunctionDef, input_roundings: int = 0) -> list[tuple[int, int]]:
    """``(N, degree)`` for every output of a generated straight-line function.

    ``N`` is the largest number of rounded operations met on a path from the
    inputs to the output, counting ``input_roundings`` for each input (1 when
    the inputs are themselves rounded values of exact numbers) and one for an
    integer constant beyond :data:`EXACT_INTEGER_MAX` (binary64 may round it): a
    sum or difference counts ``max(N_left, N_right) + 1``, a product
    ``N_left + N_right + 1`` (every product of the expanded polynomial picks up
    the rounding factors of both operands), a negation nothing.  The degree is
    the total degree of the output as a polynomial in the inputs.
    """
    args, assignments, returned = _straight_line(fdef)
    env: dict[str, tuple[int, int]] = {a: (input_roundings, 1) for a in args}

    def walk(node: ast.expr) -> tuple[int, int]:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant):
            big = isinstance(node.value, int) and abs(node.value) > EXACT_INTEGER_MAX
            return (1 if big else 0, 0)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return walk(node.operand)
        if isinstance(node, ast.BinOp):
            (nl, dl), (nr, dr) = walk(node.left), walk(node.right)
            if isinstance(node.op, ast.Mult):
                return (nl + nr + 1, dl + dr)
            if isinstance(node.op, (ast.Add, ast.Sub)):
                return (max(nl, nr) + 1, max(dl, dr))
        raise AssertionError(f"unexpected syntax: {ast.dump(node)}")

    for target, expr in assignments:
        env[target] = walk(expr)
    return [env[r] for r in returned]


# -- programs for any polynomial (parametric families) ------------------------------------
#
# The families of :mod:`quadric_contact.family` need the same kind of code for polynomials
# known only at run time (the coefficients of P, the Deltas, ... as polynomials in the
# family's parameters): a straight-line function in the grammar above, with its magnitude
# companion and its rounding counts, so that the float filter's error bounds
# (:mod:`quadric_contact.modes.errorbounds`) apply to it unchanged.  Each polynomial is put
# in nested Horner form (one variable after the other) and the subexpressions the outputs
# share are computed once (sympy's ``cse``).


def horner_form(terms: dict[tuple[int, ...], int], symbols: Sequence[sp.Symbol]) -> sp.Expr:
    """The polynomial ``sum c * prod symbols**e`` in nested Horner form.

    Horner's rule in the first symbol, whose coefficients are polynomials in the
    others, each in Horner form in turn; a gap in the exponents becomes a power
    (printed as a product).

    Examples
    --------
    >>> u, w = sp.symbols("u w")
    >>> horner_form({(2, 0): 3, (1, 1): -2, (0, 0): 5}, (u, w))
    u*(3*u - 2*w) + 5
    """
    if not terms:
        return sp.Integer(0)
    if not symbols:
        return sp.Integer(sum(terms.values()))
    x, rest = symbols[0], symbols[1:]
    groups: dict[int, dict[tuple[int, ...], int]] = {}
    for mono, c in terms.items():
        if c:
            groups.setdefault(mono[0], {})[mono[1:]] = c
    if not groups:
        return sp.Integer(0)
    exponents = sorted(groups, reverse=True)
    acc = horner_form(groups[exponents[0]], rest)
    for prev, nxt in itertools.pairwise(exponents):
        acc = acc * x ** (prev - nxt) + horner_form(groups[nxt], rest)
    return acc * x ** exponents[-1]


def _python_code(expr: sp.Expr) -> str:
    """Python text of an integer polynomial expression over ``+ - *`` (powers become products)."""
    if expr.is_Symbol:
        return str(expr)
    if expr.is_Integer:
        return str(int(expr))
    if expr.is_Add:
        terms = expr.as_ordered_terms()
        terms = [t for t in terms if t.as_coeff_Mul()[0] > 0] + [t for t in terms if t.as_coeff_Mul()[0] < 0]
        out = ""
        for term in terms:
            if out and term.as_coeff_Mul()[0] < 0:
                out += " - " + _python_code(-term)
            else:
                out += (" + " if out else "") + _python_code(term)
        return f"({out})"
    if expr.is_Mul:
        c, rest = expr.as_coeff_Mul()
        if c < 0:
            return f"(-{_python_code(-expr)})"
        return "(" + "*".join(_python_code(f) for f in expr.as_ordered_factors()) + ")"
    if expr.is_Pow and expr.exp.is_Integer and int(expr.exp) >= 1:
        return "(" + "*".join([_python_code(expr.base)] * int(expr.exp)) + ")"
    raise AssertionError(f"not an integer polynomial over + - *: {expr}")


@dataclass(frozen=True)
class Program:
    """A straight-line program for polynomials with integer coefficients, and what the
    float filter needs to bound its rounding errors.

    Attributes
    ----------
    name : str
        The function's name; the magnitude companion is ``{name}_magnitude``.
    args, outputs : tuple of str
        Argument and output names.
    source : str
        The text of both functions (value and magnitude companion), in the grammar of
        the generated modules: assignments over ``+ - *`` with integer literals.
    degree, value_counts, magnitude_counts : tuple of int
        Per output: total degree, rounding counts of the value program (exact
        inputs) and of the magnitude companion (see :func:`rounding_counts`).
    path_bound : int
        The largest value any assignment of the magnitude companion takes at all
        ones (exact): with non-zero inputs at most ``X >= 1`` in magnitude, every
        intermediate of either program is at most ``path_bound * X**max(degree)``
        before rounding.
    operations : int
        Binary operations in the value program.
    """

    name: str
    args: tuple[str, ...]
    outputs: tuple[str, ...]
    source: str
    degree: tuple[int, ...]
    value_counts: tuple[int, ...]
    magnitude_counts: tuple[int, ...]
    path_bound: int
    operations: int


def _interpret(fdef: ast.FunctionDef, values: Sequence[Any]) -> tuple[dict[str, Any], list[Any]]:
    """Run a straight-line function of the grammar above on ``values`` without compiling
    it: every assignment, and the outputs."""
    args, assignments, returned = _straight_line(fdef)
    env: dict[str, Any] = dict(zip(args, values, strict=True))

    def walk(node: ast.expr) -> Any:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -walk(node.operand)
        if isinstance(node, ast.BinOp):
            left, right = walk(node.left), walk(node.right)
            if isinstance(node.op, ast.Mult):
                return left * right
            if isinstance(node.op, ast.Add):
                return left + right
            if isinstance(node.op, ast.Sub):
                return left - right
        raise AssertionError(f"unexpected syntax: {ast.dump(node)}")

    for target, expr in assignments:
        env[target] = walk(expr)
    return env, [env[r] for r in returned]


def emit_program(
    name: str,
    args: Sequence[str],
    outputs: Sequence[tuple[str, dict[tuple[int, ...], int]]],
    doc: str = "Generated by quadric_contact.codegen.emit_program.",
) -> Program:
    """Straight-line code (nested Horner form, shared subexpressions) for polynomials with
    integer coefficients, with its magnitude companion and rounding counts.

    Parameters
    ----------
    name : str
        Name of the emitted function.
    args : sequence of str
        Argument names (identifiers chosen by the caller, never user text).
    outputs : sequence of (str, dict)
        Output name and polynomial: exponent tuple over ``args`` to integer coefficient.
    doc : str
        The docstring.

    Returns
    -------
    Program

    Examples
    --------
    >>> p = emit_program("f", ("p0", "p1"), [("a", {(2, 0): 1, (0, 1): -3}), ("b", {(2, 0): 2})])
    >>> for line in p.source.splitlines()[2:6]:
    ...     print(line)
        t0 = p0*p0
        a = t0 - 3*p1
        b = 2*t0
        return (a, b)
    >>> p.degree, p.value_counts, p.magnitude_counts
    ((2, 2), (2, 2), (2, 2))
    """
    symbols = [sp.Symbol(a) for a in args]
    taken = set(args) | {o for o, _ in outputs}
    temps = (sp.Symbol(f"t{i}") for i in itertools.count() if f"t{i}" not in taken)
    forms = [horner_form(poly, symbols) for _, poly in outputs]
    replacements, reduced = sp.cse(forms, symbols=temps, optimizations=None)
    lines = [f"def {name}({', '.join(args)}):", f'    """{doc}"""']
    for target, expr in [*replacements, *zip((sp.Symbol(o) for o, _ in outputs), reduced, strict=True)]:
        node = ast.parse(_python_code(expr), mode="eval").body
        lines.append(f"    {target} = {_print_expr(node)}")
    names = [o for o, _ in outputs]
    lines.append(f"    return ({', '.join(names)}{',' if len(names) == 1 else ''})")
    fdef = _functions("\n".join(lines))[name]
    magnitude = emit_magnitude_function(fdef)
    mag_def = _functions("\n".join(magnitude))[f"{name}_magnitude"]
    value_counts = rounding_counts(fdef, 0)
    mag_counts = rounding_counts(mag_def, 0)
    env, _ = _interpret(mag_def, [1] * len(args))
    operations = sum(isinstance(n, ast.BinOp) for n in ast.walk(fdef))
    return Program(
        name=name,
        args=tuple(args),
        outputs=tuple(names),
        source="\n".join([*lines, "", "", *magnitude, ""]),
        degree=tuple(d for _, d in value_counts),
        value_counts=tuple(n for n, _ in value_counts),
        magnitude_counts=tuple(n for n, _ in mag_counts),
        path_bound=max(abs(int(v)) for v in env.values()),
        operations=operations,
    )


#: Functions whose rounding counts and magnitude companions are emitted:
#: (module, function name, names of the outputs).
FILTERED_FUNCTIONS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("formulas", "pencil_coefficients", ("c0", "c1", "c2", "c3", "c4")),
    ("formulas", "paper_deltas", ("Delta2", "Delta3", "Delta4")),
    ("kernels", "leading_minors_3", ("m2", "m3")),
    ("kernels", "quadric_invariants", ("trA", "JA", "detA", "E1", "E2", "E3", "E4")),
)


def _kernel_value_functions() -> list[str]:
    args, minors = derive_leading_minors_3()
    out = _emit_function(
        "leading_minors_3",
        args,
        minors,
        "(m2, m3): leading principal minors of orders 2 and 3 of the symmetric 3x3 matrix\n"
        "    with upper entries aij (Sylvester's criterion; order 1 is a00 itself).",
    )
    out += ["", ""]
    cargs, compact = derive_compact_deltas()
    out += [
        *_emit_function(
            "paper_deltas_compact",
            cargs,
            compact,
            "Delta_2, Delta_3 and 27 Delta_4 (same signs as paper_deltas) in about 60 operations,\n"
            "    for exact arithmetic; 27 Delta_4 = 4 I^3 - J^2 with the invariants I, J of the quartic.",
        )[:-1],
        "    return (Delta2, Delta3, Delta4_27)",
    ]
    out += ["", ""]
    args, invariants = derive_quadric_invariants()
    out += _emit_function(
        "quadric_invariants",
        args,
        invariants,
        "(trA, JA, detA, E1, E2, E3, E4) of the symmetric Q with upper entries qij: trace, sum of\n"
        "    principal 2x2 minors and determinant of the quadratic part, and the sums of the principal\n"
        "    minors of each order of Q.",
    )
    return out


def _format_counts(counts: dict[str, dict[str, tuple[Any, ...]]]) -> list[str]:
    lines = ["ROUNDING_COUNTS = {"]
    for fname, entry in counts.items():
        lines.append(f"    {fname!r}: {{")
        for key, value in entry.items():
            lines.append(f"        {key!r}: {value!r},")
        lines.append("    },")
    lines.append("}")
    return lines


def emit_kernels(formulas_text: str | None = None) -> str:
    """The full text of ``_generated/kernels.py``."""
    if formulas_text is None:
        formulas_text = emit_formulas()
    value_lines = _kernel_value_functions()
    sources = {"formulas": _functions(formulas_text), "kernels": _functions("\n".join(value_lines))}
    out: list[str] = [
        '"""Companions of the closed forms for the number modes, generated by ``quadric_contact.codegen``.',
        "",
        "Do not edit: regenerate with ``python -m quadric_contact.codegen``.  Two more",
        "straight-line functions (the leading minors of a quadratic part and the invariants",
        "that fix the affine type of a quadric), the magnitude companion of every filtered",
        "function (same operations, minus turned into plus, to be called with absolute",
        "values), and ROUNDING_COUNTS: for every output, the largest number of rounded",
        "operations on a path from the inputs (exact inputs, rounded inputs, and for the",
        "magnitude companion) and its degree.  Like ``formulas``, everything runs on any",
        "number type and compiles with numba unchanged.",
        '"""',
        "",
        "# ruff: noqa",
        "",
        *value_lines,
        "",
        "",
    ]
    counts: dict[str, dict[str, tuple[Any, ...]]] = {}
    for module, fname, outputs in FILTERED_FUNCTIONS:
        fdef = sources[module][fname]
        mag_lines = emit_magnitude_function(fdef)
        out += [*mag_lines, "", ""]
        mag_def = _functions("\n".join(mag_lines))[f"{fname}_magnitude"]
        exact = rounding_counts(fdef, 0)
        rounded = rounding_counts(fdef, 1)
        mag = rounding_counts(mag_def, 0)
        if [d for _, d in exact] != [d for _, d in mag]:
            raise AssertionError(f"magnitude companion of {fname} has other degrees")
        counts[fname] = {
            "module": (module,),
            "outputs": outputs,
            "degree": tuple(d for _, d in exact),
            "value": tuple(n for n, _ in exact),
            "value_rounded_inputs": tuple(n for n, _ in rounded),
            "magnitude": tuple(n for n, _ in mag),
        }
    out += _format_counts(counts)
    out.append("")
    return "\n".join(out)


def regenerate_kernels(path: Path = KERNELS_PATH, check: bool = False) -> bool:
    """Write (or with ``check=True`` only compare) ``_generated/kernels.py``."""
    verify_invariants()
    verify_compact_deltas()
    text = emit_kernels()
    current = path.read_text() if path.exists() else None
    if check:
        return current == text
    path.write_text(text)
    return current == text


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


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="quadric-contact codegen", description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="only check that the file is current")
    args = parser.parse_args(argv)
    status = 0
    for path, fn in ((GENERATED_PATH, regenerate), (KERNELS_PATH, regenerate_kernels)):
        same = fn(check=args.check)
        if args.check:
            print(f"{path.name}: " + ("current" if same else "OUT OF DATE"))
            status |= 0 if same else 1
        else:
            print(f"wrote {path} ({'unchanged' if same else 'changed'})")
    return status


if __name__ == "__main__":
    sys.exit(main())
