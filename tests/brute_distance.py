"""A brute-force minimiser at high precision: the tests' independent reference for the
first-contact scale and the distance.

Nothing here uses the pencil, the discriminant or the secular equation of the package.
A function of a direction ``u`` on the unit sphere is minimised by a grid of directions
(numpy, binary64), then each of the best few grid points is polished by Newton's method on
the gradient in a local chart, with mpmath at ``digits`` significant digits and numerical
derivatives (``mpmath.diff``), and the least polished value is returned.

* :func:`ray_scale`: cast rays from the centre of ``E`` in the metric of ``E``; the smallest
  positive parameter at which a ray meets the surface of ``Q`` (a quadratic equation per ray)
  is the scale at which ``E`` reaches that point, and the first-contact scale is its minimum
  over the directions.
* :func:`perram_wertheim`: the contact function of two ellipsoids by its own formula
  (Perram and Wertheim 1985), a maximum over ``l`` in ``[0, 1]`` found by golden section.
* :func:`plane_gap`: the signed distance of the lowest point of ``E`` above a plane, minimised
  over the surface of ``E``.
"""

from __future__ import annotations

import mpmath
import numpy as np

from quadric_contact.exact.precision import working_precision


def _mat(q):
    return mpmath.matrix([[mpmath.mpf(x.numerator) / x.denominator for x in row] for row in q.matrix])


def _centred(E):
    M = _mat(E)
    A = M[:3, :3]
    b = M[:3, 3]
    c = -(A**-1) * b
    r = (c.T * A * c)[0] - M[3, 3]
    return A, c, r


def _chart(u0):
    """Two unit vectors orthogonal to ``u0`` and to each other."""
    a = np.array([1.0, 0.0, 0.0]) if abs(u0[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = np.cross(u0, a)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u0, e1)
    return e1, e2


def minimise_on_sphere(fn, *, digits=40, grid=48, polish=6):
    """``min fn(u)`` over unit vectors ``u`` (mpmath 3-vectors), to about ``digits`` digits.

    ``fn`` returns an mpf, or ``+inf`` where undefined.  The minimiser must be a smooth,
    nondegenerate local minimum (a tangency), which every test pair is built to have.
    """
    th = np.linspace(0, np.pi, grid + 1)[1:-1]
    ph = np.linspace(0, 2 * np.pi, 2 * grid, endpoint=False)
    dirs = np.array([[np.sin(a) * np.cos(b), np.sin(a) * np.sin(b), np.cos(a)] for a in th for b in ph])
    dirs = np.vstack([dirs, [[0, 0, 1], [0, 0, -1]]])
    with working_precision(dps=17):
        vals = np.array([float(fn(mpmath.matrix(list(u)))) for u in dirs])
    order = np.argsort(vals)
    best = mpmath.inf
    with working_precision(dps=digits + 10):
        for i in order[:polish]:
            if not np.isfinite(vals[i]):
                continue
            u0 = dirs[i]
            e1, e2 = _chart(u0)

            def g(a, b, u0=u0, e1=e1, e2=e2):
                v = mpmath.matrix(list(u0)) + a * mpmath.matrix(list(e1)) + b * mpmath.matrix(list(e2))
                return fn(v / mpmath.norm(v))

            try:
                a, b = mpmath.findroot(
                    [
                        lambda a, b: mpmath.diff(lambda x: g(x, b), a),
                        lambda a, b: mpmath.diff(lambda y: g(a, y), b),
                    ],
                    (mpmath.mpf(0), mpmath.mpf(0)),
                    tol=mpmath.mpf(10) ** (-2 * digits),
                    maxsteps=60,
                )
                best = min(best, g(a, b))
            except (ValueError, ZeroDivisionError):
                best = min(best, g(mpmath.mpf(0), mpmath.mpf(0)))
    return best


def ray_scale(E, Q, *, digits=40):
    """The first-contact scale of ``E`` to the surface of ``Q`` by ray casting."""
    with working_precision(dps=digits + 10):
        A, c, r = _centred(E)
        L = mpmath.cholesky(A)
        Linv_T = (L**-1).T
        M = _mat(Q)
        Q00, bq = M[:3, :3], M[:3, 3]
        qc = (c.T * Q00 * c)[0] + 2 * (bq.T * c)[0] + M[3, 3]
        grad = Q00 * c + bq

    def s_of(u):
        w = mpmath.sqrt(r) * (Linv_T * u)
        a = (w.T * Q00 * w)[0]
        b = 2 * (grad.T * w)[0]
        roots = [x for x in _quadratic(a, b, qc) if x > 0]
        return min(roots) if roots else mpmath.inf

    return minimise_on_sphere(s_of, digits=digits)


def _quadratic(a, b, c):
    if a == 0:
        return [] if b == 0 else [-c / b]
    d = b * b - 4 * a * c
    if d < 0:
        return []
    s = mpmath.sqrt(d)
    # the stable pair of formulas
    q = -(b + mpmath.sign(b) * s) / 2 if b != 0 else s / 2
    return [q / a, c / q] if q != 0 else [mpmath.mpf(0)]


def perram_wertheim(E, Q, *, digits=40):
    """``sqrt(F)`` for the Perram-Wertheim contact function ``F`` of two ellipsoids:
    ``F = max_{l in [0, 1]} l (1 - l) d^T ((1 - l) A^-1 + l B^-1)^-1 d`` with ``d`` the
    difference of the centres and ``x^T A x <= 1``, ``x^T B x <= 1`` the centred solids."""
    with working_precision(dps=digits + 10):
        A, ca, ra = _centred(E)
        B, cb, rb = _centred(Q)
        Ai, Bi = (A / ra) ** -1, (B / rb) ** -1
        d = cb - ca

        def F(lam):
            return lam * (1 - lam) * (d.T * ((1 - lam) * Ai + lam * Bi) ** -1 * d)[0]

        lo, hi = mpmath.mpf(0), mpmath.mpf(1)
        phi = (mpmath.sqrt(5) - 1) / 2
        while hi - lo > mpmath.mpf(10) ** (-digits // 2 - 4):
            m1, m2 = hi - phi * (hi - lo), lo + phi * (hi - lo)
            if F(m1) < F(m2):
                lo = m1
            else:
                hi = m2
        # the maximiser is known to ~digits/2 digits; the value is then known to ~digits
        return mpmath.sqrt(F((lo + hi) / 2))


def plane_gap(E, normal, offset, *, digits=40):
    """``min over the surface of E of (n . x - d) / |n|``: the signed distance of the solid of
    ``E`` from the plane ``n . x = d`` (negative: the depth below it)."""
    with working_precision(dps=digits + 10):
        A, c, r = _centred(E)
        L = mpmath.cholesky(A)
        Linv_T = (L**-1).T
        n = mpmath.matrix([mpmath.mpf(x.numerator) / x.denominator for x in normal])
        d = mpmath.mpf(offset.numerator) / offset.denominator
        nn = mpmath.norm(n)

    def h(u):
        x = c + mpmath.sqrt(r) * (Linv_T * u)
        return ((n.T * x)[0] - d) / nn

    return minimise_on_sphere(h, digits=digits)
