"""The signed distance of a sphere from a quadric's solid from one certified root of the
point-quadric secular equation: exact real algebraic numbers without the pencil's discriminant.

The certificate
---------------
Translate to the centre ``c`` of the sphere: the quadric is ``Q(c + y) = y^T A y + 2 b . y + q``
with ``q = Q(c)``.  For a multiplier ``mu`` with ``M = I + mu A`` positive definite, the function
``|y|^2 + mu Q(c + y)`` is strictly convex, with minimiser ``y(mu) = -mu M^-1 b`` and minimum
``L(mu) = mu q - mu^2 b^T M^-1 b``.  If ``Q(c + y(mu)) = 0``, every point ``y`` of the surface
has ``|y|^2 = |y|^2 + mu Q(c + y) >= L(mu) = |y(mu)|^2``, with equality at ``y(mu)`` only: the
point ``c + y(mu)`` is *the* nearest point of the surface, at squared distance ``L(mu)``.  No
other critical point of the distance has to be compared with it.

On the interval of definite members ``phi(mu) = Q(c + y(mu))`` decreases
(``phi' = -2 g^T M^-1 g`` with ``g`` the half-gradient at ``y(mu)``) from ``phi(0) = q``.  With
``det M = 1 + s1 mu + s2 mu^2 + s3 mu^3`` (``s_k`` the principal minor sums of ``A``) and
``adj M = I + mu (s1 I - A) + mu^2 adj A``::

    L = N / det,   N = mu q det - mu^2 b^T adj(M) b,   phi = L' = S / det^2,   S = det N' - N det'

(``S`` is the secular polynomial, of degree at most 6).  The root ``mu*`` of ``phi`` is found
in binary64 on the eigenvalues of ``A`` and certified exactly: rationals ``a < b`` with
``I + a A`` and ``I + b A`` positive definite (then so is every member between them) and
``S(a) > 0 > S(b)``.  It is the only root of ``S`` in ``[a, b]``: the root of the one
irreducible factor ``f`` of ``S`` that changes sign there.

The numbers
-----------
Every number of the answer is a rational function ``w(mu*) / u(mu*)`` of ``mu*``, or a square
root of one: the squared distance of the centre ``h = |c - p*|^2 = N / det``
(``= N' / det'`` at a root of ``S``), the coordinates of the nearest point
``p* = c - mu adj(M) b / det``, the squares ``y_i^2 / h`` of the unit normal's coordinates
(``y = p* - c``) and ``rho^2 y_i^2 / h``, the squares of ``point_E - c``.  Its characteristic
polynomial over ``Q(mu*)`` is ``Res_mu(f, x u - w)`` up to a constant (interpolated from
``deg f + 1`` resultants at integer ``x``), a power of its minimal polynomial, which is
therefore its squarefree part: no factorisation.

The signed distance ``s sqrt(h) - rho`` (``s = -1`` when the centre lies in the solid) is a
root of ``F = U^2 - rho^2 V^2`` with ``m_h((x + rho)^2) = U + rho V`` (``U, V`` over Q,
``m_h`` the minimal polynomial of ``h``): the characteristic polynomial over Q of
``sqrt(h) - rho`` in the field ``k(sqrt h, rho)``, ``k = Q(h)``, of degree ``4 deg m_h``.
``F`` is the minimal polynomial when that field has this degree and ``F`` is squarefree (then
the number generates the field).  Norms and small primes certify the degree: a square of
``k`` has a square norm, so ``h`` (and ``rho^2 h``) is no square in ``k`` when
``N(h) = (-1)^n m_0 / m_n`` is no rational square; and a prime ``p`` at which ``m_h`` is
squarefree with a root ``a`` gives a prime ``(p, h - a)`` of ``k`` of degree one, so ``rho^2``
(or ``h``, ``rho^2 h``) is no square in ``k`` when it is none modulo ``p`` (Kummer-Dedekind).
``F`` squarefree modulo a prime is squarefree.  Where ``h`` is a square of ``k`` (the slab of
two parallel planes: the distance of the centre from a plane is in ``k``), ``m_h(x^2)``
factors and ``s sqrt(h)`` is a root of one factor ``g``: the same construction with
``g(x + rho)``, factored.  Otherwise ``F`` is factored.  The witnesses' square roots of numbers
``v`` of ``Q(mu*)`` are roots of ``m_v(x^2)``, irreducible when the norm of ``v`` is no
rational square (else factored).

Each number is isolated among the roots of its minimal polynomial by an interval from
certified ball arithmetic (``arb``, the root ``mu*`` contracted by the interval Newton
operator): the polynomial changes sign across it (exact rational signs) and its derivative
has no zero on it (a ball), so exactly one root lies inside.

When a step does not certify (no root of ``phi`` between the poles: the nearest points are a
circle or meet the singular members, the symmetric configurations; or a ball too wide),
:func:`sphere_distance` returns None and the caller takes the general route
(:mod:`quadric_contact.theory.contact_scale` and the secular equation).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache
from typing import Any

import flint
import numpy as np

from quadric_contact.exact.algebraic import RealAlgebraic
from quadric_contact.exact.isolating import primitive, root_among, root_in_ball, sign_at_rational
from quadric_contact.exact.precision import working_precision
from quadric_contact.model.quadric import Quadric

__all__ = ["SphereDistance", "SpherePair", "sphere_distance", "sphere_pair"]

Point = tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic]

_BITS = (128, 512, 2048)
"""The precisions (bits) of the ball arithmetic, tried in turn."""

_PRIMES = 24
"""How many primes are tried to certify the degree of the distance's field."""


@dataclass(frozen=True)
class SphereDistance:
    """The exact answer of the fast path.

    Attributes
    ----------
    distance : RealAlgebraic
        The signed distance.
    foot : callable
        ``foot()``: the nearest point of the surface of ``K`` to the centre (a tuple of 3
        RealAlgebraic), its coordinates isolated when asked for; None if the balls did not
        isolate them.
    multiplier : callable
        ``multiplier()``: ``(mu, point_of)``, the multiplier of the nearest point (for ``K`` as
        given) and ``point_of(m, i)``, coordinate ``i`` of ``c - m adj(I + m A) b / det`` at a
        number ``m`` of any type with ``+ - * /`` and Fraction constants (the witnesses
        evaluate it on the multiplication matrices of ``Q(mu)``); built when first asked for.
    witnesses : callable
        ``witnesses()``: ``(normal, point_E)``, the unit normal of ``K`` at the nearest point,
        out of the solid, and ``point_E = c - rho normal``; None if the balls did not isolate
        them.
    """

    distance: RealAlgebraic
    foot: Callable[[], tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic] | None]
    multiplier: Callable[[], tuple[RealAlgebraic, Callable[[Any, int], Any]]]
    witnesses: Callable[[], tuple[Point, Point] | None]


# -- integer polynomials and their roots ---------------------------------------------------


def _fmpq(x: Fraction) -> Any:
    return flint.fmpq(x.numerator, x.denominator)


def _horner(cs: Sequence[Any], x: Any) -> Any:
    out = cs[-1]
    for a in reversed(cs[:-1]):
        out = out * x + a
    return out


@lru_cache(maxsize=8)
def _vandermonde_inverse(n: int) -> Any:
    """The inverse of the Vandermonde matrix of the nodes ``-n//2 .. n - n//2`` (``n + 1`` of
    them), as an ``fmpq_mat``."""
    nodes = _nodes(n)
    V = flint.fmpq_mat(n + 1, n + 1, [x**k for x in nodes for k in range(n + 1)])
    return V.inv()


def _nodes(n: int) -> list[int]:
    return [k - n // 2 for k in range(n + 1)]


def _minimal_polynomial(f: Any, u: Any, w: Any) -> Any:
    """The minimal polynomial (``fmpz_poly``, primitive) of ``w(mu) / u(mu)`` for ``mu`` a root
    of the irreducible ``f``: the squarefree part of ``Res_mu(f, x u - w)``, a power of it.
    None when ``u`` vanishes at a root of ``f`` (the resultant then has a lower degree)."""
    n = f.degree()
    top = max(u.degree(), w.degree())
    lc = f.leading_coefficient()
    values = []
    for x in _nodes(n):
        g = u * x - w  # Res(f, g) = lc(f)^deg(g) prod g(roots): made formal of degree `top`
        values.append(f.resultant(g) * lc ** (top - g.degree()) if not g.is_zero() else 0)
    values = flint.fmpq_mat(n + 1, 1, values)
    coeffs = _vandermonde_inverse(n) * values
    R = flint.fmpq_poly([coeffs[k, 0] for k in range(n + 1)]).numer()
    if R.degree() < n:
        return None  # u vanishes at a conjugate: the quotient is not defined there
    g = R.gcd(R.derivative())
    if g.degree() > 0:
        R = R // g
    return primitive(R)


@lru_cache(maxsize=1)
def _primes() -> tuple[int, ...]:
    """Primes below ``2^31`` for the certificates (derived once, by flint's primality test)."""
    out: list[int] = []
    n = (1 << 31) - 1
    while len(out) < _PRIMES:
        if flint.fmpz(n).is_prime():
            out.append(n)
        n -= 2
    return tuple(out)


def _square(n: int) -> bool:
    return n >= 0 and math.isqrt(n) ** 2 == n


def _rational_sqrt(x: Fraction) -> Fraction | None:
    n, d = x.numerator, x.denominator
    sn, sd = math.isqrt(n), math.isqrt(d)
    return Fraction(sn, sd) if sn * sn == n and sd * sd == d else None


def _field_degree_certified(m: Any, r2: Fraction | None) -> tuple[bool, bool]:
    """``(proven, square)``: is it proven that ``h`` (a root of the irreducible ``m``) is no
    square in ``k = Q(h)`` and, with ``r2`` (``rho^2``, not a rational square; None: skip),
    that ``r2`` and ``r2 h`` are no squares in ``k`` either (then ``k(sqrt h, rho)`` has
    degree 4 over ``k``)?  ``square``: not proven because ``h`` looks like a square.

    First by norms: a square of ``k`` has a rational square for norm, and
    ``N(h) = (-1)^n m_0 / m_n`` (a square iff ``(-1)^n m_0 m_n`` is), ``N(r2) = r2^n``.  Then
    by primes: a prime ``p`` not dividing the leading coefficient at which ``m`` has a simple
    root ``a`` gives a prime ``(p, h - a)`` of ``k`` of degree one (Kummer-Dedekind, over the
    integers localised at ``p``); a square of ``k`` that is a unit there is a square modulo
    ``p``."""
    n = m.degree()
    lc, m0 = int(m[n]), int(m[0])
    norm = (-1) ** n * m0 * lc
    rr = 0 if r2 is None else r2.numerator * r2.denominator
    need_h = _square(norm)
    need_r = r2 is not None and n % 2 == 0
    need_rh = r2 is not None and _square(norm if n % 2 == 0 else norm * rr)
    if not (need_h or need_r or need_rh):
        return True, False
    if n == 1:  # k = Q: the norms decide
        return False, need_h
    tries = 4  # primes with roots spent on h or r2 h: a square norm mostly means a square
    for p in _primes():
        if lc % p == 0 or m0 % p == 0 or (rr and rr % p == 0):
            continue
        half = (p - 1) // 2
        r_no = bool(rr) and pow(rr % p, half, p) != 1
        if not (need_h or need_rh or r_no):
            continue  # p can prove nothing still needed
        mp = flint.nmod_poly(m, p)
        if mp.gcd(mp.derivative()).degree() > 0:
            continue  # not squarefree modulo p: every root would need its own check
        if not (need_h or need_rh):  # a root is needed, not its value
            x = flint.nmod_poly([0, 1], p)
            if (x.pow_mod(p, mp) - x).gcd(mp).degree() > 0:
                need_r = False
        else:
            roots = [int(a) for a, _ in mp.roots()]
            if roots:
                need_r = need_r and not r_no
                tries -= 1
            for a in roots:
                need_h = need_h and pow(a, half, p) == 1
                need_rh = need_rh and pow(rr % p * a, half, p) == 1
            if tries == 0 and (need_h or need_rh):
                return False, need_h
        if not (need_h or need_r or need_rh):
            return True, False
    return False, need_h


def _squarefree_mod_prime(F: Any) -> bool:
    lc = int(F.leading_coefficient())
    for p in _primes()[:6]:
        if lc % p == 0:
            continue
        Fp = flint.nmod_poly(F, p)
        if Fp.gcd(Fp.derivative()).degree() == 0:
            return True
    return False


def _conjugate_product(g: Any, r2: Fraction, squared: bool) -> Any:
    """``P(x) = g(z(x, rho)) g(z(x, -rho))`` for ``z = (x + rho)^2`` (``squared``) or
    ``z = x + rho``, ``rho^2 = r2``, as a primitive integer polynomial; ``g(z(x, rho))`` itself
    when ``rho`` is rational.  With ``g(z(x, rho)) = U + rho V`` (``U, V`` over Q) the product
    is ``U^2 - r2 V^2``."""
    rho = _rational_sqrt(r2)
    if rho is not None:
        x_rho = flint.fmpq_poly([_fmpq(rho), 1])
        return primitive(flint.fmpq_poly(g)(x_rho * x_rho if squared else x_rho).numer())
    r = _fmpq(r2)
    if squared:
        s, t = flint.fmpq_poly([r, 0, 1]), flint.fmpq_poly([0, 2])  # (x + rho)^2 = s + rho t
    else:
        s, t = flint.fmpq_poly([0, 1]), flint.fmpq_poly([1])  # x + rho
    rt = t * r
    U = flint.fmpq_poly([0])
    V = flint.fmpq_poly([0])
    for c in reversed(g.coeffs()):
        U, V = U * s + V * rt + c, U * t + V * s
    return primitive((U * U - V * V * r).numer())


def _vanishing(factors: Sequence[Any], ball: Any) -> Any:
    """The one factor whose enclosure on ``ball`` holds 0, or None."""
    if not ball.is_finite():
        return None
    hits = [g for g in factors if g(ball).contains(0)]
    return primitive(hits[0]) if len(hits) == 1 else None


def _distance_number(m: Any, r2: Fraction, balls: Callable[[int], tuple[Any, Any]]) -> RealAlgebraic | None:
    """The signed distance ``beta - rho``, ``beta = s sqrt(h)`` with ``h`` a root of the
    irreducible ``m`` and ``rho^2 = r2``; ``balls(bits)`` gives enclosures of ``beta`` and
    ``rho`` at about ``bits`` bits.

    ``F = U^2 - r2 V^2`` from ``m((x + rho)^2)`` (the module notes) is the minimal
    polynomial when :func:`_field_degree_certified` proves the degree of the field and ``F``
    is squarefree.  Where ``h`` is a square of ``k``, ``m(x^2)`` factors and ``beta`` is a
    root of a factor ``g`` of degree ``deg m``: the same construction on ``g(x + rho)``, and
    its factors.  Otherwise ``F`` is factored."""
    rational = _rational_sqrt(r2) is not None
    proven, square = _field_degree_certified(m, None if rational else r2)
    F = _conjugate_product(m, r2, squared=True)
    if proven and (rational or _squarefree_mod_prime(F)):
        return _first(lambda bits: root_in_ball(F, _difference(balls(bits))))
    if square:
        halves = [g for g, _ in primitive(m(flint.fmpz_poly([0, 0, 1]))).factor()[1]]
        if len(halves) > 1:  # h = beta^2 in k
            g = _first(lambda bits: _vanishing(halves, balls(bits)[0]))
            if g is None:
                return None
            factors = [f for f, _ in _conjugate_product(g, r2, squared=False).factor()[1]]
            return _first(lambda bits: root_among(factors, _difference(balls(bits))))
    factors = [f for f, _ in F.factor()[1]]
    return _first(lambda bits: root_among(factors, _difference(balls(bits))))


def _difference(pair: tuple[Any, Any]) -> Any:
    return pair[0] - pair[1]


def _first(attempt: Callable[[int], Any]) -> Any:
    """``attempt(bits)`` at the precisions of :data:`_BITS` in turn, the first not None."""
    for bits in _BITS:
        with working_precision(bits + 16):
            out = attempt(bits)
        if out is not None:
            return out
    return None


# -- the pair ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Secular:
    """The secular polynomial and the numerators of the answer, over the integers, for the
    quadric scaled to integers (its multiplier scales with it)."""

    A: list[list[int]]
    det: Any  # fmpz_poly: det(I + mu A)
    secular: Any  # fmpz_poly: S, the secular polynomial
    N: Any  # fmpz_poly: dc^2 N (L = N / (dc^2 det))
    P: list[Any]  # fmpz_poly: C_i det - mu (adj M b)_i dc  (p_i = P_i / (dc det))
    dc: int
    q: int  # dc^2 Q(c) (integer-scaled quadric)
    b: list[int]  # dc b


def _secular(K: Quadric, C: Sequence[int], dc: int) -> _Secular:
    """``K`` (scaled to integers) translated to ``c = C / dc``."""
    ints, _ = K.integer_form()
    a00, a01, a02, b0, a11, a12, b1, a22, b2, k33 = ints
    A = [[a00, a01, a02], [a01, a11, a12], [a02, a12, a22]]
    bq = (b0, b1, b2)
    AC = [A[i][0] * C[0] + A[i][1] * C[1] + A[i][2] * C[2] for i in range(3)]
    b = [AC[i] + bq[i] * dc for i in range(3)]  # dc (A c + b)
    q = sum(C[i] * (AC[i] + 2 * bq[i] * dc) for i in range(3)) + k33 * dc * dc  # dc^2 Q(c)
    ad00, ad11, ad22 = a11 * a22 - a12 * a12, a00 * a22 - a02 * a02, a00 * a11 - a01 * a01
    ad01, ad02, ad12 = a02 * a12 - a01 * a22, a01 * a12 - a02 * a11, a01 * a02 - a00 * a12
    adj = [[ad00, ad01, ad02], [ad01, ad11, ad12], [ad02, ad12, ad22]]
    s1 = a00 + a11 + a22
    s2 = ad00 + ad11 + ad22
    s3 = a00 * ad00 + a01 * ad01 + a02 * ad02
    Ab = [A[i][0] * b[0] + A[i][1] * b[1] + A[i][2] * b[2] for i in range(3)]
    v1 = [s1 * b[i] - Ab[i] for i in range(3)]
    v2 = [adj[i][0] * b[0] + adj[i][1] * b[1] + adj[i][2] * b[2] for i in range(3)]
    w0 = b[0] * b[0] + b[1] * b[1] + b[2] * b[2]
    w1 = b[0] * v1[0] + b[1] * v1[1] + b[2] * v1[2]
    w2 = b[0] * v2[0] + b[1] * v2[1] + b[2] * v2[2]
    det = flint.fmpz_poly([1, s1, s2, s3])
    N = flint.fmpz_poly([0, q, q * s1 - w0, q * s2 - w1, q * s3 - w2])
    secular = N.derivative() * det - N * det.derivative()
    P = [det * C[i] - flint.fmpz_poly([0, b[i], v1[i], v2[i]]) for i in range(3)]
    return _Secular(A, det, secular, N, P, dc, q, b)


def _floats(xs: Sequence[int], shift: int) -> list[float] | None:
    """``x / 2^shift`` in binary64 (None on overflow)."""
    try:
        return [float(x >> shift) for x in xs]
    except OverflowError:
        return None


def _root_float(A: list[list[int]], b: list[int], q: int) -> float | None:
    """The root of ``phi`` between the poles, in binary64 (on the eigenvalues of ``A``: Newton's
    method kept inside a bracket); None when ``phi`` has no sign change there.

    ``phi`` is unchanged when ``b`` and ``q`` are scaled by ``2^k`` and ``4^k``, and its root
    scales inversely with ``A``: both are scaled into the range of binary64 first."""
    ea = max(max(abs(x) for row in A for x in row).bit_length() - 600, 0)
    eb = max(max(abs(x) for x in b).bit_length() - 600, (abs(q).bit_length() - 1200) // 2, 0)
    flat = _floats([x for row in A for x in row], ea)
    bs = _floats(b, eb)
    qs = _floats([q], 2 * eb)
    if flat is None or bs is None or qs is None or qs[0] == 0:
        return None
    lam, V = np.linalg.eigh(np.array(flat).reshape(3, 3))
    if not np.all(np.isfinite(lam)):
        return None
    lams = [float(x) for x in lam]
    beta2 = [float(x) ** 2 for x in V.T @ np.array(bs)]
    qf = qs[0]

    def phi(m: float) -> tuple[float, float]:
        val, der = qf, 0.0
        for la, be in zip(lams, beta2, strict=True):
            d = 1.0 + m * la
            val += m * be * (m * la / d - 2.0) / d
            der -= 2.0 * be / (d * d * d)
        return val, der

    lo = max((-1.0 / x for x in lams if x > 0), default=-math.inf)
    hi = min((-1.0 / x for x in lams if x < 0), default=math.inf)
    step = 1.0 / max(max(abs(x) for x in lams), 1e-300)
    if qf > 0:  # phi decreases from phi(0) > 0: the root is above 0
        lo = 0.0
        if not math.isfinite(hi):
            hi = step
            while phi(hi)[0] > 0:
                hi *= 2.0
                if hi > 1e300:
                    return None
    else:
        hi = 0.0
        if not math.isfinite(lo):
            lo = -step
            while phi(lo)[0] < 0:
                lo *= 2.0
                if lo < -1e300:
                    return None
    m = 0.5 * (lo + hi)
    for _ in range(300):
        v, d = phi(m)
        if not math.isfinite(v):
            return None
        if v == 0:
            break
        if v > 0:
            lo = m
        else:
            hi = m
        if hi - lo <= 4 * math.ulp(max(abs(lo), abs(hi))):
            break
        newton = m - v / d if d < 0 else math.nan
        m = newton if lo < newton < hi else 0.5 * (lo + hi)
    return math.ldexp(m, -ea)


def _definite(A: list[list[int]], det: Any, a: Any) -> bool:
    """Is ``I + a A`` positive definite (its leading principal minors positive)?  ``a`` an
    ``fmpq``."""
    m1 = 1 + a * A[0][0]
    m2 = m1 * (1 + a * A[1][1]) - a * a * (A[0][1] * A[0][1])
    return m1 > 0 and m2 > 0 and det(a) > 0


def _bracket(sec: _Secular, mf: float) -> tuple[Fraction, Fraction] | None:
    """Rationals ``a < mu* < b`` with definite ends and ``S(a) > 0 > S(b)``."""
    m = Fraction(mf)
    for bits in (40, 28, 16):
        w = abs(m) / (1 << bits)
        a, b = m - w, m + w
        qa, qb = _fmpq(a), _fmpq(b)
        secular = sec.secular
        if secular(qa) > 0 > secular(qb) and _definite(sec.A, sec.det, qa) and _definite(sec.A, sec.det, qb):
            return a, b
    return None


def _contract(f: Any, a: Fraction, b: Fraction, bits: int) -> Any:
    """A ball around the only root of ``f`` in ``[a, b]``, about ``bits`` bits wide: the
    interval Newton operator ``m - f(m) / f'(X)``, which holds every root of ``f`` in ``X``,
    intersected with ``X`` at every step."""
    X = flint.arb(_fmpq(a)).union(flint.arb(_fmpq(b)))
    df = f.derivative()
    tiny = flint.arb(2) ** (-bits)
    for _ in range(64):
        d = df(X)
        if d.contains(0):
            break
        m = flint.arb(X.mid())
        Y = (m - f(m) / d).intersection(X)
        if Y.rad() >= X.rad() * 0.75:
            break
        X = Y
        if X.rad() <= abs(X.mid()) * tiny:
            break
    return X


def _scaled_root(f: Any, a: Fraction, b: Fraction, d: int) -> RealAlgebraic:
    """``d mu`` for the only root ``mu`` of the irreducible ``f`` in ``[a, b]`` (``d > 0``)."""
    n = f.degree()
    g = primitive(flint.fmpz_poly([int(c) * d ** (n - k) for k, c in enumerate(f.coeffs())]))
    if n == 1:
        return RealAlgebraic(Fraction(-int(g[0]), int(g[1])))
    return RealAlgebraic._from_integer_polynomial(g, a * d, b * d)


@dataclass(frozen=True)
class SpherePair:
    """A sphere and a quadric, read once: the centre, ``rho^2``, the side of the centre and the
    secular data."""

    centre: tuple[Fraction, Fraction, Fraction]
    r2: Fraction
    inside: bool
    K: Quadric
    sec: _Secular


def sphere_pair(E: Quadric, K: Quadric) -> SpherePair:
    """The sphere ``E`` (the paper's sign) and the quadric ``K`` (the sign of its solid).

    Examples
    --------
    >>> p = sphere_pair(Quadric.sphere(1, (0, 0, 5)), Quadric.ellipsoid(3, 2, 2))
    >>> p.centre, p.r2, p.inside
    ((Fraction(0, 1), Fraction(0, 1), Fraction(5, 1)), Fraction(1, 1), False)
    """
    a00, _, _, e0, _, _, e1, _, e2, e33 = E.upper
    centre = (-e0 / a00, -e1 / a00, -e2 / a00)
    r2 = centre[0] ** 2 + centre[1] ** 2 + centre[2] ** 2 - e33 / a00
    dc = math.lcm(centre[0].denominator, centre[1].denominator, centre[2].denominator)
    sec = _secular(K, [x.numerator * (dc // x.denominator) for x in centre], dc)
    return SpherePair(centre, r2, sec.q < 0, K, sec)


def sphere_distance(pair: SpherePair) -> SphereDistance | None:
    """The signed distance of the sphere from the solid of ``K`` (the nearest point of the
    surface to the centre certified by a definite multiplier), or None where the certificate
    does not apply (the caller then takes the general route).

    Parameters
    ----------
    pair : SpherePair
        A sphere and a quadric of Table 1 (a plane has a closed form).

    Examples
    --------
    >>> r = sphere_distance(sphere_pair(Quadric.sphere(1, (0, 0, 5)), Quadric.ellipsoid(3, 2, 2)))
    >>> r.distance, [str(x) for x in r.foot()]
    (RealAlgebraic(2), ['0', '0', '2'])
    """
    sec, r2 = pair.sec, pair.r2
    if sec.q == 0:
        return None  # the centre on the surface
    mf = _root_float(sec.A, sec.b, sec.q)
    ab = None if mf is None else _bracket(sec, mf)
    if ab is None:
        return None
    a, b = ab
    factors = sec.secular.factor()[1]
    if len(factors) == 1 and factors[0][1] == 1:  # S irreducible: S(a) S(b) < 0 was checked
        f = primitive(factors[0][0])
    else:
        changes = (g for g, _ in factors if sign_at_rational(g, a) * sign_at_rational(g, b) < 0)
        f = next((primitive(g) for g in changes), None)
    if f is None:  # pragma: no cover - S changes sign on [a, b]
        return None
    m_h = _minimal_polynomial(f, sec.det.derivative() * (sec.dc * sec.dc), sec.N.derivative())
    if m_h is None:  # det' vanishes at a conjugate of mu*: the quotient N / det itself
        m_h = _minimal_polynomial(f, sec.det * (sec.dc * sec.dc), sec.N)
    if m_h is None:  # pragma: no cover - det has no root in common with f (det(mu*) > 0)
        return None
    s = -1 if pair.inside else 1

    def balls(bits: int) -> tuple[Any, Any]:
        X = _contract(f, a, b, bits)
        h = sec.N(X) / (sec.det(X) * (sec.dc * sec.dc))
        return s * h.sqrt(), flint.arb(_fmpq(r2)).sqrt()

    dist = _distance_number(m_h, r2, balls)
    if dist is None:
        return None
    return SphereDistance(
        dist, _foot(sec, f, a, b), _multiplier(sec, f, a, b, pair.K), _witnesses(pair, f, a, b)
    )


def _foot(
    sec: _Secular, f: Any, a: Fraction, b: Fraction
) -> Callable[[], tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic] | None]:
    """The nearest point ``c + y(mu*)``, exactly (each coordinate a number of ``Q(mu*)``)."""

    def foot() -> tuple[RealAlgebraic, RealAlgebraic, RealAlgebraic] | None:
        m_p = [_minimal_polynomial(f, sec.det * sec.dc, P) for P in sec.P]
        for bits in _BITS:
            with working_precision(bits + 16):
                X = _contract(f, a, b, bits)
                den = sec.det(X) * sec.dc
                p = [
                    None if m is None else root_in_ball(m, P(X) / den)
                    for m, P in zip(m_p, sec.P, strict=True)
                ]
            if p[0] is not None and p[1] is not None and p[2] is not None:
                return p[0], p[1], p[2]
        return None

    return foot


def _square_root(m: Any, ball: Any) -> RealAlgebraic | None:
    """``beta`` with ``beta^2 = v``, ``v`` a root of the irreducible ``m``, ``beta`` in ``ball``:
    a root of ``m(x^2)``, irreducible when the norm of ``v`` is no rational square (else
    factored)."""
    n = m.degree()
    P = primitive(m(flint.fmpz_poly([0, 0, 1])))
    if not _square((-1) ** n * int(m[0]) * int(m[n])):
        return root_in_ball(P, ball)
    return root_among([g for g, _ in P.factor()[1]], ball)


def _witnesses(
    pair: SpherePair, f: Any, a: Fraction, b: Fraction
) -> Callable[[], tuple[Point, Point] | None]:
    """The normal ``side y / |y|`` (``y = p* - c``; ``side`` ``+1`` for the centre in the solid,
    ``-1`` outside) and ``point_E = c - rho normal``.  ``normal_i^2 = y_i^2 / h`` is a number
    of ``Q(mu*)``, ``Y_i^2 / (det N)`` with ``Y_i = P_i - C_i det``; ``point_E_i - c_i`` is a
    square root of ``rho^2 normal_i^2``."""
    sec, r2 = pair.sec, pair.r2
    side = 1 if pair.inside else -1
    rn, rd = r2.numerator, r2.denominator

    def witnesses() -> tuple[Point, Point] | None:
        C = [int(x * sec.dc) for x in pair.centre]
        Y = [P - sec.det * C[i] for i, P in enumerate(sec.P)]  # dc det y_i
        m_u = [_minimal_polynomial(f, sec.det * sec.N, y * y) for y in Y]
        if any(m is None for m in m_u):
            return None
        m_t = []  # rho^2 normal_i^2: m(y / r2), scaled to integers
        for m in m_u:
            n = m.degree()
            m_t.append(
                primitive(flint.fmpz_poly([int(c) * rn ** (n - k) * rd**k for k, c in enumerate(m.coeffs())]))
            )
        for bits in _BITS:
            with working_precision(bits + 16):
                X = _contract(f, a, b, bits)
                den = sec.det(X) * sec.dc
                y = [y(X) / den for y in Y]
                norm = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt()
                rho = flint.arb(_fmpq(r2)).sqrt()
                normal = [_square_root(m, side * yi / norm) for m, yi in zip(m_u, y, strict=True)]
                shift = [_square_root(m, -rho * side * yi / norm) for m, yi in zip(m_t, y, strict=True)]
            if all(x is not None for x in normal) and all(x is not None for x in shift):
                point_E = tuple(_shifted(t, c) for t, c in zip(shift, pair.centre, strict=True))
                return tuple(normal), point_E  # type: ignore[return-value]
        return None

    return witnesses


def _shifted(t: Any, c: Fraction) -> RealAlgebraic:
    """``c + t`` for a rational ``c``: the minimal polynomial of ``t`` at ``x - c``, the
    isolating interval moved by ``c``."""
    if t.is_rational:
        return RealAlgebraic(c + t.as_fraction())
    g = primitive((flint.fmpq_poly(t.integer_poly)(flint.fmpq_poly([_fmpq(-c), 1]))).numer())
    return RealAlgebraic._from_integer_polynomial(g, t.lo + c, t.hi + c)


def _multiplier(
    sec: _Secular, f: Any, a: Fraction, b: Fraction, K: Quadric
) -> Callable[[], tuple[RealAlgebraic, Callable[[Any, int], Any]]]:
    """``(mu, point_of)`` for ``K`` as given, whose integer form is ``scale K``: its multiplier
    is ``scale mu*``."""

    def multiplier() -> tuple[RealAlgebraic, Callable[[Any, int], Any]]:
        _, scale = K.integer_form()
        return _scaled_root(f, a, b, scale), _point_of(sec, scale)

    return multiplier


def _point_of(sec: _Secular, scale: int) -> Callable[[Any, int], Any]:
    """``point_of(m, i)``: coordinate ``i`` of ``c + y(m)`` for the multiplier ``m`` of ``K`` as
    given (``m / scale`` for the quadric scaled to integers)."""
    det = [Fraction(int(x)) for x in sec.det.coeffs()]
    num = [[Fraction(int(x), sec.dc) for x in P.coeffs()] or [Fraction(0)] for P in sec.P]
    d = Fraction(scale)

    def point_of(m: Any, i: int) -> Any:
        t = m / d
        return _horner(num[i], t) / _horner(det, t)

    return point_of
