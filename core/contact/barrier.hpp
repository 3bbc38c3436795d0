#pragma once
/// @file The IPC log barrier on squared distances (Li et al. 2020, eq. 6; with the
/// codimensional thickness offset of C-IPC, Li et al. 2021, §4).

namespace progsim {

/// b(s) = −(s − ŝ)² ln(s / ŝ) for 0 < s < ŝ, 0 for s ≥ ŝ, +∞ for s ≤ 0 (IPC eq. 6).
/// progsim evaluates it on s = d² − ξ² with d the unsigned distance and ξ the thickness
/// offset, and ŝ = (ξ + d̂)² − ξ², so the barrier activates at the gap d − ξ = d̂.
double barrier(double s, double s_hat);
/// db/ds (0 for s ≥ ŝ).
double barrier_first_derivative(double s, double s_hat);
/// d²b/ds² (0 for s ≥ ŝ).
double barrier_second_derivative(double s, double s_hat);

/// The barrier argument s = d² − ξ² of a squared distance d² and offset ξ (C-IPC §4).
inline double barrier_argument(double distance_squared, double offset) {
  return distance_squared - offset * offset;
}
/// The activation ŝ = (ξ + d̂)² − ξ² for offset ξ and activation gap d̂.
inline double barrier_activation(double offset, double dhat) {
  return (offset + dhat) * (offset + dhat) - offset * offset;
}

}  // namespace progsim
