"""Real symmetric pencils ``l E + Q`` with ``E`` of signature (3, 1): exact inertia,
Segre types, canonical forms, realisations by ellipsoids, and the inertia count.

Shared by Corollary 10 (an ellipsoid's pencil has at most one non-real pair),
Lemma 12 and Theorem 13 (the signs of the roots tell the region).

The inertia count.  For real ``l`` not a root, let ``nu(l)`` be the number of
positive eigenvalues of ``M(l) = l E + Q``.  It is constant between real roots
(the eigenvalues of a symmetric matrix depend continuously on its entries and
none crosses 0), ``nu(+inf) = n_+(E) = 3`` and ``nu(-inf) = n_+(-E) = 1``
(``M(l)/|l| -> +-E``).  At a real root ``l0`` with kernel ``K = ker M(l0)`` of
dimension ``g`` (the number of Jordan blocks, at most the multiplicity ``m``):

(a) ``|nu(l0 + t) - nu(l0 - t)| <= g`` for small ``t > 0``: the non-zero
    eigenvalues of ``M(l0)`` keep their signs (continuity, Weyl's inequality),
    only the ``g`` zero ones can move;
(b) if ``E`` is positive definite on ``K`` then ``nu(l0 + t) - nu(l0 - t) = g = m``:
    by the inertia of a perturbation (write ``M(l0) + tE`` in a basis adapted to
    ``K^perp + K``; for small ``t`` the block on ``K^perp`` keeps the inertia of
    ``M(l0)`` there, and the Schur complement is ``t (E|K + O(t))``, of the inertia
    of ``t E|K``; Haynsworth's inertia additivity adds them), and the blocks are
    all of size 1 because the eigenvector ``v`` of a Jordan chain is ``E``-neutral
    (``M(l0) v = 0``, ``M(l0) u = -E v`` give ``v^T E v = -v^T M(l0) u = 0``), so
    ``m = g``.

Summing the jumps, ``sum over real roots of (nu(l0+) - nu(l0-)) = 3 - 1 = 2``.
These are the only facts used; :func:`neutral_chain_identity` checks the
identity of (b) symbolically.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction

import sympy as sp

from quadric_contact.paper.proving import ensure
from quadric_contact.theory.segre import segre_symbol

Partition = tuple[int, ...]


def variations(signs: Sequence[int]) -> int:
    nz = [s for s in signs if s]
    return sum(1 for u, v in itertools.pairwise(nz) if u != v)


def inertia(M: sp.Matrix) -> tuple[int, int, int]:
    """``(n_+, n_-, n_0)`` of a real symmetric matrix with rational entries, exactly: its
    characteristic polynomial has only real roots, so Descartes' rule of signs counts the
    positive and the negative ones exactly."""
    x = sp.Symbol("x")
    coeffs = sp.Poly(M.charpoly(x).as_expr(), x).all_coeffs()  # highest degree first
    zeros = 0
    while coeffs and coeffs[-1] == 0:
        coeffs.pop()
        zeros += 1
    signs = [int(sp.sign(c)) for c in coeffs]
    n = len(coeffs) - 1
    positive = variations(signs)
    negative = variations([s * (-1) ** (n - k) for k, s in enumerate(signs)])
    ensure(positive + negative + zeros == M.shape[0], "a symmetric matrix has real eigenvalues")
    return positive, negative, zeros


def neutral_chain_identity() -> bool:
    """``M v = 0`` and ``M u = -E v`` with ``M`` symmetric give ``v^T E v = 0``: the
    identity ``v^T E v + v^T (M u + E v) - u^T (M v) = 0`` for symbolic symmetric ``M, E``."""
    M = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"m{min(i, j)}{max(i, j)}"))
    E = sp.Matrix(4, 4, lambda i, j: sp.Symbol(f"e{min(i, j)}{max(i, j)}"))
    v = sp.Matrix(sp.symbols("v0:4"))
    u = sp.Matrix(sp.symbols("u0:4"))
    expr = (v.T * E * v)[0, 0] - (v.T * (M * u + E * v))[0, 0] + (u.T * (M * v))[0, 0]
    return sp.expand(expr) == 0


# -- Segre types of 4 x 4 real pencils with det E != 0 ----------------------------------------


def _partitions(n: int, largest: int | None = None) -> Iterator[Partition]:
    largest = n if largest is None else largest
    if n == 0:
        yield ()
        return
    for first in range(min(n, largest), 0, -1):
        for rest in _partitions(n - first, first):
            yield (first, *rest)


def _group_key(blocks: Partition) -> tuple[int, int, int]:
    """The package's order of Segre groups (quadric_contact.theory.segre): decreasing multiplicity,
    then decreasing largest block, then fewer blocks first."""
    return (-sum(blocks), -blocks[0], len(blocks))


def _show(blocks: Partition) -> str:
    return "".join(map(str, blocks)) if len(blocks) == 1 else "(" + "".join(map(str, blocks)) + ")"


@dataclass(frozen=True)
class SegreType:
    """The Jordan structure of a real regular 4 x 4 pencil: the block sizes at each real
    eigenvalue (``real``) and at each pair of non-real conjugate eigenvalues (``pairs``, the
    sizes at one of the two; its conjugate has the same)."""

    real: tuple[Partition, ...]
    pairs: tuple[Partition, ...]

    @property
    def symbol(self) -> str:
        """The paper's notation with the number of distinct real roots as subscript."""
        groups = sorted([*self.real, *(p for p in self.pairs for _ in range(2))], key=_group_key)
        return "[" + "".join(_show(g) for g in groups) + f"]_{len(self.real)}"

    @property
    def real_blocks(self) -> int:
        """``g`` summed over the real eigenvalues: the number of real Jordan blocks."""
        return sum(len(b) for b in self.real)

    @property
    def nonreal_roots(self) -> int:
        """Number of non-real roots of ``det(l E + Q)``, with multiplicity."""
        return 2 * sum(sum(b) for b in self.pairs)


def segre_types() -> list[SegreType]:
    """Every Segre type of a real regular 4 x 4 pencil: multisets of groups, each a partition
    at a real eigenvalue (weight its size) or at a conjugate pair (weight twice its size),
    of total weight 4."""
    groups = [("r", p) for n in range(1, 5) for p in _partitions(n)]
    groups += [("c", p) for n in range(1, 3) for p in _partitions(n)]

    def weight(g: tuple[str, Partition]) -> int:
        return sum(g[1]) * (1 if g[0] == "r" else 2)

    out: list[SegreType] = []

    def extend(chosen: list[tuple[str, Partition]], start: int, left: int) -> None:
        if left == 0:
            real = tuple(sorted((p for k, p in chosen if k == "r"), key=_group_key))
            pairs = tuple(sorted((p for k, p in chosen if k == "c"), key=_group_key))
            out.append(SegreType(real, pairs))
            return
        for i in range(start, len(groups)):
            if weight(groups[i]) <= left:
                extend([*chosen, groups[i]], i, left - weight(groups[i]))

    extend([], 0, 4)
    symbols = [t.symbol for t in out]
    ensure(len(set(symbols)) == len(symbols), "the symbol (with its subscript) names the type")
    return out


# -- canonical blocks ---------------------------------------------------------------------------


def _flip(k: int) -> sp.Matrix:
    return sp.Matrix(k, k, lambda i, j: 1 if i + j == k - 1 else 0)


def _above_flip(k: int) -> sp.Matrix:
    return sp.Matrix(k, k, lambda i, j: 1 if i + j == k - 2 else 0)


def real_block(k: int, eigenvalue: int, sign: int) -> tuple[sp.Matrix, sp.Matrix]:
    """``(E_k, Q_k) = (s F, s (G - l0 F))`` with ``F`` the k x k flip matrix and ``G`` the
    flip shifted up: ``l E_k + Q_k = s ((l - l0) F + G)``, one Jordan block of size ``k``
    at ``l0``, with sign ``s`` (the sign characteristic)."""
    F, G = _flip(k), _above_flip(k)
    return sign * F, sign * (G - eigenvalue * F)


def pair_block(k: int, a: int, b: int) -> tuple[sp.Matrix, sp.Matrix]:
    """``(E, Q)``, 2k x 2k, with ``-E^-1 Q`` the real Jordan matrix of ``a +- i b`` with blocks of
    size ``k`` (2 x 2 blocks ``[[a, b], [-b, a]]`` on the diagonal, ``I_2`` above it): the symmetric
    solutions ``S`` of ``S J = J^T S`` form a linear space; the first non-singular one met
    (free parameters set to small integers in a fixed order) is ``E``, and ``Q = -E J``."""
    n = 2 * k
    J = sp.zeros(n, n)
    for i in range(k):
        J[2 * i : 2 * i + 2, 2 * i : 2 * i + 2] = sp.Matrix([[a, b], [-b, a]])
        if i + 1 < k:
            J[2 * i : 2 * i + 2, 2 * i + 2 : 2 * i + 4] = sp.eye(2)
    names = {(i, j): sp.Symbol(f"s{i}{j}") for i in range(n) for j in range(i, n)}
    S = sp.Matrix(n, n, lambda i, j: names[(min(i, j), max(i, j))])
    solution = sp.solve(list(S * J - J.T * S), list(names.values()), dict=True)
    ensure(len(solution) == 1, "the intertwining equations are linear")
    general = S.subs(solution[0])
    free = sorted(general.free_symbols, key=str)
    for values in itertools.product((1, 0, -1, 2), repeat=len(free)):
        E = general.subs(dict(zip(free, values, strict=True)))
        if E.det() != 0:
            return E, -E * J
    raise AssertionError("no non-singular symmetric intertwiner found")  # pragma: no cover


def canonical_pencil(t: SegreType, signs: Sequence[int]) -> tuple[sp.Matrix, sp.Matrix]:
    """A block-diagonal pencil of type ``t``: real eigenvalues 0, 1, 2, ... with the given signs,
    one per real block in order; non-real pairs ``j +- i`` (j = 1, 2)."""
    blocks: list[tuple[sp.Matrix, sp.Matrix]] = []
    it = iter(signs)
    for value, partition in enumerate(t.real):
        blocks += [real_block(k, value, next(it)) for k in partition]
    for j, partition in enumerate(t.pairs, start=1):
        blocks += [pair_block(k, j, 1) for k in partition]
    return sp.diag(*(e for e, _ in blocks)), sp.diag(*(q for _, q in blocks))


def package_segre(E: sp.Matrix, Q: sp.Matrix) -> str:
    """The Segre symbol computed by the package (invariant factors over Q, exact)."""

    def rat(M: sp.Matrix) -> list[list[Fraction]]:
        return [[Fraction(int(v.p), int(v.q)) for v in M.row(i)] for i in range(4)]

    return str(segre_symbol(rat(E), rat(Q)))


def ellipsoid_form(E: sp.Matrix) -> sp.Matrix:
    """A rational ``T`` with ``T^T E T = diag(p1, p2, p3, -n)``, ``p_i, n > 0``, for ``E`` of signature
    (3, 1): a vector ``x`` with ``x^T E x < 0`` comes last, and an ``E``-orthogonal basis of its
    ``E``-orthogonal complement (on which ``E`` is positive definite, so Gram-Schmidt never meets a
    zero pivot) comes first.  ``diag(p1, p2, p3, -n)`` is the ellipsoid
    ``p1 x^2 + p2 y^2 + p3 z^2 = n`` and the congruence keeps the Segre type."""
    unit = [sp.Matrix([1 if i == k else 0 for i in range(4)]) for k in range(4)]
    trial = [*unit, *(u + s * w for u, w in itertools.combinations(unit, 2) for s in (1, -1))]
    x = next((v for v in trial if (v.T * E * v)[0, 0] < 0), None)
    ensure(x is not None, "a vector of negative E-norm among e_i, e_i +- e_j")
    basis: list[sp.Matrix] = []
    for u in unit:
        w = u - (x.T * E * u)[0, 0] / (x.T * E * x)[0, 0] * x
        for b in basis:
            w = w - (b.T * E * w)[0, 0] / (b.T * E * b)[0, 0] * b
        if any(w) and len(basis) < 3:
            ensure((w.T * E * w)[0, 0] > 0, "E is positive definite on the complement")
            basis.append(w)
    ensure(len(basis) == 3, "three E-orthogonal vectors")
    T = sp.Matrix.hstack(*basis, x)
    ensure(T.det() != 0, "a basis")
    D = T.T * E * T
    ensure(D.is_diagonal() and all(D[i, i] > 0 for i in range(3)) and D[3, 3] < 0, f"diagonal {D}")
    return T


# -- the root signs of Table 4 from the inertia count ---------------------------------------------

_a, _b, _c = sp.symbols("a b c", positive=True)
_X = sp.symbols("x y z w", real=True)


def standard_matrix(equation: str) -> sp.Matrix:
    """The symmetric matrix of a standard equation of Table 1 (in ``x, y, z`` with positive
    parameters ``a, b, c``), from its homogenisation: ``M_ij = d^2 F / dX_i dX_j / 2``."""
    x, y, z, w = _X
    names = {"a": _a, "b": _b, "c": _c, "x": x, "y": y, "z": z}
    f = sp.sympify(equation, locals=names)
    fh = sp.expand(f.subs({x: x / w, y: y / w, z: z / w}, simultaneous=True) * w**2)
    return sp.Matrix(4, 4, lambda i, j: sp.diff(fh, _X[i], _X[j]) / 2)


@dataclass(frozen=True)
class RootSignDerivation:
    """What the inertia count needs of a quadric ``Q`` in standard form, and what it gives."""

    positive: int  # n_+(Q)
    kernel: int  # dim ker Q, every kernel vector at infinity (last coordinate 0)
    unbounded: dict[int, bool]  # sigma -> every component of {sigma Q > 0} is unbounded (a ray)
    patterns: dict[str, str]  # region "R-" / "R+" -> root signs, negative first

    def pattern(self, region: str) -> str:
        return self.patterns[region]


def derive_root_signs(M: sp.Matrix) -> RootSignDerivation:
    """The root signs of ``det(l E + Q)`` for an ellipsoid ``E`` not in transversal contact with
    ``Q`` (matrix ``M`` in standard form), region by region, by the inertia count.

    ``N_-``, the number of negative roots, is ``n_+(Q) - 1`` when ``E`` lies in ``R+`` and
    ``n_+(Q) + 1`` in ``R-``; 0 is a root of multiplicity ``dim ker Q``."""
    signs: dict[int, int] = {}
    for value, multiplicity in M.eigenvals().items():
        sign = sp.sign(value)
        ensure(sign.is_number, f"the sign of the eigenvalue {value} is known")
        signs[int(sign)] = signs.get(int(sign), 0) + multiplicity
    positive, zero = signs.get(1, 0), signs.get(0, 0)
    kernel = M.nullspace()
    ensure(len(kernel) == zero, "a symmetric matrix: the kernel is the zero eigenspace")
    ensure(all(v[3] == 0 for v in kernel), "ker Q lies at infinity (last coordinate 0)")
    A, b = M[:3, :3], M[:3, 3]
    ensure(A.is_diagonal(), "the quadratic part of a standard form is diagonal")
    # Along p + t s e_k: Q = Q(p) + 2 t s (A_kk p_k + b_k) + t^2 A_kk (A diagonal): choosing s, sigma Q
    # does not decrease for t >= 0 as soon as sigma A_kk >= 0, so the ray stays in {sigma Q > 0}.
    p = sp.Matrix(sp.symbols("p1:4", real=True))
    t, s_ = sp.symbols("t s", real=True)
    for k in range(3):
        e = sp.Matrix([1 if i == k else 0 for i in range(3)])

        def value(q: sp.Matrix) -> sp.Expr:
            return (q.T * A * q)[0, 0] + 2 * (b.T * q)[0, 0] + M[3, 3]

        along = (
            value(p + t * s_ * e) - value(p) - 2 * t * s_ * (A[k, k] * p[k] + b[k]) - t**2 * s_**2 * A[k, k]
        )
        ensure(sp.expand(along) == 0, f"Q along the axis {k}")
    unbounded = {sigma: any(sigma * sp.sign(A[k, k]) >= 0 for k in range(3)) for sigma in (1, -1)}
    patterns = {}
    for region, negative in (("R+", positive - 1), ("R-", positive + 1)):
        patterns[region] = "-" * negative + "0" * zero + "+" * (4 - negative - zero)
        ensure(4 - negative - zero >= 0, f"{region}: at most four roots")
    return RootSignDerivation(positive, zero, unbounded, patterns)
