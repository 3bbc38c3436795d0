#include "energy/neo_hookean_membrane.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"

namespace progsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Invariants of C = FᵀF for a 3×2 F, computed from A = C − I so that small strains keep
/// their relative precision (tr C − 2 − ln det C is O(‖A‖²); forming it from tr C and ln det C
/// would leave only ~1e-16/‖A‖² of relative precision, enough to stall line searches in stiff,
/// bending-dominated problems).
struct Strain {
  Mat2 c;          ///< C = FᵀF
  double det_c;    ///< det C = ‖f₁ × f₂‖²
  double kappa;    ///< det A
  double u;        ///< det C − 1 = tr A + det A
  double log_det;  ///< ln det C
  bool valid;      ///< det C > 0

  explicit Strain(const Mat32& f) {
    c = f.transpose() * f;
    det_c = f.col(0).cross(f.col(1)).squaredNorm();
    const double a00 = f.col(0).squaredNorm() - 1.0, a11 = f.col(1).squaredNorm() - 1.0;
    const double a01 = c(0, 1);
    kappa = a00 * a11 - a01 * a01;
    u = a00 + a11 + kappa;
    valid = det_c > 0.0;
    // log1p(u) near rest; ln ‖f₁ × f₂‖² where u itself has lost its relative precision (slivers).
    log_det = !valid ? 0.0 : std::abs(u) < 0.5 ? std::log1p(u) : std::log(det_c);
  }
  /// C⁻¹ (2×2).
  Mat2 inverse() const {
    Mat2 c_inverse;
    c_inverse << c(1, 1), -c(0, 1), -c(1, 0), c(0, 0);
    return c_inverse / det_c;
  }
};

}  // namespace

NeoHookeanMembrane::NeoHookeanMembrane(const Positions& rest, const Faces& faces,
                                       const std::vector<ShellMaterial>& face_materials)
    : StencilTerm<3>(triangle_stencils(faces, rest.rows(), "membrane"),
                     static_cast<int>(rest.rows())) {
  if (face_materials.size() != static_cast<std::size_t>(faces.rows()))
    fail(Status::invalid_argument, "membrane: " + std::to_string(face_materials.size()) +
                                       " face materials for " + std::to_string(faces.rows()) +
                                       " faces");
  elements_.resize(faces.rows());
  rest_area_.resize(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const TriangleFrame frame = rest_triangle_frame(rest, faces, f, "membrane");
    const double area = frame.area;
    Element& el = elements_[f];
    el.beta = frame.beta;
    const ShellMaterial& m = face_materials[f];
    el.weight = m.thickness * area;
    el.mu = shear_modulus(m);
    el.lambda = plane_stress_lambda(m);
    rest_area_[f] = area;
  }
}

double NeoHookeanMembrane::element_value(int e, const LocalVector& xe) const {
  const Element& el = elements_[e];
  const Strain strain(deformation_gradient(elements_[e].beta, xe));
  if (!strain.valid) return std::numeric_limits<double>::infinity();  // degenerate triangle
  const double l = strain.log_det;
  // W = μ/2 (tr C − 2 − ln det C) + λ/8 (ln det C)² (PSQ footnote 1; Chen et al. 2018),
  // with tr C − 2 − ln det C = (u − log1p(u)) − det A.
  const double w = 0.5 * el.mu * ((strain.u - l) - strain.kappa) + 0.125 * el.lambda * l * l;
  return el.weight * w;
}

void NeoHookeanMembrane::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  const Element& el = elements_[e];
  const Mat32 f = deformation_gradient(elements_[e].beta, xe);
  const Strain strain(f);
  if (!strain.valid) {
    g.setConstant(kNaN);  // infinite energy: no meaningful force (see class comment)
    return;
  }
  // ∂W/∂F = μ F + (λ/2 ln det C − μ) F C⁻¹ (from ∂ ln det C/∂F = 2 F C⁻¹)
  //       = F C⁻¹ (μ (C − I) + λ/2 ln det C I), which is exactly zero at rest.
  Mat2 a = strain.c - Mat2::Identity();
  a *= el.mu;
  a.diagonal().array() += 0.5 * el.lambda * strain.log_det;
  const Mat32 p = f * (strain.inverse() * a);
  // ∂E/∂x_a = t Ā (∂W/∂F) β_a.
  for (int v = 0; v < 3; ++v) g.segment<3>(3 * v) = el.weight * (p * el.beta.row(v).transpose());
}

bool NeoHookeanMembrane::stress_derivative(int e, const Mat32& f, Matrix6& hf) const {
  const Element& el = elements_[e];
  const Strain strain(f);
  if (!strain.valid) return false;
  const double log_det = strain.log_det;
  const Mat2 c_inverse = strain.inverse();
  const Vec3 normal = f.col(0).cross(f.col(1));
  const Mat32 g = f * c_inverse;                                             // G = F C⁻¹
  const Mat3 normal_projector = normal * normal.transpose() / strain.det_c;  // I − F C⁻¹ Fᵀ
  const double s = 0.5 * el.lambda * log_det - el.mu;
  // ∂²W/∂F_ij∂F_kl = μ δ_ik δ_jl + λ G_ij G_kl + s (n̂_i n̂_k C⁻¹_lj − G_il G_kj), from
  // d(F C⁻¹) = n̂n̂ᵀ dF C⁻¹ − G dFᵀ G and d ln det C = 2⟨G, dF⟩. vec F is column-major: r = i+3j.
  for (int l = 0; l < 2; ++l)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
          double v = el.lambda * g(i, j) * g(k, l) +
                     s * (normal_projector(i, k) * c_inverse(l, j) - g(i, l) * g(k, j));
          if (i == k && j == l) v += el.mu;
          hf(i + 3 * j, k + 3 * l) = v;
        }
  return true;
}

void NeoHookeanMembrane::pull_back(int e, const Matrix6& hf, LocalMatrix& h) const {
  const Element& el = elements_[e];
  // T = hf B (6×9), then h = t Ā Bᵀ T; B maps x_a,k to F_kl with weight β_al.
  Eigen::Matrix<double, 6, 9> t;
  for (int b = 0; b < 3; ++b)
    for (int k = 0; k < 3; ++k)
      t.col(3 * b + k) = hf.col(k) * el.beta(b, 0) + hf.col(k + 3) * el.beta(b, 1);
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      h.row(3 * a + i) = el.weight * (el.beta(a, 0) * t.row(i) + el.beta(a, 1) * t.row(i + 3));
}

void NeoHookeanMembrane::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  Matrix6 hf;
  if (!stress_derivative(e, deformation_gradient(elements_[e].beta, xe), hf)) {
    h.setConstant(kNaN);
    return;
  }
  pull_back(e, hf, h);
}

void NeoHookeanMembrane::element_projected_hessian(int e, const LocalVector& xe,
                                                   LocalMatrix& h) const {
  Matrix6 hf;
  if (!projected_stress_derivative(e, deformation_gradient(elements_[e].beta, xe), hf)) {
    h.setConstant(kNaN);
    return;
  }
  pull_back(e, hf, h);
}

bool NeoHookeanMembrane::projected_stress_derivative(int e, const Mat32& f, Matrix6& hf) const {
  const Element& el = elements_[e];
  const Strain strain(f);
  if (!strain.valid) return false;
  const Vec3 normal = f.col(0).cross(f.col(1));
  const double j = std::sqrt(strain.det_c);  // J = σ₁σ₂ = ‖f₁ × f₂‖
  // W is isotropic, W = Ψ(σ₁, σ₂) with σ the singular values of F = U Σ Vᵀ, so ∂²W/∂F² has a
  // closed-form eigensystem (Smith et al. 2019, "Analytic eigensystems for isotropic distortion
  // energies", extended by the two out-of-plane modes n̂ v_jᵀ of a 3×2 F).
  // V from the 2×2 eigenproblem C = FᵀF = V diag(σ₁², σ₂²) Vᵀ.
  const Mat2& c = strain.c;
  const double radius = std::hypot(0.5 * (c(0, 0) - c(1, 1)), c(0, 1));
  const double s1 = std::sqrt(0.5 * (c(0, 0) + c(1, 1)) + radius);
  const double s2 = j / s1;
  const double angle = 0.5 * std::atan2(2.0 * c(0, 1), c(0, 0) - c(1, 1));
  const Vec2 v1(std::cos(angle), std::sin(angle)), v2(-std::sin(angle), std::cos(angle));
  const double mu = el.mu, lambda = el.lambda, log_j = 0.5 * strain.log_det;
  const double q = lambda * log_j - mu;
  // Ψ = μ/2 (σ₁² + σ₂² − 2 − 2 ln J) + λ/2 (ln J)²: out-of-plane n̂v_jᵀ: Ψ_j/σ_j; twist
  // (u₁v₂ᵀ − u₂v₁ᵀ)/√2: (Ψ₁+Ψ₂)/(σ₁+σ₂); flip (u₁v₂ᵀ + u₂v₁ᵀ)/√2: (Ψ₁−Ψ₂)/(σ₁−σ₂);
  // scaling u_jv_jᵀ: the eigensystem of the 2×2 ∂²Ψ/∂σ².
  const double out1 = mu + q / (s1 * s1), out2 = mu + q / (s2 * s2);
  const double twist = mu + q / j, flip = mu - q / j;
  const double p11 = mu * (1.0 + 1.0 / (s1 * s1)) + lambda * (1.0 - log_j) / (s1 * s1);
  const double p22 = mu * (1.0 + 1.0 / (s2 * s2)) + lambda * (1.0 - log_j) / (s2 * s2);
  const double p12 = lambda / j;
  const double p_radius = std::hypot(0.5 * (p11 - p22), p12);
  const double scale1 = 0.5 * (p11 + p22) + p_radius, scale2 = 0.5 * (p11 + p22) - p_radius;
  if (std::min({out1, out2, twist, flip, scale2}) >= 0.0) return stress_derivative(e, f, hf);
  const Vec3 n_hat = normal / j;
  const Vec3 u1 = f * v1 / s1;
  const Vec3 u2 = n_hat.cross(u1);  // = F v₂/σ₂ (V is a rotation), accurate for slivers
  const double p_angle = 0.5 * std::atan2(2.0 * p12, p11 - p22);
  const double pc = std::cos(p_angle), ps = std::sin(p_angle);
  hf.setZero();
  const auto add_mode = [&hf](double eigenvalue, const Mat32& mode) {
    if (eigenvalue <= 0.0) return;
    const Eigen::Map<const Eigen::Matrix<double, 6, 1>> m(mode.data());
    hf.noalias() += eigenvalue * m * m.transpose();
  };
  constexpr double kInvSqrt2 = 0.70710678118654752440;
  add_mode(out1, n_hat * v1.transpose());
  add_mode(out2, n_hat * v2.transpose());
  add_mode(twist, kInvSqrt2 * (u1 * v2.transpose() - u2 * v1.transpose()));
  add_mode(flip, kInvSqrt2 * (u1 * v2.transpose() + u2 * v1.transpose()));
  add_mode(scale1, pc * u1 * v1.transpose() + ps * u2 * v2.transpose());
  add_mode(scale2, -ps * u1 * v1.transpose() + pc * u2 * v2.transpose());
  return true;
}

}  // namespace progsim
