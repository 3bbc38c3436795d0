#include "energy/hinge_bending.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace progsim {
namespace {

using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Matrix12x9 = Eigen::Matrix<double, 12, 9>;
using Matrix8 = Eigen::Matrix<double, 8, 8>;
using Matrix12x8 = Eigen::Matrix<double, 12, 8>;

/// Q = W ⊗ I₃ (12×9): an orthonormal basis of the complement of the rigid translations of the
/// four hinge vertices (W's columns are Helmert contrasts, orthogonal to (1, 1, 1, 1)).
Matrix12x9 translation_complement() {
  Eigen::Matrix<double, 4, 3> w;
  w << 1.0, 1.0, 1.0, -1.0, 1.0, 1.0, 0.0, -2.0, 1.0, 0.0, 0.0, -3.0;
  w.col(0) /= std::sqrt(2.0);
  w.col(1) /= std::sqrt(6.0);
  w.col(2) /= std::sqrt(12.0);
  Matrix12x9 q = Matrix12x9::Zero();
  for (int i = 0; i < 4; ++i)
    for (int a = 0; a < 3; ++a) q.block<3, 3>(3 * i, 3 * a) = w(i, a) * Mat3::Identity();
  return q;
}

}  // namespace

HingeBending::HingeBending(const Positions& rest, const Faces& faces,
                           const std::vector<Hinge>& hinges,
                           const std::vector<ShellMaterial>& face_materials)
    : StencilTerm<4>(
          [&] {
            std::vector<Stencil> stencils(hinges.size());
            for (std::size_t e = 0; e < hinges.size(); ++e) {
              stencils[e] = {hinges[e].v0, hinges[e].v1, hinges[e].v2, hinges[e].v3};
              for (int v : stencils[e])
                if (v < 0 || v >= rest.rows())
                  fail(Status::invalid_argument, "bending: hinge " + std::to_string(e) +
                                                     " has vertex index " + std::to_string(v) +
                                                     " out of range");
            }
            return stencils;
          }(),
          static_cast<int>(rest.rows())) {
  const Eigen::Index num_faces = faces.rows();
  if (face_materials.size() != static_cast<std::size_t>(num_faces))
    fail(Status::invalid_argument, "bending: " + std::to_string(face_materials.size()) +
                                       " face materials for " + std::to_string(num_faces) +
                                       " faces");
  const auto face_has = [&](int f, int a, int b, int c) {
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) == a && faces(f, (k + 1) % 3) == b && faces(f, (k + 2) % 3) == c) return true;
    return false;
  };
  elements_.resize(hinges.size());
  for (std::size_t e = 0; e < hinges.size(); ++e) {
    const Hinge& hg = hinges[e];
    if (hg.f0 < 0 || hg.f0 >= num_faces || hg.f1 < 0 || hg.f1 >= num_faces ||
        !face_has(hg.f0, hg.v0, hg.v1, hg.v2) || !face_has(hg.f1, hg.v1, hg.v0, hg.v3))
      fail(Status::invalid_argument,
           "bending: hinge " + std::to_string(e) + " does not match its faces");
    const Vec3 x0 = rest.row(hg.v0), x1 = rest.row(hg.v1), x2 = rest.row(hg.v2),
               x3 = rest.row(hg.v3);
    const Vec3 edge = x1 - x0;
    const double area1 = 0.5 * edge.cross(x2 - x0).norm();
    const double area2 = 0.5 * (x3 - x0).cross(edge).norm();
    if (!(area1 > 0.0) || !(area2 > 0.0) || !std::isfinite(area1 + area2))
      fail(Status::invalid_mesh, "bending: hinge " + std::to_string(e) + " (faces " +
                                     std::to_string(hg.f0) + ", " + std::to_string(hg.f1) +
                                     ") has a degenerate rest face");
    const double k = 0.5 * (hinge_bending_modulus(face_materials[hg.f0]) +
                            hinge_bending_modulus(face_materials[hg.f1]));
    elements_[e].rest_angle = dihedral_angle(x0, x1, x2, x3);
    // ‖ē‖²/(Ā₁ + Ā₂): Grinspun et al. 2003's 3‖ē‖²/(Ā₁ + Ā₂) without the 3, which makes
    // Σ_e over a uniformly bent sheet equal k κ² A, the plate energy (D/2) κ² A with D = 2k.
    elements_[e].stiffness = k * edge.squaredNorm() / (area1 + area2);
  }
}

double HingeBending::angle_change(int e, const LocalVector& xe) const {
  double delta =
      dihedral_angle(xe.segment<3>(0), xe.segment<3>(3), xe.segment<3>(6), xe.segment<3>(9)) -
      elements_[e].rest_angle;
  if (delta > kPi) delta -= 2.0 * kPi;
  if (delta <= -kPi) delta += 2.0 * kPi;
  return delta;
}

double HingeBending::element_value(int e, const LocalVector& xe) const {
  const double delta = angle_change(e, xe);
  return elements_[e].stiffness * delta * delta;  // k (θ − θ̄)² ‖ē‖²/(Ā₁+Ā₂) (Grinspun 2003)
}

void HingeBending::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const double delta = angle_change(e, xe);
  g = (2.0 * elements_[e].stiffness * delta) * HingeFrame(xe).angle_gradient();
}

void HingeBending::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  const double delta = angle_change(e, xe);
  const HingeFrame frame(xe);
  const Vector12 g = frame.angle_gradient();
  // ∇²E = 2 c (∇θ ∇θᵀ + (θ − θ̄) ∇²θ), c = k ‖ē‖²/(Ā₁+Ā₂).
  h = frame.angle_hessian();
  h *= delta;
  h.noalias() += g * g.transpose();
  h *= 2.0 * elements_[e].stiffness;
}

void HingeBending::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  if (projection_ == HingeProjection::gauss_newton || angle_change(e, xe) == 0.0) {
    // At θ = θ̄ the exact Hessian is 2c ∇θ∇θᵀ, PSD already: no eigen-decomposition needed.
    const Vector12 g = HingeFrame(xe).angle_gradient();
    h.noalias() = (2.0 * elements_[e].stiffness) * g * g.transpose();  // 2c ∇θ∇θᵀ
    return;
  }
  static const Matrix12x9 q = translation_complement();
  element_hessian(e, xe, h);
  // Besides the three translations, the stretch along the edge s_i = ((x_i − x0)·ê) ê leaves θ
  // and ∇θ unchanged, so it is in h's null space too. With Q₈ (12×8) an orthonormal basis of
  // the complement of these four, h = Q₈ (Q₈ᵀ h Q₈) Q₈ᵀ exactly, and clamping the eigenvalues
  // of the 8×8 reduced matrix is the 12×12 clamp at about half the cost.
  const Vec3 x0 = xe.segment<3>(0);
  const Vec3 e_hat = (xe.segment<3>(3) - x0).normalized();
  Vector12 stretch;
  for (int i = 0; i < 4; ++i)
    stretch.segment<3>(3 * i) = (xe.segment<3>(3 * i) - x0).dot(e_hat) * e_hat;
  Eigen::Matrix<double, 9, 1> v = q.transpose() * stretch;  // in translation-free coordinates
  v /= v.norm();
  v[8] += v[8] >= 0.0 ? 1.0 : -1.0;  // Householder vector: I − 2vvᵀ/vᵀv maps the stretch to ∓e₉
  const Matrix9 reflector = Matrix9::Identity() - (2.0 / v.squaredNorm()) * v * v.transpose();
  const Matrix12x8 basis = q * reflector.leftCols<8>();
  const Matrix8 reduced = basis.transpose() * h * basis;
  Eigen::SelfAdjointEigenSolver<Matrix8> eig(reduced);
  const Eigen::Matrix<double, 8, 1> lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return;
  const Matrix12x8 modes = basis * eig.eigenvectors();
  h.noalias() = modes * lambda.cwiseMax(0.0).asDiagonal() * modes.transpose();
}

}  // namespace progsim
