"""Numeric lambdas of a family's quantities: vectorised functions of parameter arrays.

Each exact quantity of a :class:`~quadric_contact.families.family.Family` is ``num / den`` with
``num, den`` in Q[parameters].  Both are scaled to primitive integer polynomials (a positive
rational factor is kept apart) and emitted by the package's code generator
(:func:`quadric_contact.families.family_emit.emit_program`: nested Horner form, subexpressions shared
between numerator and denominator), with the magnitude companion and the rounding counts
the float filter's error bounds are derived from.  The same program runs in every backend:

``"numpy"``
    binary64 on numpy arrays (the program's operations are array operations);
``"numba"``
    the program compiled by numba, in a loop over the points;
``"mpmath"``
    mpmath numbers at ``dps`` digits (default 50) on object arrays;
``"certified"``
    the *sign* of the quantity at each binary64 point, never wrong: the value and its
    magnitude companion in binary64 (numba when it is installed), the rigorous bound
    ``|fl(p) - p| <= K M`` of :func:`quadric_contact.modes.kernels.errorbounds.program_errbound`
    for each of numerator and denominator; ``-1, 0, 1`` where the bound decides it and
    ``2`` (``UNCERTAIN``) where it does not, at a pole, where an input is not finite or
    where a product underflowed (below) -- an int8 array;
``"exact"``
    the exact value (:class:`~fractions.Fraction`) at each point, point by point with
    python-flint (the reference the others are measured against).

The error model (Higham's, as in :mod:`quadric_contact.modes.kernels.errorbounds`) needs every
operation to be rounded with relative error at most ``u``.  Sums and differences always are
(a result in the subnormal range is exact); a product is when its result is at least
``2^-1021`` in magnitude or an operand is zero.  The certified programs are run one
operation per line with that check after every product, in the value program and in its
magnitude companion, and a point where one fails is ``UNCERTAIN`` (the static input guards
of the pair filter would exclude most inputs below 1 for the degrees of a family's
quantities).  Overflow needs no check: every computed value is at most the computed
magnitude in absolute value (rounding is monotone), so an infinite or NaN intermediate
makes the magnitude infinite or NaN and the point uncertain.  The bound itself is
``fl(K M) + 2^-1074``, which stays an upper bound if the product underflows.  Integer
constants beyond ``2^53`` count as rounded operands in the rounding counts.

The generated text is compiled only after it has been checked to be in the grammar of the
generated modules (assignments of ``+ - *`` over names and integer literals): the names are
the program's own (``p0, p1, ...``, ``t0, ...``), never the user's, and the numbers come from
the exact polynomials.
"""

from __future__ import annotations

import ast
import math
import sys
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import flint
import mpmath
import numpy as np

from quadric_contact.exact.errors import ChoiceError
from quadric_contact.exact.precision import working_precision
from quadric_contact.exact.straight_line import (
    EXACT_INTEGER_MAX,
    _functions,
    _print_expr,
    _straight_line,
)
from quadric_contact.families.family_emit import Program, emit_program
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.modes.kernels.errorbounds import program_errbound

if TYPE_CHECKING:
    from quadric_contact.families.family import Family
    from quadric_contact.families.rational_functions import RationalFunction

__all__ = ["BACKENDS", "UNCERTAIN", "CompiledQuantity", "FamilyFunction", "compile_quantity", "lambdify"]

BACKENDS = ("numpy", "numba", "mpmath", "certified", "exact")
UNCERTAIN = 2
"""The certified backend's code for "the sign is not certain here" (non-zero, never read as 0)."""


def _integer_polynomial(p: Any) -> tuple[dict[tuple[int, ...], int], Fraction]:
    """``p = factor * P`` with ``P`` a primitive integer polynomial, ``factor > 0`` rational."""
    d = p.to_dict()
    if not d:
        return {}, Fraction(1)
    den = 1
    for c in d.values():
        den = den * int(c.q) // math.gcd(den, int(c.q))
    ints = {tuple(int(e) for e in m): int(c.p) * (den // int(c.q)) for m, c in d.items()}
    g = 0
    for v in ints.values():
        g = math.gcd(g, v)
    return {m: v // g for m, v in ints.items()}, Fraction(g, den)


@dataclass(frozen=True)
class CompiledQuantity:
    """A quantity ``num / den`` compiled for the numeric backends.

    ``value = scale * N / D`` with ``N``, ``D`` the outputs of :attr:`program` (``D`` absent,
    i.e. 1, for a polynomial) and ``scale`` a positive rational.
    """

    name: str
    program: Program
    scale: Fraction
    has_denominator: bool
    error_bounds: tuple[float, ...]
    checked_source: str
    functions: dict[str, Any]

    @property
    def source(self) -> str:
        return self.program.source


TINY = 2.0**-1021
"""A product of two non-zero binary64 numbers at least this large in magnitude was rounded
with relative error at most ``u`` (it did not underflow)."""

_MAX = sys.float_info.max
_SMALLEST = 5e-324
"""``2^-1074``, added to the computed bound ``fl(K M)``: if that product underflows it is
rounded with an absolute error below ``2^-1075``, and the sum is then exact; otherwise the
addition changes nothing and the relative rounding of the product is in ``K``."""


def _literal(value: int) -> str:
    # numba types integer literals as int64: a constant beyond 2^53 is written as its binary64
    # rounding (which the rounding counts charge; numpy rounds it the same way).
    return repr(float(value)) if abs(value) > EXACT_INTEGER_MAX else str(value)


def _ssa(
    fdef: ast.FunctionDef, inputs: dict[str, str], prefix: str, checks: bool = True
) -> tuple[list[str], list[str]]:
    """A straight-line function of the generated grammar as single assignments, one operation
    each, with (``checks``) a check after every product that it did not underflow (``ok``
    becomes false where a product of two non-zero numbers is below :data:`TINY`).  Returns the
    lines and the names (or literals) of the outputs."""
    args, assignments, returned = _straight_line(fdef)
    env = {a: inputs[a] for a in args}
    lines: list[str] = []
    count = 0

    def fresh() -> str:
        nonlocal count
        count += 1
        return f"{prefix}{count}"

    def walk(node: ast.expr) -> str:
        if isinstance(node, ast.Name):
            return env[node.id]
        if isinstance(node, ast.Constant) and isinstance(node.value, int):
            return _literal(node.value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
            t = fresh()
            lines.append(f"    {t} = -{walk(node.operand)}")
            return t
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult)):
            left, right = walk(node.left), walk(node.right)
            op = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*"}[type(node.op)]
            t = fresh()
            lines.append(f"    {t} = {left} {op} {right}")
            if op == "*" and checks:
                lines.append(f"    ok = ok & ((abs({t}) >= {TINY!r}) | ({left} == 0.0) | ({right} == 0.0))")
            return t
        raise AssertionError(f"unexpected syntax: {ast.dump(node)}")

    for target, expr in assignments:
        env[target] = walk(expr)
    return lines, [env[r] for r in returned]


def _checked_source(program: Program) -> str:
    """``checked(p0, ..)``: the value program at the inputs and its magnitude companion at their
    absolute values, one operation per line, with the underflow checks of :func:`_ssa` and a
    check that the inputs are finite; returns ``(values..., magnitudes..., ok)``."""
    fns = _functions(program.source)
    args = list(program.args)
    lines = [f"def checked({', '.join(args)}):"]
    lines.append("    ok = " + (" & ".join(f"(abs({a}) <= {_MAX!r})" for a in args) if args else "True"))
    for a in args:
        lines.append(f"    a_{a} = abs({a})")
    v_lines, v_out = _ssa(fns["quantity"], {a: a for a in args}, "v")
    m_lines, m_out = _ssa(fns["quantity_magnitude"], {a: f"a_{a}" for a in args}, "m")
    lines += v_lines + m_lines
    lines.append(f"    return ({', '.join([*v_out, *m_out, 'ok'])},)")
    return "\n".join(lines) + "\n"


def _checked(source: str) -> None:
    """Raise AssertionError unless every function of ``source`` is a straight-line function
    of the generated grammar (the printer re-prints every expression it accepts)."""
    for fdef in _functions(source).values():
        _, assignments, _ = _straight_line(fdef)
        for _, expr in assignments:
            _print_expr(expr)


def _compile_source(source: str, namespace: dict[str, Any]) -> dict[str, Any]:
    """Compile generated text (checked by :func:`_checked` or made from fixed templates)."""
    code = compile(ast.parse(source), "<quadric_contact family program>", "exec")
    exec(code, namespace)
    return namespace


def compile_quantity(name: str, value: RationalFunction, nparams: int) -> CompiledQuantity:
    """Emit and compile the program of one quantity (see the module docstring)."""
    args = tuple(f"p{i}" for i in range(nparams))
    num, fn = _integer_polynomial(value.num)
    outputs: list[tuple[str, dict[tuple[int, ...], int]]] = [("n", num)]
    scale = fn
    has_den = not value.den.is_constant()
    if has_den:
        den, fd = _integer_polynomial(value.den)
        outputs.append(("d", den))
        scale = fn / fd
    elif not value.den.is_one():
        scale = fn / Fraction(int(value.den.leading_coefficient().p), int(value.den.leading_coefficient().q))
    label = "".join(c for c in name if c.isalnum() or c in " _^<>=/*+-.")  # the docstring: no quotes
    program = emit_program(
        "quantity", args, outputs, doc=f"{label}: generated by quadric_contact.families.family_numeric."
    )
    if program.path_bound >= 2**1000:
        raise OverflowError(f"{name}: coefficients beyond the range of binary64")
    _checked(program.source)
    bounds = tuple(
        program_errbound(nv, nm, d)
        for nv, nm, d in zip(program.value_counts, program.magnitude_counts, program.degree, strict=True)
    )
    checked = _checked_source(program)
    functions = _compile_source(program.source + "\n\n" + checked, {"__builtins__": {"abs": abs}})
    functions = {k: v for k, v in functions.items() if k != "__builtins__"}
    return CompiledQuantity(name, program, scale, has_den, bounds, checked, functions)


# -- numba kernels (fixed templates; the only names are the program's) ---------------------------


def _value_kernel_source(nparams: int, has_den: bool, scale: float) -> str:
    xs = ", ".join(f"P[{k}, i]" for k in range(nparams))
    value = f"{scale!r} * r[0] / r[1]" if has_den else f"{scale!r} * r[0]"
    return (
        "def kernel(P, out):\n"
        "    for i in range(out.shape[0]):\n"
        f"        r = quantity({xs})\n"
        f"        out[i] = {value}\n"
    )


def _sign_kernel_source(nparams: int, bounds: tuple[float, ...]) -> str:
    xs = ", ".join(f"P[{k}, i]" for k in range(nparams))
    n = len(bounds)
    lines = [
        "def kernel(P, out):",
        "    for i in range(out.shape[0]):",
        f"        r = checked({xs})",
        f"        if not r[{2 * n}]:",
        f"            out[i] = {UNCERTAIN}",
        "            continue",
    ]
    for j, K in enumerate(bounds):
        lines += [
            f"        b = {K!r} * r[{n + j}] + {_SMALLEST!r}",
            f"        if r[{j}] > b:",
            "            sj = 1",
            f"        elif r[{j}] < -b:",
            "            sj = -1",
            f"        elif r[{n + j}] == 0.0:",
            "            sj = 0",
            "        else:",
            f"            sj = {UNCERTAIN}",
        ]
        if j == 0:
            lines.append("        s = sj")
        else:  # the denominator: a pole or an uncertain sign leaves the point uncertain
            lines += [
                f"        if sj == 0 or sj == {UNCERTAIN} or s == {UNCERTAIN}:",
                f"            s = {UNCERTAIN}",
                "        else:",
                "            s = s * sj",
            ]
    lines.append("        out[i] = s")
    return "\n".join(lines) + "\n"


def _values_source(program: Program) -> str:
    """``values(p0, ..)``: the value program, one operation per line, without checks (for numba)."""
    args = list(program.args)
    lines, out = _ssa(_functions(program.source)["quantity"], {a: a for a in args}, "v", checks=False)
    return "\n".join([f"def values({', '.join(args)}):", *lines, f"    return ({', '.join(out)},)"]) + "\n"


def _numba_kernel(cq: CompiledQuantity, kind: str) -> Any:
    key = f"numba_{kind}"
    if key in cq.functions:
        return cq.functions[key]
    import numba  # numba is optional: only the numba backend imports it

    program = _compile_source(
        _values_source(cq.program) + "\n\n" + cq.checked_source, {"__builtins__": {"abs": abs}}
    )
    nparams = len(cq.program.args)
    if kind == "value":
        ns: dict[str, Any] = {"quantity": numba.njit(program["values"])}
        source = _value_kernel_source(nparams, cq.has_denominator, float(cq.scale))
    else:
        ns = {"checked": numba.njit(program["checked"])}
        source = _sign_kernel_source(nparams, cq.error_bounds)
    kernel = numba.njit(_compile_source(source, ns)["kernel"])
    cq.functions[key] = kernel
    return kernel


# -- the backends --------------------------------------------------------------------------------


def _numpy_values(cq: CompiledQuantity, xs: list[np.ndarray]) -> np.ndarray:
    r = cq.functions["quantity"](*xs)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = float(cq.scale) * (r[0] / r[1] if cq.has_denominator else r[0])
    return np.asarray(out, dtype=np.float64) * np.ones(np.shape(xs[0]) if xs else ())


def _numpy_signs(cq: CompiledQuantity, xs: list[np.ndarray]) -> np.ndarray:
    shape = np.shape(xs[0]) if xs else ()
    with np.errstate(all="ignore"):
        r = cq.functions["checked"](*xs)
    n = len(cq.error_bounds)
    ok = np.broadcast_to(np.asarray(r[2 * n], dtype=bool), shape)
    signs = []
    for j, K in enumerate(cq.error_bounds):
        v = np.broadcast_to(np.asarray(r[j], dtype=np.float64), shape)
        m = np.broadcast_to(np.asarray(r[n + j], dtype=np.float64), shape)
        b = K * m + _SMALLEST
        sj = np.full(shape, UNCERTAIN, dtype=np.int8)
        sj[m == 0.0] = 0
        sj[v > b] = 1
        sj[v < -b] = -1
        signs.append(sj)
    s = signs[0]
    if n == 2:
        d = signs[1]
        bad = (d == 0) | (d == UNCERTAIN) | (s == UNCERTAIN)
        s = np.where(bad, UNCERTAIN, s * d).astype(np.int8)
    return np.where(ok, s, UNCERTAIN).astype(np.int8)


def _mpmath_values(cq: CompiledQuantity, xs: list[np.ndarray], dps: int) -> np.ndarray:
    with working_precision(dps=dps):
        to_mpf = np.frompyfunc(mpmath.mpf, 1, 1)
        ys = [to_mpf(np.asarray(x, dtype=np.float64)) for x in xs]
        r = cq.functions["quantity"](*ys)
        scale = mpmath.mpf(cq.scale.numerator) / cq.scale.denominator
        out = scale * (r[0] / r[1] if cq.has_denominator else r[0])
        shape = np.shape(xs[0]) if xs else ()
        return np.asarray(out, dtype=object) * np.ones(shape, dtype=object)


def _exact_values(value: RationalFunction, xs: list[np.ndarray]) -> np.ndarray:
    shape = np.shape(xs[0]) if xs else ()
    flat = [np.asarray(x, dtype=np.float64).reshape(-1) for x in xs]
    n = int(np.prod(shape, dtype=np.int64))
    out = np.empty(n, dtype=object)
    num, den = value.num, value.den
    for i in range(n):
        args = []
        for x in flat:
            f = Fraction(float(x[i]))
            args.append(flint.fmpq(f.numerator, f.denominator))
        d = den(*args) if args else den.leading_coefficient()
        if d == 0:
            out[i] = None
            continue
        q = (num(*args) if args else num.leading_coefficient()) / d
        out[i] = Fraction(int(q.p), int(q.q))
    return out.reshape(shape)


class FamilyFunction:
    """A vectorised function of the family's parameters (from :meth:`Family.lambdify`).

    Call it with one array per parameter, positionally in the family's order or by name;
    the arrays broadcast as in numpy.  ``.source`` is the generated program.
    """

    def __init__(self, fam: Family, name: str, backend: str, cq: CompiledQuantity | None, **options: Any):
        self.family = fam
        self.name = name
        self.backend = backend
        self.compiled = cq
        self.options = options

    @property
    def source(self) -> str:
        return self.compiled.source if self.compiled is not None else ""

    def _arrays(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> list[np.ndarray]:
        params = self.family.parameters
        if args and kwargs:
            raise TypeError("give the parameters positionally or by name, not both")
        if kwargs:
            missing = [p for p in params if p not in kwargs]
            unknown = [k for k in kwargs if k not in params]
            if missing or unknown:
                raise TypeError(f"{self.name}: parameters {params}; missing {missing}, unknown {unknown}")
            args = tuple(kwargs[p] for p in params)
        if len(args) != len(params):
            raise TypeError(
                f"{self.name}: expected {len(params)} arrays ({', '.join(params)}), got {len(args)}"
            )
        return [np.asarray(a, dtype=np.float64) for a in np.broadcast_arrays(*[np.asarray(a) for a in args])]

    def __call__(self, *args: Any, **kwargs: Any) -> np.ndarray:
        xs = self._arrays(args, kwargs)
        b = self.backend
        if b == "exact":
            return _exact_values(self.family.quantity(self.name).value, xs)
        cq = self.compiled
        assert cq is not None
        if b == "numpy":
            return _numpy_values(cq, xs)
        if b == "mpmath":
            return _mpmath_values(cq, xs, int(self.options.get("dps", 50)))
        if b in ("numba", "certified"):
            if not HAVE_NUMBA:
                return _numpy_values(cq, xs) if b == "numba" else _numpy_signs(cq, xs)
            shape = np.shape(xs[0]) if xs else ()
            P = np.ascontiguousarray(np.stack([x.reshape(-1) for x in xs])) if xs else np.empty((0, 1))
            n = P.shape[1] if xs else 1
            out = np.empty(n, dtype=np.float64 if b == "numba" else np.int8)
            _numba_kernel(cq, "value" if b == "numba" else "sign")(P, out)
            return out.reshape(shape)
        raise AssertionError(b)

    def __repr__(self) -> str:
        return f"FamilyFunction({self.name!r}, backend={self.backend!r}, parameters={self.family.parameters})"


def lambdify(fam: Family, name: str, backend: str = "numpy", **options: Any) -> FamilyFunction:
    """A vectorised function of parameter arrays for the quantity ``name`` of ``fam``.

    Parameters
    ----------
    fam : Family
    name : str
        A key of :attr:`Family.quantities` (``"c0" .. "c4"``, ``"Delta2" .. "Delta4"``, ...).
    backend : {"numpy", "numba", "mpmath", "certified", "exact"}
        See the module docstring.  ``"certified"`` returns int8 signs (``2`` uncertain).
    dps : int, optional
        Digits for ``"mpmath"`` (default 50).

    Returns
    -------
    FamilyFunction

    Examples
    --------
    >>> from quadric_contact import family
    >>> fam = family("(x - u)^2 + y^2 + 3*(z - w)^2 - 0.1", "x^2 + y^2 - 0.25*(z - 3)^2 - 1", "u w")
    >>> d4 = fam.lambdify("Delta4")
    >>> float(d4(3.0, 5.5)) == float(fam.evaluate("Delta4", u=3, w=5.5))
    True

    The certified signs: apart, crossing (``Delta_4 < 0``), and on the trunk's axis, where
    the pencil has a double root (``Delta_4 = 0`` exactly):

    >>> fam.lambdify("Delta4", backend="certified")([3.0, 1.0, 0.0], [5.5, 3.0, 3.0])
    array([ 1, -1,  0], dtype=int8)
    """
    if backend not in BACKENDS:
        raise ChoiceError(
            f"backend must be one of {', '.join(BACKENDS)}, got {backend!r}", backend, choices=tuple(BACKENDS)
        )
    q = fam.quantity(name)  # ChoiceError with the names if unknown
    if backend == "exact":
        return FamilyFunction(fam, name, backend, None, **options)
    cache = fam.__dict__.setdefault("_compiled", {})
    cq = cache.get(name)
    if cq is None:
        cq = cache[name] = compile_quantity(name, q.value, len(fam.parameters))
    return FamilyFunction(fam, name, backend, cq, **options)
