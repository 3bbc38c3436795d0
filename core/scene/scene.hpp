#pragma once
/// @file A scene: bodies, materials, handles, effects and solver settings. Parsed from JSON
/// (scene_json.hpp) or built in code; validated before anything is simulated.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "energy/shell_material.hpp"
#include "energy/solid_material.hpp"
#include "mesh/triangle_mesh.hpp"
#include "scene/effects.hpp"
#include "scene/keyframes.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {

/// How steps advance.
enum class StepMode {
  dynamic,      ///< implicit Euler: minimise the incremental potential with inertia
  quasistatic,  ///< each step minimises the potential energy (no inertia) at that step's loads
};

/// A body: a shell (a triangle mesh) or a volumetric solid (tets), already transformed to world
/// space, with its material and pressure.
struct Body {
  std::string name;
  /// A shell's mesh; for a solid, all its vertices (interior ones too) with its boundary faces
  /// (tet_boundary_faces(), so interior vertices belong to no face).
  TriangleMesh mesh;
  /// Shells: all of it; solids: E, ν, ρ and friction (thickness, bending and strain limit do not
  /// apply).
  ShellMaterial material;
  double pressure = 0.0;         ///< Pa, applied if the pressure effect is enabled
  double pressure_ramp = 0.0;    ///< s; pressure grows linearly from 0 over this time (0: at once)
  Vec3 velocity = Vec3::Zero();  ///< m/s, initial velocity of every vertex (dynamic scenes)
  /// Non-empty: the body is a volumetric solid (VPD §3.1) whose tets index mesh.vertices,
  /// positively oriented (tet_mesh.hpp).
  Tets tets;
  SolidModel solid_model = SolidModel::neo_hookean;  ///< the solid's energy density (solids only)
};

/// Rigid motion of a handle or an obstacle: x(t) = c + R(ω t)(x₀ − c) + v t + offset, with R a
/// rotation about `axis` through centre c; or, keyframed, x(t) = c + R(t)(x₀ − c) + T(t) +
/// offset with the pose (R, T) interpolated between keyframes (keyframe_pose()).
struct HandleMotion {
  Vec3 velocity = Vec3::Zero();   ///< m/s
  Vec3 axis = Vec3::UnitZ();      ///< unit rotation axis
  Vec3 center = Vec3::Zero();     ///< m
  double angular_velocity = 0.0;  ///< rad/s
  Vec3 offset = Vec3::Zero();     ///< m, a translation a designer drags between steps
  /// Poses at increasing times, the first held before it and the last after it; non-empty
  /// excludes `velocity` and `angular_velocity` (validate_motion()).
  std::vector<MotionKeyframe> keyframes;
  Interpolation interpolation = Interpolation::linear;  ///< between keyframes

  /// Where a point whose rest position is `rest` (m) is at time t (s).
  Vec3 position(const Vec3& rest, double t) const;
  /// Whether the motion changes with time (a velocity, an angular velocity or two keyframes).
  bool moves() const;
};

/// A collision object: a triangle mesh on a rigid script, not simulated (C-IPC codimensional
/// obstacles). Contact, friction and the contact offset act on it; it has no offset itself.
struct Obstacle {
  std::string name;
  TriangleMesh mesh;      ///< world space at t = 0
  HandleMotion motion;    ///< scripted rigid motion (static by default)
  double friction = 0.0;  ///< Coulomb coefficient μ of its surface
  /// Progressive collision object (PSQ §4.6): coarse levels of a progressive simulation meet a
  /// decimated copy, refined with the shell (ObstacleHierarchy). Direct solves ignore it.
  bool progressive = false;
};

/// The analytic ground: the half-space n·x ≥ height, a collision object without a mesh.
struct Ground {
  bool enabled = false;
  Vec3 normal = Vec3::UnitY();  ///< unit normal pointing to the free side
  double height = 0.0;          ///< m, offset of the plane along the normal
  double friction = 0.0;        ///< Coulomb coefficient μ
};

/// Contact settings (IPC, Li et al. 2020; C-IPC, Li et al. 2021), used when the contact
/// effect is enabled.
struct ContactSettings {
  double dhat = 1e-3;  ///< activation gap d̂ (m): the barrier acts on pairs closer than this
  /// Barrier stiffness κ (N/m³ on squared distances); 0 chooses it from the scene's loads and
  /// grows it when a gap gets tiny (adaptive, IPC §4.3).
  double stiffness = 0.0;
  double friction_velocity = 1e-3;  ///< ε_v (m/s): slip speed below which friction is smoothed
  /// A progressive run may start from a finest rest shape that crosses itself or an obstacle
  /// (safe refinement separates it level by level); false: such a scene is refused.
  bool crossing_start = false;
};

/// The wind at one time of a gust.
struct WindKeyframe {
  double time = 0.0;             ///< s
  Vec3 velocity = Vec3::Zero();  ///< m/s
};

/// The wind effect: aerodynamic drag and lift of the air on every face (WindForce), dynamic
/// scenes only.
struct WindSettings {
  Vec3 velocity = Vec3::Zero();  ///< m/s, the wind when there are no keyframes
  double density = 1.2;          ///< ρ of the air (kg/m³)
  double drag = 1.2;             ///< C_d of the normal pressure drag (1)
  double lift = 0.0;             ///< C_L of the lift across the relative wind (1); 0: none
  /// Gusts: the wind at increasing times, linear between them, held before the first and after
  /// the last; empty: `velocity` at all times.
  std::vector<WindKeyframe> keyframes;

  /// The wind at time t (s), m/s.
  Vec3 at(double t) const;
};

/// Bits of Handle::axes: the coordinates a handle prescribes.
enum HandleAxis : unsigned {
  handle_axis_x = 1u,
  handle_axis_y = 2u,
  handle_axis_z = 4u,
  handle_axes_all = 7u,  ///< a clamp
};

/// An axis-aligned box of world positions (m) that selects vertices (a scene's "box").
struct VertexBox {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();

  /// Indices of the rows of `positions` inside the box, boundary included, ascending.
  std::vector<int> select(const Positions& positions) const;
};

struct Scene;

/// The vertices of body `body` of `scene` inside `box` (a group given by a region). Throws
/// Error(invalid_scene), starting with `what`, for a body that does not exist or a box that holds
/// no vertex of it.
std::vector<int> body_vertices_in(const Scene& scene, int body, const VertexBox& box,
                                  const std::string& what);

/// What a handle holds of its vertices.
enum class HandleSupport {
  /// Each vertex's prescribed coordinates (Handle::axes) follow the script; the others are free
  /// per vertex: a clamp, a roller or a symmetry plane.
  position,
  /// The group moves rigidly: it turns as the script turns it (held still by a static script),
  /// and translates freely along the coordinates not in Handle::axes, by one translation common
  /// to its vertices. A shell has no rotational DOFs, so a group of two or more rows of vertices
  /// holds the slope of a rotation support (a guided or sliding clamp; a prescribed end rotation
  /// with a free end position, as in Sze et al. 2004's roll-up test). Direct simulations only.
  rotation,
};

/// Vertices of one body held on a scripted trajectory (Dirichlet boundary condition).
struct Handle {
  int body = 0;               ///< index into Scene::bodies
  std::vector<int> vertices;  ///< vertex indices within the body's mesh
  HandleMotion motion;
  /// The world coordinates the handle prescribes (HandleAxis bits); the others are free: a
  /// roller or a symmetry plane. A position support needs at least one; a rotation support may
  /// have none (a free translation). The script moves only the prescribed coordinates of a
  /// position support.
  unsigned axes = handle_axes_all;
  HandleSupport support = HandleSupport::position;  ///< what the handle holds
  /// The box that selected `vertices` when a box alone did: a level with other vertices (VPD's
  /// coarse tet levels) selects its own by it. Empty for vertices listed by index.
  std::optional<VertexBox> region;
};

/// How a load's total force is spread over its vertex group.
enum class LoadDistribution {
  mass,        ///< f_i = F m_i / Σ m_j, by lumped vertex mass
  area,        ///< f_i = F A_i / Σ A_j, by lumped vertex area (a third of each incident face)
  per_vertex,  ///< f_i = F: the force acts on every vertex of the group
};

/// A point or line load on a vertex group of one body, grown linearly from 0 over `ramp`: a dead
/// (fixed direction and size) force, a dead moment (a force couple), a follower force along the
/// surface normal, or any of them together.
struct Load {
  int body = 0;               ///< index into Scene::bodies
  std::vector<int> vertices;  ///< vertex indices within the body's mesh
  Vec3 force = Vec3::Zero();  ///< N: the total, or per vertex with LoadDistribution::per_vertex
  LoadDistribution distribution = LoadDistribution::mass;
  Vec3 moment_axis = Vec3::UnitZ();  ///< direction a of the moment (any length > 0)
  /// N·m: the moment M a of a couple on the group (its forces sum to zero), weighted like the
  /// force (per_vertex: equally); 0: none.
  double moment = 0.0;
  /// N along the unit vertex normals (the faces' winding), spread like the force, following the
  /// surface as it turns (FollowerLoads); 0: none. Direct simulations only.
  double normal_force = 0.0;
  double ramp = 0.0;  ///< s; the load grows linearly from 0 over this time (0: at once)
  std::optional<VertexBox> region;  ///< as Handle::region
};

/// How the proxy energy of a coarse level reaches the finest mesh (PSQ §4.3).
enum class ProxyProlongation {
  composed,  ///< P_L^{L−1} ∘ ⋯ ∘ P_{l+1}^l: each level's offsets rotate with its own faces
  direct,    ///< P^l (PSQ eq. 9): every finest offset rotates with one level-l face
};

/// The Newton matrix of preview steps (the proxy energy's Hessian stand-in).
enum class ProxyHessian {
  /// galerkin in dynamic scenes (each preview step solved to the tolerance: 261 Newton
  /// iterations, all 30 steps converged, against 1473 with 11 steps at the cap for level, on the
  /// 8.6K-vertex drape), level in quasistatic ones (PSQ Algorithm 1 as published)
  automatic,
  level,     ///< the level's own shell Hessian (PSQ Algorithm 1 line 7): O(|V_l|) per iteration
  galerkin,  ///< Uᵀ ∇²Ψ_L U (offsets frozen, PSQ eq. 10): a finest assembly per refresh
};

/// The membrane energy of a shell.
enum class MembraneModel {
  neo_hookean,    ///< NeoHookeanMembrane
  tension_field,  ///< its relaxation, free in compression (TensionFieldMembrane, Pipkin 1986)
};

/// How a finer level of a progressive animation predicts its step (the x̂ of its incremental
/// potential) from the coarser level's trajectory (Progressive Dynamics).
enum class DynamicsPrediction {
  /// PD++ (Zhang, James and Kaufman 2025), VPD eq. 2's velocity-only prolongation: the level's
  /// own positions and the coarser level's velocity, x̂ = x_{l+1}^t + h U v_l^t.
  velocity_only,
  /// PD eq. 5: the coarser level's positions and velocity, x̂ = P(x_l^t) + h U v_l^t; resets
  /// the fine positions toward the coarse ones every step.
  prolonged_positions,
  /// PSQ per frame (PD §4.3, Fig. 6; for comparison only): x̂ = P(x_l^{t+1}), each step a
  /// proximal relaxation toward the prolonged coarse frame, with no inertia of its own.
  per_frame,
};

/// How a scene is simulated progressively (PSQ, Zhang et al. 2023): the levels of its mesh
/// hierarchy and how much work a preview step does.
struct ProgressiveSettings {
  int coarse_levels = 0;          ///< levels below the scene's mesh; 0: a direct simulation
  double coarsening_ratio = 4.0;  ///< vertex-count ratio between successive levels (> 1)
  /// Explicit vertex counts of the coarse levels (coarsest first); overrides the two above.
  std::vector<int> level_vertices;
  int preview_iterations = 8;  ///< Newton iterations per preview step (PSQ §4.5, Algorithm 1)
  /// Tolerance of preview solves, for their Newton steps and for when a preview level is at
  /// rest (PSQ Algorithm 1 line 10: ‖d‖₂ < √n_l h ε); 0: the solver's tolerance.
  double preview_tolerance = 0.0;
  ProxyProlongation prolongation = ProxyProlongation::composed;
  ProxyHessian hessian = ProxyHessian::automatic;
  /// Quasistatic steps add PSQ eq. 1's proximal term ½h⁻²‖x − xᵗ‖²_M (eq. 3 with the level's
  /// lumped masses): an artificial gradient flow that keeps the Newton matrix definite for free
  /// bodies (a cloth dropped on a sphere). On every level and in the direct baseline alike.
  bool proximal = false;
  /// The membrane the coarse levels' proxy evaluates on the finest mesh (and the level
  /// preconditioner on the level's): neo_hookean is PSQ's Ψ_L (eq. 2); tension_field lets a
  /// coarse preview shorten its faces at no cost, as wrinkles finer than its mesh would (our
  /// extension, for flat cloth whose coarse levels lock). The finest level and every direct
  /// solve keep neo_hookean.
  MembraneModel preview_membrane = MembraneModel::neo_hookean;
  /// Dynamic scenes: how a finer level predicts its steps from the coarser trajectory.
  DynamicsPrediction prediction = DynamicsPrediction::velocity_only;
  /// Dynamic scenes with the Galerkin Hessian: how far (in mean finest edge lengths) the finest
  /// state may move, net of its mean translation, before the matrix is reassembled; 0: every
  /// iteration (quasistatic previews, capped at preview_iterations, always reassemble).
  double galerkin_refresh = 0.5;
  /// Dynamic scenes: weight w ≥ 0 of the consistency penalty (VPD eq. 4, from PD++), the
  /// mass-weighted quadratic w/(2h²) ‖x − P(x_{l−1}^{t+1})‖²_M pulling each finer level toward
  /// the prolonged coarser frame (w = 1 weighs it like the inertia); 0: no penalty term.
  double consistency_weight = 0.0;

  /// Levels below the scene's mesh that the settings ask for (the finest level's index).
  int num_coarse_levels() const {
    return level_vertices.empty() ? coarse_levels : static_cast<int>(level_vertices.size());
  }
  /// True when the scene asks for more than one level.
  bool enabled() const { return num_coarse_levels() > 0; }
};

/// Everything needed to run a simulation.
struct Scene {
  std::string name = "scene";
  StepMode mode = StepMode::dynamic;
  double time_step = 0.01;               ///< s
  double duration = 1.0;                 ///< s
  int output_every = 1;                  ///< steps between written meshes
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);  ///< m/s²
  double gravity_ramp = 0.0;  ///< s; gravity grows linearly from 0 over this time (0: at once)
  EffectSet effects;
  std::vector<Body> bodies;
  std::vector<Handle> handles;
  std::vector<Load> loads;          ///< point and line loads (each an energy term's group)
  std::vector<Obstacle> obstacles;  ///< collision objects (need the contact effect)
  Ground ground;                    ///< analytic ground (needs the contact effect)
  ContactSettings contact;
  WindSettings wind;  ///< used when the wind effect is enabled
  NewtonSettings solver;
  ProgressiveSettings progressive;

  /// Number of steps: round(duration / time_step), at least 1.
  int num_steps() const;
};

/// The fraction of a ramped load acting at time t (s): min(1, t / ramp), 1 for ramp = 0
/// (Body::pressure_ramp, Load::ramp, Scene::gravity_ramp).
double ramp_factor(double t, double ramp);

/// Checks a motion: finite values, a non-zero rotation axis, valid keyframes
/// (validate_keyframes()) and not both keyframes and a velocity or an angular velocity. Throws
/// Error(status) naming `where` (the motion's path, e.g. "handles[0].motion").
void validate_motion(const HandleMotion& motion, const std::string& where,
                     Status status = Status::invalid_scene);

/// Whether the body is a volumetric solid (it has tets).
inline bool is_solid(const Body& body) {
  return body.tets.rows() > 0;
}

/// Whether the scene has bodies and every one is a volumetric solid.
inline bool all_solid(const Scene& scene) {
  return !scene.bodies.empty() && std::all_of(scene.bodies.begin(), scene.bodies.end(), is_solid);
}

/// Whether the scene has both shells and volumetric solids.
inline bool mixes_shells_and_solids(const Scene& scene) {
  return std::any_of(scene.bodies.begin(), scene.bodies.end(), is_solid) && !all_solid(scene);
}

/// The material of a solid body's tets: its material's E, ν and ρ with its solid_model.
inline SolidMaterial solid_material(const Body& body) {
  return {body.material.youngs_modulus, body.material.poisson_ratio, body.material.density,
          body.solid_model};
}

/// Checks a scene built in code (the JSON parser calls it too): ranges of every parameter,
/// valid meshes, handle indices in range. Throws Error(invalid_scene / invalid_mesh).
void validate_scene(const Scene& scene);

}  // namespace progsim
