"""Straight-line programs: the tiny grammar of the generated formulas, read with :mod:`ast`.

The functions of :mod:`quadric_contact._generated` (and the programs the families
emit at run time, :mod:`quadric_contact.families.family_emit`) are straight-line code:
assignments of expressions built from names, integer constants, binary ``+ - *``
and unary minus, and a tuple return.  This module reads such a function
(:func:`_straight_line`), prints its expressions back byte for byte
(:func:`_print_expr`), derives its magnitude companion
(:func:`emit_magnitude_function`: every minus turned into a plus) and both in one
program that shares their products (:func:`emit_value_and_magnitude_function`), counts the
rounded operations on every path from the inputs (:func:`rounding_counts`, what the
error bounds of :mod:`quadric_contact.modes.kernels.errorbounds` are built from) and runs it
without compiling it (:func:`_interpret`).

It imports nothing but the standard library: the code generator
(:mod:`quadric_contact.codegen`, development time) and the run-time code (the
families' numeric lambdas, the smallness filter's error bounds) share it, and the
run-time code never imports the generator.
"""

from __future__ import annotations

import ast
import copy
from collections.abc import Sequence
from typing import Any

__all__ = [
    "EXACT_INTEGER_MAX",
    "emit_magnitude_function",
    "emit_value_and_magnitude_function",
    "rounding_counts",
]

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


def emit_value_and_magnitude_function(fdef: ast.FunctionDef) -> list[str]:
    """``NAME_and_magnitude``: the values of a generated straight-line function and of its
    magnitude companion (at the absolute values of the same arguments) in one program, returned
    as ``(values..., magnitudes...)``, with the same bits as the two programs.

    The value program is copied operation by operation (one temporary per operation, in the same
    order and association).  The magnitude of a product of two operands whose magnitudes are
    their absolute values -- arguments, constants and such products -- is the absolute value of
    the computed product: rounding to nearest is symmetric, ``|fl(x y)| = fl(|x| |y|)``.  Only the
    other products (a sum times something) and the sums are computed again, so for a program
    that adds up products of its arguments, as the Delta forms do, the companion costs additions
    and a few products instead of as many products again."""
    args, assignments, returned = _straight_line(fdef)
    lines: list[str] = []
    count = 0
    # name -> (value text, magnitude text, magnitude is the absolute value of the value)
    env: dict[str, tuple[str, str, bool]] = {a: (a, f"abs({a})", True) for a in args}

    def temp(kind: str, text: str) -> str:
        nonlocal count
        count += 1
        name = f"_{kind}{count}"
        lines.append(f"    {name} = {text}")
        return name

    def walk(node: ast.expr) -> tuple[str, str, bool]:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant) and type(node.value) is int:
            return (str(node.value), str(abs(node.value)), True)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            if isinstance(node.operand, ast.Constant):
                value, mag, exact = walk(node.operand)
                return (f"(-{value})", mag, exact)
            value, mag, exact = walk(node.operand)
            return (temp("v", f"-{value}"), mag, exact)
        if isinstance(node, ast.BinOp) and type(node.op) in _PRECEDENCE:
            lv, lm, le = walk(node.left)
            rv, rm, re_ = walk(node.right)
            value = temp("v", f"{lv} {_SYMBOL[type(node.op)]} {rv}")
            if isinstance(node.op, ast.Mult):
                if le and re_:
                    return (value, f"abs({value})", True)
                return (value, temp("m", f"{lm} * {rm}"), False)
            return (value, temp("m", f"{lm} + {rm}"), False)
        raise AssertionError(f"unexpected syntax in a generated straight-line function: {ast.dump(node)}")

    for target, expr in assignments:
        env[target] = walk(expr)
    values = [env[r][0] for r in returned]
    mags = [env[r][1] for r in returned]
    head = [
        f"def {fdef.name}_and_magnitude({', '.join(args)}):",
        f'    """``{fdef.name}`` and its magnitude companion at the absolute values of the arguments,',
        "    ``(values..., magnitudes...)``: the same operations as the two programs, with the",
        '    absolute value of a computed product standing for the same product of absolute values."""',
    ]
    return [*head, *lines, f"    return ({', '.join(values + mags)})"]


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


def _interpret(fdef: ast.FunctionDef, values: Sequence[Any]) -> tuple[dict[str, Any], list[Any]]:
    """Run a straight-line function of the grammar above (and ``abs`` of one operand, as the
    fused value-and-magnitude programs use it) on ``values`` without compiling it: every
    assignment, and the outputs."""
    args, assignments, returned = _straight_line(fdef)
    env: dict[str, Any] = dict(zip(args, values, strict=True))

    def walk(node: ast.expr) -> Any:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            return -walk(node.operand)
        if (
            isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "abs"
            and len(node.args) == 1 and not node.keywords
        ):  # fmt: skip
            return abs(walk(node.args[0]))  # the fused value-and-magnitude programs
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
