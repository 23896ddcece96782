"""Derive the unrolled block code of the binary64 kernels and write ``_generated/blocks.py``.

The gathers that copy matrices into block buffers and check their symmetry, the loads, the
row maxima and input guards, ``pencil_coefficients`` cut in two for a fixed matrix, and the
row bound of the semi-static filter (:func:`derive_row_bound`), with the proofs the error
bounds of :mod:`quadric_contact.modes.kernels.errorbounds` rest on: that ``24 W_k`` bounds
the magnitude program of ``c_k`` (:func:`verify_row_bound`), the row bounds of the leading
minors (:func:`verify_minor_row_bounds`, :func:`verify_member_minor_row_bounds`) and the
exact zeros of a plane's pencil (:func:`verify_plane_zeros`).  :func:`emit_blocks` prints
the file, :func:`regenerate_blocks` checks the proofs and writes (or checks) it.
"""

from __future__ import annotations

import math
from itertools import combinations, permutations
from pathlib import Path
from typing import Any

import sympy as sp

from quadric_contact._generated import kernels as generated_kernels
from quadric_contact.codegen.emission import emit_expression, emit_function, format_counts
from quadric_contact.codegen.formulas import (
    coefficient_symbols,
    derive_paper_deltas,
    derive_pencil,
    emit_formulas,
    symmetric_matrix,
)
from quadric_contact.codegen.kernels import derive_compact_deltas, derive_leading_minors_3, emit_kernels
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.straight_line import (
    _functions,
    _interpret,
    emit_magnitude_function,
    emit_value_and_magnitude_function,
    rounding_counts,
)

__all__ = [
    "BLOCKS_PATH",
    "FLAT_LOWER",
    "FLAT_UPPER",
    "ROW_SYMBOLS",
    "derive_row_bound",
    "emit_blocks",
    "regenerate_blocks",
    "verify_member_minor_row_bounds",
    "verify_minor_row_bounds",
    "verify_plane_zeros",
    "verify_row_bound",
]

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
    the Laplace expansion of :func:`~quadric_contact.codegen.formulas.derive_pencil` groups them."""
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
    R = ROW_SYMBOLS[0]
    args, minors = derive_leading_minors_3()
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{min(i, j)}{max(i, j)}"))
    text = "\n".join(emit_function("leading_minors_3", args, minors, "", returned=("m2", "m3")))
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
    A, args = symmetric_matrix("m")
    magnitude = generated_kernels.leading_minors_4_magnitude(*args)
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
        out.append(f"    {sym} = {emit_expression(expr)}")
    for k in range(5):
        out.append(f"    c{k} = {emit_expression(outputs[k])}")
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
            out.append(f"    {sym} = {emit_expression(expr)}")
        out.append(f"    c{k_fixed} = {emit_expression(outputs[k_fixed])}")
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
            out.append(f"    {sym} = {emit_expression(expr)}")
        for k in range(5):
            if k != k_fixed:
                out.append(f"    c{k} = {emit_expression(outputs[k])}")
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
    rb_lines = emit_function(
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
    out += [line.replace("ROUNDING_COUNTS", "BLOCK_COUNTS") for line in format_counts(counts)]
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
