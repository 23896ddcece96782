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


def _fibonacci(n):
    """``n`` nearly even unit vectors."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    phi = np.pi * (1 + 5**0.5) * k
    s = np.sqrt(1 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], -1)


def _first_hit(a, b, c):
    """The least positive root of ``a s^2 + b s + c`` (numpy, inf when none)."""
    with np.errstate(all="ignore"):
        d = b * b - 4 * a * c
        sq = np.sqrt(np.where(d >= 0, d, np.nan))
        r1 = (-b - sq) / (2 * a)
        r2 = (-b + sq) / (2 * a)
        lin = np.where(b != 0, -c / b, np.nan)
        r1 = np.where(a == 0, lin, r1)
        r2 = np.where(a == 0, lin, r2)
        r1 = np.where(r1 > 0, r1, np.inf)
        r2 = np.where(r2 > 0, r2, np.inf)
        out = np.fmin(r1, r2)
    return np.where(np.isnan(out), np.inf, out)


def surface_gap(E, Q, *, digits=40, shift=None, n_points=900, n_dirs=2500, polish=6):
    """``min |x - y|`` over ``x`` on the surface of ``E`` and ``y`` on that of ``Q``, by rays:
    from each point ``x`` of ``E`` (the unit sphere mapped by a Cholesky factor) cast rays in
    every direction ``w``; the least positive parameter at which a ray meets ``Q`` is a length
    ``|x - y|``.  A grid over both spheres in binary64, then Newton's method on the gradient in
    four local chart coordinates at ``digits`` digits.  ``shift`` (mpf 3-vector) translates
    ``E`` first.  For solids apart this is their distance."""
    with working_precision(dps=digits + 15):
        A, c, r = _centred(E)
        if shift is not None:
            c = c + mpmath.matrix(list(shift))
        L = mpmath.cholesky(A)
        T = mpmath.sqrt(r) * (L**-1).T
        M = _mat(Q)
        Q00, bq, q33 = M[:3, :3], M[:3, 3], M[3, 3]
    Tf = np.array(T.tolist(), dtype=float)
    cf = np.array(c.T.tolist()[0], dtype=float)
    Qf = np.array(Q00.tolist(), dtype=float)
    bf = np.array(bq.T.tolist()[0], dtype=float)
    qf = float(q33)
    U = _fibonacci(n_points)
    W = _fibonacci(n_dirs)
    X = cf + U @ Tf.T  # points of E
    gx = X @ Qf + bf  # (n_points, 3)
    cx = np.einsum("ij,ij->i", X @ Qf, X) + 2 * X @ bf + qf
    a = np.einsum("ij,ij->i", W @ Qf, W)  # (n_dirs,)
    b = 2 * gx @ W.T  # (n_points, n_dirs)
    s = _first_hit(a[None, :], b, cx[:, None])
    flat = np.argsort(s, axis=None)
    starts, seen = [], set()
    for f in flat:
        i, j = divmod(int(f), n_dirs)
        if not np.isfinite(s[i, j]):
            break
        key = (i // 3, j // 25)
        if key in seen:
            continue
        seen.add(key)
        starts.append((U[i], W[j]))
        if len(starts) >= polish:
            break

    def hit(x, w):
        aa = (w.T * Q00 * w)[0]
        bb = 2 * ((Q00 * x + bq).T * w)[0]
        cc = (x.T * Q00 * x)[0] + 2 * (bq.T * x)[0] + q33
        roots = [v for v in _quadratic(aa, bb, cc) if v > 0]
        return min(roots) if roots else mpmath.inf

    best = mpmath.inf
    with working_precision(dps=digits + 15):
        for u0, w0 in starts:
            e1, e2 = _chart(u0)
            f1, f2 = _chart(w0)

            def g(p, q, m, n, u0=u0, e1=e1, e2=e2, w0=w0, f1=f1, f2=f2):
                u = mpmath.matrix(list(u0)) + p * mpmath.matrix(list(e1)) + q * mpmath.matrix(list(e2))
                w = mpmath.matrix(list(w0)) + m * mpmath.matrix(list(f1)) + n * mpmath.matrix(list(f2))
                return hit(c + T * (u / mpmath.norm(u)), w / mpmath.norm(w))

            def grad(*z):
                return [mpmath.diff(lambda h, k=k: g(*z[:k], h, *z[k + 1 :]), z[k]) for k in range(4)]

            zero = mpmath.mpf(0)
            try:
                z = mpmath.findroot(
                    [lambda *z, k=k: grad(*z)[k] for k in range(4)],
                    (zero, zero, zero, zero),
                    tol=mpmath.mpf(10) ** (-2 * digits),
                    maxsteps=60,
                )
                best = min(best, g(*z))
            except (ValueError, ZeroDivisionError):
                best = min(best, g(zero, zero, zero, zero))
    return best
