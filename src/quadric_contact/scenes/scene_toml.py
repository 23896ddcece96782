"""Scenes: objects, moving ellipsoids, a time span and the effects wanted, read from TOML.

A scene file (TOML; numbers are read *exactly*: ``5.5`` is ``11/2``, and a
string such as ``"1/3"`` or ``"8.36291"`` is accepted wherever a number is;
every number and every equation is read by the package's own parser,
:mod:`quadric_contact.exact.reading`, never evaluated)::

    [scene]
    name = "The bee and the tree (Example 17)"
    time = [0, 8]                      # the time span
    effects = ["zone", "contact", "relative_position", "first_contact"]
    on_not_small = "refuse"            # or "warn" (see below)
    places = 12                        # decimal places printed for event times
    reading = "geometry"               # or "paper" (see below)
    distance_tolerance = "1/1000"      # for the distance effect (see below)
    distance_evaluations = 400

    [[object]]
    name = "tree"
    tree = { plane = "z = 6", plus = "crown", minus = "trunk" }

    [[object.piece]]
    name = "crown"
    equation = "x^2 + y^2 + 3*(z - 8.36291)^2 = 20"

    [[object.piece]]
    name = "trunk"
    equation = "x^2 + y^2 - 0.25*(z - 3)^2 = 1"

    [[ellipsoid]]
    name = "bee"
    equation = "(x - 3)^2 + (y - 3)^2 + 3*(z - 5.5)^2 = 0.1"
    motion = { type = "keyframes", keys = [
        { t = 0, at = [3, 3, 5.5] },
        { t = 2, at = [1.2, 0, 5], rotation = [1, 0, 0, 0] } ] }

Quadrics (pieces and ellipsoids) are given by exactly one of
``equation = "..."`` (in ``x, y, z``; ``"lhs = rhs"`` allowed, ``^`` is a
power, products are written with ``*``: the grammar is in
:mod:`quadric_contact.exact.reading`),
``matrix = [[...], ...]`` (symmetric 4x4), ``standard = "<type>"`` with
``a``, ``b``, ``c`` (the forms of Table 1, e.g. ``"hyperboloid of one
sheet"``), ``standard = "ellipsoid"`` with ``semi_axes = [a, b, c]``,
``standard = "sphere"`` with ``radius``, or ``standard = "plane"`` with
``normal`` and ``offset`` (``n . x = offset``; ``R-`` is ``n . x <= offset``).
Optional ``rotation = [w, x, y, z]`` (a rational quaternion, applied about the
origin) then ``center = [x, y, z]`` (a translation) place a standard form.
A piece may say which of its regions is the object's inside: ``inside = "R-"``
(default) or ``"R+"``.

An object is one ``[[object]]`` with ``[[object.piece]]`` s and an optional
``tree``: a plane with what lies on its ``plus`` (``R+``, Zone 1) and
``minus`` (``R-``, Zone 2) side, each a piece name, another ``{ plane = ...,
plus = ..., minus = ... }`` or absent (nothing there).  Without a tree every
piece is checked everywhere.

Motions (``[ellipsoid.motion]``; the default is ``type = "still"``):

``type = "linear"``
    ``velocity = [vx, vy, vz]``; the centre is at its initial place at
    ``start`` (default the start of the span).
``type = "polynomial"``
    ``translation = [[x0, x1, ...], [y0, ...], [z0, ...]]``: the centre's
    displacement ``sum x_k t^k``; optional ``quaternion = [[w0, w1, ...],
    [x...], [y...], [z...]]``: the rotation about the centre of the
    quaternion with these polynomial components.  A component may also be
    written as a polynomial in ``t`` (``"2*t - 5*t^2"``, degree at most
    :data:`~quadric_contact.exact.bounds.MAX_MOTION_DEGREE`).
``type = "keyframes"``
    ``keys = [{ t = ..., at = [x, y, z], rotation = [w, x, y, z] }, ...]``:
    the centre passes through ``at`` at time ``t`` (linear in between);
    ``rotation`` (optional) is the orientation relative to the initial one,
    interpolated linearly in the quaternion's components.

Effects: ``zone`` (Algorithm 1), ``contact`` (Algorithm 2),
``contact_kind`` (Table 3), ``relative_position`` (Table 4),
``first_contact``, ``smallness`` (report the smallness of every moving
ellipsoid with respect to every piece), ``distance`` (the least signed
distance of each moving ellipsoid from each piece's solid over the time span,
and when it is reached: :mod:`quadric_contact.scenes.scene_distance`).  Only
what they need is computed.

The ``distance`` effect encloses the least distance in ``[lo, hi]`` with
``hi - lo <= distance_tolerance`` (in the scene's units, default ``1/1000``,
at least :data:`~quadric_contact.exact.bounds.MIN_DISTANCE_TOLERANCE`),
evaluating at most ``distance_evaluations`` distances per (ellipsoid, piece)
(default 400, at most
:data:`~quadric_contact.exact.bounds.MAX_DISTANCE_EVALUATIONS`); where the
budget runs out first the report gives the enclosure reached and says so.
It is not available, and the report says why, for an ellipsoid whose
orientation changes, a piece cut by planes of its object's tree, and a
piece whose inside is not the solid of its quadric.

Only what the scene asks for, per object: an optional ``[effects]`` table
narrows the effects for some ellipsoids and pieces::

    [effects]
    ellipsoids = { scout = ["zone", "contact", "relative_position"], worker = ["first_contact"] }
    pieces = { "tree/crown" = ["contact", "first_contact"] }

Each list replaces the scene's effects for that ellipsoid or piece; a pair
(ellipsoid, piece) gets the effects that the scene, the ellipsoid and the
piece all ask for, and the work ledger compares what was done with every
effect computed everywhere.

Smallness (Tables 1, 2) of each moving ellipsoid with respect to each
quadric piece is checked when the scene is loaded, if its effects rely on
Theorem 2; ``on_not_small = "refuse"`` rejects a scene where it fails,
``"warn"`` keeps it, with a warning, and the contact where all roots are real
is then reported as undecided.

``mutual = true`` (or a list of ellipsoid names) asks for the contacts of the
moving ellipsoids with each other, at exact times
(:mod:`quadric_contact.scenes.mutual`).

A piece is the part of its quadric on the kept side of every plane on its
path in the object's tree: the ellipsoid is in contact with it where it
crosses the surface *as cut* (``reading = "geometry"``, the default).
``reading = "paper"`` keeps the reading of Algorithm 1, where a piece whose
zone the ellipsoid reaches counts as its whole quadric (Example 17).

Names are unique: two pieces of one object, and two objects or
ellipsoids of a scene (an object and an ellipsoid included), never share one.

Every error names the file, the key and what was expected
(:class:`~quadric_contact.exact.errors.SceneError`).
"""

from __future__ import annotations

import os
import stat
import tomllib
from collections.abc import Mapping, Sequence
from fractions import Fraction
from importlib import resources
from pathlib import Path
from typing import Any

from quadric_contact.exact.bounds import MAX_MOTION_DEGREE, MAX_PLACES, MAX_SCENE_BYTES, MAX_SCENE_DEPTH
from quadric_contact.exact.errors import QuadricContactError, SceneError
from quadric_contact.exact.printing import safe_text, unsafe_characters
from quadric_contact.exact.rational import to_fraction
from quadric_contact.exact.reading import MAX_DIGITS, parse_number, parse_univariate
from quadric_contact.model.classification import QuadricKind
from quadric_contact.model.quadric import Quadric
from quadric_contact.scenes.composite import Composite, Piece, Split
from quadric_contact.scenes.scene_model import (
    DISTANCE_EVALUATIONS,
    DISTANCE_TOLERANCE,
    EFFECTS,
    EXCLUDED_KINDS,
    READINGS,
    MovingEllipsoid,
    Scene,
    check_on_not_small,
    distance_options,
)
from quadric_contact.scenes.trajectory import (
    Keyframes,
    PolynomialMotion,
    Stationary,
    Trajectory,
)
from quadric_contact.theory.results import Region

__all__ = ["builtin_scene", "builtin_scene_names", "load_scene", "parse_scene", "read_scene_file"]


class _BadFloat:
    """A TOML float that is not a finite number (inf, nan) or is beyond the number
    parser's bounds, kept for the error message."""

    def __init__(self, text: str, reason: str = "") -> None:
        self.text = text
        self.reason = reason

    def __repr__(self) -> str:
        return self.text


def _nesting_depth(text: str) -> int:
    """An upper bound of how deep arrays and inline tables nest in TOML ``text``:
    the deepest run of open ``[`` / ``{`` not yet closed, counted outside strings
    and comments, in one pass (``tomllib`` reads nesting by recursion, so a deep
    enough file would raise :class:`RecursionError` in it)."""
    depth = deepest = 0
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c == "#":
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        if c in "\"'":
            triple = text.startswith(c * 3, i)
            quote = c * 3 if triple else c
            i += len(quote)
            while i < n and not text.startswith(quote, i):
                if c == '"' and text[i] == "\\":
                    i += 1
                elif not triple and text[i] == "\n":
                    break
                i += 1
            i += len(quote)
            continue
        if c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth = max(0, depth - 1)
        i += 1
    return deepest


def _parse_float(text: str) -> Any:
    """A TOML float, read exactly by the package's number parser (bounded:
    ``1e99999999`` is refused, not computed)."""
    if text.lstrip("+-") in ("inf", "nan"):
        return _BadFloat(text, "not finite")
    try:
        return parse_number(text)
    except QuadricContactError as exc:
        return _BadFloat(text, str(exc).splitlines()[0])


_MISSING = object()


def _show(value: Any) -> str:
    if isinstance(value, Fraction):
        return str(value)
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        if not value:
            return "an empty list"
        if len(value) <= 8 and all(isinstance(v, (int, Fraction, str, _BadFloat)) for v in value):
            return "[" + ", ".join(_show(v) for v in value) + "]"
        return "a list"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    return repr(value)


class _Reader:
    def __init__(self, source: str) -> None:
        self.source = source

    def error(self, key: str, expected: str, got: Any = _MISSING, cause: str = "") -> SceneError:
        msg = f"{self.source}: {key}: expected {expected}"
        if got is not _MISSING:
            msg += f", got {_show(got)}"
        if cause:
            msg += f" ({cause})"
        return SceneError(msg, None if got is _MISSING else got, file=self.source, key=key, expected=expected)

    def keys(self, table: Mapping[str, Any], key: str, allowed: Sequence[str]) -> None:
        for k in table:
            if k not in allowed:
                where = f"{key}.{k}" if key else k
                raise self.error(where, f"one of the keys {', '.join(allowed)}", cause=f"unknown key {k!r}")

    def table(self, parent: Mapping[str, Any], name: str, key: str, required: bool = True) -> dict[str, Any]:
        v = parent.get(name, _MISSING)
        if v is _MISSING:
            if required:
                raise self.error(key, "a table", cause="missing")
            return {}
        if not isinstance(v, dict):
            raise self.error(key, "a table", v)
        return v

    def array_of_tables(self, parent: Mapping[str, Any], name: str, key: str) -> list[dict[str, Any]]:
        v = parent.get(name, _MISSING)
        if v is _MISSING:
            raise self.error(key, f"at least one [[{key}]] table", cause="missing")
        if not isinstance(v, list) or not v or not all(isinstance(t, dict) for t in v):
            raise self.error(key, f"at least one [[{key}]] table", v)
        return v

    def string(self, table: Mapping[str, Any], name: str, key: str, default: Any = _MISSING) -> str:
        v = table.get(name, _MISSING)
        if v is _MISSING:
            if default is _MISSING:
                raise self.error(key, "a string", cause="missing")
            return str(default)
        if not isinstance(v, str) or not v.strip():
            raise self.error(key, "a non-empty string", v)
        bad = unsafe_characters(v)
        if bad:
            raise self.error(
                key,
                "a string without control or format characters (escape sequences, line breaks, "
                f"bidi overrides), got {safe_text(v)!r} with {safe_text(''.join(bad[:5]))}",
                cause="unsafe characters",
            )
        return v

    def number(self, value: Any, key: str, *, positive: bool = False) -> Fraction:
        if value is _MISSING:
            raise self.error(key, "a finite number", cause="missing")
        if isinstance(value, (bool, dict, list)) or value is None:
            raise self.error(key, "a finite number", value)
        if isinstance(value, _BadFloat):
            raise self.error(key, "a finite number", value, value.reason)
        try:
            x = to_fraction(value)
        except QuadricContactError as exc:
            raise self.error(key, "a finite number", value, str(exc)) from exc
        if max(abs(x.numerator), x.denominator) >= 10**MAX_DIGITS:
            raise self.error(key, "a finite number", value, f"more than {MAX_DIGITS} digits (MAX_DIGITS)")
        if positive and x <= 0:
            raise self.error(key, "a positive number", value)
        return x

    def vector(self, value: Any, key: str, n: int) -> tuple[Fraction, ...]:
        if not isinstance(value, list) or len(value) != n:
            raise self.error(key, f"a list of {n} numbers", value)
        return tuple(self.number(v, f"{key}[{i}]") for i, v in enumerate(value))

    def poly_list(self, value: Any, key: str, n: int) -> tuple[tuple[Fraction, ...], ...]:
        expected = f"a list of {n} polynomials in t (coefficient lists in ascending powers, or text)"
        if not isinstance(value, list) or len(value) != n:
            raise self.error(key, expected, value)
        out = []
        for i, comp in enumerate(value):
            if isinstance(comp, str):
                out.append(self.polynomial_in_t(comp, f"{key}[{i}]"))
                continue
            if not isinstance(comp, list):
                raise self.error(
                    f"{key}[{i}]", "a list of coefficients (ascending powers of t) or a polynomial in t", comp
                )
            if len(comp) > MAX_MOTION_DEGREE + 1:  # before any coefficient is read
                raise self.error(
                    f"{key}[{i}]",
                    f"at most {MAX_MOTION_DEGREE + 1} coefficients, a degree of at most {MAX_MOTION_DEGREE} "
                    "in t (MAX_MOTION_DEGREE)",
                    f"{len(comp)} coefficients",
                )
            out.append(tuple(self.number(c, f"{key}[{i}][{j}]") for j, c in enumerate(comp)))
        return tuple(out)

    def polynomial_in_t(self, text: str, key: str) -> tuple[Fraction, ...]:
        """A polynomial in ``t`` written as text (``"3 - 2*t^2"``), as coefficients."""
        expected = f"a polynomial in t of degree at most {MAX_MOTION_DEGREE} (MAX_MOTION_DEGREE)"
        try:
            return parse_univariate(text, "t", max_degree=MAX_MOTION_DEGREE)
        except QuadricContactError as exc:
            raise self.error(key, expected, text, str(exc)) from exc


_QUADRIC_KEYS = (
    "equation",
    "matrix",
    "standard",
    "a",
    "b",
    "c",
    "semi_axes",
    "radius",
    "normal",
    "offset",
    "rotation",
    "center",
)


def _quadric(r: _Reader, t: Mapping[str, Any], key: str) -> Quadric:
    given = [k for k in ("equation", "matrix", "standard") if k in t]
    if len(given) != 1:
        raise r.error(
            key,
            "exactly one of equation, matrix or standard",
            cause=f"found {', '.join(given) if given else 'none'}",
        )
    how = given[0]
    try:
        if how == "equation":
            q = Quadric.from_equation(r.string(t, "equation", f"{key}.equation"))
        elif how == "matrix":
            m = t["matrix"]
            if not isinstance(m, list) or len(m) != 4:
                raise r.error(f"{key}.matrix", "a 4x4 matrix (a list of 4 rows)", m)
            rows = [r.vector(row, f"{key}.matrix[{i}]", 4) for i, row in enumerate(m)]
            q = Quadric.from_matrix(rows)
        else:
            q = _standard(r, t, key)
    except SceneError:
        raise
    except QuadricContactError as exc:
        raise r.error(f"{key}.{how}", "a valid quadric", t[how], str(exc)) from exc
    if how != "standard":
        for extra in ("a", "b", "c", "semi_axes", "radius", "normal", "offset"):
            if extra in t:
                raise r.error(f"{key}.{extra}", f"no parameters with {how} (they belong to standard = ...)")
    placed = q
    if "rotation" in t:
        quat = r.vector(t["rotation"], f"{key}.rotation", 4)
        if not any(quat):
            raise r.error(f"{key}.rotation", "a non-zero quaternion [w, x, y, z]", t["rotation"])
        placed = placed.rotated(quat)
    if "center" in t:
        placed = placed.translated(r.vector(t["center"], f"{key}.center", 3))
    return placed


_STANDARD = {
    "ellipsoid",
    "sphere",
    "plane",
    *(k.value for k in QuadricKind if k.in_table_1),
}


def _standard(r: _Reader, t: Mapping[str, Any], key: str) -> Quadric:
    kind = r.string(t, "standard", f"{key}.standard")
    if kind not in _STANDARD:
        raise r.error(f"{key}.standard", f"one of {sorted(_STANDARD)}", kind)
    if kind == "sphere":
        return Quadric.sphere(r.number(t.get("radius", _MISSING), f"{key}.radius", positive=True))
    if kind == "plane":
        normal = r.vector(t.get("normal", _MISSING), f"{key}.normal", 3)
        if not any(normal):
            raise r.error(f"{key}.normal", "a non-zero normal vector", t.get("normal"))
        return Quadric.plane(normal, r.number(t.get("offset", 0), f"{key}.offset"))
    if kind == "ellipsoid" and "semi_axes" in t:
        a, b, c = (
            r.number(v, f"{key}.semi_axes[{i}]", positive=True)
            for i, v in enumerate(r.vector(t["semi_axes"], f"{key}.semi_axes", 3))
        )
        return Quadric.ellipsoid(a, b, c)
    needed = {
        "ellipsoid": "abc",
        "hyperboloid of one sheet": "abc",
        "hyperboloid of two sheets": "abc",
        "elliptic paraboloid": "ab",
        "hyperbolic paraboloid": "ab",
        "elliptic cylinder": "ab",
        "hyperbolic cylinder": "ab",
        "parabolic cylinder": "a",
        "parallel planes": "a",
    }[kind]
    params = {p: r.number(t.get(p, _MISSING), f"{key}.{p}", positive=True) for p in needed}
    return Quadric.standard(kind, **params)


def _piece(r: _Reader, t: Mapping[str, Any], key: str) -> Piece:
    r.keys(t, key, ("name", "inside", *_QUADRIC_KEYS))
    name = r.string(t, "name", f"{key}.name")
    q = _quadric(r, t, key)
    if q.kind in EXCLUDED_KINDS:
        reason = q.kind.excluded_reason or q.kind.real_points
        raise r.error(key, "a quadric of Table 1 or a plane", q.kind.value, reason)
    inside = r.string(t, "inside", f"{key}.inside", default="R-")
    if inside not in ("R-", "R+"):
        raise r.error(f"{key}.inside", "'R-' or 'R+'", inside)
    return Piece(name, q, Region(inside))


def _tree(r: _Reader, node: Any, key: str, pieces: dict[str, Piece], used: list[str]) -> Split | Piece | None:
    if isinstance(node, str):
        if node not in pieces:
            raise r.error(key, f"the name of a piece of this object ({', '.join(pieces)})", node)
        used.append(node)
        return pieces[node]
    if not isinstance(node, dict):
        raise r.error(key, "a piece name or a table { plane = ..., plus = ..., minus = ... }", node)
    r.keys(node, key, ("plane", "plus", "minus"))
    text = r.string(node, "plane", f"{key}.plane")
    try:
        plane = Quadric.from_equation(text)
    except QuadricContactError as exc:
        raise r.error(f"{key}.plane", "the equation of a plane", text, str(exc)) from exc
    if plane.kind is not QuadricKind.PLANE:
        raise r.error(f"{key}.plane", "the equation of a plane", text, f"it is a {plane.kind.value}")
    plus = _tree(r, node["plus"], f"{key}.plus", pieces, used) if "plus" in node else None
    minus = _tree(r, node["minus"], f"{key}.minus", pieces, used) if "minus" in node else None
    return Split(plane, plus, minus, name=text)


def _object(r: _Reader, t: Mapping[str, Any], key: str) -> Composite:
    r.keys(t, key, ("name", "piece", "tree"))
    name = r.string(t, "name", f"{key}.name")
    plist = [
        _piece(r, p, f"{key}.piece[{i}]") for i, p in enumerate(r.array_of_tables(t, "piece", f"{key}.piece"))
    ]
    pieces: dict[str, Piece] = {}
    for i, p in enumerate(plist):
        if p.name in pieces:
            raise r.error(f"{key}.piece[{i}].name", "a name not used by another piece of the object", p.name)
        pieces[p.name] = p
    if "tree" not in t:
        return Composite.union(name, plist)
    used: list[str] = []
    root = _tree(r, t["tree"], f"{key}.tree", pieces, used)
    unused = [n for n in pieces if n not in used]
    if unused:
        raise r.error(f"{key}.tree", f"every piece placed in the tree (missing: {', '.join(unused)})")
    return Composite(name, root)


def _motion(r: _Reader, t: Mapping[str, Any], key: str, span: tuple[Fraction, Fraction]) -> Trajectory:
    kind = r.string(t, "type", f"{key}.type", default="still")
    if kind == "still":
        r.keys(t, key, ("type",))
        return Stationary()
    if kind == "linear":
        r.keys(t, key, ("type", "velocity", "start"))
        v = r.vector(t.get("velocity", _MISSING), f"{key}.velocity", 3)
        start = r.number(t.get("start", span[0]), f"{key}.start")
        return PolynomialMotion.linear(v, start)
    if kind == "polynomial":
        r.keys(t, key, ("type", "translation", "quaternion"))
        tr = r.poly_list(t.get("translation", _MISSING), f"{key}.translation", 3)
        quat = r.poly_list(t["quaternion"], f"{key}.quaternion", 4) if "quaternion" in t else None
        return PolynomialMotion(tr, quat)
    if kind == "keyframes":
        r.keys(t, key, ("type", "keys"))
        keys = t.get("keys", _MISSING)
        if not isinstance(keys, list) or not keys:
            raise r.error(f"{key}.keys", "a non-empty list of { t = ..., at = [x, y, z] } tables", keys)
        parsed = []
        last: Fraction | None = None
        for i, k in enumerate(keys):
            kk = f"{key}.keys[{i}]"
            if not isinstance(k, dict):
                raise r.error(kk, "a table { t = ..., at = [x, y, z], rotation = [w, x, y, z] }", k)
            r.keys(k, kk, ("t", "at", "rotation"))
            time = r.number(k.get("t", _MISSING), f"{kk}.t")
            if last is not None and time <= last:
                raise r.error(f"{kk}.t", f"a time after the previous key's ({last})", time)
            last = time
            at = r.vector(k.get("at", _MISSING), f"{kk}.at", 3)
            rot = None
            if "rotation" in k:
                rot = r.vector(k["rotation"], f"{kk}.rotation", 4)
                if not any(rot):
                    raise r.error(f"{kk}.rotation", "a non-zero quaternion [w, x, y, z]", k["rotation"])
            parsed.append((time, at, rot))
        return Keyframes(parsed)
    raise r.error(f"{key}.type", "one of 'still', 'linear', 'polynomial', 'keyframes'", kind)


def _ellipsoid(
    r: _Reader, t: Mapping[str, Any], key: str, span: tuple[Fraction, Fraction]
) -> MovingEllipsoid:
    r.keys(t, key, ("name", "motion", *[k for k in _QUADRIC_KEYS if k not in ("normal", "offset")]))
    name = r.string(t, "name", f"{key}.name")
    q = _quadric(r, t, key)
    try:
        e = q.as_ellipsoid()
    except QuadricContactError as exc:
        raise r.error(key, "a real ellipsoid", q.kind.value, str(exc)) from exc
    motion = r.table(t, "motion", f"{key}.motion", required=False)
    traj = _motion(r, motion, f"{key}.motion", span)
    try:  # validate the motion on the span now (e.g. a vanishing quaternion)
        traj.segments(span[0], span[1], e.center() or (Fraction(0),) * 3)
    except SceneError as exc:
        raise r.error(f"{key}.motion", "a motion defined on the whole time span", cause=str(exc)) from exc
    return MovingEllipsoid(name, e, traj)


def _distinct_names(r: _Reader, named: Sequence[tuple[str, str]]) -> None:
    """Refuse a name given to two objects, two ellipsoids, or an object and an ellipsoid."""
    seen: dict[str, str] = {}
    for key, name in named:
        if name in seen:
            raise r.error(
                f"{key}.name",
                "a name not used by another object or ellipsoid",
                name,
                f"{seen[name]}.name is also {name!r}",
            )
        seen[name] = key


def _effect_list(r: _Reader, value: Any, key: str) -> tuple[str, ...]:
    if not isinstance(value, list) or not all(isinstance(e, str) for e in value):
        raise r.error(key, f"a list of effect names from {list(EFFECTS)}", value)
    for i, e in enumerate(value):
        if e not in EFFECTS:
            raise r.error(f"{key}[{i}]", f"one of {list(EFFECTS)}", e)
    return tuple(dict.fromkeys(value))


def _object_effects(
    r: _Reader, data: Mapping[str, Any], objects: Sequence[Composite], ells: Sequence[MovingEllipsoid]
) -> tuple[dict[str, tuple[str, ...]], dict[tuple[str, str], tuple[str, ...]]]:
    """The optional ``[effects]`` table: ``ellipsoids = { name = [...] }`` and
    ``pieces = { "object/piece" = [...] }``, each list replacing the scene's effects for
    that ellipsoid or piece (a pair gets what the scene, its ellipsoid and its piece all ask for)."""
    table = r.table(data, "effects", "effects", required=False)
    r.keys(table, "effects", ("ellipsoids", "pieces"))
    names = {e.name for e in ells}
    pieces = {f"{o.name}/{p.name}": (o.name, p.name) for o in objects for p in o.pieces}
    per_ellipsoid: dict[str, tuple[str, ...]] = {}
    for name, value in r.table(table, "ellipsoids", "effects.ellipsoids", required=False).items():
        if name not in names:
            raise r.error(
                f"effects.ellipsoids.{name}", f"the name of an ellipsoid ({', '.join(sorted(names))})", name
            )
        per_ellipsoid[name] = _effect_list(r, value, f"effects.ellipsoids.{name}")
    per_piece: dict[tuple[str, str], tuple[str, ...]] = {}
    for name, value in r.table(table, "pieces", "effects.pieces", required=False).items():
        if name not in pieces:
            raise r.error(f"effects.pieces.{name}", f"'object/piece' of a piece ({', '.join(pieces)})", name)
        per_piece[pieces[name]] = _effect_list(r, value, f"effects.pieces.{name}")
    return per_ellipsoid, per_piece


def parse_scene(
    text: str, source: str = "<scene>", *, check_smallness: bool = True, on_not_small: str | None = None
) -> Scene:
    """Build a :class:`Scene` from TOML text (see the module documentation for the format).

    Parameters
    ----------
    text : str
        The TOML text.
    source : str
        Where it came from (for messages).
    check_smallness : bool, default True
        Check smallness now if the scene's effects rely on Theorem 2.
    on_not_small : {"refuse", "warn"}, optional
        Override the scene's policy (None: the scene's own).

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        For any problem, naming ``source``, the key and what was expected.
    ChoiceError
        ``on_not_small`` is not ``"refuse"``, ``"warn"`` or None.

    Examples
    --------
    >>> scene = parse_scene('''
    ... [scene]
    ... name = "a sphere rolls over a saddle"
    ... time = [0, 4]
    ... [[object]]
    ... name = "saddle"
    ... [[object.piece]]
    ... name = "s"
    ... equation = "z = x^2/4 - y^2/4"
    ... [[ellipsoid]]
    ... name = "ball"
    ... standard = "sphere"
    ... radius = 0.25
    ... center = [-2, 0, 2]
    ... motion = { type = "linear", velocity = [1, 0, -0.5] }
    ... ''')
    >>> scene.span, scene.ellipsoids[0].quadric.center()
    ((Fraction(0, 1), Fraction(4, 1)), (Fraction(-2, 1), Fraction(0, 1), Fraction(2, 1)))
    """
    check_on_not_small(on_not_small)
    r = _Reader(source)
    if not isinstance(text, str):
        raise SceneError(f"{source}: expected the scene's text, got {type(text).__name__}", text, file=source)
    text = str.__str__(text)  # a plain copy of a subclass
    if len(text) > MAX_SCENE_BYTES:
        raise SceneError(
            f"{source}: {len(text)} characters, more than {MAX_SCENE_BYTES} (MAX_SCENE_BYTES)",
            source,
            file=source,
        )
    depth = _nesting_depth(text)
    if depth > MAX_SCENE_DEPTH:
        raise SceneError(
            f"{source}: tables or arrays nested {depth} deep, more than {MAX_SCENE_DEPTH} (MAX_SCENE_DEPTH)",
            source,
            file=source,
        )
    try:
        data = tomllib.loads(text, parse_float=_parse_float)
    except (tomllib.TOMLDecodeError, ValueError) as exc:  # ValueError: an integer beyond 4300 digits
        raise SceneError(f"{source}: not valid TOML: {exc}", text, file=source) from exc
    except RecursionError:  # pragma: no cover - the depth is checked first
        raise SceneError(f"{source}: nested too deep (MAX_SCENE_DEPTH)", source, file=source) from None
    r.keys(data, "", ("scene", "object", "ellipsoid", "effects"))
    meta = r.table(data, "scene", "scene")
    r.keys(
        meta,
        "scene",
        (
            "name",
            "description",
            "time",
            "effects",
            "on_not_small",
            "places",
            "reading",
            "mutual",
            "distance_tolerance",
            "distance_evaluations",
        ),
    )
    name = r.string(meta, "name", "scene.name")
    description = meta.get("description", "")
    if not isinstance(description, str):
        raise r.error("scene.description", "a string", description)
    span_raw = meta.get("time", _MISSING)
    if span_raw is _MISSING:
        raise r.error("scene.time", "[start, end]", cause="missing")
    span_v = r.vector(span_raw, "scene.time", 2)
    if not span_v[0] < span_v[1]:
        raise r.error(
            "scene.time",
            "[start, end] with start < end",
            span_raw,
            f"the time span is {'empty' if span_v[0] == span_v[1] else 'reversed'}: "
            f"the end {span_v[1]} is not after the start {span_v[0]}",
        )
    span = (span_v[0], span_v[1])
    effects_raw = meta.get("effects", ["zone", "contact", "first_contact"])
    if (
        not isinstance(effects_raw, list)
        or not effects_raw
        or not all(isinstance(e, str) for e in effects_raw)
    ):
        raise r.error("scene.effects", f"a non-empty list of effect names from {list(EFFECTS)}", effects_raw)
    for i, e in enumerate(effects_raw):
        if e not in EFFECTS:
            raise r.error(f"scene.effects[{i}]", f"one of {list(EFFECTS)}", e)
    policy = r.string(meta, "on_not_small", "scene.on_not_small", default="refuse")
    if policy not in ("refuse", "warn"):
        raise r.error("scene.on_not_small", "'refuse' or 'warn'", policy)
    places_raw = meta.get("places", 12)
    if isinstance(places_raw, bool) or not isinstance(places_raw, int) or not 0 <= places_raw <= MAX_PLACES:
        expected = f"an integer number of decimal places in [0, {MAX_PLACES}] (MAX_PLACES)"
        raise r.error("scene.places", expected, places_raw)
    reading = r.string(meta, "reading", "scene.reading", default="geometry")
    if reading not in READINGS:
        raise r.error("scene.reading", " or ".join(repr(x) for x in READINGS), reading)
    tolerance = r.number(meta.get("distance_tolerance", DISTANCE_TOLERANCE), "scene.distance_tolerance")
    evaluations = meta.get("distance_evaluations", DISTANCE_EVALUATIONS)
    distance_options(tolerance, evaluations, source)  # the range, naming the key
    objects = tuple(
        _object(r, t, f"object[{i}]") for i, t in enumerate(r.array_of_tables(data, "object", "object"))
    )
    ells = tuple(
        _ellipsoid(r, t, f"ellipsoid[{i}]", span)
        for i, t in enumerate(r.array_of_tables(data, "ellipsoid", "ellipsoid"))
    )
    _distinct_names(
        r,
        [(f"object[{i}]", o.name) for i, o in enumerate(objects)]
        + [(f"ellipsoid[{i}]", e.name) for i, e in enumerate(ells)],
    )
    mutual_raw = meta.get("mutual", False)
    if mutual_raw is True:
        mutual = tuple(e.name for e in ells)
    elif mutual_raw is False:
        mutual = ()
    elif isinstance(mutual_raw, list) and all(isinstance(n, str) for n in mutual_raw):
        unknown = [n for n in mutual_raw if n not in {e.name for e in ells}]
        if unknown:
            raise r.error("scene.mutual", "names of the scene's ellipsoids", unknown)
        mutual = tuple(dict.fromkeys(mutual_raw))
    else:
        raise r.error("scene.mutual", "true, false or a list of ellipsoid names", mutual_raw)
    per_ellipsoid, per_piece = _object_effects(r, data, objects, ells)
    scene = Scene(
        name,
        objects,
        ells,
        span,
        tuple(dict.fromkeys(effects_raw)),
        description,
        source,
        policy,
        places_raw,
        ellipsoid_effects=per_ellipsoid,
        piece_effects=per_piece,
        reading=reading,
        mutual=mutual,
        distance_tolerance=tolerance,
        distance_evaluations=evaluations,
    )
    if check_smallness and scene.needs_smallness():
        scene.check_smallness(on_not_small=on_not_small)
    return scene


def builtin_scene_names() -> list[str]:
    """Names of the scenes shipped with the package (``quadric_contact/scenes/*.toml``).

    Examples
    --------
    >>> "bee_and_tree" in builtin_scene_names()
    True
    """
    folder = resources.files("quadric_contact").joinpath("scenes")
    return sorted(p.name[: -len(".toml")] for p in folder.iterdir() if p.name.endswith(".toml"))


def builtin_scene(name: str = "bee_and_tree", **kwargs: Any) -> Scene:
    """Load a built-in scene by name (default: the bee and the tree of Example 17).

    Parameters
    ----------
    name : str
        One of :func:`builtin_scene_names`.
    **kwargs
        ``check_smallness``, ``on_not_small``: as for :func:`parse_scene`.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        No built-in scene has this name.

    References
    ----------
    Example 17, Fig. 8 (the default scene).

    Examples
    --------
    >>> s = builtin_scene()
    >>> s.name, [o.name for o in s.objects], [e.name for e in s.ellipsoids]
    ('The bee and the tree (Example 17)', ['tree'], ['bee'])
    """
    if name not in builtin_scene_names():
        raise SceneError(
            f"no built-in scene {name!r}; built-in scenes: {', '.join(builtin_scene_names())}", name
        )
    res = resources.files("quadric_contact").joinpath("scenes", f"{name}.toml")
    return parse_scene(res.read_text(encoding="utf-8"), f"<built-in scene {name}>", **kwargs)


def load_scene(path: str | Path, **kwargs: Any) -> Scene:
    """Load a scene from a TOML file, or a built-in scene by name.

    Parameters
    ----------
    path : str or Path
        A file, or the name of a built-in scene (:func:`builtin_scene_names`).
    check_smallness : bool, default True
        Check smallness now if the scene's effects need it.
    on_not_small : {"refuse", "warn"}, optional
        Override the scene's policy (None: the scene's own).

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        The file cannot be read or is not a valid scene (the message names
        the file, the key and what was expected).
    ChoiceError
        ``on_not_small`` is not ``"refuse"``, ``"warn"`` or None.
    """
    p = Path(path)
    if not p.exists():
        if str(path) in builtin_scene_names():
            return builtin_scene(str(path), **kwargs)
        raise SceneError(
            f"{path}: no such file (built-in scenes: {', '.join(builtin_scene_names())})",
            str(path),
            file=str(path),
        )
    return parse_scene(read_scene_file(p), str(path), **kwargs)


def read_scene_file(path: str | Path) -> str:
    """The text of a scene file: a regular file (not a device such as ``/dev/zero``,
    a FIFO that would block, or a directory) of at most
    :data:`~quadric_contact.exact.bounds.MAX_SCENE_BYTES` bytes, in UTF-8.  The file
    is opened without blocking and checked on the open descriptor, so what is read
    is what was checked."""

    def refuse(why: str, exc: BaseException | None = None) -> SceneError:
        return SceneError(f"{path}: cannot read the scene file: {why}", str(path), file=str(path))

    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise refuse(exc.strerror or str(exc)) from exc
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise refuse("not a regular file (a directory, a device, a FIFO or a socket)")
        if info.st_size > MAX_SCENE_BYTES:
            raise refuse(f"{info.st_size} bytes, more than {MAX_SCENE_BYTES} (MAX_SCENE_BYTES)")
        with os.fdopen(fd, "rb", closefd=False) as f:
            data = f.read(MAX_SCENE_BYTES + 1)
    except OSError as exc:
        raise refuse(exc.strerror or str(exc)) from exc
    finally:
        os.close(fd)
    if len(data) > MAX_SCENE_BYTES:
        raise refuse(f"more than {MAX_SCENE_BYTES} bytes (MAX_SCENE_BYTES)")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise refuse(f"not UTF-8 text ({exc.reason} at byte {exc.start})") from exc
