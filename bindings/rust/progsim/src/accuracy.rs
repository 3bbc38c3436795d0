//! [`Accuracy`]: what accuracy costs in time on one scene, progressive (PSQ) against direct
//! solves on every level, each compared with the converged finest result.

use std::mem::MaybeUninit;
use std::path::Path;
use std::ptr::{self, NonNull};

use progsim_sys as sys;

use crate::error::check_thread;
use crate::{c_path, check_version, count_from, not_in_callback, Error, Result, Status};

/// How a row's result was computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Preview on the coarsest level, then refinement level by level (PSQ).
    Progressive,
    /// The level solved on its own with the same solver.
    Direct,
}

/// One level's result, as `progsim accuracy` writes it to `accuracy.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct AccuracyRow {
    /// How it was computed.
    pub method: Method,
    /// 0 = coarsest.
    pub level: usize,
    /// Vertices of the level's mesh.
    pub vertices: usize,
    /// Newton iterations on the level.
    pub newton_iterations: usize,
    /// Wall time, s: progressive, from the start until this level's equilibrium (coarser
    /// levels and refinements included); direct, the level's own solve over the load script.
    pub seconds: f64,
    /// Wall time building the level's start from the coarser level, s.
    pub refine_seconds: f64,
    /// RMS distance to the converged finest result over the bounding-box diagonal.
    pub error_rms: f64,
    /// Maximum distance to the converged finest result over the bounding-box diagonal.
    pub error_max: f64,
    /// Face pairs crossing in the level's final state (CGAL's exact check).
    pub intersecting_pairs: usize,
    /// Whether the level ended at equilibrium, progressive or direct.
    pub converged: bool,
    /// Load steps of the scene's script solved (fewer in a direct solve stopped early).
    pub load_steps: usize,
    /// False for a direct solve stopped by [`AccuracyDef::direct_time_ratio`]: its `seconds`
    /// (and any speed-up against it) is then only a lower bound.
    pub finished: bool,
}

/// Which levels an accuracy run solves directly, and for how long. The default solves every
/// level with no time limit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AccuracyDef {
    /// Levels solved directly, in this order (each from 0 to the finest). Empty: every level,
    /// coarsest first.
    pub direct_levels: Vec<i32>,
    /// Stop each direct solve within the Newton iteration that takes it past this many times
    /// the progressive time to the converged finest level (its row then has `finished` false). On
    /// large scenes the direct finest solve takes hours; a limit still measures a lower bound of
    /// the speed-up. 0: no limit.
    pub direct_time_ratio: f64,
    /// The ratio multiplies the coarse preview's time instead: a run capped at R stops as soon
    /// as it shows the preview at least R times faster than the direct solve.
    pub direct_time_of_preview: bool,
}

impl AccuracyDef {
    /// The C def borrowing `self`'s levels: valid while `self` is.
    fn to_raw(&self) -> Result<sys::ps_accuracy_def> {
        let mut raw = MaybeUninit::<sys::ps_accuracy_def>::uninit();
        // SAFETY: ps_accuracy_def_init() fills every field of a non-NULL def.
        let mut raw = unsafe {
            sys::ps_accuracy_def_init(raw.as_mut_ptr());
            raw.assume_init()
        };
        raw.num_direct_levels = i32::try_from(self.direct_levels.len()).map_err(|_| {
            Error::new(Status::InvalidArgument, "too many direct levels for the C ABI")
        })?;
        if !self.direct_levels.is_empty() {
            raw.direct_levels = self.direct_levels.as_ptr();
        }
        raw.direct_time_ratio = self.direct_time_ratio;
        raw.direct_time_base = if self.direct_time_of_preview {
            sys::PS_TIME_BASE_PREVIEW
        } else {
            sys::PS_TIME_BASE_PIPELINE
        };
        Ok(raw)
    }
}

/// The results of one accuracy run. Owns a C `ps_accuracy`, destroyed on drop. `Send` but not
/// `Sync` (calls on one handle must not overlap).
pub struct Accuracy {
    raw: NonNull<sys::ps_accuracy>,
    rows: Vec<AccuracyRow>,
    direct_time_limit: f64,
}

// SAFETY: the results are immutable C data with no thread affinity; not Sync keeps calls on
// the handle (which rewrite the thread's last error) from overlapping.
unsafe impl Send for Accuracy {}

impl Accuracy {
    /// Runs the scene file (which needs a `"progressive"` section with coarse levels)
    /// progressively and directly on every level. Long: minutes for large meshes.
    ///
    /// # Errors
    /// As [`Accuracy::run_with`].
    pub fn run(scene_path: impl AsRef<Path>) -> Result<Accuracy> {
        Self::run_with(scene_path, &AccuracyDef::default())
    }

    /// Runs the scene file progressively and directly on the levels `def` names, each direct
    /// solve within `def`'s time limit.
    ///
    /// # Errors
    /// [`Status::Io`], [`Status::InvalidScene`] (a malformed scene, or one without coarse
    /// levels), [`Status::Unsupported`] (a dynamic scene), [`Status::InvalidArgument`] (a
    /// direct level that does not exist, a negative or NaN time ratio),
    /// [`Status::Intersecting`].
    pub fn run_with(scene_path: impl AsRef<Path>, def: &AccuracyDef) -> Result<Accuracy> {
        check_version()?;
        not_in_callback()?;
        let path = c_path(scene_path.as_ref())?;
        let raw_def = def.to_raw()?;
        let mut out = ptr::null_mut();
        // SAFETY: path and raw_def (borrowing def's levels) are valid for the call; no progress
        // callback; out receives an owned handle.
        let status = unsafe { sys::ps_accuracy_run_scene_file(path.as_ptr(), &raw_def, &mut out) };
        check_thread(status)?;
        let raw = NonNull::new(out).ok_or_else(|| {
            Error::new(Status::Internal, "ps_accuracy_run_scene_file returned no handle")
        })?;
        let mut accuracy = Accuracy { raw, rows: Vec::new(), direct_time_limit: 0.0 };
        accuracy.rows = accuracy.read_rows()?;
        // SAFETY: live handle; the field outlives the call.
        check_thread(unsafe {
            sys::ps_accuracy_direct_time_limit(raw.as_ptr(), &mut accuracy.direct_time_limit)
        })?;
        Ok(accuracy)
    }

    /// The rows: progressive levels first (coarsest first), then the direct solves.
    pub fn rows(&self) -> &[AccuracyRow] {
        &self.rows
    }

    /// The direct solves' time limit in seconds: [`AccuracyDef::direct_time_ratio`] times its
    /// base's time in this run; 0 without a limit.
    pub fn direct_time_limit(&self) -> f64 {
        self.direct_time_limit
    }

    /// Writes `accuracy.csv`, `accuracy.md`, `error_vs_time.png`, `error_by_level.png` and
    /// `time_by_level.png` into `dir` (created).
    ///
    /// # Errors
    /// [`Status::Io`] naming a file that cannot be written.
    pub fn write(&self, dir: impl AsRef<Path>) -> Result<()> {
        not_in_callback()?;
        let dir = c_path(dir.as_ref())?;
        // SAFETY: live handle; dir is valid for the call.
        check_thread(unsafe { sys::ps_accuracy_write(self.raw.as_ptr(), dir.as_ptr()) })
    }

    fn read_rows(&self) -> Result<Vec<AccuracyRow>> {
        let mut count = 0i32;
        // SAFETY: live handle; count outlives the call.
        check_thread(unsafe { sys::ps_accuracy_num_rows(self.raw.as_ptr(), &mut count) })?;
        (0..count).map(|index| self.read_row(index)).collect()
    }

    fn read_row(&self, index: i32) -> Result<AccuracyRow> {
        let mut row = MaybeUninit::<sys::ps_accuracy_row>::uninit();
        // SAFETY: live handle; row outlives the call.
        check_thread(unsafe {
            sys::ps_accuracy_get_row(self.raw.as_ptr(), index, row.as_mut_ptr())
        })?;
        // SAFETY: PS_OK, so the library wrote the whole struct.
        let raw = unsafe { row.assume_init() };
        Ok(AccuracyRow {
            method: if raw.method == sys::PS_METHOD_PROGRESSIVE {
                Method::Progressive
            } else {
                Method::Direct
            },
            level: count_from(raw.level),
            vertices: count_from(raw.vertices),
            newton_iterations: count_from(raw.newton_iterations),
            seconds: raw.seconds,
            refine_seconds: raw.refine_seconds,
            error_rms: raw.error_rms,
            error_max: raw.error_max,
            intersecting_pairs: count_from(raw.intersecting_pairs),
            converged: raw.converged != 0,
            load_steps: count_from(raw.load_steps),
            finished: raw.finished != 0,
        })
    }
}

impl Drop for Accuracy {
    fn drop(&mut self) {
        // SAFETY: owned handle, destroyed once.
        unsafe { sys::ps_accuracy_destroy(self.raw.as_ptr()) }
    }
}

impl std::fmt::Debug for Accuracy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Accuracy").field("rows", &self.rows).finish()
    }
}
