#pragma once
/// @file The linear prolongation between two tet levels, P = W (VPD §3.3): each fine vertex
/// the barycentric combination of the corners of its bound coarse tet (tet_binding.hpp).
#include <vector>

#include "hierarchy/prolongation.hpp"
#include "hierarchy/tet_binding.hpp"

namespace progsim {

/// W (|V_fine| × |V_coarse|), row i the weights of fine vertex i's binding on its tet's corners.
/// Rows sum to 1, so W reproduces every affine map of the coarse mesh exactly (W X̄_c = X̄_f for
/// the rest positions, and translations and rotations of the coarse level move the fine level
/// rigidly).
ProlongationMatrix tet_prolongation_matrix(const std::vector<TetBinding>& bindings,
                                           const TetMesh& coarse);

}  // namespace progsim
