#include "scene/keyframes.hpp"

#include <cmath>

namespace progsim {
namespace {

/// Unit axes closer than this (1 − |cos|) count as one axis.
constexpr double kSameAxis = 1e-12;

Eigen::Quaterniond key_rotation(const MotionKeyframe& key) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(key.angle, key.axis.normalized()));
}

/// R between keys a and b at weight w (keyframe_pose() documents the choice).
Eigen::Quaterniond blend_rotation(const MotionKeyframe& a, const MotionKeyframe& b, double w) {
  const Vec3 ua = a.axis.normalized(), ub = b.axis.normalized();
  const double cosine = ua.dot(ub);
  if (a.angle == 0.0 || b.angle == 0.0 || std::abs(cosine) >= 1.0 - kSameAxis) {
    const Vec3 axis = a.angle != 0.0 ? ua : ub;
    const double angle_b = cosine < 0.0 && a.angle != 0.0 ? -b.angle : b.angle;  // same axis
    return Eigen::Quaterniond(Eigen::AngleAxisd((1.0 - w) * a.angle + w * angle_b, axis));
  }
  return key_rotation(a).slerp(w, key_rotation(b));  // Shoemake 1985: shortest arc
}

}  // namespace

double interpolation_weight(Interpolation mode, double s) {
  switch (mode) {
    case Interpolation::hold:
      return 0.0;
    case Interpolation::smooth:
      return s * s * (3.0 - 2.0 * s);  // smoothstep 3s² − 2s³: zero slope at s = 0 and 1
    case Interpolation::linear:
      break;
  }
  return s;
}

RigidPose keyframe_pose(const std::vector<MotionKeyframe>& keys, Interpolation mode, double t) {
  const KeyBlend blend = key_blend(keys, t, mode);
  const MotionKeyframe &a = keys[blend.from], &b = keys[blend.to];
  const double w = blend.weight;
  return {blend_rotation(a, b, w), (1.0 - w) * a.translation + w * b.translation};
}

void validate_keyframes(const std::vector<MotionKeyframe>& keys, const std::string& where,
                        Status status) {
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const MotionKeyframe& key = keys[k];
    const std::string name = where + ".keyframes[" + std::to_string(k) + "]";
    if (!std::isfinite(key.time)) fail(status, name + ".time must be a finite number");
    if (k > 0 && !(key.time > keys[k - 1].time))
      fail(status, name + ".time = " + std::to_string(key.time) +
                       " must be later than the keyframe before it (" +
                       std::to_string(keys[k - 1].time) + ")");
    if (!key.translation.allFinite())
      fail(status, name + ".translation has a non-finite component");
    if (!key.axis.allFinite() || !(key.axis.norm() > 0.0))
      fail(status, name + ".axis must be finite and non-zero");
    if (!std::isfinite(key.angle)) fail(status, name + ".angle must be a finite number");
  }
}

}  // namespace progsim
