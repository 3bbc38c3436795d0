//! Plain data: how to build hierarchies and simulations, effects, handle motions, statistics.

use std::fmt;
use std::mem::MaybeUninit;
use std::ops::BitOr;

use progsim_sys as sys;

use crate::{Error, Prediction, Result, Status};

/// How to build a [`Hierarchy`](crate::Hierarchy). The default (no coarse levels) gives one
/// level: the input mesh itself. [`Default`] gives the library's defaults (from
/// `ps_hierarchy_def_init()`); change fields with struct-update syntax:
///
/// ```
/// # use progsim::HierarchyDef;
/// let def = HierarchyDef { coarse_vertex_counts: vec![26], ..HierarchyDef::default() };
/// assert_eq!((def.tet_size_factor, def.tet_cell_size), (0.6, 0.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct HierarchyDef {
    /// Vertex count of each level below the finest (distinct, each at least 4 and below the
    /// mesh's; any order). Empty: a single level.
    pub coarse_vertex_counts: Vec<i32>,
    /// Vertices a simulation will pin ([`SimulationDef`]'s pinned vertices): vertex group 0,
    /// kept on every level at their rest positions. A progressive simulation's pins must be
    /// exactly these.
    pub pinned_vertices: Vec<i32>,
    /// Several vertex groups instead of `pinned_vertices` (not both): per vertex of the mesh
    /// its group, −1 for none, groups numbered 0, 1, ... without gaps; empty: none. Each is kept
    /// on every level; a progressive simulation's handle i must be group i (the pinned
    /// vertices group 0, then [`Simulation::add_handle`](crate::Simulation::add_handle) the
    /// next) (`ps_hierarchy_def.vertex_group_ids`).
    pub vertex_group_ids: Vec<i32>,
    /// Contact offset ξ, m, ≥ 0; default 0. Coarse levels never cross themselves; with the
    /// offset a contact simulation will use (half the shell thickness), no collapse also brings
    /// a vertex and a face, or two edges, within 2ξ (`ps_hierarchy_def.contact_offset`).
    pub contact_offset: f64,
    /// Solids only: each coarse level is tetrahedralized with tets and boundary faces about
    /// this many times its surface's mean edge length (m/m), in (0, 100]; default 0.6
    /// (`ps_hierarchy_def.tet_size_factor`). Shells ignore it.
    pub tet_size_factor: f64,
    /// Solids from a closed surface only: the largest tet circumradius of the finest level, m,
    /// ≥ 0; default 0 = the surface's bounding-box diagonal / 20
    /// (`ps_hierarchy_def.tet_cell_size`). The tet count grows like (size / tet_cell_size)³.
    pub tet_cell_size: f64,
}

/// The C defaults, filled by `ps_hierarchy_def_init()`.
fn raw_hierarchy_def() -> sys::ps_hierarchy_def {
    let mut raw = MaybeUninit::<sys::ps_hierarchy_def>::uninit();
    // SAFETY: ps_hierarchy_def_init() fills every field of a non-NULL def.
    unsafe {
        sys::ps_hierarchy_def_init(raw.as_mut_ptr());
        raw.assume_init()
    }
}

impl Default for HierarchyDef {
    fn default() -> HierarchyDef {
        let raw = raw_hierarchy_def();
        HierarchyDef {
            coarse_vertex_counts: Vec::new(),
            pinned_vertices: Vec::new(),
            vertex_group_ids: Vec::new(),
            contact_offset: raw.contact_offset,
            tet_size_factor: raw.tet_size_factor,
            tet_cell_size: raw.tet_cell_size,
        }
    }
}

impl HierarchyDef {
    /// The C def borrowing `self`'s vectors: valid while `self` is.
    pub(crate) fn to_raw(&self) -> Result<sys::ps_hierarchy_def> {
        let mut raw = raw_hierarchy_def();
        raw.num_coarse_levels = i32::try_from(self.coarse_vertex_counts.len()).map_err(|_| {
            Error::new(Status::InvalidArgument, "too many coarse levels for the C ABI")
        })?;
        if !self.coarse_vertex_counts.is_empty() {
            raw.coarse_vertex_counts = self.coarse_vertex_counts.as_ptr();
        }
        if !self.pinned_vertices.is_empty() {
            raw.pinned_vertices = self.pinned_vertices.as_ptr();
            raw.num_pinned_vertices = self.pinned_vertices.len();
        }
        if !self.vertex_group_ids.is_empty() {
            raw.vertex_group_ids = self.vertex_group_ids.as_ptr();
            raw.num_vertex_group_ids = self.vertex_group_ids.len();
        }
        raw.contact_offset = self.contact_offset;
        raw.tet_size_factor = self.tet_size_factor;
        raw.tet_cell_size = self.tet_cell_size;
        Ok(raw)
    }
}

/// How steps advance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Implicit Euler with inertia (`PS_MODE_DYNAMIC`).
    #[default]
    Dynamic,
    /// Each step minimises the potential energy at its loads (`PS_MODE_QUASISTATIC`).
    Quasistatic,
}

impl Mode {
    pub(crate) fn to_raw(self) -> sys::ps_mode {
        match self {
            Mode::Dynamic => sys::PS_MODE_DYNAMIC,
            Mode::Quasistatic => sys::PS_MODE_QUASISTATIC,
        }
    }

    pub(crate) fn from_raw(raw: sys::ps_mode) -> Option<Mode> {
        match raw {
            sys::PS_MODE_DYNAMIC => Some(Mode::Dynamic),
            sys::PS_MODE_QUASISTATIC => Some(Mode::Quasistatic),
            _ => None,
        }
    }
}

/// One physical effect; only enabled effects cost anything.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Neo-Hookean membrane stretching.
    Membrane,
    /// Discrete hinge bending.
    Bending,
    /// Uniform gravity (see [`SimulationDef::gravity`]).
    Gravity,
    /// Uniform inner pressure of closed meshes (see [`SimulationDef::pressure`]).
    Pressure,
    /// IPC barrier self-contact with CCD: configurations never intersect.
    Contact,
    /// Coulomb friction on contacts (see [`SimulationDef::friction`]).
    Friction,
    /// Barrier keeping membrane stretches below [`SimulationDef::strain_limit`].
    StrainLimit,
    /// Aerodynamic drag and lift of [`SimulationDef::wind_velocity`] on every face (dynamic
    /// simulations only).
    Wind,
    /// Hyperelastic energy of the tets of volumetric bodies.
    Elasticity,
}

impl Effect {
    /// Every effect, in bit order.
    pub const ALL: [Effect; 9] = [
        Effect::Membrane,
        Effect::Bending,
        Effect::Gravity,
        Effect::Pressure,
        Effect::Contact,
        Effect::Friction,
        Effect::StrainLimit,
        Effect::Wind,
        Effect::Elasticity,
    ];

    /// The C `ps_effect` bit of this effect.
    pub fn bit(self) -> u32 {
        match self {
            Effect::Membrane => sys::PS_EFFECT_MEMBRANE,
            Effect::Bending => sys::PS_EFFECT_BENDING,
            Effect::Gravity => sys::PS_EFFECT_GRAVITY,
            Effect::Pressure => sys::PS_EFFECT_PRESSURE,
            Effect::Contact => sys::PS_EFFECT_CONTACT,
            Effect::Friction => sys::PS_EFFECT_FRICTION,
            Effect::StrainLimit => sys::PS_EFFECT_STRAIN_LIMIT,
            Effect::Wind => sys::PS_EFFECT_WIND,
            Effect::Elasticity => sys::PS_EFFECT_ELASTICITY,
        }
    }
}

/// A set of [`Effect`]s (the C `ps_effect` bits). Build with `|`:
/// `Effect::Membrane | Effect::Gravity`.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Effects(u32);

impl Effects {
    /// No effect at all.
    pub const fn empty() -> Effects {
        Effects(0)
    }

    /// Every effect this binding knows.
    pub fn all() -> Effects {
        Effect::ALL.into_iter().collect()
    }

    /// The set with exactly these bits, including bits this binding does not know (a newer
    /// library's effects), which the library rejects if it does not know them either.
    pub const fn from_bits_retain(bits: u32) -> Effects {
        Effects(bits)
    }

    /// The C `ps_effect` bits.
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// Whether `effect` is in the set.
    pub fn contains(self, effect: Effect) -> bool {
        self.0 & effect.bit() != 0
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The set with `effect` added.
    #[must_use]
    pub fn with(self, effect: Effect) -> Effects {
        Effects(self.0 | effect.bit())
    }

    /// The set with `effect` removed.
    #[must_use]
    pub fn without(self, effect: Effect) -> Effects {
        Effects(self.0 & !effect.bit())
    }

    /// Adds (`enabled`) or removes `effect`.
    pub fn set(&mut self, effect: Effect, enabled: bool) {
        *self = if enabled { self.with(effect) } else { self.without(effect) };
    }

    /// The known effects in the set, in bit order.
    pub fn iter(self) -> impl Iterator<Item = Effect> {
        Effect::ALL.into_iter().filter(move |effect| self.contains(*effect))
    }
}

impl fmt::Debug for Effects {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut set = f.debug_set();
        set.entries(self.iter());
        let unknown = self.0 & !Effects::all().0;
        if unknown != 0 {
            set.entry(&format_args!("{unknown:#x}"));
        }
        set.finish()
    }
}

impl From<Effect> for Effects {
    fn from(effect: Effect) -> Effects {
        Effects(effect.bit())
    }
}

impl FromIterator<Effect> for Effects {
    fn from_iter<I: IntoIterator<Item = Effect>>(effects: I) -> Effects {
        effects.into_iter().fold(Effects::empty(), Effects::with)
    }
}

impl BitOr for Effect {
    type Output = Effects;
    fn bitor(self, other: Effect) -> Effects {
        Effects::from(self).with(other)
    }
}

impl BitOr<Effect> for Effects {
    type Output = Effects;
    fn bitor(self, other: Effect) -> Effects {
        self.with(other)
    }
}

impl BitOr for Effects {
    type Output = Effects;
    fn bitor(self, other: Effects) -> Effects {
        Effects(self.0 | other.0)
    }
}

/// A simulation described in code, for [`Simulation::new`](crate::Simulation::new).
///
/// [`Default`] gives the library's defaults (from `ps_sim_def_init()`, which follows the
/// parameter table: `progsim params` prints it). Change fields with struct-update syntax:
///
/// ```
/// # use progsim::{Effect, SimulationDef};
/// let def = SimulationDef {
///     pinned_vertices: vec![420, 440],
///     gravity: [0.0, 0.0, -9.81],
///     effects: Effect::Membrane | Effect::Gravity,
///     ..SimulationDef::default()
/// };
/// assert_eq!(def.time_step, 0.01);
/// ```
///
/// Ranges are checked when the simulation is created ([`Status::InvalidArgument`] naming
/// the parameter). The C def's CLI-only fields (`simulation_duration`,
/// `simulation_output_every`) keep their defaults: a binding steps explicitly.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulationDef {
    /// Time step h, s, in (0, 100]; default 0.01 (`simulation.time_step`).
    pub time_step: f64,
    /// Gravity grows linearly from 0 to its full value over this time, s, in [0, 1e7]; default
    /// 0 = full gravity at once (`simulation.gravity_ramp`): quasistatic self-weight in load
    /// steps, like a body's pressure ramp.
    pub gravity_ramp: f64,
    /// Young's modulus E, Pa, in (0, 1e13]; default 1e6 (`material.youngs_modulus`).
    pub youngs_modulus: f64,
    /// Young's modulus of the bending term alone, Pa, in [0, 1e13]; default 0 = `youngs_modulus`
    /// (`material.bending_youngs_modulus`).
    pub bending_youngs_modulus: f64,
    /// Poisson ratio ν, dimensionless, in (−1, 0.5); default 0.3 (`material.poisson_ratio`).
    pub poisson_ratio: f64,
    /// Shell thickness, m, in (0, 10]; default 1e-3 (`material.thickness`).
    pub thickness: f64,
    /// Volumetric density ρ, kg/m³, in (0, 1e6]; default 200 (`material.density`).
    pub density: f64,
    /// Coulomb friction coefficient μ in [0, 10]; default 0 (`material.friction`).
    pub friction: f64,
    /// Largest membrane stretch, 0 (none) or in (1, 100]; default 0 (`material.strain_limit`).
    pub strain_limit: f64,
    /// Contact activation gap d̂, m, in (0, 10]; default 1e-3 (`contact.dhat`).
    pub contact_dhat: f64,
    /// Barrier stiffness κ, N/m³, ≥ 0; default 0 = adaptive (`contact.stiffness`).
    pub contact_stiffness: f64,
    /// Friction smoothing speed ε_v, m/s, in (0, 1e3]; default 1e-3
    /// (`contact.friction_velocity`).
    pub contact_friction_velocity: f64,
    /// A progressive simulation may start from a finest rest shape that crosses itself (safe
    /// refinement separates it level by level); default false: such a simulation is refused
    /// with [`Status::Intersecting`] naming a crossing pair (`contact.crossing_start`).
    pub contact_crossing_start: bool,
    /// Newton stops when ‖p‖∞ / s < tolerance · bounding-box diagonal (s = h for dynamics,
    /// 1 for quasistatics); dimensionless, in (0, 1]; default 1e-5
    /// (`solver.newton_tolerance`).
    pub newton_tolerance: f64,
    /// Cap on Newton iterations per step, ≥ 1; default 100
    /// (`solver.max_newton_iterations`). Hitting it is reported in [`LevelStats`], not an
    /// error.
    pub max_newton_iterations: i32,
    /// CG iterations refining each projected Newton step against the exact Hessian, ≥ 0;
    /// default 0 = off (`solver.max_cg_iterations`). Faster on soft twisting cloth, slower
    /// on stiff shells; never used in the coarse levels' proxy solves.
    pub max_cg_iterations: i32,
    /// Lengthen whole Newton steps whose energy fell much more than predicted, doubling the
    /// step while the energy falls and CCD allows; default true
    /// (`solver.line_search_extrapolation`). False for comparison runs.
    pub line_search_extrapolation: bool,
    /// Weight w of a progressive animation's consistency penalty w/(2h²)‖x − P(x_coarser)‖²_M
    /// pulling each finer level toward the prolonged coarser frame (VPD eq. 4; 1 weighs it
    /// like the inertia), in [0, 1e12]; default 0 = off (`progressive.consistency_weight`).
    pub consistency_weight: f64,
    /// A progressive animation's Galerkin proxy Hessian is reassembled once the finest state has
    /// moved this many mean finest edge lengths (net of its mean translation) or Newton
    /// contracts slowly, in [0, 1e6]; default 0.5; 0 = every Newton iteration
    /// (`progressive.galerkin_refresh`).
    pub galerkin_refresh: f64,
    /// PSQ's Newton iterations per preview step on a coarse level (PSQ §4.5), ≥ 1; default 8
    /// (`progressive.preview_iterations`).
    pub preview_iterations: i32,
    /// Tolerance of preview solves and of a preview level being at rest, in [0, 1]; default 0 =
    /// [`newton_tolerance`](Self::newton_tolerance) (`progressive.preview_tolerance`).
    pub preview_tolerance: f64,
    /// Quasistatic steps add PSQ eq. 1's proximal term on every level and in the direct
    /// baseline, keeping free bodies solvable; default false (`progressive.proximal`).
    pub proximal: bool,
    /// How steps advance; default [`Mode::Dynamic`] (on several levels: a progressive
    /// animation).
    pub mode: Mode,
    /// How a progressive animation's finer levels predict their steps; default
    /// [`Prediction::VelocityOnly`].
    pub prediction: Prediction,
    /// Enabled effects; default membrane, bending and gravity.
    pub effects: Effects,
    /// Gravity, m/s², `[gx, gy, gz]`; default `[0, -9.81, 0]`. Used while
    /// [`Effect::Gravity`] is enabled.
    pub gravity: [f64; 3],
    /// Inner pressure, Pa; default 0. Used while [`Effect::Pressure`] is enabled.
    pub pressure: f64,
    /// Finest-level vertex indices held still; they form handle 0 (see
    /// [`Simulation::set_handle_motion`](crate::Simulation::set_handle_motion)). Default:
    /// none, and then the simulation has no handle.
    pub pinned_vertices: Vec<i32>,
    /// The steady wind, m/s, `[wx, wy, wz]`; default zero (still air: drag only). Used while
    /// [`Effect::Wind`] is enabled: per face, drag ½ρC_dA|u·n|(u·n)n and lift across the
    /// relative wind u (scenes/README.md, "Wind").
    pub wind_velocity: [f64; 3],
    /// Gusts: `[time s, wx, wy, wz m/s]` rows at increasing times, the wind linear between them
    /// and held outside them; they replace `wind_velocity`. Default: none.
    pub wind_keyframes: Vec<[f64; 4]>,
    /// Air density ρ, kg/m³, in (0, 1e4]; default 1.2 (`wind.density`).
    pub wind_density: f64,
    /// Drag coefficient C_d of each face, in [0, 100]; default 1.2 (`wind.drag`).
    pub wind_drag: f64,
    /// Lift coefficient C_L of each face, in [0, 100]; default 0 = no lift (`wind.lift`).
    pub wind_lift: f64,
}

/// The C defaults, filled by `ps_sim_def_init()`.
fn raw_sim_def() -> sys::ps_sim_def {
    let mut raw = MaybeUninit::<sys::ps_sim_def>::uninit();
    // SAFETY: ps_sim_def_init() fills every field of a non-NULL def.
    unsafe {
        sys::ps_sim_def_init(raw.as_mut_ptr());
        raw.assume_init()
    }
}

impl Default for SimulationDef {
    fn default() -> SimulationDef {
        let raw = raw_sim_def();
        SimulationDef {
            time_step: raw.simulation_time_step,
            gravity_ramp: raw.simulation_gravity_ramp,
            youngs_modulus: raw.material_youngs_modulus,
            bending_youngs_modulus: raw.material_bending_youngs_modulus,
            poisson_ratio: raw.material_poisson_ratio,
            thickness: raw.material_thickness,
            density: raw.material_density,
            friction: raw.material_friction,
            strain_limit: raw.material_strain_limit,
            contact_dhat: raw.contact_dhat,
            contact_stiffness: raw.contact_stiffness,
            contact_friction_velocity: raw.contact_friction_velocity,
            contact_crossing_start: raw.contact_crossing_start != 0,
            newton_tolerance: raw.solver_newton_tolerance,
            max_newton_iterations: raw.solver_max_newton_iterations,
            max_cg_iterations: raw.solver_max_cg_iterations,
            line_search_extrapolation: raw.solver_line_search_extrapolation != 0,
            consistency_weight: raw.progressive_consistency_weight,
            galerkin_refresh: raw.progressive_galerkin_refresh,
            preview_iterations: raw.progressive_preview_iterations,
            preview_tolerance: raw.progressive_preview_tolerance,
            proximal: raw.progressive_proximal != 0,
            mode: Mode::from_raw(raw.mode).unwrap_or_default(),
            prediction: Prediction::from_raw(raw.prediction).unwrap_or_default(),
            effects: Effects::from_bits_retain(raw.effects),
            gravity: raw.gravity,
            pressure: raw.pressure,
            pinned_vertices: Vec::new(),
            wind_velocity: raw.wind_velocity,
            wind_keyframes: Vec::new(),
            wind_density: raw.wind_density,
            wind_drag: raw.wind_drag,
            wind_lift: raw.wind_lift,
        }
    }
}

impl SimulationDef {
    /// The library's defaults (same as [`Default::default`]).
    pub fn new() -> SimulationDef {
        SimulationDef::default()
    }

    /// The C def borrowing `self.pinned_vertices` and `self.wind_keyframes`: valid while `self`
    /// is.
    pub(crate) fn to_raw(&self) -> sys::ps_sim_def {
        let mut raw = raw_sim_def();
        raw.simulation_time_step = self.time_step;
        raw.simulation_gravity_ramp = self.gravity_ramp;
        raw.material_youngs_modulus = self.youngs_modulus;
        raw.material_bending_youngs_modulus = self.bending_youngs_modulus;
        raw.material_poisson_ratio = self.poisson_ratio;
        raw.material_thickness = self.thickness;
        raw.material_density = self.density;
        raw.material_friction = self.friction;
        raw.material_strain_limit = self.strain_limit;
        raw.contact_dhat = self.contact_dhat;
        raw.contact_stiffness = self.contact_stiffness;
        raw.contact_friction_velocity = self.contact_friction_velocity;
        raw.contact_crossing_start = i32::from(self.contact_crossing_start);
        raw.solver_newton_tolerance = self.newton_tolerance;
        raw.solver_max_newton_iterations = self.max_newton_iterations;
        raw.solver_max_cg_iterations = self.max_cg_iterations;
        raw.solver_line_search_extrapolation = i32::from(self.line_search_extrapolation);
        raw.progressive_consistency_weight = self.consistency_weight;
        raw.progressive_galerkin_refresh = self.galerkin_refresh;
        raw.progressive_preview_iterations = self.preview_iterations;
        raw.progressive_preview_tolerance = self.preview_tolerance;
        raw.progressive_proximal = i32::from(self.proximal);
        raw.mode = self.mode.to_raw();
        raw.prediction = self.prediction.to_raw();
        raw.effects = self.effects.bits();
        raw.gravity = self.gravity;
        raw.pressure = self.pressure;
        if !self.pinned_vertices.is_empty() {
            raw.pinned_vertices = self.pinned_vertices.as_ptr();
            raw.num_pinned_vertices = self.pinned_vertices.len();
        }
        raw.wind_velocity = self.wind_velocity;
        raw.wind_density = self.wind_density;
        raw.wind_drag = self.wind_drag;
        raw.wind_lift = self.wind_lift;
        if !self.wind_keyframes.is_empty() {
            raw.wind_keyframes = self.wind_keyframes.as_ptr().cast::<f64>();
            raw.num_wind_keyframes = self.wind_keyframes.len();
        }
        raw
    }
}

/// A rigid script for a handle's vertices, from the next step on:
/// x(t) = c + R(ω t)(x̄ − c) + v t + offset, with t the simulated time and x̄ the rest
/// position. The default holds the vertices at rest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandleMotion {
    /// v, m/s; default zero.
    pub velocity: [f64; 3],
    /// Rotation axis (any non-zero length; normalised by the library); default +z.
    pub axis: [f64; 3],
    /// c, the point the rotation axis passes through, m; default the origin.
    pub center: [f64; 3],
    /// ω, rad/s; default 0.
    pub angular_velocity: f64,
    /// A translation added on top (what a designer drags), m; default zero.
    pub offset: [f64; 3],
}

impl Default for HandleMotion {
    fn default() -> HandleMotion {
        HandleMotion {
            velocity: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            center: [0.0; 3],
            angular_velocity: 0.0,
            offset: [0.0; 3],
        }
    }
}

/// One key of keyframed handle motion ([`Simulation::set_handle_keyframes`]): the pose at
/// `time`, x = c + R(x̄ − c) + T + offset with R the rotation by `angle` about `axis` through the
/// handle motion's centre c.
///
/// [`Simulation::set_handle_keyframes`]: crate::Simulation::set_handle_keyframes
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Keyframe {
    /// s; strictly increasing from key to key.
    pub time: f64,
    /// T, m; default zero.
    pub translation: [f64; 3],
    /// Rotation axis (any non-zero length); default +z.
    pub axis: [f64; 3],
    /// Rotation about `axis`, rad (right-handed); default 0.
    pub angle: f64,
}

impl Default for Keyframe {
    fn default() -> Keyframe {
        Keyframe { time: 0.0, translation: [0.0; 3], axis: [0.0, 0.0, 1.0], angle: 0.0 }
    }
}

impl Keyframe {
    /// The row (time, tx, ty, tz, ax, ay, az, angle) of `ps_sim_set_handle_keyframes`.
    pub(crate) fn row(&self) -> [f64; 8] {
        let [tx, ty, tz] = self.translation;
        let [ax, ay, az] = self.axis;
        [self.time, tx, ty, tz, ax, ay, az, self.angle]
    }
}

/// How keyframed motion moves between two keys (s ∈ [0, 1) the segment's parameter).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Interpolation {
    /// A step: the earlier key's pose until the next key (`PS_INTERPOLATION_HOLD`).
    Hold,
    /// Uniformly in time (`PS_INTERPOLATION_LINEAR`, the default).
    #[default]
    Linear,
    /// Smoothstep 3s² − 2s³: zero velocity at every key (`PS_INTERPOLATION_SMOOTH`).
    Smooth,
}

impl Interpolation {
    pub(crate) fn to_raw(self) -> sys::ps_interpolation {
        match self {
            Interpolation::Hold => sys::PS_INTERPOLATION_HOLD,
            Interpolation::Linear => sys::PS_INTERPOLATION_LINEAR,
            Interpolation::Smooth => sys::PS_INTERPOLATION_SMOOTH,
        }
    }
}

/// What a handle holds of its vertices (the C `ps_support`). Scene key `handles[i].support`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Support {
    /// Each vertex's prescribed coordinates follow the script, the others are free per vertex
    /// (a clamp, a roller, a symmetry plane): `PS_SUPPORT_POSITION`, the default.
    #[default]
    Position,
    /// The group moves rigidly: it turns as its script turns it (held still by a static script)
    /// and translates freely along the coordinates outside its axes (`PS_SUPPORT_ROTATION`).
    /// Two or more rows of a shell's vertices hold a slope. Single-level simulations only.
    Rotation,
}

impl Support {
    pub(crate) fn to_raw(self) -> sys::ps_support {
        match self {
            Support::Position => sys::PS_SUPPORT_POSITION,
            Support::Rotation => sys::PS_SUPPORT_ROTATION,
        }
    }
}

/// The world coordinates a handle prescribes (the C `ps_axis` bits); the others are free: a
/// roller or a symmetry plane. Scene key `handles[i].axes`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Axes {
    /// Holds x.
    pub x: bool,
    /// Holds y.
    pub y: bool,
    /// Holds z.
    pub z: bool,
}

impl Axes {
    /// All three coordinates: a clamp (every handle's default).
    pub const ALL: Axes = Axes { x: true, y: true, z: true };
    /// None: a rotation support's free translation.
    pub const NONE: Axes = Axes { x: false, y: false, z: false };

    /// The C `ps_axis` bits.
    pub fn bits(self) -> u32 {
        let mut bits = 0;
        if self.x {
            bits |= sys::PS_AXIS_X;
        }
        if self.y {
            bits |= sys::PS_AXIS_Y;
        }
        if self.z {
            bits |= sys::PS_AXIS_Z;
        }
        bits
    }
}

/// What a handle's support applies to the shell after a solve (`ps_handle_reaction`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandleReaction {
    /// N, summed over the handle's vertices; 0 along the coordinates it leaves free.
    pub force: [f64; 3],
    /// N·m, about [`point`](Self::point).
    pub moment: [f64; 3],
    /// m, the centroid of the handle's vertices.
    pub point: [f64; 3],
}

impl From<sys::ps_handle_reaction> for HandleReaction {
    fn from(raw: sys::ps_handle_reaction) -> HandleReaction {
        HandleReaction { force: raw.force, moment: raw.moment, point: raw.point }
    }
}

/// Statistics of one level, accumulated over every step taken at it. Levels not visited
/// yet report zeros.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelStats {
    /// Which level.
    pub level: usize,
    /// Steps taken at this level.
    pub steps: usize,
    /// Total Newton iterations over those steps.
    pub newton_iterations: usize,
    /// Steps whose Newton solve met the tolerance.
    pub converged_steps: usize,
    /// Wall time spent stepping at this level, s.
    pub seconds: f64,
    /// Incremental potential after the last step, J.
    pub energy: f64,
    /// ‖∇E‖ over the free degrees of freedom after the last step, N.
    pub gradient_norm: f64,
    /// Simulated time reached, s.
    pub simulated_time: f64,
    /// RMS vertex distance to the converged finest solution over the bounding-box diagonal
    /// (dimensionless); `None` until the finest level is at equilibrium.
    pub error_rms: Option<f64>,
    /// Maximum vertex distance to the converged finest solution over the bounding-box
    /// diagonal (dimensionless); `None` until measured.
    pub error_max: Option<f64>,
    /// Solves at a fixed time ([`Simulation::settle`](crate::Simulation::settle)).
    pub settles: usize,
    /// Whether the last solve left an equilibrium (quasistatic scenes: the tolerance met with
    /// the scripts arrived, before any Newton step with the proximal term, no strain limit
    /// still raised).
    pub equilibrium: bool,
    /// Wall time refining the coarser level into this one, s.
    pub refine_seconds: f64,
    /// How the level's start was built from the coarser level.
    pub refinement: RefinementStats,
    /// Contact pairs whose offset is still lowered after the last solve (where contact kept
    /// a split from opening fully); 0 normally.
    pub reduced_offsets: usize,
    /// Faces whose strain limit is still raised after the last solve; 0 normally.
    pub raised_limits: usize,
    /// Obstacle vertices the level's contact meets: fewer than the scene's on coarse levels
    /// when obstacles are progressive (PSQ §4.6); 0 without obstacles.
    pub obstacle_vertices: usize,
    /// How the progressive obstacles were refined into this level (zeros without).
    pub obstacle_refinement: RefinementStats,
    /// CG iterations refining projected Newton steps ([`SimulationDef::max_cg_iterations`]
    /// > 0; never in the coarse levels' proxy solves); 0 when refinement is off.
    pub cg_iterations: usize,
    /// Newton steps the line search lengthened beyond a whole step
    /// ([`SimulationDef::line_search_extrapolation`]); 0 when it is off.
    pub extrapolated_steps: usize,
    /// How the level's refined start was brought under its strain limits.
    pub strain_correction: StrainCorrectionStats,
}

/// How a refined start was brought under its strain limits (PSQ §4.4.5): the new vertices
/// move, the coarser level's held, until every face is under its limit (the coarser vertices
/// move too where that cannot be reached with them held). All zeros for level 0 and for
/// scenes without strain limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StrainCorrectionStats {
    /// Faces at or beyond their strain limit before the correction.
    pub strained_faces: usize,
    /// Faces beyond it after the correction (0: the start is strain-feasible).
    pub over_limit_faces: usize,
    /// Newton iterations of the correction.
    pub newton_iterations: usize,
    /// Whether the coarser level's vertices had to move too.
    pub moved_coarse_vertices: bool,
    /// Largest principal stretch of a limited face before the correction.
    pub stretch_before: f64,
    /// Largest principal stretch of a limited face after it.
    pub stretch_after: f64,
}

impl From<sys::ps_strain_correction_stats> for StrainCorrectionStats {
    fn from(raw: sys::ps_strain_correction_stats) -> StrainCorrectionStats {
        StrainCorrectionStats {
            strained_faces: crate::count_from(raw.strained_faces),
            over_limit_faces: crate::count_from(raw.over_limit_faces),
            newton_iterations: crate::count_from(raw.newton_iterations),
            moved_coarse_vertices: raw.moved_coarse_vertices != 0,
            stretch_before: raw.stretch_before,
            stretch_after: raw.stretch_after,
        }
    }
}

/// How a level's start was built from the coarser level by safe refinement (PSQ §4.4); all
/// zeros for level 0 and for scenes without contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefinementStats {
    /// Colour batches of vertex splits.
    pub batches: usize,
    /// Vertex splits over all batches.
    pub splits: usize,
    /// Splits whose target direction was unsafe (PSQ Algorithm 5).
    pub random_directions: usize,
    /// Additive-CCD advancement rounds over all batches.
    pub rounds: usize,
    /// Moving vertices stopped by contact before their target.
    pub stopped_vertices: usize,
    /// Stopped vertices relaxed locally (PSQ §4.4.3).
    pub relaxed_vertices: usize,
    /// Newton iterations of those relaxations.
    pub relaxation_iterations: usize,
    /// Contact pairs left within their offset, opened by later solves.
    pub inside_pairs: usize,
    /// 1 − Σ‖x̂ − x‖ / Σ‖x̂ − x₀‖ over the moving vertices: 1 when all reached their targets.
    pub reached: f64,
    /// Smallest gap d − ξ of contact pairs outside their offsets, m.
    pub min_gap: f64,
}

impl From<sys::ps_refinement_stats> for RefinementStats {
    fn from(raw: sys::ps_refinement_stats) -> RefinementStats {
        RefinementStats {
            batches: crate::count_from(raw.batches),
            splits: crate::count_from(raw.splits),
            random_directions: crate::count_from(raw.random_directions),
            rounds: crate::count_from(raw.rounds),
            stopped_vertices: crate::count_from(raw.stopped_vertices),
            relaxed_vertices: crate::count_from(raw.relaxed_vertices),
            relaxation_iterations: crate::count_from(raw.relaxation_iterations),
            inside_pairs: crate::count_from(raw.inside_pairs),
            reached: raw.reached,
            min_gap: raw.min_gap,
        }
    }
}

impl From<sys::ps_level_stats> for LevelStats {
    fn from(raw: sys::ps_level_stats) -> LevelStats {
        let measured = |value: f64| (!value.is_nan()).then_some(value);
        LevelStats {
            level: crate::count_from(raw.level),
            steps: crate::count_from(raw.steps),
            newton_iterations: crate::count_from(raw.newton_iterations),
            converged_steps: crate::count_from(raw.converged_steps),
            seconds: raw.seconds,
            energy: raw.energy,
            gradient_norm: raw.gradient_norm,
            simulated_time: raw.simulated_time,
            error_rms: measured(raw.error_rms),
            error_max: measured(raw.error_max),
            settles: crate::count_from(raw.settles),
            equilibrium: raw.equilibrium != 0,
            refine_seconds: raw.refine_seconds,
            refinement: RefinementStats::from(raw.refinement),
            reduced_offsets: crate::count_from(raw.reduced_offsets),
            raised_limits: crate::count_from(raw.raised_limits),
            obstacle_vertices: crate::count_from(raw.obstacle_vertices),
            obstacle_refinement: RefinementStats::from(raw.obstacle_refinement),
            cg_iterations: crate::count_from(raw.cg_iterations),
            extrapolated_steps: crate::count_from(raw.extrapolated_steps),
            strain_correction: StrainCorrectionStats::from(raw.strain_correction),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_come_from_the_library() {
        let def = SimulationDef::default();
        assert_eq!(def.time_step, 0.01);
        assert_eq!(def.youngs_modulus, 1e6);
        assert_eq!(def.bending_youngs_modulus, 0.0);
        assert_eq!(def.poisson_ratio, 0.3);
        assert_eq!(def.thickness, 1e-3);
        assert_eq!(def.density, 200.0);
        assert_eq!(def.newton_tolerance, 1e-5);
        assert_eq!(def.max_newton_iterations, 100);
        assert_eq!(def.max_cg_iterations, 0);
        assert!(def.line_search_extrapolation);
        assert_eq!(def.mode, Mode::Dynamic);
        assert_eq!(def.prediction, Prediction::VelocityOnly);
        assert_eq!(def.consistency_weight, 0.0);
        assert_eq!(def.galerkin_refresh, 0.5);
        assert_eq!((def.preview_iterations, def.preview_tolerance, def.proximal), (8, 0.0, false));
        assert_eq!(def.gravity_ramp, 0.0);
        assert_eq!(def.effects, Effect::Membrane | Effect::Bending | Effect::Gravity);
        assert_eq!(def.gravity, [0.0, -9.81, 0.0]);
        assert_eq!(def.pressure, 0.0);
        assert!(def.pinned_vertices.is_empty());
        assert_eq!(def.wind_velocity, [0.0; 3]);
        assert!(def.wind_keyframes.is_empty());
        assert_eq!((def.wind_density, def.wind_drag, def.wind_lift), (1.2, 1.2, 0.0));
    }

    #[test]
    fn raw_def_carries_every_field() {
        let def = SimulationDef {
            time_step: 0.02,
            gravity_ramp: 0.3,
            mode: Mode::Quasistatic,
            prediction: Prediction::PerFrame,
            consistency_weight: 0.5,
            galerkin_refresh: 0.0,
            preview_iterations: 3,
            preview_tolerance: 1e-3,
            proximal: true,
            effects: Effect::Membrane.into(),
            gravity: [1.0, 2.0, 3.0],
            pinned_vertices: vec![3, 5],
            wind_velocity: [4.0, 5.0, 6.0],
            wind_keyframes: vec![[0.0, 1.0, 2.0, 3.0], [1.0, 0.0, 0.0, 0.0]],
            wind_lift: 0.5,
            ..SimulationDef::default()
        };
        let raw = def.to_raw();
        assert_eq!(raw.wind_velocity, [4.0, 5.0, 6.0]);
        assert_eq!(raw.wind_lift, 0.5);
        assert_eq!(raw.num_wind_keyframes, 2);
        // SAFETY: to_raw() points at def.wind_keyframes' 2 rows of 4 doubles, alive here.
        let rows = unsafe { std::slice::from_raw_parts(raw.wind_keyframes, 8) };
        assert_eq!(rows[4], 1.0);
        assert_eq!(raw.simulation_time_step, 0.02);
        assert_eq!(raw.simulation_gravity_ramp, 0.3);
        assert_eq!(raw.mode, sys::PS_MODE_QUASISTATIC);
        assert_eq!(raw.prediction, sys::PS_PREDICTION_PER_FRAME);
        assert_eq!(raw.progressive_consistency_weight, 0.5);
        assert_eq!(raw.progressive_galerkin_refresh, 0.0);
        assert_eq!(raw.progressive_preview_iterations, 3);
        assert_eq!(raw.progressive_preview_tolerance, 1e-3);
        assert_eq!(raw.progressive_proximal, 1);
        assert_eq!(raw.effects, sys::PS_EFFECT_MEMBRANE);
        assert_eq!(raw.gravity, [1.0, 2.0, 3.0]);
        assert_eq!(raw.num_pinned_vertices, 2);
        assert_eq!(raw.pinned_vertices, def.pinned_vertices.as_ptr());
    }

    #[test]
    fn hierarchy_defaults_come_from_the_library() {
        let def = HierarchyDef::default();
        assert!(def.coarse_vertex_counts.is_empty() && def.pinned_vertices.is_empty());
        assert_eq!(def.contact_offset, 0.0);
        assert_eq!((def.tet_size_factor, def.tet_cell_size), (0.6, 0.0));
        let def = HierarchyDef {
            coarse_vertex_counts: vec![26, 60],
            tet_size_factor: 0.8,
            tet_cell_size: 0.05,
            ..HierarchyDef::default()
        };
        let raw = def.to_raw().unwrap();
        assert_eq!((raw.tet_size_factor, raw.tet_cell_size), (0.8, 0.05));
        assert_eq!(raw.num_coarse_levels, 2);
        assert_eq!(raw.coarse_vertex_counts, def.coarse_vertex_counts.as_ptr());
        assert!(raw.vertex_group_ids.is_null() && raw.num_vertex_group_ids == 0);
        let grouped = HierarchyDef { vertex_group_ids: vec![-1, 0, 1], ..HierarchyDef::default() };
        let raw = grouped.to_raw().unwrap();
        assert_eq!(raw.vertex_group_ids, grouped.vertex_group_ids.as_ptr());
        assert_eq!(raw.num_vertex_group_ids, 3);
    }

    #[test]
    fn effect_sets_combine() {
        let mut effects = Effect::Membrane | Effect::Gravity;
        assert!(effects.contains(Effect::Gravity) && !effects.contains(Effect::Bending));
        effects.set(Effect::Gravity, false);
        effects.set(Effect::Pressure, true);
        assert_eq!(effects.iter().collect::<Vec<_>>(), [Effect::Membrane, Effect::Pressure]);
        assert_eq!(Effects::all().bits(), 0b1_1111_1111);
        assert_eq!(format!("{:?}", Effects::from_bits_retain(0x81)), "{Membrane, Wind}");
        assert_eq!(format!("{:?}", Effects::from_bits_retain(0x101)), "{Membrane, Elasticity}");
        assert_eq!(format!("{:?}", Effects::from_bits_retain(0x201)), "{Membrane, 0x200}");
        assert!(Effects::empty().is_empty());
    }
}
