// ps_sim_add_handle, ps_sim_add_obstacle and its motion, ps_sim_set_ground: the scene's
// scripted and collision objects from code (scene keys "handles", "obstacles", "ground").
#include <cmath>
#include <string>

#include "handles.hpp"
#include "motion_args.hpp"

namespace progsim::capi {
namespace {

constexpr int32_t kObstacleCookie = 0x5053424f;  // "PSBO"

/// Throws ApiError(PS_ERROR_OUT_OF_RANGE) unless the scene has obstacle `obstacle`.
void require_obstacle(const ps_sim& sim, int32_t obstacle) {
  const auto n = static_cast<int32_t>(sim.scene.obstacles.size());
  if (obstacle < 0 || obstacle >= n)
    api_fail(PS_ERROR_OUT_OF_RANGE, "obstacle " + std::to_string(obstacle) +
                                        " does not exist (the simulation has " + std::to_string(n) +
                                        " obstacles)");
}

std::string obstacle_name(std::size_t obstacle) {
  return "obstacles[" + std::to_string(obstacle) + "]";
}

/// The scene's Obstacle a def describes, named as the scene file names it.
Obstacle obstacle_from_def(const ps_obstacle_def& def, std::size_t index) {
  require_initialized(def.internal_cookie, kObstacleCookie, "ps_obstacle_def");
  Obstacle obstacle;
  obstacle.name = obstacle_name(index);
  obstacle.mesh = borrowed_mesh(def.vertices, def.num_vertices, def.faces, def.num_faces);
  obstacle.friction = def.friction;
  obstacle.progressive = def.progressive != 0;
  return obstacle;
}

/// Scripts obstacle `obstacle` with `motion` from the next step on.
void set_obstacle_motion(ps_sim& sim, int32_t obstacle, const HandleMotion& motion) {
  edit_scene(sim, [&](Scene& scene) { scene.obstacles[obstacle].motion = motion; });
}

/// Rebuilds the simulation with `handle` added; its index into *out_index (nullable).
void add_handle(ps_sim& sim, Handle handle, const char* call, int32_t* out_index) {
  Scene scene = sim.scene;
  scene.handles.push_back(std::move(handle));
  rebuild_scene(sim, std::move(scene), call);
  if (out_index) *out_index = static_cast<int32_t>(sim.scene.handles.size()) - 1;
}

}  // namespace

VertexBox checked_box(const double lo[3], const double hi[3]) {
  const char* axes = "xyz";
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(lo[k]) || !std::isfinite(hi[k]))
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               std::string("box_min/box_max along ") + axes[k] + " is not finite");
    if (lo[k] > hi[k])
      api_fail(PS_ERROR_INVALID_ARGUMENT, std::string("box_min.") + axes[k] + " = " +
                                              std::to_string(lo[k]) + " is above box_max." +
                                              axes[k] + " = " + std::to_string(hi[k]));
  }
  return {Vec3(lo[0], lo[1], lo[2]), Vec3(hi[0], hi[1], hi[2])};
}

}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_sim_add_handle(ps_sim* sim, int32_t body, const int32_t* vertices,
                                 size_t num_vertices, int32_t* out_index) {
  return guarded(error_slot(sim), "ps_sim_add_handle", [&] {
    require_idle(sim);
    if (num_vertices > 0) require(vertices, "vertices (with num_vertices > 0)");
    Handle handle;
    handle.body = body;
    if (num_vertices > 0) handle.vertices.assign(vertices, vertices + num_vertices);
    add_handle(*sim, std::move(handle), "ps_sim_add_handle", out_index);
  });
}

PS_API int32_t ps_sim_add_handle_box(ps_sim* sim, int32_t body, const double box_min[3],
                                     const double box_max[3], int32_t* out_index) {
  return guarded(error_slot(sim), "ps_sim_add_handle_box", [&] {
    require_idle(sim);
    require(box_min, "box_min");
    require(box_max, "box_max");
    Handle handle;
    handle.body = body;
    handle.region = checked_box(box_min, box_max);
    handle.vertices = body_vertices_in(sim->scene, body, *handle.region, "the handle's box");
    add_handle(*sim, std::move(handle), "ps_sim_add_handle_box", out_index);
  });
}

PS_API void ps_obstacle_def_init(ps_obstacle_def* def) {
  if (!def) return;
  *def = ps_obstacle_def{};
  def->internal_cookie = kObstacleCookie;
}

PS_API int32_t ps_sim_add_obstacle(ps_sim* sim, const ps_obstacle_def* def, int32_t* out_index) {
  return guarded(error_slot(sim), "ps_sim_add_obstacle", [&] {
    require_idle(sim);
    require(def, "def");
    Scene scene = sim->scene;
    scene.obstacles.push_back(obstacle_from_def(*def, scene.obstacles.size()));
    rebuild_scene(*sim, std::move(scene), "ps_sim_add_obstacle");
    if (out_index) *out_index = static_cast<int32_t>(sim->scene.obstacles.size()) - 1;
  });
}

PS_API int32_t ps_sim_num_obstacles(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_num_obstacles", [&] {
    require_idle(sim);
    require(out, "out");
    *out = static_cast<int32_t>(sim->scene.obstacles.size());
  });
}

PS_API int32_t ps_sim_set_obstacle_motion(ps_sim* sim, int32_t obstacle, const double velocity[3],
                                          const double axis[3], const double center[3],
                                          double angular_velocity, const double offset[3]) {
  return guarded(error_slot(sim), "ps_sim_set_obstacle_motion", [&] {
    require_idle(sim);
    require_obstacle(*sim, obstacle);
    set_obstacle_motion(*sim, obstacle,
                        velocity_motion(velocity, axis, center, angular_velocity, offset,
                                        obstacle_name(obstacle) + ".motion"));
  });
}

PS_API int32_t ps_sim_set_obstacle_keyframes(ps_sim* sim, int32_t obstacle, const double* rows,
                                             size_t num_rows, int32_t interpolation) {
  return guarded(error_slot(sim), "ps_sim_set_obstacle_keyframes", [&] {
    require_idle(sim);
    require_obstacle(*sim, obstacle);
    set_obstacle_motion(*sim, obstacle,
                        keyframe_motion(sim->scene.obstacles[obstacle].motion, rows, num_rows,
                                        interpolation, obstacle_name(obstacle) + ".motion"));
  });
}

PS_API int32_t ps_sim_set_ground(ps_sim* sim, int32_t enabled, const double normal[3],
                                 double height, double friction) {
  return guarded(error_slot(sim), "ps_sim_set_ground", [&] {
    require_idle(sim);
    Ground ground;
    ground.enabled = enabled != 0;
    ground.normal = vec3_or(normal, Vec3::UnitY());
    if (!ground.normal.allFinite() || !(ground.normal.norm() > 0.0) || !std::isfinite(height))
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "ground: normal must be finite and non-zero, height finite");
    ground.normal.normalize();
    ground.height = height;
    ground.friction = friction;
    edit_scene(*sim, [&](Scene& scene) { scene.ground = ground; });
  });
}

}  // extern "C"
