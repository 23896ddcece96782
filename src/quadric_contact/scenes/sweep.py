"""Sweeps: one scene under many perturbations, on one machine or a dask cluster.

A sweep runs a scene ``n`` times, run ``i`` with every ellipsoid's path moved
by small rational offsets drawn from a generator seeded with ``(seed, i)``
(:func:`perturbed`; run ``0`` is the scene itself), and keeps of each run a
small exact summary: for each (ellipsoid, object) the first contact and the
event times as decimals of the exact algebraic numbers (:func:`summarize`).
The summaries depend only on the scene, ``seed``, ``i`` and the amplitude,
so a sweep gives the same results serially, on a ``dask.distributed``
``LocalCluster`` (the default) or on any cluster whose scheduler address is
given (``quadric-contact sweep --scheduler tcp://host:8786``), whatever the
order in which the runs finish.

Only the scene's TOML text travels to the workers; each worker reads it once.
"""

from __future__ import annotations

import hashlib
import random
import re
import statistics
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from fractions import Fraction
from typing import Any

from quadric_contact.exact.bounds import SCHEDULER_TIMEOUT
from quadric_contact.exact.errors import MissingDependencyError, SceneError, SchedulerError
from quadric_contact.scenes.scene_model import MovingEllipsoid, Scene
from quadric_contact.scenes.scene_toml import parse_scene
from quadric_contact.scenes.simulate import simulate
from quadric_contact.scenes.trajectory import Keyframes, Stationary

__all__ = ["SweepResult", "check_scheduler_address", "perturbed", "run_sweep", "summarize"]

_SCENES: dict[str, Scene] = {}


def _scene(text: str, source: str) -> Scene:
    """The scene of a TOML text, read once per process."""
    key = hashlib.sha256(text.encode()).hexdigest()
    if key not in _SCENES:
        _SCENES[key] = parse_scene(text, source)
    return _SCENES[key]


def _offset(rng: random.Random, amplitude: Fraction) -> Fraction:
    steps = 1000
    return amplitude * Fraction(rng.randint(-steps, steps), steps)


def perturbed(scene: Scene, index: int, *, seed: int = 0, amplitude: Fraction = Fraction(1, 20)) -> Scene:
    """The scene with every ellipsoid's path moved by offsets of at most ``amplitude``
    per coordinate (multiples of ``amplitude / 1000``), drawn from ``random.Random``
    seeded with ``(seed, index)``; ``index = 0`` is the scene itself.

    Keyframed paths have each key moved; other motions have the ellipsoid's
    initial place moved (its shape, hence its smallness, is unchanged).

    Examples
    --------
    >>> from quadric_contact.scenes.scene_toml import builtin_scene
    >>> bee = builtin_scene()
    >>> perturbed(bee, 0) is bee
    True
    >>> a, b = perturbed(bee, 7, seed=1), perturbed(bee, 7, seed=1)
    >>> keys = [s.ellipsoids[0].trajectory.keys for s in (a, b, bee)]
    >>> keys[0] == keys[1] != keys[2]
    True
    """
    if index == 0:
        return scene
    rng = random.Random(f"{seed}:{index}")
    ells = []
    for e in scene.ellipsoids:
        traj = e.trajectory
        if isinstance(traj, Keyframes):
            keys = [
                (k.time, tuple(v + _offset(rng, amplitude) for v in k.position), k.rotation)
                for k in traj.keys
            ]
            ells.append(MovingEllipsoid(e.name, e.quadric, Keyframes(keys)))
        else:
            shift = tuple(_offset(rng, amplitude) for _ in range(3))
            moved = e.quadric.translated(shift)
            ells.append(
                MovingEllipsoid(e.name, moved, traj if not isinstance(traj, Stationary) else Stationary())
            )
    return replace(scene, ellipsoids=tuple(ells), smallness=dict(scene.smallness), warnings=[])


def summarize(result: Any, places: int) -> list[dict[str, Any]]:
    """For each (ellipsoid, object) of a run: the first contact (time to ``places``
    decimals, pieces) and, for a complete timeline, the event times."""
    out = []
    for p in result.pairs:
        first = None
        if p.first_contact is not None:
            first = {"time": p.first_contact[0].decimal(places), "pieces": list(p.first_contact[1])}
        out.append(
            {
                "ellipsoid": p.ellipsoid,
                "object": p.object.name,
                "first_contact": first,
                "events": [e.time.decimal(places) for e in p.events] if p.complete else None,
            }
        )
    return out


def _run_chunk(
    text: str,
    source: str,
    indices: Sequence[int],
    seed: int,
    amplitude: Fraction,
    effects: Sequence[str] | None,
    places: int,
) -> list[tuple[int, list[dict[str, Any]]]]:
    base = _scene(text, source)
    out = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for i in indices:
            result = simulate(
                perturbed(base, i, seed=seed, amplitude=amplitude), effects=effects, progress=False
            )
            out.append((i, summarize(result, places)))
    return out


@dataclass
class SweepResult:
    """The runs of a sweep, in order of their index, and how it ran."""

    scene: str
    runs: list[list[dict[str, Any]]]
    seed: int
    amplitude: Fraction
    effects: tuple[str, ...]
    seconds: float
    where: str

    def first_contacts(self, ellipsoid: str, obj: str) -> list[str | None]:
        """The first contact time (decimal) of one pair in every run (None: no contact)."""
        out: list[str | None] = []
        for run in self.runs:
            pair = next(p for p in run if p["ellipsoid"] == ellipsoid and p["object"] == obj)
            out.append(None if pair["first_contact"] is None else pair["first_contact"]["time"])
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "scene": self.scene,
            "runs": len(self.runs),
            "seed": self.seed,
            "amplitude": str(self.amplitude),
            "effects": list(self.effects),
            "where": self.where,
            "seconds": round(self.seconds, 3),
            "results": [{"index": i, "pairs": run} for i, run in enumerate(self.runs)],
        }

    def format_text(self) -> str:
        """A summary: per pair, how many runs touched and the spread of the first contact."""
        lines = [
            f"sweep of {self.scene}: {len(self.runs)} runs (run 0 unperturbed; offsets up to "
            f"{self.amplitude} per coordinate, seed {self.seed}), effects {', '.join(self.effects)}",
            f"ran {where_text(self.where)} in {self.seconds:.1f} s",
        ]
        if not self.runs:
            return "\n".join(lines)
        for p in self.runs[0]:
            firsts = self.first_contacts(p["ellipsoid"], p["object"])
            hit = [float(t) for t in firsts if t is not None]
            line = f"  {p['ellipsoid']} vs {p['object']}: first contact in {len(hit)} of {len(firsts)} runs"
            if hit:
                line += (
                    f"; time min {min(hit):.6f}, median {statistics.median(hit):.6f}, max {max(hit):.6f}"
                    f" (unperturbed: {firsts[0] if firsts[0] is not None else 'none'})"
                )
            lines.append(line)
        return "\n".join(lines)


def where_text(where: str) -> str:
    return "serially" if where == "serial" else f"on {where}"


_ADDRESS = re.compile(
    r"(?:(tcp|tls|ucx|ws|wss)://)?(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9][A-Za-z0-9.-]{0,252}):([0-9]{1,5})"
)


def check_scheduler_address(address: Any) -> str:
    """``address`` if it is a scheduler address dask connects to over the network:
    ``[tcp|tls|ucx|ws|wss://]host:port`` with a port in 1..65535.

    A scheduler is a trust boundary: the sweep sends it tasks and runs what its
    workers send back, so only a cluster one trusts should be named.  Anything
    else (``file://``, ``inproc://``, code, a path) is refused before any
    connection.

    Raises
    ------
    SchedulerError
        Naming the address and what was expected.
    """
    if not isinstance(address, str) or not (m := _ADDRESS.fullmatch(address)) or not 0 < int(m[3]) < 65536:
        raise SchedulerError(
            f"--scheduler: {str(address)[:100]!r} is not a scheduler address: expected "
            "tcp://host:port (or tls://, ucx://, ws://, wss://), a port in 1..65535",
            address,
        )
    return address


def run_sweep(
    text: str,
    source: str = "<scene>",
    runs: int = 10_000,
    *,
    seed: int = 0,
    amplitude: Fraction = Fraction(1, 20),
    effects: Sequence[str] | None = ("first_contact",),
    places: int = 12,
    scheduler: str | None = None,
    client: Any = None,
    serial: bool = False,
    workers: int = 2,
    threads: int = 1,
    processes: bool = True,
    chunk: int | None = None,
    progress: bool | None = None,
) -> SweepResult:
    """Run a scene under ``runs`` perturbations (:func:`perturbed`), serially or on dask.

    Parameters
    ----------
    text, source : str
        The scene's TOML text and where it came from.
    runs : int
        Number of runs (run ``0`` is the unperturbed scene).
    seed : int
    amplitude : Fraction
        Largest offset per coordinate.
    effects : sequence of str, optional
        The effects of every run (default: the first contact only; None: the scene's).
    places : int
        Decimal places of the summarised times.
    scheduler : str, optional
        The address of a ``dask.distributed`` scheduler; without it (and
        without ``client``) a ``LocalCluster`` of ``workers`` workers is started.
    client : dask.distributed.Client, optional
        Use this client.
    serial : bool
        Run here, one after another (the reference the cluster must match).
    workers, threads, processes
        The ``LocalCluster``: workers, threads per worker, worker processes
        (else threads in this process).
    chunk : int, optional
        Runs per task (default: about 8 tasks per worker).
    progress : bool, optional
        A progress bar on stderr (default: on a terminal).

    Returns
    -------
    SweepResult

    Raises
    ------
    SceneError
        A bad scene or argument.
    MissingDependencyError
        A cluster is asked for and dask.distributed is not installed.
    """
    if runs < 1:
        raise SceneError(f"a sweep needs at least one run, got {runs}", runs)
    if amplitude < 0:
        raise SceneError(f"the amplitude must not be negative, got {amplitude}", amplitude)
    base = _scene(text, source)  # read it here first: a bad scene fails before any cluster starts
    eff = tuple(base.effects if effects is None else effects)
    started = time.perf_counter()
    size = chunk or max(1, min(250, runs // (max(1, workers) * 8)))
    chunks = [list(range(k, min(runs, k + size))) for k in range(0, runs, size)]
    results: dict[int, list[dict[str, Any]]] = {}
    bar = _bar(runs, progress)

    def take(out: list[tuple[int, list[dict[str, Any]]]]) -> None:
        for i, summary in out:
            results[i] = summary
        if bar is not None:
            bar.update(len(out))

    try:
        if serial:
            where = "serial"
            for c in chunks:
                take(_run_chunk(text, source, c, seed, amplitude, eff, places))
        else:
            where = _run_on_dask(
                text, source, chunks, seed, amplitude, eff, places, take,
                scheduler=scheduler, client=client, workers=workers, threads=threads, processes=processes,
            )  # fmt: skip
    finally:
        if bar is not None:
            bar.close()
    return SweepResult(
        base.name,
        [results[i] for i in range(runs)],
        seed,
        amplitude,
        eff,
        time.perf_counter() - started,
        where,
    )


def _run_on_dask(
    text: str,
    source: str,
    chunks: list[list[int]],
    seed: int,
    amplitude: Fraction,
    effects: tuple[str, ...],
    places: int,
    take: Callable[[list[tuple[int, list[dict[str, Any]]]]], None],
    *,
    scheduler: str | None,
    client: Any,
    workers: int,
    threads: int,
    processes: bool,
) -> str:
    try:
        from dask.distributed import Client, LocalCluster, as_completed  # dask is optional (the dask extra)
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise MissingDependencyError(
            'a sweep on a cluster needs dask.distributed: pip install ".[dask]" from a checkout '
            "(or run it serially: quadric-contact sweep --serial, run_sweep(..., serial=True))"
        ) from exc
    cluster = None
    own = client is None
    if own:
        if scheduler is None:
            cluster = LocalCluster(
                n_workers=workers, threads_per_worker=threads, processes=processes, dashboard_address=None
            )
            client = Client(cluster)
        else:
            address = check_scheduler_address(scheduler)
            try:
                client = Client(address, timeout=SCHEDULER_TIMEOUT)
            except (OSError, TimeoutError) as exc:
                raise SchedulerError(
                    f"--scheduler {address}: cannot connect within {SCHEDULER_TIMEOUT:g} s "
                    f"(SCHEDULER_TIMEOUT): {exc}",
                    address,
                ) from exc
    where = (
        f"a LocalCluster of {workers} worker(s)"
        if cluster is not None
        else f"the cluster at {client.scheduler.address}"
    )
    try:
        futures = [
            client.submit(_run_chunk, text, source, c, seed, amplitude, effects, places, pure=False)
            for c in chunks
        ]
        for future in as_completed(futures):
            take(future.result())
    finally:
        if own:
            client.close()
        if cluster is not None:
            cluster.close()
    return where


def _bar(total: int, enabled: bool | None) -> Any:
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        return None
    from tqdm import tqdm  # tqdm takes tens of ms to import: only when a progress bar is shown

    return tqdm(total=total, desc="sweep", unit="run", file=sys.stderr)
