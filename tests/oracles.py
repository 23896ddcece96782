"""Reference answers the tests compare the predicates with.

* :func:`scalar_codes`: the exact scalar path (``characteristic_polynomial``,
  Yang's discrimination sequence for contact; Descartes' rule and Table 4 with
  smallness asserted for the region) as the array predicates' codes.
* :func:`mpmath_nonreal` and :func:`numpy_nonreal`: numeric root finding, an
  oracle independent of the discriminants, answering None where a root is too
  close to the real axis to call.
"""

from __future__ import annotations

import mpmath
import numpy as np

from quadric_contact import ExcludedQuadricError, characteristic_polynomial
from quadric_contact.exact.precision import working_precision
from quadric_contact.modes import ContactCode, RegionCode
from quadric_contact.theory.regions import decide_region


def scalar_codes(e, q):
    """``(ContactCode, RegionCode)`` of the pair by the exact scalar path."""
    P = characteristic_polynomial(e, q)
    contact = ContactCode.NO_CONTACT if P.structure.all_real else ContactCode.CONTACT
    try:
        region = RegionCode.from_region(decide_region(P, small=True, method="theory").region)
    except ExcludedQuadricError:
        region = RegionCode.EXCLUDED
    return contact, region


def mpmath_nonreal(P, digits=50):
    """Non-real roots of ``P`` by mpmath polyroots at ``digits``, or None if too close to call
    (also where the iteration does not converge: a multiple root, such as the triple root of
    two coaxial spheroids, can stall it)."""
    with working_precision(dps=digits):
        coeffs = [mpmath.mpf(c.numerator) / c.denominator for c in reversed(P.coefficients)]
        try:
            roots = mpmath.polyroots(coeffs, maxsteps=400, extraprec=4 * digits)
        except mpmath.libmp.NoConvergence:
            return None
        scale = max(1, max(abs(r) for r in roots))
        imag = [abs(mpmath.im(r)) / scale for r in roots]
        if any(mpmath.mpf(10) ** (-digits // 2) < v < mpmath.mpf(10) ** (-digits // 4) for v in imag):
            return None
        return any(v > mpmath.mpf(10) ** (-digits // 4) for v in imag)


def numpy_nonreal(E, Q):
    """Non-real eigenvalues of ``-Q E^-1`` (numpy arrays), or None if too close to call."""
    w = np.linalg.eigvals(-Q @ np.linalg.inv(E))
    scale = max(1.0, float(np.max(np.abs(w))))
    im = np.abs(w.imag) / scale
    if np.any((im > 1e-12) & (im < 1e-6)):
        return None
    return bool(np.any(im >= 1e-6))


def _criterion(what, E, Q, mode="certified"):
    """The paper's criterion on a stack (or one pair): the first stage of every mode, which
    these tests check mode by mode; ``mode.last`` counts its stages by name."""
    from quadric_contact.modes import StageCounts, get_mode
    from quadric_contact.modes.codes import StageMethod
    from quadric_contact.modes.stacks.batch import as_stack, make_pairs

    m = get_mode(mode)
    pairs, shape = make_pairs(as_stack(E, "E"), as_stack(Q, "Q"))
    codes, names, which = m.staged(StageMethod(f"criterion_{what}"), pairs)
    counts = StageCounts()
    for k, name in enumerate(names):
        counts.add(name, int(np.count_nonzero(which == k)))
    counts.undecided = int(np.count_nonzero(which < 0))
    m._record(counts)
    if shape == ():
        return (ContactCode if what == "contact" else RegionCode)(int(codes[0]))
    return codes.reshape(shape)


def criterion_contact(E, Q, *, mode="certified"):
    """``1`` non-real roots, ``0`` all roots real, ``2`` uncertain (:class:`ContactCode` values)."""
    return _criterion("contact", E, Q, mode)


def criterion_region(E, Q, *, mode="certified"):
    """The criterion and Table 4's reading of the root signs, no smallness (:class:`RegionCode`)."""
    return _criterion("region", E, Q, mode)


def smallness_codes(E, Q, *, mode="certified", client=None, compute=True):
    """Smallness codes of a stack (as :func:`quadric_contact.theory.smallness` gives them), and for a
    single pair its :class:`SmallnessCode` (the scalar predicate gives the report)."""
    from quadric_contact.modes import SmallnessCode
    from quadric_contact.modes.stacks.batch import is_stack, run_stack

    if is_stack(E) or is_stack(Q):
        return run_stack("smallness", E, Q, mode, client, compute)
    return SmallnessCode(int(run_stack("smallness", [E], [Q], mode)[0]))
