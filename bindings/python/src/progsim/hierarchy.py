"""Mesh hierarchies (``ps_hierarchy``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Optional, Sequence, Tuple, Union

import numpy as np

from ._native import (
    NativeObject,
    as_faces,
    as_indices,
    as_vertices,
    check_create,
    int32_value,
    fetch_rows,
)
from ._progsim_cffi import ffi, lib

if TYPE_CHECKING:  # pragma: no cover
    from .simulation import Simulation

__all__ = ["Hierarchy"]

PathLike = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]


def _hierarchy_def(coarse_vertex_counts: Optional[Sequence[int]]):
    """A filled ``ps_hierarchy_def*`` (NULL for the defaults) and the buffer it borrows."""
    if coarse_vertex_counts is None:
        return ffi.NULL, None
    counts = as_indices(coarse_vertex_counts, "coarse_vertex_counts", "(k,)")
    definition = ffi.new("ps_hierarchy_def*")
    lib.ps_hierarchy_def_init(definition)
    buffer = ffi.from_buffer("int32_t[]", counts) if counts.size else ffi.NULL
    definition.coarse_vertex_counts = buffer
    definition.num_coarse_levels = int(counts.size)
    return definition, (counts, buffer)


class Hierarchy(NativeObject):
    """A mesh hierarchy: level 0 is the coarsest, level ``num_levels - 1`` the input mesh.

    Build one from arrays (``Hierarchy(vertices, faces)``) or from a file
    (:meth:`from_file`). This version builds single-level hierarchies (the input mesh
    itself); ``coarse_vertex_counts`` raises :class:`~progsim.UnsupportedError` until
    multi-level hierarchies arrive.

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
    ) -> None:
        """Builds a hierarchy from a triangle mesh, validating it first.

        Args:
            vertices: (n, 3) positions in metres; converted to C-contiguous float64
                (no copy if it already is).
            faces: (m, 3) vertex indices, counter-clockwise seen from the front; converted to
                C-contiguous int32 (no copy if it already is).
            coarse_vertex_counts: target vertex counts of the coarser levels, increasing
                (not supported yet).

        Raises:
            InvalidMeshError: NaN/Inf coordinates, out-of-range indices, degenerate faces,
                non-manifold edges or unreferenced vertices; the message names the first
                offender (e.g. ``vertex 4``).
            InvalidArgumentError: arrays of the wrong shape or dtype.
            UnsupportedError: ``coarse_vertex_counts`` given.
        """
        self._init_native()
        vertex_array = as_vertices(vertices)
        face_array = as_faces(faces)
        definition, keep = _hierarchy_def(coarse_vertex_counts)
        out = ffi.new("ps_hierarchy**")
        check_create(
            lib.ps_hierarchy_create(
                definition,
                ffi.from_buffer("double[]", vertex_array),
                vertex_array.shape[0],
                ffi.from_buffer("int32_t[]", face_array),
                face_array.shape[0],
                out,
            )
        )
        del keep
        self._adopt(out[0])

    @classmethod
    def from_file(
        cls, path: PathLike, *, coarse_vertex_counts: Optional[Sequence[int]] = None
    ) -> "Hierarchy":
        """Builds a hierarchy from an OBJ, OFF or PLY triangle mesh file (positions in metres).

        Raises:
            ProgsimIOError: the file cannot be read.
            InvalidMeshError: the mesh fails validation (see :class:`Hierarchy`).
        """
        self = cls.__new__(cls)
        self._init_native()
        definition, keep = _hierarchy_def(coarse_vertex_counts)
        out = ffi.new("ps_hierarchy**")
        check_create(lib.ps_hierarchy_create_from_file(definition, os.fsencode(path), out))
        del keep
        self._adopt(out[0])
        return self

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
        return fetch_rows(self._call, lib.ps_hierarchy_get_rest_positions, self._level(level), np.float64, out)

    def faces(self, level: Optional[int] = None, out: Optional[np.ndarray] = None) -> np.ndarray:
        """Faces of ``level`` (default: the finest) as an int32 (m, 3) array of vertex indices.

        Args:
            out: optional C-contiguous int32 (m, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(self._call, lib.ps_hierarchy_get_faces, self._level(level), np.int32, out)

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
