// ps_sim_*: creating simulations and changing their parameters between steps.
#include <algorithm>

#include "handles.hpp"
#include "motion_args.hpp"
#include "progressive/progressive_dynamics.hpp"
#include "progressive/volumetric_dynamics.hpp"
#include "scene/scene_json.hpp"
#include "scene/scene_parameters.hpp"
#include "sim_def.hpp"

namespace progsim::capi {
namespace {

/// A dynamic scene on several levels is a progressive animation (PD, or VPD for a solid).
bool animated_progressively(const Scene& scene, int num_levels) {
  return num_levels > 1 && scene.mode == StepMode::dynamic;
}

/// The driver of a solid's scene on `hierarchy` (a solid's, counted as in use by the caller).
void build_solid_driver(ps_sim& sim, const Scene& scene, const ps_hierarchy& hierarchy) {
  if (hierarchy.num_levels() == 1) {  // a direct simulation builds its own one-level hierarchy
    sim.simulation = std::make_unique<ProgressiveSimulation>(scene, nullptr);
    return;
  }
  if (!animated_progressively(scene, hierarchy.num_levels()))
    api_fail(PS_ERROR_UNSUPPORTED,
             "a quasistatic solid on several levels: PSQ refines shells; animate it (dynamic "
             "mode, VPD) or simulate one level directly");
  sim.animation = std::make_unique<VolumetricDynamics>(scene, hierarchy.solid);
}

/// The handle of a simulation of `scene` at the coarsest level, its driver built on `hierarchy`
/// (nullptr: the driver builds a shell hierarchy from the scene's bodies); the caller sets its
/// hierarchy.
std::unique_ptr<ps_sim> build_sim(Scene scene, const ps_hierarchy* hierarchy) {
  auto sim = std::make_unique<ps_sim>();
  if (hierarchy && hierarchy->solid) {
    build_solid_driver(*sim, scene, *hierarchy);
  } else {
    std::shared_ptr<const MeshHierarchy> shells = hierarchy ? hierarchy->shared : nullptr;
    const int levels =
        hierarchy ? hierarchy->num_levels() : scene.progressive.num_coarse_levels() + 1;
    if (animated_progressively(scene, levels))
      sim->animation = std::make_unique<ProgressiveDynamics>(scene, std::move(shells));
    else
      sim->simulation = std::make_unique<ProgressiveSimulation>(scene, std::move(shells));
  }
  sim->scene = std::move(scene);
  return sim;
}

/// A simulation of scene on hierarchy (borrowed and counted as in use).
std::unique_ptr<ps_sim> make_sim(const ps_hierarchy* hierarchy, Scene scene) {
  auto sim = build_sim(std::move(scene), hierarchy);
  sim->hierarchy = hierarchy;
  ++hierarchy->simulations;  // last: nothing below can throw
  sim->counts_as_user = true;
  return sim;
}

/// A simulation of a parsed scene that owns its hierarchy: a solid's tet levels (the levels its
/// "progressive" section asks for), or the hierarchy its driver builds from its bodies (shells,
/// or shells and solids on one level).
std::unique_ptr<ps_sim> sim_from_scene(Scene scene) {
  if (all_solid(scene)) {
    auto owned = std::make_unique<ps_hierarchy>(
        std::make_shared<const TetHierarchy>(build_scene_tet_hierarchy(scene)));
    auto sim = build_sim(std::move(scene), owned.get());
    sim->owned_hierarchy = std::move(owned);
    sim->hierarchy = sim->owned_hierarchy.get();
    return sim;
  }
  auto sim = build_sim(std::move(scene), nullptr);
  sim->owned_hierarchy = std::make_unique<ps_hierarchy>(
      sim->animation ? static_cast<const ProgressiveDynamics&>(*sim->animation).shared_hierarchy()
                     : sim->simulation->shared_hierarchy());
  sim->hierarchy = sim->owned_hierarchy.get();
  return sim;
}

/// Whether the simulation has stepped, settled or refined since it was created or restarted.
bool started(const ps_sim& sim) {
  if (sim.animation) return sim.animation->level() > 0 || sim.animation->num_frames(0) > 1;
  const LevelRecord& first = sim.simulation->records().front();
  return sim.simulation->level() > 0 || first.steps + first.settles > 0;
}

/// The initial velocities of a progressive animation's preview (empty for other drivers).
Vector preview_velocities(const ps_sim& sim) {
  if (!sim.animation) return {};
  Positions positions, velocities;
  sim.animation->read_frame(0, 0, positions, velocities);
  return as_dofs(velocities);
}

/// Swaps in a driver built on the simulation's hierarchy for `scene`, keeping a progressive
/// animation's initial velocities; on error nothing changed.
void replace_driver(ps_sim& sim, Scene scene) {
  const Vector velocities = preview_velocities(sim);
  std::unique_ptr<ps_sim> fresh = build_sim(std::move(scene), sim.hierarchy);
  if (fresh->animation && velocities.size() > 0 && !velocities.isZero(0.0))
    fresh->animation->set_preview_velocities(velocities);
  sim.simulation = std::move(fresh->simulation);
  sim.animation = std::move(fresh->animation);
  sim.scene = std::move(fresh->scene);
}

const char* kind_name(ps_sim_kind kind) {
  switch (kind) {
    case PS_SIM_PSQ:
      return "a progressive quasistatic simulation (PSQ)";
    case PS_SIM_PROGRESSIVE_DYNAMICS:
      return "a progressive animation (Progressive Dynamics: a dynamic simulation on several "
             "levels)";
    case PS_SIM_VOLUMETRIC_DYNAMICS:
      return "a progressive animation of a solid (VPD: a dynamic simulation on several tet "
             "levels)";
    default:
      return "a direct simulation (one level)";
  }
}

/// Throws ApiError(PS_ERROR_OUT_OF_RANGE) unless the scene has handle `handle`.
void require_handle(const ps_sim& sim, int32_t handle) {
  const auto n = static_cast<int32_t>(sim.scene.handles.size());
  if (handle < 0 || handle >= n)
    api_fail(PS_ERROR_OUT_OF_RANGE, "handle " + std::to_string(handle) +
                                        " does not exist (the simulation has " + std::to_string(n) +
                                        " handles)");
}

std::string handle_motion_name(int32_t handle) {
  return "handles[" + std::to_string(handle) + "].motion";
}

/// The reactions after the last solve on a level (empty before any, and on previews).
const std::vector<HandleReaction>& last_reactions(const ps_sim& sim, int32_t level) {
  level_mesh(*sim.hierarchy, level);  // range check with the ABI's message
  if (sim.simulation) return sim.simulation->records()[level].reactions;
  const std::vector<DynamicStepRecord>& steps = sim.animation->record(level).steps;
  static const std::vector<HandleReaction> none;
  return steps.empty() ? none : steps.back().reactions;
}

void copy3(const Vec3& v, double out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = v[k];
}

}  // namespace

ps_sim_kind sim_kind(const ps_sim& sim) {
  if (sim.animation)
    return sim.hierarchy->solid ? PS_SIM_VOLUMETRIC_DYNAMICS : PS_SIM_PROGRESSIVE_DYNAMICS;
  return sim.hierarchy->num_levels() > 1 ? PS_SIM_PSQ : PS_SIM_DIRECT;
}

void rebuild_scene(ps_sim& sim, Scene scene, const char* what) {
  if (started(sim))
    api_fail(PS_ERROR_WRONG_CALL_ORDER,
             std::string(what) +
                 " changes the scene's structure and is only allowed before the first step, "
                 "settle or refinement (create a new simulation)");
  replace_driver(sim, std::move(scene));
}

void apply_scene(ps_sim& sim, Scene scene) {
  if (started(sim))
    edit_scene(sim, [&](Scene& edited) { edited = std::move(scene); });
  else
    replace_driver(sim, std::move(scene));
}

ProgressiveSimulation& quasistatic_driver(const ps_sim& sim) {
  if (!sim.simulation)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             std::string("this simulation is ") + kind_name(sim_kind(sim)) +
                 ", whose levels are animations: the call applies to PSQ and direct simulations");
  return *sim.simulation;
}

ProgressiveAnimation& animation_driver(const ps_sim& sim) {
  if (!sim.animation)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             std::string("this simulation is ") + kind_name(sim_kind(sim)) +
                 ": frames, initial velocities and restarts belong to a progressive animation "
                 "(PS_MODE_DYNAMIC on a hierarchy of several levels)");
  return *sim.animation;
}

}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API int32_t ps_sim_create(const ps_hierarchy* hierarchy, const ps_sim_def* def, ps_sim** out) {
  return guarded(nullptr, "ps_sim_create", [&] {
    require(hierarchy, "hierarchy");
    require(out, "out");
    ps_sim_def defaults;
    ps_sim_def_init(&defaults);
    if (hierarchy->solid) defaults.effects = PS_EFFECT_ELASTICITY | PS_EFFECT_GRAVITY;
    const int32_t finest = hierarchy->num_levels() - 1;
    const Tets tets = hierarchy->solid ? hierarchy->solid->levels.back().tets : Tets();
    *out = make_sim(hierarchy,
                    scene_from_def(def ? *def : defaults, level_mesh(*hierarchy, finest), tets))
               .release();
  });
}

PS_API int32_t ps_sim_create_from_scene(const char* json, const char* base_dir, ps_sim** out) {
  return guarded(nullptr, "ps_sim_create_from_scene", [&] {
    require(json, "json");
    require(out, "out");
    *out = sim_from_scene(parse_scene(json, base_dir ? base_dir : ".")).release();
  });
}

PS_API int32_t ps_sim_create_from_scene_file(const char* path, ps_sim** out) {
  return guarded(nullptr, "ps_sim_create_from_scene_file", [&] {
    require(path, "path");
    require(out, "out");
    *out = sim_from_scene(load_scene_file(path)).release();
  });
}

PS_API void ps_sim_destroy(ps_sim* sim) {
  delete sim;
}

PS_API const char* ps_sim_last_error(const ps_sim* sim) {
  return sim ? sim->last_error.c_str() : ps_last_error();
}

PS_API int32_t ps_sim_hierarchy(const ps_sim* sim, const ps_hierarchy** out) {
  return guarded(error_slot(sim), "ps_sim_hierarchy", [&] {
    require_idle(sim);
    require(out, "out");
    *out = sim->hierarchy;
  });
}

PS_API int32_t ps_sim_get_kind(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_get_kind", [&] {
    require_idle(sim);
    require(out, "out");
    *out = sim_kind(*sim);
  });
}

PS_API int32_t ps_sim_set_progress_callback(ps_sim* sim, ps_progress_fn fn, void* user_data) {
  return guarded(error_slot(sim), "ps_sim_set_progress_callback", [&] {
    require_idle(sim);
    sim->progress = fn;
    sim->progress_user_data = user_data;
  });
}

PS_API int32_t ps_sim_set_param(ps_sim* sim, const char* name, double value) {
  return guarded(error_slot(sim), "ps_sim_set_param", [&] {
    require_idle(sim);
    require(name, "name");
    edit_scene(*sim, [&](Scene& scene) { set_scene_parameter(scene, name, value); });
  });
}

PS_API int32_t ps_sim_get_param(const ps_sim* sim, const char* name, double* out) {
  return guarded(error_slot(sim), "ps_sim_get_param", [&] {
    require_idle(sim);
    require(name, "name");
    require(out, "out");
    *out = scene_parameter(sim->scene, name);
  });
}

PS_API int32_t ps_sim_set_mode(ps_sim* sim, int32_t mode) {
  return guarded(error_slot(sim), "ps_sim_set_mode", [&] {
    require_idle(sim);
    if (mode != PS_MODE_DYNAMIC && mode != PS_MODE_QUASISTATIC)
      api_fail(PS_ERROR_INVALID_ARGUMENT, "mode = " + std::to_string(mode) + " is not a ps_mode");
    edit_scene(*sim, [&](Scene& scene) {
      scene.mode = mode == PS_MODE_DYNAMIC ? StepMode::dynamic : StepMode::quasistatic;
    });
  });
}

PS_API int32_t ps_sim_get_mode(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_get_mode", [&] {
    require_idle(sim);
    require(out, "out");
    *out = sim->scene.mode == StepMode::dynamic ? PS_MODE_DYNAMIC : PS_MODE_QUASISTATIC;
  });
}

PS_API int32_t ps_sim_set_prediction(ps_sim* sim, int32_t prediction) {
  return guarded(error_slot(sim), "ps_sim_set_prediction", [&] {
    require_idle(sim);
    const DynamicsPrediction rule = prediction_from_enum(prediction);
    edit_scene(*sim, [&](Scene& scene) { scene.progressive.prediction = rule; });
  });
}

PS_API int32_t ps_sim_get_prediction(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_get_prediction", [&] {
    require_idle(sim);
    require(out, "out");
    *out = prediction_enum(sim->scene.progressive.prediction);
  });
}

PS_API int32_t ps_sim_set_effect(ps_sim* sim, uint32_t effect, int32_t enabled) {
  return guarded(error_slot(sim), "ps_sim_set_effect", [&] {
    require_idle(sim);
    if (effect == 0 || (effect & (effect - 1)) != 0)
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "effect = " + std::to_string(effect) + " is not a single ps_effect bit");
    uint32_t bits = effect_bits(sim->scene.effects);
    bits = enabled ? (bits | effect) : (bits & ~effect);
    const EffectSet effects = effects_from_bits(bits);
    edit_scene(*sim, [&](Scene& scene) { scene.effects = effects; });
  });
}

PS_API int32_t ps_sim_get_effects(const ps_sim* sim, uint32_t* out) {
  return guarded(error_slot(sim), "ps_sim_get_effects", [&] {
    require_idle(sim);
    require(out, "out");
    *out = effect_bits(sim->scene.effects);
  });
}

PS_API int32_t ps_sim_num_handles(const ps_sim* sim, int32_t* out) {
  return guarded(error_slot(sim), "ps_sim_num_handles", [&] {
    require_idle(sim);
    require(out, "out");
    *out = static_cast<int32_t>(sim->scene.handles.size());
  });
}

PS_API int32_t ps_sim_set_handle_motion(ps_sim* sim, int32_t handle, const double velocity[3],
                                        const double axis[3], const double center[3],
                                        double angular_velocity, const double offset[3]) {
  return guarded(error_slot(sim), "ps_sim_set_handle_motion", [&] {
    require_idle(sim);
    require_handle(*sim, handle);
    const HandleMotion motion = velocity_motion(velocity, axis, center, angular_velocity, offset,
                                                handle_motion_name(handle));
    edit_scene(*sim, [&](Scene& scene) { scene.handles[handle].motion = motion; });
  });
}

PS_API int32_t ps_sim_set_handle_keyframes(ps_sim* sim, int32_t handle, const double* rows,
                                           size_t num_rows, int32_t interpolation) {
  return guarded(error_slot(sim), "ps_sim_set_handle_keyframes", [&] {
    require_idle(sim);
    require_handle(*sim, handle);
    const HandleMotion motion = keyframe_motion(sim->scene.handles[handle].motion, rows, num_rows,
                                                interpolation, handle_motion_name(handle));
    edit_scene(*sim, [&](Scene& scene) { scene.handles[handle].motion = motion; });
  });
}

PS_API int32_t ps_sim_set_handle_axes(ps_sim* sim, int32_t handle, uint32_t axes) {
  return guarded(error_slot(sim), "ps_sim_set_handle_axes", [&] {
    require_idle(sim);
    require_handle(*sim, handle);
    edit_scene(*sim, [&](Scene& scene) { scene.handles[handle].axes = axes; });
  });
}

PS_API int32_t ps_sim_set_handle_support(ps_sim* sim, int32_t handle, int32_t support,
                                         uint32_t axes) {
  return guarded(error_slot(sim), "ps_sim_set_handle_support", [&] {
    require_idle(sim);
    require_handle(*sim, handle);
    if (support != PS_SUPPORT_POSITION && support != PS_SUPPORT_ROTATION)
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "support = " + std::to_string(support) + " is not a ps_support");
    edit_scene(*sim, [&](Scene& scene) {
      scene.handles[handle].support =
          support == PS_SUPPORT_ROTATION ? HandleSupport::rotation : HandleSupport::position;
      scene.handles[handle].axes = axes;
    });
  });
}

PS_API int32_t ps_sim_get_handle_reaction(const ps_sim* sim, int32_t level, int32_t handle,
                                          ps_handle_reaction* out) {
  return guarded(error_slot(sim), "ps_sim_get_handle_reaction", [&] {
    require_idle(sim);
    require(out, "out");
    require_handle(*sim, handle);
    const std::vector<HandleReaction>& reactions = last_reactions(*sim, level);
    if (reactions.empty())
      api_fail(PS_ERROR_WRONG_CALL_ORDER,
               "level " + std::to_string(level) +
                   " has no reaction: no solve on it yet, or it is a preview level (its proxy "
                   "holds the finest handle vertices)");
    copy3(reactions[handle].force, out->force);
    copy3(reactions[handle].moment, out->moment);
    copy3(reactions[handle].point, out->point);
  });
}

}  // extern "C"
