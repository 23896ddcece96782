"""Numeric lambdas of a family's quantities: vectorised functions of parameter arrays.

Each exact quantity of a :class:`~quadric_contact.family.Family` is ``num / den`` with
``num, den`` in Q[parameters].  Both are scaled to primitive integer polynomials (a positive
rational factor is kept apart) and emitted by the package's code generator
(:func:`quadric_contact.codegen.emit_program`: nested Horner form, subexpressions shared
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
    ``|fl(p) - p| <= K M`` of :func:`quadric_contact.modes.errorbounds.program_errbound`
    for each of numerator and denominator; ``-1, 0, 1`` where the bound decides it and
    ``2`` (``UNCERTAIN``) where it does not, at a pole, or outside the guarded range
    (below) -- an int8 array;
``"exact"``
    the exact value (:class:`~fractions.Fraction`) at each point, point by point with
    python-flint (the reference the others are measured against).

The certified backend's guards follow :mod:`quadric_contact.modes.errorbounds`: a non-zero
input at least ``2^e_min`` in magnitude is a multiple of ``2^(e_min - 52)``, so every
non-zero intermediate of a degree-``D`` program is at least ``2^(D (e_min - 52))``, chosen
normal with room for the bound ``K M``; inputs at most ``2^e_max`` keep every intermediate
below ``path_bound * 2^(D e_max) < 2^1021``.  A point with an input outside (or NaN) is
``UNCERTAIN``.  Large integer constants of the program (beyond ``2^53``) count as rounded
operands in the rounding counts.

The generated text is compiled only after it has been checked to be in the grammar of the
generated modules (assignments of ``+ - *`` over names and integer literals): the names are
the program's own (``p0, p1, ...``, ``t0, ...``), never the user's, and the numbers come from
the exact polynomials.
"""

from __future__ import annotations

import ast
import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import TYPE_CHECKING, Any

import numpy as np

from .codegen import EXACT_INTEGER_MAX, Program, _functions, _print_expr, _straight_line, emit_program
from .modes.errorbounds import program_errbound

if TYPE_CHECKING:
    from .family import Family, RationalFunction

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
    input_min: float
    input_max: float
    functions: dict[str, Any]

    @property
    def source(self) -> str:
        return self.program.source


def _guards(program: Program, bounds: tuple[float, ...]) -> tuple[float, float]:
    """``(input_min, input_max)`` for the certified backend (see the module docstring)."""
    D = max(program.degree, default=0)
    if D == 0:
        return 0.0, math.inf
    positive = [b for b in bounds if b > 0]  # K = 0: no rounding at all (a single input, say)
    k_exp = math.floor(math.log2(min(positive))) if positive else 0
    q = math.ceil((-1022 - k_exp + 2) / D)  # D q + log2(K) >= -1020: intermediates and K M normal
    e_min = min(q + 52, 0)
    room = 1020 - math.log2(max(program.path_bound, 1)) - 1  # (1 + u)^N < 2 for the roundings
    if room <= 0:
        raise OverflowError("the program's coefficients are too large for binary64")
    e_max = math.floor(room / D)
    return 2.0**e_min, 2.0**e_max


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
    program = emit_program(
        "quantity", args, outputs, doc=f"{name}: generated by quadric_contact.family_numeric."
    )
    if program.path_bound >= 2**1000:
        raise OverflowError(f"{name}: coefficients beyond the range of binary64")
    _checked(program.source)
    bounds = tuple(
        program_errbound(nv, nm, d)
        for nv, nm, d in zip(program.value_counts, program.magnitude_counts, program.degree, strict=True)
    )
    lo, hi = _guards(program, bounds)
    functions = _compile_source(program.source, {"__builtins__": {}})
    return CompiledQuantity(
        name,
        program,
        scale,
        has_den,
        bounds,
        lo,
        hi,
        {k: v for k, v in functions.items() if k != "__builtins__"},
    )


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


def _sign_kernel_source(nparams: int, bounds: tuple[float, ...], lo: float, hi: float) -> str:
    lines = ["def kernel(P, out):", "    for i in range(out.shape[0]):", "        ok = True"]
    for k in range(nparams):
        lines += [
            f"        a{k} = abs(P[{k}, i])",
            f"        if not (a{k} == 0.0 or ({lo!r} <= a{k} and a{k} <= {hi!r})):",
            "            ok = False",
        ]
    lines += ["        if not ok:", f"            out[i] = {UNCERTAIN}", "            continue"]
    xs = ", ".join(f"P[{k}, i]" for k in range(nparams))
    axs = ", ".join(f"a{k}" for k in range(nparams))
    lines += [f"        r = quantity({xs})", f"        m = quantity_magnitude({axs})", "        s = 1"]
    for j, K in enumerate(bounds):
        lines += [
            f"        b = {K!r} * m[{j}]",
            f"        if r[{j}] > b:",
            "            sj = 1",
            f"        elif r[{j}] < -b:",
            "            sj = -1",
            f"        elif m[{j}] == 0.0:",
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


_BIG_LITERAL = re.compile(r"(?<![A-Za-z_0-9.])([0-9]{16,})(?![0-9.])")


def _float_literals(source: str) -> str:
    """The program with every integer literal beyond ``EXACT_INTEGER_MAX`` written as the
    binary64 number nearest to it."""

    def repl(m: re.Match[str]) -> str:
        k = int(m.group(1))
        return repr(float(k)) if k > EXACT_INTEGER_MAX else m.group(1)

    return _BIG_LITERAL.sub(repl, source)


def _numba_kernel(cq: CompiledQuantity, kind: str) -> Any:
    key = f"numba_{kind}"
    if key in cq.functions:
        return cq.functions[key]
    import numba

    # numba types integer literals as int64: a constant beyond 2^53 becomes its binary64
    # rounding (which the rounding counts already charge; numpy rounds it the same way).
    program = _compile_source(_float_literals(cq.program.source), {"__builtins__": {}})
    ns: dict[str, Any] = {
        "quantity": numba.njit(program["quantity"]),
        "quantity_magnitude": numba.njit(program["quantity_magnitude"]),
    }
    nparams = len(cq.program.args)
    if kind == "value":
        source = _value_kernel_source(nparams, cq.has_denominator, float(cq.scale))
    else:
        source = _sign_kernel_source(nparams, cq.error_bounds, cq.input_min, cq.input_max)
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
    ok = np.ones(shape, dtype=bool)
    for x in xs:
        a = np.abs(x)
        ok &= (a == 0.0) | ((a >= cq.input_min) & (a <= cq.input_max))
    safe = [np.where(ok, x, 0.0) for x in xs]
    r = cq.functions["quantity"](*safe)
    m = cq.functions["quantity_magnitude"](*[np.abs(x) for x in safe])
    out = np.full(shape, UNCERTAIN, dtype=np.int8)
    signs = []
    for j, K in enumerate(cq.error_bounds):
        v = np.asarray(r[j] * np.ones(shape))
        mj = np.asarray(m[j] * np.ones(shape))
        b = K * mj
        sj = np.full(shape, UNCERTAIN, dtype=np.int8)
        sj[mj == 0.0] = 0
        sj[v > b] = 1
        sj[v < -b] = -1
        signs.append(sj)
    s = signs[0]
    if len(signs) == 2:
        d = signs[1]
        bad = (d == 0) | (d == UNCERTAIN) | (s == UNCERTAIN)
        s = np.where(bad, UNCERTAIN, s * d).astype(np.int8)
    out[ok] = s[ok]
    return out


def _mpmath_values(cq: CompiledQuantity, xs: list[np.ndarray], dps: int) -> np.ndarray:
    import mpmath

    with mpmath.workdps(dps):
        to_mpf = np.frompyfunc(mpmath.mpf, 1, 1)
        ys = [to_mpf(np.asarray(x, dtype=np.float64)) for x in xs]
        r = cq.functions["quantity"](*ys)
        scale = mpmath.mpf(cq.scale.numerator) / cq.scale.denominator
        out = scale * (r[0] / r[1] if cq.has_denominator else r[0])
        shape = np.shape(xs[0]) if xs else ()
        return np.asarray(out, dtype=object) * np.ones(shape, dtype=object)


def _exact_values(value: RationalFunction, xs: list[np.ndarray]) -> np.ndarray:
    import flint

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
            from .modes._jit import HAVE_NUMBA

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
        raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
    q = fam.quantity(name)  # KeyError with the names if unknown
    if backend == "exact":
        return FamilyFunction(fam, name, backend, None, **options)
    cache = fam.__dict__.setdefault("_compiled", {})
    cq = cache.get(name)
    if cq is None:
        cq = cache[name] = compile_quantity(name, q.value, len(fam.parameters))
    return FamilyFunction(fam, name, backend, cq, **options)
