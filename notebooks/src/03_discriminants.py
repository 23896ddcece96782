# %% [markdown]
# # 3. Discriminants: how many real roots, without computing them
#
# Theorem 2 says that for a small ellipsoid, *transversal contact* is the same as
# *$\mathfrak P$ has a non-real root*.  Corollary 10 decides that with two polynomial
# expressions in the coefficients, taken from a **complete discrimination system**
# (Yang 1999), so no root is ever computed:
#
# $$\text{transversal contact} \iff \Delta_4<0 \ \text{ or }\ (\Delta_4=0 \text{ and } \Delta_3<0).$$
#
# This notebook builds the discrimination system, checks the paper's $\Delta_3$ and
# $\Delta_4$ against it (and finds a misprint), draws where $\Delta_4$ changes sign,
# replays Example 11, the case $\Delta_4=0$, and ends with the finer invariant behind
# Table 3: the Segre characteristic of the pencil.

# %%
from fractions import Fraction as F
from itertools import pairwise

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc
from quadric_contact.exact.discriminants import revised_sign_list
from quadric_contact.interfaces.plotting import plot_quadric
from quadric_contact.paper import ERRATA, PRINTED
from quadric_contact.theory.contact_kind import analyze_contact
from quadric_contact.theory.segre import segre_symbol
from quadric_contact.theory.smallness import smallness

lam = sp.Symbol("lambda")

# %% [markdown]
# ## Yang's discrimination sequence
#
# For $f$ of degree $n$, the *discrimination sequence* $D_1,\dots,D_n$ is made of
# principal minors of the Sylvester-like matrix of $f$ and $f'$.  Its *revised sign
# list* (zeros inside the list replaced by a fixed pattern) tells, exactly:
#
# * the number of distinct pairs of non-real roots $=$ the number $v$ of sign changes;
# * the number of distinct real roots $= l-2v$, with $l$ the number of non-zero signs.
#
# `discrimination_sequence` evaluates generated straight-line formulas, so it runs on
# integers, fractions, floats, numpy arrays and even sympy symbols.  Let us try it on
# quartics whose roots we choose.

# %%
cases = {
    "four real": [1, 2, 3, 4],
    "two real, one pair": [1, 2, sp.I, -sp.I],
    "two pairs": [1 + sp.I, 1 - sp.I, 2 + sp.I, 2 - sp.I],
    "double real, one pair": [-F(1, 2), -F(1, 2), 4 * sp.I / sp.sqrt(3), -4 * sp.I / sp.sqrt(3)],
    "double + two simple": [1, 1, 2, 3],
    "triple + simple": [1, 1, 1, 2],
    "two doubles": [1, 1, 2, 2],
    "double pair": [sp.I, -sp.I, sp.I, -sp.I],
    "quadruple": [1, 1, 1, 1],
}


def sign(x):
    return (x > 0) - (x < 0)


print(f"{'roots':24s} {'signs of D1..D4':18s} {'revised':18s} structure")
for name, roots in cases.items():
    poly = sp.Poly(sp.expand(sp.prod([lam - r for r in roots])), lam)
    coeffs = [F(int(c.p), int(c.q)) for c in reversed(poly.all_coeffs())]  # c0 .. c4
    D = qc.discrimination_sequence(coeffs)
    s = [sign(d) for d in D]
    print(f"{name:24s} {s!s:18s} {revised_sign_list(s)!s:18s} {qc.root_structure(coeffs).describe()}")

# %% [markdown]
# The counts need only *signs*: the sequence is exact on rational input, so the answer
# is exact too.  Multiplicities come from applying the same count to $\gcd(f, f')$
# (`root_structure` does this).
#
# ## The paper's $\Delta_3$ and $\Delta_4$
#
# Section 3.2 prints $\Delta_3$ and $\Delta_4$.  They are $D_3$ and $D_4$ with a positive
# factor removed: $D_3 = 2c_4^2\Delta_3$ and $D_4 = c_4^2\Delta_4$.  With symbols:

# %%
c = sp.symbols("c0:5")
D1, D2, D3, D4 = qc.discrimination_sequence(list(c))
d2, d3, d4 = qc.paper_deltas(list(c))
print("D3 - 2 c4^2 Delta3 =", sp.expand(D3 - 2 * c[4] ** 2 * d3))
print("D4 - c4^2 Delta4   =", sp.expand(D4 - c[4] ** 2 * d4))

# %% [markdown]
# Now compare with what is printed.  $\Delta_3$ agrees.  $\Delta_4$ does not: one term
# differs.

# %%
printed3, printed4 = sp.sympify(PRINTED["Delta3"]), sp.sympify(PRINTED["Delta4"])
print("printed Delta3 - true Delta3 =", sp.expand(printed3 - d3))
print("printed Delta4 - true Delta4 =", sp.factor(sp.expand(printed4 - d4)))
e = next(e for e in ERRATA if e.key == "delta4-term")
print(f"\nerratum: printed {e.printed}, should be {e.corrected}\n  ({e.evidence.split('.')[0]})")

# %% [markdown]
# Does it matter?  Put the bee of Example 17 at $(3/5, 1/2, 21/10)$, where it pokes
# into the trunk of its tree.  The true $\Delta_4$ is negative: contact.  The printed
# formula gives a positive number, and Corollary 10 would report no contact.

# %%
bee = qc.Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
crown = qc.Quadric.from_equation("x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
trunk = qc.Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
printed_delta4 = sp.lambdify(c, printed4)
poking = bee.translated((F(3, 5) - 3, F(1, 2) - 3, F(21, 10) - F(11, 2)))
P = qc.characteristic_polynomial(poking, trunk)
print("true Delta4    =", float(P.deltas()[2]))
print("printed Delta4 =", float(printed_delta4(*P.coefficients)))
print(qc.transversal_contact(poking, trunk))

# %% [markdown]
# The case $\Delta_4=0$ is not a curiosity either.  The bee and the crown have the same
# quadratic part, $x^2+y^2+3z^2$ (the bee is a scaled copy of the crown).  At
# $\lambda=-1$ the quadratic part of $\lambda E+Q$ vanishes, the matrix has rank at most 2,
# and $(\lambda+1)^2$ divides $\mathfrak P$: a double root for *every* translation of the
# bee.  Here $\Delta_4=0$ and $\Delta_3>0$ says no contact.

# %%
P = qc.characteristic_polynomial(bee, crown)
print("P =", sp.factor(P.as_sympy()))
print("signs of (Delta2, Delta3, Delta4):", P.delta_signs())
print(qc.transversal_contact(bee, crown))

# ## Where $\Delta_4$ changes sign
#
# Move a small sphere (radius $1/3$) in the plane $y=0$ near the tree's trunk and colour
# each centre by the sign of $\Delta_4$ (exact, one pencil per pixel).  The true trunk
# profile $x^2-(z-3)^2/4=1$ is drawn on top: $\Delta_4<0$ exactly on the band of centres
# whose sphere crosses the surface, and $\Delta_4>0$ on both sides, inside and outside.

# %%
r = F(1, 3)
xs = [F(i, 20) for i in range(-60, 61, 2)]
zs = [F(k, 20) for k in range(-40, 161, 4)]
grid = np.zeros((len(zs), len(xs)))
for j, x in enumerate(xs):
    for i, z in enumerate(zs):
        grid[i, j] = qc.characteristic_polynomial(qc.Quadric.sphere(r, center=(x, 0, z)), trunk).delta_signs()[2]
fig, ax = plt.subplots(figsize=(6, 5))
ax.pcolormesh([float(x) for x in xs], [float(z) for z in zs], grid, cmap="coolwarm_r", shading="nearest", vmin=-1, vmax=1)
zz = np.linspace(-2, 8, 200)
for side in (1, -1):
    ax.plot(side * np.sqrt(1 + (zz - 3) ** 2 / 4), zz, "k", lw=1)
ax.set(xlabel="x of the centre", ylabel="z of the centre", title="sign of Δ4: blue > 0, red < 0", aspect="equal")

# %% [markdown]
# The band has the width of the sphere's diameter, measured along the normal of the
# trunk.  Where the two sides meet (on the axis, $x=0$) the sphere is centred on the
# trunk's axis: the pencil then has multiple roots and $\Delta_4=0$ (white).
#
# ## $\Delta_4$ along a path
#
# Along the segment from $(-3, 0, 3)$ to $(3, 0, 3)$, through the waist of the trunk, the
# sphere crosses the surface twice and passes the axis.  $\Delta_4$ spans many orders of
# magnitude, so we plot $\operatorname{sign}(\Delta_4)\log_{10}(1+|\Delta_4|)$.

# %%
ts = [F(k, 200) for k in range(-600, 601, 3)]
vals = [float(qc.characteristic_polynomial(qc.Quadric.sphere(r, center=(t, 0, 3)), trunk).deltas()[2]) for t in ts]
fig, ax = plt.subplots(figsize=(8, 3))
ax.plot([float(t) for t in ts], np.sign(vals) * np.log10(1 + np.abs(vals)))
ax.axhline(0, color="k", lw=0.5)
for x in (-1 - r, -1 + r, 1 - r, 1 + r):
    ax.axvline(float(x), color="r", ls=":", lw=1)
ax.set(xlabel="x of the centre (z = 3)", ylabel="sign · log10(1 + |Δ4|)", title="Δ4 < 0 exactly while the sphere crosses the waist (dotted: tangencies)")

# %% [markdown]
# The dotted lines are the exact tangencies $x=\pm1\pm r$: the sphere of radius $r$
# touches the waist circle of radius 1.  At each of them $\Delta_4$ vanishes (a double
# root) and changes sign.  Let us check at the first one, exactly:

# %%
for x in (-1 - r, -1 + r, 1 - r, 1 + r):
    P = qc.characteristic_polynomial(qc.Quadric.sphere(r, center=(x, 0, 3)), trunk)
    print(f"x = {x!s:5s}  Delta4 = {P.deltas()[2]}  roots: {P.structure.describe()}")

# %% [markdown]
# ## Example 11: $\Delta_4 = 0$ and $\Delta_3 < 0$
#
# The ellipsoid $2x^2+2y^2+3z^2=1$ and the paraboloid $x^2+y^2+8z=0$ have
# $\mathfrak P(\lambda)=-(1+2\lambda)^2(16+3\lambda^2)$: a double real root and a pair of
# non-real roots.  Then $\Delta_4=0$ and the second clause of Corollary 10 decides.

# %%
E11 = qc.Quadric.from_equation(PRINTED["Example 11 E"])
Q11 = qc.Quadric.from_equation(PRINTED["Example 11 Q"])
P11 = qc.characteristic_polynomial(E11, Q11)
print("P =", sp.factor(P11.as_sympy()), "  printed:", PRINTED["Example 11 P"])
print("(Delta2, Delta3, Delta4) =", P11.deltas())
print(qc.transversal_contact(E11, Q11))

# %% [markdown]
# The paper prints $\Delta_3=-400$.  With its own formula the value is $-13790208$; no
# rescaling of $\mathfrak P$ gives $-400$.  Only the sign is used, and the sign is right:

# %%
e = next(e for e in ERRATA if e.key == "example-11-delta3")
print(e.printed, "->", e.corrected)
print("Delta3 from the printed formula:", printed3.subs(dict(zip(c, P11.coefficients, strict=True))))

# %%
fig = plt.figure(figsize=(5, 4.5))
ax = fig.add_subplot(projection="3d")
plot_quadric(ax, Q11, [(-1.2, 1.2), (-1.2, 1.2), (-0.8, 0.8)], color="tab:green", alpha=0.35)
plot_quadric(ax, E11, color="tab:orange", alpha=0.8)
ax.set_box_aspect((1.2, 1.2, 0.8))
ax.set_title("Fig. 6: the ellipsoid crosses the paraboloid", fontsize=9)

# %% [markdown]
# Corollary 10 uses only two members of the system.  That is enough because the pencil
# contains an ellipsoid: $-E^{-1}Q$ is self-adjoint for the form $E$, which has one
# negative square, so at most one pair of roots is non-real (a quartic with two
# non-real pairs would have $\Delta_4>0$ and slip through the two clauses).  The
# package's `transversal_contact` classifies the roots with the whole sequence
# (`P.structure`) anyway, which also gives the multiplicities.

# %% [markdown]
# ## Segre types and Table 3
#
# The proof of Theorem 2 goes through the classification of pencils of quadrics by their
# **Segre characteristic**: for each root $\lambda_0$ of $\mathfrak P$, the sizes of the
# Jordan blocks of $-E^{-1}Q$ there.  `[(11)11]_3` reads: a double root carrying two
# blocks of size 1 (the member $\lambda_0E+Q$ has rank 2), two simple roots, and 3
# distinct real roots in all.  `segre_symbol` computes it exactly, from the gcds of the
# minors of $\lambda E+Q$ (the invariant factors):

# %%
print(segre_symbol(E11, Q11), "| Example 11: P =", sp.factor(P11.as_sympy()))

# %% [markdown]
# Table 3 relates the Segre types to the kind of contact.  The Segre symbol alone does not
# fix the kind; the singular members do: at a multiple root $\lambda_0$, the real singular
# points of $\lambda_0E+Q$ that lie on $E$ are exactly the points of tangency.
# `analyze_contact` reads them off exactly.  A gallery:

# %%
S, Ell = qc.Quadric.sphere, qc.Quadric.ellipsoid
gallery = [
    ("bee and trunk (Example 17)", bee, trunk),
    ("sphere on the axis of a cylinder", S(F(1, 2)), qc.Quadric.elliptic_cylinder(1, 1)),
    ("concentric spheres", S(F(1, 2)), S(1)),
    ("ellipsoid on a paraboloid's vertex", Ell(F(1, 2), F(1, 3), F(1, 4), center=(0, 0, F(1, 4))), qc.Quadric.elliptic_paraboloid(2, 3)),
    ("sphere touching one of two planes", S(F(1, 2)), qc.Quadric.two_parallel_planes((1, 0, 0), -F(1, 2), F(3, 2))),
    ("sphere in an elliptic cylinder", S(F(1, 2), center=(F(3, 2), 0, 0)), qc.Quadric.from_equation("x**2/4 + y**2 - 1")),
    ("sphere between two sheets", S(1), qc.Quadric.hyperboloid_two_sheets(1, 1, 1)),
    ("sphere in an elliptic throat", S(1), qc.Quadric.from_equation("x**2/4 + y**2 - z**2 - 1")),
    ("sphere crossing the trunk", S(F(1, 3), center=(1, 0, 3)), trunk),
    ("Example 11", E11, Q11),
    ("sphere in a circular throat", S(1), qc.Quadric.from_equation("x**2 + y**2 - z**2/4 - 1")),
]
sym = {-1: "<0", 0: "=0", 1: ">0"}
print(f"{'configuration':36s} {'Segre':13s} {'kind':19s} {'Delta3':6s} {'Delta4':6s} small")
for name, e, q in gallery:
    a_ = analyze_contact(e, q)
    _, s3, s4 = a_.polynomial.delta_signs()
    print(f"{name:36s} {a_.segre!s:13s} {a_.kind.value:19s} {sym[s3]:6s} {sym[s4]:6s} {smallness(e, q).small}")

# %% [markdown]
# Read it against Table 3:
#
# * transversal contact is exactly the last clause of the table, $\Delta_4<0$ or
#   ($\Delta_4=0$ and $\Delta_3<0$): the Segre types `[1111]_2` and `[(11)11]_1`;
# * every tangency has $\Delta_4=0$ (a multiple root) and $\Delta_3\ge0$, but so do some
#   configurations with no contact at all (the concentric spheres, the sphere on
#   the cylinder's axis): the discriminants detect *crossing*, not touching;
# * `[(11)11]_3` appears with no contact and with two tangent points: the Segre symbol
#   does not decide the kind, the kernels of the singular members do;
# * the computed symbols differ from the printed Table 3 in places: two tangent points
#   come with `[(11)(11)]_2` (printed under "no contact"), and the sphere in the
#   elliptic cylinder has `[(21)1]` with 2 distinct real roots (printed with subscript 3).
#
# The singular members carry the points of tangency, exactly (in $\mathbb Q(\sqrt d)$):

# %%
for name, e, q in [gallery[3], gallery[6], gallery[7]]:
    a_ = analyze_contact(e, q)
    pts = [[str(c.to_sympy()) for c in p] for m in a_.members for p in m.points]
    print(f"{name}: lambda0 = {[str(m.root.to_sympy()) for m in a_.members]}, rank {[m.rank for m in a_.members]}, tangent at {pts}")

# %%
fig = plt.figure(figsize=(13, 4.2))
panels = [
    (gallery[3], [(-1.5, 1.5), (-1.5, 1.5), (-0.2, 1.2)], "one tangent point [211]_3"),
    (gallery[6], [(-2.5, 2.5), (-2.5, 2.5), (-2.5, 2.5)], "two tangent points [(11)(11)]_2"),
    (gallery[10], [(-2, 2), (-2, 2), (-2, 2)], "a curve of tangency [(111)1]_2"),
]
for k, ((_, e, q), box, title) in enumerate(panels):
    ax = fig.add_subplot(1, 3, k + 1, projection="3d")
    plot_quadric(ax, q, box, color="tab:green", alpha=0.25)
    plot_quadric(ax, e, color="tab:orange", alpha=0.9)
    for m in analyze_contact(e, q).members:
        for p in m.points:
            ax.scatter(*[float(c.to_sympy()) for c in p], color="k", s=30, depthshade=False)
    ax.set(xlim=box[0], ylim=box[1], zlim=box[2])
    ax.set_box_aspect([hi - lo for lo, hi in box])
    ax.set_title(title, fontsize=9)

# %% [markdown]
# ## Exercise
#
# Count the distinct real roots of $\lambda^4-5\lambda^2+4+\tfrac{1}{10}\lambda^3$ with
# Yang's rule: compute the discrimination sequence, its revised sign list, the number
# $l$ of non-zero signs and the number $v$ of sign changes, and store $l-2v$ in
# `answer`.

# %%
coeffs = [4, 0, -5, F(1, 10), 1]
s = revised_sign_list([sign(d) for d in qc.discrimination_sequence(coeffs)])
nonzero = [t for t in s if t]
v = sum(1 for a, b in pairwise(nonzero) if a != b)
answer = len(nonzero) - 2 * v

# %%
# Check against the exact classification and against numpy's floating-point roots.
assert answer == qc.root_structure(coeffs).distinct_real
assert answer == sum(abs(z.imag) < 1e-9 for z in np.roots([float(t) for t in reversed(coeffs)]))
print("correct!", answer, "distinct real roots")
