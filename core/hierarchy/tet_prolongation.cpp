#include "hierarchy/tet_prolongation.hpp"

namespace progsim {

ProlongationMatrix tet_prolongation_matrix(const std::vector<TetBinding>& bindings,
                                           const TetMesh& coarse) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(4 * bindings.size());
  for (std::size_t i = 0; i < bindings.size(); ++i)
    for (int k = 0; k < 4; ++k)
      triplets.emplace_back(static_cast<int>(i), coarse.tets(bindings[i].tet, k),
                            bindings[i].weights[k]);
  ProlongationMatrix w(static_cast<Eigen::Index>(bindings.size()), coarse.num_vertices());
  w.setFromTriplets(triplets.begin(), triplets.end());
  return w;
}

}  // namespace progsim
