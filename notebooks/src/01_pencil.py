# %% [markdown]
# # 1. The pencil λE + Q and its characteristic polynomial
#
# An ellipsoid $\mathcal E$ and another quadric $\mathcal Q$ are given by symmetric
# $4\times4$ matrices $E$ and $Q$: a point $(x, y, z)$ lies on the surface when
# $X^T Q X = 0$ with $X = (x, y, z, 1)$.  The paper studies the **pencil**
# $\lambda E + Q$ and its **characteristic polynomial** (eq. (1))
#
# $$\mathfrak P(\lambda) = \det(\lambda E + Q) = c_4\lambda^4 + c_3\lambda^3 + c_2\lambda^2 + c_1\lambda + c_0 .$$
#
# Everything in `quadric_contact` is exact: numbers become fractions, and a float
# is the binary fraction it stores.

# %%
from fractions import Fraction

import matplotlib.pyplot as plt
import numpy as np
import sympy as sp

import quadric_contact as qc

# %% [markdown]
# ## Quadrics are exact matrices
#
# The bee of Example 17 and the trunk of its tree, from their equations:

# %%
bee = qc.Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
trunk = qc.Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
print(bee.kind, "|", trunk.kind)
bee.to_sympy()

# %% [markdown]
# The same surfaces can be built from parameters; the type is decided exactly
# from the inertia of the matrix and of its quadratic part.

# %%
for q in [qc.Quadric.ellipsoid(3, 2, 1), qc.Quadric.hyperboloid_two_sheets(1, 1, 2),
          qc.Quadric.hyperbolic_paraboloid(2, 1), qc.Quadric.from_equation("x**2 + y**2 - z**2")]:
    print(f"{q.kind.value:28s} {q.equation()} = 0")

# %% [markdown]
# ## The characteristic polynomial
#
# `characteristic_polynomial` evaluates a closed form derived once with sympy (a
# Laplace expansion of the determinant) on exact integers.  Let us check it
# against a plain symbolic determinant.

# %%
P = qc.characteristic_polynomial(bee, trunk)
lam = sp.Symbol("lambda")
by_sympy = sp.expand((lam * bee.to_sympy() + trunk.to_sympy()).det())
print("P(λ) =", P)
print("same as sympy's determinant:", sp.expand(P.as_sympy() - by_sympy) == 0)

# %% [markdown]
# Two coefficients are easy to read: $c_4 = \det E$ and $c_0 = \det Q$.

# %%
c0, c1, c2, c3, c4 = P.coefficients
print(c4 == Fraction(str(bee.to_sympy().det())), c0 == Fraction(str(trunk.to_sympy().det())))

# %% [markdown]
# ## Roots tell the story
#
# The roots of $\mathfrak P$ are the eigenvalues of $-QE^{-1}$.  Non-real roots
# always mean that the surfaces cross (Remark 9); with all roots real and a
# *small* ellipsoid there is no crossing (Theorem 2).  `structure` classifies the
# roots exactly and `signs` gives their sign pattern.

# %%
print(P.structure.describe(), "| signs:", P.signs.pattern)
print("numpy eigenvalues of -Q E^-1:", np.round(np.linalg.eigvals(-trunk.to_numpy() @ np.linalg.inv(bee.to_numpy())), 4))

# %% [markdown]
# Now move the bee towards the trunk along the $x$ axis and watch the roots.
# When the bee crosses the surface two roots meet and leave the real line.

# %%
xs = np.linspace(0.0, 3.0, 121)
real_parts, imag_parts = [], []
for x in xs:
    e = qc.Quadric.ellipsoid(Fraction(1, 3), Fraction(1, 3), Fraction(1, 5), center=(Fraction(x).limit_denominator(1000), 0, 3))
    w = np.roots([float(c) for c in reversed(qc.characteristic_polynomial(e, trunk).coefficients)])
    w = w[np.argsort(w.real)]
    real_parts.append(w.real)
    imag_parts.append(np.abs(w.imag))
real_parts, imag_parts = np.array(real_parts), np.array(imag_parts)
fig, ax = plt.subplots(1, 2, figsize=(10, 3.5))
ax[0].plot(xs, real_parts)
ax[0].set(xlabel="x of the centre", ylabel="Re λ", title="real parts of the four roots")
ax[1].plot(xs, imag_parts.max(axis=1))
ax[1].set(xlabel="x of the centre", ylabel="max |Im λ|", title="non-real roots while crossing")
plt.tight_layout()

# %% [markdown]
# ## A picture of the pair
#
# `plot_quadric` draws any quadric: the type is decided exactly, the principal axes
# are computed in floating point (a picture), and unbounded surfaces are clipped to a
# box.

# %%
from quadric_contact.interfaces.plotting import plot_quadric

fig = plt.figure(figsize=(5, 5))
ax = fig.add_subplot(projection="3d")
box = [(-2.5, 4), (-2.5, 4), (0, 7)]
plot_quadric(ax, trunk, box, alpha=0.3)
plot_quadric(ax, bee, color="orange", alpha=1)
ax.set(xlim=box[0], ylim=box[1], zlim=box[2])
ax.set_box_aspect((6.5, 6.5, 7))
ax.set_title("the bee and the trunk (Example 17)")

# %% [markdown]
# ## Example 11: a double root
#
# For $2x^2 + 2y^2 + 3z^2 = 1$ and $x^2 + y^2 + 8z = 0$ the paper factors
# $\mathfrak P(\lambda) = -(1 + 2\lambda)^2(16 + 3\lambda^2)$.

# %%
P11 = qc.characteristic_polynomial("2*x**2 + 2*y**2 + 3*z**2 - 1", "x**2 + y**2 + 8*z")
print(sp.factor(P11.as_sympy()))
print(P11.structure.describe())

# %% [markdown]
# ## Exercise
#
# For the unit sphere centred at $(0, 0, z_c)$ and the plane $z = 0$, Theorem 14
# says $\mathfrak P(\lambda) = -\lambda^2\,(r^2 + 4\lambda(\lambda - z_c))/(4r^6)$
# with $r = 1$.  Compute $c_3$ for $z_c = 2$ with the package and store it in
# `answer`.

# %%
answer = qc.characteristic_polynomial(qc.Quadric.sphere(1, center=(0, 0, 2)), "z").coefficients[3]

# %%
# Check: c3 is the coefficient of λ^3 in -λ²(1 + 4λ(λ - 2))/4, i.e. 2.
assert answer == 2, answer
print("correct!")
