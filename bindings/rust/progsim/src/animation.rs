//! Progressive animation (Progressive Dynamics, and VPD for solids): the preview's frames, the
//! finer levels animated over the same span, initial velocities, restarts and per-step
//! statistics.

use std::mem::MaybeUninit;

use progsim_sys as sys;

use crate::{c_level, count_from, read_triples, Error, Result, Simulation, Status};

/// How a progressive animation's finer levels predict each step (the x̂ of its incremental
/// potential) from the coarser level's frames x_l^t, v_l^t, with U the intrinsic part of the
/// prolongation P.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Prediction {
    /// PD++'s velocity-only prolongation, x̂ = x_{l+1}^t + h U v_l^t: temporally smooth
    /// (`PS_PREDICTION_VELOCITY_ONLY`, the default).
    #[default]
    VelocityOnly,
    /// PD eq. 5, x̂ = P(x_l^t) + h U v_l^t: resets the fine positions toward the coarse ones
    /// every step (`PS_PREDICTION_PROLONGED_POSITIONS`).
    ProlongedPositions,
    /// PSQ per frame, x̂ = P(x_l^{t+1}), for comparison (`PS_PREDICTION_PER_FRAME`).
    PerFrame,
}

impl Prediction {
    pub(crate) fn to_raw(self) -> sys::ps_prediction {
        match self {
            Prediction::VelocityOnly => sys::PS_PREDICTION_VELOCITY_ONLY,
            Prediction::ProlongedPositions => sys::PS_PREDICTION_PROLONGED_POSITIONS,
            Prediction::PerFrame => sys::PS_PREDICTION_PER_FRAME,
        }
    }

    pub(crate) fn from_raw(raw: sys::ps_prediction) -> Option<Prediction> {
        match raw {
            sys::PS_PREDICTION_VELOCITY_ONLY => Some(Prediction::VelocityOnly),
            sys::PS_PREDICTION_PROLONGED_POSITIONS => Some(Prediction::ProlongedPositions),
            sys::PS_PREDICTION_PER_FRAME => Some(Prediction::PerFrame),
            _ => None,
        }
    }
}

/// What drives a [`Simulation`]; it follows from the hierarchy's levels and the mode at
/// creation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SimulationKind {
    /// One level: a direct simulation (`PS_SIM_DIRECT`).
    Direct,
    /// Several quasistatic levels: Progressive Shell Quasistatics (`PS_SIM_PSQ`).
    Psq,
    /// Several dynamic levels: a progressive animation (`PS_SIM_PROGRESSIVE_DYNAMICS`).
    ProgressiveDynamics,
    /// A solid's hierarchy ([`Hierarchy::is_solid`](crate::Hierarchy::is_solid)) of several
    /// dynamic levels: volumetric progressive dynamics (VPD), a progressive animation over
    /// tet levels, each with its own elastics (`PS_SIM_VOLUMETRIC_DYNAMICS`).
    VolumetricDynamics,
}

impl SimulationKind {
    fn from_raw(raw: sys::ps_sim_kind) -> Option<SimulationKind> {
        match raw {
            sys::PS_SIM_DIRECT => Some(SimulationKind::Direct),
            sys::PS_SIM_PSQ => Some(SimulationKind::Psq),
            sys::PS_SIM_PROGRESSIVE_DYNAMICS => Some(SimulationKind::ProgressiveDynamics),
            sys::PS_SIM_VOLUMETRIC_DYNAMICS => Some(SimulationKind::VolumetricDynamics),
            _ => None,
        }
    }
}

/// One step of one level of a progressive animation: what produced frame `step`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepStats {
    /// 1-based: the step from frame `step − 1` to frame `step`.
    pub step: usize,
    /// This step's Newton iterations.
    pub newton_iterations: usize,
    /// Whether the step's Newton solve met the tolerance.
    pub converged: bool,
    /// Simulated time after the step, s.
    pub time: f64,
    /// Wall time of the step, s.
    pub seconds: f64,
    /// ½ vᵀ M v after the step, J (the level's masses).
    pub kinetic_energy: f64,
    /// Σ m x / Σ m after the step, m.
    pub center_of_mass: [f64; 3],
    /// How far the centre of mass has moved away from the preview's since frame 0, m (PD
    /// Fig. 19); 0 on level 0.
    pub com_deviation: f64,
    /// VPD App. C eq. 18: the continuity error over the step's own solve residual
    /// (dimensionless; ≤ 1 for implicit Euler on the level alone).
    pub continuity: f64,
    /// VPD App. C eq. 17: ‖xᵗ − x̃ᵗ‖_M, m (mass-weighted RMS).
    pub continuity_error: f64,
    /// VPD App. C eq. 19: distance of the level, projected onto the coarser level, to the
    /// coarser frame, m (mass-weighted RMS); 0 on level 0.
    pub consistency: f64,
}

impl From<sys::ps_step_stats> for StepStats {
    fn from(raw: sys::ps_step_stats) -> StepStats {
        StepStats {
            step: count_from(raw.step),
            newton_iterations: count_from(raw.newton_iterations),
            converged: raw.converged != 0,
            time: raw.time,
            seconds: raw.seconds,
            kinetic_energy: raw.kinetic_energy,
            center_of_mass: raw.center_of_mass,
            com_deviation: raw.com_deviation,
            continuity: raw.continuity,
            continuity_error: raw.continuity_error,
            consistency: raw.consistency,
        }
    }
}

/// One computed level of a progressive animation: its size and work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynamicLevelStats {
    /// Which level.
    pub level: usize,
    /// Vertices of the level's mesh.
    pub vertices: usize,
    /// Steps animated at this level.
    pub steps: usize,
    /// Newton iterations over its steps.
    pub newton_iterations: usize,
    /// Steps whose Newton solve met the tolerance.
    pub converged_steps: usize,
    /// The level's frame 0 is the animation's frame `first_step` (0 unless it is a window,
    /// [`Simulation::refine_window`](crate::Simulation::refine_window)).
    pub first_step: usize,
    /// Wall time of its steps, s.
    pub seconds: f64,
}

impl From<sys::ps_dynamic_level_stats> for DynamicLevelStats {
    fn from(raw: sys::ps_dynamic_level_stats) -> DynamicLevelStats {
        DynamicLevelStats {
            level: count_from(raw.level),
            vertices: count_from(raw.vertices),
            steps: count_from(raw.steps),
            newton_iterations: count_from(raw.newton_iterations),
            converged_steps: count_from(raw.converged_steps),
            first_step: count_from(raw.first_step),
            seconds: raw.seconds,
        }
    }
}

/// One frame of a level of a progressive animation.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// 0 = the level's initial state, k = its state after step k.
    pub index: usize,
    /// `[x, y, z]` per vertex of the level, m.
    pub positions: Vec<[f64; 3]>,
    /// `[vx, vy, vz]` per vertex of the level, m/s.
    pub velocities: Vec<[f64; 3]>,
}

/// A frame number as the C `int32_t`, or [`Status::OutOfRange`].
fn c_frame(frame: usize) -> Result<i32> {
    i32::try_from(frame)
        .map_err(|_| Error::new(Status::OutOfRange, format!("frame {frame} does not exist")))
}

/// The animation calls. On a simulation that is not a progressive animation (see
/// [`kind`](Simulation::kind)) they return [`Status::InvalidArgument`] naming its kind.
impl Simulation<'_> {
    /// What drives this simulation.
    ///
    /// # Errors
    /// Inside a progress closure ([`Status::WrongCallOrder`]).
    pub fn kind(&self) -> Result<SimulationKind> {
        let raw = self.handle()?;
        let mut kind = 0;
        // SAFETY: live simulation, valid out-pointer.
        self.check(unsafe { sys::ps_sim_get_kind(raw, &mut kind) })?;
        SimulationKind::from_raw(kind as sys::ps_sim_kind)
            .ok_or_else(|| Error::new(Status::Internal, format!("unknown simulation kind {kind}")))
    }

    /// Sets how a progressive animation's finer levels predict their steps, for the next
    /// [`refine`](Simulation::refine).
    ///
    /// # Errors
    /// [`Status::WrongCallOrder`] on a progressive animation once a finer level has been
    /// computed ([`restart`](Self::restart) first).
    pub fn set_prediction(&mut self, prediction: Prediction) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation.
        self.check(unsafe { sys::ps_sim_set_prediction(raw, prediction.to_raw() as i32) })
    }

    /// The prediction finer levels of a progressive animation use.
    ///
    /// # Errors
    /// Inside a progress closure ([`Status::WrongCallOrder`]).
    pub fn prediction(&self) -> Result<Prediction> {
        let raw = self.handle()?;
        let mut prediction = 0;
        // SAFETY: live simulation, valid out-pointer.
        self.check(unsafe { sys::ps_sim_get_prediction(raw, &mut prediction) })?;
        Prediction::from_raw(prediction as sys::ps_prediction)
            .ok_or_else(|| Error::new(Status::Internal, format!("unknown prediction {prediction}")))
    }

    /// Frames of a computed level: previewed steps + 1 (frame 0 is the initial state).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level that does not exist or has not been computed.
    pub fn num_frames(&self, level: usize) -> Result<usize> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut frames = 0;
        // SAFETY: live simulation, valid out-pointer.
        self.check(unsafe { sys::ps_sim_num_frames(raw, level, &mut frames) })?;
        Ok(count_from(frames))
    }

    /// Positions of frame `frame` of a computed level, `[x, y, z]` (m) per vertex.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level or frame not computed; [`Status::Io`] if the
    /// frame file cannot be read.
    pub fn frame_positions(&self, level: usize, frame: usize) -> Result<Vec<[f64; 3]>> {
        self.read_frame(level, frame, sys::ps_sim_get_frame_positions)
    }

    /// Velocities of frame `frame` of a computed level, m/s per vertex; as
    /// [`frame_positions`](Self::frame_positions).
    ///
    /// # Errors
    /// As `frame_positions`.
    pub fn frame_velocities(&self, level: usize, frame: usize) -> Result<Vec<[f64; 3]>> {
        self.read_frame(level, frame, sys::ps_sim_get_frame_velocities)
    }

    /// Runs one of the two frame getters with the size-then-fill protocol.
    fn read_frame(
        &self,
        level: usize,
        frame: usize,
        getter: unsafe extern "C" fn(
            *const sys::ps_sim,
            i32,
            i32,
            *mut f64,
            usize,
            *mut usize,
        ) -> i32,
    ) -> Result<Vec<[f64; 3]>> {
        let raw = self.handle()?;
        let (level, frame) = (c_level(level)?, c_frame(frame)?);
        read_triples(|out, capacity, count| {
            // SAFETY: live simulation; out is NULL or valid for `capacity` doubles.
            self.check(unsafe { getter(raw, level, frame, out, capacity, count) })
        })
    }

    /// The frames of a computed level in order, each read from disk when the iterator
    /// reaches it (long animations do not fill memory).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level not computed; each item as
    /// [`frame_positions`](Self::frame_positions).
    pub fn frames(&self, level: usize) -> Result<impl Iterator<Item = Result<Frame>> + '_> {
        let frames = self.num_frames(level)?;
        Ok((0..frames).map(move |index| {
            Ok(Frame {
                index,
                positions: self.frame_positions(level, index)?,
                velocities: self.frame_velocities(level, index)?,
            })
        }))
    }

    /// Sets the preview's initial velocities, one `[vx, vy, vz]` (m/s) per vertex of level
    /// 0, before its first step.
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for a wrong count or a NaN/Inf entry;
    /// [`Status::WrongCallOrder`] after a preview step ([`restart`](Self::restart) first).
    /// Nothing changes on error.
    pub fn set_preview_velocities(&mut self, velocities: &[[f64; 3]]) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation; [f64; 3] slices are 3·len consecutive doubles, read during
        // the call only.
        self.check(unsafe {
            sys::ps_sim_set_preview_velocities(
                raw,
                velocities.as_ptr().cast::<f64>(),
                3 * velocities.len(),
            )
        })
    }

    /// Discards every level's frames and starts the preview again at rest with the current
    /// parameters (initial velocities set before are discarded too).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] if this is not a progressive animation.
    pub fn restart(&mut self) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation.
        self.check(unsafe { sys::ps_sim_restart(raw) })
    }

    /// Per-step statistics of a computed level, in order.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level not computed.
    pub fn step_stats(&self, level: usize) -> Result<Vec<StepStats>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut count = 0usize;
        // SAFETY: live simulation; NULL out asks for the size.
        let status =
            unsafe { sys::ps_sim_get_step_stats(raw, level, std::ptr::null_mut(), 0, &mut count) };
        self.check(status)?;
        let mut stats: Vec<sys::ps_step_stats> = Vec::with_capacity(count);
        let mut written = 0usize;
        // SAFETY: the buffer holds `count` structs; the library writes `written` of them.
        let status = unsafe {
            sys::ps_sim_get_step_stats(raw, level, stats.as_mut_ptr(), count, &mut written)
        };
        self.check(status)?;
        // SAFETY: PS_OK, so the first `written` (≤ count) structs are filled.
        unsafe { stats.set_len(written.min(count)) };
        Ok(stats.into_iter().map(StepStats::from).collect())
    }

    /// Size and work of a computed level.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level not computed.
    pub fn dynamic_level_stats(&self, level: usize) -> Result<DynamicLevelStats> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut stats = MaybeUninit::<sys::ps_dynamic_level_stats>::uninit();
        // SAFETY: live simulation; on PS_OK the library wrote the whole struct.
        self.check(unsafe { sys::ps_sim_get_dynamic_level_stats(raw, level, stats.as_mut_ptr()) })?;
        // SAFETY: PS_OK, so the struct is filled.
        Ok(DynamicLevelStats::from(unsafe { stats.assume_init() }))
    }
}
