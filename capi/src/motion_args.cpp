// The scripted motion of a handle or an obstacle from the C ABI's arguments.
#include "motion_args.hpp"

#include "api_guard.hpp"

namespace progsim::capi {
namespace {

Interpolation interpolation_from_enum(int32_t interpolation) {
  switch (interpolation) {
    case PS_INTERPOLATION_HOLD:
      return Interpolation::hold;
    case PS_INTERPOLATION_LINEAR:
      return Interpolation::linear;
    case PS_INTERPOLATION_SMOOTH:
      return Interpolation::smooth;
    default:
      api_fail(PS_ERROR_INVALID_ARGUMENT,
               "interpolation = " + std::to_string(interpolation) + " is not a ps_interpolation");
  }
}

/// The core's motion rules as argument errors; the rotation axis made unit.
HandleMotion checked(HandleMotion motion, const std::string& where) {
  validate_motion(motion, where, Status::invalid_argument);
  motion.axis.normalize();
  return motion;
}

}  // namespace

Vec3 vec3_or(const double* v, const Vec3& fallback) {
  return v ? Vec3(v[0], v[1], v[2]) : fallback;
}

HandleMotion velocity_motion(const double velocity[3], const double axis[3], const double center[3],
                             double angular_velocity, const double offset[3],
                             const std::string& where) {
  HandleMotion motion;
  motion.velocity = vec3_or(velocity, Vec3::Zero());
  motion.axis = vec3_or(axis, Vec3::UnitZ());
  motion.center = vec3_or(center, Vec3::Zero());
  motion.angular_velocity = angular_velocity;
  motion.offset = vec3_or(offset, Vec3::Zero());
  return checked(motion, where);
}

HandleMotion keyframe_motion(const HandleMotion& current, const double* rows, std::size_t num_rows,
                             int32_t interpolation, const std::string& where) {
  require(rows, "rows");
  if (num_rows == 0) api_fail(PS_ERROR_INVALID_ARGUMENT, "num_rows = 0: give at least one key");
  HandleMotion motion;
  motion.center = current.center;
  motion.offset = current.offset;
  motion.interpolation = interpolation_from_enum(interpolation);
  for (std::size_t k = 0; k < num_rows; ++k) {
    const double* row = rows + 8 * k;  // time, tx, ty, tz, ax, ay, az, angle
    motion.keyframes.push_back(
        {row[0], Vec3(row[1], row[2], row[3]), Vec3(row[4], row[5], row[6]), row[7]});
  }
  return checked(motion, where);
}

}  // namespace progsim::capi
