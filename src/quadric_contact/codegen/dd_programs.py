"""Derive the double-double programs and write ``_generated/dd_programs.py``.

``kernels.quadric_invariants`` evaluated in double-double arithmetic: the cofactors of the
quadratic part (``adjugate_3_dd``), then the invariants (``quadric_invariants_dd``), with
products by Dekker's exact product and DWTimesFP1 and sums by AccurateDWPlusDW in balanced
trees (:func:`emit_dd_programs`), and the magnitudes of the invariants formed from the
cofactors.  The programs are checked by reading them exactly and along their paths
(:func:`verify_dd_programs`: they compute the invariants, and their magnitudes are the
binary64 companion's), and :func:`dd_rounding_counts` reads off the rounding double-double
operations on their paths, from which
:data:`quadric_contact.modes.kernels.errorbounds.INVARIANTS_DD_ERRBOUND` is derived.
:func:`regenerate_dd` checks the programs and writes (or checks) the file.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import sympy as sp

from quadric_contact.codegen.emission import emit_function
from quadric_contact.codegen.formulas import symmetric_matrix
from quadric_contact.codegen.kernels import (
    QUADRATIC_PART_INDICES,
    derive_quadric_invariants,
    emit_kernels,
    verify_invariants,
)
from quadric_contact.exact.entries import ENTRY_INDICES
from quadric_contact.exact.straight_line import (
    _functions,
    _interpret,
    emit_magnitude_function,
    rounding_counts,
)

__all__ = [
    "COFACTOR_INDICES",
    "COFACTOR_OUTPUTS",
    "DD_OPERATIONS",
    "DD_PATH",
    "dd_rounding_counts",
    "derive_adjugate_3",
    "derive_cofactor_forms",
    "emit_dd_programs",
    "regenerate_dd",
    "verify_cofactor_forms",
    "verify_dd_programs",
]

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
    magnitude = emit_function(
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
