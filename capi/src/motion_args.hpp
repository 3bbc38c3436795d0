#pragma once
/// @file The scripted motion of a handle or an obstacle from the C ABI's arguments.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.hpp"

namespace progsim::capi {

/// A nullable C vector as a Vec3 (`fallback` for NULL).
Vec3 vec3_or(const double* v, const Vec3& fallback);

/// x(t) = c + R(ω t)(x̄ − c) + v t + offset from ps_sim_set_*_motion()'s nullable arguments,
/// checked by the core's rules (Error(invalid_argument) naming `where`), axis made unit.
HandleMotion velocity_motion(const double velocity[3], const double axis[3], const double center[3],
                             double angular_velocity, const double offset[3],
                             const std::string& where);

/// Keyframed motion from ps_sim_set_*_keyframes()'s rows (time, tx, ty, tz, ax, ay, az, angle),
/// keeping `current`'s centre and offset; checked like velocity_motion(). Throws
/// ApiError(PS_ERROR_NULL_ARGUMENT / PS_ERROR_INVALID_ARGUMENT) for no rows or a bad
/// interpolation.
HandleMotion keyframe_motion(const HandleMotion& current, const double* rows, std::size_t num_rows,
                             int32_t interpolation, const std::string& where);

}  // namespace progsim::capi
