"""The work budget: every bound on what the package accepts, in one place.

Every public entry point either answers within these bounds or refuses before
the work starts, with an error of the package's hierarchy
(:mod:`quadric_contact.exact.errors`) that names the input and the limit.  The
bounds are on the size of what is read (text, digits, degrees, terms,
parameters, files), never on the time a computation took, so an answer does
not depend on the machine.  ``benchmarks/bench_parsing.py`` measures the
slowest inputs the text bounds admit; the README's section "Bounds" lists them
all.

The modules that enforce a bound read it from here:
:mod:`~quadric_contact.exact.reading` (text), :mod:`~quadric_contact.exact.rational`
(numbers given as objects), :mod:`~quadric_contact.scenes.trajectory` (motions),
:mod:`~quadric_contact.families` (families of quadrics),
:mod:`~quadric_contact.scenes.scene_toml` (scene files), the exact engine
(:func:`check_pair_size`), the distance along a scene's paths and the command line.
"""

from __future__ import annotations

from fractions import Fraction

__all__ = [
    "MAX_AMPLITUDE",
    "MAX_AMPLITUDE_DIGITS",
    "MAX_CLI_BODIES",
    "MAX_CLI_COUNT",
    "MAX_CLI_PROCESSES",
    "MAX_DEGREE",
    "MAX_DEPTH",
    "MAX_DIGITS",
    "MAX_DISTANCE_EVALUATIONS",
    "MAX_EXPONENT",
    "MAX_FAMILY_TERMS",
    "MAX_FAMILY_WORK_PRODUCTS",
    "MAX_FRAMES",
    "MAX_LENGTH",
    "MAX_MOTION_DEGREE",
    "MAX_PAIR_BITS",
    "MAX_PARAMETERS",
    "MAX_PLACES",
    "MAX_REFERENCE_POINTS",
    "MAX_SCENE_BYTES",
    "MAX_SCENE_DEPTH",
    "MAX_WORK",
    "MIN_DISTANCE_TOLERANCE",
    "SCHEDULER_TIMEOUT",
    "WORK_BITS",
]

# -- text (the reader, exact/reading.py) ----------------------------------------------

MAX_LENGTH = 5_000
"""Longest text read, in characters: a number with a numerator and a
denominator of :data:`MAX_DIGITS` digits fits, and so does a quadric's
printed equation with coefficients of a few hundred digits."""

MAX_DIGITS = 1_000
"""Most decimal digits in the numerator, and in the denominator, of a literal
(its significant digits), of any rational that arises while evaluating, and of
any number given as an object (an int, a Fraction, a Decimal).  It keeps each
arithmetic step cheap, and below Python's limit of 4300 digits for converting
integers to and from text."""

MAX_EXPONENT = 1_000
"""Largest exponent of ``**`` / ``^`` (the result must also respect
:data:`MAX_DIGITS` and :data:`MAX_DEGREE`)."""

MAX_DEPTH = 64
"""Deepest nesting of parentheses and unary signs (exponents are literals, and
a power of a power needs parentheses)."""

MAX_DEGREE = 8
"""Highest total degree of any polynomial that arises while evaluating (the
result may be required to have a lower one, 2 for a quadric); so
``(x**2 + 1)**2 - x**4`` is read as the quadric ``2*x**2 + 1``."""

MAX_WORK = 5_000
"""Most arithmetic steps spent on one input.  A product of polynomials with
``m`` and ``n`` terms costs ``m*n`` steps, a sum as many as the terms of the
smaller operand (at least one); each step counts once more for every
:data:`WORK_BITS` bits of the largest coefficient it produced (numerator and
denominator together), since big numbers cost more."""

WORK_BITS = 512
"""Coefficient size counted as one more step; see :data:`MAX_WORK`."""

# -- motions (scenes/trajectory.py) ---------------------------------------------------

MAX_MOTION_DEGREE = MAX_DEGREE
"""Highest degree in ``t`` of each component of a polynomial motion (its
translation and its quaternion), given as text or as a coefficient list: a
list has at most ``MAX_MOTION_DEGREE + 1`` entries, counted before any is
read."""

# -- the distance along a scene's paths (scenes/scene_distance.py) ---------------------

MAX_DISTANCE_EVALUATIONS = 2_000
"""Most signed distances evaluated for one (moving ellipsoid, piece) pair of a scene's
``distance`` effect (the scene's ``distance_evaluations``, default 400).  One costs from
a millisecond (a sphere, or an ellipsoid against a plane: closed forms) to a few seconds
(an ellipsoid against a curved quadric: a branch and bound)."""

MIN_DISTANCE_TOLERANCE = Fraction(1, 10**12)
"""Narrowest enclosure of the least distance a scene may ask for (its
``distance_tolerance``, in the scene's units).  Each distance along the path is enclosed
in binary64, about ``2^-52`` of its size wide, so below this no number of evaluations
narrows the enclosure of a least distance of a few thousand units to the tolerance: the
run would spend its whole budget (:data:`MAX_DISTANCE_EVALUATIONS`) in vain."""

# -- families of quadrics (families/) -------------------------------------------------

MAX_PARAMETERS = 4
"""Most parameters of a family of quadrics: the terms of its discriminants grow
as a high power of their number (eight parameters in 160 characters give a
``Δ4`` of nine million terms)."""

MAX_REFERENCE_POINTS = 500
"""Most small rational points tried in search of a family's reference point (where
``E`` is an ellipsoid) when none is given with ``at=``; the candidates are
``0, 1, 1/2, 2, ...`` in every parameter, 10**n of them for n parameters."""

MAX_FAMILY_TERMS = 5_000
"""Most terms (monomials in the parameters) of any polynomial built for a family's
characteristic polynomial and discriminants (``Δ4`` is the largest); each is
turned into a sympy expression, at about 0.2 ms a term."""

MAX_FAMILY_WORK_PRODUCTS = 5_000_000
"""Most term-by-term products spent building a family's characteristic polynomial
and discriminants, charged *before* each product (the product of the operands'
term counts, which also bounds the terms of its result: nothing larger is ever
allocated)."""

# -- the exact engine (theory/, on huge rationals) ------------------------------------

MAX_PAIR_BITS = 2_500
"""Most bits of a pair for the exact geometric decision
(:func:`~quadric_contact.theory.geometric.decide_geometrically`, which ``check``
uses): the bits of each matrix as integers over one common denominator
(:func:`~quadric_contact.exact.size.pair_bits`), ``E``'s plus ``Q``'s.  Its cost
grows with a high power of this size: measured on random pairs on 2 shared
cores, 620 bits take 0.24 s, 1250 bits 0.57 s, 2560 bits 1.6 s, 5220 bits 5.4 s
(and 490-digit entries 220 s).  A pair of binary64 floats of ordinary exponents
has about 150; beyond the bound the pair is refused with
:class:`~quadric_contact.exact.errors.WorkLimitError` naming it, before the work."""

# -- output -----------------------------------------------------------------------------

MAX_PLACES = 100
"""Most decimal places printed for an event time (a scene's ``places``, the
command line's ``--places``); each place costs a refinement of a real algebraic
number."""

# -- files (scenes/scene_toml.py) -------------------------------------------------------

MAX_SCENE_BYTES = 1_000_000
"""Largest scene file read, in bytes; only regular files are read (not a
device, a FIFO or a directory), and at most this many bytes are read."""

MAX_SCENE_DEPTH = 32
"""Deepest nesting of tables and arrays in a scene file."""

# -- the command line -------------------------------------------------------------------

MAX_CLI_COUNT = 10_000_000
"""Largest count on the command line (``--perturbations``, ``--chunk``, ``--seed``)."""

MAX_CLI_BODIES = 100_000
"""Most ellipsoids (``--bodies``) and pieces (``--pieces``) of a generated scene."""

MAX_CLI_PROCESSES = 256
"""Most worker processes or threads (``--workers``, ``--threads``)."""

MAX_FRAMES = 1_000
"""Most frames of an animation (``--frames``)."""

MAX_AMPLITUDE = 1_000
"""Largest ``--amplitude`` of a sweep's perturbations (in the scene's units)."""

MAX_AMPLITUDE_DIGITS = 30
"""Most digits in the numerator and the denominator of ``--amplitude``."""

SCHEDULER_TIMEOUT = 10.0
"""Seconds allowed to connect to a dask scheduler given by ``--scheduler``
(a connection, not a computation: the time of the sweep itself is not
bounded)."""
