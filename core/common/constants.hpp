#pragma once
/// @file Mathematical constants shared by every part of progsim.

namespace progsim {

/// π to double precision.
inline constexpr double kPi = 3.14159265358979323846;
/// 2π (exactly twice kPi in double precision).
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace progsim
