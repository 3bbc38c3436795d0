#pragma once
/// @file Internal to core/mesh: the checks that triangle and tet mesh validation share, worded
/// "<label>: <element> 12 ..." where the element is "face" or "tet".
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"

namespace progsim {

/// Throws Error(Status::invalid_mesh, "<label>: <what>").
[[noreturn]] inline void reject_mesh(const std::string& label, const std::string& what) {
  fail(Status::invalid_mesh, label + ": " + what);
}

/// Rejects the first vertex with a non-finite coordinate.
inline void check_finite_vertices(const Positions& vertices, const std::string& label) {
  for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double x = vertices(v, k);
      if (std::isfinite(x)) continue;
      std::ostringstream s;
      s << "vertex " << v << " has a non-finite coordinate (" << x << ')';
      reject_mesh(label, s.str());
    }
  }
}

/// Rejects the first element (a row of `elements`, named `element`) with an index outside
/// [0, num_vertices).
template <class Elements>
void check_element_indices(const Elements& elements, int num_vertices, const std::string& element,
                           const std::string& label) {
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (Eigen::Index k = 0; k < elements.cols(); ++k) {
      const int v = elements(e, k);
      if (v >= 0 && v < num_vertices) continue;
      reject_mesh(label, element + " " + std::to_string(e) + " references vertex " +
                             std::to_string(v) + ", but the mesh has " +
                             std::to_string(num_vertices) + " vertices");
    }
  }
}

/// Rejects the first vertex that no element uses. Precondition: indices are in range.
template <class Elements>
void check_referenced_vertices(const Elements& elements, int num_vertices,
                               const std::string& element, const std::string& label) {
  std::vector<bool> used(num_vertices, false);
  for (Eigen::Index i = 0; i < elements.size(); ++i) used[elements.data()[i]] = true;
  for (int v = 0; v < num_vertices; ++v)
    if (!used[v])
      reject_mesh(label, "vertex " + std::to_string(v) + " is not referenced by any " + element);
}

}  // namespace progsim
