"""Machine-checked proofs of the paper's numbered results: records, runner, report.

The directory ``proofs/`` of a checkout (installed with the package as
``quadric_contact_proofs``) holds one module per numbered result of the paper
(``lemma_03_curvature.py``, ``theorem_13_table_4.py``, ...).  Each module
defines ``proof = Proof(...)`` and registers its checks with the
:meth:`Proof.check` decorator.  A check is a function without arguments that
re-derives one printed statement and returns a :class:`Finding`:
:func:`agrees` when the paper's statement holds, or :func:`differs` with what
the paper prints and what is true.

Each check states its :class:`Method`.  The proof methods (symbolic identity,
exhaustive case analysis, exact construction, exact computation) establish
their statement; *evidence* (a search of a stated size) supports a part of a
claim that no check proves, which the result must name (``not_proven``);
a *cross-check* compares the package's implementation with a statement the
proof methods establish, and is no part of any proof.  From this each result
gets a :class:`Verdict`: ``proven``, ``proven, with recorded errata`` or
``evidence only``.

Checks belong to a :class:`Profile`: the default profile (every proof and the
small evidence searches; about half a minute) or the full profile only (large
searches and cross-checks).  ``quadric-contact prove`` runs the default
profile, ``quadric-contact prove --full`` everything.

The expectation is declared with the check: a check that is expected to
find a misprint names the key of an :class:`~quadric_contact.paper.errata.Erratum`
in :data:`~quadric_contact.paper.errata.ERRATA`.  The status of a check is then

``PASS``
    the paper's statement was re-derived and no erratum was expected;
``DIFFERS``
    the paper's statement is wrong exactly as the named, registered erratum
    records (an expectation, not a failure);
``FAIL``
    an unexplained difference (no erratum named, or one that is not
    registered), an erratum that is no longer reproduced, or a consistency
    condition of the derivation that did not hold (:func:`ensure`);
``ERROR``
    the check raised;
``SKIPPED``
    a check of the full profile that was not asked for, or one whose
    optional dependency (hypothesis, for the cross-checks) is not installed.

A result passes (exit status 0 of ``quadric-contact prove``) when none of its
checks is ``FAIL`` or ``ERROR``.

The report ``proofs/REPORT.md`` is rendered from the declarations (result,
checks, methods, verdicts, expected errata) and from
:data:`~quadric_contact.paper.errata.ERRATA`, never from timings, so it is
deterministic; :func:`write_report` runs every check of the full profile
first and refuses to write a report that the checks do not support, and the
test suite checks that the committed file equals :func:`render_report`.
"""

from __future__ import annotations

import functools
import importlib.util
import re
import sys
import time
import traceback
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from types import ModuleType
from typing import Any

from quadric_contact.exact.errors import MissingDependencyError, ProofsNotFoundError, QuadricContactError
from quadric_contact.paper.errata import ERRATA, Erratum
from quadric_contact.paper.results import FURTHER_RESULTS, NUMBERED_RESULTS

RESULTS: tuple[str, ...] = NUMBERED_RESULTS + FURTHER_RESULTS
"""The results a proof module may prove: the paper's numbered ones, then the further results
the package relies on (:data:`~quadric_contact.paper.results.FURTHER_RESULTS`)."""

__all__ = [
    "PACKAGE_NAME",
    "REPORT_NAME",
    "CheckRecord",
    "CheckSpec",
    "Finding",
    "Method",
    "Profile",
    "Proof",
    "ProofFailure",
    "ProofRecord",
    "Status",
    "Verdict",
    "agrees",
    "checkout_proofs_dir",
    "differs",
    "ensure",
    "find_proofs_dir",
    "installed_proofs_dir",
    "load_proofs",
    "render_report",
    "run_proof",
    "search_settings",
    "select",
    "write_report",
]

REPORT_NAME = "REPORT.md"
PACKAGE_NAME = "quadric_contact_proofs"
"""Name under which the proofs directory is imported (its modules may import
each other's private helpers relatively, ``from ._pencils import ...``), and
under which the wheel installs it."""

OPTIONAL_DEPENDENCIES = {"hypothesis": 'pip install ".[test]"'}
"""Packages a check may declare in ``requires`` (beyond the package's own
dependencies), with how to install them."""


class Method(StrEnum):
    """How a check establishes its statement."""

    IDENTITY = "symbolic identity"
    CASES = "exhaustive case analysis"
    CONSTRUCTION = "exact construction"
    COMPUTATION = "exact computation"
    EVIDENCE = "evidence"
    CROSS_CHECK = "cross-check"

    @property
    def proves(self) -> bool:
        """A proof method: the check establishes its statement (evidence and
        cross-checks do not)."""
        return self not in (Method.EVIDENCE, Method.CROSS_CHECK)


class Profile(StrEnum):
    """Which run of ``quadric-contact prove`` includes a check."""

    DEFAULT = "default"
    FULL = "full"


class Verdict(StrEnum):
    """What the checks of a result establish."""

    PROVEN = "proven"
    PROVEN_WITH_ERRATA = "proven, with recorded errata"
    EVIDENCE_ONLY = "evidence only"


class Status(StrEnum):
    PASS = "PASS"
    DIFFERS = "DIFFERS"
    FAIL = "FAIL"
    ERROR = "ERROR"
    SKIPPED = "SKIPPED"

    @property
    def ok(self) -> bool:
        """Matched its recorded expectation (or was not run on purpose)."""
        return self in (Status.PASS, Status.DIFFERS, Status.SKIPPED)


class ProofFailure(AssertionError):
    """A consistency condition inside a derivation did not hold."""


def ensure(condition: Any, message: str) -> None:
    """Raise :class:`ProofFailure` with ``message`` unless ``condition`` is true.

    Used instead of ``assert`` so that derivations are checked under ``python -O`` too.
    """
    if not condition:
        raise ProofFailure(message)


@dataclass(frozen=True)
class Finding:
    """What a check established.

    Attributes
    ----------
    agrees : bool
        The paper's statement holds.
    statement : str
        What was established, in one sentence.
    printed, true : str or None
        When the statement does not hold: what the paper prints and what is true.
    """

    agrees: bool
    statement: str
    printed: str | None = None
    true: str | None = None


def agrees(statement: str) -> Finding:
    """The paper's statement was re-derived; ``statement`` says what was shown."""
    return Finding(True, statement)


def differs(printed: str, true: str, statement: str = "") -> Finding:
    """The paper prints ``printed`` where ``true`` holds."""
    return Finding(False, statement or f"printed {printed}; true {true}", printed, true)


@dataclass(frozen=True)
class CheckSpec:
    """One declared check of a proof module."""

    name: str
    title: str
    method: Method
    func: Callable[[], Finding]
    erratum: str | None = None
    full: bool = False
    size: str | None = None
    requires: tuple[str, ...] = ()

    @property
    def expected_status(self) -> Status:
        return Status.DIFFERS if self.erratum else Status.PASS

    @property
    def profile(self) -> Profile:
        return Profile.FULL if self.full else Profile.DEFAULT

    @property
    def method_text(self) -> str:
        return f"{self.method.value} ({self.size})" if self.size else self.method.value

    def missing(self) -> list[str]:
        """The declared optional dependencies that are not installed."""
        return [name for name in self.requires if importlib.util.find_spec(name) is None]


def search_settings(examples: int) -> Any:
    """Hypothesis settings of every hypothesis search in ``proofs/``: ``examples``
    examples, derandomized and without an example database, so that a search states
    its size and gives the same evidence on every run; no deadline, no health checks
    (the examples are exact computations of very different costs).  Hypothesis is
    imported here, when a search runs: the proofs load without it."""
    from hypothesis import HealthCheck, settings  # hypothesis is heavy and optional: only a search imports it

    return settings(
        max_examples=examples,
        derandomize=True,
        database=None,
        deadline=None,
        suppress_health_check=list(HealthCheck),
    )


class Proof:
    """The checks of one numbered result.

    Parameters
    ----------
    result : str
        The paper's label, one of :data:`~quadric_contact.paper.results.NUMBERED_RESULTS`
        (``"Lemma 3"``, ``"eq. (1)"``, ``"Section 3.2"``), or a further result the package
        relies on, one of :data:`~quadric_contact.paper.results.FURTHER_RESULTS`.
    title : str
        What the result says, in a few words.
    covers : sequence of str
        Further numbered items the module checks (tables, equations).
    not_proven : str
        The part of the claim that no check of the module proves (it rests on
        the paper's argument and is supported by evidence only), or ``""`` when
        the checks prove all of it.  Required when a check is ``Method.EVIDENCE``.
    relies_on : sequence of str
        Other numbered results the proof uses as established (their own
        verdicts apply).

    Examples
    --------
    >>> proof = Proof("Remark 16", "the sign of c3 is the side of the centre")
    >>> @proof.check("a trivial identity", method=Method.IDENTITY)
    ... def trivial():
    ...     return agrees("1 + 1 = 2")
    >>> [c.name for c in proof.checks], str(proof.verdict)
    (['trivial'], 'proven')
    """

    def __init__(
        self,
        result: str,
        title: str,
        *,
        covers: Sequence[str] = (),
        not_proven: str = "",
        relies_on: Sequence[str] = (),
    ) -> None:
        for label in (result, *relies_on):
            if label not in RESULTS:
                raise ValueError(
                    f"{label!r} is not one of the paper's numbered results or further results {RESULTS}"
                )
        if result in relies_on:
            raise ValueError(f"{result} cannot rely on itself")
        self.result = result
        self.title = title
        self.covers = tuple(covers)
        self.not_proven = " ".join(not_proven.split())
        self.relies_on = tuple(relies_on)
        self.checks: list[CheckSpec] = []
        self.name = ""  # the module's name, set by the loader
        self.doc = ""  # the module's docstring, set by the loader
        self.path: Path | None = None

    def check(
        self,
        title: str,
        *,
        method: Method,
        erratum: str | None = None,
        full: bool = False,
        size: str | None = None,
        requires: Sequence[str] = (),
    ) -> Callable[[Callable[[], Finding]], Callable[[], Finding]]:
        """Register a check.

        Parameters
        ----------
        title : str
            What is checked (one line).
        method : Method
            How.  ``Method.EVIDENCE`` and ``Method.CROSS_CHECK`` require ``size``
            (how many examples).
        erratum : str, optional
            Key of the :class:`~quadric_contact.paper.errata.Erratum` this check is
            expected to demonstrate.
        full : bool
            Only in the full profile (``quadric-contact prove --full``; pytest
            runs it with ``-m slow``): large searches, cross-checks, anything
            that would push the default run past half a minute.
        size : str, optional
            The size of a search (``"400 hypothesis examples"``).
        requires : sequence of str
            Optional packages the check needs (keys of ``OPTIONAL_DEPENDENCIES``);
            without them it is skipped, with a note saying how to install them.
        """
        if not method.proves and not size:
            raise ValueError(f"{method.value} check {title!r} must state its size")
        unknown = [r for r in requires if r not in OPTIONAL_DEPENDENCIES]
        if unknown:
            raise ValueError(f"check {title!r} requires undeclared optional packages {unknown}")

        def register(func: Callable[[], Finding]) -> Callable[[], Finding]:
            if any(c.name == func.__name__ for c in self.checks):
                raise ValueError(f"duplicate check name {func.__name__!r} in {self.result}")
            self.checks.append(
                CheckSpec(func.__name__, title, method, func, erratum, full, size, tuple(requires))
            )
            return func

        return register

    def search(
        self,
        title: str,
        *,
        examples: int,
        large: int,
        detail: str = "",
        method: Method = Method.EVIDENCE,
        unit: str = "hypothesis examples",
        requires: Sequence[str] = ("hypothesis",),
    ) -> Callable[[Callable[[int], Finding]], Callable[[int], Finding]]:
        """Register a search twice: ``examples`` examples in the default profile,
        and ``large`` examples in the full profile (``<name>_large``, title suffixed
        "(large search)").  ``examples=0`` registers the large search only (a
        cross-check of the full profile keeps its plain name then).  The decorated
        function takes the number of examples; ``detail`` is appended to the
        stated size."""
        if method.proves:
            raise ValueError("a search is evidence or a cross-check, not a proof")
        suffix = f", {detail}" if detail else ""

        def register(func: Callable[[int], Finding]) -> Callable[[int], Finding]:
            runs = [(func.__name__, examples, False, title)] if examples else []
            if examples:
                runs.append((f"{func.__name__}_large", large, True, f"{title} (large search)"))
            else:
                runs.append((func.__name__, large, True, title))
            for name, n, full, label in runs:
                run = functools.partial(func, n)
                run.__name__ = name  # type: ignore[attr-defined]
                self.check(label, method=method, full=full, size=f"{n} {unit}{suffix}", requires=requires)(
                    run
                )
            return func

        return register

    def validate(self) -> None:
        """Raise :class:`~quadric_contact.exact.errors.QuadricContactError` when the
        declarations contradict each other: evidence for a part of the claim that
        ``not_proven`` does not name."""
        if any(c.method is Method.EVIDENCE for c in self.checks) and not self.not_proven:
            raise QuadricContactError(
                f"{self.result}: evidence checks support a part of the claim that no check proves; "
                "name it in Proof(..., not_proven=...)",
                self.result,
            )

    @property
    def methods(self) -> list[Method]:
        return sorted({c.method for c in self.checks}, key=list(Method).index)

    @property
    def errata(self) -> list[str]:
        """Keys of the errata its checks demonstrate, sorted."""
        return sorted({c.erratum for c in self.checks if c.erratum})

    @property
    def expected_status(self) -> Status:
        return Status.DIFFERS if any(c.erratum for c in self.checks) else Status.PASS

    @property
    def verdict(self) -> Verdict:
        """``evidence only`` when a part of the claim is not proven (``not_proven``);
        otherwise ``proven``, ``with recorded errata`` when a check demonstrates one."""
        if self.not_proven:
            return Verdict.EVIDENCE_ONLY
        return Verdict.PROVEN_WITH_ERRATA if self.errata else Verdict.PROVEN

    @property
    def order(self) -> int:
        return RESULTS.index(self.result)

    def __repr__(self) -> str:
        return f"Proof({self.result!r}, {len(self.checks)} checks, module {self.name!r})"


# -- running -----------------------------------------------------------------------


@dataclass(frozen=True)
class CheckRecord:
    """The outcome of one check."""

    spec: CheckSpec
    status: Status
    finding: Finding | None = None
    message: str = ""
    seconds: float = 0.0

    def describe(self) -> str:
        """One sentence: what was found, and for a difference what the paper prints."""
        f = self.finding
        if self.status is Status.DIFFERS and f is not None:
            return f"printed {f.printed}; true {f.true} [erratum {self.spec.erratum}]"
        if self.status in (Status.FAIL, Status.ERROR):
            return self.message
        if self.status is Status.SKIPPED:
            return self.message or "not run (full profile only: --full)"
        return f.statement if f is not None else ""


_ERRATA_BY_KEY = {e.key: e for e in ERRATA}
_ERRATA_KEYS = set(_ERRATA_BY_KEY)


def run_check(spec: CheckSpec) -> CheckRecord:
    """Run one check and compare its finding with its declared expectation."""
    start = time.perf_counter()
    try:
        finding = spec.func()
    except ProofFailure as exc:
        return CheckRecord(spec, Status.FAIL, None, f"derivation failed: {exc}", time.perf_counter() - start)
    except Exception as exc:
        tb = traceback.format_exception_only(type(exc), exc)[-1].strip()
        return CheckRecord(spec, Status.ERROR, None, f"raised {tb}", time.perf_counter() - start)
    seconds = time.perf_counter() - start
    if not isinstance(finding, Finding):
        return CheckRecord(spec, Status.ERROR, None, f"returned {finding!r} instead of a Finding", seconds)
    if spec.erratum is not None and spec.erratum not in _ERRATA_KEYS:
        return CheckRecord(
            spec, Status.FAIL, finding, f"names erratum {spec.erratum!r}, which is not in ERRATA", seconds
        )
    if finding.agrees:
        if spec.erratum is None:
            return CheckRecord(spec, Status.PASS, finding, "", seconds)
        return CheckRecord(
            spec,
            Status.FAIL,
            finding,
            f"erratum {spec.erratum!r} is no longer reproduced: {finding.statement}",
            seconds,
        )
    if spec.erratum is None:
        return CheckRecord(
            spec,
            Status.FAIL,
            finding,
            f"unexplained difference: printed {finding.printed}; true {finding.true}",
            seconds,
        )
    return CheckRecord(spec, Status.DIFFERS, finding, "", seconds)


@dataclass(frozen=True)
class ProofRecord:
    """The outcomes of all checks of one result."""

    proof: Proof
    checks: tuple[CheckRecord, ...] = field(default_factory=tuple)

    @property
    def status(self) -> Status:
        statuses = [c.status for c in self.checks]
        for s in (Status.ERROR, Status.FAIL, Status.DIFFERS, Status.PASS):
            if s in statuses:
                return s
        return Status.SKIPPED

    @property
    def ok(self) -> bool:
        return all(c.status.ok for c in self.checks)

    @property
    def seconds(self) -> float:
        return sum(c.seconds for c in self.checks)

    def line(self) -> str:
        """The one-line summary printed by ``quadric-contact prove``: the status, the result, and for
        each erratum demonstrated what the paper prints and what is true (the registered wording;
        ``-v`` shows what each check computed), or why a check failed or was skipped."""
        p = self.proof
        ran = [c for c in self.checks if c.status is not Status.SKIPPED]
        head = f"{self.status.value:<8} {p.name}  {p.result}: {p.title}"
        counts = f"{len(ran)} check{'s' if len(ran) != 1 else ''}"
        not_run = [c for c in self.checks if c.status is Status.SKIPPED and not c.message]
        if not_run:
            counts += f"; {len(not_run)} of the full profile not run"
        missing = [c for c in self.checks if c.status is Status.SKIPPED and c.message]
        if missing:
            counts += f"; {len(missing)} skipped: {missing[0].message}"
        notes: list[str] = []
        for c in self.checks:
            if c.status is Status.DIFFERS:
                e = _ERRATA_BY_KEY[c.spec.erratum]  # type: ignore[index]
                note = f"printed {e.printed}; true {e.corrected} [{e.key}]"
            elif c.status in (Status.FAIL, Status.ERROR):
                note = f"{c.spec.name}: {c.describe()}"
            else:
                continue
            if note not in notes:
                notes.append(note)
        detail = f" -- {' | '.join(notes)}" if notes else ""
        return f"{head} ({counts}){detail}"


def run_proof(
    proof: Proof,
    *,
    profile: Profile | str = Profile.FULL,
    only: Iterable[str] | None = None,
    on_check: Callable[[CheckRecord], None] | None = None,
) -> ProofRecord:
    """Run the checks of one proof in ``profile`` (the default profile skips the
    checks of the full profile; ``only``: check names to run, the rest are skipped).
    A check whose optional dependency is missing is skipped with a note."""
    full = Profile(profile) is Profile.FULL
    wanted = set(only) if only is not None else None
    records = []
    for spec in proof.checks:
        if (wanted is not None and spec.name not in wanted) or (spec.full and not full):
            rec = CheckRecord(spec, Status.SKIPPED)
        elif missing := spec.missing():
            how = "; ".join(f"{m} ({OPTIONAL_DEPENDENCIES[m]})" for m in missing)
            rec = CheckRecord(spec, Status.SKIPPED, message=f"needs {how}")
        else:
            rec = run_check(spec)
        if on_check is not None:
            on_check(rec)
        records.append(rec)
    return ProofRecord(proof, tuple(records))


# -- discovery ----------------------------------------------------------------------


def _is_proofs_dir(path: Path) -> bool:
    return path.is_dir() and (path / "__init__.py").is_file() and any(_module_files(path))


def _module_files(path: Path) -> list[Path]:
    return sorted(p for p in path.glob("*.py") if not p.name.startswith("_"))


def installed_proofs_dir() -> Path | None:
    """The proofs installed with the package: the wheel ships ``proofs/`` as the
    package ``quadric_contact_proofs``, installed beside ``quadric_contact`` itself
    (the same ``site-packages``), or None.

    Only that place counts, never a search of ``sys.path``: with ``python -m`` the
    first entry of ``sys.path`` is the current directory, so a search would import
    a ``quadric_contact_proofs`` planted there."""
    path = Path(__file__).resolve().parents[2] / PACKAGE_NAME
    return path if _is_proofs_dir(path) else None


def checkout_proofs_dir() -> Path | None:
    """``proofs/`` of the checkout holding this package's source
    (``<checkout>/src/quadric_contact/...`` beside ``<checkout>/pyproject.toml``),
    or None when the package is not run from a checkout."""
    here = Path(__file__).resolve()
    src, root = here.parents[2], here.parents[3]
    if src.name != "src" or not (root / "pyproject.toml").is_file():
        return None
    path = root / "proofs"
    return path if _is_proofs_dir(path) else None


def find_proofs_dir(explicit: str | Path | None = None) -> Path:
    """Locate the proofs.

    ``explicit`` if given; else ``proofs/`` of the checkout holding this
    package's source (a checkout or an editable install); else the proofs
    installed with the package (``quadric_contact_proofs``, shipped in the
    wheel, beside ``quadric_contact``).  Never the current directory or its
    parents: importing a proof runs its code, and a ``proofs/`` folder planted
    above the working directory would run as whoever calls ``prove`` there.

    Raises
    ------
    ProofsNotFoundError
        If none is found (the message lists every place looked at), or
        ``explicit`` is not a proofs directory.
    """
    if explicit is not None:
        path = Path(explicit).expanduser().resolve()
        if not _is_proofs_dir(path):
            raise ProofsNotFoundError(
                f"{path} is not a proofs directory (it needs an __init__.py and proof modules, "
                "like proofs/ in a checkout of quadric-contact)",
                str(path),
            )
        return path
    for found in (checkout_proofs_dir(), installed_proofs_dir()):
        if found is not None:
            return found
    here = Path(__file__).resolve()
    raise ProofsNotFoundError(
        f"no proofs found: looked for proofs/ of a checkout around the package's source "
        f"({here.parents[3] / 'proofs'}) and for the proofs installed with the package (module "
        f"{PACKAGE_NAME} in {here.parents[2]}, not installed); pass --proofs-dir DIR, the proofs/ "
        "directory of a checkout of quadric-contact",
        str(here.parents[2]),
    )


def _import_package(directory: Path) -> ModuleType:
    existing = sys.modules.get(PACKAGE_NAME)
    if existing is not None and Path(getattr(existing, "__file__", "")).parent == directory:
        return existing
    for name in [m for m in sys.modules if m == PACKAGE_NAME or m.startswith(PACKAGE_NAME + ".")]:
        del sys.modules[name]
    spec = importlib.util.spec_from_file_location(
        PACKAGE_NAME, directory / "__init__.py", submodule_search_locations=[str(directory)]
    )
    assert spec is not None and spec.loader is not None
    package = importlib.util.module_from_spec(spec)
    sys.modules[PACKAGE_NAME] = package
    spec.loader.exec_module(package)
    return package


def load_proofs(directory: str | Path | None = None) -> list[Proof]:
    """Import every proof module of ``directory`` (default :func:`find_proofs_dir`),
    in the paper's order.

    Raises
    ------
    ProofsNotFoundError
        If the directory is not found.
    MissingDependencyError
        If a proof module needs a package that is not installed (the proofs use the
        test dependencies, hypothesis in particular).
    QuadricContactError
        If a module does not define ``proof``, or two modules claim one result.
    """
    path = find_proofs_dir(directory)
    _import_package(path)
    proofs: list[Proof] = []
    for file in _module_files(path):
        try:
            module = importlib.import_module(f"{PACKAGE_NAME}.{file.stem}")
        except ModuleNotFoundError as exc:
            raise MissingDependencyError(
                f"{file.name} needs {exc.name!r}, which is not installed (the proofs load with the "
                "package's own dependencies; a check that needs an optional one declares it)",
                exc.name,
            ) from exc
        proof = getattr(module, "proof", None)
        if not isinstance(proof, Proof):
            raise QuadricContactError(f"{file} defines no `proof = Proof(...)`", str(file))
        proof.name = file.stem
        proof.doc = (module.__doc__ or "").strip()
        proof.path = file
        if not proof.doc:
            raise QuadricContactError(f"{file} has no docstring stating the claim", str(file))
        proof.validate()
        proofs.append(proof)
    seen: dict[str, str] = {}
    for p in proofs:
        if p.result in seen:
            raise QuadricContactError(f"{p.name} and {seen[p.result]} both prove {p.result}", p.result)
        seen[p.result] = p.name
    return sorted(proofs, key=lambda p: (p.order, p.name))


def _normalise(name: str) -> str:
    return re.sub(r"[^a-z0-9]+", "", name.lower())


def select(proofs: Sequence[Proof], names: Sequence[str]) -> list[Proof]:
    """The proofs named by module name, a prefix of it, or the result's label
    (``"lemma_03_curvature"``, ``"lemma_03"``, ``"Lemma 3"``, ``"table 4"``).

    Raises
    ------
    QuadricContactError
        For a name that matches nothing or more than one result.
    """
    if not names:
        return list(proofs)
    chosen: list[Proof] = []
    for name in names:
        key = _normalise(name)
        exact = [p for p in proofs if _normalise(p.result) == key or p.name == name]
        matches = exact or [
            p
            for p in proofs
            if p.name.startswith(name)
            or _normalise(p.name).startswith(key)
            or any(_normalise(c) == key for c in p.covers)
        ]
        if len(matches) != 1:
            what = (
                "matches nothing" if not matches else f"is ambiguous ({', '.join(p.name for p in matches)})"
            )
            available = ", ".join(p.name for p in proofs)
            raise QuadricContactError(f"{name!r} {what}; available: {available}", name)
        if matches[0] not in chosen:
            chosen.append(matches[0])
    return chosen


# -- the report ----------------------------------------------------------------------


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _demonstrations(proofs: Sequence[Proof]) -> dict[str, list[tuple[Proof, CheckSpec]]]:
    out: dict[str, list[tuple[Proof, CheckSpec]]] = {e.key: [] for e in ERRATA}
    for p in proofs:
        for c in p.checks:
            if c.erratum is not None:
                out.setdefault(c.erratum, []).append((p, c))
    return out


def _body_paragraphs(doc: str) -> list[str]:
    """The docstring's paragraphs after its heading line, each joined into one line."""
    text = re.sub(r":\w+:`~?([^`]+)`", r"`\1`", doc)  # reST roles -> code spans
    paragraphs = [" ".join(p.split()) for p in text.split("\n\n")]
    return [p for p in paragraphs[1:] if p]


def _relies(p: Proof) -> str:
    return ", ".join(p.relies_on) if p.relies_on else "-"


def render_report(proofs: Sequence[Proof], errata: Sequence[Erratum] = ERRATA) -> str:
    """The text of ``proofs/REPORT.md`` for these (loaded) proofs."""
    n_checks = sum(len(p.checks) for p in proofs)
    n_full = sum(1 for p in proofs for c in p.checks if c.full)
    n_differs = sum(1 for p in proofs for c in p.checks if c.erratum)
    verdicts = {v: sum(1 for p in proofs if p.verdict is v) for v in Verdict}
    demonstrated = _demonstrations(proofs)
    lines = [
        "# Proofs report",
        "",
        "Generated by `quadric-contact prove --report` from the modules in `proofs/` and the errata",
        "registry `quadric_contact.paper.ERRATA`; do not edit by hand (`tests/test_proofs.py` fails",
        "when this file is out of date).  The report is written only after every check of the full",
        "profile has run and matched its recorded expectation.",
        "",
        "Verdict of a result: **proven**, every part of its claim is established by checks that",
        "prove (the methods below other than evidence and cross-checks); **proven, with recorded",
        "errata**, the same, where the printed statement differs from the truth as recorded in the",
        "errata; **evidence only**, a part of the claim (named under the result) rests on the paper's",
        "argument and is supported here by evidence only (searches or single constructions), not by",
        "a proof.  A result may rely on other results, whose verdicts then apply too.",
        "",
        "Status of a check: **PASS**, the printed statement is re-derived in exact arithmetic;",
        "**DIFFERS**, the printed statement is wrong, as recorded in the errata below (the check",
        "demonstrates the erratum).  Methods that prove: *symbolic identity* (sympy proves an",
        "identity in the paper's symbols), *exhaustive case analysis* (every case of a finite",
        "classification is examined), *exact construction* (an explicit exact example exhibits an",
        "existence claim or refutes a universal one), *exact computation* (the printed numbers of a",
        "worked example recomputed exactly).  Methods that do not: *evidence* (a search of the",
        "stated size that found no counterexample, for a part of a claim no check proves) and",
        "*cross-check* (a search comparing the package's implementation with a statement the other",
        "checks prove: it tests the code and is no part of the proof).",
        "",
        "Profiles: `quadric-contact prove` runs the default profile (every proof and the small",
        "evidence searches, about half a minute); `quadric-contact prove --full` adds the checks",
        "marked *(full profile)*: large searches and cross-checks.",
        "",
        f"{len(proofs)} results: {verdicts[Verdict.PROVEN]} proven, {verdicts[Verdict.PROVEN_WITH_ERRATA]} "
        f"proven with recorded errata, {verdicts[Verdict.EVIDENCE_ONLY]} evidence only.  {n_checks} checks "
        f"({n_full} of them in the full profile only), {n_differs} of them demonstrating "
        f"{len([e for e in errata if demonstrated.get(e.key)])} errata.",
        "",
        "## Results",
        "",
        "| Result | Module | Verdict | Errata | Relies on | Methods | Checks |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for p in proofs:
        result = p.result + (f" ({', '.join(p.covers)})" if p.covers else "")
        keys = ", ".join(p.errata) or "-"
        methods = ", ".join(m.value for m in p.methods)
        lines.append(
            f"| {_cell(result)} | `{p.name}` | {p.verdict.value} | {keys} | {_relies(p)} | {methods} "
            f"| {len(p.checks)} |"
        )
    lines += ["", "## Checks", ""]
    for p in proofs:
        lines += [f"### {p.result}: {p.title}", ""]
        verdict = f"**Verdict:** {p.verdict.value}"
        if p.errata:
            verdict += f" ({', '.join(p.errata)})"
        if p.relies_on:
            verdict += f"; relies on {', '.join(p.relies_on)}"
        lines += [verdict + ".", ""]
        if p.not_proven:
            lines += [f"**Not proven here (evidence only):** {p.not_proven}", ""]
        for paragraph in _body_paragraphs(p.doc):
            lines += [paragraph, ""]
        lines += ["| Check | Method | Status |", "| --- | --- | --- |"]
        for c in p.checks:
            status = c.expected_status.value + (f" ({c.erratum})" if c.erratum else "")
            full = " (full profile)" if c.full else ""
            lines.append(f"| `{c.name}`: {_cell(c.title)}{full} | {_cell(c.method_text)} | {status} |")
        lines.append("")
    lines += ["## Errata", ""]
    for e in errata:
        demos = demonstrated.get(e.key, [])
        lines += [
            f"### `{e.key}`: {e.location}",
            "",
            f"- **Printed:** {e.printed}",
            f"- **Corrected:** {e.corrected}",
            f"- **Evidence:** {e.evidence}",
        ]
        if e.confidence:
            lines.append(f"- **Confidence:** {e.confidence}")
        lines.append(f"- **Consequence:** {e.consequence}")
        if demos:
            refs = ", ".join(f"`{p.name}::{c.name}`" for p, c in demos)
            lines.append(f"- **Demonstrated by:** {refs}")
        else:
            lines.append("- **Demonstrated by:** no proof module (see the evidence)")
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def write_report(
    directory: str | Path | None = None,
    *,
    on_check: Callable[[CheckRecord], None] | None = None,
) -> tuple[Path, list[ProofRecord]]:
    """Run every check (the full profile) and write ``REPORT.md`` if all matched.

    Parameters
    ----------
    directory : path, optional
        The proofs directory (default :func:`find_proofs_dir`).
    on_check : callable, optional
        Called with each :class:`CheckRecord` as it completes (progress output).

    Returns
    -------
    (path, records)
        The report's path and the records of every proof.  The file is written
        only when every check ran and matched its expectation (a check skipped for
        a missing optional dependency blocks it); otherwise it is left untouched.

    Raises
    ------
    ProofsNotFoundError
        If the proofs directory is not found.
    QuadricContactError
        If the proofs found are the copy installed with the package: the report
        belongs to a checkout (pass its ``proofs/`` directory).
    """
    path = find_proofs_dir(directory)
    if path.name != "proofs":
        raise QuadricContactError(
            f"the proofs found are the copy installed with the package ({path}); the report is written "
            "into a checkout: pass --proofs-dir with its proofs/ directory",
            str(path),
        )
    proofs = load_proofs(path)
    records = [run_proof(p, profile=Profile.FULL, on_check=on_check) for p in proofs]
    target = path / REPORT_NAME
    if all(c.status in (Status.PASS, Status.DIFFERS) for r in records for c in r.checks):
        target.write_text(render_report(proofs))
    return target, records
