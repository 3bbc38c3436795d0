"""Design sweeps: one coarse preview of a scene per parameter combination, run on Dask.

A designer explores many previews (PD++'s "five-hat trick"), keeps one and refines it::

    import progsim
    from progsim.sweep import Range, sweep

    runs = sweep("scenes/pd_flag.json",
                 {"material.youngs_modulus": Range(5e5, 2e6, 4),
                  "scene.wind.drag": [0.8, 1.2]})
    runs.write("results/flag_sweep")        # runs.csv and contact_sheet.png
    with runs.refine(3) as sim:             # the chosen run, level by level
        sim.write_mesh(None, "flag_final.obj")

Each run is a task of ``dask.distributed``: with ``client=None`` a ``LocalCluster`` of one
single-threaded worker process per core is started and closed again; pass a ``Client`` or a
scheduler address for a real cluster (the scene's mesh files must then be readable at the
same path on every worker), or ``client="serial"`` to run in this process without Dask.

Parameter names (the keys of ``parameters``):

* a name of :data:`progsim.PARAMETERS` (``material.youngs_modulus``, ``gravity.z``, ...) or of
  :data:`progsim.CHOICES`: set on the simulation before the first step;
* ``initial_velocity``: a 3-vector given to every preview vertex;
* ``handle.<i>.keyframes``: a dict of :meth:`Simulation.set_handle_keyframes` arguments;
* ``scene.<dotted path>``: any member of the scene file (``scene.wind.velocity``,
  ``scene.bodies.0.material.thickness``), replaced before the simulation is made.

Threads: the library releases the GIL inside its calls (cffi does so around every C call),
so threads of one process can step different simulations at once; one simulation is used by
one thread at a time (its calls hold a lock). OpenMP inside each call uses
``OMP_NUM_THREADS`` threads: the local cluster starts its workers with one, so that runs on
different cores do not compete and give the same bits as a serial run with one thread.
"""

from __future__ import annotations

import csv
import itertools
import json
import os
import pickle
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import (
    Any,
    Callable,
    Dict,
    Iterable,
    List,
    Mapping,
    Optional,
    Sequence,
    TypeVar,
    Union,
)

import numpy as np
from tqdm.auto import tqdm

from ._errors import InvalidArgumentError, ProgsimError
from .scene_text import load_scene, override
from .simulation import CHOICES, PARAMETERS, Simulation

T = TypeVar("T")

__all__ = [
    "Range",
    "RunSpec",
    "RunResult",
    "Sweep",
    "grid",
    "sampled",
    "run_preview",
    "sweep",
]

#: Environment of the local cluster's worker processes (see the module's "Threads").
WORKER_ENV = {"OMP_NUM_THREADS": "1", "OMP_WAIT_POLICY": "passive"}

#: Outcome columns of :meth:`Sweep.rows`, after ``index`` and the parameters.
OUTCOME_COLUMNS = (
    "status",
    "error",
    "steps",
    "simulated_time",
    "center_of_mass_x",
    "center_of_mass_y",
    "center_of_mass_z",
    "kinetic_energy",
    "newton_iterations",
    "converged_steps",
    "seconds",
    "bytes_in",
    "bytes_out",
)


@dataclass(frozen=True)
class Range:
    """``num`` evenly spaced values from ``start`` to ``stop`` (both included) in a grid;
    uniform samples between them in :func:`sampled`."""

    start: float
    stop: float
    num: int

    def values(self) -> List[float]:
        """The grid values."""
        if self.num < 1:
            raise InvalidArgumentError(f"a Range needs num >= 1, got {self.num}")
        return [float(v) for v in np.linspace(self.start, self.stop, self.num)]


ParameterSpace = Mapping[str, Union[Range, Sequence[Any]]]


def _choices(name: str, values: Union[Range, Sequence[Any]]) -> List[Any]:
    """The values of one parameter's axis."""
    listed = values.values() if isinstance(values, Range) else list(values)
    if not listed:
        raise InvalidArgumentError(f"sweep parameter {name} has no values")
    return listed


def grid(parameters: ParameterSpace) -> List[Dict[str, Any]]:
    """Every combination of the parameters' values (the last name varies fastest)."""
    names = list(parameters)
    axes = [_choices(name, parameters[name]) for name in names]
    return [dict(zip(names, combination)) for combination in itertools.product(*axes)]


def sampled(parameters: ParameterSpace, samples: int, seed: int = 0) -> List[Dict[str, Any]]:
    """``samples`` combinations drawn at random (numpy's PCG64 seeded by ``seed``): a Range
    uniformly between its ends, a list by picking one of its values."""
    if samples < 1:
        raise InvalidArgumentError(f"samples must be >= 1, got {samples}")
    rng = np.random.default_rng(seed)
    runs = []
    for _ in range(samples):
        run = {}
        for name, values in parameters.items():
            if isinstance(values, Range):
                run[name] = float(rng.uniform(values.start, values.stop))
            else:
                listed = _choices(name, values)
                run[name] = listed[int(rng.integers(len(listed)))]
        runs.append(run)
    return runs


@dataclass(frozen=True)
class RunSpec:
    """Everything a worker needs for one run: small and picklable."""

    index: int
    scene: Dict[str, Any]
    base_dir: str
    values: Dict[str, Any]
    steps: Optional[int] = None


@dataclass
class RunResult:
    """One run's outcome; ``positions`` is its last preview frame (None after an error)."""

    index: int
    values: Dict[str, Any]
    status: str = "PS_OK"
    error: str = ""
    outcome: Dict[str, float] = field(default_factory=dict)
    positions: Optional[np.ndarray] = None
    faces: Optional[np.ndarray] = None


def _check_name(name: str) -> None:
    """Raises InvalidArgumentError for a name no rule of the module's list accepts."""
    if name in PARAMETERS or name in CHOICES or name == "initial_velocity":
        return
    if name.startswith("scene.") and len(name) > len("scene."):
        return
    parts = name.split(".")
    if len(parts) == 3 and parts[0] == "handle" and parts[1].isdigit() and parts[2] == "keyframes":
        return
    raise InvalidArgumentError(
        f"unknown sweep parameter {name!r}: use a progsim.PARAMETERS or progsim.CHOICES name, "
        "initial_velocity, handle.<i>.keyframes or scene.<path>"
    )


def _scene_of(spec: RunSpec) -> Dict[str, Any]:
    """The spec's scene with its ``scene.`` overrides applied."""
    scene = spec.scene
    for name, value in spec.values.items():
        if name.startswith("scene."):
            scene = override(scene, name[len("scene.") :], value)
    return scene


def _apply(sim: Simulation, name: str, value: Any) -> None:
    """Sets one non-scene parameter on a simulation that has not stepped yet."""
    if name in PARAMETERS:
        sim.set_param(name, value)
    elif name in CHOICES:
        sim.set_choice(name, value)
    elif name == "initial_velocity":
        count = sim.hierarchy.level_size(0)[0]
        sim.set_preview_velocities(np.tile(np.asarray(value, dtype=float), (count, 1)))
    elif name.startswith("handle."):
        sim.set_handle_keyframes(int(name.split(".")[1]), **value)


def open_run(spec: RunSpec) -> Simulation:
    """The run's simulation, made from its scene and set up, before its first step."""
    sim = Simulation.from_scene(json.dumps(_scene_of(spec)), spec.base_dir)
    try:
        for name, value in spec.values.items():
            if not name.startswith("scene."):
                _apply(sim, name, value)
    except BaseException:
        sim.close()
        raise
    return sim


def preview_steps(sim: Simulation, steps: Optional[int]) -> int:
    """``steps``, else the scene's duration over its time step (at least one)."""
    if steps is not None:
        return int(steps)
    duration = sim.get_param("simulation.duration")
    return max(1, int(round(duration / sim.get_param("simulation.time_step"))))


def _outcome(sim: Simulation, steps: int, seconds: float) -> Dict[str, float]:
    """The outcome metrics of a finished preview: an animation's from its last step record,
    a PSQ or direct run's from its level statistics."""
    if sim.kind in ("progressive_dynamics", "volumetric_dynamics"):
        last, work = sim.step_stats(0)[-1], sim.dynamic_level_stats(0)
        com, kinetic, simulated = (
            last["center_of_mass"],
            float(last["kinetic_energy"]),
            last["time"],
        )
    else:
        work = sim.level_stats(0)
        com, kinetic = sim.positions(0).mean(axis=0), float("nan")
        simulated = work.simulated_time
    return {
        "steps": steps,
        "simulated_time": float(simulated),
        "center_of_mass_x": float(com[0]),
        "center_of_mass_y": float(com[1]),
        "center_of_mass_z": float(com[2]),
        "kinetic_energy": kinetic,
        "newton_iterations": work.newton_iterations,
        "converged_steps": work.converged_steps,
        "seconds": seconds,
    }


def run_preview(spec: RunSpec) -> RunResult:
    """Runs one preview (a Dask task). A progsim error (bad parameter, non-finite state)
    becomes the result's ``status`` and ``error``, so the other runs go on."""
    result = RunResult(spec.index, spec.values)
    start = time.perf_counter()
    try:
        with open_run(spec) as sim:
            steps = preview_steps(sim, spec.steps)
            sim.step_preview(steps)
            result.outcome = _outcome(sim, steps, time.perf_counter() - start)
            result.positions = sim.positions(0)
            result.faces = sim.hierarchy.faces(0)
    except ProgsimError as error:
        result.status, result.error = error.status or "PS_ERROR_INTERNAL", str(error)
    return result


def _cell(value: Any) -> Any:
    """A CSV cell: numbers as they are, anything else as compact JSON."""
    if isinstance(value, (int, float, str)):
        return value
    return json.dumps(np.asarray(value).tolist() if isinstance(value, np.ndarray) else value)


class Sweep:
    """The runs of :func:`sweep`, in the order of their parameter combinations."""

    def __init__(self, specs: List[RunSpec], results: List[RunResult]):
        self.specs = specs
        self.results = sorted(results, key=lambda result: result.index)
        self._bytes_in = [len(pickle.dumps(spec)) for spec in specs]

    def __len__(self) -> int:
        return len(self.results)

    def rows(self) -> List[Dict[str, Any]]:
        """One dict per run: ``index``, the parameters, then :data:`OUTCOME_COLUMNS`."""
        rows = []
        for result in self.results:
            row: Dict[str, Any] = {"index": result.index}
            row.update({name: _cell(value) for name, value in result.values.items()})
            row.update({"status": result.status, "error": result.error})
            row.update(result.outcome)
            row["bytes_in"] = self._bytes_in[result.index]
            row["bytes_out"] = len(pickle.dumps(result))
            rows.append({name: row.get(name, "") for name in self.columns()})
        return rows

    def columns(self) -> List[str]:
        """The table's column names."""
        names = list(self.specs[0].values) if self.specs else []
        return ["index"] + names + list(OUTCOME_COLUMNS)

    def write_csv(self, path: Union[str, Path]) -> None:
        """Writes :meth:`rows` as CSV (a header line, then one line per run)."""
        with open(path, "w", newline="", encoding="utf-8") as out:
            writer = csv.DictWriter(out, fieldnames=self.columns())
            writer.writeheader()
            writer.writerows(self.rows())

    def contact_sheet(self, path: Union[str, Path], columns: int = 4) -> None:
        """Draws every run's last preview frame (matplotlib, PNG), titled by its index and
        parameters; failed runs show their status."""
        from .contact_sheet import draw_contact_sheet

        draw_contact_sheet(self.results, path, columns)

    def write(self, directory: Union[str, Path]) -> Path:
        """Writes ``runs.csv`` and ``contact_sheet.png`` into ``directory`` (made if needed)."""
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        self.write_csv(directory / "runs.csv")
        self.contact_sheet(directory / "contact_sheet.png")
        return directory

    def refine(self, index: int, levels: Optional[int] = None, progress: Any = False) -> Simulation:
        """Runs run ``index`` again here (the same preview, bit for bit with one OpenMP
        thread) and refines it level by level, ``levels`` times (default: to the finest).
        The caller owns the returned simulation (``with`` or ``close()``)."""
        if not 0 <= index < len(self.specs):
            raise InvalidArgumentError(f"no run {index}: the sweep has {len(self.specs)}")
        spec = self.specs[index]
        sim = open_run(spec)
        try:
            sim.step_preview(preview_steps(sim, spec.steps), progress=progress)
            remaining = sim.num_levels - 1 if levels is None else int(levels)
            for _ in range(remaining):
                sim.refine(progress=progress)
        except BaseException:
            sim.close()
            raise
        return sim


def _specs(
    scene: Union[str, Path, Mapping[str, Any]],
    runs: Iterable[Dict[str, Any]],
    steps: Optional[int],
    base_dir: Optional[Union[str, Path]],
) -> List[RunSpec]:
    """The runs' specs; a scene path gives the base folder of its relative mesh paths."""
    # A string holding a JSON object's brace is the scene's text, any other a file's path.
    is_path = isinstance(scene, Path) or (isinstance(scene, str) and "{" not in scene)
    if is_path:
        scene = Path(scene)
        base_dir = base_dir or scene.resolve().parent
    loaded = load_scene(scene)
    folder = str(Path(base_dir or os.getcwd()).resolve())
    specs = [RunSpec(i, loaded, folder, values, steps) for i, values in enumerate(runs)]
    for name in specs[0].values if specs else ():
        _check_name(name)
    return specs


def _run_on_dask(
    specs: List[RunSpec], client: Any, retries: int, progress: bool
) -> List[RunResult]:
    """Submits one task per spec and gathers them as they finish (a tqdm bar if asked)."""
    from distributed import as_completed

    futures = [
        client.submit(
            run_preview,
            spec,
            key=f"progsim-run-{spec.index}-{id(specs)}",
            retries=retries,
            pure=False,
        )
        for spec in specs
    ]
    bar = _bar(len(specs), progress)
    results = []
    for future in as_completed(futures):
        results.append(future.result())
        bar.update(1)
    bar.close()
    return results


def _bar(total: int, progress: bool) -> tqdm:
    """A tqdm bar counting finished runs; drawn only when ``progress`` is true."""
    return tqdm(total=total, desc="sweep", unit="run", disable=not progress)


def run_on(client: Any, workers: Optional[int], work: Callable[[Any], T]) -> T:
    """``work(dask_client)`` on ``client``: a ``distributed.Client`` as given, a scheduler
    address connected for the call, or None: a :func:`local_client` made and closed for it."""
    if client is not None and not isinstance(client, str):
        return work(client)
    from distributed import Client

    with local_client(workers) if client is None else Client(client) as own:
        try:
            return work(own)
        finally:
            if client is None:
                own.cluster.close()


def local_client(workers: Optional[int] = None):
    """A ``Client`` of a new ``LocalCluster``: ``workers`` single-threaded worker processes
    (default: one per core) with :data:`WORKER_ENV`. Close it (and its cluster) when done.
    """
    from distributed import Client, LocalCluster

    cluster = LocalCluster(
        n_workers=workers or os.cpu_count() or 1,
        threads_per_worker=1,
        processes=True,
        env=WORKER_ENV,
        dashboard_address=None,
    )
    return Client(cluster)


def sweep(
    scene: Union[str, Path, Mapping[str, Any]],
    parameters: ParameterSpace,
    client: Any = None,
    *,
    samples: Optional[int] = None,
    seed: int = 0,
    steps: Optional[int] = None,
    retries: int = 2,
    workers: Optional[int] = None,
    base_dir: Optional[Union[str, Path]] = None,
    progress: bool = True,
) -> Sweep:
    """Runs one preview of ``scene`` per combination of ``parameters``.

    Args:
        scene: a scene file's path, its JSON text (comments allowed) or a dict.
        parameters: name → a list of values or a :class:`Range` (names: the module's list).
        client: None for a local cluster made for this sweep, a ``distributed.Client``, a
            scheduler address (``"tcp://host:8786"``) or ``"serial"`` (this process, no Dask).
        samples: draw this many combinations at random (:func:`sampled`) instead of the grid.
        seed: the random draws' seed.
        steps: preview steps per run (default: the scene's duration over its time step).
        retries: times a task that raised is tried again (a worker that dies is replaced by
            the scheduler without counting).
        workers: the local cluster's worker processes (default: one per core).
        base_dir: folder of the scene's relative mesh paths (default: the scene file's folder,
            or the current one for text and dicts).
        progress: a tqdm bar counting finished runs.

    Raises:
        InvalidArgumentError: an unknown parameter name or an empty list of values.
        InvalidSceneError: the scene is not JSON.
    """
    runs = sampled(parameters, samples, seed) if samples is not None else grid(parameters)
    specs = _specs(scene, runs, steps, base_dir)
    if client == "serial":
        bar = _bar(len(specs), progress)
        results = []
        for spec in specs:
            results.append(run_preview(spec))
            bar.update(1)
        bar.close()
        return Sweep(specs, results)
    return Sweep(
        specs,
        run_on(client, workers, lambda dask: _run_on_dask(specs, dask, retries, progress)),
    )
