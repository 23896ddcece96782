"""What accuracy costs: the number modes and their peers, measured in one run.

Everything is measured against the exact answer for the binary64 matrices the
predicates receive (:class:`~quadric_contact.modes.ExactMode`).  Used by
``quadric-contact bench`` and the scripts in ``benchmarks/``.

Populations
-----------
``random``
    :func:`~quadric_contact.testing.samples.random_pairs` over the ten types (Table 1 and
    the plane).  Rounding makes the rotated cylinders and parallel planes only
    *nearly* degenerate, so some of their pairs are genuinely hard.
``generic``
    The same with the types that rounding does not make nearly degenerate for the
    contact question (:data:`~quadric_contact.testing.samples.GENERIC_KINDS`).
``hard``
    The hard-case suite (:mod:`quadric_contact.testing.hardcases`).

The populations of the complete decision and of the kernels are
:func:`~quadric_contact.testing.samples.complete_populations` and
:func:`~quadric_contact.testing.samples.kernel_population`.

Peers
-----
``numpy eigvals``, ``numpy roots``, ``sympy`` and ``fcl GJK``
(:mod:`quadric_contact.testing.peers`); python-fcl's solid overlap is compared with the
exact "contact or one inside the other"
(:func:`~quadric_contact.testing.references.exact_overlap`).
"""

from __future__ import annotations

import contextlib
import functools
import json
import math
import os
import platform
import resource
import subprocess
import sys
import tempfile
import time
import tracemalloc
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from quadric_contact.exact.errors import MissingDependencyError
from quadric_contact.exact.optional import pyplot
from quadric_contact.model.classification import QuadricKind
from quadric_contact.modes import (
    BallMode,
    CertifiedMode,
    ContactCode,
    ExactMode,
    FilterMode,
    FloatMode,
    MpmathMode,
    NumberMode,
    OverlapCode,
)
from quadric_contact.modes.kernels import native
from quadric_contact.modes.kernels._jit import COMPILE_NOTICE, TWINS_NOTICE
from quadric_contact.modes.kernels.support_drivers import read_all
from quadric_contact.modes.predicates import corollary_10, overlap, relative_position, transversal_contact
from quadric_contact.modes.stacks.batch import run_stack
from quadric_contact.modes.stacks.packing import Packed, pack
from quadric_contact.testing.hardcases import FAMILIES, hard_cases
from quadric_contact.testing.peers import EIG_TOL, peer_fcl, peer_numpy_eigvals, peer_numpy_roots, peer_sympy
from quadric_contact.testing.references import exact_overlap
from quadric_contact.testing.samples import (
    GENERIC_KINDS,
    SAMPLE_KINDS,
    complete_populations,
    kernel_population,
    random_pairs,
)
from quadric_contact.testing.symmetric import axis_family, stable

__all__ = ["PROFILES", "Measurement", "Report", "run"]

K = QuadricKind

PROFILES: dict[str, dict[str, Any]] = {
    "smoke": {  # seconds: what the test suite runs
        "pairs": 2_000,
        "slow_pairs": 100,
        "sympy_pairs": 2,
        "fcl_pairs": 200,
        "sizes": (10**3, 10**4),
        "escalation_pairs": 10**4,
        "exact_timing_pairs": 200,
        "hard_families": ("example-11", "delta4-zero", "dyadic-tangent", "ladder"),
        "complete_pairs": 5_000,
        "exact_scalar_pairs": 200,
        "fcl_complete_pairs": 200,
        "kernel_pairs": 20_000,
        "cold_start": False,
    },
    "quick": {
        "pairs": 20_000,  # fast modes on the random populations
        "slow_pairs": 1_000,  # ball, mpmath, exact, numpy roots
        "sympy_pairs": 10,
        "fcl_pairs": 2_000,
        "sizes": (10**3, 10**4, 10**5, 10**6),
        "escalation_pairs": 10**6,
        "exact_timing_pairs": 5_000,
        "complete_pairs": 10**6,
        "exact_scalar_pairs": 2_000,
        "fcl_complete_pairs": 5_000,
        "kernel_pairs": 2 * 10**6,
        "cold_start": True,
    },
    "full": {
        "pairs": 200_000,
        "slow_pairs": 5_000,
        "sympy_pairs": 40,
        "fcl_pairs": 20_000,
        "sizes": (10**3, 10**4, 10**5, 10**6, 10**7),
        "escalation_pairs": 10**7,
        "exact_timing_pairs": 20_000,
        "complete_pairs": 4 * 10**6,
        "exact_scalar_pairs": 10_000,
        "fcl_complete_pairs": 20_000,
        "kernel_pairs": 4 * 10**6,
        "cold_start": True,
    },
}


def criterion_stack(E: Any, Q: Any, *, mode: Any = "certified") -> np.ndarray:
    """The paper's criterion on a stack (:func:`quadric_contact.corollary_10`): the stage the
    number modes compute first, and what the mode measurements below time."""
    return run_stack("criterion", E, Q, mode)


@dataclass
class Measurement:
    """One method on one population."""

    method: str
    kind: str  # "mode" or "peer"
    population: str
    n: int
    seconds: float
    wrong: int
    undecided: int
    note: str = ""

    @property
    def per_test(self) -> float:
        return self.seconds / max(self.n, 1)

    @property
    def wrong_rate(self) -> float:
        return self.wrong / max(self.n, 1)

    @property
    def undecided_rate(self) -> float:
        return self.undecided / max(self.n, 1)


@dataclass
class Figure:
    """One line of the summary: what is measured (``name``), the peer or machine limit it is
    measured against in the same run (``against``; empty for a time or a rate of its own),
    the value and its unit, and the figures it was computed from (``note``)."""

    name: str
    against: str
    measured: float
    unit: str
    note: str = ""


@dataclass
class Report:
    profile: str
    machine: dict[str, Any]
    measurements: list[Measurement] = field(default_factory=list)
    ladder: dict[str, dict[str, int]] = field(default_factory=dict)
    throughput: list[dict[str, Any]] = field(default_factory=list)
    bandwidth: dict[str, float] = field(default_factory=dict)
    escalation: dict[str, Any] = field(default_factory=dict)
    summary: list[Figure] = field(default_factory=list)
    not_measured: list[str] = field(default_factory=list)
    huge: dict[str, Any] | None = None
    missing: list[str] = field(default_factory=list)
    complete: list[dict[str, Any]] = field(default_factory=list)
    native: list[dict[str, Any]] = field(default_factory=list)
    exact_scalar: list[dict[str, Any]] = field(default_factory=list)
    float_families: list[dict[str, Any]] = field(default_factory=list)
    kernels: list[dict[str, Any]] = field(default_factory=list)
    kernel_bandwidth: dict[str, dict[str, float]] = field(default_factory=dict)
    cold_start: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> str:
        data = asdict(self)
        for m, d in zip(self.measurements, data["measurements"], strict=True):
            d.update(per_test=m.per_test, wrong_rate=m.wrong_rate, undecided_rate=m.undecided_rate)
        return json.dumps(data, indent=1, default=str)

    def table(self) -> str:
        lines = [f"# quadric-contact bench ({self.profile} profile)", ""]
        lines += [f"machine: {self.machine}", ""]
        if self.missing:
            lines += [f"not measured (missing optional packages): {', '.join(self.missing)}", ""]
        if self.measurements:
            lines += ["## Time per test and errors", ""]
            lines += [
                "| population | method | pairs | time per test | wrong | undecided | note |",
                "|---|---|---:|---:|---:|---:|---|",
            ]
        for m in self.measurements:
            lines.append(
                f"| {m.population} | {m.method} | {m.n} | {_fmt_time(m.per_test)} | "
                f"{m.wrong} ({m.wrong_rate:.2%}) | {m.undecided} ({m.undecided_rate:.2%}) | {m.note} |"
            )
        if self.ladder:
            methods = list(next(iter(self.ladder.values())))
            lines += [
                "",
                "## Near-tangent ladder: wrong answers (of 40 per distance: 10 types x 2 sides x away/into)",
                "",
            ]
            lines += ["| distance | " + " | ".join(methods) + " |", "|---|" + "---:|" * len(methods)]
            for d, row in self.ladder.items():
                lines.append(f"| {d} | " + " | ".join(str(row[m]) for m in methods) + " |")
        if self.throughput:
            lines += ["", "## Throughput against batch size", ""]
            lines += ["| mode | pairs | seconds | pairs/s | peak numpy memory |", "|---|---:|---:|---:|---:|"]
            for row in self.throughput:
                lines.append(
                    f"| {row['mode']} | {row['n']} | {row['seconds']:.4f} | {row['rate']:.3g} | "
                    f"{_fmt_bytes(row['peak_bytes'])} |"
                )
        if self.bandwidth:
            b = self.bandwidth
            lines += [
                "",
                f"Reading the inputs once ({b['pairs']} pairs, {_fmt_bytes(b['bytes'])}): "
                f"{b['seconds']:.4f} s, {b['gbytes_per_s']:.1f} GB/s = {b['pairs_per_s']:.3g} pairs/s "
                "(the memory-bandwidth limit).",
            ]
        if self.escalation:
            lines += ["", "## Escalation past the filter (certified, transversal contact)", ""]
            for pop, e in self.escalation.items():
                lines.append(
                    f"- {pop}: {e['escalated']} of {e['pairs']} ({e['rate']:.2e}); stages {e['stages']}"
                )
        if self.complete:
            lines += [
                "",
                "## The complete decision against the certified criterion kernel, same pairs, same run",
                "",
                "Throughput as a fraction of the kernel's (distinct pairs; one matrix against the",
                "stack for the environment); wrong: against the certified answer.",
                "",
                "| population | question, mode | pairs | time per pair | pairs/s | of the kernel | "
                "reached the exact stage | wrong | settled by |",
                "|---|---|---:|---:|---:|---:|---:|---:|---|",
            ]
            for row in self.complete:
                wrong = "" if row.get("wrong") is None else f"{row['wrong']} ({row['wrong'] / row['n']:.2%})"
                exact = "" if row.get("exact_pairs") is None else f"{row['exact_pairs'] / row['n']:.2e}"
                lines.append(
                    f"| {row['population']} | {row['method']} | {row['n']} | "
                    f"{_fmt_time(row['seconds'] / row['n'])} "
                    f"| {row['n'] / row['seconds']:.3g} | {_fmt_ratio(row.get('ratio'))} | {exact} "
                    f"| {wrong} | {row.get('stages', '')} |"
                )
        if self.native:
            lines += [
                "",
                "## The native kernels against numba's run-time compile of the same kernels",
                "",
                "Certified, distinct pairs; fresh processes, the two ways alternated three times, the",
                "best time of each; speed: the native kernels' throughput over numba's.",
                "",
                "| population | question | pairs | native, a pair | numba at run time, a pair | speed |",
                "|---|---|---:|---:|---:|---:|",
            ]
            for nrow in self.native:
                lines.append(
                    f"| {nrow['population']} | {nrow['question']} | {nrow['n']} | "
                    f"{_fmt_time(nrow['native'] / nrow['n'])} | {_fmt_time(nrow['numba'] / nrow['n'])} | "
                    f"{nrow['numba'] / nrow['native']:.2f} |"
                )
        if self.exact_scalar:
            lines += [
                "",
                "## The exact scalar decision, one pair at a time (binary64 input, certified mode)",
                "",
                f"Each pair's time is the least of {SCALAR_ROUNDS} rounds over the population.",
                "",
                "| population | pairs | median | 90th percentile | slowest | decided by |",
                "|---|---:|---:|---:|---:|---|",
            ]
            for srow in self.exact_scalar:
                rules = ", ".join(f"{k} {v}" for k, v in sorted(srow["rules"].items()))
                lines.append(
                    f"| {srow['population']} | {srow['n']} | {_fmt_time(srow['median'])} | "
                    f"{_fmt_time(srow['p90'])} | {_fmt_time(srow['max'])} | {rules} |"
                )
        if self.float_families:
            lines += [
                "",
                "## The float mode where rounding misleads (against the exact decision)",
                "",
                "| family | pairs | float mode wrong | raw float criterion wrong |",
                "|---|---:|---:|---:|",
            ]
            for row in self.float_families:
                lines.append(
                    f"| {row['family']} | {row['n']} | {row['float wrong']} "
                    f"| {row['raw float criterion wrong']} |"
                )
        if self.kernels:
            lines += [
                "",
                "## Kernels at the memory limit (small ellipsoids against larger ones, float64 (N, 4, 4))",
                "",
                "| input | method | pairs | pairs/s | fraction of the read-bandwidth limit |",
                "|---|---|---:|---:|---:|",
            ]
            for row in self.kernels:
                frac = "" if row.get("fraction") is None else f"{row['fraction']:.2f}"
                lines.append(
                    f"| {row['input']} | {row['method']} | {row['n']} | {row['rate']:.3g} | {frac} |"
                )
            for name, b in self.kernel_bandwidth.items():
                lines.append(
                    f"\nReading the inputs of the {name} pairs once: {_fmt_bytes(b['bytes'])} "
                    f"in {b['seconds']:.4f} s, "
                    f"{b['gbytes_per_s']:.1f} GB/s = {b['pairs_per_s']:.3g} pairs/s."
                )
        if self.cold_start:
            c = self.cold_start
            lines += [
                "",
                "## First use (1000 pairs: transversal_contact, then overlap; fresh processes, one "
                "numba cache directory that starts empty)",
                "",
            ]
            for key, what in (
                ("native", "empty cache, the default with the native kernels (nothing compiled)"),
                ("fresh", "empty cache, without the native kernels (their Python twins answer)"),
                (
                    "compiling",
                    "empty cache, without them, waiting for the compile (QUADRIC_CONTACT_KERNELS=wait)",
                ),
                ("warm", "without them, a fourth process, the cache filled by the third"),
            ):
                if key not in c:
                    continue
                r = c[key]
                lines.append(
                    f"- {what}: import {r['import']:.1f} s, transversal_contact {r['first']:.2f} s, "
                    f"overlap {r['overlap']:.2f} s, process {r['wall']:.1f} s in all"
                )
        if self.huge:
            h = self.huge
            lines += [
                "",
                f"## Chunked run: {h['pairs']:.3g} pairs in chunks of {h['chunk']}: {h['seconds']:.1f} s, "
                f"peak RSS {_fmt_bytes(h['peak_rss'])}, contact {h['contact']}",
            ]
        if self.summary:
            lines += [
                "",
                "## Summary: rates, and ratios against the peers and the read bandwidth of this run",
                "",
                "| measured | against | value | from |",
                "|---|---|---:|---|",
            ]
            for f in self.summary:
                lines.append(f"| {f.name} | {f.against} | {f.measured:.3g} {f.unit} | {f.note} |")
        for reason in self.not_measured:
            lines += ["", f"Not measured: {reason}."]
        return "\n".join(lines) + "\n"


def _fmt_ratio(ratio: float | None) -> str:
    return "" if ratio is None or not math.isfinite(ratio) else f"{ratio:.2f}"


def _fmt_time(s: float) -> str:
    if s >= 1e-3:
        return f"{s * 1e3:.3g} ms"
    if s >= 1e-6:
        return f"{s * 1e6:.3g} us"
    return f"{s * 1e9:.3g} ns"


def _fmt_bytes(b: float) -> str:
    for unit in ("B", "KB", "MB", "GB"):
        if b < 1024 or unit == "GB":
            return f"{b:.3g} {unit}"
        b /= 1024
    return f"{b:.3g} GB"


# -- helpers ---------------------------------------------------------------------------------


_SETTLE_SECONDS = 0.5
_SETTLE_RUNS = 15


def _best_of(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """The shortest of at least ``repeat`` runs of ``fn``, and its last result.  A run of a few
    milliseconds is timed again, up to :data:`_SETTLE_RUNS` times while the runs take less than
    :data:`_SETTLE_SECONDS` in all: the best of three such runs wandered by a third from one
    report to the next (a thread woken late, a page faulted in), and a ratio of two of them
    with it."""
    best, out = math.inf, None
    runs, spent = 0, 0.0
    while runs < max(1, repeat) or (runs < _SETTLE_RUNS and spent < _SETTLE_SECONDS):
        t = time.perf_counter()
        out = fn()
        dt = time.perf_counter() - t
        best = min(best, dt)
        runs += 1
        spent += dt
    return best, out


@contextlib.contextmanager
def _traced() -> Iterator[list[int]]:
    box = [0]
    tracemalloc.start()
    try:
        yield box
    finally:
        box[0] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()


def machine_info() -> dict[str, Any]:
    import numba  # heavy and optional: only its version is read

    info = {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "numba": numba.__version__,
        "cpus": os.cpu_count(),
        "platform": platform.platform(),
    }
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                info["cpu"] = line.split(":", 1)[1].strip()
                break
    return info


# -- measurements -------------------------------------------------------------------------------


def _modes() -> list[tuple[str, NumberMode]]:
    return [
        ("float", FloatMode()),
        ("filter", FilterMode()),
        ("certified", CertifiedMode()),
        ("ball (128 bits)", BallMode(128)),
        ("mpmath (50 digits)", MpmathMode(50)),
        ("exact", ExactMode()),
    ]


_SLOW = ("ball (128 bits)", "mpmath (50 digits)", "exact")


def _measure_modes(
    population: str, E: np.ndarray, Q: np.ndarray, truth: np.ndarray, cfg: dict[str, Any], report: Report
) -> None:
    n_slow = min(len(E), cfg["slow_pairs"])
    for name, mode in _modes():
        n = n_slow if name in _SLOW else len(E)
        repeat = 1 if name in _SLOW else 3
        seconds, codes = _best_of(functools.partial(criterion_stack, E[:n], Q[:n], mode=mode), repeat)
        decided = codes != 2
        note = ""
        if isinstance(mode, CertifiedMode):
            note = f"stages {mode.last}"
        report.measurements.append(
            Measurement(
                name,
                "mode",
                population,
                n,
                seconds,
                int(np.count_nonzero(decided & (codes != truth[:n]))),
                int(np.count_nonzero(~decided)),
                note,
            )
        )


def _measure_peers(
    population: str,
    E: np.ndarray,
    Q: np.ndarray,
    truth: np.ndarray,
    cfg: dict[str, Any],
    report: Report,
) -> None:
    seconds, codes = _best_of(lambda: peer_numpy_eigvals(E, Q), 1)
    report.measurements.append(
        Measurement(
            "numpy eigvals",
            "peer",
            population,
            len(E),
            seconds,
            int(np.count_nonzero(codes != truth)),
            0,
            f"tol {EIG_TOL}",
        )
    )
    n = min(len(E), cfg["slow_pairs"])
    seconds, codes = _best_of(lambda: peer_numpy_roots(E[:n], Q[:n]), 1)
    report.measurements.append(
        Measurement(
            "numpy roots",
            "peer",
            population,
            n,
            seconds,
            int(np.count_nonzero(codes != truth[:n])),
            0,
            f"tol {EIG_TOL}",
        )
    )
    n = min(len(E), cfg["sympy_pairs"])
    seconds, codes = _best_of(lambda: peer_sympy(E[:n], Q[:n]), 1)
    report.measurements.append(
        Measurement(
            "sympy det+discriminant",
            "peer",
            population,
            n,
            seconds,
            int(np.count_nonzero(codes != truth[:n])),
            0,
        )
    )


def _measure_fcl(rng: np.random.Generator, cfg: dict[str, Any], report: Report) -> None:
    try:
        import fcl  # noqa: F401  (optional, the bench extra: is python-fcl installed?)
    except ImportError:
        report.missing.append("python-fcl")
        return
    n = cfg["fcl_pairs"]
    E, Q, _, geo_e, geo_q = random_pairs(n, rng, kinds=(K.ELLIPSOID,), with_geometry=True)
    keep = np.flatnonzero(geo_q["sign"] > 0)
    E, Q = E[keep], Q[keep]
    geo_q = {k: v[keep] for k, v in geo_q.items()}
    geo_e = {k: v[keep] for k, v in geo_e.items()}
    contact = criterion_stack(E, Q, mode="exact")
    truth = exact_overlap(E, Q, contact)
    seconds, got = _best_of(lambda: peer_fcl(geo_e, geo_q, range(len(E))), 1)
    report.measurements.append(
        Measurement(
            "fcl GJK",
            "peer",
            "random ellipsoid pairs (solid overlap)",
            len(E),
            seconds,
            int(np.count_nonzero(got != truth)),
            0,
            "truth: contact or one inside the other",
        )
    )
    seconds, codes = _best_of(lambda: criterion_stack(E, Q), 3)
    report.measurements.append(
        Measurement(
            "certified",
            "mode",
            "random ellipsoid pairs (solid overlap)",
            len(E),
            seconds,
            int(np.count_nonzero(codes != contact)),
            0,
            "transversal contact; overlap adds an exact centre test",
        )
    )


def _hard(report: Report, cfg: dict[str, Any]) -> None:
    cases = [c for c in hard_cases(cfg.get("hard_families", FAMILIES)) if not c.exact_input]
    E = np.stack([c.matrices()[0] for c in cases])
    Q = np.stack([c.matrices()[1] for c in cases])
    truth = criterion_stack(E, Q, mode="exact")
    _measure_modes("hard", E, Q, truth, {**cfg, "slow_pairs": len(E)}, report)
    _measure_peers("hard", E, Q, truth, cfg, report)
    # the ladder, distance by distance
    ladder = [k for k, c in enumerate(cases) if c.family == "ladder" and c.direction != "tangent"]
    distances = sorted({str(cases[k].distance) for k in ladder}, key=lambda d: int(d.split("-")[-1]))
    methods: dict[str, np.ndarray] = {}
    El, Ql = E[ladder], Q[ladder]
    for name, mode in _modes():
        methods[name] = criterion_stack(El, Ql, mode=mode)
    methods["numpy eigvals"] = peer_numpy_eigvals(El, Ql)
    methods["numpy roots"] = peer_numpy_roots(El, Ql)
    t = truth[ladder]
    for d in distances:
        sel = np.array([cases[k].distance == d for k in ladder])
        report.ladder[str(d)] = {
            name: int(np.count_nonzero(sel & (codes != 2) & (codes != t))) for name, codes in methods.items()
        }
    # fcl on the ellipsoid rungs (solid overlap: contact, or E inside Q on the R- side)
    with contextlib.suppress(ImportError):
        import fcl  # noqa: F401  (optional, the bench extra: is python-fcl installed?)

        rungs = [k for k in ladder if cases[k].kind == "ellipsoid"]
        geometry = [cases[k].geometry or {} for k in rungs]
        geo_e = {key: np.array([g["E"][key] for g in geometry]) for key in ("axes", "rotation", "center")}
        geo_q = {key: np.array([g["Q"][key] for g in geometry]) for key in ("axes", "rotation", "center")}
        region = [cases[k].side for k in rungs]
        overlap = np.array(
            [
                int(truth[k] == ContactCode.CONTACT or side == "R-")
                for k, side in zip(rungs, region, strict=True)
            ]
        )
        seconds, got = _best_of(lambda: peer_fcl(geo_e, geo_q, range(len(rungs))), 1)
        report.measurements.append(
            Measurement(
                "fcl GJK",
                "peer",
                "hard (ellipsoid ladder, solid overlap)",
                len(rungs),
                seconds,
                int(np.count_nonzero(got != overlap)),
                0,
            )
        )
        for d in distances:
            sel = np.array([cases[k].distance == d for k in rungs])
            report.ladder[str(d)]["fcl GJK (ellipsoid rungs)"] = int(np.count_nonzero(sel & (got != overlap)))
        for row in report.ladder.values():
            row.setdefault("fcl GJK (ellipsoid rungs)", 0)


def read_bandwidth(E: np.ndarray, Q: np.ndarray, repeat: int = 15) -> dict[str, float]:
    """The time to read every byte of ``E`` and ``Q`` once (a compiled, threaded sum):
    no kernel that reads its inputs can be faster."""
    read_all(E[:10], Q[:10])
    seconds, _ = _best_of(lambda: read_all(E, Q), repeat)
    nbytes = E.nbytes + Q.nbytes
    return {
        "pairs": len(E),
        "bytes": nbytes,
        "seconds": seconds,
        "gbytes_per_s": nbytes / seconds / 1e9,
        "pairs_per_s": len(E) / seconds,
    }


def _throughput(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> None:
    top = max(cfg["sizes"])
    pool = min(top, 10**6)
    E, Q, _ = random_pairs(pool, rng, kinds=GENERIC_KINDS)
    if top > pool:
        reps = -(-top // pool)
        E = np.tile(E, (reps, 1, 1))[:top]
        Q = np.tile(Q, (reps, 1, 1))[:top]
    report.bandwidth = read_bandwidth(E, Q)
    for size in cfg["sizes"]:
        for name, mode in (("float", FloatMode()), ("filter", FilterMode()), ("certified", CertifiedMode())):
            e, q = E[:size], Q[:size]
            repeat = 5 if size <= 10**5 else 2
            seconds, _ = _best_of(functools.partial(criterion_stack, e, q, mode=mode), repeat)
            with _traced() as peak:
                criterion_stack(e, q, mode=mode)
            report.throughput.append(
                {"mode": name, "n": size, "seconds": seconds, "rate": size / seconds, "peak_bytes": peak[0]}
            )
    size = min(top, 10**5)
    seconds, _ = _best_of(functools.partial(peer_numpy_eigvals, E[:size], Q[:size]), 2)
    report.throughput.append(
        {"mode": "numpy eigvals", "n": size, "seconds": seconds, "rate": size / seconds, "peak_bytes": 0}
    )


def _escalation(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> None:
    total = cfg["escalation_pairs"]
    for population, kinds in (("generic", GENERIC_KINDS), ("random", SAMPLE_KINDS)):
        mode = CertifiedMode()
        done = 0
        while done < total:
            n = min(10**6, total - done)
            E, Q, _ = random_pairs(n, rng, kinds=kinds)
            criterion_stack(E, Q, mode=mode)
            done += n
        report.escalation[population] = {
            "pairs": total,
            "escalated": mode.counts.escalated,
            "rate": mode.counts.escalated / total,
            "stages": str(mode.counts),
        }


def _stage_fractions(counts: Any) -> str:
    total = max(counts.total, 1)
    parts = [f"{stage} {n / total:.3g}" for stage, n in counts.decided.items() if n]
    if counts.undecided:
        parts.append(f"undecided {counts.undecided / total:.3g}")
    return ", ".join(parts)


NATIVE_AGAINST_JIT_CODE = """
import functools, json, sys
import numpy as np
from quadric_contact.interfaces.benchmark import _best_of, criterion_stack
from quadric_contact.modes.predicates import overlap, relative_position, transversal_contact
from quadric_contact.testing.samples import complete_populations
n, seed = int(sys.argv[1]), int(sys.argv[2])
out = {}
for population, (E, Q, _) in complete_populations(n, np.random.default_rng(seed)).items():
    head = (E[:100], Q if Q.ndim == 2 else Q[:100])
    for name, fn in (("criterion kernel", criterion_stack), ("contact", transversal_contact),
                     ("region", relative_position), ("overlap", overlap)):
        fn(*head)
        out[population + "|" + name] = _best_of(functools.partial(fn, E, Q), 3)[0]
print(json.dumps(out))
"""


def native_against_run_time_compile(n: int, rounds: int = 3, seed: int = 0) -> dict[str, dict[str, float]]:
    """The certified criterion kernel and the complete certified decision on the populations of
    :func:`~quadric_contact.testing.samples.complete_populations`, with the native kernels and
    with numba's run-time compile of the same kernels (loaded from its cache): fresh processes,
    the two alternated ``rounds`` times (this host's speed drifts by tens of percent within a
    minute), the best time of each.
    Returns ``{"population|question": {"native": s, "numba": s}}``; empty without native
    kernels."""
    lib = native.library() if native.enabled() else None
    if lib is None or not lib.usable:
        return {}
    src = str(Path(__file__).resolve().parents[2])
    best: dict[str, dict[str, float]] = {}
    for _ in range(rounds):
        for way, flag in (("native", "1"), ("numba", "0")):
            env = dict(
                os.environ,
                QUADRIC_CONTACT_NATIVE=flag,
                QUADRIC_CONTACT_KERNELS="wait",
                PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""),
            )
            proc = subprocess.run(
                [sys.executable, "-c", NATIVE_AGAINST_JIT_CODE, str(n), str(seed)],
                capture_output=True,
                text=True,
                check=True,
                env=env,
            )
            for key, seconds in json.loads(proc.stdout).items():
                row = best.setdefault(key, {})
                row[way] = min(row.get(way, math.inf), seconds)
    return best


def _against_run_time_compile(report: Report, n: int) -> None:
    """The table of :func:`native_against_run_time_compile`."""
    for key, t in native_against_run_time_compile(n).items():
        population, question = key.split("|")
        report.native.append({"population": population, "question": question, "n": n, **t})


def _complete(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> None:
    """Population by population: the certified criterion kernel alone, and the complete decision
    of each question (certified, and float) on the same pairs, as a fraction of the kernel's
    throughput; which stage settled how many pairs; the float mode's and the peers' errors
    against the certified answer."""
    n = cfg["complete_pairs"]
    for population, (E, Q, geometry) in complete_populations(n, rng).items():
        head = (E[:100], Q if Q.ndim == 2 else Q[:100])
        for fn in (transversal_contact, relative_position, overlap):
            fn(*head)  # compile / load the kernels
            fn(*head, mode="float")
        criterion_stack(*head)
        base, _ = _best_of(functools.partial(criterion_stack, E, Q), 3)
        report.complete.append(
            {
                "population": population,
                "method": "certified criterion kernel alone",
                "n": n,
                "seconds": base,
                "ratio": 1.0,
                "stages": "non-real roots or not (no smallness, no region)",
            }
        )
        truth: dict[str, np.ndarray] = {}
        questions = (("contact", transversal_contact), ("region", relative_position), ("overlap", overlap))
        for question, fn in questions:
            mode = CertifiedMode()
            seconds, truth[question] = _best_of(functools.partial(fn, E, Q, mode=mode), 3)
            report.complete.append(
                {
                    "population": population,
                    "method": f"{question}, certified",
                    "n": n,
                    "seconds": seconds,
                    "ratio": base / seconds,
                    "stages": _stage_fractions(mode.last),
                    "exact_pairs": mode.last.decided.get("exact pair", 0),
                }
            )
            fmode = FloatMode()
            seconds, got = _best_of(functools.partial(fn, E, Q, mode=fmode), 3)
            report.complete.append(
                {
                    "population": population,
                    "method": f"{question}, float",
                    "n": n,
                    "seconds": seconds,
                    "ratio": base / seconds,
                    "wrong": int(np.count_nonzero(got != truth[question])),
                    "stages": _stage_fractions(fmode.last),
                }
            )
        if geometry is None:
            continue
        m = min(n, 200_000)
        seconds, eig = _best_of(functools.partial(peer_numpy_eigvals, E[:m], Q[:m]), 1)
        report.complete.append(
            {
                "population": population,
                "method": "numpy batch eigvals (peer)",
                "n": m,
                "seconds": seconds,
                "ratio": base / n * m / seconds,
                "wrong": int(np.count_nonzero(eig != truth["contact"][:m])),
                "stages": "non-real eigenvalues of -Q E^-1 (tolerance 1e-9)",
            }
        )
        try:
            import fcl  # noqa: F401  (optional, the bench extra: is python-fcl installed?)
        except ImportError:
            continue
        k = min(n, cfg["fcl_complete_pairs"])
        if k == 0:
            continue
        t0 = time.perf_counter()
        got = peer_fcl(geometry[0], geometry[1], range(k))
        seconds = time.perf_counter() - t0
        certified_overlap = truth["overlap"][:k] != int(OverlapCode.SEPARATE)
        report.complete.append(
            {
                "population": population,
                "method": "python-fcl GJK, solid overlap (peer)",
                "n": k,
                "seconds": seconds,
                "ratio": base / n * k / seconds,
                "wrong": int(np.count_nonzero(got != certified_overlap)),
                "stages": "against the certified overlap",
            }
        )
    _against_run_time_compile(report, n)


SCALAR_ROUNDS = 7
"""Rounds of the exact scalar decision's timing (each pair's least time is kept)."""
SCALAR_PAUSE = 0.3
"""Seconds between two rounds (the host's slow spells last seconds)."""


def _exact_scalar(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> None:
    """The exact scalar decision (one pair at a time, binary64 input, the certified mode's scalar
    path) on pairs of every type and of similar sizes: median and 90th percentile per pair, and
    how many pairs each rule of the decision table settled.  Each pair's time is the least of
    ``SCALAR_ROUNDS`` rounds over the populations, ``SCALAR_PAUSE`` apart (as :mod:`timeit`
    takes the least of its repeats): a shared host's speed drifts by tens of percent for seconds
    at a time, and a single pass reads the drift as much as the code."""
    n = cfg["exact_scalar_pairs"]
    populations = {k: v for k, v in complete_populations(n, rng).items() if k != "environment"}
    times = {k: [math.inf] * n for k in populations}
    rules: dict[str, dict[str, int]] = {k: {} for k in populations}
    for round_ in range(SCALAR_ROUNDS):
        if round_:
            time.sleep(SCALAR_PAUSE)
        for population, (E, Q, _) in populations.items():
            for i in range(n):
                q = Q if Q.ndim == 2 else Q[i]
                t0 = time.perf_counter()
                r = transversal_contact(E[i], q)
                times[population][i] = min(times[population][i], time.perf_counter() - t0)
                if round_ == 0:
                    by = str(getattr(r, "decided_by", None))
                    rules[population][by] = rules[population].get(by, 0) + 1
    for population in populations:
        least = sorted(times[population])
        report.exact_scalar.append(
            {
                "population": population,
                "n": n,
                "median": least[n // 2],
                "p90": least[int(0.9 * n)],
                "max": least[-1],
                "rules": rules[population],
            }
        )


def _float_families(report: Report) -> None:
    """The float mode against the exact decision on the symmetric placements and on the
    hard-case ladders down to 1e-12 from tangency (the rounded matrices' exact answer)."""
    family = axis_family()
    keep = stable(family, lambda E, Q: transversal_contact(E, Q, mode="exact"))
    family = [p for p, k in zip(family, keep, strict=True) if k]
    sets = {"symmetric placements on circular axes (stable)": ([p.E for p in family], [p.Q for p in family])}
    ladder = [
        c.matrices()
        for c in hard_cases(("ladder",))
        if c.direction != "tangent" and c.distance is not None and float(c.distance) >= 1e-12
    ]
    sets["hard-case ladders, 1e-2 .. 1e-12"] = ([e for e, _ in ladder], [q for _, q in ladder])
    for name, (es, qs) in sets.items():
        E, Q = np.stack(es), np.stack(qs)
        exact = transversal_contact(E, Q, mode="exact")
        report.float_families.append(
            {
                "family": name,
                "n": len(es),
                "float wrong": int(np.count_nonzero(transversal_contact(E, Q, mode="float") != exact)),
                "raw float criterion wrong": int(np.count_nonzero(corollary_10(E, Q, mode="float") != exact)),
            }
        )


def _kernels(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> None:
    """The criterion alone (float, filter, certified; float64 and packed input) and the complete
    decision on distinct pairs and on one matrix against the stack (broadcasting), each against
    the time it takes to read its inputs once, and numpy's batch eigenvalues on the same pairs
    (distinct, and one matrix against the stack) against the certified codes."""
    n = cfg["kernel_pairs"]
    E, Q = kernel_population(n, rng)
    repeat = 7  # best of 7: each run is tens of milliseconds, and a shared machine is noisy
    report.kernel_bandwidth = {"distinct": read_bandwidth(E, Q), "broadcast": read_bandwidth(E, Q[:1])}
    PE, PQ = Packed(pack(E)), Packed(pack(Q))
    inputs = {
        "distinct": (E, Q),
        "broadcast": (E, Q[0]),
        "distinct, packed": (PE, PQ),
        "broadcast, packed": (PE, Packed(pack(Q[:1]))),
    }
    methods: list[tuple[str, Any, Callable[..., Any]]] = [
        ("float", FloatMode(), criterion_stack),
        ("filter", FilterMode(), criterion_stack),
        ("certified", CertifiedMode(), criterion_stack),
        ("certified, complete decision", CertifiedMode(), transversal_contact),
    ]
    for label, (e, q) in inputs.items():
        limit = report.kernel_bandwidth["broadcast" if label.startswith("broadcast") else "distinct"]
        packed = "packed" in label
        lim_rate = limit["pairs_per_s"] * (128 / 80 if packed else 1.0)
        for name, mode, fn in methods:
            if packed and name in ("float", "filter"):
                continue
            seconds, _ = _best_of(functools.partial(fn, e, q, mode=mode), repeat)
            report.kernels.append(
                {
                    "input": label,
                    "method": name,
                    "n": n,
                    "seconds": seconds,
                    "rate": n / seconds,
                    "fraction": None if name.endswith("decision") else n / seconds / lim_rate,
                }
            )
    m = min(n, 200_000)
    peers = {"distinct": Q[:m], "broadcast": np.broadcast_to(Q[0], (m, 4, 4))}
    for label, q in peers.items():
        seconds, eig = _best_of(functools.partial(peer_numpy_eigvals, E[:m], q), 1)
        ref = criterion_stack(E[:m], q, mode=CertifiedMode())
        report.kernels.append(
            {
                "input": label,
                "method": "numpy batch eigvals (peer)",
                "n": m,
                "seconds": seconds,
                "rate": m / seconds,
                "fraction": None,
                "wrong": int(np.count_nonzero(eig != ref)),
            }
        )


COLD_START_CODE = """
import time
t0 = time.perf_counter()
import numpy as np
import quadric_contact as qc
from quadric_contact.testing.samples import kernel_population
t1 = time.perf_counter()
E, Q = kernel_population(1000, np.random.default_rng(0))
qc.transversal_contact(E, Q)
t2 = time.perf_counter()
qc.overlap(E, Q)
t3 = time.perf_counter()
print(t1 - t0, t2 - t1, t3 - t2)
"""


def cold_start() -> dict[str, Any]:
    """The first array calls (the complete decision, certified, and the overlap, on 1000 pairs)
    in fresh interpreters sharing a numba cache directory that starts empty, as after ``pip
    install``:

    * ``native``: the default where the package was built with its native kernels
      (:mod:`quadric_contact.modes.kernels.native`): nothing to compile (not measured without them);
    * ``fresh``: without the native kernels, the calls answered by the kernels' Python twins
      (the background warm-up is not started here: the ``twins`` policy);
    * ``compiling``: without them, the ``wait`` policy, the calls compiling what they need (what
      the first call cost before the twins, and what a large first call costs);
    * ``warm``: a fourth process, which loads what the third one compiled.

    For each: the import time, the two calls' times, the wall time of the process, and whether
    it printed the twins' or the compiler's notice."""
    src = str(Path(__file__).resolve().parents[2])
    out: dict[str, Any] = {}
    lib = native.library() if native.enabled() else None
    runs = [("native", "wait", "1")] if lib is not None and lib.usable else []
    runs += [("fresh", "twins", "0"), ("compiling", "wait", "0"), ("warm", "wait", "0")]
    with tempfile.TemporaryDirectory(prefix="quadric-contact-cache-") as cache:
        for run_, policy, use_native in runs:
            env = dict(
                os.environ,
                QUADRIC_CONTACT_CACHE_DIR=cache,
                QUADRIC_CONTACT_KERNELS=policy,
                QUADRIC_CONTACT_NATIVE=use_native,
                PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""),
            )
            t = time.perf_counter()
            proc = subprocess.run(
                [sys.executable, "-c", COLD_START_CODE], capture_output=True, text=True, check=True, env=env
            )
            wall = time.perf_counter() - t
            imp, first, overlap = (float(v) for v in proc.stdout.split())
            out[run_] = {
                "import": imp,
                "first": first,
                "overlap": overlap,
                "wall": wall,
                "twins": TWINS_NOTICE.split("{")[0][:40] in proc.stderr,
                "notice": COMPILE_NOTICE.split("{")[0][:40] in proc.stderr,
            }
    return out


def _exact_timing(report: Report, cfg: dict[str, Any], rng: np.random.Generator) -> dict[str, float]:
    n = cfg["exact_timing_pairs"]
    E, Q, _ = random_pairs(n, rng)
    out = {}
    for backend in ("int", "fmpz"):
        seconds, _ = _best_of(functools.partial(criterion_stack, E, Q, mode=ExactMode(backend)), 2)
        out[backend] = seconds / n
    return out


def _summary(report: Report, exact_per_pair: dict[str, float]) -> None:
    """The summary: each figure of the run against its peer (numpy's batch eigenvalues, the
    plain float kernel, python-flint, sympy) or against the time it takes to read the inputs
    once, all measured in this run."""

    def rate(method: str, population: str = "generic") -> float:
        m = next(m for m in report.measurements if m.method == method and m.population == population)
        return 1.0 / m.per_test

    def batch_rate(mode: str) -> tuple[float, int]:
        """Pairs per second at the largest batch size measured for ``mode``."""
        row = max((t for t in report.throughput if t["mode"] == mode), key=lambda t: t["n"])
        return float(row["rate"]), int(row["n"])

    # Batch throughput from the throughput table: the largest batch of each method, where
    # fixed per-call costs no longer count; the per-test times of the 'generic' population
    # (smaller batches) are given alongside.
    cert_small, flt_small, eig_small = rate("certified"), rate("float"), rate("numpy eigvals")
    (cert, n_cert), (flt, _), (eig, n_eig) = (
        batch_rate("certified"),
        batch_rate("float"),
        batch_rate("numpy eigvals"),
    )
    generic_cert = next(
        m for m in report.measurements if m.method == "certified" and m.population == "generic"
    )
    wrong, small_n = generic_cert.wrong, generic_cert.n
    report.summary.append(
        Figure(
            "certified criterion, pairs per second",
            "numpy batch eigvals",
            cert / eig,
            "x",
            f"batches of {n_cert:.0e} and {n_eig:.0e}; at {small_n} pairs: "
            f"{cert_small / eig_small:.1f}x; certified wrong: {wrong}",
        )
    )
    report.summary.append(
        Figure(
            "certified criterion, pairs per second",
            "the plain float kernel",
            cert / flt,
            "x",
            f"at {small_n} pairs: {cert_small / flt_small:.2f}x",
        )
    )
    big = max((t for t in report.throughput if t["mode"] == "float"), key=lambda t: t["n"])
    if report.bandwidth:
        ratio = big["seconds"] / (big["n"] / report.bandwidth["pairs_per_s"])
        report.summary.append(
            Figure(
                "float kernel, time",
                "reading its inputs once (read bandwidth)",
                ratio,
                "x",
                f"at {big['n']} pairs; read at {report.bandwidth['gbytes_per_s']:.1f} GB/s",
            )
        )
    best = min(exact_per_pair.values())
    which = min(exact_per_pair, key=exact_per_pair.get)  # type: ignore[arg-type]
    sym = [m for m in report.measurements if m.method == "sympy det+discriminant"]
    sympy_note = (
        f"; sympy det+discriminant {1e6 * sum(m.seconds for m in sym) / max(sum(m.n for m in sym), 1):.0f} us"
        if sym
        else ""
    )
    report.summary.append(
        Figure(
            "exact mode, time per pair (binary64 input)",
            "python-flint fmpz backend, sympy",
            best * 1e6,
            "us",
            f"fastest backend: {which}; int (compiled pencil, bounded binary64 Deltas) "
            f"{exact_per_pair['int'] * 1e6:.1f} us, python-flint fmpz {exact_per_pair['fmpz'] * 1e6:.1f} us"
            f"{sympy_note}",
        )
    )
    _kernel_summary(report)
    if "generic" in report.escalation:
        e = report.escalation["generic"]
        every_type = report.escalation.get("random")
        report.summary.append(
            Figure(
                "pairs escalated past the float stage (certified)",
                "",
                e["rate"],
                "",
                f"{e['escalated']} of {e['pairs']} generic pairs"
                + (f"; pairs of every type: {every_type['rate']:.2e}" if every_type else ""),
            )
        )
    if report.huge:
        report.summary.append(
            Figure(
                f"peak memory, {report.huge['pairs']:.3g} pairs in chunks",
                "",
                report.huge["peak_rss"] / 2**30,
                "GB",
                f"chunks of {report.huge['chunk']}, {report.huge['seconds']:.1f} s",
            )
        )


def _kernel_summary(report: Report) -> None:
    rows = {(r["input"], r["method"]): r for r in report.kernels}
    if rows:
        cert = rows[("distinct", "certified")]
        bcast = rows[("broadcast", "certified")]
        flt, fil = rows[("distinct", "float")], rows[("distinct", "filter")]
        eig = rows[("distinct", "numpy batch eigvals (peer)")]
        beig = rows[("broadcast", "numpy batch eigvals (peer)")]
        comp = rows[("distinct", "certified, complete decision")]
        bcomp = rows[("broadcast", "certified, complete decision")]
        n = cert["n"]
        limit = report.kernel_bandwidth["distinct"]
        report.summary += [
            Figure(
                "certified criterion, distinct (N, 4, 4) pairs",
                "",
                cert["rate"],
                "pairs/s",
                f"N = {n}; packed {rows[('distinct, packed', 'certified')]['rate']:.3g}; "
                f"complete decision {comp['rate']:.3g} pairs/s",
            ),
            Figure(
                "certified criterion, one matrix against a stack",
                "",
                bcast["rate"],
                "pairs/s",
                f"N = {n}; complete decision {bcomp['rate']:.3g} pairs/s",
            ),
            Figure(
                "certified criterion, one matrix against a stack, pairs per second",
                "numpy batch eigvals, same pairs",
                bcast["rate"] / beig["rate"],
                "x",
                f"eigvals on {beig['n']} of the same pairs: {beig['rate']:.3g} pairs/s, "
                f"{beig.get('wrong')} differ from certified; on distinct pairs "
                f"{cert['rate'] / eig['rate']:.0f}x, eigvals {eig['rate']:.3g} pairs/s, "
                f"{eig.get('wrong')} differ",
            ),
            Figure(
                "filter, time, distinct pairs",
                "the plain float kernel",
                flt["rate"] / fil["rate"],
                "x",
                f"float {flt['rate']:.3g}, filter {fil['rate']:.3g} pairs/s",
            ),
            Figure(
                "certified criterion, distinct pairs, pairs per second",
                "reading its inputs once (read bandwidth)",
                cert["fraction"],
                "",
                f"read at {limit['gbytes_per_s']:.1f} GB/s = {limit['pairs_per_s']:.3g} pairs/s; "
                f"float {flt['fraction']:.2f}, filter {fil['fraction']:.2f}, "
                f"broadcast certified {bcast['fraction']:.2f}",
            ),
        ]
    c = report.cold_start
    if c:
        fresh, warm = c["fresh"], c["warm"]
        if "native" in c:
            report.summary.append(
                Figure(
                    "first array call, empty numba cache, native kernels (nothing compiled)",
                    "",
                    c["native"]["first"],
                    "s",
                    f"import {c['native']['import']:.1f} s; process {c['native']['wall']:.1f} s in all",
                )
            )
        report.summary += [
            Figure(
                "first array call, empty numba cache, no native kernels (the twins answer)",
                "",
                fresh["first"],
                "s",
                f"import {fresh['import']:.1f} s; the same call waiting for the compile: "
                f"{c['compiling']['first']:.1f} s",
            ),
            Figure(
                "first array call, a second process (cache filled)",
                "",
                warm["first"],
                "s",
                f"import {warm['import']:.1f} s",
            ),
        ]
    else:
        report.not_measured.append(
            f"the first array call with an empty numba cache (a fresh process compiles every kernel; "
            f"the {report.profile} profile leaves it out, the quick and full profiles measure it)"
        )


# -- the chunked run ---------------------------------------------------------------------------------


def peak_rss() -> int:
    """Peak resident set size of this process's own address space, in bytes.

    On Linux ``VmHWM`` from ``/proc/self/status``: ``getrusage``'s ``ru_maxrss`` is
    preserved across ``execve`` and inherited from the parent at ``fork``, so in a
    subprocess started by a process holding large arrays it reports the parent's peak,
    not the child's.  Elsewhere ``ru_maxrss`` (kilobytes on Linux, bytes on macOS)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return int(rss if sys.platform == "darwin" else rss * 1024)


def huge_run(pairs: int = 10**8, chunk: int = 250_000, seed: int = 0) -> dict[str, Any]:
    """Process ``pairs`` pairs in dask chunks (generated chunk by chunk, never all in
    memory) and return the time, the counts and the peak RSS of this process."""
    import dask.array as da  # optional (the dask extra)

    nchunks = -(-pairs // chunk)

    def block(block_info: Any = None) -> np.ndarray:
        k = block_info[None]["chunk-location"][0]
        n = block_info[None]["chunk-shape"][0]
        E, Q, _ = random_pairs(n, np.random.default_rng(seed + k), kinds=GENERIC_KINDS)
        return np.concatenate([E[:, None], Q[:, None]], axis=1)

    chunks = ((chunk,) * (pairs // chunk) + ((pairs % chunk,) if pairs % chunk else ()), (2,), (4,), (4,))
    both = da.map_blocks(block, chunks=chunks, dtype=np.float64)
    mode = CertifiedMode()
    t = time.perf_counter()
    codes = criterion_stack(both[:, 0], both[:, 1], mode=mode)
    seconds = time.perf_counter() - t
    return {
        "pairs": pairs,
        "chunk": chunk,
        "chunks": nchunks,
        "seconds": seconds,
        "contact": int(np.count_nonzero(codes == 1)),
        "stages": str(mode.counts),
        "peak_rss": peak_rss(),
    }


def huge_run_subprocess(pairs: int, chunk: int) -> dict[str, Any]:
    """:func:`huge_run` in a fresh interpreter, so that its peak RSS is its own."""
    code = (
        "import json, sys; from quadric_contact.interfaces.benchmark import huge_run; "
        f"print(json.dumps(huge_run({pairs}, {chunk})))"
    )
    env = dict(os.environ)
    src = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    return dict(json.loads(out.stdout.strip().splitlines()[-1]))


# -- the run and the plot ---------------------------------------------------------------------------


def run(
    profile: str = "quick",
    *,
    seed: int = 0,
    huge: bool = False,
    huge_pairs: int = 10**8,
    log: Callable[[str], None] = print,
) -> Report:
    """Measure everything of a profile (``"quick"`` or ``"full"``) and return the report."""
    if profile not in PROFILES:
        raise ValueError(f"profile must be one of {tuple(PROFILES)}")
    cfg = PROFILES[profile]
    rng = np.random.default_rng(seed)
    report = Report(profile, machine_info())
    for population, kinds in (("generic", GENERIC_KINDS), ("random", SAMPLE_KINDS)):
        log(f"modes and peers on {cfg['pairs']} {population} pairs ...")
        E, Q, _ = random_pairs(cfg["pairs"], rng, kinds=kinds)
        criterion_stack(E[:100], Q[:100], mode="float")  # compile / load the kernels
        truth = criterion_stack(E, Q, mode="exact")
        _measure_modes(population, E, Q, truth, cfg, report)
        _measure_peers(population, E, Q, truth, cfg, report)
    log("hard cases ...")
    _hard(report, cfg)
    log("python-fcl ...")
    _measure_fcl(rng, cfg, report)
    log("throughput and bandwidth ...")
    _throughput(report, cfg, rng)
    log("escalation ...")
    _escalation(report, cfg, rng)
    log("exact mode per pair ...")
    exact = _exact_timing(report, cfg, rng)
    log(f"the complete decision on {cfg['complete_pairs']} pairs per population ...")
    _complete(report, cfg, rng)
    log(f"the exact scalar decision on {cfg['exact_scalar_pairs']} pairs per population ...")
    _exact_scalar(report, cfg, rng)
    log("the float mode on symmetric placements and near-tangent ladders ...")
    _float_families(report)
    log(f"kernels at the memory limit on {cfg['kernel_pairs']} pairs ...")
    _kernels(report, cfg, rng)
    if cfg.get("cold_start"):
        log("first use: a fresh process with an empty numba cache (compiles every kernel it needs) ...")
        report.cold_start = cold_start()
    if huge:
        log(f"chunked run of {huge_pairs:.3g} pairs (in a subprocess) ...")
        report.huge = huge_run_subprocess(huge_pairs, 250_000)
    _summary(report, exact)
    return report


def plot(report: Report, path: Path) -> Path | None:
    """Time per test against error rate (one point per method and population), and
    throughput against batch size; returns the file written, or None without matplotlib."""
    try:
        plt = pyplot("benchmark plots")
    except MissingDependencyError:
        report.missing.append("matplotlib")
        return None
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.5))
    floor = 1e-6
    for ax, population in zip(axes[:2], ("random", "hard"), strict=True):
        for m in report.measurements:
            if not m.population.startswith(population):
                continue
            err = max(m.wrong_rate, floor)
            marker = "o" if m.kind == "mode" else "s"
            ax.scatter(m.per_test, err, marker=marker, s=50)
            label = m.method + (f" ({m.undecided_rate:.1%} undecided)" if m.undecided else "")
            ax.annotate(label, (m.per_test, err), fontsize=7, xytext=(4, 3), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 1)
        ax.set_xlabel("time per test (s)")
        ax.set_ylabel(f"fraction wrong (0 drawn at {floor:g})")
        ax.set_title(f"{population} pairs: what accuracy costs")
        ax.grid(True, which="both", alpha=0.3)
    ax = axes[2]
    for name in sorted({t["mode"] for t in report.throughput}):
        pts = [(t["n"], t["rate"]) for t in report.throughput if t["mode"] == name]
        ax.plot(*zip(*pts, strict=True), marker="o", label=name)
    if report.bandwidth:
        ax.axhline(report.bandwidth["pairs_per_s"], color="k", linestyle="--", label="reading the inputs")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("batch size (pairs)")
    ax.set_ylabel("pairs per second")
    ax.set_title("throughput")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
