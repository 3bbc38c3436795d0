#pragma once
/// @file How far a scripted step of handle vertices may go before a face next to them collapses:
/// the free vertices stay where they are until the next solve, so a handle moved about one edge
/// length lands on (or passes) its free neighbours and the faces between them lose all their area.
#include "common/types.hpp"

namespace progsim {

/// The largest fraction α ∈ (0, 1] of the scripted step `step` (3|V|, non-zero only where
/// vertices are moved) from `x` (3|V|, m) such that every face with a moved and an unmoved vertex
/// keeps at least `kept` ∈ (0, 1) of its area along its current normal all the way:
/// n(x + α' d)·n(x) ≥ kept |n(x)|² for α' ∈ [0, α], with n = (x₁ − x₀) × (x₂ − x₀) the face's area
/// vector. Faces whose three vertices all move are the script's own and are not bounded.
double max_handle_step(const Faces& faces, const Vector& x, const Vector& step, double kept);

}  // namespace progsim
