#pragma once
/// @file ps_sim_def ↔ Scene: the def's numeric fields are generated from the parameter table.
#include "progsim.h"
#include "scene/scene.hpp"

namespace progsim::capi {

/// The scene a def describes on the given mesh (one body, handle 0 = the pinned vertices): a
/// shell, or with `tets` a solid whose faces are `mesh`'s (its boundary).
/// Throws ApiError(PS_ERROR_UNINITIALIZED_DEF) for a def not filled by ps_sim_def_init().
Scene scene_from_def(const ps_sim_def& def, const TriangleMesh& mesh, const Tets& tets = Tets());

/// The ps_prediction of a prediction rule, and back (ApiError(PS_ERROR_INVALID_ARGUMENT) for a
/// value that is not a ps_prediction).
ps_prediction prediction_enum(DynamicsPrediction rule);
DynamicsPrediction prediction_from_enum(int32_t prediction);

/// The ps_effect bits of an effect set, and back.
uint32_t effect_bits(const EffectSet& effects);
EffectSet effects_from_bits(uint32_t bits);

}  // namespace progsim::capi
