#include "energy/hyperelastic_density.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace progsim {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// det F − 1 from H = F − I, without forming det F: tr H + i₂(H) + det H, so that a small
/// strain keeps its relative precision (the energies are O(‖H‖²) near rest).
double volume_change(const Mat3& h) {
  const double trace = h.trace();
  const double second_invariant = 0.5 * (trace * trace - (h * h).trace());
  return trace + second_invariant + h.determinant();
}

/// u − ln(1 + u), O(u²): a series where the subtraction would cancel.
double u_minus_log1p(double u) {
  if (std::abs(u) > 1e-2) return u - std::log1p(u);
  double term = u * u, sum = 0.0;  // Σ_{k≥2} (−1)^k u^k / k
  for (int k = 2; k <= 9; ++k, term *= -u) sum += term / k;
  return sum;
}

/// The 9×9 matrix of X ↦ A X B over vec X (column-major): ∂(AXB)_ij/∂X_kl = A_ik B_lj.
Mat9 sandwich(const Mat3& a, const Mat3& b) {
  Mat9 m;
  for (int l = 0; l < 3; ++l)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) m(i + 3 * j, k + 3 * l) = a(i, k) * b(l, j);
  return m;
}

/// The 9×9 matrix of X ↦ A Xᵀ B over vec X: ∂(AXᵀB)_ij/∂X_kl = A_il B_kj.
Mat9 transposed_sandwich(const Mat3& a, const Mat3& b) {
  Mat9 m;
  for (int l = 0; l < 3; ++l)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) m(i + 3 * j, k + 3 * l) = a(i, l) * b(k, j);
  return m;
}

Eigen::Map<const Eigen::Matrix<double, 9, 1>> vec(const Mat3& m) {
  return Eigen::Map<const Eigen::Matrix<double, 9, 1>>(m.data());
}

/// cof F = det F · F⁻ᵀ, column j = f_{j+1} × f_{j+2} (columns f of F), defined for any F.
Mat3 cofactor(const Mat3& f) {
  Mat3 c;
  for (int j = 0; j < 3; ++j) c.col(j) = f.col((j + 1) % 3).cross(f.col((j + 2) % 3));
  return c;
}

Mat3 cross_matrix(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

/// ∂²(det F)/∂F² (9×9): block (j, l) is ∂(cof F)_{:,j}/∂f_l = ±[f_m]× (m the third column).
Mat9 determinant_hessian(const Mat3& f) {
  Mat9 m = Mat9::Zero();
  for (int j = 0; j < 3; ++j) {
    const int next = (j + 1) % 3, last = (j + 2) % 3;
    m.block<3, 3>(3 * j, 3 * next) = -cross_matrix(f.col(last));  // ∂(f_n × f_l)/∂f_n
    m.block<3, 3>(3 * j, 3 * last) = cross_matrix(f.col(next));   // ∂(f_n × f_l)/∂f_l
  }
  return m;
}

/// F = U Σ Vᵀ with U, V rotations (det +1); Σ's last entry carries the sign of det F.
struct RotationSvd {
  Mat3 u, v;
  Vec3 sigma;
  explicit RotationSvd(const Mat3& f) {
    const Eigen::JacobiSVD<Mat3> svd(f, Eigen::ComputeFullU | Eigen::ComputeFullV);
    u = svd.matrixU();
    v = svd.matrixV();
    sigma = svd.singularValues();
    if (u.determinant() < 0.0) {
      u.col(2) *= -1.0;
      sigma(2) *= -1.0;
    }
    if (v.determinant() < 0.0) {
      v.col(2) *= -1.0;
      sigma(2) *= -1.0;
    }
  }
  Mat3 rotation() const { return u * v.transpose(); }
};

// ---- neo-Hookean: ψ = μ/2 (tr C − 3) − μ ln J + λ/2 (ln J)² (Bonet and Wood 2008, eq. 6.27)

double neo_hookean_density(const LameParameters& p, const Mat3& f) {
  const Mat3 h = f - Mat3::Identity();
  const double u = volume_change(h);
  if (!(u > -1.0)) return std::numeric_limits<double>::infinity();
  const double log_j = std::log1p(u);
  // tr C − 3 − 2 ln J = ‖H‖² + 2(tr H − ln J), and tr H − ln J = (u − ln(1+u)) − i₂ − det H.
  const double i2_plus_det = u - h.trace();
  const double deviatoric = h.squaredNorm() + 2.0 * (u_minus_log1p(u) - i2_plus_det);
  return 0.5 * p.mu * deviatoric + 0.5 * p.lambda * log_j * log_j;
}

Mat3 neo_hookean_stress(const LameParameters& p, const Mat3& f) {
  const double j = f.determinant();
  if (!(j > 0.0)) return Mat3::Constant(kNaN);
  const Mat3 f_inv_t = f.inverse().transpose();
  // P = μ (F − F⁻ᵀ) + λ ln J F⁻ᵀ (Bonet and Wood 2008, eq. 6.28)
  return p.mu * (f - f_inv_t) +
         p.lambda * std::log1p(volume_change(f - Mat3::Identity())) * f_inv_t;
}

Mat9 neo_hookean_stress_derivative(const LameParameters& p, const Mat3& f) {
  const double j = f.determinant();
  if (!(j > 0.0)) return Mat9::Constant(kNaN);
  const Mat3 g = f.inverse().transpose();
  const double log_j = std::log1p(volume_change(f - Mat3::Identity()));
  // ∂P_ij/∂F_kl = μ δ_ik δ_jl + (μ − λ ln J) G_il G_kj + λ G_ij G_kl, G = F⁻ᵀ
  // (from dF⁻ᵀ = −F⁻ᵀ dFᵀ F⁻ᵀ and d ln J = ⟨F⁻ᵀ, dF⟩).
  Mat9 d = (p.mu - p.lambda * log_j) * transposed_sandwich(g, g);
  d.noalias() += p.lambda * vec(g) * vec(g).transpose();
  d.diagonal().array() += p.mu;
  return d;
}

// ---- St. Venant–Kirchhoff: ψ = μ tr E² + λ/2 (tr E)² (Bonet and Wood 2008, eq. 6.11)

Mat3 green_strain(const Mat3& f) {
  const Mat3 h = f - Mat3::Identity();
  return 0.5 * (h + h.transpose() + h.transpose() * h);  // (FᵀF − I)/2 without cancellation
}

double stvk_density(const LameParameters& p, const Mat3& f) {
  const Mat3 e = green_strain(f);
  return p.mu * e.squaredNorm() + 0.5 * p.lambda * e.trace() * e.trace();
}

/// S = 2μE + λ tr E I, the second Piola–Kirchhoff stress.
Mat3 stvk_second_piola(const LameParameters& p, const Mat3& f) {
  const Mat3 e = green_strain(f);
  return 2.0 * p.mu * e + p.lambda * e.trace() * Mat3::Identity();
}

Mat3 stvk_stress(const LameParameters& p, const Mat3& f) {
  return f * stvk_second_piola(p, f);
}

Mat9 stvk_stress_derivative(const LameParameters& p, const Mat3& f) {
  // ∂P_ij/∂F_kl = δ_ik S_lj + μ F_il F_kj + μ (FFᵀ)_ik δ_jl + λ F_ij F_kl (from P = FS and
  // dS = 2μ dE + λ tr(dE) I, dE = (dFᵀF + FᵀdF)/2).
  Mat9 d = sandwich(Mat3::Identity(), stvk_second_piola(p, f));
  d += p.mu * transposed_sandwich(f, f);
  d += p.mu * sandwich(f * f.transpose(), Mat3::Identity());
  d.noalias() += p.lambda * vec(f) * vec(f).transpose();
  return d;
}

// ---- fixed corotated: ψ = μ ‖F − R‖² + λ/2 (J − 1)² (Stomakhin et al. 2012, eq. 4)

double corotated_density(const LameParameters& p, const Mat3& f) {
  const RotationSvd svd(f);
  const double u = volume_change(f - Mat3::Identity());
  return p.mu * (svd.sigma.array() - 1.0).square().sum() + 0.5 * p.lambda * u * u;
}

Mat3 corotated_stress(const LameParameters& p, const Mat3& f) {
  // P = 2μ (F − R) + λ (J − 1) cof F (Stomakhin et al. 2012, eq. 5)
  const double u = volume_change(f - Mat3::Identity());
  return 2.0 * p.mu * (f - RotationSvd(f).rotation()) + p.lambda * u * cofactor(f);
}

/// ∂R/∂F (9×9): on the twist modes U (e_a e_bᵀ − e_b e_aᵀ) Vᵀ/√2 the eigenvalue 2/(σ_a + σ_b),
/// zero on the other six modes (Smith, de Goes and Kim 2019, "Analytic eigensystems for
/// isotropic distortion energies", §5.1).
Mat9 rotation_derivative(const RotationSvd& svd) {
  Mat9 d = Mat9::Zero();
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    const double sum = svd.sigma(a) + svd.sigma(b);
    if (!(std::abs(sum) > 1e-300)) continue;  // the twist is undefined: no rotation change
    const Mat3 mode =
        (svd.u.col(a) * svd.v.col(b).transpose() - svd.u.col(b) * svd.v.col(a).transpose()) *
        std::sqrt(0.5);
    d.noalias() += (2.0 / sum) * vec(mode) * vec(mode).transpose();
  }
  return d;
}

Mat9 corotated_stress_derivative(const LameParameters& p, const Mat3& f) {
  const RotationSvd svd(f);
  const double u = volume_change(f - Mat3::Identity());
  const Mat3 cof = cofactor(f);
  // 2μ (I − ∂R/∂F) + λ (cof F ⊗ cof F + (J − 1) ∂²J/∂F²)
  Mat9 d = -2.0 * p.mu * rotation_derivative(svd);
  d.diagonal().array() += 2.0 * p.mu;
  d.noalias() += p.lambda * vec(cof) * vec(cof).transpose();
  d += p.lambda * u * determinant_hessian(f);
  return d;
}

}  // namespace

double hyperelastic_density(SolidModel model, const LameParameters& lame, const Mat3& f) {
  switch (model) {
    case SolidModel::neo_hookean:
      return neo_hookean_density(lame, f);
    case SolidModel::stvk:
      return stvk_density(lame, f);
    case SolidModel::corotated:
      return corotated_density(lame, f);
  }
  return kNaN;
}

Mat3 first_piola_stress(SolidModel model, const LameParameters& lame, const Mat3& f) {
  switch (model) {
    case SolidModel::neo_hookean:
      return neo_hookean_stress(lame, f);
    case SolidModel::stvk:
      return stvk_stress(lame, f);
    case SolidModel::corotated:
      return corotated_stress(lame, f);
  }
  return Mat3::Constant(kNaN);
}

Mat9 stress_derivative(SolidModel model, const LameParameters& lame, const Mat3& f) {
  switch (model) {
    case SolidModel::neo_hookean:
      return neo_hookean_stress_derivative(lame, f);
    case SolidModel::stvk:
      return stvk_stress_derivative(lame, f);
    case SolidModel::corotated:
      return corotated_stress_derivative(lame, f);
  }
  return Mat9::Constant(kNaN);
}

}  // namespace progsim
