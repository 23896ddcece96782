"""Hostile inputs the parser accepts, generated and run in a child process under limits.

Hypothesis builds batches of inputs for the entry points (equations, numbers,
paths in ``t``, motions, families, scene files, ``check``) from pieces that
have broken the package before: long runs of blanks, digits, underscores and
dots, huge exponents, deep nesting, many parameters, names that collide,
control characters.  Each batch runs in a fresh interpreter that

* limits its CPU time and its address space (``resource.setrlimit``), so a
  hang or a runaway allocation ends the child instead of the test run, and an
  abort (SIGABRT) shows as a signal;
* arms an audit hook (``sys.addaudithook``) after warming up, which records
  any program run, code compiled or executed that is not a module file, a
  module imported for the first time, or a socket opened;
* answers every input or refuses it with an error of the package's hierarchy,
  and reports anything else, and the CPU time each input took.

The default suite runs a few batches; ``-m slow`` runs the long fuzz
(``HOSTILE_FUZZ_EXAMPLES`` batches, 400 by default) and writes the slowest
inputs to ``HOSTILE_FUZZ_REPORT`` if set.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

ROOT = Path(__file__).resolve().parents[1]

CPU_SECONDS = 120
"""CPU limit of one child (a batch): far above what the bounds allow, so only a hang reaches it."""

MEMORY_BYTES = 3 * 1024**3
"""Address-space limit of one child."""

SLOWEST: list[tuple[float, str, str]] = []

CHILD = r"""
import io, json, resource, sys, time, contextlib
resource.setrlimit(resource.RLIMIT_CPU, ({cpu}, {cpu}))
resource.setrlimit(resource.RLIMIT_AS, ({mem}, {mem}))
cases = json.loads(sys.stdin.read())

import quadric_contact as qc
from quadric_contact.exact.errors import QuadricContactError
from quadric_contact.exact.rational import to_fraction
from quadric_contact.exact.reading import parse_univariate
from quadric_contact.families.family import family
from quadric_contact.interfaces.cli import main
from quadric_contact.scenes.scene_toml import parse_scene
from quadric_contact.scenes.trajectory import PolynomialMotion

def run(kind, a, b, c):
    if kind == "equation":
        q = qc.Quadric.from_equation(a); repr(q); q.equation()
    elif kind == "number":
        str(to_fraction(a))
    elif kind == "path":
        parse_univariate(a, "t")
    elif kind == "motion":
        PolynomialMotion(json.loads(a), json.loads(b) if b else None)
    elif kind == "family":
        fam = family(a, b, c)
        fam.coefficients; fam.deltas; fam.characteristic_polynomial("mu")
    elif kind == "scene":
        parse_scene(a, check_smallness=False)
    elif kind == "check":
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            status = main(["check", a, b])
        assert status in (0, 2, 3), status
    elif kind == "pair":
        r = qc.relative_position(a, b); repr(r); json.dumps(r.to_dict())

# warm up every path once, so that the hook below sees only what inputs cause
for case in ({warm}):
    try:
        run(*case)
    except QuadricContactError:
        pass

events = []
armed = [True]
_FROM_FILE_OK = True
def hook(event, args):
    if not armed[0]:
        return
    if event in ("os.system", "subprocess.Popen", "os.exec", "os.posix_spawn", "os.fork", "socket.connect",
                 "socket.bind", "ctypes.dlopen"):
        events.append(f"{{event}} {{args!r:.100}}")
    elif event == "import" and args and args[0] not in sys.modules:
        events.append(f"import {{args[0]!r}}")
    elif event in ("exec", "compile"):
        if event == "exec":
            name = getattr(args[0], "co_filename", None)
        else:
            name = args[1] if len(args) > 1 else None
        if not (isinstance(name, str) and name.endswith(".py")):
            events.append(f"{{event}} of {{str(name)!r:.80}}")
sys.addaudithook(hook)

out = []
for kind, a, b, c in cases:
    t0 = time.process_time()
    try:
        run(kind, a, b, c)
        verdict = "answered"
    except QuadricContactError as exc:
        verdict = "refused"
    except BaseException as exc:
        verdict = f"UNEXPECTED {{type(exc).__name__}}: {{str(exc)[:200]}}"
    out.append((kind, verdict, time.process_time() - t0))
armed[0] = False
print(json.dumps({{"results": out, "events": events}}))
"""

WARM = (
    '("equation", "x^2+y^2+z^2-1", "", ""), ("number", "1/3", "", ""), ("path", "t^2", "", ""),'
    ' ("motion", "[[0, 1], [0], [0]]", "[[1], [0], [0], [0, 1]]", ""),'
    ' ("family", "(x-u)^2+y^2+z^2-1", "x^2+y^2-z^2-1", "u"),'
    ' ("scene", "[scene]", "", ""), ("check", "x^2+y^2+z^2-1", "x^2+y^2-z^2/4-1", ""),'
    ' ("pair", "x^2+y^2+z^2-1", "x^2+y^2-z^2/4-1", "")'
)


def run_batch(cases: list[tuple[str, str, str, str]]) -> dict[str, Any]:
    """Run ``cases`` in a child under the limits; fail on a crash, a signal or an audit event."""
    env = dict(os.environ, PYTHONPATH=str(ROOT / "src"))
    code = CHILD.format(cpu=CPU_SECONDS, mem=MEMORY_BYTES, warm=WARM)
    done = subprocess.run(
        [sys.executable, "-c", code],
        input=json.dumps(cases),
        capture_output=True,
        text=True,
        env=env,
        timeout=CPU_SECONDS * 4,
    )
    why = f"child ended with {done.returncode}: {done.stderr[-3000:]}\ncases: {cases!r:.3000}"
    assert done.returncode == 0, why
    report = json.loads(done.stdout.strip().splitlines()[-1])
    assert not report["events"], report["events"]
    for (kind, verdict, seconds), case in zip(report["results"], cases, strict=True):
        assert not verdict.startswith("UNEXPECTED"), (verdict, case)
        SLOWEST.append((seconds, verdict, f"{kind}: {case[1][:80]!r} {case[2][:60]!r} {case[3][:30]!r}"))
    _write_report()
    return report


def _write_report() -> None:
    """The slowest inputs so far, to ``HOSTILE_FUZZ_REPORT`` if set (after every batch,
    so that an interrupted run still leaves its findings)."""
    target = os.environ.get("HOSTILE_FUZZ_REPORT")
    if not target:
        return
    ranked = sorted(SLOWEST, reverse=True)
    admitted = [r for r in ranked if r[1] == "answered"]
    summary = {"inputs": len(SLOWEST), "slowest": ranked[:10], "slowest_answered": admitted[:10]}
    Path(target).write_text(json.dumps(summary, indent=1))


# -- the generators ---------------------------------------------------------------------------

RUNS = [" ", "\t", "\u00a0", "1", "_", ".", "e", "1_", "..", "(", "-", "+", "x", "*", "9", "0", "\n"]
RUNS += ["\x1b"]
TOKENS = ["x", "y", "z", "t", "1", "1e999", "1e-999", "0.5", "/", "*", "+", "-", "**", "^", "(", ")", "="]
TOKENS += [" "]


@st.composite
def hostile_text(draw: Any, limit: int = 5200) -> str:
    parts = []
    for _ in range(draw(st.integers(1, 4))):
        choice = draw(st.integers(0, 3))
        if choice == 0:
            parts.append(draw(st.sampled_from(RUNS)) * draw(st.integers(0, limit)))
        elif choice == 1:
            parts.append("".join(draw(st.lists(st.sampled_from(TOKENS), max_size=200))))
        elif choice == 2:
            depth = draw(st.integers(0, 100))
            parts.append("(" * depth + draw(st.sampled_from(["x", "1", "x**2"])) + ")" * depth)
        else:
            digits = draw(st.integers(1, 1200))
            parts.append("1" * digits + draw(st.sampled_from(["", "e", "e9", "/3", "." + "7" * 50, "**8"])))
    return "".join(parts)[: limit + 10]


PARAMETER_NAMES = ["u", "v", "w", "s", "a", "b", "c", "d", "e", "f", "lambda", "t", "mu", "name", "E"]
PARAMETER_NAMES += ["class"]


@st.composite
def family_case(draw: Any) -> tuple[str, str, str, str]:
    names = draw(st.lists(st.sampled_from(PARAMETER_NAMES), min_size=1, max_size=8, unique=True))
    factors = [f"({n}+{draw(st.integers(1, 9))})" for n in names]
    power = draw(st.integers(1, 3))
    e = f"({'*'.join(factors[:2])})^{power}*x^2 + y^2 + z^2 - 1"
    q = f"{'*'.join(factors)}*x^2 + ({'+'.join(names)})*y^2 - z^2 - 1"
    return ("family", e, q, " ".join(names))


@st.composite
def motion_case(draw: Any) -> tuple[str, str, str, str]:
    n = draw(st.integers(0, 300))
    top = json.dumps([0] * n + [1])
    quat = json.dumps([[4], [0], [0], [0] * draw(st.integers(0, 120)) + [1]])
    return ("motion", f"[{top}, [0], [0]]", quat, "")


@st.composite
def scene_case(draw: Any) -> tuple[str, str, str, str]:
    depth = draw(st.integers(0, 700))
    name = draw(st.sampled_from(["bee", "bee\\u001b[2J", "bee\\r\\nfirst contact: t = 0", "bee\\u202e"]))
    text = f'[scene]\nname = "{name}"\ntime = [0, 1]\nplaces = {draw(st.integers(0, 2000))}\n'
    text += "x = " + "[" * depth + "1" + "]" * depth + "\n"
    return ("scene", text, "", "")


def text_case(kind: str) -> Any:
    return st.tuples(st.just(kind), hostile_text(), hostile_text(600), st.just(""))


CASES = st.one_of(
    text_case("equation"),
    text_case("number"),
    text_case("path"),
    text_case("check"),
    text_case("pair"),
    family_case(),
    motion_case(),
    scene_case(),
)

BATCHES = st.lists(CASES, min_size=1, max_size=12)


@settings(max_examples=2, deadline=None, suppress_health_check=list(HealthCheck))
@given(BATCHES)
def test_hostile_batches_are_answered_or_refused_in_a_limited_child(cases):
    run_batch(cases)


def test_the_issue_corpus_runs_clean_in_a_limited_child():
    """The inputs that hung, aborted or crashed the package, as one batch."""
    run_batch(
        [
            ("number", " " * 4999 + "!", "", ""),
            ("number", "1" * 4999 + "e", "", ""),
            ("equation", "\t" * 4999 + "x", "", ""),
            ("motion", json.dumps([[0] * 200 + [1], [0], [0]]), "", ""),
            ("motion", "[[0, 1], [0], [0]]", json.dumps([[4], [0], [0], [0] * 100 + [1]]), ""),
            ("family", "x^2+y^2+z^2-1", "(a+2)*(b+3)*(c+4)*(d+5)*x^2 + y^2 - z^2 - 1", "a b c d"),
            (
                "family",
                "x^2+y^2+z^2-1",
                "(a+2)*(b+3)*(c+4)*(d+5)*(e+6)*(f+7)*(g+8)*(h+9)*x^2 + y^2 - z^2 - 1",
                "a b c d e f g h",
            ),
            ("family", "(x-lambda)^2+y^2+z^2-1", "z", "lambda"),
            ("scene", "x = " + "[" * 600 + "]" * 600, "", ""),
        ]
    )


@pytest.mark.slow
def test_the_long_fuzz():
    examples = int(os.environ.get("HOSTILE_FUZZ_EXAMPLES", "400"))

    @settings(max_examples=examples, deadline=None, suppress_health_check=list(HealthCheck))
    @given(BATCHES)
    def fuzz(cases: list[tuple[str, str, str, str]]) -> None:
        run_batch(cases)

    fuzz()
