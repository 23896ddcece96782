"""Reading equations and numbers: the package's parser against the sympy reader it replaced.

Measures the time per text of

* ``Quadric.from_equation`` (the package's tokenizer, recursive-descent parser
  and exact polynomial evaluation, :mod:`quadric_contact.exact.reading`), and
* the peer: the sympy-based reader the package used before (``parse_expr``
  with implicit multiplication, ``^``, rationalised decimals, then
  ``sympy.Poly``), kept here, and only here, as a private copy,

on the equations of the README, the documentation and the built-in scenes, on random quadrics
(printed in several spellings), and on numbers (``to_fraction`` against the old
``Fraction``-then-``sympify`` path).  Both readers must give the same exact
matrix for every text, or the run stops.  Last, the slowest inputs the bounds
admit (``MAX_LENGTH`` characters of the costliest shapes) are timed with the
package's parser alone: the old reader runs code and hangs on some of them.

Run: ``PYTHONPATH=src python benchmarks/bench_parsing.py [--quadrics N] [--seed S]``.
The figures depend on the machine: re-measure rather than quote them.
"""

from __future__ import annotations

import argparse
import random
import re
import time
from collections.abc import Callable, Sequence
from fractions import Fraction
from importlib import resources
from pathlib import Path
from typing import Any

from quadric_contact import Quadric
from quadric_contact.exact.errors import QuadricContactError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.exact.reading import MAX_DEPTH, MAX_LENGTH
from quadric_contact.model.parsing import parse_quadric_equation

ROOT = Path(__file__).resolve().parents[1]

# -- the peer: the sympy-based reader this package used before -------------------------------


def _old_upper(text: str) -> tuple[Fraction, ...]:
    """The old ``Quadric.from_equation`` on a string, as the ten upper entries.

    Private to this benchmark: ``parse_expr`` evaluates its input as Python,
    so it must never see untrusted text.  The benchmark gives it only the
    texts it generates itself.
    """
    import sympy
    from sympy.parsing.sympy_parser import (
        convert_xor,
        implicit_multiplication_application,
        parse_expr,
        rationalize,
        standard_transformations,
    )

    x, y, z = sympy.symbols("x y z")
    names = {"x": x, "y": y, "z": z}
    allowed = {
        name: getattr(sympy, name)
        for name in ("Integer", "Rational", "Float", "Symbol", "Number", "sqrt", "Mul", "Add", "Pow")
    }
    transformations = (
        *standard_transformations,
        implicit_multiplication_application,
        convert_xor,
        rationalize,
    )
    sides = text.strip().split("=")
    parts = [
        parse_expr(s, local_dict=dict(names), global_dict=dict(allowed), transformations=transformations)
        for s in sides
    ]
    expr = parts[0] - parts[1] if len(parts) == 2 else parts[0]
    poly = sympy.Poly(sympy.expand(expr), x, y, z)
    if poly.total_degree() > 2:
        raise ValueError("degree")

    def c(m: Any) -> Fraction:
        v = poly.coeff_monomial(m)
        return Fraction(int(v.p), int(v.q))

    h = Fraction(1, 2)
    return (
        c(x**2),
        c(x * y) * h,
        c(x * z) * h,
        c(x) * h,
        c(y**2),
        c(y * z) * h,
        c(y) * h,
        c(z**2),
        c(z) * h,
        c(1),
    )


def _old_number(text: str) -> Fraction:
    """The old ``to_fraction`` on a string: ``Fraction(text)``, else ``sympify``."""
    import sympy

    try:
        return Fraction(text.strip().replace("_", ""))
    except (ValueError, ZeroDivisionError):
        pass
    v = sympy.sympify(text, rational=True)
    return Fraction(int(v.p), int(v.q))


# -- the texts ----------------------------------------------------------------------------------


def readme_equations() -> list[str]:
    """Equation strings of the README, of the documentation's pages and of the built-in scenes."""
    texts = [(ROOT / "README.md").read_text()] + [p.read_text() for p in sorted((ROOT / "docs").glob("*.md"))]
    found = []
    for text in texts:
        found += re.findall(r'(?:from_equation|analyze_contact|plane_side)\((?:[a-z]+, )?"([^"]+)"', text)
        found += re.findall(r'analyze_contact\("[^"]+", "([^"]+)"\)', text)
    folder = resources.files("quadric_contact").joinpath("scenes")
    for f in folder.iterdir():
        if f.name.endswith(".toml"):
            found += re.findall(r'^equation = "([^"]+)"', f.read_text(), flags=re.M)
            found += re.findall(r'plane = "([^"]+)"', f.read_text())
    readable = []
    for text in dict.fromkeys(found):
        try:
            parse_quadric_equation(text)
        except QuadricContactError:
            continue  # the README's examples of refusals
        readable.append(text)
    return readable


def _coefficient(rng: random.Random) -> Fraction:
    return Fraction(rng.randint(-999, 999), rng.choice([1, 1, 1, 2, 3, 4, 7, 10, 100]))


def _number_text(c: Fraction, rng: random.Random) -> str:
    if c.denominator in (1, 2, 4, 10, 100) and rng.random() < 0.5:
        return str(c.numerator * 100 // c.denominator / 100) if (c * 100).denominator == 1 else str(c)
    return str(c) if c.denominator == 1 else f"{c.numerator}/{c.denominator}"


def random_quadrics(n: int, seed: int) -> list[str]:
    """Random quadrics, half written out term by term, half as scaled squares
    about a centre (``a*(x - p)^2 + ...``), with ``**`` or ``^`` and random spacing."""
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        power = rng.choice(["**", "^"])
        sp = rng.choice(["", " "])
        if rng.random() < 0.5:
            monomials = ["x{p}2", "x*y", "x*z", "x", "y{p}2", "y*z", "y", "z{p}2", "z", ""]
            terms = []
            for m in monomials:
                c = _coefficient(rng)
                if c == 0 or rng.random() < 0.3:
                    continue
                body = m.format(p=power)
                num = _number_text(abs(c), rng)
                text = f"{num}*{body}" if body else num
                terms.append(("-" if c < 0 else "+") + sp + text)
            eq = sp.join(terms).lstrip("+ ") or "0"
        else:
            parts = []
            for v in "xyz":
                a, p = _coefficient(rng), _coefficient(rng)
                sign = "-" if p >= 0 else "+"
                parts.append(f"{_number_text(a, rng)}*({v}{sp}{sign}{sp}{_number_text(abs(p), rng)}){power}2")
            eq = f"{sp}+{sp}".join(parts) + f" = {_number_text(abs(_coefficient(rng)), rng)}"
        out.append(eq)
    return out


def numbers(n: int, seed: int) -> list[str]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        kind = rng.random()
        if kind < 0.4:
            out.append(f"{rng.randint(-(10**6), 10**6) / 1000:.3f}")
        elif kind < 0.7:
            out.append(f"{rng.randint(-999, 999)}/{rng.randint(1, 999)}")
        elif kind < 0.9:
            out.append(f"{rng.randint(1, 99)}e-{rng.randint(1, 9)}")
        else:
            out.append(f"{rng.randint(1, 9)}/{rng.randint(1, 9)} + {rng.randint(1, 9)}/{rng.randint(1, 9)}")
    return out


def slowest_inputs() -> list[tuple[str, str]]:
    """The costliest shapes the bounds admit, each filled to ``MAX_LENGTH``."""

    def fill(unit: str, tail: str = "1") -> str:
        return unit * ((MAX_LENGTH - len(tail)) // len(unit)) + tail

    return [
        ("a sum of ones", fill("1+")),
        ("a sum of squares", fill("x^2 + ")),
        ("a sum of products", fill("x*y - ")),
        ("degree-8 products (work bound)", fill("(x + y + z + 1)^4*(x - y + z - 1)^4 - ")),
        ("squares of sums (work bound)", fill("(x + y + z + 1/3)^2 + ")),
        ("big powers (work bound)", fill("3**600/7**400 + ")),
        ("a chain of divisions (digit bound)", fill("7/", "7")),
        ("decimals", fill("0.123456789 + ")),
        ("1000-digit literals", fill("9" * 999 + " + ")),
        ("nesting at MAX_DEPTH", fill("(" * MAX_DEPTH + "x" + ")" * MAX_DEPTH + " + ")),
        ("unary signs", fill("-" * (MAX_DEPTH - 1) + "x + ")),
        ("a chained power", "x**2 + " + "9**9**9"),
        ("too long", "x" * (10 * MAX_LENGTH)),
        ("unknown names", fill("x2 + ")),
        # runs that a scanning tokenizer retried at every position (quadratic: 0.4-0.8 s)
        ("blanks then a bad character", " " * (MAX_LENGTH - 1) + "!"),
        ("tabs then a bad character", "\t" * (MAX_LENGTH - 1) + "!"),
        ("digits then a bare exponent", "1" * (MAX_LENGTH - 1) + "e"),
        ("digits then a dangling underscore", "1" * (MAX_LENGTH - 1) + "_"),
        ("a decimal then a bare exponent", "." + "1" * (MAX_LENGTH - 2) + "e"),
    ]


# -- timing --------------------------------------------------------------------------------------


def per_item(fn: Callable[[str], Any], texts: Sequence[str], repeat: int) -> float:
    """Best-of-``repeat`` mean time per text, in microseconds."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        for t in texts:
            fn(t)
        best = min(best, (time.perf_counter() - t0) / len(texts))
    return best * 1e6


def main(argv: Sequence[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    ap.add_argument("--quadrics", type=int, default=10_000, help="random quadrics (default 10000)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    args = ap.parse_args(argv)

    # the slowest admitted inputs first, before the peer fills the heap with sympy's caches
    print(f"slowest admitted inputs, package parser only (MAX_LENGTH = {MAX_LENGTH}; the bound is 100 ms);")
    print(f"best and worst of {args.repeat + 2} runs:")
    print(f"{'input':<36} {'chars':>7} {'best ms':>8} {'worst ms':>9}  outcome")
    worst = 0.0
    for name, text in slowest_inputs():
        times = []
        for _ in range(args.repeat + 2):
            t0 = time.perf_counter()
            try:
                parse_quadric_equation(text)
                outcome = "read"
            except QuadricContactError as exc:
                outcome = "refused: " + str(exc).splitlines()[0][:58]
            times.append((time.perf_counter() - t0) * 1e3)
        worst = max(worst, max(times))
        print(f"{name:<36} {len(text):>7} {min(times):>8.2f} {max(times):>9.2f}  {outcome}")
    print(f"slowest single run: {worst:.1f} ms")

    suites = {
        "README and scene equations": readme_equations(),
        f"{args.quadrics} random quadrics": random_quadrics(args.quadrics, args.seed),
    }
    print()
    for name, texts in suites.items():
        for t in texts:
            new, old = parse_quadric_equation(t), _old_upper(t)
            if new != old:
                raise SystemExit(f"the readers disagree on {t!r}: {new} != {old}")
        print(f"checked: both readers give the same exact matrix on the {len(texts)} texts of {name!r}")
    nums = numbers(2000, args.seed)
    for t in nums:
        if to_fraction(t) != _old_number(t):
            raise SystemExit(f"the number readers disagree on {t!r}")
    print("checked: both number readers agree on 2000 numbers")

    print()
    print(f"{'texts':<34} {'n':>6} {'parser us':>10} {'sympy us':>10} {'ratio':>7}")
    rows = [
        (name, texts, lambda t: Quadric.from_equation(t), _old_upper) for name, texts in suites.items()
    ] + [("2000 numbers (to_fraction)", nums, to_fraction, _old_number)]
    for name, texts, new_fn, old_fn in rows:
        repeat = args.repeat if len(texts) <= 2000 else 1
        t_new = per_item(new_fn, texts, repeat)
        t_old = per_item(old_fn, texts, repeat)
        print(f"{name:<34} {len(texts):>6} {t_new:>10.1f} {t_old:>10.1f} {t_old / t_new:>6.0f}x")


if __name__ == "__main__":
    main()
