"""The fast block kernels: every layout (distinct pairs, one matrix against a stack on
either side, float64 ``(N, 4, 4)`` or packed ``(N, 10)``) gives the codes of the numpy
fallback, and the certified answers are those of exact arithmetic; the packed layout's
public API; the first-use notice."""

from __future__ import annotations

import types

import numpy as np
import pytest
from tests.oracles import criterion_contact, criterion_region

import quadric_contact as qc
from quadric_contact.modes import CertifiedMode, FilterMode, FloatMode
from quadric_contact.modes.kernels._jit import HAVE_NUMBA
from quadric_contact.testing.hardcases import hard_cases
from quadric_contact.testing.samples import kernel_population, random_pairs

PREDICATES = [criterion_contact, criterion_region]


@pytest.fixture(scope="module")
def pairs():
    E, Q = kernel_population(1500, np.random.default_rng(5))
    E2, Q2, _ = random_pairs(1500, np.random.default_rng(6))
    cases = [
        c for c in hard_cases(["ladder", "dyadic-tangent", "delta4-zero", "huge-offset"]) if not c.exact_input
    ]
    E3 = np.stack([c.matrices()[0] for c in cases])
    Q3 = np.stack([c.matrices()[1] for c in cases])
    return np.concatenate([E, E2, E3]), np.concatenate([Q, Q2, Q3])


def _layouts(E, Q):
    """The pairs in every layout the kernels read: ``(name, E, Q)`` (the fixed layouts take
    ``Q[7]`` or ``E[11]`` against the whole other stack)."""
    return [
        ("distinct", E, Q),
        ("packed", qc.Packed(qc.pack(E)), qc.Packed(qc.pack(Q))),
        ("packed E", qc.Packed(qc.pack(E)), Q),
        ("fixed Q", E, Q[7]),
        ("fixed Q, packed", qc.Packed(qc.pack(E)), qc.Packed(qc.pack(Q[7:8]))),
        ("fixed E", E[11], Q),
    ]


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("size", ["some", pytest.param("all", marks=pytest.mark.slow)])
@pytest.mark.parametrize("predicate", PREDICATES)
@pytest.mark.parametrize("cls", [FloatMode, FilterMode])
def test_every_layout_gives_the_numpy_codes(pairs, predicate, cls, size):
    E, Q = pairs
    if size == "some":  # 1200 of the 3000 random pairs and every hard case (all: -m slow)
        sub = np.r_[0:600, 1500:2100, 3000 : len(E)]
        E, Q = E[sub], Q[sub]
    for name, e, q in _layouts(E, Q):
        a = np.asarray(predicate(e, q, mode=cls(backend="numba"))).reshape(-1)
        b = np.asarray(predicate(e, q, mode=cls(backend="numpy"))).reshape(-1)
        assert (a == b).all(), name
        if name.startswith("fixed Q"):
            ref = predicate(E, np.broadcast_to(Q[7], E.shape), mode=cls(backend="numpy"))
            assert (a == ref).all(), name
        elif name == "fixed E":
            ref = predicate(np.broadcast_to(E[11], Q.shape), Q, mode=cls(backend="numpy"))
            assert (a == ref).all(), name
        else:
            assert (a == predicate(E, Q, mode=cls(backend="numpy"))).all(), name


@pytest.mark.parametrize("predicate", PREDICATES)
def test_certified_is_exact_in_every_layout(pairs, predicate):
    E, Q = pairs
    sub = np.r_[0:300, 1500:1800, 3000 : len(E)]
    E, Q = E[sub], Q[sub]
    truth = predicate(E, Q, mode="exact")
    for name, e, q in _layouts(E, Q):
        got = np.asarray(predicate(e, q, mode=CertifiedMode())).reshape(-1)
        if name.startswith("fixed Q"):
            ref = predicate(E, np.broadcast_to(Q[7], E.shape), mode="exact")
        elif name == "fixed E":
            ref = predicate(np.broadcast_to(E[11], Q.shape), Q, mode="exact")
        else:
            ref = truth
        assert (got == ref).all(), name


def test_complete_decision_reads_packed_input():
    E, Q = kernel_population(400, np.random.default_rng(8))
    a = qc.transversal_contact(E, Q)
    b = qc.transversal_contact(qc.Packed(qc.pack(E)), qc.Packed(qc.pack(Q)))
    assert (a == b).all()
    c = qc.relative_position(qc.Packed(qc.pack(E)), Q[0])
    assert (c == qc.relative_position(E, Q[0])).all()


def test_pack_and_unpack():
    rng = np.random.default_rng(2)
    A = rng.normal(size=(3, 5, 4, 4))
    M = A + np.swapaxes(A, -1, -2)
    P = qc.pack(M)
    assert P.shape == (3, 5, 10)
    assert (qc.unpack(P) == M).all()
    assert qc.Packed(P).shape == (3, 5)
    with pytest.raises(qc.NotSymmetricError):
        qc.pack(A)
    with pytest.raises(qc.ShapeError):
        qc.pack(np.zeros((2, 3, 3)))
    with pytest.raises(qc.ShapeError):
        qc.unpack(np.zeros((2, 9)))
    with pytest.raises(qc.ShapeError):
        qc.Packed(np.zeros((2, 9)))


def test_pack_names_a_non_finite_entry():
    """A NaN or an infinity is a ``NonFiniteError`` naming the matrix and the entry (not an
    asymmetry: NaN differs from itself)."""
    M = np.repeat(np.diag([1.0, 1.0, 1.0, -1.0])[None], 3, axis=0)
    M[1, 2, 1] = M[1, 1, 2] = np.nan
    with pytest.raises(qc.NonFiniteError, match=r"matrix 1 of the stack .* at \(1, 2\): nan") as info:
        qc.pack(M)
    assert info.value.details == {"entry": (1, 2), "index": 1}
    with pytest.raises(qc.NonFiniteError, match=r"at \(0, 0\): inf"):
        qc.pack(np.diag([np.inf, 1.0, 1.0, -1.0]))
    exact = np.diag([1, 1, 1, -1]).astype(object)
    exact[3, 3] = float("-inf")
    with pytest.raises(qc.NonFiniteError, match=r"at \(3, 3\): -inf"):
        qc.pack(exact)


def test_packed_input_is_validated():
    E, Q = kernel_population(4, np.random.default_rng(9))
    P = qc.pack(E)
    P[2, 0] = np.nan
    with pytest.raises(qc.NonFiniteError):
        qc.transversal_contact(qc.Packed(P), Q, mode="certified")
    P = qc.pack(E)
    P[1] = qc.pack(np.diag([1.0, 1.0, -1.0, -1.0])[None])[0]  # a hyperboloid, not an ellipsoid
    with pytest.raises(qc.NotAnEllipsoidError):
        qc.transversal_contact(qc.Packed(P), Q, mode="filter")


def test_the_first_compilation_says_so_once(monkeypatch, capsys):
    from quadric_contact.modes.kernels import _jit

    if not HAVE_NUMBA:
        pytest.skip("numba not installed")
    monkeypatch.setattr(_jit, "_notice_printed", False)
    listener = _jit._CompileNotice()

    def event(module, cached=True):
        func = types.SimpleNamespace(__module__=module)
        cache = types.SimpleNamespace(_cache_path="/some/cache" if cached else None)
        return types.SimpleNamespace(data={"dispatcher": types.SimpleNamespace(py_func=func, _cache=cache)})

    listener.on_start(event("somebody_else"))
    # an uncached helper compiled for a call from Python is not a cache miss: no notice
    listener.on_start(event("quadric_contact.modes.decision.separation", cached=False))
    assert capsys.readouterr().err == ""
    listener.on_start(event("quadric_contact.modes.kernels.criterion"))
    listener.on_start(event("quadric_contact.modes.decision.separation"))
    err = capsys.readouterr().err
    assert err.count("compiling the numba kernels once") == 1


def test_kernels_compile_in_a_thread_of_their_own():
    """The compiler runs on a fresh Python stack whatever the depth of the caller (see
    :func:`~quadric_contact.modes.kernels._jit.compile_on_a_fresh_stack`): the compile event is seen
    in the compiler's thread, not the caller's; a kernel that calls another compiles it in
    that same thread (no wait on the compiler's lock); errors reach the caller."""
    import threading

    if not HAVE_NUMBA:
        pytest.skip("numba not installed")
    from numba.core import event
    from numba.core.errors import TypingError

    from quadric_contact.modes.kernels._jit import njit

    @njit(cache=False)
    def inner(x):
        return 2 * x

    @njit(cache=False)
    def outer(x):
        return inner(x) + 1

    @njit(cache=False)
    def broken(x):
        return x.no_such_attribute

    threads: list[str] = []

    class Seen(event.Listener):
        def on_start(self, ev):
            threads.append(threading.current_thread().name)

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", Seen()):
        assert outer(20) == 41
        assert outer(1.5) == 4.0
    assert len(threads) >= 4  # outer and inner, for two signatures
    assert set(threads) == {"quadric-contact compiler"}
    with pytest.raises(TypingError, match="no_such_attribute"):
        broken(1)


@pytest.mark.parametrize("n", [0, 1, 16383, 16384 * 2 + 7, 10**6 + 3])
@pytest.mark.parametrize("threads", [1, 2, 4])
def test_run_parallel_covers_every_item_once(n: int, threads: int) -> None:
    """The threads take the slices in turn: together they cover ``range(n)`` exactly once."""
    import threading

    from quadric_contact.modes.kernels.threads import run_parallel

    seen = np.zeros(n, dtype=np.int64)
    lock = threading.Lock()

    def kernel(lo: int, hi: int) -> None:
        with lock:
            seen[lo:hi] += 1

    run_parallel(kernel, n, threads=threads)
    assert (seen == 1).all()


@pytest.mark.parametrize("n", [0, 1, 16384, 40000, 2_000_000])
def test_slices_shrink_and_cover_the_batch(n: int) -> None:
    """Guided slices: they tile ``range(n)``, no slice but the last is under MIN_PER_THREAD,
    and they never grow, so the last slice a thread takes is a short one."""
    from quadric_contact.modes.kernels.threads import MIN_PER_THREAD, _slices

    bounds = _slices(n, 2)
    sizes = np.diff(bounds)
    assert bounds[0] == 0 and bounds[-1] == n and (sizes > 0).all()
    assert (sizes[:-1] >= MIN_PER_THREAD).all()
    assert (np.diff(sizes[:-1]) <= 0).all()
    if n >= 10 * MIN_PER_THREAD:
        assert sizes[-1] <= MIN_PER_THREAD < sizes[0]


def test_certified_ellipsoids_are_ellipsoids():
    """The short ellipsoid test of classify: the same answer compiled and in numpy, never an
    ellipsoid that is not one (exact type), the canonical sign of the invariant classification
    where that is certain, and it certifies the ordinary ellipsoids of a stack (what it is for)."""
    from quadric_contact.model.classification import QuadricKind
    from quadric_contact.model.quadric import Quadric
    from quadric_contact.modes.decision.answers import UNCERTAIN_ROW, row_of, rows_from_invariant_signs
    from quadric_contact.modes.facts import certified_ellipsoid_signs, float_invariant_signs

    rng = np.random.default_rng(11)
    E, Q, _ = random_pairs(400, rng)
    floats = [h for h in hard_cases() if not h.exact_input]
    hard = np.array([m for h in floats for m in h.matrices()], dtype=float)
    for M in (E, -E, Q, hard):
        got = certified_ellipsoid_signs(M)
        assert (got == certified_ellipsoid_signs(M, backend="numpy")).all()
        rows = rows_from_invariant_signs(float_invariant_signs(M, filtered=True))
        for k in np.flatnonzero(got):
            assert Quadric.from_matrix(M[k]).kind is QuadricKind.ELLIPSOID
            assert rows[k] in (row_of(QuadricKind.ELLIPSOID, int(got[k])), UNCERTAIN_ROW)
    assert (certified_ellipsoid_signs(E) == 1).all() and (certified_ellipsoid_signs(-E) == -1).all()


def test_exact_facts_agree_with_the_integers():
    """The facts of certified ellipsoids (no integers) are the exact ones: ``det Q = 0`` and
    ``rank Q <= 2`` from the exact null space, the masks from the exact invariant signs."""
    from fractions import Fraction

    from quadric_contact.exact.linalg import nullspace
    from quadric_contact.modes.decision.answers import masks_from_invariant_signs
    from quadric_contact.modes.facts import exact_facts
    from quadric_contact.modes.numbers.objects import ExactMode
    from quadric_contact.modes.stacks.batch import as_stack

    rng = np.random.default_rng(12)
    E, Q, _ = random_pairs(300, rng)
    for M in (E, -E, Q):
        stack = as_stack(M, "Q")
        rows = np.arange(len(M))
        flags, masks = exact_facts(stack, rows)
        exact = [[[Fraction(v) for v in r] for r in m] for m in M]
        rank = np.array([4 - len(nullspace(m, zero=Fraction(0), one=Fraction(1))) for m in exact])
        assert (flags == ((rank < 4).astype(np.int8) | ((rank <= 2).astype(np.int8) << 1))).all()
        assert (masks == masks_from_invariant_signs(ExactMode().invariant_signs(stack, rows))).all()


@pytest.mark.skipif(not HAVE_NUMBA, reason="numba not installed")
def test_cached_kernels_are_keyed_on_every_source_they_inline(tmp_path):
    """numba keys a cached kernel on its own file; a kernel whose generated programs or inlined
    helpers changed must not load stale machine code (old formulas with new error bounds)."""
    import shutil

    from quadric_contact.modes.kernels import _jit
    from quadric_contact.modes.kernels.criterion import kernel

    k = kernel("fixed_q", True, False)
    holder = getattr(k._cache, "_cache_file", k._cache)
    module = k.py_func.__module__
    assert holder._source_stamp[1] == _jit._sources_digest(module=module)
    package = _jit.PACKAGE_ROOT
    shutil.copytree(package, tmp_path, dirs_exist_ok=True, ignore=shutil.ignore_patterns("__pycache__"))
    decision_kernel = "quadric_contact.modes.kernels.decision"
    before = _jit._sources_digest(tmp_path, module)
    assert before == _jit._sources_digest(module=module)
    blocks = tmp_path / "_generated" / "blocks.py"
    blocks.write_text(blocks.read_text().replace("Delta2 = ", "Delta2 =  ", 1))
    assert _jit._sources_digest(tmp_path, module) != before
    # the decision table the decision kernel reads as constants is part of its source
    before = _jit._sources_digest(tmp_path, decision_kernel)
    table = tmp_path / "theory" / "decision.py"
    text = table.read_text()
    table.write_text(text.replace("UNCERTAIN = 0, 1, 2", "UNCERTAIN =  0, 1, 2", 1))
    assert _jit._sources_digest(tmp_path, decision_kernel) != before
    # the Python around the kernels is not their source, nor is another kernel's module:
    # editing them compiles nothing again
    before = _jit._sources_digest(tmp_path, decision_kernel)
    for other in ("decision/pipeline.py", "distance/scale_kernel.py"):
        path = tmp_path / "modes" / other
        path.write_text(path.read_text() + "\n")
    assert _jit._sources_digest(tmp_path, decision_kernel) == before


def test_kernel_sources_are_the_compiled_modules_and_what_they_import():
    """Every module that compiles code is among the kernels' sources, with the tables it
    imports; the cascade, the predicates and the modes' classes are not."""

    from quadric_contact.modes.kernels import _jit

    sources = set(_jit.kernel_sources())
    package = _jit.PACKAGE_ROOT
    compiled = 0
    for path in (package / "modes").rglob("*.py"):
        text = path.read_text()
        if "@njit" in text or "@_njit" in text or "jitable(" in text:
            compiled += 1
            assert path.relative_to(package).as_posix() in sources, path
    assert compiled >= 10
    assert {
        "theory/decision.py",
        "theory/regions.py",
        "modes/kernels/errorbounds.py",
        "_generated/blocks.py",
    } <= sources
    assert sources.isdisjoint(
        {
            "modes/decision/pipeline.py",
            "modes/predicates.py",
            "modes/numbers/number_mode.py",
            "modes/numbers/objects.py",
        }
    )
    # a kernel's sources are its module and what it imports, followed through compiled modules
    assert _jit.kernel_sources(module="quadric_contact.modes.distance.scale_kernel") == [
        "modes/distance/scale_kernel.py",
        "modes/kernels/_jit.py",
    ]
    decision = set(_jit.kernel_sources(module="quadric_contact.modes.kernels.decision"))
    assert {"modes/kernels/criterion.py", "modes/kernels/signature.py", "_generated/blocks.py"} <= decision
    assert "modes/distance/scale_kernel.py" not in decision
