"""What accuracy costs in time (``ps_accuracy``): a scene solved progressively and directly on
every level of its hierarchy, each result compared with the converged finest one."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import List, Optional, Sequence, Union

from ._native import (
    NativeObject,
    ProgressArg,
    ProgressRun,
    check_create,
    index_buffer,
    real_value,
)
from ._progsim_cffi import ffi, lib

__all__ = ["AccuracyRow", "Accuracy"]

PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]


@dataclass(frozen=True)
class AccuracyRow:
    """One level's result (``ps_accuracy_row``), as ``progsim accuracy`` writes it."""

    method: str  #: ``"progressive"`` (preview, refinement; PSQ) or ``"direct"``
    level: int  #: 0 = coarsest
    vertices: int  #: of the level's mesh
    newton_iterations: int  #: on the level
    #: s; progressive: from the start until this level's equilibrium, coarser levels and
    #: refinements included; direct: the level's own solve over the load script
    seconds: float
    refine_seconds: float  #: s, building the level's start from the coarser level
    error_rms: float  #: RMS distance to the converged finest result / bbox diagonal
    error_max: float  #: max distance to the converged finest result / bbox diagonal
    intersecting_pairs: int  #: face pairs crossing in the final state (CGAL exact check)
    #: the level ended at equilibrium, progressive or direct
    converged: bool
    #: load steps of the scene's script solved (fewer in a direct solve stopped early)
    load_steps: int
    #: False for a direct solve stopped by ``direct_time_ratio``: its ``seconds`` (and any
    #: speed-up against it) is then only a lower bound
    finished: bool


class Accuracy(NativeObject):
    """Runs a scene file (with a ``"progressive"`` section) progressively and directly on every
    level; :attr:`rows` holds the results, :meth:`write` the CSV, Markdown and PNG report.

    Example::

        with progsim.Accuracy("scenes/psq_plate_buckling.json", progress=True) as report:
            for row in report.rows:
                print(row.method, row.level, row.seconds, row.error_max)
            report.write("results/plate")
    """

    _last_error_fn = staticmethod(lambda handle: lib.ps_last_error())

    def __init__(
        self,
        scene_path: PathLike,
        *,
        direct_levels: Optional[Sequence[int]] = None,
        direct_time_ratio: float = 0.0,
        direct_time_of_preview: bool = False,
        progress: ProgressArg = False,
    ) -> None:
        """Runs the scene (long: ``progress=True`` shows a bar per phase and load step).

        Args:
            scene_path: a scene file with a ``"progressive"`` section.
            direct_levels: the levels solved directly, in this order (default: every level).
            direct_time_ratio: stop each direct solve within the Newton iteration that takes
                it past this many times the progressive time to the converged finest level
                (its row then has ``finished=False``); 0 (default) for no limit.
            direct_time_of_preview: the ratio multiplies the coarse preview's time instead, so
                that a run capped at R stops as soon as it shows the preview at least R times
                faster than the direct solve.
            progress: ``True`` for a tqdm bar, ``False`` for none, or a callable
                ``(done, total, phase) -> bool`` returning True to cancel.

        Raises:
            ProgsimIOError: the file cannot be read.
            InvalidSceneError: a malformed scene, or one without coarse levels.
            UnsupportedError: a dynamic scene.
            InvalidArgumentError: a direct level that does not exist, a negative time ratio.
            CancelledError: the progress callable asked to stop.
        """
        super().__init__()
        run = ProgressRun(progress)
        definition = ffi.new("ps_accuracy_def*")
        lib.ps_accuracy_def_init(definition)
        levels, buffer = index_buffer(direct_levels, "direct_levels")
        definition.direct_levels = buffer
        definition.num_direct_levels = int(levels.size)
        definition.direct_time_ratio = real_value(direct_time_ratio, "direct_time_ratio")
        definition.direct_time_base = (
            lib.PS_TIME_BASE_PREVIEW if direct_time_of_preview else lib.PS_TIME_BASE_PIPELINE
        )
        run.install(definition)
        out = ffi.new("ps_accuracy**")
        try:
            status = lib.ps_accuracy_run_scene_file(os.fsencode(scene_path), definition, out)
        finally:
            run.close()
        del levels, buffer
        run.reraise()
        check_create(status)
        self._cdata = ffi.gc(out[0], lib.ps_accuracy_destroy)
        self.rows: List[AccuracyRow] = [self._row(k) for k in range(self._num_rows())]
        limit = ffi.new("double*")
        self._call(lib.ps_accuracy_direct_time_limit, limit)
        #: The direct solves' time limit in seconds (the ratio times its base's time in this
        #: run); 0 without a limit.
        self.direct_time_limit: float = float(limit[0])

    def _num_rows(self) -> int:
        count = ffi.new("int32_t*")
        self._call(lib.ps_accuracy_num_rows, count)
        return int(count[0])

    def _row(self, index: int) -> AccuracyRow:
        row = ffi.new("ps_accuracy_row*")
        self._call(lib.ps_accuracy_get_row, index, row)
        return AccuracyRow(
            method="progressive" if row.method == lib.PS_METHOD_PROGRESSIVE else "direct",
            level=int(row.level),
            vertices=int(row.vertices),
            newton_iterations=int(row.newton_iterations),
            seconds=float(row.seconds),
            refine_seconds=float(row.refine_seconds),
            error_rms=float(row.error_rms),
            error_max=float(row.error_max),
            intersecting_pairs=int(row.intersecting_pairs),
            converged=bool(row.converged),
            load_steps=int(row.load_steps),
            finished=bool(row.finished),
        )

    def write(self, directory: PathLike) -> None:
        """Writes ``accuracy.csv``, ``accuracy.md``, ``error_vs_time.png``,
        ``error_by_level.png`` and ``time_by_level.png`` into ``directory`` (created).

        Raises:
            ProgsimIOError: a file cannot be written.
        """
        self._call(lib.ps_accuracy_write, os.fsencode(directory))

    def __repr__(self) -> str:
        return f"<progsim.Accuracy {len(self.rows)} rows>"
