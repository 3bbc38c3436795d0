#include "energy/triangle_frame.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "common/error.hpp"

namespace progsim {

TriangleFrame rest_triangle_frame(const Positions& rest, const Faces& faces, Eigen::Index f,
                                  const std::string& term) {
  const Vec3 x0 = rest.row(faces(f, 0));
  const Vec3 e1 = Vec3(rest.row(faces(f, 1))) - x0, e2 = Vec3(rest.row(faces(f, 2))) - x0;
  const Vec3 normal = e1.cross(e2);
  TriangleFrame frame;
  frame.area = 0.5 * normal.norm();
  if (!(frame.area > 0.0) || !std::isfinite(frame.area))
    fail(Status::invalid_mesh, term + ": rest face " + std::to_string(f) + " is degenerate (area " +
                                   std::to_string(frame.area) + " m²)");
  // D̄ = Tᵀ [e1 e2] (2×2) with T = [t1 t2] an orthonormal frame of the rest triangle's plane.
  Mat32 tangents, edges;
  tangents.col(0) = e1.normalized();
  tangents.col(1) = normal.normalized().cross(tangents.col(0));
  edges << e1, e2;
  const Mat2 rest_inverse = (tangents.transpose() * edges).inverse();
  // F = D D̄⁻¹ = (x1 − x0) D̄⁻¹[0, :] + (x2 − x0) D̄⁻¹[1, :]
  frame.beta.row(1) = rest_inverse.row(0);
  frame.beta.row(2) = rest_inverse.row(1);
  frame.beta.row(0) = -frame.beta.row(1) - frame.beta.row(2);
  return frame;
}

std::vector<std::array<int, 3>> triangle_stencils(const Faces& faces, Eigen::Index num_vertices,
                                                  const std::string& term) {
  std::vector<std::array<int, 3>> stencils(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = faces(f, k);
      if (v < 0 || v >= num_vertices)
        fail(Status::invalid_mesh, term + ": face " + std::to_string(f) + " has vertex index " +
                                       std::to_string(v) + ", outside [0, " +
                                       std::to_string(num_vertices) + ")");
      stencils[f][k] = v;
    }
  return stencils;
}

}  // namespace progsim
