#include "hierarchy/tet_hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "hierarchy/decimation.hpp"
#include "hierarchy/tet_prolongation.hpp"
#include "mesh/mesh_topology.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_mesh_validation.hpp"

namespace progsim {
namespace {

/// Where each phase ends in the progress fraction: decimation, then tetrahedralization, then
/// binding, each spread evenly over its levels.
constexpr double kDecimationEnd = 0.2;
constexpr double kTetrahedralizationEnd = 0.8;

/// The caller's progress callback, rescaled to the part [lo, hi] of the whole build.
struct ProgressSpan {
  HierarchyProgress progress;
  void* user;
  double lo, hi;

  /// Reports `fraction` of this span; throws Error(cancelled) if the callback says stop.
  void report(double fraction, const char* phase) const {
    if (progress && !forward(const_cast<ProgressSpan*>(this), fraction, phase))
      fail(Status::cancelled, "tet hierarchy: cancelled by the progress callback");
  }

  /// A HierarchyProgress (for decimate()) whose user pointer is a ProgressSpan with a callback.
  static bool forward(void* span, double fraction, const char* phase) {
    const auto* self = static_cast<const ProgressSpan*>(span);
    return self->progress(self->user, self->lo + (self->hi - self->lo) * fraction, phase);
  }
};

void check_counts(std::vector<int> counts, int boundary_vertices) {
  std::sort(counts.begin(), counts.end());
  for (std::size_t k = 0; k < counts.size(); ++k)
    if (counts[k] < 4 || counts[k] >= boundary_vertices || (k > 0 && counts[k] == counts[k - 1]))
      fail(Status::invalid_argument,
           "tet hierarchy: boundary vertex count " + std::to_string(counts[k]) +
               " must be at least 4, below the finest boundary's " +
               std::to_string(boundary_vertices) + " vertices and given once");
}

/// S_0 … S_{L−1}: the finest boundary decimated to the counts (VPD §3.1.2, Garland–Heckbert).
std::vector<TriangleMesh> decimated_surfaces(const TriangleMesh& boundary,
                                             const TetHierarchyOptions& tet_options,
                                             const ProgressSpan& span) {
  HierarchyOptions options;
  options.coarse_vertex_counts = tet_options.coarse_boundary_vertex_counts;
  options.keep_input_positions = tet_options.keep_input_positions;
  ProgressSpan forwarded = span;
  const MeshHierarchy surfaces =
      decimate(boundary, options, span.progress ? &ProgressSpan::forward : nullptr, &forwarded);
  std::vector<TriangleMesh> out;
  for (int l = 0; l < surfaces.finest(); ++l) out.push_back(surfaces.levels[l].rest);
  return out;
}

/// The tetrahedralization bounds of one level, scaled with its surface's mean edge length.
TetrahedralizeOptions level_options(const TriangleMesh& surface,
                                    const TetHierarchyOptions& options) {
  const double mean_edge =
      mean_edge_length(build_topology(surface.faces, surface.num_vertices()), surface.vertices);
  TetrahedralizeOptions o = options.tetrahedralize;
  o.cell_size = o.facet_size = o.edge_size = options.size_factor * mean_edge;
  o.facet_distance = o.cell_size / 10.0;
  return o;
}

}  // namespace

TetHierarchy build_tet_hierarchy(const TetMesh& finest, const TetHierarchyOptions& options,
                                 HierarchyProgress progress, void* user) {
  validate_tet_mesh(finest, "tet hierarchy: finest level");
  if (!(options.size_factor > 0.0) || !std::isfinite(options.size_factor))
    fail(Status::invalid_argument, "tet hierarchy: size_factor must be positive and finite (got " +
                                       std::to_string(options.size_factor) + ")");
  // VPD §3.1.2: the finest boundary S_L, decimated into S_{L−1} … S_0.
  const TriangleMesh boundary = extract_tet_boundary(finest).surface;
  check_counts(options.coarse_boundary_vertex_counts, boundary.num_vertices());
  const std::vector<TriangleMesh> surfaces =
      decimated_surfaces(boundary, options, {progress, user, 0.0, kDecimationEnd});
  TetHierarchy hierarchy;
  const int coarse_levels = static_cast<int>(surfaces.size());
  for (int l = 0; l < coarse_levels; ++l) {
    // VPD §3.1.2: each surface tetrahedralized on its own (CGAL Mesh_3 here, TetWild there).
    hierarchy.levels.push_back(
        tetrahedralize_surface(surfaces[l], level_options(surfaces[l], options)));
    ProgressSpan{progress, user, kDecimationEnd, kTetrahedralizationEnd}.report(
        (l + 1.0) / coarse_levels, "tetrahedralization");
  }
  hierarchy.levels.push_back(finest);
  for (int l = 0; l < coarse_levels; ++l) {
    // VPD §3.3.3: level l+1's vertices bound to level l's tets, W_l from the weights.
    hierarchy.bindings.push_back(bind_to_tets(hierarchy.levels[l], hierarchy.levels[l + 1]));
    hierarchy.to_finer.push_back(
        tet_prolongation_matrix(hierarchy.bindings[l], hierarchy.levels[l]));
    ProgressSpan{progress, user, kTetrahedralizationEnd, 1.0}.report((l + 1.0) / coarse_levels,
                                                                     "binding");
  }
  return hierarchy;
}

}  // namespace progsim
