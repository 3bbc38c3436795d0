#pragma once
/// @file The membrane deformation gradient of a triangle, F = D D̄⁻¹ (3 × 2), with D = [x1 − x0,
/// x2 − x0] and D̄ the rest edges in an orthonormal frame of the rest triangle (C-IPC §4;
/// Chen et al. 2018). Shared by the membrane energy and the strain limit.
#include <array>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace progsim {

using Mat32 = Eigen::Matrix<double, 3, 2>;

/// Rest constants of one triangle: F = Σ_a x_a β_aᵀ (rows of beta sum to zero).
struct TriangleFrame {
  Mat32 beta;   ///< ∂F/∂x_a = I₃ ⊗ β_aᵀ
  double area;  ///< rest area Ā (m²)
};

/// The rest frame of face f. Throws Error(invalid_mesh), prefixed by `term`, if the rest
/// triangle has zero or non-finite area.
TriangleFrame rest_triangle_frame(const Positions& rest, const Faces& faces, Eigen::Index f,
                                  const std::string& term);

/// The faces as stencils of three vertex indices, checked: Error(invalid_mesh), prefixed by
/// `term`, naming the face and the index outside [0, num_vertices).
std::vector<std::array<int, 3>> triangle_stencils(const Faces& faces, Eigen::Index num_vertices,
                                                  const std::string& term);

/// F (3 × 2) at the stacked triangle positions xe (9).
inline Mat32 deformation_gradient(const Mat32& beta, const Eigen::Matrix<double, 9, 1>& xe) {
  Mat32 f = xe.segment<3>(0) * beta.row(0);
  f.noalias() += xe.segment<3>(3) * beta.row(1);
  f.noalias() += xe.segment<3>(6) * beta.row(2);
  return f;
}

}  // namespace progsim
