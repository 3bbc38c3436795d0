#include "sim_def.hpp"

#include "api_guard.hpp"
#include "scene/scene_parameters.hpp"

namespace progsim::capi {
namespace {
constexpr int32_t kSimCookie = 0x50535344;  // "PSSD"
constexpr uint32_t kAllEffects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING | PS_EFFECT_GRAVITY |
                                 PS_EFFECT_PRESSURE | PS_EFFECT_CONTACT | PS_EFFECT_FRICTION |
                                 PS_EFFECT_STRAIN_LIMIT | PS_EFFECT_WIND | PS_EFFECT_ELASTICITY;
}  // namespace

uint32_t effect_bits(const EffectSet& effects) {
  uint32_t bits = 0;
  for (unsigned e = 0; e < static_cast<unsigned>(Effect::count_); ++e)
    if (effects.has(static_cast<Effect>(e))) bits |= 1u << e;
  return bits;
}

EffectSet effects_from_bits(uint32_t bits) {
  if (bits & ~kAllEffects)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "effects has unknown bits " + std::to_string(bits & ~kAllEffects));
  EffectSet effects;
  for (unsigned e = 0; e < static_cast<unsigned>(Effect::count_); ++e)
    if (bits & (1u << e)) effects.enable(static_cast<Effect>(e));
  return effects;
}

ps_prediction prediction_enum(DynamicsPrediction rule) {
  switch (rule) {
    case DynamicsPrediction::prolonged_positions:
      return PS_PREDICTION_PROLONGED_POSITIONS;
    case DynamicsPrediction::per_frame:
      return PS_PREDICTION_PER_FRAME;
    default:
      return PS_PREDICTION_VELOCITY_ONLY;
  }
}

DynamicsPrediction prediction_from_enum(int32_t prediction) {
  switch (prediction) {
    case PS_PREDICTION_VELOCITY_ONLY:
      return DynamicsPrediction::velocity_only;
    case PS_PREDICTION_PROLONGED_POSITIONS:
      return DynamicsPrediction::prolonged_positions;
    case PS_PREDICTION_PER_FRAME:
      return DynamicsPrediction::per_frame;
    default:
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "prediction = " + std::to_string(prediction) + " is not a ps_prediction");
  }
}

Scene scene_from_def(const ps_sim_def& def, const TriangleMesh& mesh, const Tets& tets) {
  require_initialized(def.internal_cookie, kSimCookie, "ps_sim_def");
  Scene scene;
  scene.name = "c_api";
  Body body;
  body.name = "body";
  body.mesh = mesh;
  body.tets = tets;
  scene.bodies.push_back(std::move(body));
  // Each table parameter group.name comes from the def field group_name.
#define PROGSIM_PARAMETER(group, name, ...) \
  set_scene_parameter(scene, #group "." #name, static_cast<double>(def.group##_##name));
#include "scene/parameters.def"
#undef PROGSIM_PARAMETER
  if (def.mode != PS_MODE_DYNAMIC && def.mode != PS_MODE_QUASISTATIC)
    api_fail(PS_ERROR_INVALID_ARGUMENT, "mode = " + std::to_string(def.mode) + " is not a ps_mode");
  scene.mode = def.mode == PS_MODE_DYNAMIC ? StepMode::dynamic : StepMode::quasistatic;
  scene.progressive.prediction = prediction_from_enum(def.prediction);
  scene.effects = effects_from_bits(def.effects);
  scene.gravity = Vec3(def.gravity[0], def.gravity[1], def.gravity[2]);
  set_scene_parameter(scene, "pressure", def.pressure);
  scene.wind.velocity = Vec3(def.wind_velocity[0], def.wind_velocity[1], def.wind_velocity[2]);
  if (def.num_wind_keyframes > 0) {
    require(def.wind_keyframes, "def.wind_keyframes (with num_wind_keyframes > 0)");
    for (std::size_t k = 0; k < def.num_wind_keyframes; ++k) {
      const double* row = def.wind_keyframes + 4 * k;
      scene.wind.keyframes.push_back({row[0], Vec3(row[1], row[2], row[3])});
    }
  }
  if (def.num_pinned_vertices > 0) {
    require(def.pinned_vertices, "def.pinned_vertices (with num_pinned_vertices > 0)");
    Handle pinned;
    pinned.vertices.assign(def.pinned_vertices, def.pinned_vertices + def.num_pinned_vertices);
    scene.handles.push_back(pinned);
  }
  return scene;
}

}  // namespace progsim::capi

extern "C" PS_API void ps_sim_def_init(ps_sim_def* def) {
  if (!def) return;
  *def = ps_sim_def{};
#define PROGSIM_PARAMETER(group, name, default_value, ...) def->group##_##name = default_value;
#include "scene/parameters.def"
#undef PROGSIM_PARAMETER
  // The named options and gravity as a scene that does not set them (Scene{}, which the
  // choice table's test holds to core/scene/choices.def); a cloth's three effects.
  const progsim::Scene scene;
  def->mode = scene.mode == progsim::StepMode::dynamic ? PS_MODE_DYNAMIC : PS_MODE_QUASISTATIC;
  def->prediction = progsim::capi::prediction_enum(scene.progressive.prediction);
  def->effects = PS_EFFECT_MEMBRANE | PS_EFFECT_BENDING | PS_EFFECT_GRAVITY;
  for (int k = 0; k < 3; ++k) def->gravity[k] = scene.gravity[k];
  def->internal_cookie = progsim::capi::kSimCookie;
}
