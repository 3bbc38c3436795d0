//! Safe Rust bindings to progsim, a library for progressive (level-of-detail) simulation of
//! cloth and thin shells.
//!
//! A [`Hierarchy`] holds a triangle mesh and its coarser levels, or a solid's tet mesh and
//! its coarser tet levels ([`Hierarchy::from_tets`]); a [`Simulation`] runs on it: preview
//! steps at the current level, then refinement to finer levels. Scenes described in JSON give
//! a simulation that owns its hierarchy ([`Simulation::from_scene`]).
//!
//! Conventions (those of the C ABI):
//! - Units are SI: metres, seconds, kilograms, pascals, radians.
//! - Positions are `[x, y, z]` triples (`(n × 3)` row-major in C); faces are `[i, j, k]`
//!   vertex indices, counter-clockwise seen from the front.
//! - Levels count from 0 (the coarsest) to `num_levels() - 1` (the user's mesh).
//! - Every fallible call returns [`Result`]; an [`Error`] carries a [`Status`] and the
//!   library's message, which names the offending vertex, JSON key, parameter or level.
//!
//! Threads: [`Hierarchy`] and [`Simulation`] are `Send` but not `Sync`. The C library
//! allows one thread at a time per handle (each handle keeps its last error message, which
//! every call rewrites, even `&self` getters), while a handle may move between threads and
//! distinct handles may run concurrently. So a simulation can be moved to, and stepped on,
//! another thread, but cannot be shared by reference between threads.
//!
//! ```no_run
//! use progsim::{Hierarchy, Simulation, SimulationDef};
//!
//! # fn main() -> progsim::Result<()> {
//! let hierarchy = Hierarchy::from_file("scenes/meshes/square_cloth.obj")?;
//! let def = SimulationDef {
//!     pinned_vertices: vec![420, 440],
//!     gravity: [0.0, 0.0, -9.81],
//!     ..SimulationDef::default()
//! };
//! let mut sim = Simulation::new(&hierarchy, &def)?;
//! sim.step_preview(10)?;
//! let lowest = sim.positions(0)?.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
//! println!("lowest point: z = {lowest:.3} m");
//! # Ok(())
//! # }
//! ```
//!
//! Linking: `progsim-sys` links `libprogsim` from `PROGSIM_LIB_DIR` (default
//! `<repo>/build/release/core`) and this crate's tests and examples get an rpath to it; other
//! binaries need the folder on their rpath (see this crate's `build.rs`) or in
//! `LD_LIBRARY_PATH`.

#![warn(missing_docs)]

mod accuracy;
mod animation;
mod def;
mod error;
mod hierarchy;
mod load;
mod obstacle;
mod simulation;

use std::cell::Cell;
use std::ffi::CString;
use std::path::Path;
use std::sync::OnceLock;

use progsim_sys as sys;

pub use accuracy::{Accuracy, AccuracyDef, AccuracyRow, Method};
pub use animation::{DynamicLevelStats, Frame, Prediction, SimulationKind, StepStats};
pub use def::{
    Axes, Effect, Effects, HandleMotion, HandleReaction, HierarchyDef, Interpolation, Keyframe,
    LevelStats, Mode, RefinementStats, SimulationDef, StrainCorrectionStats, Support,
};
pub use error::{Error, Result, Status};
pub use hierarchy::Hierarchy;
pub use load::{Load, LoadDistribution};
pub use obstacle::{Ground, Obstacle};
pub use simulation::Simulation;

/// The C header version these bindings were generated from, packed as
/// major·10000 + minor·100 + patch.
pub const HEADER_VERSION: i32 = sys::PS_VERSION_HEADER;

/// The loaded library's version, packed like [`HEADER_VERSION`].
pub fn library_version() -> i32 {
    // SAFETY: no arguments; thread-safe.
    unsafe { sys::ps_version() }
}

/// The loaded library's version as text, e.g. `"0.1.0"`.
pub fn library_version_string() -> &'static str {
    // SAFETY: returns a static NUL-terminated string; thread-safe.
    unsafe { error::static_str(sys::ps_version_string()) }
}

/// Fixes the threads of progsim's parallel loops for the whole process (1 to 1024), or `0` to
/// let the library choose (the default): the cores other processes leave idle, sampled every
/// 0.25 s while it computes, so that a loaded machine needs no `OMP_WAIT_POLICY`.
/// `OMP_NUM_THREADS`, if set, caps the automatic count. Any other value is
/// [`Status::InvalidArgument`] and leaves the setting unchanged.
pub fn set_threads(threads: i32) -> Result<()> {
    // SAFETY: takes a value; thread-safe.
    error::check_thread(unsafe { sys::ps_set_threads(threads) })
}

/// `(setting, current)`: the value of [`set_threads`] (0: automatic) and the threads a large
/// parallel loop gets now.
pub fn threads() -> Result<(i32, i32)> {
    let (mut setting, mut current) = (0, 0);
    // SAFETY: both pointers are valid for one write; thread-safe.
    error::check_thread(unsafe { sys::ps_get_threads(&mut setting, &mut current) })?;
    Ok((setting, current))
}

/// One named option of [`Simulation::set_choice`] (the choice table; scene keys of the same
/// names).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChoiceInfo {
    /// `"group.name"`, e.g. `"progressive.prolongation"`.
    pub name: &'static str,
    /// The admissible values; the first is the default.
    pub options: Vec<&'static str>,
    /// One-sentence description.
    pub doc: &'static str,
}

/// Every named option the library knows, in table order.
pub fn choices() -> Vec<ChoiceInfo> {
    // SAFETY: no arguments; thread-safe.
    let count = unsafe { sys::ps_choice_count() };
    (0..count)
        .filter_map(|index| {
            let mut info = std::mem::MaybeUninit::<sys::ps_choice_info>::uninit();
            // SAFETY: index in range, valid out-pointer; on PS_OK every field is a static string.
            unsafe {
                (sys::ps_choice_info_get(index, info.as_mut_ptr()) == sys::PS_OK as i32).then(
                    || {
                        let info = info.assume_init();
                        ChoiceInfo {
                            name: error::static_str(info.name),
                            options: error::static_str(info.options).split('|').collect(),
                            doc: error::static_str(info.doc),
                        }
                    },
                )
            }
        })
        .collect()
}

/// Checks once per process that the loaded library can serve these bindings (same major
/// version, library minor version at least the header's); later calls return the first
/// answer. [`Hierarchy`] and scene constructors call it, so calling it yourself is only
/// needed to fail early.
///
/// # Errors
/// [`Status::VersionMismatch`] naming both versions.
pub fn check_version() -> Result<()> {
    not_in_callback()?;
    static CHECKED: OnceLock<Result<()>> = OnceLock::new();
    CHECKED
        // SAFETY: takes an integer; thread-safe; its message is read on this thread at once.
        .get_or_init(|| error::check_thread(unsafe { sys::ps_check_version(HEADER_VERSION) }))
        .clone()
}

thread_local! {
    /// Whether this thread is inside a progress closure called by the C library.
    static IN_PROGRESS_CALLBACK: Cell<bool> = const { Cell::new(false) };
}

/// Marks the calling thread as inside a progress closure until dropped (also when the
/// closure unwinds).
pub(crate) struct CallbackScope(());

impl CallbackScope {
    pub(crate) fn enter() -> CallbackScope {
        IN_PROGRESS_CALLBACK.with(|flag| flag.set(true));
        CallbackScope(())
    }
}

impl Drop for CallbackScope {
    fn drop(&mut self) {
        IN_PROGRESS_CALLBACK.with(|flag| flag.set(false));
    }
}

/// [`Status::WrongCallOrder`] inside a progress closure: the C contract forbids callbacks to
/// call back into progsim, so every call on a handle checks this first.
pub(crate) fn not_in_callback() -> Result<()> {
    if IN_PROGRESS_CALLBACK.with(Cell::get) {
        return Err(Error::new(
            Status::WrongCallOrder,
            "progsim was called from inside a progress callback, which the library does not \
             allow; act after the call returns",
        ));
    }
    Ok(())
}

/// `text` as a C string, or [`Status::InvalidArgument`] naming `what` if it holds a NUL.
pub(crate) fn c_string(text: &str, what: &str) -> Result<CString> {
    CString::new(text).map_err(|_| {
        Error::new(Status::InvalidArgument, format!("{what} {text:?} contains a NUL byte"))
    })
}

/// `path` as a C string (its bytes on Unix, UTF-8 elsewhere).
pub(crate) fn c_path(path: &Path) -> Result<CString> {
    #[cfg(unix)]
    let bytes = {
        use std::os::unix::ffi::OsStrExt;
        path.as_os_str().as_bytes().to_vec()
    };
    #[cfg(not(unix))]
    let bytes = path
        .to_str()
        .ok_or_else(|| {
            Error::new(Status::InvalidArgument, format!("path {} is not UTF-8", path.display()))
        })?
        .as_bytes()
        .to_vec();
    CString::new(bytes).map_err(|_| {
        Error::new(Status::InvalidArgument, format!("path {} contains a NUL byte", path.display()))
    })
}

/// A level number as the C `int32_t`, or [`Status::OutOfRange`].
pub(crate) fn c_handle(handle: usize) -> Result<i32> {
    i32::try_from(handle)
        .map_err(|_| Error::new(Status::OutOfRange, format!("handle {handle} does not exist")))
}

pub(crate) fn c_level(level: usize) -> Result<i32> {
    i32::try_from(level)
        .map_err(|_| Error::new(Status::OutOfRange, format!("level {level} does not exist")))
}

/// Reads a size-then-fill array of `(n × 3)` values: `call(out, capacity, count)` is
/// called once with `out` NULL to learn `count` = 3n, then with a buffer of that size.
pub(crate) fn read_triples<T: Copy + Default>(
    call: impl FnMut(*mut T, usize, &mut usize) -> Result<()>,
) -> Result<Vec<[T; 3]>> {
    read_rows(call)
}

/// Reads a size-then-fill array of `(n × N)` values, as [`read_triples`] for rows of `N`.
pub(crate) fn read_rows<T: Copy + Default, const N: usize>(
    mut call: impl FnMut(*mut T, usize, &mut usize) -> Result<()>,
) -> Result<Vec<[T; N]>> {
    let mut count = 0usize;
    call(std::ptr::null_mut(), 0, &mut count)?;
    if count % N != 0 {
        return Err(Error::new(
            Status::Internal,
            format!("the library reported {count} values, not a multiple of {N}"),
        ));
    }
    let mut out = vec![[T::default(); N]; count / N];
    let mut written = 0usize;
    // [T; N] has the layout of N consecutive T, so out is `count` consecutive T.
    call(out.as_mut_ptr().cast::<T>(), count, &mut written)?;
    if written != count {
        return Err(Error::new(
            Status::Internal,
            format!("the library announced {count} values but wrote {written}"),
        ));
    }
    Ok(out)
}

/// The library's usize-valued count as a Rust count (negative values, which the C side
/// never gives, read as 0).
pub(crate) fn count_from(value: i32) -> usize {
    usize::try_from(value).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions_agree() {
        assert_eq!(check_version(), Ok(()));
        assert_eq!(library_version(), HEADER_VERSION);
        let [major, minor, patch] =
            [HEADER_VERSION / 10000, HEADER_VERSION / 100 % 100, HEADER_VERSION % 100];
        assert_eq!(library_version_string(), format!("{major}.{minor}.{patch}"));
    }

    #[test]
    fn strings_with_nul_are_rejected_before_the_call() {
        let error = c_string("a\0b", "parameter name").unwrap_err();
        assert_eq!(error.code, Status::InvalidArgument);
        assert!(error.message.contains("NUL"));
        assert_eq!(c_level(usize::MAX).unwrap_err().code, Status::OutOfRange);
    }
}
