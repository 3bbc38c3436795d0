#include "hierarchy/barycentric_prolongation.hpp"

#include "common/parallel.hpp"

namespace progsim {

BarycentricProlongation::BarycentricProlongation(const Faces& coarse_faces, int coarse_vertices,
                                                 const SurfaceAnchors& anchors)
    : Prolongation(intrinsic_matrix(anchors, coarse_faces, coarse_vertices)) {}

void BarycentricProlongation::offsets(const Positions& coarse, Positions& out) const {
  check_shapes(coarse, out, "offsets");
  out.setZero();
}

void BarycentricProlongation::apply(const Positions& coarse, Positions& fine) const {
  check_shapes(coarse, fine, "apply");
  const Eigen::Index n = fine.rows();
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) fine.row(i) = intrinsic_point(coarse, i).transpose();
}

}  // namespace progsim
