"""Straight-line programs for polynomials known only at run time (the families' numeric lambdas).

The families of :mod:`quadric_contact.families.family` need the same kind of code as the
generated modules for polynomials known only at run time (the coefficients of ``P``,
the Deltas, ... as polynomials in the family's parameters): a straight-line function
in the grammar of :mod:`quadric_contact.exact.straight_line`, with its magnitude companion
and its rounding counts, so that the float filter's error bounds
(:mod:`quadric_contact.modes.kernels.errorbounds`) apply to it unchanged.  Each polynomial is
put in nested Horner form (one variable after the other) and the subexpressions the
outputs share are computed once (sympy's ``cse``).

This is run-time code (:mod:`quadric_contact.families.family_numeric` calls
:func:`emit_program`); the code generator :mod:`quadric_contact.codegen` is
development time only and is never imported at run time.
"""

from __future__ import annotations

import ast
import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import sympy as sp

from quadric_contact.exact.straight_line import (
    _functions,
    _interpret,
    _print_expr,
    emit_magnitude_function,
    rounding_counts,
)

__all__ = ["Program", "emit_program", "horner_form"]


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


def emit_program(
    name: str,
    args: Sequence[str],
    outputs: Sequence[tuple[str, dict[tuple[int, ...], int]]],
    doc: str = "Generated by quadric_contact.families.family_emit.emit_program.",
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
