#pragma once
/// @file Exact intersection tests of triangle meshes (CGAL's exact predicates): the
/// independent check that a configuration is free of intersections (DESIGN.md §5), used by
/// contact tests and to reject scenes that start intersecting.
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace progsim {

/// Two faces of a mesh whose triangles intersect (other than through shared vertices or
/// edges of adjacent faces). a < b.
struct FacePair {
  int a, b;
};

/// Pairs of intersecting faces of `faces` placed at `positions` (|V| × 3), found with
/// CGAL::Polygon_mesh_processing::self_intersections on an AABB tree, with exact predicates.
/// The mesh may consist of several components: intersections between components count too.
/// Returns at most max_pairs pairs (0: no limit), sorted by (a, b).
/// Precondition: faces reference valid vertices and no face repeats a vertex.
std::vector<FacePair> intersecting_faces(const Positions& positions, const Faces& faces,
                                         std::size_t max_pairs = 0);

/// Throws Error(intersecting) naming the first intersecting face pair and their vertices,
/// prefixed by `label`, if the mesh at `positions` intersects itself.
void check_intersection_free(const Positions& positions, const Faces& faces,
                             const std::string& label);

}  // namespace progsim
