// ps_load_def, ps_sim_add_load, ps_sim_num_loads: point and line loads from code.
#include "handles.hpp"

namespace progsim::capi {
namespace {

constexpr int32_t kLoadCookie = 0x50534c44;  // "PSLD"

LoadDistribution distribution_from_enum(int32_t distribution) {
  switch (distribution) {
    case PS_LOAD_BY_MASS:
      return LoadDistribution::mass;
    case PS_LOAD_BY_AREA:
      return LoadDistribution::area;
    case PS_LOAD_PER_VERTEX:
      return LoadDistribution::per_vertex;
    default:
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "distribution = " + std::to_string(distribution) + " is not a ps_load_distribution");
  }
}

/// The group of a def given by its box (Load::region and the body's vertices inside it).
void select_box(const ps_load_def& def, const Scene& scene, Load& load) {
  if (!def.box_min || !def.box_max)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "def.box_min and def.box_max: a load's box needs both corners (or neither)");
  if (def.num_vertices > 0)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "a load's group is given by vertices or by a box, not both (num_vertices = " +
                 std::to_string(def.num_vertices) + " with a box)");
  load.region = checked_box(def.box_min, def.box_max);
  load.vertices = body_vertices_in(scene, def.body, *load.region, "the load's box");
}

/// The scene's Load a def describes (checked by the core's validate_scene when added).
Load load_from_def(const ps_load_def& def, const Scene& scene) {
  require_initialized(def.internal_cookie, kLoadCookie, "ps_load_def");
  Load load;
  load.body = def.body;
  if (def.box_min || def.box_max) {
    select_box(def, scene, load);
  } else if (def.num_vertices > 0) {
    require(def.vertices, "def.vertices (with num_vertices > 0)");
    load.vertices.assign(def.vertices, def.vertices + def.num_vertices);
  }
  load.force = Vec3(def.force[0], def.force[1], def.force[2]);
  load.distribution = distribution_from_enum(def.distribution);
  load.moment_axis = Vec3(def.moment_axis[0], def.moment_axis[1], def.moment_axis[2]);
  load.moment = def.moment;
  load.normal_force = def.normal_force;
  load.ramp = def.ramp;
  return load;
}

}  // namespace
}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API void ps_load_def_init(ps_load_def* def) {
  if (!def) return;
  *def = ps_load_def{};
  def->distribution = PS_LOAD_BY_MASS;
  def->moment_axis[2] = 1.0;
  def->internal_cookie = kLoadCookie;
}

PS_API int32_t ps_sim_add_load(ps_sim* sim, const ps_load_def* def, int32_t* out_index) {
  return guarded(error_slot(sim), "ps_sim_add_load", [&] {
    require_idle(sim);
    require(def, "def");
    const Load load = load_from_def(*def, sim->scene);
    edit_scene(*sim, [&](Scene& scene) { scene.loads.push_back(load); });
    if (out_index) *out_index = static_cast<int32_t>(sim->scene.loads.size()) - 1;
  });
}

PS_API int32_t ps_sim_num_loads(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_num_loads", [&] {
    require_idle(sim);
    require(out, "out");
    *out = static_cast<int32_t>(sim->scene.loads.size());
  });
}

}  // extern "C"
