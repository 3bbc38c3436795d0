//! [`Hierarchy`]: a mesh, its decimated coarser levels and the prolongations between them.

use std::fmt;
use std::path::Path;
use std::ptr::{self, NonNull};

use progsim_sys as sys;

use crate::error::{check, check_thread};
use crate::{
    c_level, c_path, check_version, not_in_callback, read_triples, Error, HierarchyDef, Result,
    Status,
};

/// A mesh hierarchy: level 0 is the coarsest, level `num_levels() - 1` the user's mesh.
/// Coarse levels come from quadric edge collapse with probabilistic quadrics (PSQ §4.1), each
/// with the shell prolongation to the finest level ([`prolong`](Self::prolong), PSQ eq. 9).
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
        check_version()?;
        let raw_def = def.to_raw()?;
        let mut out = ptr::null_mut();
        // SAFETY: [[f64; 3]] / [[i32; 3]] are 3n consecutive values; every pointer is valid
        // for the call, which copies what it reads.
        let status = unsafe {
            sys::ps_hierarchy_create(
                &raw_def,
                vertices.as_ptr().cast::<f64>(),
                vertices.len(),
                faces.as_ptr().cast::<i32>(),
                faces.len(),
                &mut out,
            )
        };
        check_thread(status)?;
        Hierarchy::from_created(out)
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
        check_version()?;
        let raw_def = def.to_raw()?;
        let path = c_path(path.as_ref())?;
        let mut out = ptr::null_mut();
        // SAFETY: def and path are valid for the call; out receives an owned handle.
        let status =
            unsafe { sys::ps_hierarchy_create_from_file(&raw_def, path.as_ptr(), &mut out) };
        check_thread(status)?;
        Hierarchy::from_created(out)
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
    /// [`Status::Io`] naming the path if it cannot be written.
    pub fn save(&self, path: impl AsRef<Path>) -> Result<()> {
        let raw = self.handle()?;
        let path = c_path(path.as_ref())?;
        // SAFETY: live handle; path valid for the call.
        let status = unsafe { sys::ps_hierarchy_save(raw, path.as_ptr()) };
        self.check(status)
    }

    /// Positions of `level` (one `[x, y, z]` per vertex, m) prolonged to the finest level by
    /// the shell prolongation x = U x_l + a(x_l) (PSQ eq. 9).
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
    /// [`Status::OutOfRange`] for a level that does not exist or is the finest.
    pub fn num_expansion_batches(&self, level: usize) -> Result<usize> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut batches = 0;
        // SAFETY: live handle, valid out-pointer.
        let status = unsafe { sys::ps_hierarchy_num_expansion_batches(raw, level, &mut batches) };
        self.check(status)?;
        Ok(crate::count_from(batches))
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

    /// The vertex and face counts of `level`, as `(num_vertices, num_faces)`.
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

    /// The faces of `level`, one `[i, j, k]` triple of vertex indices per triangle.
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
