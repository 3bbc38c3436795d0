"""Mesh hierarchies (``ps_hierarchy``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Optional, Sequence, Tuple, Union

import numpy as np

from ._native import (
    NativeObject,
    ProgressArg,
    ProgressRun,
    as_faces,
    as_vertices,
    check_create,
    int32_value,
    fetch_rows,
    index_buffer,
    output_array,
    real_value,
)
from ._progsim_cffi import ffi, lib

if TYPE_CHECKING:  # pragma: no cover
    from .simulation import Simulation

__all__ = ["Hierarchy"]

PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]


def _hierarchy_def(
    coarse_vertex_counts: Optional[Sequence[int]],
    pinned: Optional[Sequence[int]],
    contact_offset: float,
    run: ProgressRun,
):
    """A filled ``ps_hierarchy_def*`` with the progress trampoline installed, and the buffers
    it borrows (keep them alive during the call)."""
    definition = ffi.new("ps_hierarchy_def*")
    lib.ps_hierarchy_def_init(definition)
    counts, buffer = index_buffer(coarse_vertex_counts, "coarse_vertex_counts")
    definition.coarse_vertex_counts = buffer
    definition.num_coarse_levels = int(counts.size)
    pins, pin_buffer = index_buffer(pinned, "pinned")
    definition.pinned_vertices = pin_buffer
    definition.num_pinned_vertices = int(pins.size)
    definition.contact_offset = real_value(contact_offset, "contact_offset")
    run.install(definition)
    return definition, (counts, buffer, pins, pin_buffer)


def _create(
    function, coarse_vertex_counts, pinned, contact_offset, progress: ProgressArg, *args: Any
) -> "ffi.CData":
    """Runs a ps_hierarchy_create* call with a def and progress reporting; returns the handle."""
    run = ProgressRun(progress)
    definition, keep = _hierarchy_def(coarse_vertex_counts, pinned, contact_offset, run)
    out = ffi.new("ps_hierarchy**")
    try:
        status = function(definition, *args, out)
    finally:
        run.close()
    del keep
    run.reraise()
    check_create(status)
    return out[0]


class Hierarchy(NativeObject):
    """A mesh hierarchy: level 0 is the coarsest, level ``num_levels - 1`` the input mesh.

    Build one from arrays (``Hierarchy(vertices, faces)``) or from a file
    (:meth:`from_file`), or load a saved one (:meth:`load`). With ``coarse_vertex_counts``
    the mesh is decimated into coarser levels (quadric edge collapse with probabilistic
    quadrics, PSQ §4.1), each with the shell prolongation to the finest level (:meth:`prolong`,
    PSQ eq. 9) and its parallel expansion batches (PSQ §4.4.4).

    Level arguments accept negative values counted from the finest level (``-1`` is the
    finest), like Python sequence indices.

    A hierarchy is a context manager; :meth:`close` releases it. Simulations created on it
    keep the native hierarchy alive: closing the Python object while they run only frees it
    once the last of them is closed or collected.
    """

    _last_error_fn = staticmethod(lib.ps_hierarchy_last_error)

    def __init__(
        self,
        vertices: Any,
        faces: Any,
        *,
        coarse_vertex_counts: Optional[Sequence[int]] = None,
        pinned: Optional[Sequence[int]] = None,
        contact_offset: float = 0.0,
        progress: ProgressArg = False,
    ) -> None:
        """Builds a hierarchy from a triangle mesh, validating it first.

        Args:
            vertices: (n, 3) positions in metres; converted to C-contiguous float64
                (no copy if it already is).
            faces: (m, 3) vertex indices, counter-clockwise seen from the front; converted to
                C-contiguous int32 (no copy if it already is).
            coarse_vertex_counts: vertex counts of the coarser levels (distinct, each at least
                4 and below n); ``None`` or empty: a single level, the mesh itself.
            pinned: vertices a simulation will pin (``Simulation(pinned=...)``): kept on every
                level at their rest positions. A progressive simulation's pins must be these.
            contact_offset: m, >= 0; default 0. Coarse levels never cross themselves; with
                the offset ξ a contact simulation will use (half the shell thickness), no
                collapse also brings a vertex and a face, or two edges, within 2ξ.
            progress: ``True`` for a tqdm bar over the decimation, ``False`` for none, or a
                callable ``(done, total, phase) -> bool`` (percent; return True to cancel).

        Raises:
            InvalidMeshError: NaN/Inf coordinates, out-of-range indices, degenerate faces,
                non-manifold edges or unreferenced vertices; the message names the first
                offender (e.g. ``vertex 4``); or a surface that cannot be decimated that far.
            InvalidArgumentError: arrays of the wrong shape or dtype, bad vertex counts.
            CancelledError: the progress callable asked to stop.
        """
        self._init_native()
        vertex_array = as_vertices(vertices)
        face_array = as_faces(faces)
        self._adopt(
            _create(
                lib.ps_hierarchy_create,
                coarse_vertex_counts,
                pinned,
                contact_offset,
                progress,
                ffi.from_buffer("double[]", vertex_array),
                vertex_array.shape[0],
                ffi.from_buffer("int32_t[]", face_array),
                face_array.shape[0],
            )
        )

    @classmethod
    def from_file(
        cls,
        path: PathLike,
        *,
        coarse_vertex_counts: Optional[Sequence[int]] = None,
        pinned: Optional[Sequence[int]] = None,
        contact_offset: float = 0.0,
        progress: ProgressArg = False,
    ) -> "Hierarchy":
        """Builds a hierarchy from an OBJ, OFF or PLY triangle mesh file (positions in metres),
        with the same options as :class:`Hierarchy`.

        Raises:
            ProgsimIOError: the file cannot be read.
            InvalidMeshError: the mesh fails validation (see :class:`Hierarchy`).
        """
        self = cls.__new__(cls)
        self._init_native()
        self._adopt(
            _create(
                lib.ps_hierarchy_create_from_file,
                coarse_vertex_counts,
                pinned,
                contact_offset,
                progress,
                os.fsencode(path),
            )
        )
        return self

    @classmethod
    def load(cls, path: PathLike) -> "Hierarchy":
        """Loads a hierarchy written by :meth:`save` or ``progsim hierarchy``.

        Raises:
            ProgsimIOError: missing, truncated or foreign file.
            InvalidArgumentError: a file whose contents are inconsistent.
        """
        self = cls.__new__(cls)
        self._init_native()
        out = ffi.new("ps_hierarchy**")
        check_create(lib.ps_hierarchy_load(os.fsencode(path), out))
        self._adopt(out[0])
        return self

    def save(self, path: PathLike) -> None:
        """Writes the hierarchy to ``path`` so that decimation is paid once.

        Raises:
            ProgsimIOError: the file cannot be written.
        """
        self._call(lib.ps_hierarchy_save, os.fsencode(path))

    @classmethod
    def _borrowed(cls, pointer: "ffi.CData", owner: "Simulation") -> "Hierarchy":
        """A view of a hierarchy owned by simulation ``owner`` (valid while it is open)."""
        self = cls.__new__(cls)
        self._init_native()
        self._cdata = pointer
        self._owner = owner
        # The native hierarchy's error slot is shared by every view: serialise them all
        # with the simulation's calls.
        self._lock = owner._lock
        return self

    def _init_native(self) -> None:
        NativeObject.__init__(self)
        self._owner: Optional["Simulation"] = None  # set for views of a simulation's hierarchy
        # One entry per live simulation on this hierarchy (list.append/pop are atomic, and
        # the simulations' destructors pop from any thread, without taking a lock).
        self._borrowers: list = []

    def _adopt(self, pointer: "ffi.CData") -> None:
        self._cdata = ffi.gc(pointer, lib.ps_hierarchy_destroy)

    def _owner_open(self) -> bool:
        return self._owner is None or not self._owner.closed

    def _release(self, cdata: "ffi.CData") -> None:
        if self._owner is not None:
            self._owner = None  # a view: the simulation frees it
        elif not self._borrowers:
            ffi.release(cdata)
        # else: the simulations' destructors hold the last references; the native hierarchy
        # is destroyed after the last of them.

    # -- queries -------------------------------------------------------------------------

    @property
    def num_levels(self) -> int:
        """Number of levels (>= 1)."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_hierarchy_num_levels, out)
        return int(out[0])

    def _level(self, level: Optional[int]) -> int:
        """``level`` as a level index: None → the finest, negative → counted from the finest."""
        if level is None:
            return self.num_levels - 1
        level = int32_value(level, "level")
        if level < 0:
            counted = self.num_levels + level
            return counted if counted >= 0 else level
        return level

    def level_size(self, level: Optional[int] = None) -> Tuple[int, int]:
        """``(num_vertices, num_faces)`` of ``level`` (default: the finest).

        Raises:
            OutOfRangeError: the level does not exist.
        """
        vertices, faces = ffi.new("size_t*"), ffi.new("size_t*")
        self._call(lib.ps_hierarchy_level_size, self._level(level), vertices, faces)
        return int(vertices[0]), int(faces[0])

    def rest_positions(
        self, level: Optional[int] = None, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Rest positions of ``level`` (default: the finest) as a float64 (n, 3) array, m.

        Args:
            out: optional C-contiguous float64 (n, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(
            self._call, lib.ps_hierarchy_get_rest_positions, (self._level(level),), np.float64, out
        )

    def faces(self, level: Optional[int] = None, out: Optional[np.ndarray] = None) -> np.ndarray:
        """Faces of ``level`` (default: the finest) as an int32 (m, 3) array of vertex indices.

        Args:
            out: optional C-contiguous int32 (m, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(self._call, lib.ps_hierarchy_get_faces, (self._level(level),), np.int32, out)

    def prolong(
        self, positions: Any, level: int = 0, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Positions of ``level`` prolonged to the finest level by the shell prolongation
        x = U x_l + a(x_l) (PSQ eq. 9) as a float64 (n_finest, 3) array, m.

        Args:
            positions: (n_level, 3) positions of the level, m.
            out: optional C-contiguous float64 (n_finest, 3) array to fill.

        Raises:
            OutOfRangeError: the level does not exist.
            InvalidArgumentError: positions of the wrong shape or not finite.
        """
        coarse = as_vertices(positions)
        source = ffi.from_buffer("double[]", coarse)
        level = self._level(level)
        count = ffi.new("size_t*")
        self._call(lib.ps_hierarchy_prolong, level, source, coarse.size, ffi.NULL, 0, count)
        array = output_array(out, count[0] // 3, np.float64, "out")
        buffer = ffi.from_buffer("double[]", array, require_writable=True)
        self._call(lib.ps_hierarchy_prolong, level, source, coarse.size, buffer, array.size, count)
        return array

    def num_expansion_batches(self, level: int = 0) -> int:
        """Number of parallel vertex-split batches refining ``level`` into ``level + 1``.

        Raises:
            OutOfRangeError: the level does not exist or is the finest.
        """
        out = ffi.new("int32_t*")
        self._call(lib.ps_hierarchy_num_expansion_batches, self._level(level), out)
        return int(out[0])

    def __repr__(self) -> str:
        if self.closed:
            return "<progsim.Hierarchy (closed)>"
        try:
            vertices, faces = self.level_size()
            return (
                f"<progsim.Hierarchy {self.num_levels} level(s), "
                f"finest {vertices} vertices, {faces} faces>"
            )
        except Exception:  # noqa: BLE001 - repr must not fail (e.g. inside a callback)
            return "<progsim.Hierarchy>"
