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
    as_tets,
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
    tet_size_factor: Optional[float] = None,
    tet_cell_size: Optional[float] = None,
    vertex_group_ids: Optional[Sequence[int]] = None,
):
    """A filled ``ps_hierarchy_def*`` with the progress trampoline installed, and the buffers
    it borrows (keep them alive during the call). ``None`` keeps a field's default."""
    definition = ffi.new("ps_hierarchy_def*")
    lib.ps_hierarchy_def_init(definition)
    counts, buffer = index_buffer(coarse_vertex_counts, "coarse_vertex_counts")
    definition.coarse_vertex_counts = buffer
    definition.num_coarse_levels = int(counts.size)
    pins, pin_buffer = index_buffer(pinned, "pinned")
    definition.pinned_vertices = pin_buffer
    definition.num_pinned_vertices = int(pins.size)
    groups, group_buffer = index_buffer(vertex_group_ids, "vertex_group_ids")
    definition.vertex_group_ids = group_buffer
    definition.num_vertex_group_ids = int(groups.size)
    definition.contact_offset = real_value(contact_offset, "contact_offset")
    if tet_size_factor is not None:
        definition.tet_size_factor = real_value(tet_size_factor, "tet_size_factor")
    if tet_cell_size is not None:
        definition.tet_cell_size = real_value(tet_cell_size, "tet_cell_size")
    run.install(definition)
    return definition, (counts, buffer, pins, pin_buffer, groups, group_buffer)


def _create(
    function,
    coarse_vertex_counts,
    pinned,
    contact_offset,
    progress: ProgressArg,
    *args: Any,
    tet_size_factor: Optional[float] = None,
    tet_cell_size: Optional[float] = None,
    vertex_group_ids: Optional[Sequence[int]] = None,
) -> "ffi.CData":
    """Runs a ps_hierarchy_create* call with a def and progress reporting; returns the handle."""
    run = ProgressRun(progress)
    definition, keep = _hierarchy_def(
        coarse_vertex_counts,
        pinned,
        contact_offset,
        run,
        tet_size_factor,
        tet_cell_size,
        vertex_group_ids,
    )
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

    A solid's hierarchy (:attr:`is_solid`; VPD §3.1.2) holds a tet mesh per level: build one
    from tets (:meth:`from_tets`), from a closed surface (:meth:`from_closed_surface`) or from
    a file (:meth:`solid_from_file`). Its levels' :meth:`rest_positions` include the interior
    vertices, :meth:`faces` are the boundary faces over them and :meth:`tets` the tets; a
    simulation on several levels of it is volumetric progressive dynamics (VPD).

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
        vertex_group_ids: Optional[Sequence[int]] = None,
    ) -> None:
        """Builds a hierarchy from a triangle mesh, validating it first.

        Args:
            vertices: (n, 3) positions in metres; converted to C-contiguous float64
                (no copy if it already is).
            faces: (m, 3) vertex indices, counter-clockwise seen from the front; converted to
                C-contiguous int32 (no copy if it already is).
            coarse_vertex_counts: vertex counts of the coarser levels (distinct, each at least
                4 and below n); ``None`` or empty: a single level, the mesh itself.
            pinned: vertices a simulation will pin (``Simulation(pinned=...)``): vertex group
                0, kept on every level at their rest positions. A progressive simulation's pins
                must be these.
            contact_offset: m, >= 0; default 0. Coarse levels never cross themselves; with
                the offset ξ a contact simulation will use (half the shell thickness), no
                collapse also brings a vertex and a face, or two edges, within 2ξ.
            progress: ``True`` for a tqdm bar over the decimation, ``False`` for none, or a
                callable ``(done, total, phase) -> bool`` (percent; return True to cancel).
            vertex_group_ids: several vertex groups instead of ``pinned`` (not both): per
                vertex its group, -1 for none, groups numbered 0, 1, ... without gaps. Each is
                kept on every level; a progressive simulation's handle i must be group i
                (``pinned`` group 0, then :meth:`Simulation.add_handle` the next).

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
                vertex_group_ids=vertex_group_ids,
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
        vertex_group_ids: Optional[Sequence[int]] = None,
    ) -> "Hierarchy":
        """Builds a hierarchy from an OBJ, OFF or PLY triangle mesh file (positions in metres),
        with the same options as :class:`Hierarchy`.

        Raises:
            ProgsimIOError: the file cannot be read.
            InvalidMeshError: the mesh fails validation (see :class:`Hierarchy`).
        """
        return cls._created(
            lib.ps_hierarchy_create_from_file,
            coarse_vertex_counts,
            pinned,
            contact_offset,
            progress,
            os.fsencode(path),
            vertex_group_ids=vertex_group_ids,
        )

    @classmethod
    def from_tets(
        cls,
        vertices: Any,
        tets: Any,
        *,
        coarse_vertex_counts: Optional[Sequence[int]] = None,
        tet_size_factor: Optional[float] = None,
        progress: ProgressArg = False,
    ) -> "Hierarchy":
        """Builds a solid's hierarchy from a tet mesh, validating it first
        (``ps_hierarchy_create_solid``).

        The finest level is the mesh unchanged; each coarser level is the tetrahedralization
        of its decimated boundary surface, and each finer level's vertices are bound to the
        next coarser level's tets (barycentric weights; VPD §3.3). Levels share no vertices.

        Args:
            vertices: (n, 3) positions in metres; converted to C-contiguous float64.
            tets: (k, 4) vertex indices, each tet positively oriented
                ((x1 − x0)·((x2 − x0) × (x3 − x0)) > 0); converted to C-contiguous int32.
            coarse_vertex_counts: boundary vertex counts of the coarser levels' decimated
                surfaces (distinct, each at least 4 and below the finest boundary's);
                ``None`` or empty: a single level, the mesh itself.
            tet_size_factor: size of a coarse level's tets and boundary faces in multiples of
                its surface's mean edge length, in (0, 100]; default (``None``) 0.6.
            progress: ``True`` for a tqdm bar, ``False`` for none, or a callable
                ``(done, total, phase) -> bool`` (phases ``"decimation"``,
                ``"tetrahedralization"``, ``"binding"``; return True to cancel).

        Raises:
            InvalidMeshError: NaN/Inf coordinates, out-of-range indices, inverted or degenerate
                tets, duplicate tets, a boundary that is not a closed manifold; the message
                names the first offender.
            InvalidArgumentError: arrays of the wrong shape or dtype, bad vertex counts or
                size factor.
            CancelledError: the progress callable asked to stop.
        """
        vertex_array = as_vertices(vertices)
        tet_array = as_tets(tets)
        return cls._created(
            lib.ps_hierarchy_create_solid,
            coarse_vertex_counts,
            None,
            0.0,
            progress,
            ffi.from_buffer("double[]", vertex_array),
            vertex_array.shape[0],
            ffi.from_buffer("int32_t[]", tet_array),
            tet_array.shape[0],
            tet_size_factor=tet_size_factor,
        )

    @classmethod
    def from_closed_surface(
        cls,
        vertices: Any,
        faces: Any,
        *,
        coarse_vertex_counts: Optional[Sequence[int]] = None,
        tet_size_factor: Optional[float] = None,
        tet_cell_size: Optional[float] = None,
        progress: ProgressArg = False,
    ) -> "Hierarchy":
        """Builds a solid's hierarchy from the solid a closed triangle surface bounds
        (``ps_hierarchy_create_solid_from_surface``): the surface is tetrahedralized (CGAL
        Mesh_3; its boundary then lies on the surface, the vertices resampled) into the finest
        level, then coarsened as in :meth:`from_tets`.

        Args:
            vertices: (n, 3) positions in metres.
            faces: (m, 3) vertex indices of a closed, non-self-intersecting surface.
            coarse_vertex_counts, tet_size_factor, progress: as in :meth:`from_tets`.
            tet_cell_size: the largest tet circumradius of the finest level, m, >= 0; default
                (``None`` or 0) the surface's bounding-box diagonal / 20. The tet count grows
                like (size / tet_cell_size)³.

        Raises:
            InvalidMeshError: a surface that is not valid, not closed or intersects itself.
            InvalidArgumentError: arrays of the wrong shape or dtype, a bad cell size, size
                factor or vertex counts.
            CancelledError: the progress callable asked to stop.
        """
        vertex_array = as_vertices(vertices)
        face_array = as_faces(faces)
        return cls._created(
            lib.ps_hierarchy_create_solid_from_surface,
            coarse_vertex_counts,
            None,
            0.0,
            progress,
            ffi.from_buffer("double[]", vertex_array),
            vertex_array.shape[0],
            ffi.from_buffer("int32_t[]", face_array),
            face_array.shape[0],
            tet_size_factor=tet_size_factor,
            tet_cell_size=tet_cell_size,
        )

    @classmethod
    def solid_from_file(
        cls,
        path: PathLike,
        *,
        coarse_vertex_counts: Optional[Sequence[int]] = None,
        tet_size_factor: Optional[float] = None,
        tet_cell_size: Optional[float] = None,
        progress: ProgressArg = False,
    ) -> "Hierarchy":
        """Builds a solid's hierarchy from a file (``ps_hierarchy_create_solid_from_file``;
        the format from the extension): a tet mesh (Medit ``.mesh``, Gmsh ``.msh`` v2/v4
        ASCII, TetGen ``.node``/``.ele``) as in :meth:`from_tets`, or a closed surface
        (``.obj``, ``.off``, ``.ply``) as in :meth:`from_closed_surface`, with the same
        options.

        Raises:
            ProgsimIOError: the file cannot be read.
            InvalidMeshError: the mesh fails validation (see :meth:`from_tets`).
        """
        return cls._created(
            lib.ps_hierarchy_create_solid_from_file,
            coarse_vertex_counts,
            None,
            0.0,
            progress,
            os.fsencode(path),
            tet_size_factor=tet_size_factor,
            tet_cell_size=tet_cell_size,
        )

    @classmethod
    def _created(cls, *args: Any, **options: Any) -> "Hierarchy":
        """A new hierarchy owning the handle ``_create(*args, **options)`` creates."""
        self = cls.__new__(cls)
        self._init_native()
        self._adopt(_create(*args, **options))
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
            UnsupportedError: a solid's hierarchy (shells only).
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

    @property
    def is_solid(self) -> bool:
        """Whether this is a solid's (tet) hierarchy rather than a shell's."""
        out = ffi.new("int32_t*")
        self._call(lib.ps_hierarchy_is_solid, out)
        return bool(out[0])

    def level_size(self, level: Optional[int] = None) -> Tuple[int, int]:
        """``(num_vertices, num_faces)`` of ``level`` (default: the finest); for a solid, its
        vertices (interior ones included) and boundary faces.

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
        """Faces of ``level`` (default: the finest) as an int32 (m, 3) array of vertex indices
        (a solid's: its boundary faces, outward).

        Args:
            out: optional C-contiguous int32 (m, 3) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(
            self._call, lib.ps_hierarchy_get_faces, (self._level(level),), np.int32, out
        )

    def tets(self, level: Optional[int] = None, out: Optional[np.ndarray] = None) -> np.ndarray:
        """Tets of a solid's ``level`` (default: the finest) as an int32 (k, 4) array of
        indices into the level's vertices (:meth:`rest_positions`), positively oriented; a
        shell's hierarchy has none: shape (0, 4).

        Args:
            out: optional C-contiguous int32 (k, 4) array to fill instead of a new one.

        Raises:
            OutOfRangeError: the level does not exist.
        """
        return fetch_rows(
            self._call, lib.ps_hierarchy_get_tets, (self._level(level),), np.int32, out, 4
        )

    def prolong(
        self, positions: Any, level: int = 0, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Positions of ``level`` prolonged to the finest level by the shell prolongation
        x = U x_l + a(x_l) (PSQ eq. 9) as a float64 (n_finest, 3) array, m. On a solid's
        hierarchy: the product of the barycentric prolongations W of the levels above (VPD
        §3.3), which carries affine maps of the coarse solid over exactly.

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
            UnsupportedError: a solid's hierarchy (shells only).
        """
        out = ffi.new("int32_t*")
        self._call(lib.ps_hierarchy_num_expansion_batches, self._level(level), out)
        return int(out[0])

    def __repr__(self) -> str:
        if self.closed:
            return "<progsim.Hierarchy (closed)>"
        try:
            vertices, faces = self.level_size()
            if self.is_solid:
                return (
                    f"<progsim.Hierarchy solid, {self.num_levels} level(s), finest {vertices} "
                    f"vertices, {len(self.tets())} tets, {faces} boundary faces>"
                )
            return (
                f"<progsim.Hierarchy {self.num_levels} level(s), "
                f"finest {vertices} vertices, {faces} faces>"
            )
        except Exception:  # noqa: BLE001 - repr must not fail (e.g. inside a callback)
            return "<progsim.Hierarchy>"
