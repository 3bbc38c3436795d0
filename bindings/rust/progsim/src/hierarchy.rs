//! [`Hierarchy`]: a mesh, its decimated coarser levels and the prolongations between them.

use std::fmt;
use std::path::Path;
use std::ptr::{self, NonNull};

use progsim_sys as sys;

use crate::error::{check, check_thread};
use crate::{
    c_level, c_path, check_version, not_in_callback, read_rows, read_triples, Error, HierarchyDef,
    Result, Status,
};

/// A mesh hierarchy: level 0 is the coarsest, level `num_levels() - 1` the user's mesh.
/// Coarse levels come from quadric edge collapse with probabilistic quadrics (PSQ §4.1), each
/// with the shell prolongation to the finest level ([`prolong`](Self::prolong), PSQ eq. 9).
///
/// A solid's hierarchy ([`is_solid`](Self::is_solid); VPD §3.1.2) holds a tet mesh per level
/// instead: build one with [`from_tets`](Self::from_tets),
/// [`from_closed_surface`](Self::from_closed_surface) or
/// [`solid_from_file`](Self::solid_from_file). Each coarse level is the tetrahedralization
/// of the next finer level's decimated boundary, and each finer level's vertices are bound to
/// the coarser level's tets (barycentric weights; VPD §3.3); levels share no vertices. Its
/// [`rest_positions`](Self::rest_positions) include the interior vertices,
/// [`faces`](Self::faces) are the boundary faces over them and [`tets`](Self::tets) the tets.
/// [`save`](Self::save) and [`num_expansion_batches`](Self::num_expansion_batches) apply to
/// shells only ([`Status::Unsupported`]).
///
/// Owns a C `ps_hierarchy`, destroyed on drop. [`Simulation`](crate::Simulation)s borrow
/// it, so it cannot be dropped (or moved) while one exists.
///
/// `Send` but not `Sync`: the C contract lets a handle move between threads, but calls on
/// one handle must not overlap, and even the `&self` getters rewrite the handle's last-error
/// message. Simulations only read the mesh data, which never changes, so a hierarchy may be
/// used on one thread while simulations borrowing it step on others.
///
/// ```compile_fail,E0277
/// fn shared_between_threads<T: Sync>() {}
/// shared_between_threads::<progsim::Hierarchy>();
/// ```
pub struct Hierarchy {
    raw: NonNull<sys::ps_hierarchy>,
}

// SAFETY: the C library allows a hierarchy to move between threads (no thread-affine state);
// not being Sync keeps calls on it from overlapping.
unsafe impl Send for Hierarchy {}

impl Hierarchy {
    /// Builds a single-level hierarchy (the mesh itself) from a triangle mesh: `vertices` (n × 3) positions in
    /// m and `faces` (m × 3) vertex indices, counter-clockwise seen from the front. Both are
    /// copied.
    ///
    /// # Errors
    /// [`Status::InvalidMesh`] naming the first offender (non-finite coordinate, index out of
    /// range, degenerate face, non-manifold edge, unreferenced vertex, empty mesh);
    /// [`Status::VersionMismatch`] if the library is too old for these bindings.
    pub fn from_mesh(vertices: &[[f64; 3]], faces: &[[i32; 3]]) -> Result<Hierarchy> {
        Hierarchy::from_mesh_with(&HierarchyDef::default(), vertices, faces)
    }

    /// As [`from_mesh`](Self::from_mesh), with levels described by `def`.
    ///
    /// # Errors
    /// As `from_mesh`; [`Status::InvalidArgument`] for vertex counts that are not distinct,
    /// below 4 or not below the mesh's; [`Status::InvalidMesh`] when the surface cannot be
    /// decimated that far while staying valid.
    pub fn from_mesh_with(
        def: &HierarchyDef,
        vertices: &[[f64; 3]],
        faces: &[[i32; 3]],
    ) -> Result<Hierarchy> {
        Hierarchy::created_from_arrays(def, vertices, faces, sys::ps_hierarchy_create)
    }

    /// As [`from_mesh`](Self::from_mesh), from flat row-major arrays: `vertices` holds
    /// x0 y0 z0 x1 y1 z1 … (m), `faces` i0 j0 k0 i1 … .
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] if a length is not a multiple of 3; else as `from_mesh`.
    pub fn from_flat(vertices: &[f64], faces: &[i32]) -> Result<Hierarchy> {
        Hierarchy::from_mesh(triples(vertices, "vertices")?, triples(faces, "faces")?)
    }

    /// Builds a single-level hierarchy from an OBJ, OFF or PLY triangle mesh file.
    ///
    /// # Errors
    /// [`Status::Io`] naming the path if it cannot be read; [`Status::InvalidMesh`] as for
    /// [`from_mesh`](Self::from_mesh).
    pub fn from_file(path: impl AsRef<Path>) -> Result<Hierarchy> {
        Hierarchy::from_file_with(&HierarchyDef::default(), path)
    }

    /// As [`from_file`](Self::from_file), with levels described by `def`.
    ///
    /// # Errors
    /// As `from_file`, and as [`from_mesh_with`](Self::from_mesh_with) for the levels.
    pub fn from_file_with(def: &HierarchyDef, path: impl AsRef<Path>) -> Result<Hierarchy> {
        let path = c_path(path.as_ref())?;
        // SAFETY: def and path are valid for the call; out receives an owned handle.
        Hierarchy::created_by(def, |raw_def, out| unsafe {
            sys::ps_hierarchy_create_from_file(raw_def, path.as_ptr(), out)
        })
    }

    /// Builds a single-level solid's hierarchy from a tet mesh: `vertices` (n × 3) positions in
    /// m and `tets` (k × 4) vertex indices, each tet positively oriented
    /// ((x1 − x0)·((x2 − x0) × (x3 − x0)) > 0). Both are copied.
    ///
    /// # Errors
    /// [`Status::InvalidMesh`] naming the first offender (non-finite coordinate, index out of
    /// range, inverted or degenerate tet, duplicate tets, a boundary that is not a closed
    /// manifold, empty mesh); [`Status::VersionMismatch`] if the library is too old for these
    /// bindings.
    pub fn from_tets(vertices: &[[f64; 3]], tets: &[[i32; 4]]) -> Result<Hierarchy> {
        Hierarchy::from_tets_with(&HierarchyDef::default(), vertices, tets)
    }

    /// As [`from_tets`](Self::from_tets), with levels described by `def`: its
    /// `coarse_vertex_counts` are the boundary vertex counts of the coarser levels' decimated
    /// surfaces (distinct, each at least 4 and below the finest boundary's), each then
    /// tetrahedralized with `def.tet_size_factor`. `def.pinned_vertices` and
    /// `def.contact_offset` do not apply to solids' coarse levels.
    ///
    /// # Errors
    /// As `from_tets`; [`Status::InvalidArgument`] for bad vertex counts or size factor.
    pub fn from_tets_with(
        def: &HierarchyDef,
        vertices: &[[f64; 3]],
        tets: &[[i32; 4]],
    ) -> Result<Hierarchy> {
        Hierarchy::created_from_arrays(def, vertices, tets, sys::ps_hierarchy_create_solid)
    }

    /// Builds a single-level solid's hierarchy from the solid a closed triangle surface bounds
    /// (`vertices` in m, `faces` counter-clockwise seen from outside), tetrahedralized by CGAL
    /// Mesh_3 with the default cell size (the bounding-box diagonal / 20); the boundary then
    /// lies on the surface, its vertices resampled.
    ///
    /// # Errors
    /// [`Status::InvalidMesh`] for a surface that is not valid, not closed or that intersects
    /// itself, naming the problem.
    pub fn from_closed_surface(vertices: &[[f64; 3]], faces: &[[i32; 3]]) -> Result<Hierarchy> {
        Hierarchy::from_closed_surface_with(&HierarchyDef::default(), vertices, faces)
    }

    /// As [`from_closed_surface`](Self::from_closed_surface), with the finest level's cell size
    /// `def.tet_cell_size` and coarser levels as in [`from_tets_with`](Self::from_tets_with).
    ///
    /// # Errors
    /// As `from_closed_surface`; [`Status::InvalidArgument`] for a bad cell size, size factor
    /// or vertex counts.
    pub fn from_closed_surface_with(
        def: &HierarchyDef,
        vertices: &[[f64; 3]],
        faces: &[[i32; 3]],
    ) -> Result<Hierarchy> {
        Hierarchy::created_from_arrays(
            def,
            vertices,
            faces,
            sys::ps_hierarchy_create_solid_from_surface,
        )
    }

    /// Builds a single-level solid's hierarchy from a file, the format from the extension: a
    /// tet mesh (Medit `.mesh`, Gmsh `.msh` v2/v4 ASCII, TetGen `.node`/`.ele`) as in
    /// [`from_tets`](Self::from_tets), or a closed surface (`.obj`, `.off`, `.ply`) as in
    /// [`from_closed_surface`](Self::from_closed_surface).
    ///
    /// # Errors
    /// [`Status::Io`] naming the path if it cannot be read; [`Status::InvalidMesh`] as for
    /// `from_tets` or `from_closed_surface`.
    pub fn solid_from_file(path: impl AsRef<Path>) -> Result<Hierarchy> {
        Hierarchy::solid_from_file_with(&HierarchyDef::default(), path)
    }

    /// As [`solid_from_file`](Self::solid_from_file), with levels (and a surface's cell size)
    /// described by `def`.
    ///
    /// # Errors
    /// As `solid_from_file`, and as [`from_tets_with`](Self::from_tets_with) for the levels.
    pub fn solid_from_file_with(def: &HierarchyDef, path: impl AsRef<Path>) -> Result<Hierarchy> {
        let path = c_path(path.as_ref())?;
        // SAFETY: def and path are valid for the call; out receives an owned handle.
        Hierarchy::created_by(def, |raw_def, out| unsafe {
            sys::ps_hierarchy_create_solid_from_file(raw_def, path.as_ptr(), out)
        })
    }

    /// Loads a hierarchy written by [`save`](Self::save) or `progsim hierarchy`.
    ///
    /// # Errors
    /// [`Status::Io`] naming the path for a missing, truncated or foreign file;
    /// [`Status::InvalidArgument`] for inconsistent contents.
    pub fn load(path: impl AsRef<Path>) -> Result<Hierarchy> {
        check_version()?;
        let path = c_path(path.as_ref())?;
        let mut out = ptr::null_mut();
        // SAFETY: path is valid for the call; out receives an owned handle.
        let status = unsafe { sys::ps_hierarchy_load(path.as_ptr(), &mut out) };
        check_thread(status)?;
        Hierarchy::from_created(out)
    }

    /// Writes the hierarchy to `path`, so that decimation is paid once.
    ///
    /// # Errors
    /// [`Status::Io`] naming the path if it cannot be written; [`Status::Unsupported`] for a
    /// solid's hierarchy (shells only).
    pub fn save(&self, path: impl AsRef<Path>) -> Result<()> {
        let raw = self.handle()?;
        let path = c_path(path.as_ref())?;
        // SAFETY: live handle; path valid for the call.
        let status = unsafe { sys::ps_hierarchy_save(raw, path.as_ptr()) };
        self.check(status)
    }

    /// Positions of `level` (one `[x, y, z]` per vertex, m) prolonged to the finest level by
    /// the shell prolongation x = U x_l + a(x_l) (PSQ eq. 9). On a solid's hierarchy: the
    /// product of the barycentric prolongations W of the levels above (VPD §3.3), which
    /// carries affine maps of the coarse solid over exactly.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist; [`Status::InvalidArgument`] if
    /// `positions` does not have one entry per vertex of the level or is not finite.
    pub fn prolong(&self, level: usize, positions: &[[f64; 3]]) -> Result<Vec<[f64; 3]>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        read_triples(|out, capacity, count| {
            // SAFETY: live handle; positions holds 3 len doubles; out is NULL or valid for
            // `capacity` doubles.
            let status = unsafe {
                sys::ps_hierarchy_prolong(
                    raw,
                    level,
                    positions.as_ptr().cast::<f64>(),
                    positions.len() * 3,
                    out,
                    capacity,
                    count,
                )
            };
            self.check(status)
        })
    }

    /// The number of parallel vertex-split batches that refine `level` into `level + 1`
    /// (PSQ §4.4.4).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level that does not exist or is the finest;
    /// [`Status::Unsupported`] for a solid's hierarchy (shells only).
    pub fn num_expansion_batches(&self, level: usize) -> Result<usize> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut batches = 0;
        // SAFETY: live handle, valid out-pointer.
        let status = unsafe { sys::ps_hierarchy_num_expansion_batches(raw, level, &mut batches) };
        self.check(status)?;
        Ok(crate::count_from(batches))
    }

    /// Runs a `ps_hierarchy_create*` call that takes vertices and cells (faces or tets) as flat
    /// arrays.
    fn created_from_arrays<const N: usize>(
        def: &HierarchyDef,
        vertices: &[[f64; 3]],
        cells: &[[i32; N]],
        create: unsafe extern "C" fn(
            *const sys::ps_hierarchy_def,
            *const f64,
            usize,
            *const i32,
            usize,
            *mut *mut sys::ps_hierarchy,
        ) -> i32,
    ) -> Result<Hierarchy> {
        Hierarchy::created_by(def, |raw_def, out| {
            // SAFETY: [[f64; 3]] / [[i32; N]] are 3n / Nk consecutive values; every pointer is
            // valid for the call, which copies what it reads.
            unsafe {
                create(
                    raw_def,
                    vertices.as_ptr().cast::<f64>(),
                    vertices.len(),
                    cells.as_ptr().cast::<i32>(),
                    cells.len(),
                    out,
                )
            }
        })
    }

    /// Runs a `ps_hierarchy_create*` call with `def` (checked and converted first) and takes
    /// ownership of the handle it creates.
    fn created_by(
        def: &HierarchyDef,
        create: impl FnOnce(*const sys::ps_hierarchy_def, *mut *mut sys::ps_hierarchy) -> i32,
    ) -> Result<Hierarchy> {
        check_version()?;
        let raw_def = def.to_raw()?;
        let mut out = ptr::null_mut();
        check_thread(create(&raw_def, &mut out))?;
        Hierarchy::from_created(out)
    }

    /// Takes ownership of a freshly created handle.
    fn from_created(raw: *mut sys::ps_hierarchy) -> Result<Hierarchy> {
        NonNull::new(raw)
            .map(|raw| Hierarchy { raw })
            .ok_or_else(|| Error::new(Status::Internal, "the library returned a NULL hierarchy"))
    }

    /// Wraps a hierarchy the caller does not own (a scene simulation's): the result must
    /// never be dropped (keep it in a `ManuallyDrop`) nor outlive its owner.
    pub(crate) fn borrowed_from(raw: NonNull<sys::ps_hierarchy>) -> Hierarchy {
        Hierarchy { raw }
    }

    /// The C handle for a call, or [`Status::WrongCallOrder`] inside a progress closure.
    pub(crate) fn handle(&self) -> Result<*mut sys::ps_hierarchy> {
        not_in_callback()?;
        Ok(self.raw.as_ptr())
    }

    /// Ok, or the error of the last failed call on this hierarchy.
    fn check(&self, status: i32) -> Result<()> {
        // SAFETY: self.raw is a live hierarchy; the message is copied at once.
        check(status, || unsafe { sys::ps_hierarchy_last_error(self.raw.as_ptr()) })
    }

    /// The number of levels (≥ 1).
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn num_levels(&self) -> usize {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut levels = 0;
        // SAFETY: live handle, valid out-pointer.
        let status = unsafe { sys::ps_hierarchy_num_levels(raw, &mut levels) };
        self.check(status).expect("ps_hierarchy_num_levels fails only on NULL arguments");
        crate::count_from(levels)
    }

    /// Whether this is a solid's (tet) hierarchy rather than a shell's.
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn is_solid(&self) -> bool {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut solid = 0;
        // SAFETY: live handle, valid out-pointer.
        let status = unsafe { sys::ps_hierarchy_is_solid(raw, &mut solid) };
        self.check(status).expect("ps_hierarchy_is_solid fails only on NULL arguments");
        solid != 0
    }

    /// The vertex and face counts of `level`, as `(num_vertices, num_faces)`; for a solid, its
    /// vertices (interior ones included) and boundary faces.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn level_size(&self, level: usize) -> Result<(usize, usize)> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let (mut num_vertices, mut num_faces) = (0usize, 0usize);
        // SAFETY: live handle, valid out-pointers.
        let status =
            unsafe { sys::ps_hierarchy_level_size(raw, level, &mut num_vertices, &mut num_faces) };
        self.check(status)?;
        Ok((num_vertices, num_faces))
    }

    /// The rest positions of `level`, one `[x, y, z]` (m) per vertex.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn rest_positions(&self, level: usize) -> Result<Vec<[f64; 3]>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        read_triples(|out, capacity, count| {
            // SAFETY: live handle; out is NULL or valid for `capacity` doubles.
            let status =
                unsafe { sys::ps_hierarchy_get_rest_positions(raw, level, out, capacity, count) };
            self.check(status)
        })
    }

    /// The faces of `level`, one `[i, j, k]` triple of vertex indices per triangle (a solid's:
    /// its boundary faces).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn faces(&self, level: usize) -> Result<Vec<[i32; 3]>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        read_triples(|out, capacity, count| {
            // SAFETY: live handle; out is NULL or valid for `capacity` indices.
            let status = unsafe { sys::ps_hierarchy_get_faces(raw, level, out, capacity, count) };
            self.check(status)
        })
    }

    /// The tets of a solid's `level`, one positively oriented `[i, j, k, l]` of indices into
    /// the level's vertices ([`rest_positions`](Self::rest_positions)) per tet; empty for a
    /// shell's hierarchy.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn tets(&self, level: usize) -> Result<Vec<[i32; 4]>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        read_rows(|out, capacity, count| {
            // SAFETY: live handle; out is NULL or valid for `capacity` indices.
            let status = unsafe { sys::ps_hierarchy_get_tets(raw, level, out, capacity, count) };
            self.check(status)
        })
    }

    /// The C handle, for calls through `progsim-sys`. Borrowed: valid while `self` is; do
    /// not destroy it.
    pub fn as_ptr(&self) -> *const sys::ps_hierarchy {
        self.raw.as_ptr()
    }
}

impl Drop for Hierarchy {
    fn drop(&mut self) {
        // SAFETY: owned handle; no simulation borrows it any more (lifetimes ensure it).
        unsafe {
            sys::ps_hierarchy_destroy(self.raw.as_ptr());
        }
    }
}

impl fmt::Debug for Hierarchy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Hierarchy").field("raw", &self.raw).finish()
    }
}

/// `flat` as triples, or [`Status::InvalidArgument`] if its length is not a multiple of 3.
fn triples<'a, T>(flat: &'a [T], what: &str) -> Result<&'a [[T; 3]]> {
    if flat.len() % 3 != 0 {
        return Err(Error::new(
            Status::InvalidArgument,
            format!("{what} has {} values, not a multiple of 3", flat.len()),
        ));
    }
    // SAFETY: [T; 3] has the size and alignment of three consecutive T, and flat holds
    // exactly len / 3 such groups.
    Ok(unsafe { std::slice::from_raw_parts(flat.as_ptr().cast::<[T; 3]>(), flat.len() / 3) })
}
