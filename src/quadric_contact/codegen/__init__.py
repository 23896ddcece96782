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
    degree.  :mod:`quadric_contact.modes.kernels.errorbounds` turns them into the
    error-bound constants.

Double-double programs (``_generated/dd_programs.py``)
-------------------------------------------------------
``quadric_invariants_dd``
    ``quadric_invariants`` evaluated in double-double arithmetic (the operations of
    :mod:`quadric_contact.modes.kernels.double_double`, passed as arguments): the same monomials,
    products by Dekker's exact product and DWTimesFP1, sums by AccurateDWPlusDW in balanced
    trees.  Checked by reading it exactly (it computes the invariants) and along its paths
    (its magnitude is the binary64 magnitude companion's); ``DD_COUNTS`` gives the rounding
    double-double operations on its paths, from which
    :data:`quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND` is derived.

The reading of straight-line code (printer, magnitude companion, rounding counts)
is :mod:`quadric_contact.exact.straight_line` and the emitter of programs for polynomials
known at run time is :mod:`quadric_contact.families.family_emit`: run-time code uses them
without importing this module, which is development time only.

Regenerate with ``python -m quadric_contact.codegen`` (or
``quadric-contact codegen``); the test suite checks that regenerating
reproduces every committed file byte for byte.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import sympy as sp

from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.straight_line import (
    _functions,
    _interpret,
    emit_magnitude_function,
    emit_value_and_magnitude_function,
    rounding_counts,
)

GENERATED_PATH = Path(__file__).parents[1] / "_generated" / "formulas.py"
KERNELS_PATH = Path(__file__).parents[1] / "_generated" / "kernels.py"


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
    (Sylvester's criterion; the order-1 minor is the entry ``a00`` itself), as a program with
    three intermediates: the 2x2 minors ``t01, t02, t12`` of the first two rows (columns
    ``01, 02, 12``), which are the pencil's ``Et01, Et02, Et12`` with the same expressions (so a
    compiler computes them once for both), ``m2 = t01`` and ``m3`` by Laplace along the third
    row, ``a22 t01 - a12 t02 + a02 t12``: three products instead of the ten of the expanded
    determinant.  Use :func:`leading_minors_expanded` for the polynomials."""
    syms = {ij: sp.Symbol(f"a{ij[0]}{ij[1]}") for ij in QUADRATIC_PART_INDICES}
    a = lambda i, j: syms[(min(i, j), max(i, j))]  # noqa: E731
    args = [syms[ij] for ij in QUADRATIC_PART_INDICES]
    t01, t02, t12 = sp.symbols("t01 t02 t12")
    return args, [
        ("t01", a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0)),
        ("t02", a(0, 0) * a(1, 2) - a(0, 1) * a(0, 2)),
        ("t12", a(0, 1) * a(1, 2) - a(0, 2) * a(1, 1)),
        ("m2", t01),
        ("m3", a(2, 2) * t01 - a(1, 2) * t02 + a(0, 2) * t12),
    ]


def derive_leading_minors_4() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """The leading principal minors ``d1 .. d4`` of a symmetric 4x4 matrix ``m`` (Sylvester's
    criterion, which decides whether a member ``s E + Q`` of the pencil is definite), as a
    program: the six 2x2 minors of the first two rows (``u01 .. u23``, columns ``jk``), ``d3`` by
    Laplace along the third row from three of them, the six 2x2 minors of the last two rows
    (``v01 .. v23``) and ``d4`` by Laplace's expansion along the first two rows."""
    m, args = symmetric_matrix("m")
    u = {(j, k): sp.Symbol(f"u{j}{k}") for j in range(4) for k in range(j + 1, 4)}
    v = {(j, k): sp.Symbol(f"v{j}{k}") for j in range(4) for k in range(j + 1, 4)}
    program: list[tuple[str, sp.Expr]] = []
    for (j, k), name in u.items():
        program.append((str(name), m[0, j] * m[1, k] - m[0, k] * m[1, j]))
    program.append(("d1", m[0, 0]))
    program.append(("d2", u[(0, 1)]))
    program.append(("d3", m[2, 2] * u[(0, 1)] - m[2, 1] * u[(0, 2)] + m[2, 0] * u[(1, 2)]))
    for (j, k), name in v.items():
        program.append((str(name), m[2, j] * m[3, k] - m[2, k] * m[3, j]))
    # Laplace along rows 0, 1: sum over column pairs (j, k) of sign * u_jk * v_(complement)
    d4 = (
        u[(0, 1)] * v[(2, 3)] - u[(0, 2)] * v[(1, 3)] + u[(0, 3)] * v[(1, 2)]
        + u[(1, 2)] * v[(0, 3)] - u[(1, 3)] * v[(0, 2)] + u[(2, 3)] * v[(0, 1)]
    )  # fmt: skip
    program.append(("d4", d4))
    return args, program


def verify_leading_minors_4() -> None:
    """Raise AssertionError unless ``d1 .. d4`` are sympy's determinants of the leading blocks."""
    m, args = symmetric_matrix("m")
    _, program = derive_leading_minors_4()
    env: dict[sp.Symbol, sp.Expr] = {}
    for name, expr in program:
        env[sp.Symbol(name)] = sp.expand(expr.xreplace(env))
    for k in range(1, 5):
        if sp.expand(env[sp.Symbol(f"d{k}")] - m[:k, :k].det(method="berkowitz")) != 0:
            raise AssertionError(f"d{k} differs from the determinant of the leading {k}x{k} block")


def leading_minors_expanded() -> dict[str, sp.Expr]:
    """``m2``, ``m3`` of :func:`derive_leading_minors_3` as polynomials in the entries."""
    _, program = derive_leading_minors_3()
    env: dict[sp.Symbol, sp.Expr] = {}
    for name, expr in program:
        env[sp.Symbol(name)] = sp.expand(expr.xreplace(env))
    return {name: env[sp.Symbol(name)] for name in ("m2", "m3")}


def derive_quadric_invariants() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """The invariants that fix the affine type of ``Q`` (see
    :mod:`quadric_contact.model.classification`): trace, ``J`` and determinant of the
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
    minors = leading_minors_expanded()
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{min(i, j)}{max(i, j)}"))
    if sp.expand(minors["m3"] - A.det()) != 0 or sp.expand(minors["m2"] - A[:2, :2].det()) != 0:
        raise AssertionError("leading minors differ from sympy's determinants")


def derive_compact_deltas() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """A short straight-line program with the signs of ``(Delta_2, Delta_3, Delta_4)``
    (about 60 operations instead of 160): ``Delta_3`` grouped by ``c3`` and ``c4``, and
    ``27 Delta_4 = 4 I^3 - J^2`` with the invariants ``I, J`` of the quartic (the discriminant
    identity), the products of two coefficients computed once (``s_k = c_k^2``, ``p_jk = c_j
    c_k``; ``I = 12 c0 c4 + u``, ``J = c2 h - 27 g + 9 c3 p12``): 32 products, 41 with the
    magnitude program sharing them
    (:func:`~quadric_contact.exact.straight_line.emit_value_and_magnitude_function`), against
    48.  Checked against :func:`derive_paper_deltas` by :func:`verify_compact_deltas`.  In floating point
    ``4 I^3 - J^2`` cancels far more than the expanded form, so its rounding bound is weaker:
    the screen uses it with that bound (``errorbounds.SEMI_DELTA``), the filter the expanded
    form."""
    c0, c1, c2, c3, c4 = coefficient_symbols(4)
    names = "p13 s2 s3 s1 p12 p24 p34 s4 u I v w h g J"
    p13, s2, s3, s1, p12, p24, p34, s4, u, I, v, w, h, g, J = sp.symbols(names)  # noqa: E741
    program = [
        ("p13", c1 * c3),
        ("s2", c2 * c2),
        ("s3", c3 * c3),
        ("s1", c1 * c1),
        ("p12", c1 * c2),
        ("p24", c2 * c4),
        ("p34", c3 * c4),
        ("s4", c4 * c4),
        ("u", s2 - 3 * p13),
        ("I", 12 * c0 * c4 + u),
        ("v", 8 * c0 * c2 - 9 * s1),
        ("w", 7 * p12 - 3 * c0 * c3),
        ("h", 72 * c0 * c4 - 2 * s2),
        ("g", c0 * s3 + s1 * c4),
        ("J", c2 * h - 27 * g + 9 * c3 * p12),
        ("Delta2", 3 * s3 - 8 * p24),
        ("Delta3", s3 * u + 2 * s4 * v + 2 * p34 * w - 4 * s2 * p24),
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
    name: str,
    args: Sequence[sp.Symbol],
    outputs: Sequence[tuple[str, sp.Expr]],
    doc: str,
    returned: Sequence[str] | None = None,
) -> list[str]:
    """A straight-line function: one assignment per ``outputs`` entry, returning ``returned``
    (by default every assigned name)."""
    lines = [f"def {name}({', '.join(str(a) for a in args)}):", f'    """{doc}"""']
    for out_name, expr in outputs:
        lines.append(f"    {out_name} = {_emit_expression(expr)}")
    names = list(returned) if returned is not None else [n for n, _ in outputs]
    lines.append(f"    return ({', '.join(names)}{',' if len(names) == 1 else ''})")
    return lines


#: Functions whose rounding counts and magnitude companions are emitted:
#: (module, function name, names of the outputs).
FILTERED_FUNCTIONS: tuple[tuple[str, str, tuple[str, ...]], ...] = (
    ("formulas", "pencil_coefficients", ("c0", "c1", "c2", "c3", "c4")),
    ("formulas", "paper_deltas", ("Delta2", "Delta3", "Delta4")),
    ("kernels", "leading_minors_3", ("m2", "m3")),
    ("kernels", "quadric_invariants", ("trA", "JA", "detA", "E1", "E2", "E3", "E4")),
    ("kernels", "leading_minors_4", ("d1", "d2", "d3", "d4")),
)


def _kernel_value_functions() -> list[str]:
    args, minors = derive_leading_minors_3()
    out = _emit_function(
        "leading_minors_3",
        args,
        minors,
        "(m2, m3): leading principal minors of orders 2 and 3 of the symmetric 3x3 matrix\n"
        "    with upper entries aij (Sylvester's criterion; order 1 is a00 itself); m3 by Laplace\n"
        "    along the third row from the 2x2 minors of the first two, the pencil's Et01, Et02, Et12.",
        returned=("m2", "m3"),
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
    out += ["", ""]
    args, minors4 = derive_leading_minors_4()
    out += _emit_function(
        "leading_minors_4",
        args,
        minors4,
        "(d1, d2, d3, d4): leading principal minors of the symmetric 4x4 matrix with upper entries\n"
        "    mij (Sylvester's criterion: is a member of the pencil definite?); d3 by Laplace along the\n"
        "    third row, d4 by Laplace along the first two rows, from the 2x2 minors of both row pairs.",
        returned=("d1", "d2", "d3", "d4"),
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
    verify_leading_minors_4()
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


# -- the unrolled block code of the binary64 kernels (``_generated/blocks.py``) ---------------

BLOCKS_PATH = Path(__file__).parents[1] / "_generated" / "blocks.py"

FLAT_UPPER: tuple[int, ...] = tuple(4 * i + j for i, j in ENTRY_INDICES)
"""Positions of the ten upper entries in a row-major 4x4 matrix (16 values)."""
FLAT_LOWER: tuple[tuple[int, int], ...] = tuple((4 * i + j, 4 * j + i) for i, j in ENTRY_INDICES if i != j)
"""``(upper, mirror)`` positions of the six off-diagonal pairs of a row-major 4x4 matrix."""

ROW_SYMBOLS = sp.symbols("R0:4"), sp.symbols("T0:4")


def _upper_names(prefix: str) -> list[str]:
    return [f"{prefix}{i}{j}" for i, j in ENTRY_INDICES]


def derive_row_bound() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """A straight-line program for the coefficients ``W_0 .. W_4`` of
    ``prod_r (R_r lambda + T_r)`` (``r = 0 .. 3``): with ``R_r``, ``T_r`` the largest
    ``|entry|`` of row ``r`` of ``E`` and of ``Q``, ``24 W_k`` bounds the magnitude program of
    ``c_k`` (:func:`verify_row_bound`).  Rows 0, 1 and rows 2, 3 are multiplied out first, as
    the Laplace expansion of :func:`derive_pencil` groups them."""
    R, T = ROW_SYMBOLS
    lam = sp.Symbol("lambda")
    top = sp.Poly(sp.expand((R[0] * lam + T[0]) * (R[1] * lam + T[1])), lam)
    bot = sp.Poly(sp.expand((R[2] * lam + T[2]) * (R[3] * lam + T[3])), lam)
    program: list[tuple[str, sp.Expr]] = []
    for name, poly in (("a", top), ("b", bot)):
        for k in range(3):
            program.append((f"{name}{k}", poly.coeff_monomial(lam**k)))
    a = [sp.Symbol(f"a{k}") for k in range(3)]
    b = [sp.Symbol(f"b{k}") for k in range(3)]
    for k in range(5):
        program.append((f"W{k}", sum((a[i] * b[k - i] for i in range(3) if 0 <= k - i <= 2), sp.Integer(0))))
    return [*R, *T], program


def _general_pencil_magnitude() -> tuple[list[sp.Expr], list[list[sp.Symbol]], list[list[sp.Symbol]]]:
    """The magnitude polynomials of ``c_0 .. c_4`` for *general* 4x4 matrices ``X``, ``Y``
    (``det(lambda X + Y)``: one term per permutation and per choice of the rows taken from
    ``X``, no two alike), as polynomials in the absolute values of the entries."""
    from itertools import combinations, permutations

    X = [[sp.Symbol(f"X{r}{s}") for s in range(4)] for r in range(4)]
    Y = [[sp.Symbol(f"Y{r}{s}") for s in range(4)] for r in range(4)]
    out = [sp.Integer(0)] * 5
    for sigma in permutations(range(4)):
        for k in range(5):
            for rows in combinations(range(4), k):
                term = sp.Integer(1)
                for r in range(4):
                    term *= X[r][sigma[r]] if r in rows else Y[r][sigma[r]]
                out[k] += term
    return out, X, Y


def verify_row_bound() -> None:
    """Raise AssertionError unless ``24 W_k(R, T)`` bounds the magnitude program of ``c_k``.

    Three exact checks: (1) the program of :func:`derive_row_bound` computes the coefficients
    of ``prod (R_r lambda + T_r)``; (2) the magnitude polynomial of ``c_k`` for general
    matrices, with every entry of row ``r`` replaced by ``R_r`` (``X``) or ``T_r`` (``Y``), is
    ``24 W_k`` (24 permutations, each with one entry per row); (3) the magnitude program of the
    generated symmetric ``pencil_coefficients``, expanded, is at most the general one at the
    symmetric point (``X_rs = X_sr = e_ij``), coefficient by coefficient.  With ``R_r`` the
    largest ``|e_rs|`` over ``s`` (the matrix being symmetric, over its row and its column),
    the magnitude polynomials having non-negative coefficients, ``M_k <= 24 W_k``."""
    args, program = derive_row_bound()
    R, T = ROW_SYMBOLS
    lam = sp.Symbol("lambda")
    env: dict[sp.Symbol, sp.Expr] = {}
    for name, expr in program:
        env[sp.Symbol(name)] = sp.expand(expr.xreplace(env))
    full = sp.Poly(sp.expand(sp.prod([R[r] * lam + T[r] for r in range(4)])), lam)
    for k in range(5):
        if sp.expand(env[sp.Symbol(f"W{k}")] - full.coeff_monomial(lam**k)) != 0:
            raise AssertionError(f"W{k} is not a coefficient of prod (R lambda + T)")
    general, X, Y = _general_pencil_magnitude()
    rows = {X[r][s]: R[r] for r in range(4) for s in range(4)}
    rows.update({Y[r][s]: T[r] for r in range(4) for s in range(4)})
    for k in range(5):
        if sp.expand(general[k].xreplace(rows) - 24 * env[sp.Symbol(f"W{k}")]) != 0:
            raise AssertionError(f"the general magnitude of c{k} is not 24 W{k}")
    E, es = symmetric_matrix("e")
    Q, qs = symmetric_matrix("q")
    sym = {X[r][s]: E[r, s] for r in range(4) for s in range(4)}
    sym.update({Y[r][s]: Q[r, s] for r in range(4) for s in range(4)})
    mag_text = "\n".join(emit_magnitude_function(_functions(emit_formulas())["pencil_coefficients"]))
    _, magnitude = _interpret(_functions(mag_text)["pencil_coefficients_magnitude"], [*es, *qs])
    for k in range(5):
        gap = sp.Poly(sp.expand(general[k].xreplace(sym) - magnitude[k]), *es, *qs)
        if any(c < 0 for c in gap.coeffs()):
            raise AssertionError(f"the magnitude program of c{k} exceeds the general magnitude")


def verify_minor_row_bounds() -> None:
    """Raise AssertionError unless the magnitude programs of the leading minors ``m2``, ``m3``
    of ``kernels.leading_minors_3`` are at most ``2 R0 R1`` and ``6 R0 R1 R2`` (``R_r`` a bound
    of every ``|a_rs|``): the general 2x2 and 3x3 determinants have 2 and 6 products, one
    entry per row, and the symmetric programs' magnitudes are at most the general ones at the
    symmetric point, coefficient by coefficient."""
    from itertools import permutations

    R = ROW_SYMBOLS[0]
    args, minors = derive_leading_minors_3()
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{min(i, j)}{max(i, j)}"))
    text = "\n".join(_emit_function("leading_minors_3", args, minors, "", returned=("m2", "m3")))
    mag_text = "\n".join(emit_magnitude_function(_functions(text)["leading_minors_3"]))
    _, magnitude = _interpret(_functions(mag_text)["leading_minors_3_magnitude"], list(args))
    for size, mag in ((2, magnitude[0]), (3, magnitude[1])):
        general = sp.Integer(0)
        rows = sp.Integer(0)
        for sigma in permutations(range(size)):
            general += sp.prod([A[r, sigma[r]] for r in range(size)])
            rows += sp.prod([R[r] for r in range(size)])
        if sp.expand(rows - math.factorial(size) * sp.prod(R[:size])) != 0:
            raise AssertionError("row bound of a minor")
        gap = sp.Poly(sp.expand(general - mag), *args)
        if any(c < 0 for c in gap.coeffs()):
            raise AssertionError(f"the magnitude program of the {size}x{size} minor exceeds the general one")


def verify_member_minor_row_bounds() -> None:
    """Raise AssertionError unless the magnitude program of each leading minor ``d_k`` of the
    generated ``kernels.leading_minors_4`` is at most ``k! R0 .. R_(k-1)`` (``R_r`` a bound of
    every entry of row ``r``): coefficient by coefficient it is at most the general ``k x k``
    determinant's ``k!`` products at the symmetric point, each of which takes one entry per row
    (the semi-static bound :data:`~quadric_contact.modes.kernels.errorbounds.MEMBER_MINORS_SEMI`)."""
    from itertools import permutations

    from quadric_contact._generated import kernels

    A, args = symmetric_matrix("m")
    magnitude = kernels.leading_minors_4_magnitude(*args)
    for size in range(1, 5):
        general = sp.Integer(0)
        for sigma in permutations(range(size)):
            general += sp.prod([A[r, sigma[r]] for r in range(size)])
        if len(list(permutations(range(size)))) != math.factorial(size):
            raise AssertionError("permutation count")
        gap = sp.Poly(sp.expand(general - sp.expand(magnitude[size - 1])), *args)
        if any(c < 0 for c in gap.coeffs()):
            raise AssertionError(f"the magnitude program of d{size} exceeds the general determinant")


def verify_plane_zeros() -> None:
    """Raise AssertionError unless, for ``Q`` with a zero quadratic part (a plane), every
    product that the pencil program adds up into ``c0`` and ``c1`` has a factor (a 2x2 minor)
    that vanishes identically, so that binary64 computes both as exact zeros (a product with
    an exact zero is an exact zero), and unless ``Delta_4`` (both forms) vanishes at
    ``c0 = c1 = 0``."""
    assignments, outputs, args = derive_pencil()
    zero = {sp.Symbol(f"q{i}{j}"): 0 for i, j in ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))}
    vanishing = {sym for sym, expr in assignments if sp.expand(expr.xreplace(zero)) == 0}
    for k in (0, 1):
        for term in sp.Add.make_args(sp.expand(outputs[k])):
            if not (term.free_symbols & vanishing):
                raise AssertionError(f"a product of c{k} has no factor that vanishes for a plane")
    c = coefficient_symbols(4)
    at = {c[0]: 0, c[1]: 0}
    _, compact = derive_compact_deltas()
    env: dict[sp.Symbol, sp.Expr] = {}
    for name, expr in compact:
        env[sp.Symbol(name)] = sp.expand(expr.xreplace(env))
    for d4 in (derive_paper_deltas()[2], env[sp.Symbol("Delta4_27")]):
        if sp.expand(d4.xreplace(at)) != 0:
            raise AssertionError("Delta_4 does not vanish at c0 = c1 = 0")


def _pencil_parts(prefix: str) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[tuple[sp.Symbol, sp.Expr]]]:
    """The pencil program split into the temporaries of one matrix (``prefix`` ``"Q"`` or
    ``"E"``) and the rest, in program order."""
    assignments, _, _ = derive_pencil()
    own = [(s, e) for s, e in assignments if str(s).startswith(prefix)]
    rest = [(s, e) for s, e in assignments if not str(s).startswith(prefix)]
    return own, rest


def _emit_pencil_split() -> list[str]:
    """``pencil(e, q)`` and, cut in two for a fixed matrix, ``pencil_q_part(q)`` /
    ``pencil_with_q_part(e, q, qp)`` and ``pencil_e_part(e)`` / ``pencil_with_e_part(e, q, ep)``:
    ``pencil_coefficients`` taking tuples of upper entries (numba cannot pass ``*args`` to an
    inlined function), the products of the fixed matrix computed once; the same expressions in
    the same order, so the values are bit for bit those of ``pencil_coefficients``."""
    assignments, outputs, args = derive_pencil()
    e_names = ", ".join(str(a) for a in args[:10])
    q_names = ", ".join(str(a) for a in args[10:])
    out: list[str] = [
        "def pencil(e, q):",
        '    """``pencil_coefficients`` of the tuples ``e``, ``q`` of upper entries."""',
        f"    {e_names} = e",
        f"    {q_names} = q",
    ]
    for sym, expr in assignments:
        out.append(f"    {sym} = {_emit_expression(expr)}")
    for k in range(5):
        out.append(f"    c{k} = {_emit_expression(outputs[k])}")
    out += ["    return (c0, c1, c2, c3, c4)", "", ""]
    for prefix, fixed, k_fixed, fixed_names in (("Q", "q", 0, q_names), ("E", "e", 4, e_names)):
        own, rest = _pencil_parts(prefix)
        names = ", ".join(str(s) for s, _ in own)
        other = "E" if prefix == "Q" else "Q"
        out += [
            f"def pencil_{fixed}_part({fixed}):",
            f'    """The products of {prefix} alone in ``pencil_coefficients``: its {other}-free 2x2 minors',
            f'    and c{k_fixed} (computed once for a fixed {prefix})."""',
            f"    {fixed_names} = {fixed}",
        ]
        for sym, expr in own:
            out.append(f"    {sym} = {_emit_expression(expr)}")
        out.append(f"    c{k_fixed} = {_emit_expression(outputs[k_fixed])}")
        out += [f"    return ({names}, c{k_fixed})", "", ""]
        out += [
            f"def pencil_with_{fixed}_part(e, q, {fixed}p):",
            f'    """``pencil_coefficients`` with the products of {prefix} alone given (``{fixed}p``, from',
            f'    ``pencil_{fixed}_part``)."""',
            f"    {e_names} = e",
            f"    {q_names} = q",
            f"    {names}, c{k_fixed} = {fixed}p",
        ]
        for sym, expr in rest:
            out.append(f"    {sym} = {_emit_expression(expr)}")
        for k in range(5):
            if k != k_fixed:
                out.append(f"    c{k} = {_emit_expression(outputs[k])}")
        out += ["    return (c0, c1, c2, c3, c4)", "", ""]
    return out


def _emit_gathers() -> list[str]:
    """Block gathers and loads: a block buffer holds row ``k`` (the ``k``-th upper entry) of
    its ``S`` columns at ``k * S``, so that the straight-line loops over a block read
    consecutive addresses and vectorise."""
    names = _upper_names("m")
    lower = dict(FLAT_LOWER)
    out = [
        "def gather_full(M, r, b, t, S):",
        '    """Copy the ten upper entries of ``M[r]`` (a row-major 4x4 matrix, 16 values) into',
        "    column ``t`` of the block buffer ``b``; True where ``M[r]`` is not symmetric (a NaN",
        '    off the diagonal counts as asymmetric)."""',
    ]
    for name, flat in zip(names, FLAT_UPPER, strict=True):
        out.append(f"    {name} = M[r, {flat}]")
    for k, name in enumerate(names):
        out.append(f"    b[{k}*S + t] = {name}" if k else f"    b[t] = {name}")
    checks = " | ".join(f"({names[FLAT_UPPER.index(u)]} != M[r, {m}])" for u, m in sorted(lower.items()))
    out += [f"    return {checks}", "", ""]
    out += [
        "def gather_packed(M, r, b, t, S):",
        '    """Copy the packed matrix ``M[r]`` (its ten upper entries) into column ``t`` of ``b``."""',
    ]
    for k in range(10):
        out.append(f"    b[{k}*S + t] = M[r, {k}]" if k else f"    b[t] = M[r, {k}]")
    out += ["", ""]
    out += [
        "def load_upper(b, i, S):",
        '    """The ten upper entries in column ``i`` of the block buffer ``b``."""',
        "    return (" + ", ".join(f"b[{k}*S + i]" if k else "b[i]" for k in range(10)) + ")",
        "",
        "",
        "def upper_full(M, r):",
        '    """The ten upper entries of ``M[r]``, a row-major 4x4 matrix (16 values)."""',
        "    return (" + ", ".join(f"M[r, {f}]" for f in FLAT_UPPER) + ")",
        "",
        "",
        "def upper_packed(M, r):",
        '    """The ten entries of the packed matrix ``M[r]``."""',
        "    return (" + ", ".join(f"M[r, {k}]" for k in range(10)) + ")",
        "",
        "",
    ]
    return out


def _emit_row_maxima() -> list[str]:
    names = _upper_names("a")
    out = [
        "def row_maxima(a):",
        '    """(R0, R1, R2, R3): the largest absolute entry of each row of a symmetric matrix, from',
        '    the tuple ``a`` of the absolute values of its upper entries."""',
        f"    {', '.join(names)} = a",
    ]
    for r in range(4):
        row = [f"a{min(r, s)}{max(r, s)}" for s in range(4)]
        out.append(f"    R{r} = max(max({row[0]}, {row[1]}), max({row[2]}, {row[3]}))")
    out += ["    return (R0, R1, R2, R3)", "", ""]
    out += [
        "def abs_upper(m):",
        '    """The absolute values of the tuple ``m`` of upper entries."""',
        "    return (" + ", ".join(f"abs(m[{k}])" for k in range(10)) + ")",
        "",
        "",
        "def smallest_nonzero(a, big):",
        '    """The smallest non-zero value of the tuple ``a`` of absolute upper entries (``big`` if',
        '    they are all zero): with the row maxima, the input guard."""',
    ]
    terms = [f"(a[{k}] if a[{k}] != 0.0 else big)" for k in range(10)]
    out.append(f"    low = {terms[0]}")
    for t in terms[1:]:
        out.append(f"    low = min(low, {t})")
    out += ["    return low", "", ""]
    out += [
        "def nonfinite(m):",
        '    """0.0 when every entry of the tuple ``m`` is finite, NaN otherwise (``x * 0`` is NaN for',
        '    an infinity and for NaN).  Branch-free."""',
        "    return " + " + ".join(f"m[{k}]*0.0" for k in range(10)),
        "",
        "",
        "def outside_count(a, low, high):",
        '    """How many of the absolute upper entries ``a`` lie outside ``{0} U [low, high]`` (a NaN',
        '    counts).  Branch-free."""',
    ]
    out.append(
        "    return "
        + " + ".join(f"((not (a[{k}] <= high)) | ((a[{k}] < low) & (a[{k}] != 0.0)))" for k in range(10))
    )
    out += [
        "",
        "",
        "def quadratic_part_zero(a):",
        '    """The quadratic part (entries 00, 01, 02, 11, 12, 22) of the tuple ``a`` of absolute upper',
        '    entries is zero: a plane."""',
        "    return max(max(max(a[0], a[1]), max(a[2], a[4])), max(a[5], a[7])) == 0.0",
        "",
        "",
    ]
    return out


def emit_blocks() -> str:
    """The full text of ``_generated/blocks.py``."""
    rb_args, rb_program = derive_row_bound()
    rb_lines = _emit_function(
        "row_bound",
        rb_args,
        [(n, e) for n, e in rb_program],
        "(W0, .., W4): the coefficients of prod_r (R_r lambda + T_r); 24 W_k bounds the magnitude\n"
        "    program of c_k when R_r, T_r are the row maxima of |E| and |Q| (verify_row_bound).",
    )
    # only the coefficients are returned
    rb_lines[-1] = "    return (W0, W1, W2, W3, W4)"
    compact = _functions(emit_kernels())["paper_deltas_compact"]
    compact_mag = emit_magnitude_function(compact)
    compact_both = emit_value_and_magnitude_function(compact)
    out: list[str] = [
        '"""Unrolled block code of the binary64 kernels, generated by ``quadric_contact.codegen``.',
        "",
        "Do not edit: regenerate with ``python -m quadric_contact.codegen``.  The gathers that",
        "copy matrices into block buffers (one row per upper entry, so that the straight-line",
        "loops over a block vectorise) and check symmetry on the way, the loads, the row maxima",
        "and the row bound of the semi-static filter (``24 W_k`` bounds the magnitude program of",
        "``c_k``, checked by ``verify_row_bound``), ``pencil_coefficients`` cut in two for a fixed",
        "matrix (the same expressions, so the same bits), the magnitude companion of",
        "``paper_deltas_compact`` and both in one program that shares their products (the same",
        "bits as the two), and BLOCK_COUNTS, the rounding counts of the straight-line",
        "functions here (as ``kernels.ROUNDING_COUNTS``).  Compiled by numba into the kernels of",
        ":mod:`quadric_contact.modes`.",
        '"""',
        "",
        "# ruff: noqa",
        "",
        f"FLAT_UPPER = {FLAT_UPPER!r}",
        '"""Positions of the ten upper entries in a row-major 4x4 matrix."""',
        "",
        "",
        *_emit_gathers(),
        *_emit_row_maxima(),
        *rb_lines,
        "",
        "",
        *_emit_pencil_split(),
        *compact_mag,
        "",
        "",
        *compact_both,
        "",
        "",
    ]
    rb_def = _functions("\n".join(rb_lines))["row_bound"]
    mag_def = _functions("\n".join(compact_mag))["paper_deltas_compact_magnitude"]
    counts: dict[str, dict[str, tuple[Any, ...]]] = {
        "row_bound": {
            "outputs": tuple(f"W{k}" for k in range(5)),
            "degree": tuple(d for _, d in rounding_counts(rb_def)),
            "value": tuple(n for n, _ in rounding_counts(rb_def)),
        },
        "paper_deltas_compact": {
            "outputs": ("Delta2", "Delta3", "Delta4_27"),
            "degree": tuple(d for _, d in rounding_counts(compact)),
            "value": tuple(n for n, _ in rounding_counts(compact)),
            "magnitude": tuple(n for n, _ in rounding_counts(mag_def)),
        },
    }
    out += [line.replace("ROUNDING_COUNTS", "BLOCK_COUNTS") for line in _format_counts(counts)]
    out.append("")
    return "\n".join(out)


def regenerate_blocks(path: Path = BLOCKS_PATH, check: bool = False) -> bool:
    """Write (or with ``check=True`` only compare) ``_generated/blocks.py``."""
    verify_row_bound()
    verify_minor_row_bounds()
    verify_member_minor_row_bounds()
    verify_plane_zeros()
    text = emit_blocks()
    current = path.read_text() if path.exists() else None
    if check:
        return current == text
    path.write_text(text)
    return current == text


# -- double-double programs (``_generated/dd_programs.py``) ------------------------------------

DD_PATH = Path(__file__).parents[1] / "_generated" / "dd_programs.py"

DD_OPERATIONS: tuple[str, ...] = ("two_sum", "two_prod", "dd_add", "dd_sub", "dd_mul_d", "dd_scale")
"""The operations a double-double program takes as its first arguments, in order (those of
:data:`quadric_contact.modes.kernels.double_double.OPERATIONS`)."""

COFACTOR_INDICES: tuple[tuple[int, int], ...] = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
"""The six independent cofactors ``C_ij`` (``i <= j``) of the symmetric quadratic part, in order."""

COFACTOR_OUTPUTS: tuple[str, ...] = ("JA", "detA", "E4")
"""The invariants the double-double program forms from the cofactors of the quadratic part."""

_Leaf = tuple[str, bool, int]
"""A term of a double-double sum: ``(name, is an argument, sign)``, standing for ``sign * name``."""


def _dd_sum_tree(items: Sequence[_Leaf], out_name: str, lines: list[str], counter: list[int]) -> _Leaf:
    """Add up ``items`` by a balanced tree, appending one assignment per sum to ``lines``
    (temporaries ``{out_name}_{k}``, ``k`` from ``counter``); the sign of a sum is the sign of
    its first term, a term of the other sign is subtracted."""
    if len(items) == 1:
        return items[0]
    mid = (len(items) + 1) // 2
    at, ap, asg = _dd_sum_tree(items[:mid], out_name, lines, counter)
    bt, bp, bsg = _dd_sum_tree(items[mid:], out_name, lines, counter)
    if ap and bp:
        rhs = f"two_sum({at}, {bt if asg == bsg else '-' + bt})"
    else:
        left = f"({at}, 0.0)" if ap else at
        right = f"({bt}, 0.0)" if bp else bt
        rhs = f"{'dd_add' if asg == bsg else 'dd_sub'}({left}, {right})"
    counter[0] += 1
    target = f"{out_name}_{counter[0]}"
    lines.append(f"    {target} = {rhs}")
    return target, False, asg


def _dd_program_lines(
    name: str,
    args: Sequence[sp.Symbol],
    outputs: Sequence[tuple[str, sp.Expr]],
    doc: str,
    pairs: Sequence[sp.Symbol] = (),
) -> list[str]:
    """A straight-line double-double program for integer polynomials of the binary64 arguments
    ``args`` and, linearly, of the double-double arguments ``pairs``.

    Every output is the sum of the terms of its expanded polynomial (``sp.Poly.terms()``: for
    the invariants, the monomials of the binary64 program, so that the paths of the two
    programs are the same products): a product of two binary64 arguments is Dekker's exact
    ``two_prod``, every further factor one ``dd_mul_d`` (a term's factors in order, the
    double-double one first; the prefixes computed once and shared), an integer coefficient (a
    power of two) an exact ``dd_scale`` (shared too), and the signed terms are added up by a
    balanced tree of ``dd_add`` / ``dd_sub`` (``two_sum``, exact, where both operands are
    arguments), so that a term passes through ``ceil(log2 n)`` of them.  Every value is a pair
    ``(hi, lo)``; an argument enters a sum as ``(x, 0.0)``."""
    names = [str(a) for a in args]
    pair_names = [str(t) for t in pairs]
    signature = ", ".join([*DD_OPERATIONS, *names, *pair_names])
    lines = [f"def {name}({signature}):", f'    """{doc}"""']
    products: dict[tuple[str, ...], str] = {}
    multiples: set[str] = set()

    def short(factor: str) -> str:
        return factor if factor in pair_names else factor.lstrip("abcdefghijklmnopqrstuvwxyz")

    def product(factors: tuple[str, ...]) -> str:
        if len(factors) == 1:
            return factors[0]
        if factors not in products:
            var = "p" + "_".join(short(f) for f in factors)
            if len(factors) == 2 and factors[0] not in pair_names:
                lines.append(f"    {var} = two_prod({factors[0]}, {factors[1]})")
            else:
                lines.append(f"    {var} = dd_mul_d({product(factors[:-1])}, {factors[-1]})")
            products[factors] = var
        return products[factors]

    for out_name, expr in outputs:
        leaves: list[_Leaf] = []
        for powers, coef in sp.Poly(expr, *args, *pairs).terms():
            k = int(coef)
            if k != coef or abs(k) & (abs(k) - 1):
                raise AssertionError(f"coefficient {coef} of {out_name} is not a power of two")
            if sum(powers[len(names) :]) > 1:
                raise AssertionError(f"{out_name} is not linear in the double-double arguments")
            factors = tuple(n for n, p in zip([*names, *pair_names], powers, strict=True) for _ in range(p))
            factors = tuple(sorted(factors, key=lambda f: f not in pair_names))  # stable
            plain = len(factors) == 1 and factors[0] in names
            text = product(factors)
            if abs(k) != 1:
                scaled = f"{text}_x{abs(k)}"
                if scaled not in multiples:
                    operand = f"({text}, 0.0)" if plain else text
                    lines.append(f"    {scaled} = dd_scale({operand}, {float(abs(k))!r})")
                    multiples.add(scaled)
                text, plain = scaled, False
            leaves.append((text, plain, 1 if k > 0 else -1))
        if not leaves:
            raise AssertionError(f"{out_name} is identically zero")
        text, plain, sign = _dd_sum_tree(leaves, out_name, lines, [0])
        if len(leaves) > 1 and sign > 0 and lines[-1].startswith(f"    {text} = "):
            lines[-1] = lines[-1].replace(f"    {text} = ", f"    {out_name} = ", 1)  # the last sum
        else:
            text = f"({text}, 0.0)" if plain else text
            lines.append(f"    {out_name} = {text if sign > 0 else f'dd_scale({text}, -1.0)'}")
    lines.append(f"    return ({', '.join(n for n, _ in outputs)})")
    return lines


def dd_rounding_counts(
    fdef: Any, pairs: dict[str, tuple[int, int, int]] | None = None
) -> dict[str, tuple[int, ...]]:
    """For every returned value of a generated double-double program (an :mod:`ast` function),
    its degree and, over all paths from the inputs, the largest number of ``dd_add`` /
    ``dd_sub`` and of ``dd_mul_d`` operations on one path (each counted apart: a path has at
    most that many of each).  A sum takes the larger count of its operands, a product adds
    them; ``two_sum`` and ``two_prod`` of two binary64 arguments and ``dd_scale`` by a power of
    two round nothing (anything else raises).  ``pairs``: the double-double arguments, with
    their own ``(additions, multiplications, degree)``."""
    import ast

    pairs = dict(pairs or {})
    args = {a.arg for a in fdef.args.args} - set(DD_OPERATIONS) - set(pairs)
    env: dict[str, tuple[int, int, int]] = {a: (0, 0, 1) for a in args}
    env.update(pairs)

    def argument(node: Any) -> bool:
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            node = node.operand
        return isinstance(node, ast.Name) and node.id in args

    def value(node: Any) -> tuple[int, int, int]:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Tuple) and len(node.elts) == 2:
            low = node.elts[1]
            if not (isinstance(low, ast.Constant) and low.value == 0.0) or not argument(node.elts[0]):
                raise AssertionError(f"unexpected pair {ast.unparse(node)}")
            return value(node.elts[0])
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return value(node.operand)
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and len(node.args) == 2):
            raise AssertionError(f"unexpected expression {ast.unparse(node)}")
        op, (x, y) = node.func.id, node.args
        if op in ("two_sum", "two_prod"):
            if not (argument(x) and argument(y)):
                raise AssertionError(f"{op} of a value that is not an argument: {ast.unparse(node)}")
            return (0, 0, 2 if op == "two_prod" else 1)
        if op == "dd_scale":
            s = getattr(y.operand if isinstance(y, ast.UnaryOp) else y, "value", None)
            if not isinstance(s, float) or math.frexp(s)[0] != 0.5:
                raise AssertionError(f"dd_scale by {ast.unparse(y)}, not a power of two")
            return value(x)
        a, b = value(x), value(y)
        if op in ("dd_add", "dd_sub"):
            if a[2] != b[2]:
                raise AssertionError("a sum of terms of different degrees")
            return (max(a[0], b[0]) + 1, max(a[1], b[1]), a[2])
        if op == "dd_mul_d" and argument(y):
            return (a[0] + b[0], a[1] + b[1] + 1, a[2] + b[2])
        raise AssertionError(f"unexpected operation {ast.unparse(node)}")

    returned: list[str] = []
    for stmt in fdef.body:
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant):
            continue
        if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
            env[stmt.targets[0].id] = value(stmt.value)
        elif isinstance(stmt, ast.Return) and isinstance(stmt.value, ast.Tuple):
            returned = [e.id for e in stmt.value.elts]  # type: ignore[attr-defined]
        else:
            raise AssertionError(f"unexpected statement {ast.unparse(stmt)}")
    return {
        "degree": tuple(env[n][2] for n in returned),
        "dd_add": tuple(env[n][0] for n in returned),
        "dd_mul_d": tuple(env[n][1] for n in returned),
    }


class _Paths:
    """A value of a program read symbolically, and its magnitude: the sum over the paths that
    make it of the absolute values of their products (in the absolute values of the inputs)."""

    def __init__(self, value: Any, magnitude: Any) -> None:
        self.value, self.magnitude = value, magnitude

    def __neg__(self) -> _Paths:
        return _Paths(-self.value, self.magnitude)


def _paths(x: Any) -> _Paths:
    """A double-double pair (or one word) as one :class:`_Paths`: its words added."""
    if isinstance(x, tuple):
        hi, lo = _paths(x[0]), _paths(x[1])
        return _Paths(hi.value + lo.value, hi.magnitude + lo.magnitude)
    if isinstance(x, _Paths):
        return x
    r = sp.Rational(x)
    return _Paths(r, abs(r))


def _symbolic_dd_operations() -> tuple[Any, ...]:
    """The operations of :data:`DD_OPERATIONS` read exactly on :class:`_Paths` (a result's low
    word is zero): what a program computes if no operation rounds, and its magnitude."""
    zero = _Paths(sp.Integer(0), sp.Integer(0))

    def add(x: Any, y: Any, sign: int) -> tuple[_Paths, _Paths]:
        a, b = _paths(x), _paths(y)
        return _Paths(a.value + sign * b.value, a.magnitude + b.magnitude), zero

    def mul(x: Any, y: Any) -> tuple[_Paths, _Paths]:
        a, b = _paths(x), _paths(y)
        return _Paths(a.value * b.value, a.magnitude * b.magnitude), zero

    def scale(x: Any, s: float) -> tuple[_Paths, _Paths]:
        a, r = _paths(x), sp.Rational(s)
        return _Paths(r * a.value, abs(r) * a.magnitude), zero

    return (
        lambda a, b: add(a, b, 1),  # two_sum
        mul,  # two_prod
        lambda x, y: add(x, y, 1),  # dd_add
        lambda x, y: add(x, y, -1),  # dd_sub
        mul,  # dd_mul_d
        scale,  # dd_scale
    )


def _run_symbolically(text: str, name: str, inputs: Sequence[Any]) -> list[_Paths]:
    """The program ``name`` of ``text`` run on :class:`_Paths` inputs with the exact operations,
    read from its :mod:`ast` (the grammar of the emitted programs: assignments of calls of the
    operations on names, negated names, ``(name, 0.0)`` pairs and float constants, and a tuple
    return), without compiling it."""
    import ast

    fdef = _functions(text)[name]
    operations = dict(zip(DD_OPERATIONS, _symbolic_dd_operations(), strict=True))
    params = [a.arg for a in fdef.args.args]
    if params[: len(DD_OPERATIONS)] != list(DD_OPERATIONS):
        raise AssertionError(f"{name} does not take the operations first")
    env: dict[str, Any] = dict(zip(params[len(DD_OPERATIONS) :], inputs, strict=True))

    def walk(node: Any) -> Any:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant) and isinstance(node.value, float):
            return node.value
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -walk(node.operand)
        if isinstance(node, ast.Tuple):
            return tuple(walk(e) for e in node.elts)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in operations:
            return operations[node.func.id](*(walk(a) for a in node.args))
        raise AssertionError(f"unexpected syntax in {name}: {ast.unparse(node)}")

    for stmt in fdef.body:
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant):
            continue
        if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
            env[stmt.targets[0].id] = walk(stmt.value)
        elif isinstance(stmt, ast.Return) and isinstance(stmt.value, ast.Tuple):
            return [_paths(walk(e)) for e in stmt.value.elts]
        else:
            raise AssertionError(f"unexpected statement in {name}: {ast.unparse(stmt)}")
    raise AssertionError(f"{name} returns nothing")


def derive_adjugate_3() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """The cofactors ``C_ij`` (``i <= j``, :data:`COFACTOR_INDICES`) of the quadratic part ``A``
    of ``Q`` (upper entries ``q00 .. q22``): the entries of ``adj(A)``, which is symmetric; each
    a 2x2 minor, a difference of two products."""
    Q, _ = symmetric_matrix("q")
    A = Q[:3, :3]
    adj = A.adjugate()
    args = [sp.Symbol(f"q{i}{j}") for i, j in QUADRATIC_PART_INDICES]
    return args, [(f"C{i}{j}", sp.expand(adj[i, j])) for i, j in COFACTOR_INDICES]


def derive_cofactor_forms() -> tuple[list[sp.Symbol], list[tuple[str, sp.Expr]]]:
    """``JA``, ``detA`` and ``E4`` as polynomials in the entries of ``Q`` and, linearly, the
    cofactors ``C_ij`` of its quadratic part: ``JA = C00 + C11 + C22`` (the principal 2x2
    minors), ``detA = q00 C00 + q01 C01 + q02 C02`` (Laplace along the first row) and ``E4 = det Q
    = q33 detA - b^T adj(A) b`` with ``b = (q03, q13, q23)`` (the determinant of a bordered
    matrix).  Where the quadratic part is close to rank 1 (a rotated parabolic cylinder, a
    pair of parallel planes), every cofactor is of the order of the rounding and ``detA``,
    ``E4`` of its square: these forms add up terms of the order of the rounding, not of the
    entries.  Checked by :func:`verify_cofactor_forms`."""
    C = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"C{min(i, j)}{max(i, j)}"))
    q = {ij: sp.Symbol(f"q{ij[0]}{ij[1]}") for ij in ENTRY_INDICES}
    b = sp.Matrix([q[(0, 3)], q[(1, 3)], q[(2, 3)]])
    det_a = q[(0, 0)] * C[0, 0] + q[(0, 1)] * C[0, 1] + q[(0, 2)] * C[0, 2]
    forms = {
        "JA": C[0, 0] + C[1, 1] + C[2, 2],
        "detA": det_a,
        "E4": sp.expand(q[(3, 3)] * det_a - (b.T * C * b)[0, 0]),
    }
    cofactors = [C[i, j] for i, j in COFACTOR_INDICES]
    return cofactors, [(name, sp.expand(forms[name])) for name in COFACTOR_OUTPUTS]


def verify_cofactor_forms() -> None:
    """Raise AssertionError unless the cofactors are those of sympy's adjugate (``A adj(A) =
    det(A) I``) and the cofactor forms, with the cofactors substituted, are the invariants."""
    Q, _ = symmetric_matrix("q")
    A = Q[:3, :3]
    _, cofactors = derive_adjugate_3()
    adj = sp.Matrix(3, 3, lambda i, j: dict(cofactors)[f"C{min(i, j)}{max(i, j)}"])
    if sp.expand(A * adj - A.det(method="berkowitz") * sp.eye(3)) != sp.zeros(3, 3):
        raise AssertionError("the cofactors are not the adjugate of the quadratic part")
    substitute = {sp.Symbol(name): expr for name, expr in cofactors}
    _, invariants = derive_quadric_invariants()
    _, forms = derive_cofactor_forms()
    for name, form in forms:
        if sp.expand(form.xreplace(substitute) - dict(invariants)[name]) != 0:
            raise AssertionError(f"the cofactor form of {name} is not the invariant")


def _dd_programs() -> tuple[list[str], list[str], list[str]]:
    """The lines of ``adjugate_3_dd``, ``quadric_invariants_dd`` and
    ``quadric_invariants_cofactor_magnitude``."""
    adj_args, cofactors = derive_adjugate_3()
    adjugate = _dd_program_lines(
        "adjugate_3_dd",
        adj_args,
        cofactors,
        "The cofactors (C00, C01, C02, C11, C12, C22) of the quadratic part of Q, in double-double:\n"
        "    each a difference of two exact products, rounded once (dd_sub, relative error at most\n"
        "    3u^2 + 13u^3 of the cofactor itself).",
    )
    args, invariants = derive_quadric_invariants()
    pairs, forms = derive_cofactor_forms()
    by_cofactors = dict(forms)
    outputs = [(name, by_cofactors.get(name, expr)) for name, expr in invariants]
    program = _dd_program_lines(
        "quadric_invariants_dd",
        args,
        outputs,
        "``quadric_invariants`` in double-double: (trA, JA, detA, E1, E2, E3, E4), each a pair\n"
        "    (hi, lo) with hi = RN(hi + lo), from the binary64 upper entries qij of Q and the cofactors\n"
        "    of its quadratic part (``adjugate_3_dd``): JA, detA and E4 are formed from the cofactors\n"
        "    (``codegen.derive_cofactor_forms``), the others from the monomials of\n"
        "    ``quadric_invariants``.  Expanded, every output has the paths of that program, so its\n"
        "    magnitude companion bounds the error; JA, detA and E4 have the tighter bound of\n"
        "    ``quadric_invariants_cofactor_magnitude`` too.",
        pairs=pairs,
    )
    magnitude_forms = [
        (name, sum((abs(c) * sp.prod([s**p for s, p in zip([*args, *pairs], m, strict=True)]) for m, c in
                    sp.Poly(expr, *args, *pairs).terms()), sp.Integer(0)))
        for name, expr in forms
    ]  # fmt: skip
    magnitude = _emit_function(
        "quadric_invariants_cofactor_magnitude",
        [*args, *pairs],
        magnitude_forms,
        "(JA, detA, E4): the magnitudes of their cofactor forms (``codegen.derive_cofactor_forms``),\n"
        "    every coefficient and argument taken absolutely: call it with the absolute upper entries\n"
        "    of Q and the absolute high words of the double-double cofactors.",
    )
    return adjugate, program, magnitude


def verify_dd_programs(text: str, companion: Any) -> None:
    """Raise AssertionError unless the double-double programs of ``text``, read exactly and
    along their paths, are what the error bounds assume:

    * ``adjugate_3_dd`` computes the cofactors, and ``quadric_invariants_dd`` on them the
      invariants;
    * expanded down to the entries (the cofactors' paths substituted), the magnitude of every
      output of ``quadric_invariants_dd`` (the sum over its paths of the absolute values of
      their products) is, polynomial for polynomial, the binary64 magnitude companion
      ``companion`` of ``quadric_invariants`` (a function of the absolute entries);
    * with the cofactors as inputs, the magnitudes of ``JA``, ``detA``, ``E4`` are the values of
      ``quadric_invariants_cofactor_magnitude`` at the absolute entries and cofactors."""
    adj_args, cofactors = derive_adjugate_3()
    args, invariants = derive_quadric_invariants()
    pairs, forms = derive_cofactor_forms()
    got_c = _run_symbolically(text, "adjugate_3_dd", [_Paths(a, a) for a in adj_args])
    for (name, expr), c in zip(cofactors, got_c, strict=True):
        if sp.expand(c.value - expr) != 0:
            raise AssertionError(f"the double-double {name} differs from its cofactor")
    got = _run_symbolically(text, "quadric_invariants_dd", [*(_Paths(a, a) for a in args), *got_c])
    reference = companion(*args)
    for (name, expr), value, mag in zip(invariants, got, reference, strict=True):
        if sp.expand(value.value - expr) != 0:
            raise AssertionError(f"the double-double {name} differs from its polynomial")
        if sp.expand(value.magnitude - mag) != 0:
            raise AssertionError(f"the magnitude of the double-double {name} is not the companion's")
    level = _run_symbolically(
        text, "quadric_invariants_dd", [*(_Paths(a, a) for a in args), *(_Paths(t, t) for t in pairs)]
    )
    magnitude_program = _functions(text)["quadric_invariants_cofactor_magnitude"]
    cofactor_magnitude = _interpret(magnitude_program, [*args, *pairs])[1]
    names = [n for n, _ in invariants]
    for (name, expr), mag in zip(forms, cofactor_magnitude, strict=True):
        read = level[names.index(name)]
        if sp.expand(read.value - expr) != 0:
            raise AssertionError(f"the double-double {name} is not its cofactor form")
        if sp.expand(read.magnitude - mag) != 0:
            raise AssertionError(f"the cofactor magnitude of {name} is not the program's")


def emit_dd_programs() -> str:
    """The full text of ``_generated/dd_programs.py``."""
    import ast

    adjugate, program, magnitude = _dd_programs()
    functions = {
        n.name: n for n in ast.parse("\n".join([*adjugate, "", *program, "", *magnitude])).body
        if isinstance(n, ast.FunctionDef)
    }  # fmt: skip
    adj_counts = dd_rounding_counts(functions["adjugate_3_dd"])
    pairs, _ = derive_cofactor_forms()
    carried = {
        str(t): (a, m, d)
        for t, a, m, d in zip(
            pairs, adj_counts["dd_add"], adj_counts["dd_mul_d"], adj_counts["degree"], strict=True
        )
    }
    counts = dd_rounding_counts(functions["quadric_invariants_dd"], carried)
    _, invariants = derive_quadric_invariants()
    mag_counts = rounding_counts(functions["quadric_invariants_cofactor_magnitude"], 0)
    entries: dict[str, dict[str, tuple[Any, ...]]] = {
        "adjugate_3_dd": {"outputs": tuple(str(t) for t in pairs), **adj_counts},
        "quadric_invariants_dd": {"outputs": tuple(n for n, _ in invariants), **counts},
        "quadric_invariants_cofactor_magnitude": {
            "outputs": COFACTOR_OUTPUTS,
            "degree": tuple(d for _, d in mag_counts),
            "magnitude": tuple(n for n, _ in mag_counts),
        },
    }
    out: list[str] = [
        '"""Double-double programs, generated by ``quadric_contact.codegen``.',
        "",
        "Do not edit: regenerate with ``python -m quadric_contact.codegen``.  The invariants that",
        "fix the affine type of a quadric (``kernels.quadric_invariants``) evaluated in",
        "double-double arithmetic: the cofactors of the quadratic part (``adjugate_3_dd``), then",
        "the invariants (``quadric_invariants_dd``), with products of two entries by Dekker's",
        "exact product, further factors by DWTimesFP1 and sums by AccurateDWPlusDW in balanced",
        "trees, and the magnitudes of the three invariants formed from the cofactors",
        "(``quadric_invariants_cofactor_magnitude``, binary64).  The operations are arguments",
        "(:mod:`quadric_contact.modes.kernels.double_double` defines them; the programs run on floats, on",
        "numpy arrays and compiled by numba alike), and DD_COUNTS gives, for every output, its",
        "degree and the largest numbers of rounding double-double additions and multiplications",
        "on a path from the inputs (and for the magnitude program its binary64 rounding count),",
        "from which :mod:`quadric_contact.modes.kernels.errorbounds` derives the error bounds.",
        '"""',
        "",
        "# ruff: noqa",
        "",
        *adjugate,
        "",
        "",
        *program,
        "",
        "",
        *magnitude,
        "",
        "",
        "DD_COUNTS = {",
    ]
    for fname, entry in entries.items():
        out.append(f"    {fname!r}: {{")
        out += [f"        {key!r}: {value!r}," for key, value in entry.items()]
        out.append("    },")
    out += ["}", ""]
    return "\n".join(out)


def regenerate_dd(path: Path = DD_PATH, check: bool = False) -> bool:
    """Write (or with ``check=True`` only compare) ``_generated/dd_programs.py``, after checking
    the programs (:func:`verify_cofactor_forms`, :func:`verify_dd_programs`)."""
    verify_invariants()
    verify_cofactor_forms()
    text = emit_dd_programs()
    invariants = _functions(emit_kernels())["quadric_invariants"]
    companion = _functions("\n".join(emit_magnitude_function(invariants)))

    def magnitude(*args: Any) -> list[Any]:
        return _interpret(companion["quadric_invariants_magnitude"], args)[1]

    verify_dd_programs(text, magnitude)
    current = path.read_text() if path.exists() else None
    if check:
        return current == text
    path.write_text(text)
    return current == text


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="quadric-contact codegen", description=__doc__.split("\n")[0])
    parser.add_argument("--check", action="store_true", help="only check that the file is current")
    args = parser.parse_args(argv)
    status = 0
    for path, fn in (
        (GENERATED_PATH, regenerate),
        (KERNELS_PATH, regenerate_kernels),
        (BLOCKS_PATH, regenerate_blocks),
        (DD_PATH, regenerate_dd),
    ):
        same = fn(check=args.check)
        if args.check:
            print(f"{path.name}: " + ("current" if same else "OUT OF DATE"))
            status |= 0 if same else 1
        else:
            print(f"wrote {path} ({'unchanged' if same else 'changed'})")
    return status


if __name__ == "__main__":
    sys.exit(main())
