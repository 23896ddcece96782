"""Lemma 12 and eq. (11): a small ellipsoid and a hyperboloid of two sheets.

Claim.  ``E`` small and not in transversal contact with a two-sheet
hyperboloid ``H``: ``E`` is in ``R-`` iff ``P`` has four negative roots, in
``R+`` iff two negative and two positive.  The proof scales ``E`` to the unit
sphere (10) centred at ``(x_c, y_c, z_c)`` and ``H`` to
``diag(1/a^2, 1/b^2, -1/c^2, 1)``, computes ``P`` (eq. (11)), factors it at
the centres ``(0, 0, 0)`` (in ``R+``) and ``(0, 0, +-(c + 1))`` (in ``R-``,
touching a vertex), and concludes by continuity, since ``P(0) != 0``.

What is checked and how.  Symbolic identities in ``a, b, c, x_c, y_c, z_c``:
``det(l S + H)`` equals the printed eq. (11) term by term; at ``(0, 0, 0)``
``a^2 b^2 c^2 P = -(l - 1)(a^2 l + 1)(b^2 l + 1)(c^2 l - 1)`` (roots
``1, 1/c^2, -1/a^2, -1/b^2``: ``--++``); at ``(0, 0, c + 1)`` and
``(0, 0, -c - 1)`` ``a^2 b^2 c^2 P = -(a^2 l + 1)(b^2 l + 1)(c l + 1)^2``
(``----``); ``P(0) = -1/(a^2 b^2 c^2)``; the positions (the unit sphere at
the origin lies in ``R+`` exactly when ``c >= 1``, the centres ``(0,0,+-(c+1))``
are in ``R-``); the scaling step (an affine change ``x -> M x`` multiplies
``P`` by ``det(M)^2`` and keeps its roots).  The continuity step, which the
paper leaves to the reader, is replaced by a proof valid at every position:
the inertia count of Theorem 13 (see ``_real_pencils``) applied to ``H``
(``n_+(H) = 3``, ``H`` non-singular, both ``{H < 0}`` and ``{H > 0}`` with only
unbounded components) gives ``N_- = n_+(H) +- 1``: four negative roots in
``R-``, two in ``R+``, for any ellipsoid not in transversal contact with
``H``, small or not.  Cross-check of the package (full profile): 400
hypothesis examples of tiny rotated ellipsoids placed anywhere off a moved
two-sheet hyperboloid show the pattern of the region of their centre.
"""

from __future__ import annotations

from fractions import Fraction

import sympy as sp

from quadric_contact import Quadric, characteristic_polynomial, paper
from quadric_contact.paper.proving import Finding, Method, Proof, agrees, ensure, search_settings

from ._real_pencils import derive_root_signs, neutral_chain_identity

proof = Proof(
    "Lemma 12", "root signs for a two-sheet hyperboloid", covers=("eq. (11)",), relies_on=("Remark 9",)
)

LAM = sp.Symbol("lambda")
a, b, c = sp.symbols("a b c", positive=True)
xc, yc, zc = sp.symbols("x_c y_c z_c", real=True)
NAMES = {"a": a, "b": b, "c": c, "x_c": xc, "y_c": yc, "z_c": zc, "LAM": LAM}
H = sp.diag(1 / a**2, 1 / b**2, -1 / c**2, 1)


def sphere(x: sp.Expr, y: sp.Expr, z: sp.Expr) -> sp.Matrix:
    """The unit sphere (10) centred at (x, y, z)."""
    return sp.Matrix([[1, 0, 0, -x], [0, 1, 0, -y], [0, 0, 1, -z], [-x, -y, -z, -1 + x**2 + y**2 + z**2]])


def printed(key: str) -> sp.Expr:
    return sp.sympify(paper.PRINTED[key].replace("lambda", "LAM"), locals=NAMES)


def P_at(x: sp.Expr, y: sp.Expr, z: sp.Expr) -> sp.Expr:
    return sp.expand((LAM * sphere(x, y, z) + H).det())


@proof.check("eq. (11) = det(l S + H), term by term", method=Method.IDENTITY)
def eq_11() -> Finding:
    P = sp.Poly(P_at(xc, yc, zc), LAM)
    shown = sp.Poly(sp.expand(printed("eq. (11)")), LAM)
    for k in range(5):
        diff = sp.simplify(P.coeff_monomial(LAM**k) - shown.coeff_monomial(LAM**k))
        ensure(diff == 0, f"coefficient of l^{k} differs by {diff}")
    ensure(sp.simplify(P.coeff_monomial(1) + 1 / (a**2 * b**2 * c**2)) == 0, "P(0) = -1/(a^2 b^2 c^2)")
    return agrees("eq. (11) holds identically in a, b, c, x_c, y_c, z_c; P(0) = -1/(a^2 b^2 c^2) != 0")


@proof.check(
    "at (0, 0, 0): a^2 b^2 c^2 P = -(l - 1)(a^2 l + 1)(b^2 l + 1)(c^2 l - 1), pattern --++",
    method=Method.IDENTITY,
)
def factor_origin() -> Finding:
    ensure(
        sp.expand(a**2 * b**2 * c**2 * P_at(0, 0, 0) - printed("Lemma 12 at (0, 0, 0)")) == 0, "factorisation"
    )
    roots = sp.roots(sp.Poly(printed("Lemma 12 at (0, 0, 0)"), LAM))
    ensure(set(roots) == {1, 1 / c**2, -1 / a**2, -1 / b**2}, f"roots {roots}")
    # The unit sphere at the origin is in R+ = {H >= 0} iff c >= 1: on it (z^2 = 1 - x^2 - y^2)
    # H - (1 - 1/c^2) = x^2/a^2 + y^2/b^2 + (x^2 + y^2)/c^2 >= 0, with equality at the poles (0, 0, +-1).
    x, y = sp.symbols("x y", real=True)
    h = x**2 / a**2 + y**2 / b**2 - (1 - x**2 - y**2) / c**2 + 1
    ensure(
        sp.expand(h - (1 - 1 / c**2) - (x**2 / a**2 + y**2 / b**2 + (x**2 + y**2) / c**2)) == 0, "min of H"
    )
    return agrees(
        "roots 1, 1/c^2 > 0 and -1/a^2, -1/b^2 < 0 (--++); the centre has H = 1 > 0 and the unit "
        "sphere lies in "
        "R+ iff c >= 1 (the size condition of Table 1)"
    )


@proof.check(
    "at (0, 0, +-(c + 1)): a^2 b^2 c^2 P = -(a^2 l + 1)(b^2 l + 1)(c l + 1)^2, pattern ----",
    method=Method.IDENTITY,
)
def factor_vertex() -> Finding:
    for z in (c + 1, -c - 1):
        ensure(
            sp.expand(a**2 * b**2 * c**2 * P_at(0, 0, z) - printed("Lemma 12 at (0, 0, c + 1)")) == 0,
            f"z = {z}",
        )
        value = sp.simplify((sp.Matrix([0, 0, z, 1]).T * H * sp.Matrix([0, 0, z, 1]))[0, 0])
        ensure(sp.simplify(value + (2 * c + 1) / c**2) == 0, f"H at the centre is {value}")
        touching = (sp.Matrix([0, 0, z - sp.sign(z) * 1, 1]).T * H * sp.Matrix([0, 0, z - sp.sign(z), 1]))[
            0, 0
        ]
        ensure(sp.simplify(touching) == 0, "the sphere touches the vertex (0, 0, +-c)")
    return agrees(
        "both centres are in R- (H = -(2c + 1)/c^2 < 0), the sphere touches the vertex, and the roots "
        "-1/a^2, -1/b^2, -1/c (double) are negative (----)"
    )


@proof.check("scaling step: x -> M x multiplies P by det(M)^2", method=Method.IDENTITY)
def scaling() -> Finding:
    s = sp.symbols("s1:4", nonzero=True)
    M = sp.diag(*s, 1)
    X = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"x{min(i, j)}{max(i, j)}"))
    Y = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"y{min(i, j)}{max(i, j)}"))
    moved = (LAM * M.T * X * M + M.T * Y * M).det(method="berkowitz")
    ensure(sp.expand(moved - M.det() ** 2 * (LAM * X + Y).det(method="berkowitz")) == 0, "det(M)^2")
    return agrees("det(l M^T S M + M^T H M) = det(M)^2 det(l S + H): scaling E to a sphere keeps the roots")


@proof.check(
    "at every position: four negative roots in R-, two in R+ (the inertia count, no continuity needed)",
    method=Method.CASES,
)
def root_signs_any_position() -> Finding:
    ensure(neutral_chain_identity(), "the eigenvector of a Jordan chain is E-neutral")
    derivation = derive_root_signs(H)
    ensure(derivation.positive == 3 and derivation.kernel == 0, "n_+(H) = 3, H non-singular")
    ensure(derivation.unbounded[1] and derivation.unbounded[-1], "no bounded component of {H != 0}")
    ensure(derivation.pattern("R-") == "----" and derivation.pattern("R+") == "--++", "the patterns")
    return agrees(
        "n_+(H) = 3, det H != 0, {H < 0} and {H > 0} without bounded components: N_- = 3 + 1 = 4 in R- "
        "(----) and 3 - 1 = 2 in R+ (--++) for every ellipsoid not in transversal contact with H"
    )


@proof.search(
    "the package: tiny ellipsoids off a moved two-sheet hyperboloid show the pattern of their region",
    examples=0,
    large=400,
    method=Method.CROSS_CHECK,
)
def placements(examples: int) -> Finding:
    from hypothesis import assume, given
    from hypothesis import strategies as st

    from quadric_contact.testing.strategies import points, rigid_motions, rotations

    seen = {"----": 0, "--++": 0}

    @search_settings(examples)
    @given(
        params=st.tuples(*(st.integers(2, 6) for _ in range(3))),
        centre=points(bound=8),
        rot=rotations(),
        motion=rigid_motions(),
    )
    def search(
        params: tuple[int, int, int], centre: tuple[Fraction, ...], rot: object, motion: object
    ) -> None:
        A, B, C = sorted(params, reverse=True)
        q = Quadric.hyperboloid_two_sheets(A, B, C).moved(motion)
        p = motion.apply(centre)
        e = Quadric.ellipsoid(Fraction(1, 10), Fraction(1, 15), Fraction(1, 20), center=p, rotation=rot)
        value = q.value_at(p)
        P = characteristic_polynomial(e, q)
        assume(P.structure.all_real and abs(value) > Fraction(1, 2))
        pattern = P.signs.pattern
        ensure(pattern == ("----" if value < 0 else "--++"), f"centre value {value}, pattern {pattern}")
        seen[pattern] += 1

    search()
    ensure(all(seen.values()), f"both regions met: {seen}")
    return agrees(f"{seen['----']} placements in R- gave ----, {seen['--++']} in R+ gave --++")
