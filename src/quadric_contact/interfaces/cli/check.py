"""``quadric-contact check E Q``: a readable, auditable report for one pair."""

from __future__ import annotations

import argparse
import json
from fractions import Fraction
from typing import Any

from quadric_contact.exact.printing import fraction_text, int_text
from quadric_contact.interfaces.cli.exits import EXIT_OK, EXIT_UNDECIDED
from quadric_contact.model.classification import QuadricKind
from quadric_contact.theory.contact_kind import ContactKind, analyze_contact
from quadric_contact.theory.pencil import as_quadric, characteristic_polynomial
from quadric_contact.theory.plane import plane_side_exact as plane_side
from quadric_contact.theory.regions import decide_region

DEFAULT_E = "(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1"
DEFAULT_Q = "x**2 + y**2 - 0.25*(z-3)**2 - 1"


def register(sub: Any) -> None:
    p = sub.add_parser(
        "check",
        help="contact and relative position of an ellipsoid E and a quadric Q",
        description="Decide exactly whether E and Q are in transversal contact and where E lies "
        "(defaults: the bee and the hyperboloid S2 of Example 17). Exit status: 0 decided, "
        "3 undecided by the theory, 2 bad input.",
    )
    p.add_argument(
        "E",
        nargs="?",
        default=DEFAULT_E,
        help="equation of the ellipsoid in x, y, z (numbers, + - * / ** ^, parentheses, one =; "
        "products written with *)",
    )
    p.add_argument("Q", nargs="?", default=DEFAULT_Q, help="equation of the other quadric (or a plane)")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of the report")
    p.add_argument(
        "--small",
        choices=("auto", "yes", "no"),
        default="auto",
        help="decide smallness (auto) or assert it",
    )
    p.add_argument(
        "--method",
        choices=("auto", "theory"),
        default="auto",
        help="'theory' uses only the paper's results; 'auto' adds the exact geometric decision",
    )
    p.set_defaults(func=run)


def _fmt(x: Fraction) -> str:
    if x.denominator == 1:
        return int_text(x.numerator)
    try:
        approx = f"{float(x):.6g}"
    except OverflowError:  # beyond the range of a float
        approx = "-inf" if x < 0 else "inf"
    return f"{fraction_text(x)}  (~ {approx})"


def _touching(analysis: Any) -> str:
    """One line for the kind of contact (Table 3) with the tangent points, for every type of Q."""
    kind = analysis.kind
    where = ", ".join("(" + ", ".join(str(c) for c in point) + ")" for point in _points(analysis))
    text = {
        ContactKind.NONE: "no (the surfaces do not touch)",
        ContactKind.TRANSVERSAL: "the surfaces cross (transversal contact)",
        ContactKind.TANGENT_POINT: f"yes, tangent at one point {where}",
        ContactKind.TWO_TANGENT_POINTS: f"yes, tangent at two points {where}",
        ContactKind.TANGENT_CURVE: "yes, along a curve of tangency",
    }.get(kind, str(kind))
    if kind is ContactKind.TRANSVERSAL and where:
        text += f", and tangent at {where}"
    return f"touching: {text} (Table 3: {kind.value}, Segre {analysis.segre})"


def _points(analysis: Any) -> list[tuple[str, ...]]:
    """The tangent points, exact, as the report's JSON writes them (each once)."""
    seen: list[tuple[str, ...]] = []
    for member in analysis.to_dict()["members"]:
        for point in member["points"]:
            if tuple(point) not in seen:
                seen.append(tuple(point))
    return seen


def run(args: argparse.Namespace) -> int:
    E = as_quadric(args.E, "E")
    Q = as_quadric(args.Q, "Q")
    small = {"auto": None, "yes": True, "no": False}[args.small]
    out: dict[str, Any] = {
        "E": {"equation": E.equation(), "kind": E.kind.value},
        "Q": {"equation": Q.equation(), "kind": Q.kind.value},
    }
    if Q.kind is QuadricKind.PLANE:
        side = plane_side(E, Q)
        out["plane_side"] = side.to_dict()
        decided = True
        P = side.polynomial
    else:
        P = characteristic_polynomial(E, Q)
        region = decide_region(P, small=small, method=args.method)
        assert region.contact is not None  # the exact path always attaches it
        out["contact"] = region.contact.to_dict()
        out["region"] = region.to_dict()
        decided = region.decided
    analysis = analyze_contact(E, Q, small=small)
    out["contact_kind"] = analysis.to_dict()
    if args.json:
        print(json.dumps(out, indent=2, default=str))
        return EXIT_OK if decided else EXIT_UNDECIDED
    lines = [
        f"E: {E.kind.value}: {E.equation()} = 0"
        + ("   (matrix negated so that det E < 0)" if P.e_flipped else ""),
        f"Q: {Q.kind.value}: {Q.equation()} = 0",
        f"P(lambda) = det(lambda E + Q) = {P}",
    ]
    d2, d3, d4 = P.deltas()
    lines += [
        f"  Delta3 = {_fmt(d3)}",
        f"  Delta4 = {_fmt(d4)}",
        f"  roots: {P.structure.describe()}; signs {P.signs.pattern} ({P.signs.method})",
    ]
    if Q.kind is QuadricKind.PLANE:
        assert side.zone is not None  # the exact path always decides
        lines += [f"zone: {side.zone.value} (Algorithm 1 zone {side.algorithm_1_zone}); {side}"]
    else:
        c = region.contact
        assert c is not None
        if c.smallness is not None:
            verdict = getattr(c.smallness, "small", c.smallness)
            lines.append(f"smallness: {verdict}")
        lines.append(f"transversal contact: {c}")
        lines.append(f"region: {region}")
    lines.append(_touching(analysis))
    print("\n".join(lines))
    return EXIT_OK if decided else EXIT_UNDECIDED
