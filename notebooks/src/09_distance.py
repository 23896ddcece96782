# %% [markdown]
# # 9. How far from contact: the first-contact scale and the signed distance
#
# The predicates of the other notebooks say *whether* and *how* an ellipsoid $E$ meets a
# quadric $Q$.  Two numbers say *how far* a pair is from meeting:
#
# * the **first-contact scale** $s^*$: scale $E$ about its centre by $s$; at $s=s^*$ it first
#   touches the surface of $Q$ (`qc.contact_scale`);
# * the **signed distance**: the Euclidean distance between the solids, or minus the
#   penetration depth when they overlap, with witness points and a normal (`qc.distance`).
#
# Both are exact.  The first is read off the pencil $\det(\lambda E_t+Q)$ of the scaled
# ellipsoid $E_t$ ($t=s^2$).

# %%
from fractions import Fraction

import matplotlib.pyplot as plt
import numpy as np

import quadric_contact as qc
from quadric_contact.exact.algebraic import real_roots
from quadric_contact.theory.contact_scale import reached_at, scale_polynomial, scaled

# %% [markdown]
# ## The scaled pencil is affine in $t=s^2$
#
# Write $E$ as $(x-c)^TA(x-c)=r$.  Scaled by $s$ about $c$ it is $(x-c)^TA(x-c)=tr$: only the
# corner of the matrix moves, so $\det(\lambda E_t+Q)=P_0(\lambda)+t\,B(\lambda)$ with
# $B(\lambda)=-r\lambda\det(\lambda A+Q_{00})$.  A flat ellipsoid beside a hyperboloid of one
# sheet, both in the plane $z=0$ of the pictures below:

# %%
E = qc.Quadric.ellipsoid(Fraction(3, 2), Fraction(1, 2), Fraction(1, 2), center=(4, 1, 0))
Q = qc.Quadric.hyperboloid_one_sheet(1, Fraction(3, 2), 1)
P0, B = scale_polynomial(E, Q)
print("P_0 =", P0)
print("B   =", B)

# %% [markdown]
# Where $E_t$ is tangent to $Q$, the pencil has a multiple root (if $X$ is the point of
# tangency, $(\lambda_0E_t+Q)X=0$ and $\mathfrak P'(\lambda_0)=k\,X^TE_tX=0$).  So $t^*$ is a
# root of the discriminant $R(t)$ of $P_0+tB$ in $\lambda$.  Not every root is a first touch:
# a tangency may be complex, or happen after the surfaces already cross.  The package tries
# the candidates in order, with the exact touching predicate at a rational on each side.

# %%
r = qc.contact_scale(E, Q)
print("s* =", r.scale, "\n   =", r.scale.decimal(30))
candidates = real_roots(r.polynomial, Fraction(0), Fraction(100))
for t in candidates:
    print(f"t = {t.decimal(12):>18}  chosen: {t == r.squared}")
lo, hi = r.bracket
print(
    "E_t reaches Q's surface at t =",
    float(lo),
    ":",
    reached_at(E, Q, lo, "E"),
    "and at",
    float(hi),
    ":",
    reached_at(E, Q, hi, "E"),
)

# %% [markdown]
# The picture in the plane $z=0$: $Q$ (black), $E$ (blue), $E$ scaled by $s^*$ (red, touching),
# and $E$ scaled to the other positive candidates (grey, dashed): those are tangencies too,
# but not the first one.


# %%
def slice_values(q, X, Y):
    m = np.array([[float(v) for v in row] for row in q.matrix])
    P = np.stack([X, Y, np.zeros_like(X), np.ones_like(X)])
    return np.einsum("i...,ij,j...->...", P, m, P)


X, Y = np.meshgrid(np.linspace(-4, 8, 600), np.linspace(-5, 6, 600))
fig, ax = plt.subplots(figsize=(7, 6))
ax.contour(X, Y, slice_values(Q, X, Y), [0], colors="k")
ax.contour(X, Y, slice_values(E, X, Y), [0], colors="tab:blue")
for t in candidates:
    if t == r.squared:
        continue
    ax.contour(X, Y, slice_values(scaled(E, t.rational_near(12)), X, Y), [0], colors="0.6", linestyles="--")
ax.contour(X, Y, slice_values(scaled(E, r.squared.rational_near(20)), X, Y), [0], colors="tab:red")
ax.set_aspect("equal")
ax.set_title(f"first contact at s* = {float(r.scale):.6f}")
plt.show()

# %% [markdown]
# ## Both scaled: the Perram-Wertheim contact function
#
# Hard-ellipsoid simulations scale **both** ellipsoids about their own centres.  The factor
# is $\sqrt F$ for the Perram-Wertheim function
# $F=\max_{\lambda\in[0,1]}\lambda(1-\lambda)\,d^T\big((1-\lambda)A^{-1}+\lambda B^{-1}\big)^{-1}d$.
# It is another number than the one-sided scale: two unit spheres 4 apart need $s=3$ when
# one grows, $s=2$ when both do.

# %%
e1, e2 = qc.Quadric.sphere(1), qc.Quadric.sphere(1, (4, 0, 0))
print(qc.contact_scale(e1, e2).scale, qc.contact_scale(e1, e2, scale="both").scale)

F2 = qc.Quadric.ellipsoid(1, 2, Fraction(1, 2), center=(3, 2, 1))
pw = qc.contact_scale(E, F2, scale="both")


def pw_curve(lam):
    def shape(q):
        m = np.array([[float(v) for v in row] for row in q.matrix])
        A, b = m[:3, :3], m[:3, 3]
        c = -np.linalg.solve(A, b)
        return A / (c @ A @ c - m[3, 3]), c

    A, a = shape(E)
    Bm, b = shape(F2)
    d = b - a
    Ai, Bi = np.linalg.inv(A), np.linalg.inv(Bm)
    return [x * (1 - x) * d @ np.linalg.solve((1 - x) * Ai + x * Bi, d) for x in lam]


lam = np.linspace(0, 1, 400)
plt.plot(lam, pw_curve(lam))
plt.axhline(float(pw.squared), color="tab:red", ls="--", label=f"s*^2 = {pw.squared.decimal(10)} (exact)")
plt.xlabel("lambda")
plt.ylabel("Perram-Wertheim F(lambda)")
plt.legend()
plt.show()

# %% [markdown]
# ## The signed distance, with witnesses
#
# For a sphere the distance comes from the point-quadric secular equation: the nearest point
# $p$ of $Q$ to the centre $c$ solves $(I+\mu Q_{00})p=c-\mu b$, and $\mu$ is a root of
# $q(p(\mu))\det(I+\mu Q_{00})^2$.  Every critical point is isolated, so the minimum is the
# global one.  `mode="exact"` gives real algebraic numbers; the default gives arb balls.

# %%
body = qc.Quadric.ellipsoid(2, Fraction(3, 2), 1)
ball = qc.Quadric.sphere(Fraction(1, 2), (Fraction(5, 2), Fraction(-3, 2), 0))
d = qc.distance(ball, body, mode="exact")
print("distance =", d.distance)
print("point on Q:", [p.decimal(12) for p in d.point_Q])
print("point on E:", [p.decimal(12) for p in d.point_E])
print("normal    :", [n.decimal(12) for n in d.normal])
print(qc.distance(ball, body, digits=40).distance.str(45))

# %% [markdown]
# A sphere in the plane of symmetry of the hyperboloid, beside its waist: the nearest points
# are a pair, mirror images in that plane, so none is singled out (`unique` is False).

# %%
print(qc.distance(ball, Q, mode="exact"))

# %%
fig, ax = plt.subplots(figsize=(6, 6))
X, Y = np.meshgrid(np.linspace(-1, 4.5, 500), np.linspace(-4, 1.5, 500))
ax.contour(X, Y, slice_values(body, X, Y), [0], colors="k")
ax.contour(X, Y, slice_values(ball, X, Y), [0], colors="tab:blue")
pq, pe = [float(v) for v in d.point_Q], [float(v) for v in d.point_E]
ax.plot([pq[0], pe[0]], [pq[1], pe[1]], "r.-")
ax.set_aspect("equal")
ax.set_title(f"distance {float(d.distance):.6f}")
plt.show()

# %% [markdown]
# ## Near touching
#
# Move the ball towards $Q$ along the normal so that it is $10^{-k}$ from touching.  The
# certified distance keeps every digit; a float GJK/EPA solver (coal, python-fcl) stops at its
# tolerance (`benchmarks/bench_distance.py` measures it on many pairs).

# %%
n = np.array([float(v) for v in d.normal])
for k in (2, 6, 10, 14):
    shift = [Fraction(float(x)) for x in -(float(d.distance) - 10.0**-k) * n]
    moved = ball.translated(shift)
    got = qc.distance(moved, body, digits=20).distance
    print(f"10^-{k:<2}: {got.str(20, radius=False)}")

# %% [markdown]
# ## Any ellipsoid against a curved quadric
#
# For an ellipsoid that is not a sphere there is no secular equation in one unknown.  The
# certified mode writes the *contact system* instead: a point `x` of `E` with outward normal
# `nu`, a signed length `t`, and `y = x + t nu` on `Q` where `Q`'s outward normal is `-nu`;
# three equations in three unknowns on each of six charts of the sphere of normals.  A branch
# and bound in interval arithmetic isolates every solution with the Krawczyk operator, so the
# extremal `t` (the largest for a convex solid, the least `t >= 0` for a separated non-convex
# one) is the global answer.  The ellipsoid `E` of the first section against the hyperboloid:

# %%
r = qc.distance(E, Q, digits=30)
print(r.method, r.distance.str(30, radius=False))
f = qc.distance(E, Q, mode="float")
print(f"float: {f.distance!r} +- {f.error:.1e}")

# %% [markdown]
# The first-contact scale of many pairs at once: a compiled kernel certifies each enclosure
# (a sign change of the secular function between two definite members of the pencil).

# %%
rng = np.random.default_rng(0)
centres = rng.uniform(-4, 4, (1000, 3))
stack = np.array([np.array(qc.Quadric.sphere(Fraction(1, 2), [Fraction(float(v)) for v in c]).matrix, dtype=float)
                  for c in centres])
enc = qc.contact_scale(stack, np.array(body.matrix, dtype=float))
print(enc[:3], "widest:", float(np.max((enc[:, 1] - enc[:, 0]) / enc[:, 1])))

# %% [markdown]
# ## Into a solid that is not convex, and a piece cut by planes
#
# The depth into a hyperboloid's solid can be reached with two contacts at once, which no
# single critical point describes.  It is bracketed instead: adding squares of linear forms
# that vanish at a point of the surface, `Q + sum s_i l_i^2`, gives an ellipsoid *inside* the
# solid and tangent to it there, whose depth is a lower bound; the translation that frees `E`
# from that ellipsoid, made a little longer and decided free of the hyperboloid exactly, is an
# upper bound.  A ball in the cap of a hyperboloid of two sheets leaves it downwards by
# `11/10 + 1/5 - 1 = 3/10`:

# %%
cap_ball = "x^2 + y^2 + (z - 11/10)^2 - 1/25"
r = qc.distance(cap_ball, "x^2 + y^2 - z^2 + 1", digits=25)
print(r.method, r.distance.str(25, radius=False))

# %% [markdown]
# A scene's piece is its quadric's solid cut by the planes on its path in the object's tree.
# For a convex solid, weak duality encloses the distance: points of the two solids bound it
# above, a separating direction with multipliers of the planes bounds it below.  The unit ball
# at height 4 above the ball of radius 2 cut to `x >= 1`: the nearest point is on the rim of the
# cut, `(1, 0, sqrt 3)`.

# %%
import flint

from quadric_contact.modes.distance.pieces import cut_piece_distance

r = cut_piece_distance("x^2 + y^2 + (z - 4)^2 - 1", "x^2 + y^2 + z^2 - 4", [("x - 1", "R+")])
rim = (1 + (4 - flint.arb(3).sqrt()) ** 2).sqrt() - 1
print(r.distance.str(15, radius=False), r.distance.overlaps(rim))
