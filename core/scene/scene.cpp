#include "scene/scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "energy/force_couple.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_mesh_validation.hpp"
#include "scene/parameter_table.hpp"

namespace progsim {

Vec3 HandleMotion::position(const Vec3& rest, double t) const {
  if (!keyframes.empty()) {
    const RigidPose pose = keyframe_pose(keyframes, interpolation, t);  // c + R(t)(x̄ − c) + T(t)
    return center + pose.rotation * (rest - center) + pose.translation + offset;
  }
  const Eigen::AngleAxisd rotation(angular_velocity * t, axis);  // x(t) = c + R(ωt)(x̄ − c) + vt
  return center + rotation * (rest - center) + velocity * t + offset;
}

bool HandleMotion::moves() const {
  return !velocity.isZero(0.0) || angular_velocity != 0.0 || keyframes.size() > 1;
}

Vec3 WindSettings::at(double t) const {
  if (keyframes.empty()) return velocity;
  const KeyBlend blend = key_blend(keyframes, t, Interpolation::linear);  // held outside
  return (1.0 - blend.weight) * keyframes[blend.from].velocity +
         blend.weight * keyframes[blend.to].velocity;
}

double ramp_factor(double t, double ramp) {
  return ramp > 0.0 ? std::min(1.0, t / ramp) : 1.0;  // linear growth from 0 over the ramp
}

int Scene::num_steps() const {
  return std::max(1, static_cast<int>(std::lround(duration / time_step)));
}

namespace {

void check(const char* group, const char* name, double value) {
  check_parameter(find_parameter(group, name), value);
}

void validate_material(const ShellMaterial& m) {
  check("material", "youngs_modulus", m.youngs_modulus);
  check("material", "bending_youngs_modulus", m.bending_youngs_modulus);
  check("material", "poisson_ratio", m.poisson_ratio);
  check("material", "thickness", m.thickness);
  check("material", "density", m.density);
  check("material", "friction", m.friction);
  check("material", "strain_limit", m.strain_limit);
  if (m.strain_limit != 0.0 && !(m.strain_limit > 1.0))
    fail(Status::invalid_scene, "material.strain_limit = " + std::to_string(m.strain_limit) +
                                    " must be 0 (no limit) or greater than 1");
}

/// A shell's mesh is a valid surface; a solid's tets are a valid tet mesh and its faces their
/// boundary.
void validate_body_geometry(const Body& body) {
  if (!is_solid(body)) return validate_mesh(body.mesh, body.name);
  const TetMesh volume{body.mesh.vertices, body.tets};
  validate_tet_mesh(volume, body.name);
  if (!same_array(body.mesh.faces, tet_boundary_faces(volume)))
    fail(Status::invalid_mesh, body.name +
                                   ": the faces of a solid body must be its tets' "
                                   "boundary (tet_boundary_faces)");
}

/// Shell and volumetric bodies, and the effects that act on each kind: membrane and bending on
/// shells, elasticity on solids. A scene may mix both kinds (solid–shell contact).
void validate_solids(const Scene& scene) {
  const auto solids = std::count_if(scene.bodies.begin(), scene.bodies.end(), is_solid);
  const auto shells = static_cast<long>(scene.bodies.size()) - solids;
  for (Effect e : {Effect::membrane, Effect::bending, Effect::strain_limit})
    if (shells == 0 && solids > 0 && scene.effects.has(e))
      fail(Status::invalid_scene, std::string("the '") + effect_name(e) +
                                      "' effect acts on shells, and the scene's bodies are "
                                      "volumetric: use 'elasticity'");
  if (solids == 0 && scene.effects.has(Effect::elasticity))
    fail(Status::invalid_scene,
         "the 'elasticity' effect acts on volumetric (tet) bodies, and the scene has none: use "
         "'membrane' and 'bending' for shells");
}

/// Obstacles, ground and contact settings; collision objects need the contact effect.
void validate_contact(const Scene& scene) {
  check("contact", "dhat", scene.contact.dhat);
  check("contact", "stiffness", scene.contact.stiffness);
  check("contact", "friction_velocity", scene.contact.friction_velocity);
  const bool contact = scene.effects.has(Effect::contact);
  if (!contact && (!scene.obstacles.empty() || scene.ground.enabled))
    fail(Status::invalid_scene,
         "the scene has obstacles or a ground but does not enable the 'contact' effect");
  if (!contact && scene.effects.has(Effect::friction))
    fail(Status::invalid_scene,
         "the 'friction' effect acts on contacts but the scene does not enable the 'contact' "
         "effect: enable 'contact' or drop 'friction'");
  for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
    const Obstacle& o = scene.obstacles[k];
    const std::string where = "obstacles[" + std::to_string(k) + "]";
    validate_mesh(o.mesh, o.name.empty() ? where : o.name);
    validate_motion(o.motion, where + ".motion");
    check("material", "friction", o.friction);
  }
  const Ground& g = scene.ground;
  if (g.enabled && (!g.normal.allFinite() || !(g.normal.norm() > 0.0) || !std::isfinite(g.height)))
    fail(Status::invalid_scene, "ground: normal must be finite and non-zero, height finite");
  check("material", "friction", g.friction);
}

/// A vertex group of handles and loads: an existing body, some vertices, each in its range.
void validate_group(const Scene& scene, int body, const std::vector<int>& vertices,
                    const std::string& where) {
  if (body < 0 || body >= static_cast<int>(scene.bodies.size()))
    fail(Status::invalid_scene, where + ": body index " + std::to_string(body) + " does not exist");
  const int n = scene.bodies[body].mesh.num_vertices();
  if (vertices.empty()) fail(Status::invalid_scene, where + ": selects no vertices");
  for (int v : vertices)
    if (v < 0 || v >= n)
      fail(Status::invalid_scene, where + ": vertex " + std::to_string(v) +
                                      " is out of range [0, " + std::to_string(n) + ")");
}

void validate_handle(const Scene& scene, std::size_t h) {
  const Handle& handle = scene.handles[h];
  const std::string where = "handles[" + std::to_string(h) + "]";
  validate_group(scene, handle.body, handle.vertices, where);
  validate_motion(handle.motion, where + ".motion");
  const bool rotation = handle.support == HandleSupport::rotation;
  if ((handle.axes == 0 && !rotation) || (handle.axes & ~unsigned{handle_axes_all}) != 0)
    fail(Status::invalid_scene, where + ": axes " + std::to_string(handle.axes) +
                                    " must be a non-empty set of x (1), y (2), z (4)" +
                                    " (empty only for a rotation support)");
  if (rotation && scene.progressive.enabled())
    fail(Status::unsupported, where + ": a rotation support needs a direct simulation " +
                                  "(progressive levels hold their handles by position only)");
}

/// A follower load: a finite force, a direct simulation, and a face on every vertex (its normal).
void validate_follower(const Scene& scene, const Load& load, const std::string& where) {
  if (!std::isfinite(load.normal_force))
    fail(Status::invalid_scene, where + ".normal_force has a non-finite value");
  if (scene.progressive.enabled())
    fail(Status::unsupported, where + ".normal_force: a follower load needs a direct simulation " +
                                  "(progressive levels carry dead loads only)");
  const Faces& faces = scene.bodies[load.body].mesh.faces;
  std::vector<bool> on_face(scene.bodies[load.body].mesh.num_vertices(), false);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) on_face[faces(f, c)] = true;
  for (int v : load.vertices)
    if (!on_face[v])
      fail(Status::invalid_scene, where + ".normal_force: vertex " + std::to_string(v) +
                                      " lies on no face, so it has no normal");
}

/// Body index, a non-empty group of vertices in range, finite values, a ramp ≥ 0 and, with a
/// moment, a group that can carry it (couple_forces with equal weights: whether it can does not
/// depend on the weights).
void validate_load(const Scene& scene, std::size_t k) {
  const Load& load = scene.loads[k];
  const std::string where = "loads[" + std::to_string(k) + "]";
  validate_group(scene, load.body, load.vertices, where);
  const Positions& rest = scene.bodies[load.body].mesh.vertices;
  Positions points(static_cast<Eigen::Index>(load.vertices.size()), 3);
  for (std::size_t j = 0; j < load.vertices.size(); ++j)
    points.row(static_cast<Eigen::Index>(j)) = rest.row(load.vertices[j]);
  if (!load.force.allFinite()) fail(Status::invalid_scene, where + ".force has a non-finite value");
  if (!std::isfinite(load.moment) || !load.moment_axis.allFinite())
    fail(Status::invalid_scene, where + ".moment has a non-finite value");
  if (load.moment != 0.0 && !(load.moment_axis.norm() > 0.0))
    fail(Status::invalid_scene, where + ".moment.axis must be non-zero");
  if (!std::isfinite(load.ramp) || !(load.ramp >= 0.0))
    fail(Status::invalid_scene, where + ".ramp must be a finite number >= 0");
  if (load.normal_force != 0.0) validate_follower(scene, load, where);
  couple_forces(points, Eigen::VectorXd::Ones(points.rows()), load.moment_axis, load.moment,
                where + ".moment");
}

void validate_progressive(const ProgressiveSettings& p) {
  const std::string where = "progressive";
  if (p.coarse_levels < 0 || p.coarse_levels > 30)
    fail(Status::invalid_scene,
         where + ".coarse_levels = " + std::to_string(p.coarse_levels) + " must lie in [0, 30]");
  if (!(p.coarsening_ratio > 1.0) || !std::isfinite(p.coarsening_ratio))
    fail(Status::invalid_scene, where + ".coarsening_ratio must be a finite number > 1");
  if (!(p.preview_tolerance >= 0.0 && p.preview_tolerance <= 1.0))
    fail(Status::invalid_scene, where + ".preview_tolerance must lie in [0, 1]");
  if (p.preview_iterations < 1)
    fail(Status::invalid_scene, where + ".preview_iterations must be >= 1");
  if (!(p.consistency_weight >= 0.0) || !std::isfinite(p.consistency_weight))
    fail(Status::invalid_scene, where + ".consistency_weight must be a finite number >= 0");
  if (!(p.galerkin_refresh >= 0.0) || !std::isfinite(p.galerkin_refresh))
    fail(Status::invalid_scene, where + ".galerkin_refresh must be a finite number >= 0");
  for (int n : p.level_vertices)
    if (n < 4)
      fail(Status::invalid_scene, where + ".levels: a level of " + std::to_string(n) +
                                      " vertices is too small (at least 4)");
}

/// Ranges of the air, finite velocities, keyframe times increasing; wind only in dynamic scenes:
/// a quasistatic step has no velocity, so the drag would be a follower load of the normals the
/// solve moves, with no potential energy to minimise.
void validate_wind(const Scene& scene) {
  const WindSettings& w = scene.wind;
  check("wind", "density", w.density);
  check("wind", "drag", w.drag);
  check("wind", "lift", w.lift);
  if (!w.velocity.allFinite())
    fail(Status::invalid_scene, "wind.velocity has a non-finite component");
  for (std::size_t k = 0; k < w.keyframes.size(); ++k) {
    const std::string where = "wind.keyframes[" + std::to_string(k) + "]";
    const WindKeyframe& key = w.keyframes[k];
    if (!std::isfinite(key.time) || key.time < 0.0)
      fail(Status::invalid_scene, where + ".time must be a finite number >= 0");
    if (k > 0 && !(key.time > w.keyframes[k - 1].time))
      fail(Status::invalid_scene, where + ".time must be later than the keyframe before it");
    if (!key.velocity.allFinite())
      fail(Status::invalid_scene, where + ".velocity has a non-finite component");
  }
  if (scene.effects.has(Effect::wind) && scene.mode == StepMode::quasistatic)
    fail(Status::invalid_scene,
         "the 'wind' effect needs a dynamic scene: its drag depends on the velocity, which a "
         "quasistatic step does not have");
}

/// What pulls a body in a quasistatic scene ("gravity", "pressure on its open surface",
/// "loads[k]"), or
/// an empty string when its loads cancel (none, or pressure on a closed surface).
std::string net_load(const Scene& scene, const Body& body) {
  if (scene.effects.has(Effect::gravity) && scene.gravity.norm() > 0.0) return "gravity";
  if (scene.effects.has(Effect::pressure) && body.pressure != 0.0) {
    const MeshTopology topology = build_topology(body.mesh.faces, body.mesh.num_vertices());
    for (bool on_boundary : topology.edge_on_boundary)
      if (on_boundary) return "pressure on its open surface";
  }
  for (std::size_t k = 0; k < scene.loads.size(); ++k) {
    const Load& load = scene.loads[k];
    if (&scene.bodies[load.body] == &body && (load.force.norm() > 0.0 || load.moment != 0.0))
      return "loads[" + std::to_string(k) + "]";
  }
  return {};
}

/// A quasistatic step minimises the potential energy: a body that a net load pulls and
/// nothing holds has no minimiser, and Newton runs it off to infinity (a free sheet under
/// gravity ended 3 steps near 2e15 m). Held: a handle on the body; with contact, a ground, an
/// obstacle or a held body it could rest on; or PSQ eq. 1's proximal term, which makes every
/// step a bounded gradient-flow step.
void validate_held(const Scene& scene) {
  if (scene.mode != StepMode::quasistatic || scene.progressive.proximal) return;
  const bool support = scene.effects.has(Effect::contact) &&
                       (scene.ground.enabled || !scene.obstacles.empty() || !scene.handles.empty());
  if (support) return;
  std::vector<bool> handled(scene.bodies.size(), false);
  for (const Handle& h : scene.handles) handled[h.body] = true;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const std::string load = net_load(scene, scene.bodies[b]);
    if (handled[b] || load.empty()) continue;
    fail(Status::invalid_scene,
         "body '" + scene.bodies[b].name + "' (bodies[" + std::to_string(b) +
             "]) is free in a quasistatic scene: " + load +
             " pulls it and nothing holds it, so its load steps have no equilibrium. Hold it "
             "with a handle, let it rest on a ground or an obstacle (with the 'contact' "
             "effect), add \"progressive\": {\"proximal\": true} (PSQ eq. 1's proximal term), "
             "or make the scene dynamic");
  }
}

}  // namespace

std::vector<int> VertexBox::select(const Positions& positions) const {
  std::vector<int> selected;
  for (Eigen::Index i = 0; i < positions.rows(); ++i) {
    const Vec3 x = positions.row(i).transpose();
    if ((x.array() >= min.array()).all() && (x.array() <= max.array()).all())
      selected.push_back(static_cast<int>(i));
  }
  return selected;
}

std::vector<int> body_vertices_in(const Scene& scene, int body, const VertexBox& box,
                                  const std::string& what) {
  if (body < 0 || body >= static_cast<int>(scene.bodies.size()))
    fail(Status::invalid_scene, what + ": body " + std::to_string(body) +
                                    " does not exist (the scene has " +
                                    std::to_string(scene.bodies.size()) + " bodies)");
  std::vector<int> selected = box.select(scene.bodies[body].mesh.vertices);
  if (selected.empty())
    fail(Status::invalid_scene,
         what + ": the box holds no vertex of body " + std::to_string(body) + "'s mesh");
  return selected;
}

void validate_motion(const HandleMotion& m, const std::string& where, Status status) {
  if (!m.velocity.allFinite() || !m.center.allFinite() || !m.offset.allFinite() ||
      !m.axis.allFinite() || !std::isfinite(m.angular_velocity))
    fail(status, where + " has a non-finite value");
  if (!(m.axis.norm() > 0.0)) fail(status, where + ".axis: the rotation axis must be non-zero");
  validate_keyframes(m.keyframes, where, status);
  if (!m.keyframes.empty() && (!m.velocity.isZero(0.0) || m.angular_velocity != 0.0))
    fail(status, where + ": give either keyframes or a velocity and angular velocity, not both");
}

void validate_scene(const Scene& scene) {
  check("simulation", "time_step", scene.time_step);
  check("simulation", "duration", scene.duration);
  check("simulation", "output_every", scene.output_every);
  check("simulation", "gravity_ramp", scene.gravity_ramp);
  check("solver", "newton_tolerance", scene.solver.tolerance);
  check("solver", "max_newton_iterations", scene.solver.max_iterations);
  check("solver", "max_cg_iterations", scene.solver.max_cg_iterations);
  if (!scene.gravity.allFinite()) fail(Status::invalid_scene, "gravity has a non-finite component");
  if (scene.bodies.empty()) fail(Status::invalid_scene, "the scene has no bodies");
  const auto first_shell = std::find_if_not(scene.bodies.begin(), scene.bodies.end(), is_solid);
  for (const Body& body : scene.bodies) {
    validate_material(body.material);
    if (!is_solid(body) && body.material.bending_model != first_shell->material.bending_model)
      fail(Status::invalid_scene, body.name + ": material.bending_model differs from " +
                                      first_shell->name + "'s (one bending model per scene)");
    validate_body_geometry(body);
    if (!std::isfinite(body.pressure) || !(body.pressure_ramp >= 0.0) ||
        !std::isfinite(body.pressure_ramp))
      fail(Status::invalid_scene,
           body.name + ": pressure and pressure_ramp must be finite, ramp ≥ 0");
    if (!body.velocity.allFinite())
      fail(Status::invalid_scene, body.name + ": velocity has a non-finite component");
  }
  for (std::size_t h = 0; h < scene.handles.size(); ++h) validate_handle(scene, h);
  for (std::size_t k = 0; k < scene.loads.size(); ++k) validate_load(scene, k);
  validate_solids(scene);
  validate_contact(scene);
  validate_progressive(scene.progressive);
  validate_wind(scene);
  validate_held(scene);
}

}  // namespace progsim
