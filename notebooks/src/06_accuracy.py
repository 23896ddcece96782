# %% [markdown]
# # 6. What accuracy costs: number modes, the hard-case ladder and structural zeros
#
# Every answer of the paper is the sign of a polynomial in the entries of $E$ and $Q$:
# the coefficients $c_0..c_4$ of $\mathfrak P(\lambda)=\det(\lambda E+Q)$, then
# $\Delta_2,\Delta_3,\Delta_4$ (Corollary 10).  Notebooks 1-5 evaluated them with exact
# fractions, one pair at a time.  This notebook evaluates the *same formulas* on stacks of
# thousands of pairs with different kinds of numbers, and asks what each kind costs and
# where it goes wrong.
#
# The answer will be: plain floating point is fast and usually right, and wrong exactly
# where it matters (near tangency, and where a value is exactly zero); the **certified**
# mode costs little more than plain float on ordinary pairs, pays more only on the hard
# ones, and is never wrong.

# %%
import time
from fractions import Fraction as F

import dask.array as da
import matplotlib.pyplot as plt
import numpy as np

import quadric_contact as qc
from quadric_contact.modes import MODES, BallMode, CertifiedMode, CriterionCode, FilterMode, MpmathMode
from quadric_contact.modes.kernels.numpy_backend import filter_quantities
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.peers import EIG_TOL, peer_numpy_eigvals, peer_numpy_roots
from quadric_contact.testing.samples import GENERIC_KINDS, SAMPLE_KINDS, random_pairs

# %% [markdown]
# ## One formula, many number modes
#
# A *number mode* is an object that evaluates the generated closed forms with its own
# numbers.  Pass its name (or an instance) as `mode=`:

# %%
for name, cls in MODES.items():
    print(f"{name:10s} certified: {cls.certified!s:5s}  {cls.__doc__.strip().splitlines()[0]}")

# %% [markdown]
# * `float`: plain binary64, answers everything, may be wrong;
# * `filter`: binary64 plus a rigorous bound on the rounding error of every value; it
#   answers only where the computed sign cannot be wrong, otherwise `UNCERTAIN`;
# * `ball`: python-flint's `arb` balls (an interval that surely contains the value) at a
#   chosen precision; again `UNCERTAIN` where the ball contains 0 but is not exactly 0;
# * `mpmath`: plain multiprecision floats, answers everything, may be wrong;
# * `exact`: integers (each matrix scaled to integers), always right, slowest;
# * `certified` (the default): `filter`, then `ball` for what the filter left, then `exact`
#   for what the ball left.  It always answers, and its answer is **the exact evaluation
#   of the criterion on the matrices as given** (a float is the dyadic fraction it stores).
#
# This notebook studies what the numbers cost on the paper's criterion, the first stage of
# every predicate: `qc.corollary_10` (does $P(\lambda)=\det(\lambda E+Q)$ have non-real
# roots?).  The predicates themselves (`qc.transversal_contact`, ...) answer the geometric
# question for every pair with the same modes; the last section shows their stages.
#
# On a stack $(\dots,4,4)$ `corollary_10` returns int8 codes (`CriterionCode`): 1 non-real
# roots (transversal contact), 0 all roots real, 2 `UNCERTAIN` (never read as "no").
# Example 11 (contact, decided by $\Delta_4=0$, $\Delta_3<0$) and Example 17's bee against
# the trunk (no contact), stacked:

# %%
ex11_E = qc.Quadric.from_equation("2*x**2 + 2*y**2 + 3*z**2 - 1").to_numpy()
ex11_Q = qc.Quadric.from_equation("x**2 + y**2 + 8*z").to_numpy()
bee = qc.Quadric.from_equation("(x-3)**2 + (y-3)**2 + 3*(z-5.5)**2 - 0.1")
trunk = qc.Quadric.from_equation("x**2 + y**2 - 0.25*(z-3)**2 - 1")
E2 = np.stack([ex11_E, bee.to_numpy()])
Q2 = np.stack([ex11_Q, trunk.to_numpy()])
for name in MODES:
    print(f"{name:10s}", qc.corollary_10(E2, Q2, mode=name))
print([CriterionCode(int(c)) for c in qc.corollary_10(E2, Q2)])

# %% [markdown]
# Batch shapes broadcast as in numpy: one ellipsoid against a stack of quadrics, or a
# grid.  Here the bee against the trunk and the crown, each at three heights (a $3\times2$
# grid of answers from a $(3,1,4,4)$ and a $(2,4,4)$ stack):

# %%
crown = qc.Quadric.from_equation("x**2 + y**2 + 3*(z - 8.36291)**2 - 20")
bees = np.stack([qc.Quadric.from_equation(f"(x-3)**2 + (y-3)**2 + 3*(z-{z})**2 - 0.1").to_numpy() for z in (5.5, 7, 9)])
print(qc.corollary_10(bees[:, None], np.stack([trunk.to_numpy(), crown.to_numpy()])))

# %% [markdown]
# ## The hard-case ladder
#
# Easy pairs are easy for every mode.  The hard ones are near tangency, where the roots of
# $\mathfrak P$ that meet when the surfaces touch are almost equal and $\Delta_4$ is almost
# 0.  `quadric_contact.testing.hardcases` builds them **exactly**: for each of the ten types of
# Table 1 and the plane, a small ellipsoid (semi-axes $1/4$ along the normal, $1/8$
# across) touching $Q$ at a vertex from the $R_-$ side and from the $R_+$ side, then moved
# along the normal by $d=10^{-2},\dots,10^{-16}$ *away* (no contact) or *into* $Q$
# (transversal contact); then everything is moved by one rational rigid motion and rounded
# to binary64.  One rung, for the ellipsoid $x^2/16+y^2/9+z^2/4=1$, before the motion:

# %%
s = np.linspace(0, 2 * np.pi, 400)
fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
for a, (lim_x, lim_z, d) in zip(ax, [((-4.5, 4.5), (-2.5, 3.0), 0.1), ((-0.4, 0.4), (1.9, 2.6), 0.02)], strict=True):
    a.plot(4 * np.cos(s), 2 * np.sin(s), color="tab:green", label="Q (section y = 0)")
    for direction, dz, colour in [("away", d, "tab:blue"), ("into", -d, "tab:red")]:
        a.plot(np.cos(s) / 8, 2 + 0.25 + dz + np.sin(s) / 4, color=colour, label=f"E moved {direction} by d")
    a.plot(np.cos(s) / 8, 2.25 + np.sin(s) / 4, "k:", lw=0.8, label="E tangent (d = 0)")
    a.set(xlim=lim_x, ylim=lim_z, aspect="equal")
ax[0].set_title("the rung of an ellipsoid, R+ side (d exaggerated)", fontsize=9)
ax[1].set_title("near the vertex (0, 0, 2)", fontsize=9)
ax[1].legend(fontsize=7, loc="upper right")
plt.tight_layout()

# %% [markdown]
# Each case carries what the construction intends, and how it is fed to the predicates
# (here: as binary64 matrices).  What is "right" for a mode is the exact answer **for the
# matrices it receives**, which the `exact` mode computes.

# %%
ladder = [c for c in hard_cases(["ladder"]) if c.direction != "tangent"]
print(len(ladder), "cases, e.g.", ladder[0].id, "-", ladder[0].description)
E = np.stack([c.matrices()[0] for c in ladder])
Q = np.stack([c.matrices()[1] for c in ladder])
distance = np.array([c.distance for c in ladder])
DISTANCES = [f"1e-{k}" for k in range(2, 17)]
truth = qc.corollary_10(E, Q, mode="exact")
intended = np.array([c.intended_contact for c in ladder])

# %% [markdown]
# First surprise: at $d=10^{-15}$ and $10^{-16}$ the exact answer for the rounded matrices
# is not always what the construction intends.  Rounding the entries to binary64 (relative
# error $2^{-53}\approx10^{-16}$) moves the surfaces by about as much as $d$: the *input*
# has already crossed over.  No number mode can undo that; only exact input can (below).

# %%
for d in DISTANCES[-4:]:
    sel = distance == d
    print(f"d = {d:6s}: rounding changed the answer in {np.count_nonzero(sel & (truth != intended)):2d} of {sel.sum()} cases")

# %% [markdown]
# Now every mode, and two floating-point peers from `quadric_contact.testing.peers`:
#
# * **numpy eigvals**: the eigenvalues of $-E^{-1}Q$ (the roots of $\mathfrak P$), in
#   batch; "non-real" when an imaginary part exceeds $10^{-9}$ of the largest modulus;
# * **numpy roots**: `numpy.roots` of the pencil's coefficients computed in binary64, pair
#   by pair, same tolerance.
#
# A method is wrong on a case when it gives a definite answer that differs from `exact`;
# `UNCERTAIN` counts separately (it is not wrong, it is honest).

# %%
methods = {
    "float": lambda: qc.corollary_10(E, Q, mode="float"),
    "mpmath 15 digits": lambda: qc.corollary_10(E, Q, mode=MpmathMode(15)),
    "mpmath 30 digits": lambda: qc.corollary_10(E, Q, mode=MpmathMode(30)),
    "filter": lambda: qc.corollary_10(E, Q, mode="filter"),
    "ball 53 bits": lambda: qc.corollary_10(E, Q, mode=BallMode(53)),
    "ball 128 bits": lambda: qc.corollary_10(E, Q, mode=BallMode(128)),
    "certified": lambda: qc.corollary_10(E, Q, mode="certified"),
    "numpy eigvals": lambda: peer_numpy_eigvals(E, Q),
    "numpy roots": lambda: peer_numpy_roots(E, Q),
}
codes = {name: run() for name, run in methods.items()}
wrong = np.array([[np.count_nonzero((distance == d) & (c != 2) & (c != truth)) for c in codes.values()] for d in DISTANCES])
undecided = np.array([[np.count_nonzero((distance == d) & (c == 2)) for c in codes.values()] for d in DISTANCES])

print(f"{'d':6s} " + " ".join(f"{name[:13]:>13s}" for name in codes))
for d, w, u in zip(DISTANCES, wrong, undecided, strict=True):
    print(f"{d:6s} " + " ".join(f"{f'{a} / {b}':>13s}" for a, b in zip(w, u, strict=True)))
print("(wrong / undecided, of 40 cases per distance: 10 types x 2 sides x away/into)")

# %%
# What the text below says, checked (the notebook fails if it stops being true).
col = {name: k for k, name in enumerate(codes)}
assert wrong[:, col["certified"]].sum() == undecided[:, col["certified"]].sum() == 0
assert wrong[:, col["filter"]].sum() == wrong[:, col["ball 53 bits"]].sum() == wrong[:, col["ball 128 bits"]].sum() == 0
assert (wrong[:, col["mpmath 30 digits"]] > 0).all() and wrong[:-2, col["float"]].sum() == 0 < wrong[-1, col["float"]]
assert wrong[:-2, col["numpy eigvals"]].sum() == 0 < wrong[-1, col["numpy eigvals"]]

fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
for ax, table, title, cmap in [(axes[0], wrong, "wrong answers", "Reds"), (axes[1], undecided, "UNCERTAIN (honest)", "Greys")]:
    ax.imshow(table, cmap=cmap, vmin=0, vmax=40, aspect="auto")
    for (i, j), v in np.ndenumerate(table):
        if v:
            ax.text(j, i, v, ha="center", va="center", fontsize=7, color="k" if v < 25 else "w")
    ax.set_xticks(range(len(codes)), list(codes), rotation=60, ha="right", fontsize=8)
    ax.set_title(f"ladder: {title} per distance", fontsize=10)
axes[0].set_yticks(range(len(DISTANCES)), DISTANCES)
axes[0].set_ylabel("distance d from tangency")
plt.tight_layout()

# %% [markdown]
# Read the picture column by column:
#
# * **float** and **mpmath at 15 digits** are right down to $d\approx10^{-14}$ and then
#   guess.  Their answers near tangency are decided by rounding noise.
# * **mpmath at 30 digits** is wrong twice at *every* distance, where 15 digits happened
#   to be right: more digits are not a guarantee.  Those two are the parallel planes,
#   whose $c_0$ and $c_1$ are zero for the exact rotated planes and tiny after rounding;
#   computed with 30 digits, the tiny values come out with the wrong signs.  Only a bound
#   on the error tells when a sign can be trusted.
# * **filter** is never wrong; it gives up from $d\approx10^{-12}$ on (and on the two
#   parallel-plane cases), and **ball** at 53 bits is never wrong either, and gives up at
#   about the same place.  At 128 bits the ball decides everything here.
# * **certified** is never wrong and never undecided.
# * **numpy eigvals** and **numpy roots** are fine far from tangency and wrong near it,
#   with no way of telling which of their answers to trust.
#
# ## Why the filter gives up
#
# The filter computes $\Delta_4$ in binary64 together with a rigorous bound on its
# rounding error (derived once from the straight-line formulas; see
# `quadric_contact.modes.kernels.errorbounds`), and reports a sign only when $|\Delta_4|$ exceeds
# the bound.  `filter_quantities` exposes those numbers.  Along the ellipsoid's rung on
# the $R_+$ side, moving away ($\Delta_4>0$, all roots real), compare the exact $\Delta_4$
# of the same scaled coefficients, the actual error of the float value, and the bound:

# %%
rung = [k for k, c in enumerate(ladder) if c.id.startswith("ladder/ellipsoid/R+/away/")]
fq = filter_quantities(E[rung], Q[rung])
d_float = fq["d"][2]
bound = np.minimum(fq["bound_relative"][2], fq["bound_absolute"][2])
d_exact = []
for j, k in enumerate(rung):
    P = qc.characteristic_polynomial(*ladder[k].input_quadrics())
    scaled = [P.coefficients[t] * F(float(fq["s"][t][j])) for t in range(5)]  # the filter's exact power-of-two scaling
    d_exact.append(qc.paper_deltas(scaled)[2])
ds = [float(F(ladder[k].distance)) for k in rung]
error = [abs(F(float(a)) - b) for a, b in zip(d_float, d_exact, strict=True)]
assert all(e <= b for e, b in zip(error, bound, strict=True)), "the bound holds"
print(f"the bound is {min(bound) / float(max(error)):.0f} to {max(bound) / float(min(e for e in error if e)):.3g} times the actual error")

fig, ax = plt.subplots(figsize=(7, 4.5))
ax.loglog(ds, [abs(float(v)) for v in d_exact], "o-", label="|Δ4|, exact (the signal)")
ax.loglog(ds, [max(float(e), 1e-22) for e in error], "s--", label="|float Δ4 − exact Δ4| (the actual error)")
ax.loglog(ds, bound, "k-", label="the filter's certified error bound")
for k, v in enumerate(d_exact):
    if v < 0:
        ax.annotate("exact Δ4 < 0:\nrounding moved E into Q", (ds[k], abs(float(v))), fontsize=7, xytext=(-60, -35), textcoords="offset points", arrowprops={"arrowstyle": "->"})
ax.invert_xaxis()
ax.set_xlabel("distance d from tangency")
ax.set_ylabel("scaled Δ4")
ax.set_title("the filter answers where the signal is above the bound", fontsize=10)
ax.legend(fontsize=8)
ax.grid(True, which="both", alpha=0.3)

# %% [markdown]
# $\Delta_4$ shrinks like $d$; the rounding error of its float evaluation stays near
# $10^{-16}$ of the size of its terms, and the bound (pessimistic by a factor of a few
# hundred: the price of being rigorous without looking at the data) stays flat.  The
# signal falls below the bound between $d=10^{-11}$ and $10^{-12}$: there the filter
# stops and hands the pair to the ball stage.  Plain float keeps reading the sign of the
# noise, and is right by luck until the error overtakes the signal near $d=10^{-15}$.
#
# ## The certified cascade: who decided what
#
# Pass a `CertifiedMode` instance to read afterwards how many entries each stage decided:
# `mode.last` for the last call, `mode.counts` summed over all calls.  On the ladder,
# distance by distance:

# %%
stages = {}
for d in DISTANCES:
    mode = CertifiedMode()
    sel = distance == d
    assert (qc.corollary_10(E[sel], Q[sel], mode=mode) == truth[sel]).all()
    stages[d] = dict(mode.last.decided)
print("d = 1e-2: ", stages["1e-2"], "\nd = 1e-16:", stages["1e-16"])

fig, ax = plt.subplots(figsize=(8, 3.5))
bottom = np.zeros(len(DISTANCES))
for stage, colour in [("filter", "tab:blue"), ("ball", "tab:orange"), ("exact", "tab:red")]:
    counts = np.array([stages[d].get(f"criterion ({stage})", 0) for d in DISTANCES])
    ax.bar(DISTANCES, counts, bottom=bottom, color=colour, label=stage)
    bottom += counts
ax.set_ylabel("ladder cases decided")
ax.set_xlabel("distance d from tangency")
ax.set_title("certified mode: which stage decided (40 cases per distance)", fontsize=10)
ax.legend(fontsize=8)
plt.setp(ax.get_xticklabels(), rotation=45)
plt.tight_layout()

# %% [markdown]
# On random pairs (`quadric_contact.testing.samples.random_pairs`: random rigid motions, binary64)
# the filter decides everything for the types that rounding leaves generic (ellipsoids,
# hyperboloids, paraboloids, planes).  Over all ten types about one pair in ten goes on
# to the ball stage: rotated cylinders and parallel planes, rounded to binary64, are only
# *nearly* degenerate (their $c_0$, or $c_0$ and $c_1$, are tiny instead of zero), and
# their pairs are genuinely hard.  The later stages are paid for only where needed.

# %%
E_g, Q_g, _ = random_pairs(3000, np.random.default_rng(6), kinds=GENERIC_KINDS)
E_r, Q_r, kinds = random_pairs(3000, np.random.default_rng(6))
for label, (Ep, Qp) in {"generic types": (E_g, Q_g), "all ten types": (E_r, Q_r)}.items():
    mode = CertifiedMode()
    qc.corollary_10(Ep, Qp, mode=mode)
    print(f"3000 random pairs, {label}: {mode.last} | escalated past the filter: {mode.last.escalated}")

# %% [markdown]
# ## Why the eigenvalue peers cannot be fixed by a tolerance
#
# Near tangency two roots of $\mathfrak P$ are almost equal.  Moved *into* $Q$ by $d$,
# they are a complex pair with imaginary part about $0.375\sqrt d$; moved *away*, they are
# real.  An eigenvalue solver perturbs a double eigenvalue by about $\sqrt{\varepsilon}
# \approx10^{-8}$ (a double root is that sensitive), so below $d\approx10^{-15}$ the
# imaginary parts it reports are noise, on both sides, and no tolerance separates them.

# %%
fig, ax = plt.subplots(figsize=(7, 4.2))
for direction, marker in [("into", "o"), ("away", "x")]:
    ks = [k for k, c in enumerate(ladder) if c.id.startswith(f"ladder/ellipsoid/R+/{direction}/")]
    w = np.linalg.eigvals(-np.linalg.solve(E[ks], Q[ks]))
    im = np.abs(w.imag).max(axis=1)
    ax.loglog([float(F(ladder[k].distance)) for k in ks], np.maximum(im, 1e-18), marker, label=f"largest |Im| of the eigenvalues, E moved {direction}")
dd = np.logspace(-16, -2, 50)
ax.loglog(dd, 0.375 * np.sqrt(dd), "k:", lw=0.8, label="0.375 √d (the exact pair, into)")
ax.axhline(EIG_TOL, color="tab:red", lw=0.8, label="the peers' tolerance (1e-9, relative to max(1, largest root))")
ax.axhline(np.sqrt(np.finfo(float).eps), color="0.5", ls="--", lw=0.8, label="√ε ≈ 1.5e-8: the solver's error at a double root")
ax.invert_xaxis()
ax.set_ylim(1e-18, 1)
ax.set_xlabel("distance d from tangency")
ax.set_title("numpy eigenvalues of −E⁻¹Q on the ellipsoid rung (away: 0 shown at 1e-18)", fontsize=9)
ax.legend(fontsize=7, loc="lower left")
ax.grid(True, which="both", alpha=0.3)

# %% [markdown]
# ## Structural zeros
#
# Some values are zero *because of what the quadric is*, not by accident: for a cylinder
# $\det Q=c_0=0$; for a plane $c_0=c_1=0$; for two quadrics with the same quadratic part
# (the bee against the crown $S_1$ of Example 17: both have quadratic part
# $\mathrm{diag}(1,1,3)$), $\lambda=-1$ is a double root and $\Delta_4=0$ identically.
# The answer then hangs on the *exact* zero: Corollary 10 with $\Delta_4=0$ asks for the
# sign of $\Delta_3$.  A float evaluation turns the zero into noise, with a random sign.
#
# **A cylinder.**  The `dyadic-tangent` family moves each quadric by an affine map with
# dyadic entries, so that binary64 holds every entry exactly.  An ellipsoid tangent to an
# elliptic cylinder from outside: exactly, $c_0=0$ and the roots are real (a double root
# where they touch).  numpy sees a tiny $\det Q$ and a complex pair:

# %%
case = next(c for c in hard_cases(["dyadic-tangent"]) if c.id == "dyadic-tangent/elliptic_cylinder/R+/tangent/0")
Ec, Qc = case.matrices()
P = qc.characteristic_polynomial(*case.input_quadrics())
print("exact: c0 =", P.coefficients[0], "|", P.structure.describe(), "| transversal contact:", bool(qc.corollary_10(Ec, Qc)))
print("numpy: det Q =", np.linalg.det(Qc))
print("numpy eigenvalues of -E^-1 Q:", np.linalg.eigvals(-np.linalg.solve(Ec, Qc)))
print("peers say contact:", peer_numpy_eigvals(Ec[None], Qc[None])[0], peer_numpy_roots(Ec[None], Qc[None])[0])

# %% [markdown]
# **Parallel planes.**  $c_0=c_1=0$ exactly for a pair of parallel planes; rotated and
# rounded to binary64 they are tiny, and plain float reads their noise.  On the random
# pairs above, by type of $Q$:

# %%
flt_r = qc.corollary_10(E_r, Q_r, mode="float")
right_r = qc.corollary_10(E_r, Q_r, mode="exact")
for k, kind in enumerate(SAMPLE_KINDS):
    sel = kinds == k
    print(f"{kind.value:26s} float wrong on {np.count_nonzero(sel & (flt_r != right_r)):3d} of {sel.sum()}")

# %% [markdown]
# **The bee and the crown.**  The bee is well outside the crown (Example 17: no contact,
# $R_+$).  Fed as binary64 and as exact decimals (`8.36291` is not a binary fraction):

# %%
bee_crown = [c for c in hard_cases(["delta4-zero"]) if c.id.startswith("delta4-zero/bee-crown/")]
for c in bee_crown:
    Eb, Qb = c.matrices()
    P = qc.characteristic_polynomial(*c.input_quadrics())
    print(f"{c.id}: exact Delta4 = {P.deltas()[2]}, Delta3 > 0: {P.deltas()[1] > 0}")
    for name in ("float", "mpmath", "filter", "ball"):
        print(f"   {name:7s} -> {CriterionCode(int(qc.corollary_10(Eb[None], Qb[None], mode=name)[0])).name}")
    mode = CertifiedMode()
    answer = CriterionCode(int(qc.corollary_10(Eb[None], Qb[None], mode=mode)[0]))
    print(f"   certified -> {answer.name}, decided by: {mode.last}")

# %% [markdown]
# Plain float computes $\Delta_4$ as a tiny number of either sign; here it comes out
# negative, and float reports a contact that is not there (mpmath does the same on the
# decimal input).  For the binary64
# input the filter recognises the structural zero: it compares the two quadratic parts
# exactly, finds them equal and knows $\Delta_4=0$.  For the exact decimal input the
# rounded quadratic parts are still equal, but the exact ones need not be, so neither
# filter nor ball may assume it; the exact stage decides.  That is the cascade working as
# designed: the expensive stage runs on the one pair that needs it.
#
# ## Exact input
#
# The ladder at $d=10^{-16}$ was partly decided by rounding.  The `ladder-exact` family
# feeds the same constructions as exact rationals (object arrays of `Fraction`): now the
# certified answer is the construction's, even at $10^{-16}$.

# %%
exact_cases = [c for c in hard_cases(["ladder-exact"]) if c.direction != "tangent"]
Ex = np.stack([c.matrices()[0] for c in exact_cases])
Qx = np.stack([c.matrices()[1] for c in exact_cases])
mode = CertifiedMode()
got = qc.corollary_10(Ex, Qx, mode=mode)
print(Ex.dtype, len(exact_cases), "cases; certified == intended:", bool((got == [c.intended_contact for c in exact_cases]).all()), "| stages:", mode.last)
print("float on the same (rounded) matrices, wrong:", np.count_nonzero(qc.corollary_10(Ex, Qx, mode="float") != got))

# %% [markdown]
# ## Accuracy against time
#
# A small measurement, run here: the 3000 random pairs of the generic types, the 3000 of
# all ten types, and the 600 ladder cases.  The fast modes and numpy eigvals run on every
# pair, the slow ones on the first 300.  **Timings depend on the machine and its load**: read them as ratios.
# `quadric-contact bench` measures the full table (more pairs, throughput against batch
# size, the escalation rate over millions of pairs; `--profile smoke|quick|full`).

# %%
def best_time(fn, repeat):
    best, out = np.inf, None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


populations = {"generic random": (E_g, Q_g), "all types random": (E_r, Q_r), "ladder (hard)": (E, Q)}
measured = []  # (population, method, seconds per test, fraction wrong, fraction undecided)
for population, (Ep, Qp) in populations.items():
    right = qc.corollary_10(Ep, Qp, mode="exact")
    for name, run, n in [
        ("float", lambda e, q: qc.corollary_10(e, q, mode="float"), len(Ep)),
        ("filter", lambda e, q: qc.corollary_10(e, q, mode=FilterMode()), len(Ep)),
        ("certified", lambda e, q: qc.corollary_10(e, q, mode="certified"), len(Ep)),
        ("ball 128", lambda e, q: qc.corollary_10(e, q, mode="ball"), 300),
        ("mpmath 50", lambda e, q: qc.corollary_10(e, q, mode="mpmath"), 300),
        ("exact", lambda e, q: qc.corollary_10(e, q, mode="exact"), 300),
        ("numpy eigvals", peer_numpy_eigvals, len(Ep)),
        ("numpy roots", peer_numpy_roots, 300),
    ]:
        seconds, out = best_time(lambda run=run, e=Ep[:n], q=Qp[:n]: run(e, q), 3 if n > 300 else 1)
        bad = np.count_nonzero((out != 2) & (out != right[:n]))
        measured.append((population, name, seconds / n, bad / n, np.count_nonzero(out == 2) / n))

print(f"{'population':17s} {'method':14s} {'per test':>10s} {'wrong':>7s} {'undecided':>9s}")
for population, name, t, w, u in measured:
    print(f"{population:17s} {name:14s} {t * 1e6:8.2f} us {w:7.2%} {u:9.2%}")
never_wrong = {name for _, name, _, w, _ in measured if w == 0}
assert {"filter", "certified", "ball 128", "exact"} <= never_wrong

# %%
floor = 1e-4
colours = {name: f"C{k}" for k, name in enumerate(dict.fromkeys(name for _, name, *_ in measured))}
fig, axes = plt.subplots(1, 3, figsize=(16, 5), sharey=True)
for ax, population in zip(axes, populations, strict=True):
    for pop, name, t, w, u in measured:
        if pop != population:
            continue
        marker = "s" if name.startswith("numpy") else "o"
        ax.scatter(t, max(w, floor), marker=marker, s=50, color=colours[name])
        label = name + (f" ({u:.0%} undecided)" if u else "")
        if w:
            ax.annotate(label, (t, w), fontsize=8, xytext=(5, 4), textcoords="offset points")
        else:  # never wrong: labels written upwards from the floor
            ax.annotate(label, (t, floor), fontsize=8, xytext=(-2, 8), textcoords="offset points", rotation=75)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(floor / 2, 1)
    ax.set_xlabel("time per test (s, this machine, now)")
    ax.set_title(f"{population}: what accuracy costs", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_ylabel(f"fraction wrong (0 drawn at {floor:g})")
plt.tight_layout()

# %% [markdown]
# The certified mode sits on the floor (never wrong).  On generic pairs it costs little
# more than plain float; where many pairs are hard it pays the later stages for those
# pairs only.  `exact` and `ball` are never wrong either, but pay their price on every
# pair instead of on the few that need it.
# Plain float and the float peers are cheap, and wrong exactly on the pairs where an
# answer is hard (mpmath, at 50 digits, happened to be right on these, at a hundred times
# the cost of exact integers).
#
# Everything also runs on dask arrays, chunk by chunk (for stacks that do not fit in
# memory); the answer is the same:

# %%
lazy = qc.corollary_10(da.from_array(E_r, chunks=(1000, 4, 4)), da.from_array(Q_r, chunks=(1000, 4, 4)))
print(type(lazy).__name__, lazy.shape, "same as numpy:", bool((lazy == qc.corollary_10(E_r, Q_r)).all()))

# %% [markdown]
# ## Exercises
#
# **1.**  On the ladder cases at $d=10^{-12}$ (`distance == "1e-12"`), how many did the
# certified mode's filter leave to the ball stage?  Store the count in `answer_1`.

# %%
sel = distance == "1e-12"
mode = CertifiedMode()
qc.corollary_10(E[sel], Q[sel], mode=mode)
answer_1 = mode.last.decided["criterion (ball)"] + mode.last.decided["criterion (exact)"]

# %%
# Check: exactly the cases where the filter alone is UNCERTAIN.
assert answer_1 == np.count_nonzero(qc.corollary_10(E[sel], Q[sel], mode="filter") == CriterionCode.UNCERTAIN) > 0, answer_1
print("correct:", answer_1, "of", sel.sum())

# %% [markdown]
# **2.**  What is the largest distance $d$ of the ladder at which plain `float` gives a
# wrong answer?  Store it as a string like `"1e-7"` in `answer_2`.

# %%
flt = qc.corollary_10(E, Q, mode="float")
answer_2 = next(d for d in DISTANCES if np.any((distance == d) & (flt != truth)))

# %%
# Check: float is right at every larger distance, and at answer_2 it is wrong on some case that
# rounding did not change (so the fault is float's evaluation, not its input).
k = DISTANCES.index(answer_2)
assert answer_2 == "1e-15" and not wrong[:k, list(codes).index("float")].any(), answer_2
assert np.any((distance == answer_2) & (flt != truth) & (truth == intended))
print("correct: float is first wrong at d =", answer_2)

# %% [markdown]
# **3.**  A sphere of radius $1/4$ inside a sphere of radius 2, $10^{-12}$ away from
# touching it (`"delta4-zero/spheres/R-/away/1e-12"`): the same quadratic part, so
# $\Delta_4=0$ identically.  Which stage of the certified mode decides it?  Store its name
# in `answer_3`.

# %%
sphere_case = next(c for c in hard_cases(["delta4-zero"]) if c.id == "delta4-zero/spheres/R-/away/1e-12")
Es, Qs = sphere_case.matrices()
mode = CertifiedMode()
qc.corollary_10(Es[None], Qs[None], mode=mode)
answer_3 = next(stage for stage, n in mode.last.decided.items() if n).split("(")[1].rstrip(")")

# %%
# Check: the stages before it are UNCERTAIN, the stage itself decides, and the answer is exact.
order = ["filter", "ball", "exact"]
singles = {"filter": FilterMode(), "ball": BallMode(128), "exact": "exact"}
results = {s: int(qc.corollary_10(Es[None], Qs[None], mode=singles[s])[0]) for s in order}
assert all(results[s] == CriterionCode.UNCERTAIN for s in order[: order.index(answer_3)]), results
assert results[answer_3] == results["exact"] == CriterionCode.ALL_REAL, results
print("correct: decided by", answer_3, {s: CriterionCode(v).name for s, v in results.items()})

# %% [markdown]
# ## The predicates: the same modes, the geometric question
#
# The criterion alone says nothing for a pair that is not small and whose roots are all
# real.  The predicates go on: smallness (Tables 1-2 on arrays), then the *separation
# certificate* (a member $sE+Q$ of the pencil that is definite proves that $E$ lies strictly
# on one side, by the S-lemma; four simple real roots without one prove a crossing), and
# the exact scalar predicates for tangencies.  On random pairs of similar sizes, where most
# pairs are not small, here is who settles what, and the criterion's error against the
# geometry:

# %%
from quadric_contact.testing.samples import random_ellipsoids

rng = np.random.default_rng(5)
Ea, _ = random_ellipsoids(2000, rng, axes=(0.5, 2.0), box=2.0)
Qa, _ = random_ellipsoids(2000, rng, axes=(0.5, 2.0), box=2.0)
mode = CertifiedMode()
contact = qc.transversal_contact(Ea, Qa, mode=mode)
print(mode.last)
criterion = qc.corollary_10(Ea, Qa)
crossing_missed = np.count_nonzero((contact == 1) & (criterion == CriterionCode.ALL_REAL))
print(f"pairs that cross: {np.count_nonzero(contact == 1)}; of them the criterion alone calls "
      f"'all roots real' (no contact under smallness): {crossing_missed}")
