"""Derive the companions of the closed forms for the number modes and write ``_generated/kernels.py``.

The leading principal minors of a quadratic part and of a member of the pencil
(Sylvester's criterion: :func:`derive_leading_minors_3`, :func:`derive_leading_minors_4`),
the invariants that fix the affine type of a quadric (:func:`derive_quadric_invariants`)
and a short program with the signs of the paper's Deltas (:func:`derive_compact_deltas`),
each checked against an independent sympy computation; then, for every function of
:data:`FILTERED_FUNCTIONS`, its magnitude companion and its rounding counts, read off the
emitted text by :mod:`quadric_contact.exact.straight_line` (:func:`emit_kernels`).
:func:`regenerate_kernels` writes (or checks) the file.
"""

from __future__ import annotations

from itertools import combinations
from pathlib import Path
from typing import Any

import sympy as sp

from quadric_contact.codegen.emission import emit_function, format_counts
from quadric_contact.codegen.formulas import (
    coefficient_symbols,
    derive_paper_deltas,
    emit_formulas,
    symmetric_matrix,
)
from quadric_contact.exact.straight_line import _functions, emit_magnitude_function, rounding_counts

__all__ = [
    "FILTERED_FUNCTIONS",
    "KERNELS_PATH",
    "QUADRATIC_PART_INDICES",
    "derive_compact_deltas",
    "derive_leading_minors_3",
    "derive_leading_minors_4",
    "derive_quadric_invariants",
    "emit_kernels",
    "leading_minors_expanded",
    "regenerate_kernels",
    "verify_compact_deltas",
    "verify_invariants",
    "verify_leading_minors_4",
]

KERNELS_PATH = Path(__file__).parents[1] / "_generated" / "kernels.py"


QUADRATIC_PART_INDICES: tuple[tuple[int, int], ...] = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
"""The six independent entries of a symmetric 3x3 quadratic part, in argument order."""


def _principal_minor_sum(M: sp.Matrix, order: int) -> sp.Expr:
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
    48.  Checked against :func:`~quadric_contact.codegen.formulas.derive_paper_deltas` by
    :func:`verify_compact_deltas`.  In floating point ``4 I^3 - J^2`` cancels far more than the
    expanded form, so its rounding bound is weaker: the screen uses it with that bound
    (``errorbounds.SEMI_DELTA``), the filter the expanded form."""
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
    out = emit_function(
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
        *emit_function(
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
    out += emit_function(
        "quadric_invariants",
        args,
        invariants,
        "(trA, JA, detA, E1, E2, E3, E4) of the symmetric Q with upper entries qij: trace, sum of\n"
        "    principal 2x2 minors and determinant of the quadratic part, and the sums of the principal\n"
        "    minors of each order of Q.",
    )
    out += ["", ""]
    args, minors4 = derive_leading_minors_4()
    out += emit_function(
        "leading_minors_4",
        args,
        minors4,
        "(d1, d2, d3, d4): leading principal minors of the symmetric 4x4 matrix with upper entries\n"
        "    mij (Sylvester's criterion: is a member of the pencil definite?); d3 by Laplace along the\n"
        "    third row, d4 by Laplace along the first two rows, from the 2x2 minors of both row pairs.",
        returned=("d1", "d2", "d3", "d4"),
    )
    return out


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
    out += format_counts(counts)
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
