"""Straight-line Python from sympy: how the generator prints what it derives.

Every generated function is a sequence of assignments of integer polynomials in its
arguments and earlier temporaries, written with ``+``, ``-``, ``*`` and integer literals
only, so that it runs on every number type the package uses.  :func:`emit_polynomial`
prints a polynomial as a sum of monomials in a deterministic order (powers as repeated
products, optionally through shared temporaries from :func:`power_temps`),
:func:`emit_function` a whole function, and :func:`format_counts` the rounding counts
that the generated modules carry next to their functions.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import sympy as sp

__all__ = ["emit_expression", "emit_function", "emit_polynomial", "format_counts", "power_temps"]


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


def emit_polynomial(expr: sp.Expr, variables: Sequence[sp.Symbol], temps: dict[tuple[int, int], str]) -> str:
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


def power_temps(
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


def emit_expression(expr: sp.Expr) -> str:
    """Print an integer polynomial in its free symbols; powers become products."""
    expr = sp.expand(expr)
    variables = sorted(expr.free_symbols, key=str)
    return emit_polynomial(expr, variables, {}) if variables else str(int(expr))


def emit_function(
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
        lines.append(f"    {out_name} = {emit_expression(expr)}")
    names = list(returned) if returned is not None else [n for n, _ in outputs]
    lines.append(f"    return ({', '.join(names)}{',' if len(names) == 1 else ''})")
    return lines


def format_counts(counts: dict[str, dict[str, tuple[Any, ...]]]) -> list[str]:
    lines = ["ROUNDING_COUNTS = {"]
    for fname, entry in counts.items():
        lines.append(f"    {fname!r}: {{")
        for key, value in entry.items():
            lines.append(f"        {key!r}: {value!r},")
        lines.append("    },")
    lines.append("}")
    return lines
