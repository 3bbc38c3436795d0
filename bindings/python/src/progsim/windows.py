"""Time-windowed refinement on Dask: the finest level of a progressive animation split into
time windows refined in parallel, each from the coarser level's state at its first frame
(PSQ's safe refinement, PD §4.6's vertical warm start), joined at the seams::

    from progsim.windows import refine_in_windows

    joined = refine_in_windows("scenes/pd_flag.json", windows=4, steps=200)
    joined.positions            # (201, n, 3): the finest level's frames 0..200
    joined.seams                # per seam: its jump and continuity against the interior's

Each window is a task: a worker makes the simulation, previews every step and refines the
levels between (the same on every worker, bit for bit with one OpenMP thread), then refines
the finest level over its window only (:meth:`Simulation.refine_window`). The coarse levels
are cheap next to the finest, so N windows on N workers take about 1/N of its time.

Continuity at a seam s (frames are joined with window k's own frames after s, so that step
s → s + 1 is window k's first step): the seam's ``jump`` is the RMS over vertices of the
distance between window k − 1's last state and window k's first (m), and its
``second_difference`` the RMS of x_{s+1} − 2 x_s + x_{s−1} over vertices (m), the discrete
acceleration h² a, compared with the same at the interior frames (``interior_median``,
``interior_max``) and, when a serial refinement is given, with the serial animation's value
at the same frame.
"""

from __future__ import annotations

import csv
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from ._errors import InvalidArgumentError
from .sweep import RunSpec, _specs, open_run, preview_steps, run_on

__all__ = [
    "WindowResult",
    "WindowedRefinement",
    "refine_in_windows",
    "window_bounds",
    "refine_window_task",
]


@dataclass
class WindowResult:
    """One window of the finest level: frames first..last (positions and velocities)."""

    first: int
    last: int
    positions: np.ndarray  #: (last − first + 1, n, 3), m
    velocities: np.ndarray  #: (last − first + 1, n, 3), m/s
    seconds: float  #: wall time of the window's refinement alone, s
    total_seconds: float  #: wall time of the whole task (preview and coarser levels too), s


def window_bounds(steps: int, windows: int) -> List[Tuple[int, int]]:
    """``windows`` contiguous (first, last) step ranges covering 0..steps, sizes within one."""
    if windows < 1 or windows > steps:
        raise InvalidArgumentError(
            f"windows must be in [1, {steps}] for {steps} steps, got {windows}"
        )
    cuts = [round(k * steps / windows) for k in range(windows + 1)]
    return list(zip(cuts[:-1], cuts[1:]))


def refine_window_task(spec: RunSpec, first: int, last: int) -> WindowResult:
    """A Dask task: the run's preview, its levels up to the finest's coarser one, then the
    finest level over steps first..last."""
    start = time.perf_counter()
    with open_run(spec) as sim:
        sim.step_preview(preview_steps(sim, spec.steps))
        for _ in range(sim.num_levels - 2):
            sim.refine()
        window_start = time.perf_counter()
        sim.refine_window(first, last)
        seconds = time.perf_counter() - window_start
        finest = sim.num_levels - 1
        frames = list(sim.frames(finest))
    positions = np.stack([frame.positions for frame in frames])
    velocities = np.stack([frame.velocities for frame in frames])
    return WindowResult(first, last, positions, velocities, seconds, time.perf_counter() - start)


def _rms(difference: np.ndarray) -> float:
    """RMS over vertices of the per-vertex distance in an (n, 3) array."""
    return float(np.sqrt(np.mean(np.sum(difference * difference, axis=1))))


def second_differences(positions: np.ndarray) -> np.ndarray:
    """RMS of x_{k+1} − 2 x_k + x_{k−1} for k = 1 … frames − 2 (index k − 1 holds frame k)."""
    return np.array(
        [
            _rms(positions[k + 1] - 2 * positions[k] + positions[k - 1])
            for k in range(1, len(positions) - 1)
        ]
    )


class WindowedRefinement:
    """The joined finest level of :func:`refine_in_windows` and its seams."""

    def __init__(self, windows: List[WindowResult], serial: Optional[np.ndarray] = None):
        self.windows = sorted(windows, key=lambda w: w.first)
        parts = [self.windows[0].positions] + [w.positions[1:] for w in self.windows[1:]]
        #: (steps + 1, n, 3): window k's frames after its first, joined
        self.positions = np.concatenate(parts)
        self.serial = serial
        self.seams = self._seams()

    def _seams(self) -> List[Dict[str, float]]:
        """One dict per seam (see the module's "Continuity")."""
        accel = second_differences(self.positions)
        seam_frames = [w.first for w in self.windows[1:]]
        interior = np.delete(accel, [s - 1 for s in seam_frames]) if len(accel) else accel
        serial_accel = second_differences(self.serial) if self.serial is not None else None
        seams = []
        for before, after in zip(self.windows, self.windows[1:]):
            s = after.first
            seam = {
                "frame": s,
                "jump": _rms(after.positions[0] - before.positions[-1]),
                "second_difference": float(accel[s - 1]),
                "interior_median": (float(np.median(interior)) if len(interior) else float("nan")),
                "interior_max": (float(np.max(interior)) if len(interior) else float("nan")),
            }
            if serial_accel is not None:
                seam["serial_second_difference"] = float(serial_accel[s - 1])
                seam["distance_to_serial"] = _rms(self.positions[s + 1] - self.serial[s + 1])
            seams.append(seam)
        return seams

    def write_csv(self, path: Union[str, Path]) -> None:
        """Writes the seams (one row each) as CSV."""
        names = list(self.seams[0]) if self.seams else ["frame"]
        with open(path, "w", newline="", encoding="utf-8") as out:
            writer = csv.DictWriter(out, fieldnames=names)
            writer.writeheader()
            writer.writerows(self.seams)


def refine_in_windows(
    scene: Union[str, Path, Mapping[str, Any]],
    windows: int,
    client: Any = None,
    *,
    values: Optional[Mapping[str, Any]] = None,
    steps: Optional[int] = None,
    workers: Optional[int] = None,
    base_dir: Optional[Union[str, Path]] = None,
    compare_serial: bool = False,
) -> WindowedRefinement:
    """Refines the finest level of ``scene`` (with sweep-style ``values``, e.g. a run of a
    sweep) in ``windows`` time windows on Dask, and joins them.

    Args:
        scene: a scene file's path, its JSON text or a dict; its hierarchy needs two levels
            or more.
        windows: how many windows (tasks).
        client: None for a local cluster made for this call, a ``distributed.Client``, a
            scheduler address or ``"serial"`` (this process, one window after the other).
        values: parameters as in :func:`progsim.sweep.sweep` (one value each).
        steps: preview steps (default: the scene's duration over its time step).
        workers: the local cluster's worker processes (default: one per core).
        base_dir: folder of the scene's relative mesh paths (as for sweeps).
        compare_serial: also refine serially here, for the seams' serial columns.
    """
    spec = _specs(scene, [dict(values or {})], steps, base_dir)[0]
    with open_run(spec) as sim:
        total = preview_steps(sim, spec.steps)
        if sim.num_levels < 2:
            raise InvalidArgumentError(
                "windowed refinement needs a hierarchy of two levels or more"
            )
    spec = RunSpec(spec.index, spec.scene, spec.base_dir, spec.values, total)
    bounds = window_bounds(total, windows)
    if client == "serial":
        results = [refine_window_task(spec, first, last) for first, last in bounds]
    else:
        results = run_on(client, workers, lambda dask: _gather(dask, spec, bounds))
    # A window of the whole span is the serial refinement, bit for bit.
    serial = refine_window_task(spec, 0, total).positions if compare_serial else None
    return WindowedRefinement(results, serial)


def _gather(client: Any, spec: RunSpec, bounds: Sequence[Tuple[int, int]]) -> List[WindowResult]:
    """One task per window, gathered."""
    futures = [
        client.submit(refine_window_task, spec, first, last, pure=False, retries=2)
        for first, last in bounds
    ]
    return client.gather(futures)
