#pragma once
/// @file The one rule every path applies before any work when contact is on: a start that
/// crosses itself or an obstacle (CGAL's exact predicates), or brings a pair within its contact
/// offset, is refused naming the pair (IPC's invariant: no accepted state ever intersects).
#include <cstddef>
#include <string>
#include <vector>

#include "contact/contact_potential.hpp"
#include "mesh/intersection_check.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// Face pairs of the shell at x (stacked DOFs) and the obstacles where `contact` holds them
/// that cross, by CGAL's exact predicates; at most max_pairs (0: all).
std::vector<FacePair> crossing_faces(const ContactPotential& contact, const Vector& x,
                                     std::size_t max_pairs);

/// Throws Error(intersecting) "<label>: shell face f (vertices a, b, c) and … cross" if the
/// shell at x crosses itself or an obstacle. `input_vertex` (empty: the identity) maps shell
/// vertices to the input mesh's, so a coarse level's message names the user's vertices.
void check_crossing_free(const ContactPotential& contact, const Vector& x, const std::string& label,
                         const std::vector<int>& input_vertex = {});

/// The scene's finest shell at rest, its obstacles at t = 0 and its ground, with contact on:
/// throws Error(intersecting) naming the first crossing face pair of the input (or a pair
/// closer than its contact offset). Does nothing without the contact effect.
void check_input_contact_free(const Scene& scene);

/// Crossing face pairs of the scene's finest shell at rest among its obstacles at t = 0.
std::size_t input_crossing_pairs(const Scene& scene);

}  // namespace progsim
