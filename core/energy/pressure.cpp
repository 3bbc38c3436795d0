#include "energy/pressure.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {
namespace {

/// [v]×, the matrix of v × · (3×3).
Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// For each face and edge k (corner k → k+1), the vertex opposite the same edge in the face
/// that runs it the other way, or −1 if that face is missing or not unique.
std::vector<std::array<int, 3>> opposite_across_edges(const Faces& faces) {
  struct Directed {
    int from, to, opposite;
    bool operator<(const Directed& o) const { return from != o.from ? from < o.from : to < o.to; }
  };
  std::vector<Directed> edges;
  edges.reserve(3 * faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      edges.push_back({faces(f, k), faces(f, (k + 1) % 3), faces(f, (k + 2) % 3)});
  std::sort(edges.begin(), edges.end());
  // The opposite vertex of the unique directed edge from → to, or −1.
  const auto unique_opposite = [&](int from, int to) {
    const Directed key{from, to, 0};
    const auto range = std::equal_range(edges.begin(), edges.end(), key);
    return range.second - range.first == 1 ? range.first->opposite : -1;
  };
  std::vector<std::array<int, 3>> across(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      across[f][k] = unique_opposite(a, b) >= 0 ? unique_opposite(b, a) : -1;
    }
  return across;
}

}  // namespace

Pressure::Pressure(const Positions& rest, const Faces& faces, double pressure)
    : StencilTerm<3>(triangle_stencils(faces, rest.rows(), "pressure"),
                     static_cast<int>(rest.rows())),
      pressure_(pressure),
      origin_(Vec3::Zero()),
      across_(opposite_across_edges(faces)) {
  std::vector<int> vertices(faces.data(), faces.data() + faces.size());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  for (int v : vertices) origin_ += rest.row(v).transpose();
  if (!vertices.empty()) origin_ /= static_cast<double>(vertices.size());
  closed_ = !across_.empty();
  for (const auto& across : across_)
    for (int d : across) closed_ = closed_ && d >= 0;
  if (closed_) {
    const double rest_volume = volume(as_dofs(rest));
    if (rest_volume < 0.0)
      fail(Status::invalid_mesh, "pressure: the closed surface has negative volume (" +
                                     std::to_string(rest_volume) +
                                     " m³); its faces must be oriented outwards");
  }
}

double Pressure::volume(const Vector& x) const {
  return ordered_sum(num_elements(),
                     [&](long e) { return element_volume(gather(static_cast<int>(e), x)); });
}

double Pressure::element_volume(const LocalVector& xe) const {
  const Vec3 a = xe.segment<3>(0) - origin_, b = xe.segment<3>(3) - origin_,
             c = xe.segment<3>(6) - origin_;
  return a.dot(b.cross(c)) / 6.0;  // signed tetrahedron volume (divergence theorem)
}

double Pressure::element_value(int, const LocalVector& xe) const {
  return -pressure_ * element_volume(xe);  // E = −p V
}

void Pressure::element_gradient(int, const LocalVector& xe, LocalVector& g) const {
  const Vec3 a = xe.segment<3>(0) - origin_, b = xe.segment<3>(3) - origin_,
             c = xe.segment<3>(6) - origin_;
  const double s = -pressure_ / 6.0;  // ∂(a·(b×c))/∂a = b×c, and cyclically
  g.segment<3>(0) = s * b.cross(c);
  g.segment<3>(3) = s * c.cross(a);
  g.segment<3>(6) = s * a.cross(b);
}

void Pressure::element_hessian(int, const LocalVector& xe, LocalMatrix& h) const {
  const Vec3 a = xe.segment<3>(0) - origin_, b = xe.segment<3>(3) - origin_,
             c = xe.segment<3>(6) - origin_;
  // ∂²(a·(b×c))/∂a∂b = −[c]×, ∂b∂c = −[a]×, ∂c∂a = −[b]×; diagonal blocks vanish.
  const double s = pressure_ / 6.0;
  const Mat3 ab = s * cross_matrix(c), bc = s * cross_matrix(a), ca = s * cross_matrix(b);
  h.setZero();
  h.block<3, 3>(0, 3) = ab;
  h.block<3, 3>(3, 0) = ab.transpose();
  h.block<3, 3>(3, 6) = bc;
  h.block<3, 3>(6, 3) = bc.transpose();
  h.block<3, 3>(6, 0) = ca;
  h.block<3, 3>(0, 6) = ca.transpose();
}

void Pressure::hessian_values(const Vector& x, bool project_psd, double* values) const {
  const double s = pressure_ / 6.0;
#pragma omp parallel for schedule(static) num_threads(loop_threads(num_elements()))
  for (int f = 0; f < num_elements(); ++f) {
    const LocalVector xe = gather(f, x);
    Eigen::Map<LocalMatrix> h(values + static_cast<std::size_t>(f) * kDofs * kDofs);
    h.setZero();
    for (int k = 0; k < 3; ++k) {
      const int i = k, j = (k + 1) % 3, opposite = (k + 2) % 3;
      // Edge a → b of this face: ∂²E/∂x_a∂x_b = (p/6)[x_c − x_d]× summed over both faces;
      // half of it is written here (the neighbour writes the other half), all of it on a
      // boundary edge, where x_d is o.
      const int d = across_[f][k];
      const Vec3 far = d >= 0 ? Vec3(x.segment<3>(3 * d)) : origin_;
      const double weight = d >= 0 ? 0.5 : 1.0;
      const Vec3 v = xe.segment<3>(3 * opposite) - far;
      const Mat3 block = (weight * s) * cross_matrix(v);
      if (!project_psd) {
        h.block<3, 3>(3 * i, 3 * j) += block;
        h.block<3, 3>(3 * j, 3 * i) += block.transpose();
        continue;
      }
      // Eigenvalue clamp of [[0, K], [Kᵀ, 0]]: ½ [[(KKᵀ)^½, K], [Kᵀ, (KᵀK)^½]], and for
      // K = κ[v]×, (KKᵀ)^½ = (KᵀK)^½ = |κ| ‖v‖ (I − v̂v̂ᵀ).
      const double length = v.norm();
      Mat3 root = (weight * std::abs(s) * length) * Mat3::Identity();
      if (length > 0.0) root.noalias() -= (weight * std::abs(s) / length) * v * v.transpose();
      h.block<3, 3>(3 * i, 3 * i) += 0.5 * root;
      h.block<3, 3>(3 * j, 3 * j) += 0.5 * root;
      h.block<3, 3>(3 * i, 3 * j) += 0.5 * block;
      h.block<3, 3>(3 * j, 3 * i) += 0.5 * block.transpose();
    }
  }
}

}  // namespace progsim
