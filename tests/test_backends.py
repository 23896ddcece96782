"""One source, two backends (:mod:`quadric_contact.modes.kernels._jit`): a function registered as
a pair is its own Python function (on scalars and on numpy columns) and, in compiled code, its
compiled side; the Python twin of a compiled kernel compiles nothing; ``select`` chooses alike
on both sides; the smallness loops are kernels with the identity the on-disk cache and the
native library know them by; without numba the plain functions run."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest

from quadric_contact.modes import FilterMode, FloatMode
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.kernels._jit import HAVE_NUMBA, compiled, jitable, njit, plain, select
from quadric_contact.modes.kernels.native import kernel_identity
from quadric_contact.modes.smallness import binary64 as sf

numba_only = pytest.mark.skipif(not HAVE_NUMBA, reason="numba is not installed")

ROOT = Path(__file__).resolve().parents[1]

SPECIAL = np.array([-np.inf, -1e308, -1.5, -0.0, 0.0, 5e-324, 0.75, 1e308, np.inf, np.nan])


@jitable(inline=True)
def _scaled(x, k):
    return select(x > 0.0, k * x, -x)


@jitable(inline=True)
def _twice_scaled(x):
    return 2.0 * _scaled(x, 3.0)


@njit(inline=True)
def _helper(x):
    return _twice_scaled(x) + 1.0


def _loop(x, out):
    for i in range(x.shape[0]):
        out[i] = _helper(x[i]) - _twice_scaled(x[i]) * 0.5


def _columns(x: np.ndarray) -> np.ndarray:
    with np.errstate(all="ignore"):
        return np.asarray((_twice_scaled(x) + 1.0) - _twice_scaled(x) * 0.5)


def test_a_plain_helper_is_its_own_function_on_scalars_and_columns():
    assert isinstance(_twice_scaled, types.FunctionType)
    assert _twice_scaled(2.0) == 12.0 and _twice_scaled(-2.0) == 4.0
    with np.errstate(all="ignore"):
        got = _twice_scaled(SPECIAL)
    want = [2.0 * (3.0 * v if v > 0.0 else -v) for v in SPECIAL.tolist()]
    assert np.array_equal(got, want, equal_nan=True)
    if HAVE_NUMBA:
        assert compiled(_twice_scaled).py_func is _twice_scaled
        assert compiled(_twice_scaled).targetoptions.get("forceinline")
        assert compiled(_helper) is _helper  # a compiled side is its own
    else:
        assert compiled(_twice_scaled) is _twice_scaled


@numba_only
def test_compiled_code_calls_the_compiled_side_with_the_same_bits():
    kernel = njit(cache=False)(_loop)
    out = np.empty_like(SPECIAL)
    kernel(SPECIAL, out)
    assert kernel.signatures  # compiled, not run as a twin
    assert compiled(_twice_scaled).signatures  # numba compiled the plain helper's compiled side
    twin = np.empty_like(SPECIAL)
    plain(kernel)(SPECIAL, twin)
    assert np.array_equal(out, twin, equal_nan=True)
    assert np.array_equal(out, _columns(SPECIAL), equal_nan=True)


@numba_only
def test_the_python_twin_compiles_nothing_and_is_made_once():
    @njit(inline=True)
    def fresh(x):
        return _scaled(x, 0.5) + 1.0

    def loop(x, out):
        for i in range(x.shape[0]):
            out[i] = fresh(x[i])

    kernel = njit(cache=False)(loop)
    twin = plain(kernel)
    assert plain(kernel) is twin and plain(loop) is twin  # one twin per function
    out = np.empty_like(SPECIAL)
    twin(SPECIAL, out)
    assert not fresh.signatures and not kernel.signatures  # nothing was compiled
    with np.errstate(all="ignore"):
        assert np.array_equal(out, np.where(SPECIAL > 0.0, 0.5 * SPECIAL, -SPECIAL) + 1.0, equal_nan=True)


@numba_only
def test_select_chooses_alike_on_columns_and_compiled():
    def loop(c, a, b, n, out, iout):
        for i in range(c.shape[0]):
            out[i] = select(c[i], a[i], b[i])
            iout[i] = select(c[i], n[i], 2)  # an integer and a literal unify to an integer

    kernel = njit(cache=False)(loop)
    rng = np.random.default_rng(3)
    a = rng.permutation(SPECIAL)
    b = rng.permutation(SPECIAL)
    c = a > b  # false for NaN
    n = np.arange(a.shape[0], dtype=np.int64) - 4
    out = np.empty_like(a)
    iout = np.empty_like(n)
    kernel(c, a, b, n, out, iout)
    assert np.array_equal(out, select(c, a, b), equal_nan=True)
    assert np.array_equal(np.signbit(out), np.signbit(select(c, a, b)))  # -0.0 kept
    assert iout.tolist() == select(c, n, 2).tolist()


@numba_only
def test_a_function_has_one_compiled_side():
    def f(x):
        return x + 1.0

    def g(x):
        return x * 2.0

    assert jitable(f, inline=True) is f
    side = compiled(f)
    assert jitable(f, inline=True) is f and compiled(f) is side
    assert njit(f, inline=True) is side  # the compiled side, whoever asks for it
    assert jitable(g) is g and not compiled(g).targetoptions.get("forceinline")
    with pytest.raises(ValueError, match="already has a compiled side"):
        jitable(g, inline=True)
    own = njit(g, inline=True)  # a forceinline helper of its own, beside the pair's
    assert own is not compiled(g) and own.targetoptions.get("forceinline")
    with pytest.raises(TypeError, match="no compiled side"):
        compiled(lambda x: x)


@numba_only
def test_the_smallness_loops_keep_the_identity_the_cache_and_the_native_library_know():
    """Each loop is a kernel of the module's own function: its module and qualified name (the
    native library's key), numba's cache stamped with the digest of every source it is made of,
    the native library asked first, no Python twin; every function a loop reaches by name is a
    plain helper with a ``forceinline`` compiled side, or another loop."""
    module = sf.__name__
    loops = {
        name: getattr(sf, name)
        for name in ("_e_rows_loop", "_e_block", "_q_rows_loop", "_pairs_loop", "_fused_loop")
    }
    for name, loop in loops.items():
        assert kernel_identity(loop) == f"{module}:{name}"
        assert loop.py_func.__qualname__ == name and loop.py_func.__globals__ is vars(sf)
        holder = getattr(loop._cache, "_cache_file", loop._cache)
        assert holder._source_stamp[1] == _jit.sources_digest(module)
        assert loop._compile_for_args.__name__ == "native_first"  # route_native, not a twin
        assert loop.targetoptions.get("nogil") and not loop.targetoptions.get("forceinline")

    def reached(fn: types.FunctionType, seen: set[str]) -> None:
        for name in fn.__code__.co_names:
            value = vars(sf).get(name)
            if name in seen or not callable(value) or isinstance(value, type):
                continue
            seen.add(name)
            if name in loops:
                continue
            if isinstance(value, types.FunctionType) and value.__module__ == module:
                assert compiled(value).targetoptions.get("forceinline"), name
                reached(value, seen)

    seen: set[str] = set()
    for loop in loops.values():
        reached(loop.py_func, seen)
    assert {"_e_row", "_q_row", "_pair_code", "_fixed_code", "_enclose", "select", "_inv"} <= seen


NO_NUMBA = """
import json, sys
sys.modules["numba"] = None  # numba cannot be imported
import numpy as np
from quadric_contact.modes import FilterMode, FloatMode
from quadric_contact.modes.kernels import _jit
from quadric_contact.modes.smallness import binary64 as sf
from tests.oracles import smallness_codes
from tests.test_smallness_arrays import random_ellipsoids, rng_quadric
from quadric_contact.model.classification import TABLE_1_KINDS

assert not _jit.HAVE_NUMBA
assert _jit.compiled(sf._e_row) is sf._e_row and sf._e_rows_loop.__class__.__name__ == "function"
rng = np.random.default_rng(5)
Es = random_ellipsoids(rng, 60, 0.3, 3, 4)
out = {}
for kind in TABLE_1_KINDS[:4]:
    q = rng_quadric(rng, kind)
    for cls in (FloatMode, FilterMode):
        out[f"{kind} {cls.__name__}"] = smallness_codes(Es, q, mode=cls()).tolist()
print(json.dumps(out))
"""


@numba_only
def test_without_numba_the_plain_functions_answer_with_the_compiled_bits():
    """A process that cannot import numba runs the plain functions (the numpy backend, the only
    one there) and gets the codes this process gets from the compiled loops."""
    from tests.oracles import smallness_codes
    from tests.test_smallness_arrays import random_ellipsoids, rng_quadric

    from quadric_contact.model.classification import TABLE_1_KINDS

    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT / "src"), str(ROOT)]))
    proc = subprocess.run(
        [sys.executable, "-c", NO_NUMBA], capture_output=True, text=True, env=env, check=True, timeout=600
    )
    got = json.loads(proc.stdout)
    rng = np.random.default_rng(5)
    Es = random_ellipsoids(rng, 60, 0.3, 3, 4)
    for kind in TABLE_1_KINDS[:4]:
        q = rng_quadric(rng, kind)
        for cls in (FloatMode, FilterMode):
            want = smallness_codes(Es, q, mode=cls(backend="numba")).tolist()
            assert got[f"{kind} {cls.__name__}"] == want, (kind, cls)
