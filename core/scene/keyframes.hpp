#pragma once
/// @file Keyframes: values given at increasing times and interpolated between them (hold,
/// linear, smoothstep), shared by the wind's gusts and keyframed rigid motion (poses of handles
/// and obstacles: a translation and a rotation about the motion's centre).
#include <Eigen/Geometry>
#include <algorithm>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"

namespace progsim {

/// How a value moves from one keyframe to the next.
enum class Interpolation {
  hold,    ///< a step: the earlier key's value until the next key's time
  linear,  ///< uniformly in time
  smooth,  ///< smoothstep 3s² − 2s³ of the segment's parameter s: zero velocity at every key
};

/// Where a time falls among keyframes: the value there is (1 − weight) key[from] + weight key[to].
struct KeyBlend {
  std::size_t from = 0;
  std::size_t to = 0;
  double weight = 0.0;  ///< in [0, 1]
};

/// The weight of the later key at segment parameter s = (t − t_a)/(t_b − t_a) ∈ [0, 1).
double interpolation_weight(Interpolation mode, double s);

/// Where time t (s) falls among `keys` (non-empty, each with a `time` in s, strictly
/// increasing): the first key before it, the last after it (held), else the segment around it.
template <typename Key>
KeyBlend key_blend(const std::vector<Key>& keys, double t, Interpolation mode) {
  const auto later = std::upper_bound(keys.begin(), keys.end(), t,
                                      [](double time, const Key& key) { return time < key.time; });
  if (later == keys.begin()) return {0, 0, 0.0};
  const std::size_t to = static_cast<std::size_t>(later - keys.begin());
  if (later == keys.end()) return {to - 1, to - 1, 0.0};
  const double s = (t - keys[to - 1].time) / (later->time - keys[to - 1].time);
  return {to - 1, to, interpolation_weight(mode, s)};
}

/// One pose of a keyframed rigid motion.
struct MotionKeyframe {
  double time = 0.0;                ///< s
  Vec3 translation = Vec3::Zero();  ///< T, m
  Vec3 axis = Vec3::UnitZ();        ///< rotation axis through the motion's centre (non-zero)
  double angle = 0.0;               ///< rotation about `axis`, rad (right-handed)
};

/// A rigid pose about a centre c: x ↦ c + R (x − c) + T.
struct RigidPose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  ///< R
  Vec3 translation = Vec3::Zero();                               ///< T, m
};

/// The pose of keyframed motion at time t (s): translations blended componentwise; rotations
/// of two keys about one axis (or antiparallel axes, or with either angle zero) by blending the
/// angle about it, so that a segment may turn more than half a turn (0 to 4π: two turns);
/// about different axes by quaternion slerp, the shortest arc between the two rotations.
/// `keys` non-empty with strictly increasing times (validate_keyframes).
RigidPose keyframe_pose(const std::vector<MotionKeyframe>& keys, Interpolation mode, double t);

/// Throws Error(status) naming `where`.keyframes[k] for a non-finite value, a zero axis or a
/// time not later than the key before it.
void validate_keyframes(const std::vector<MotionKeyframe>& keys, const std::string& where,
                        Status status);

}  // namespace progsim
