# %% [markdown]
# # 4. Relative positions and Descartes' rule (Table 4)
#
# A quadric $\mathcal Q$ splits space into
#
# $$R_-=\{X^TQX\le0\},\qquad R_+=\{X^TQX\ge0\}\qquad\text{(eq. (8))}.$$
#
# When a small ellipsoid does not cross $\mathcal Q$ it lies in one of them (tangency
# allowed).  **Theorem 13**: which one is read off the *signs of the roots* of
# $\mathfrak P(\lambda)=\det(\lambda E+Q)$, and since all roots are then real, Descartes'
# rule reads those signs off the *signs of the coefficients*.  No root is computed.
#
# Sign conventions (the package follows the paper): $E$ is normalised so that
# $\det E<0$ (its inside is negative); $Q$ is taken exactly as given, so $-Q$ has the same
# surface with $R_-$ and $R_+$ swapped.

# %%
from fractions import Fraction as F

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc
from quadric_contact.exact.descartes import sign_variations
from quadric_contact.interfaces.plotting import plot_quadric
from quadric_contact.theory.regions import derive_root_sign_table

lam = sp.Symbol("lambda")

# %% [markdown]
# ## Table 4, derived
#
# The package does not copy Table 4: `derive_root_sign_table` rebuilds it the way
# Lemma 12 argues, by putting a small ellipsoid at one point of $R_-$ and one of $R_+$
# of each standard form and reading the root signs exactly.  Inside a region the
# pattern cannot change, because no root crosses 0 there.

# %%
derived = derive_root_sign_table()
assert derived == qc.ROOT_SIGN_TABLE
print(f"{'type of Q':28s} {'R-':6s} {'R+':6s}")
for kind, row in qc.ROOT_SIGN_TABLE.items():
    print(f"{kind.value:28s} {row[qc.Region.R_MINUS]:6s} {row[qc.Region.R_PLUS]:6s}")

# %% [markdown]
# Two roots of each pattern never change sign (for the ellipsoid: always two negative
# roots); the other two carry the position.  Degenerate quadrics have $\det Q=0$, hence
# $\mathfrak P(0)=c_0=0$: a structural zero root (two for a plane or parallel planes).
#
# ## Lemma 12 by hand: the hyperboloid of two sheets
#
# The paper's proof scales the ellipsoid to the unit sphere centred at
# $(x_c,y_c,z_c)$ and takes $H=\mathrm{diag}(1/a^2,1/b^2,-1/c^2,1)$.  Let sympy do the
# "direct calculation" of eq. (11), then compare with the formula as printed.

# %%
a, b, c_ = sp.symbols("a b c", positive=True)
xc, yc, zc = sp.symbols("x_c y_c z_c", real=True)
H = sp.diag(1 / a**2, 1 / b**2, -1 / c_**2, 1)
S = sp.Matrix([[1, 0, 0, -xc], [0, 1, 0, -yc], [0, 0, 1, -zc], [-xc, -yc, -zc, -1 + xc**2 + yc**2 + zc**2]])  # eq. (10)
P11 = sp.expand((lam * S + H).det())
printed_11 = sp.sympify(  # eq. (11) as printed ("lam" for lambda, a Python keyword)
    "-lam**4 + ((x_c**2 - 1)/a**2 + (y_c**2 - 1)/b**2 + (1 - z_c**2)/c**2 + 1)*lam**3"
    " + ((c**2*(a**2 + b**2 - 1) + a**2 + b**2 - a**2*b**2 - (a**2 + b**2)*z_c**2 + (c**2 - a**2)*y_c**2"
    " + (c**2 - b**2)*x_c**2)/(a**2*b**2*c**2))*lam**2"
    " - (a**2 + b**2 - c**2 + x_c**2 + y_c**2 + z_c**2 - 1)/(a**2*b**2*c**2)*lam - 1/(a**2*b**2*c**2)",
    locals={"a": a, "b": b, "c": c_, "x_c": xc, "y_c": yc, "z_c": zc, "lam": lam},
)
print("eq. (11) as printed equals det(lambda S + H):", sp.simplify(P11 - printed_11) == 0)
print("centre (0, 0, 0):    ", sp.factor(P11.subs({xc: 0, yc: 0, zc: 0}) * a**2 * b**2 * c_**2))
print("centre (0, 0, c + 1):", sp.factor(P11.subs({xc: 0, yc: 0, zc: c_ + 1}) * a**2 * b**2 * c_**2))

# %% [markdown]
# At the centre of $R_+$ (between the sheets) the roots are $1, -1/a^2, -1/b^2, 1/c^2$: two
# of each sign, `--++`.  Touching the vertex from inside $R_-$ they are all negative,
# `----`.  The package gets the same from exact numbers:

# %%
h2 = qc.Quadric.hyperboloid_two_sheets(2, 3, 1)  # a = 2, b = 3, c = 1
for centre in [(0, 0, 0), (0, 0, 2)]:
    r = qc.relative_position(qc.Quadric.sphere(1, center=centre), h2)
    print(centre, r.region, r.polynomial.signs.pattern, "|", r.decided_by)

# %% [markdown]
# ## Watching the roots move
#
# Now slide a sphere of radius $1/2$ along the $z$ axis, from between the sheets of
# $x^2+y^2-z^2=-1$ into its upper sheet.  The two positive roots meet (first tangency),
# leave the real line while the sphere crosses the surface (a non-real pair: transversal
# contact), come back as a double root (second tangency) and go on as two negative roots.
# They cannot simply pass through 0: $\mathfrak P(0)=\det Q\ne0$.

# %%
Q = qc.Quadric.hyperboloid_two_sheets(1, 1, 1)
half = F(1, 2)
zs = [F(k, 100) for k in range(0, 301, 2)]
roots, regions = [], []
for z in zs:
    E = qc.Quadric.sphere(half, center=(0, 0, z))
    P = qc.characteristic_polynomial(E, Q)
    w = np.roots([float(t) for t in reversed(P.coefficients)])
    roots.append(w[np.lexsort((w.imag, w.real))])
    regions.append(qc.relative_position(E, Q).region)
roots = np.array(roots)
zf = np.array([float(z) for z in zs])
crossing = np.array([r is qc.Region.CONTACT for r in regions])

fig, ax = plt.subplots(1, 3, figsize=(14, 3.8))
for k in range(4):
    ax[0].plot(zf, roots[:, k].real, ".", ms=2)
ax[0].fill_between(zf, -3, 1.5, where=crossing, color="red", alpha=0.1, label="transversal contact")
ax[0].axhline(0, color="k", lw=0.5)
ax[0].set(ylim=(-3, 1.5), xlabel="z of the centre", ylabel="Re λ", title="real parts")
ax[0].legend(fontsize=8)
ax[1].plot(zf, np.abs(roots.imag).max(axis=1))
ax[1].fill_between(zf, 0, 0.6, where=crossing, color="red", alpha=0.1)
ax[1].set(xlabel="z of the centre", ylabel="max |Im λ|", title="non-real roots only while crossing")
sc = ax[2].scatter(roots.real.ravel(), roots.imag.ravel(), c=np.repeat(zf, 4), s=4, cmap="viridis")
ax[2].axvline(0, color="k", lw=0.5)
ax[2].set(xlim=(-3, 1.5), xlabel="Re λ", ylabel="Im λ", title="root paths in the complex plane")
fig.colorbar(sc, ax=ax[2], label="z of the centre")
plt.tight_layout()

# %% [markdown]
# The exact region along the path, with the boundaries where it changes (rational
# sample points here, so the tangencies show up as the first and last contact samples):

# %%
changes = [(float(zs[i]), str(regions[i - 1]), str(regions[i])) for i in range(1, len(zs)) if regions[i] != regions[i - 1]]
print(changes)
print("the tangencies are at z = 1 +- 1/2 exactly (the vertex is at z = 1):")
for z in (F(1, 2), F(3, 2)):
    P = qc.characteristic_polynomial(qc.Quadric.sphere(half, center=(0, 0, z)), Q)
    print(f"  z = {z}: {sp.factor(P.as_sympy())}  ->  {P.structure.describe()}, region {qc.relative_position(qc.Quadric.sphere(half, center=(0, 0, z)), Q).region}")

# %%
fig = plt.figure(figsize=(5, 5.5))
ax = fig.add_subplot(projection="3d")
box = [(-2.5, 2.5), (-2.5, 2.5), (-3, 3.5)]
plot_quadric(ax, Q, box, color="tab:green", alpha=0.2)
colours = {qc.Region.R_PLUS: "tab:blue", qc.Region.R_MINUS: "tab:purple", qc.Region.CONTACT: "tab:red"}
for z in [F(-1, 2), F(1), F(5, 2)]:
    E = qc.Quadric.sphere(half, center=(0, 0, z))
    region = qc.relative_position(E, Q).region
    plot_quadric(ax, E, n=24, color=colours[region], alpha=0.9, label=f"z = {z}: {region}")
ax.set(xlim=box[0], ylim=box[1], zlim=box[2])
ax.set_box_aspect([hi - lo for lo, hi in box])
ax.view_init(8, -60)
ax.legend(fontsize=8, loc="upper left")
ax.set_title("x² + y² - z² = -1 and three spheres of radius 1/2", fontsize=9)

# %% [markdown]
# ## From roots to coefficients: Descartes' rule
#
# For a polynomial whose roots are all real, the number of positive roots *equals* the
# number of sign changes in its coefficient sequence, and the number of negative roots
# equals that of $\mathfrak P(-\lambda)$ (Curtiss 1918).  So each row of Table 4 has a
# coefficient test.  The count for every pattern:

# %%
for pattern in sorted({p for row in qc.ROOT_SIGN_TABLE.values() for p in row.values()}):
    roots_ = [{"-": -1, "0": 0, "+": 1}[s] * (k + 1) for k, s in enumerate(pattern)]  # distinct roots with these signs
    coeffs = [int(t) for t in reversed(sp.Poly(-sp.prod([lam - r for r in roots_]), lam).all_coeffs())]
    print(f"{pattern}: c0..c4 = {coeffs!s:28s} sign changes = {sign_variations(coeffs)} = number of '+'")

# %% [markdown]
# (Whatever the roots, once their signs are fixed the number of sign changes is fixed;
# which coefficients may vanish is what the longer conditions of Table 4 describe.  The
# sign-change counts printed in some rows of Table 4 contradict the root signs beside
# them: Descartes' rule gives one sign change per positive root, as above.)
#
# ## Example 17: the bee outside the trunk
#
# The paper concludes that the bee is outside the hyperboloid $S_2$ because
# $c_3>0$, $c_2>0$, $c_1<0$.

# %%
bee = qc.Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
trunk = qc.Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
r = qc.relative_position(bee, trunk)
P2 = r.polynomial
print("P2 =", P2, " (printed: -0.3 λ^4 + 45.7375 λ^3 + 34.125 λ^2 - 11.6625 λ + 0.25)")
print("coefficient signs c0..c4:", ["+" if t > 0 else "-" if t < 0 else "0" for t in P2.coefficients])
print(r)
print("Table 4 patterns for this Q:", r.expected)

# %% [markdown]
# ## The sign convention at work
#
# Multiply $Q$ by $-1$: the same surface, but now "outside" is $R_-$.  The roots change
# sign and the region swaps; the answer is still right for the matrix given.

# %%
for q in (trunk, -trunk):
    r = qc.relative_position(bee, q)
    print(f"value of X^T Q X at the bee's centre: {float(q.value_at((3, 3, 5.5))):+.3f} -> {r.region}, roots {r.polynomial.signs.pattern}")

# %% [markdown]
# ## A plane: Theorem 14
#
# For a plane no smallness is needed.  With the sphere of radius $r$ centred at
# $(0,0,z_c)$ and the plane $z=0$ (matrix with only the entries $1/2$ in the last row and
# column), eq. (12) is $\mathfrak P(\lambda)=-\lambda^2\,(r^2+4\lambda(\lambda-z_c))/(4r^6)$:
# two zero roots and $\tfrac12(z_c\pm\sqrt{z_c^2-r^2})$, non-real exactly when
# $|z_c|<r$.

# %%
r_ = sp.Symbol("r", positive=True)
Ssph = sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, -zc], [0, 0, -zc, zc**2 - r_**2]]) / r_**2
P0 = sp.Matrix([[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, sp.Rational(1, 2)], [0, 0, sp.Rational(1, 2), 0]])
P12 = sp.factor((lam * Ssph + P0).det())
print("det(lambda S + P0) =", P12)
print("equals eq. (12):", sp.simplify(P12 - (-(lam**2) * (r_**2 + 4 * lam * (lam - zc)) / (4 * r_**6))) == 0)
for z in (-2, 0, F(1, 2), 1, 2):
    s = qc.plane_side(qc.Quadric.sphere(1, center=(0, 0, z)), "z")
    print(f"  z_c = {z!s:4s}: zone {s.zone!s:8s} tangent={s.tangent!s:5s} c3 = {s.c3}, c3^2 - 4 c4 c2 = {s.discriminant}")

# %% [markdown]
# ## Exercise
#
# Without computing any root, count the positive roots of $\mathfrak P_2$ (the bee and
# the trunk) from its coefficients, and store the count in `answer`.  Hint: all its roots
# are real (no contact), so Descartes' rule is exact.

# %%
answer = sign_variations(P2.coefficients)

# %%
# Check: the certified root isolation agrees, and the count says R+ for a one-sheet hyperboloid.
assert answer == P2.signs.positive == 3
assert qc.ROOT_SIGN_TABLE[trunk.kind][qc.Region.R_PLUS].count("+") == answer
print("correct!")
