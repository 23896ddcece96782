"""The binary64 stages, under their former name.

The code lives in modules split by responsibility:

* :mod:`~quadric_contact.modes.float_modes`: the ``float`` and ``filter`` modes and their drivers;
* :mod:`~quadric_contact.modes.kernels_criterion`: the fast kernels (plain float and the
  filter's semi-static screen, at the speed of memory);
* :mod:`~quadric_contact.modes.kernels_filter`: the general kernels (the dynamic filter, plain
  float with exact facts);
* :mod:`~quadric_contact.modes.kernels_support`: invariant signs, stack checks, region codes,
  the bandwidth floor;
* :mod:`~quadric_contact.modes.numpy_fallback`: the numpy variant of all of them;
* :mod:`~quadric_contact.modes.threads`: splitting a range of pairs over threads.

This module re-exports what callers imported from it.
"""

from __future__ import annotations

from quadric_contact.modes.float_modes import (
    BACKENDS,
    BLOCK,
    HAVE_NUMBA,
    FilterMode,
    FloatMode,
    _diagnose,
    check_stack,
    exact_facts,
    float_invariant_signs,
    float_pairs,
    read_all,
    region_codes_from_signs,
    stage_codes,
)
from quadric_contact.modes.numpy_fallback import (
    filter_quantities,
    proportional_quadratic_parts,
    screen_quantities,
)
from quadric_contact.modes.threads import run_parallel, single_threaded

__all__ = [
    "BACKENDS",
    "BLOCK",
    "HAVE_NUMBA",
    "FilterMode",
    "FloatMode",
    "_diagnose",
    "check_stack",
    "exact_facts",
    "filter_quantities",
    "float_invariant_signs",
    "float_pairs",
    "proportional_quadratic_parts",
    "read_all",
    "region_codes_from_signs",
    "run_parallel",
    "screen_quantities",
    "single_threaded",
    "stage_codes",
]
