//! [`Simulation`]: preview steps at the current level, refinement, results.

use std::any::Any;
use std::ffi::{c_char, c_void, CStr};
use std::fmt;
use std::marker::PhantomData;
use std::mem::{ManuallyDrop, MaybeUninit};
use std::panic::{self, AssertUnwindSafe};
use std::path::Path;
use std::ptr::{self, NonNull};

use progsim_sys as sys;

use crate::error::{check, check_thread, static_str};
use crate::{
    c_handle, c_level, c_path, c_string, check_version, count_from, not_in_callback, read_triples,
    Axes, CallbackScope, Effect, Effects, Error, Ground, HandleMotion, HandleReaction, Hierarchy,
    Interpolation, Keyframe, LevelStats, Load, Mode, Obstacle, Result, SimulationDef, Status,
    Support,
};

/// A simulation of one [`Hierarchy`]: preview steps at the current level (starting at level
/// 0, at rest), then [`refine`](Self::refine) to finer levels.
///
/// The lifetime `'h` is that of the hierarchy the simulation reads, which the C library
/// borrows: a `Simulation<'h>` from [`Simulation::new`] keeps its `&'h Hierarchy` borrowed,
/// so the hierarchy cannot be dropped first. Scene simulations
/// ([`from_scene`](Self::from_scene), [`from_scene_file`](Self::from_scene_file)) own their
/// hierarchy inside the C library, which destroys it with the simulation; they borrow
/// nothing and are `Simulation<'static>` (see [`hierarchy`](Self::hierarchy)).
///
/// ```compile_fail,E0505
/// # use progsim::{Hierarchy, Simulation, SimulationDef};
/// let hierarchy = Hierarchy::from_file("mesh.obj").unwrap();
/// let sim = Simulation::new(&hierarchy, &SimulationDef::default()).unwrap();
/// drop(hierarchy); // error: `hierarchy` is still borrowed by `sim`
/// sim.current_level();
/// ```
///
/// `Send` but not `Sync`: the C contract lets a simulation move between threads, but calls
/// on it must not overlap (every call, `&self` getters included, rewrites its last-error
/// message), and progress callbacks run on the calling thread. The borrowed hierarchy is
/// only read, which the contract allows from simulations on several threads at once; the
/// simulation never hands out a `&Hierarchy` it borrows, so sending it cannot make two
/// threads call the hierarchy.
///
/// ```compile_fail,E0277
/// fn shared_between_threads<T: Sync>() {}
/// shared_between_threads::<progsim::Simulation<'static>>();
/// ```
pub struct Simulation<'h> {
    raw: NonNull<sys::ps_sim>,
    /// The hierarchy of a scene simulation, owned by the C simulation: never dropped here.
    owned_hierarchy: Option<ManuallyDrop<Hierarchy>>,
    _hierarchy: PhantomData<&'h Hierarchy>,
}

// SAFETY: the C library allows a simulation to move between threads; `!Sync` keeps calls
// from overlapping; the borrowed hierarchy is only read by the C simulation, which the
// contract allows concurrently with calls on the hierarchy from its own thread.
unsafe impl Send for Simulation<'_> {}

impl<'h> Simulation<'h> {
    /// Creates a simulation of `hierarchy` as described by `def`, at level 0 and at rest.
    ///
    /// On a solid's hierarchy ([`Hierarchy::is_solid`]) the body is the finest tet mesh
    /// (`youngs_modulus`, `poisson_ratio` and `density` its material), and `def.effects` must
    /// include [`Effect::Elasticity`](crate::Effect::Elasticity) and no shell effect
    /// (membrane, bending, pressure, strain limit, wind): set them, e.g.
    /// `effects: Effect::Elasticity | Effect::Gravity`. Several levels animate it with VPD
    /// ([`SimulationKind::VolumetricDynamics`](crate::SimulationKind)) in
    /// [`Mode::Dynamic`](crate::Mode).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for a parameter out of range (naming it);
    /// [`Status::InvalidScene`] for a pinned vertex out of range (naming it), or on a solid's
    /// hierarchy for effects without elasticity or with a shell effect (naming it);
    /// [`Status::Unsupported`] for a solid's hierarchy of several levels in
    /// [`Mode::Quasistatic`](crate::Mode) or with pinned vertices.
    pub fn new(hierarchy: &'h Hierarchy, def: &SimulationDef) -> Result<Simulation<'h>> {
        let raw_def = def.to_raw();
        let mut out = ptr::null_mut();
        // SAFETY: live hierarchy; raw_def borrows def.pinned_vertices, alive for the call.
        let status = unsafe { sys::ps_sim_create(hierarchy.handle()?, &raw_def, &mut out) };
        check_thread(status)?;
        Simulation::from_created(out, None)
    }

    /// Takes ownership of a freshly created simulation.
    fn from_created(
        raw: *mut sys::ps_sim,
        owned_hierarchy: Option<ManuallyDrop<Hierarchy>>,
    ) -> Result<Simulation<'h>> {
        let raw = NonNull::new(raw).ok_or_else(|| {
            Error::new(Status::Internal, "the library returned a NULL simulation")
        })?;
        Ok(Simulation { raw, owned_hierarchy, _hierarchy: PhantomData })
    }

    /// The C handle for a call, or [`Status::WrongCallOrder`] inside a progress closure.
    pub(crate) fn handle(&self) -> Result<*mut sys::ps_sim> {
        not_in_callback()?;
        Ok(self.raw.as_ptr())
    }

    /// Ok, or the error of the last failed call on this simulation.
    pub(crate) fn check(&self, status: i32) -> Result<()> {
        // SAFETY: self.raw is a live simulation; the message is copied at once.
        check(status, || unsafe { sys::ps_sim_last_error(self.raw.as_ptr()) })
    }

    /// The hierarchy of a scene simulation (created with [`from_scene`](Self::from_scene) or
    /// [`from_scene_file`](Self::from_scene_file)), borrowed from the simulation. `None` for
    /// a simulation from [`new`](Self::new): use the `&Hierarchy` you created it with.
    pub fn hierarchy(&self) -> Option<&Hierarchy> {
        self.owned_hierarchy.as_deref()
    }

    /// Sets a numeric parameter between steps, by name: any parameter-table name
    /// (`"material.youngs_modulus"` Pa, `"material.thickness"` m, `"simulation.time_step"`
    /// s, `"solver.newton_tolerance"`, …; `progsim params` lists them with units and
    /// ranges) or `"gravity.x"`, `"gravity.y"`, `"gravity.z"` (m/s²), `"pressure"` (Pa, all
    /// bodies).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for an unknown name (the message lists the known ones) or
    /// a value out of range (NaN included); the simulation is then unchanged.
    pub fn set_param(&mut self, name: &str, value: f64) -> Result<()> {
        let raw = self.handle()?;
        let name = c_string(name, "parameter name")?;
        // SAFETY: live simulation, NUL-terminated name.
        let status = unsafe { sys::ps_sim_set_param(raw, name.as_ptr(), value) };
        self.check(status)
    }

    /// Reads a parameter by name (names and units as in [`set_param`](Self::set_param)).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for an unknown name.
    pub fn param(&self, name: &str) -> Result<f64> {
        let raw = self.handle()?;
        let name = c_string(name, "parameter name")?;
        let mut value = 0.0;
        // SAFETY: live simulation, NUL-terminated name, valid out-pointer.
        let status = unsafe { sys::ps_sim_get_param(raw, name.as_ptr(), &mut value) };
        self.check(status)?;
        Ok(value)
    }

    /// Sets a named option by name to one of its values (see [`choices`](crate::choices):
    /// `"material.bending_model"`, `"progressive.proxy_hessian"`, …). Before the first
    /// step, settle or refinement the simulation is rebuilt with it (its kind follows
    /// `"simulation.mode"`); later it applies between steps like [`set_param`](Self::set_param)
    /// (`"progressive.prolongation"` from the next level on).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for an unknown name or value (the message lists the known
    /// ones); the simulation is then unchanged.
    pub fn set_choice(&mut self, name: &str, value: &str) -> Result<()> {
        let raw = self.handle()?;
        let name = c_string(name, "option name")?;
        let value = c_string(value, "option value")?;
        // SAFETY: live simulation, NUL-terminated strings.
        let status = unsafe { sys::ps_sim_set_choice(raw, name.as_ptr(), value.as_ptr()) };
        self.check(status)
    }

    /// The value of a named option (material options: the first body's).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for an unknown name.
    pub fn choice(&self, name: &str) -> Result<&'static str> {
        let raw = self.handle()?;
        let name = c_string(name, "option name")?;
        let mut value = ptr::null();
        // SAFETY: live simulation, NUL-terminated name, valid out-pointer.
        let status = unsafe { sys::ps_sim_get_choice(raw, name.as_ptr(), &mut value) };
        self.check(status)?;
        // SAFETY: on PS_OK the library returned one of its static option strings.
        Ok(unsafe { static_str(value) })
    }

    /// Enables or disables one effect between steps.
    ///
    /// # Errors
    /// Only if the library rejects the effect set (not expected for known effects).
    pub fn set_effect(&mut self, effect: Effect, enabled: bool) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_set_effect(raw, effect.bit(), i32::from(enabled)) };
        self.check(status)
    }

    /// Switches between dynamic and quasistatic stepping between steps (switching to
    /// quasistatic zeroes the velocities).
    ///
    /// # Errors
    /// Inside a progress closure ([`Status::WrongCallOrder`]).
    pub fn set_mode(&mut self, mode: Mode) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_set_mode(raw, mode.to_raw() as i32) };
        self.check(status)
    }

    /// The stepping mode.
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn mode(&self) -> Mode {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut mode = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_get_mode(raw, &mut mode) };
        self.check(status).expect("ps_sim_get_mode fails only on NULL arguments");
        Mode::from_raw(mode as sys::ps_mode).expect("the library returns a known mode")
    }

    /// The enabled effects.
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn effects(&self) -> Effects {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut bits = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_get_effects(raw, &mut bits) };
        self.check(status).expect("ps_sim_get_effects fails only on NULL arguments");
        Effects::from_bits_retain(bits)
    }

    /// The number of handles (scripted vertex groups): 1 for a [`SimulationDef`] with pinned
    /// vertices (handle 0), else 0; a scene's `handles` array otherwise.
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn num_handles(&self) -> usize {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut handles = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_num_handles(raw, &mut handles) };
        self.check(status).expect("ps_sim_num_handles fails only on NULL arguments");
        count_from(handles)
    }

    /// Scripts handle `handle` (0 ≤ handle < [`num_handles`](Self::num_handles)) from the
    /// next step on; see [`HandleMotion`]. Replaces keyframes
    /// ([`set_handle_keyframes`](Self::set_handle_keyframes)).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the handle does not exist; [`Status::InvalidArgument`] for a
    /// zero or non-finite axis.
    pub fn set_handle_motion(&mut self, handle: usize, motion: &HandleMotion) -> Result<()> {
        self.set_motion(sys::ps_sim_set_handle_motion, c_handle(handle)?, motion)
    }

    /// `setter` (ps_sim_set_handle_motion or ps_sim_set_obstacle_motion) on object `index`.
    fn set_motion(
        &mut self,
        setter: MotionSetter,
        index: i32,
        motion: &HandleMotion,
    ) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation; each vector points to 3 doubles alive for the call.
        let status = unsafe {
            setter(
                raw,
                index,
                motion.velocity.as_ptr(),
                motion.axis.as_ptr(),
                motion.center.as_ptr(),
                motion.angular_velocity,
                motion.offset.as_ptr(),
            )
        };
        self.check(status)
    }

    /// Scripts handle `handle` by keyframes from the next step on, interpolated by
    /// `interpolation`: x(t) = c + R(t)(x̄ − c) + T(t) + offset with c and offset those of the
    /// handle's current motion; translations blend componentwise, rotations about one axis by
    /// their angle (a segment may turn several times), about different axes by slerp. Before
    /// the first key its pose, after the last held. Replaces the velocity and angular velocity.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the handle does not exist; [`Status::InvalidArgument`] for no
    /// keys, a NaN/Inf value, a zero axis or times not strictly increasing (the message names
    /// the key). On error the motion is unchanged.
    pub fn set_handle_keyframes(
        &mut self,
        handle: usize,
        keys: &[Keyframe],
        interpolation: Interpolation,
    ) -> Result<()> {
        self.set_keyframes(sys::ps_sim_set_handle_keyframes, c_handle(handle)?, keys, interpolation)
    }

    /// `setter` (ps_sim_set_handle_keyframes or ps_sim_set_obstacle_keyframes) on object `index`.
    fn set_keyframes(
        &mut self,
        setter: KeyframeSetter,
        index: i32,
        keys: &[Keyframe],
        interpolation: Interpolation,
    ) -> Result<()> {
        let raw = self.handle()?;
        let rows: Vec<[f64; 8]> = keys.iter().map(Keyframe::row).collect();
        // SAFETY: live simulation; `rows` holds keys.len() rows of 8 doubles alive for the call.
        let status = unsafe {
            setter(
                raw,
                index,
                rows.as_ptr().cast::<f64>(),
                rows.len(),
                interpolation.to_raw() as i32,
            )
        };
        self.check(status)
    }

    /// Makes handle `handle` prescribe only the coordinates in `axes` from the next step on;
    /// its vertices move freely along the others (a roller: `Axes { x: false, y: false, z: true }`).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the handle does not exist; [`Status::InvalidScene`] for no
    /// axis.
    pub fn set_handle_axes(&mut self, handle: usize, axes: Axes) -> Result<()> {
        let raw = self.handle()?;
        let handle = c_handle(handle)?;
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_set_handle_axes(raw, handle, axes.bits()) };
        self.check(status)
    }

    /// Makes handle `handle` a `support` prescribing the coordinates in `axes` from the next
    /// step on ([`Support::Rotation`]: the group turns with its script and translates freely
    /// along the other coordinates; [`Axes::NONE`] allowed only there).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the handle does not exist; [`Status::InvalidScene`] for no
    /// axis on a position support; [`Status::Unsupported`] for a rotation support on several
    /// levels.
    pub fn set_handle_support(
        &mut self,
        handle: usize,
        support: Support,
        axes: Axes,
    ) -> Result<()> {
        let raw = self.handle()?;
        let handle = c_handle(handle)?;
        // SAFETY: live simulation.
        let status = unsafe {
            sys::ps_sim_set_handle_support(raw, handle, support.to_raw() as i32, axes.bits())
        };
        self.check(status)
    }

    /// The force and moment handle `handle`'s support applied after the last solve on `level`
    /// (∂E/∂x at its prescribed coordinates; in a quasistatic step it balances the loads).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] for a level or handle that does not exist;
    /// [`Status::WrongCallOrder`] before any solve on the level, or on a preview level (its
    /// proxy holds the finest handle vertices and reports no reaction).
    pub fn handle_reaction(&self, level: usize, handle: usize) -> Result<HandleReaction> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let handle = c_handle(handle)?;
        let mut out = MaybeUninit::<sys::ps_handle_reaction>::uninit();
        // SAFETY: live simulation; on PS_OK the library wrote the whole struct.
        let status =
            unsafe { sys::ps_sim_get_handle_reaction(raw, level, handle, out.as_mut_ptr()) };
        self.check(status)?;
        // SAFETY: PS_OK, so the struct is filled.
        Ok(HandleReaction::from(unsafe { out.assume_init() }))
    }

    /// Adds a handle: finest-level `vertices` of body `body` (0 for [`Simulation::new`]), held
    /// at rest until [`set_handle_motion`](Self::set_handle_motion) or
    /// [`set_handle_keyframes`](Self::set_handle_keyframes) scripts them; returns its index.
    /// This rebuilds the simulation, so only before the first step, settle or refinement. On
    /// a hierarchy of several levels handle i must be the hierarchy's vertex group i
    /// ([`HierarchyDef`](crate::HierarchyDef)'s `vertex_group_ids`, or its pinned vertices for
    /// group 0 alone): after [`SimulationDef`]'s pinned vertices (group 0), each call adds the
    /// next group.
    ///
    /// # Errors
    /// [`Status::InvalidScene`] for no vertices or a body or vertex out of range (named);
    /// [`Status::WrongCallOrder`] after a step; [`Status::InvalidArgument`] on several levels
    /// for vertices that are not a vertex group of the hierarchy. Nothing changes on error.
    pub fn add_handle(&mut self, body: usize, vertices: &[i32]) -> Result<usize> {
        let raw = self.handle()?;
        let body = c_body(body)?;
        let mut index = 0;
        // SAFETY: live simulation; `vertices` is alive for the call.
        let status = unsafe {
            sys::ps_sim_add_handle(raw, body, vertices.as_ptr(), vertices.len(), &mut index)
        };
        self.check(status)?;
        Ok(count_from(index))
    }

    /// Adds a handle of the vertices of body `body` inside the axis-aligned box
    /// [`box_min`, `box_max`] (m, boundary included; scene key `"handles"` with a `"box"`),
    /// otherwise as [`add_handle`](Self::add_handle); returns its index. On a solid's hierarchy
    /// of several levels (VPD) every level holds the vertices its box holds there.
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for a non-finite corner or `box_min` above `box_max`;
    /// [`Status::InvalidScene`] for a body out of range or a box that holds no vertex of the
    /// body (or, VPD, of some level: named); [`Status::WrongCallOrder`] after a step. Nothing
    /// changes on error.
    pub fn add_handle_box(
        &mut self,
        body: usize,
        box_min: [f64; 3],
        box_max: [f64; 3],
    ) -> Result<usize> {
        let raw = self.handle()?;
        let body = c_body(body)?;
        let mut index = 0;
        // SAFETY: live simulation; both corners are 3 doubles alive for the call.
        let status = unsafe {
            sys::ps_sim_add_handle_box(raw, body, box_min.as_ptr(), box_max.as_ptr(), &mut index)
        };
        self.check(status)?;
        Ok(count_from(index))
    }

    /// Number of obstacles ([`add_obstacle`](Self::add_obstacle) and the scene's `"obstacles"`).
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn num_obstacles(&self) -> usize {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut obstacles = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_num_obstacles(raw, &mut obstacles) };
        self.check(status).expect("ps_sim_num_obstacles fails only on NULL arguments");
        count_from(obstacles)
    }

    /// Adds an obstacle (see [`Obstacle`]), static until
    /// [`set_obstacle_motion`](Self::set_obstacle_motion) or
    /// [`set_obstacle_keyframes`](Self::set_obstacle_keyframes); returns its index. Needs
    /// [`Effect::Contact`](crate::Effect::Contact). Like [`add_handle`](Self::add_handle), only
    /// before the first step.
    ///
    /// # Errors
    /// [`Status::InvalidMesh`] naming the first bad element; [`Status::Intersecting`] if it
    /// crosses the shell at t = 0 or comes within its contact offset;
    /// [`Status::InvalidScene`] without contact or for a friction out of range;
    /// [`Status::WrongCallOrder`] after a step. Nothing changes on error.
    pub fn add_obstacle(&mut self, obstacle: &Obstacle) -> Result<usize> {
        let raw = self.handle()?;
        let def = obstacle.to_raw();
        let mut index = 0;
        // SAFETY: live simulation; def borrows obstacle's arrays, alive for the call.
        let status = unsafe { sys::ps_sim_add_obstacle(raw, &def, &mut index) };
        self.check(status)?;
        Ok(count_from(index))
    }

    /// As [`set_handle_motion`](Self::set_handle_motion), for obstacle `obstacle` (its rest
    /// positions are those at t = 0).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the obstacle does not exist; [`Status::InvalidArgument`] for
    /// a zero or non-finite axis.
    pub fn set_obstacle_motion(&mut self, obstacle: usize, motion: &HandleMotion) -> Result<()> {
        self.set_motion(sys::ps_sim_set_obstacle_motion, c_obstacle(obstacle)?, motion)
    }

    /// As [`set_handle_keyframes`](Self::set_handle_keyframes), for obstacle `obstacle`;
    /// messages name `obstacles[i].motion.keyframes[k]`.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the obstacle does not exist; otherwise as
    /// [`set_handle_keyframes`](Self::set_handle_keyframes).
    pub fn set_obstacle_keyframes(
        &mut self,
        obstacle: usize,
        keys: &[Keyframe],
        interpolation: Interpolation,
    ) -> Result<()> {
        self.set_keyframes(
            sys::ps_sim_set_obstacle_keyframes,
            c_obstacle(obstacle)?,
            keys,
            interpolation,
        )
    }

    /// Sets the analytic ground (see [`Ground`]) or removes it (`None`). Needs
    /// [`Effect::Contact`](crate::Effect::Contact); allowed between steps.
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for a zero or non-finite normal or height;
    /// [`Status::InvalidScene`] for a friction out of range or without contact;
    /// [`Status::Intersecting`] if the shell is not above it by its contact offset. Nothing
    /// changes on error.
    pub fn set_ground(&mut self, ground: Option<&Ground>) -> Result<()> {
        let raw = self.handle()?;
        let ground_or_default = ground.copied().unwrap_or_default();
        // SAFETY: live simulation; the normal points to 3 doubles alive for the call.
        let status = unsafe {
            sys::ps_sim_set_ground(
                raw,
                i32::from(ground.is_some()),
                ground_or_default.normal.as_ptr(),
                ground_or_default.height,
                ground_or_default.friction,
            )
        };
        self.check(status)
    }

    /// Number of point and line loads ([`add_load`](Self::add_load) and the scene's `"loads"`).
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn num_loads(&self) -> usize {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut loads = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_num_loads(raw, &mut loads) };
        self.check(status).expect("ps_sim_num_loads fails only on NULL arguments");
        count_from(loads)
    }

    /// Adds a dead point or line load from the next step on (see [`Load`]); returns its index
    /// (0, 1, ... in order of addition). Progressive simulations apply it on the finest level's
    /// vertices, through the prolongation on coarse levels.
    ///
    /// # Errors
    /// [`Status::InvalidScene`] naming the load and the problem: no vertices, a vertex or body
    /// out of range, a non-finite value, a zero moment axis, a negative ramp, a group on one
    /// line along the moment's axis. Nothing changes on error.
    pub fn add_load(&mut self, load: &Load) -> Result<usize> {
        let raw = self.handle()?;
        let def = load.to_raw();
        let mut index = 0;
        // SAFETY: live simulation; def borrows load.vertices, alive for the call.
        let status = unsafe { sys::ps_sim_add_load(raw, &def, &mut index) };
        self.check(status)?;
        Ok(count_from(index))
    }

    /// Advances `steps` steps of [`param("simulation.time_step")`](Self::param) seconds at
    /// the current level. Newton trouble does not fail the call: see
    /// [`level_stats`](Self::level_stats).
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] for `steps` = 0 (or above `i32::MAX`);
    /// [`Status::Numerical`] if a step produced non-finite positions.
    pub fn step_preview(&mut self, steps: u32) -> Result<()> {
        let raw = self.handle()?;
        let steps = c_steps(steps)?;
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_step_preview(raw, steps) };
        self.check(status)
    }

    /// As [`step_preview`](Self::step_preview), calling `progress(done, total, phase)` after
    /// each step (`phase` is `"preview"`). Return `true` from `progress` to cancel: the call
    /// then stops after that step and returns [`Status::Cancelled`], the simulation keeping
    /// the state of the last completed step. (Cancelling after the last step changes
    /// nothing: the call has finished.)
    ///
    /// If `progress` panics, the C call is cancelled at once, and the panic resumes once the
    /// C call has returned: it never unwinds through C. The simulation stays usable.
    ///
    /// `progress` must not call progsim (the C library forbids calls from callbacks): such
    /// calls fail with [`Status::WrongCallOrder`], and the getters that return plain values
    /// panic, which cancels as above.
    ///
    /// # Errors
    /// As `step_preview`, and [`Status::Cancelled`].
    pub fn step_preview_with_progress<F>(&mut self, steps: u32, progress: F) -> Result<()>
    where
        F: FnMut(u32, u32, &str) -> bool,
    {
        let steps = c_steps(steps)?;
        // SAFETY: live simulation.
        self.with_progress(progress, |sim| unsafe { sys::ps_sim_step_preview(sim, steps) })
    }

    /// Refines the current level l to l + 1 with the prolongation P^l_{l+1} (PSQ eq. 7), so
    /// that later steps run on the finer level (previews below the finest level).
    ///
    /// A progressive animation ([`SimulationKind::ProgressiveDynamics`](crate::SimulationKind),
    /// or `VolumetricDynamics` for a solid) instead animates level l + 1 over every previewed
    /// step (PD eqs. 5–6), each step predicted from level l's frames
    /// ([`prediction`](Self::prediction)); its frames are then read with
    /// [`frame_positions`](Self::frame_positions).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] at the finest level; [`Status::Intersecting`] when, with contact,
    /// no safe position is found for a vertex split (PSQ §4.4's safe expansion);
    /// [`Status::WrongCallOrder`] for a progressive animation with no preview step. The state
    /// is unchanged on error.
    pub fn refine(&mut self) -> Result<()> {
        let raw = self.handle()?;
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_refine(raw) };
        self.check(status)
    }

    /// Progressive animation only: animates the next level over the previewed steps
    /// `first_step..=last_step` only, so that time windows of a long animation can be refined
    /// apart (on several machines) and joined. The level's frame 0 is the animation's frame
    /// `first_step` ([`DynamicLevelStats::first_step`](crate::DynamicLevelStats)): the coarser
    /// frame refined by PSQ's safe refinement (PD §4.6's vertical warm start) unless it is 0.
    ///
    /// # Errors
    /// As [`refine`](Self::refine); [`Status::InvalidArgument`] for a window outside the
    /// previewed steps (or numbers that do not fit the C ABI) or a simulation that is not a
    /// progressive animation; [`Status::WrongCallOrder`] above a level that is a window;
    /// [`Status::Unsupported`] for a window after frame 0 of a solid under contact.
    pub fn refine_window(&mut self, first_step: u32, last_step: u32) -> Result<()> {
        let raw = self.handle()?;
        let (first, last) = match (i32::try_from(first_step), i32::try_from(last_step)) {
            (Ok(first), Ok(last)) => (first, last),
            _ => {
                return Err(Error::new(
                    Status::InvalidArgument,
                    "the window does not fit the C ABI",
                ))
            }
        };
        // SAFETY: live simulation.
        let status = unsafe { sys::ps_sim_refine_window(raw, first, last) };
        self.check(status)
    }

    /// Solves again at the current time and loads until the level is at equilibrium or
    /// `max_solves` solves were made; returns whether equilibrium was reached.
    ///
    /// # Errors
    /// [`Status::InvalidArgument`] if `max_solves` is 0 or does not fit the C ABI.
    pub fn settle(&mut self, max_solves: u32) -> Result<bool> {
        let raw = self.handle()?;
        let max_solves = i32::try_from(max_solves).map_err(|_| {
            Error::new(Status::InvalidArgument, "max_solves does not fit the C ABI")
        })?;
        let mut reached = 0i32;
        // SAFETY: live simulation; `reached` outlives the call.
        let status = unsafe { sys::ps_sim_settle(raw, max_solves, &mut reached) };
        self.check(status)?;
        Ok(reached != 0)
    }

    /// As [`refine`](Self::refine), reporting progress as
    /// [`step_preview_with_progress`](Self::step_preview_with_progress) does (phase
    /// `"refine"`; a progressive animation reports after each step, `total` being the
    /// previewed steps, and discards the level when cancelled).
    ///
    /// # Errors
    /// As `refine`, and [`Status::Cancelled`].
    pub fn refine_with_progress<F>(&mut self, progress: F) -> Result<()>
    where
        F: FnMut(u32, u32, &str) -> bool,
    {
        // SAFETY: live simulation.
        self.with_progress(progress, |sim| unsafe { sys::ps_sim_refine(sim) })
    }

    /// Installs `progress` as the C progress callback for the duration of `call`, then
    /// removes it. A panic in `progress` cancels the call and is resumed afterwards.
    fn with_progress<F>(
        &mut self,
        progress: F,
        call: impl FnOnce(*mut sys::ps_sim) -> i32,
    ) -> Result<()>
    where
        F: FnMut(u32, u32, &str) -> bool,
    {
        let mut state = ProgressState { callback: progress, panic: None };
        let sim = self.handle()?;
        // SAFETY: `state` outlives the call below, after which the callback is removed; the
        // trampoline matches ps_progress_fn and never unwinds.
        let installed = unsafe {
            sys::ps_sim_set_progress_callback(
                sim,
                Some(progress_trampoline::<F>),
                ptr::addr_of_mut!(state).cast::<c_void>(),
            )
        };
        self.check(installed)?;
        let status = call(sim);
        // Copy the message first: the next call on the handle clears it.
        let result = self.check(status);
        // SAFETY: removing the callback; `state` is no longer referenced afterwards.
        let removed = unsafe { sys::ps_sim_set_progress_callback(sim, None, ptr::null_mut()) };
        if let Some(payload) = state.panic.take() {
            panic::resume_unwind(payload);
        }
        result?;
        self.check(removed)
    }

    /// The current level (0 = coarsest).
    ///
    /// # Panics
    /// Inside a progress closure (the C library forbids calls from callbacks).
    pub fn current_level(&self) -> usize {
        let raw = self.handle().unwrap_or_else(|error| panic!("{error}"));
        let mut level = 0;
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_current_level(raw, &mut level) };
        self.check(status).expect("ps_sim_current_level fails only on NULL arguments");
        count_from(level)
    }

    /// The positions of `level`, one `[x, y, z]` (m) per vertex of that level: the current
    /// state for the current level, the state when it was refined for a coarser one, the
    /// current state prolonged to it for a finer one.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn positions(&self, level: usize) -> Result<Vec<[f64; 3]>> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        read_triples(|out, capacity, count| {
            // SAFETY: live simulation; out is NULL or valid for `capacity` doubles.
            let status = unsafe { sys::ps_sim_get_positions(raw, level, out, capacity, count) };
            self.check(status)
        })
    }

    /// Writes `level`'s current mesh ([`positions`](Self::positions) and the level's faces)
    /// to `path`; the extension picks the format (`.obj`, `.off`, `.ply`).
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist; [`Status::Io`] naming the path if
    /// it cannot be written.
    pub fn write_mesh(&self, level: usize, path: impl AsRef<Path>) -> Result<()> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let path = c_path(path.as_ref())?;
        // SAFETY: live simulation, NUL-terminated path.
        let status = unsafe { sys::ps_sim_write_mesh(raw, level, path.as_ptr()) };
        self.check(status)
    }

    /// The statistics of `level`, accumulated over every step taken at it.
    ///
    /// # Errors
    /// [`Status::OutOfRange`] if the level does not exist.
    pub fn level_stats(&self, level: usize) -> Result<LevelStats> {
        let raw = self.handle()?;
        let level = c_level(level)?;
        let mut stats = MaybeUninit::<sys::ps_level_stats>::uninit();
        // SAFETY: live simulation; on PS_OK the library wrote the whole struct.
        let status = unsafe { sys::ps_sim_get_level_stats(raw, level, stats.as_mut_ptr()) };
        self.check(status)?;
        // SAFETY: PS_OK, so the struct is filled.
        Ok(LevelStats::from(unsafe { stats.assume_init() }))
    }

    /// The C handle, for calls through `progsim-sys`. Borrowed: valid while `self` is; do
    /// not destroy it, and do not install a progress callback through it.
    pub fn as_ptr(&self) -> *const sys::ps_sim {
        self.raw.as_ptr()
    }
}

impl Simulation<'static> {
    /// Creates a simulation from a JSON scene (format: `scenes/README.md`; `//` comments
    /// allowed). Its bodies' meshes form the hierarchy, which the simulation owns (see
    /// [`hierarchy`](Self::hierarchy)). Relative mesh paths start from `base_dir` (`None`:
    /// the current directory).
    ///
    /// # Errors
    /// [`Status::InvalidScene`] with the JSON path of the problem (unknown key such as a
    /// typo, missing field, value out of range, malformed JSON); [`Status::InvalidMesh`];
    /// [`Status::Io`] for an unreadable mesh file.
    pub fn from_scene(json: &str, base_dir: Option<&Path>) -> Result<Simulation<'static>> {
        check_version()?;
        let json = c_string(json, "scene JSON")?;
        let base_dir = base_dir.map(c_path).transpose()?;
        let mut out = ptr::null_mut();
        // SAFETY: NUL-terminated strings (base_dir nullable) alive for the call.
        let status = unsafe {
            sys::ps_sim_create_from_scene(
                json.as_ptr(),
                base_dir.as_ref().map_or(ptr::null(), |dir| dir.as_ptr()),
                &mut out,
            )
        };
        check_thread(status)?;
        Simulation::with_own_hierarchy(out)
    }

    /// As [`from_scene`](Self::from_scene), reading the scene from the file at `path`;
    /// relative mesh paths start from the file's directory.
    ///
    /// # Errors
    /// As `from_scene`, and [`Status::Io`] if the file cannot be read.
    pub fn from_scene_file(path: impl AsRef<Path>) -> Result<Simulation<'static>> {
        check_version()?;
        let path = c_path(path.as_ref())?;
        let mut out = ptr::null_mut();
        // SAFETY: NUL-terminated path alive for the call.
        let status = unsafe { sys::ps_sim_create_from_scene_file(path.as_ptr(), &mut out) };
        check_thread(status)?;
        Simulation::with_own_hierarchy(out)
    }

    /// Takes ownership of a fresh scene simulation and wraps the hierarchy it owns.
    fn with_own_hierarchy(raw: *mut sys::ps_sim) -> Result<Simulation<'static>> {
        let mut sim = Simulation::from_created(raw, None)?;
        let mut hierarchy = ptr::null();
        // SAFETY: live simulation, valid out-pointer.
        let status = unsafe { sys::ps_sim_hierarchy(sim.raw.as_ptr(), &mut hierarchy) };
        sim.check(status)?;
        let hierarchy = NonNull::new(hierarchy.cast_mut()).ok_or_else(|| {
            Error::new(Status::Internal, "the scene simulation has a NULL hierarchy")
        })?;
        // The C simulation owns and destroys it; only const calls reach it through Hierarchy.
        sim.owned_hierarchy = Some(ManuallyDrop::new(Hierarchy::borrowed_from(hierarchy)));
        Ok(sim)
    }
}

impl Drop for Simulation<'_> {
    fn drop(&mut self) {
        // SAFETY: owned handle, destroyed once; it destroys a scene's hierarchy with it.
        unsafe { sys::ps_sim_destroy(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Simulation<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Simulation")
            .field("raw", &self.raw)
            .field("owns_hierarchy", &self.owned_hierarchy.is_some())
            .finish()
    }
}

/// A step count as the C `int32_t`.
/// The C setters of a handle's or an obstacle's velocity motion.
type MotionSetter = unsafe extern "C" fn(
    *mut sys::ps_sim,
    i32,
    *const f64,
    *const f64,
    *const f64,
    f64,
    *const f64,
) -> i32;

/// The C setters of a handle's or an obstacle's keyframes.
type KeyframeSetter = unsafe extern "C" fn(*mut sys::ps_sim, i32, *const f64, usize, i32) -> i32;

fn c_obstacle(obstacle: usize) -> Result<i32> {
    i32::try_from(obstacle)
        .map_err(|_| Error::new(Status::OutOfRange, format!("obstacle {obstacle} does not exist")))
}

fn c_steps(steps: u32) -> Result<i32> {
    i32::try_from(steps).map_err(|_| {
        Error::new(Status::InvalidArgument, format!("steps = {steps} exceeds i32::MAX"))
    })
}

/// What the progress trampoline reaches through `user_data`.
struct ProgressState<F> {
    callback: F,
    /// The payload of a panic in `callback`, resumed after the C call returns.
    panic: Option<Box<dyn Any + Send + 'static>>,
}

/// The `ps_progress_fn` calling a Rust closure. Never unwinds into C: a panic is caught,
/// stored and answered with "cancel".
unsafe extern "C" fn progress_trampoline<F>(
    user_data: *mut c_void,
    done: i32,
    total: i32,
    phase: *const c_char,
) -> i32
where
    F: FnMut(u32, u32, &str) -> bool,
{
    // SAFETY: user_data is the ProgressState<F> installed by with_progress, alive and not
    // otherwise accessed during the C call that invokes us (on the same thread).
    let state = unsafe { &mut *user_data.cast::<ProgressState<F>>() };
    if state.panic.is_some() {
        return 1;
    }
    let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
        let _scope = CallbackScope::enter();
        let phase = if phase.is_null() {
            Default::default()
        } else {
            // SAFETY: the library passes a NUL-terminated static phase name.
            unsafe { CStr::from_ptr(phase) }.to_string_lossy()
        };
        (state.callback)(count_u32(done), count_u32(total), &phase)
    }));
    match outcome {
        Ok(cancel) => i32::from(cancel),
        Err(payload) => {
            state.panic = Some(payload);
            1
        }
    }
}

/// A C work-unit count as u32 (negative values, which the C side never gives, read as 0).
fn count_u32(value: i32) -> u32 {
    u32::try_from(value).unwrap_or(0)
}

/// A body index as the C ABI takes it, or [`Status::InvalidScene`].
fn c_body(body: usize) -> Result<i32> {
    i32::try_from(body)
        .map_err(|_| Error::new(Status::InvalidScene, format!("body index {body} does not exist")))
}
