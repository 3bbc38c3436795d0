#include "energy/midedge_parts.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "common/error.hpp"

namespace progsim::midedge {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// ∇²_ξ of the products λ1λ2, λ2λ0, λ0λ1 of barycentric coordinates, with ξ = (λ1, λ2).
std::array<Mat2, 3> product_hessians() {
  std::array<Mat2, 3> h;
  h[0] << 0.0, 1.0, 1.0, 0.0;
  h[1] << 0.0, -1.0, -1.0, -2.0;
  h[2] << -2.0, -1.0, -1.0, 0.0;
  return h;
}

/// Row k of the fit's matrix G: for an interior edge, the products μ_{j+1} μ_{j+2} of the
/// barycentric coordinates of p_k unfolded about its edge into the face's plane (the quadratic
/// w = Σ_j c_j λ_{j+1} λ_{j+2}, zero at the corners, takes the height of p_k there); for a
/// boundary edge, κ_nn + ν κ_tt of each product (scaled to 1).
Vec3 fit_row(const std::array<Vec3, 6>& x, const std::array<Vec2, 3>& corner, const Mat2& jinv,
             int k, bool interior, double nu) {
  const int a = (k + 1) % 3, b = (k + 2) % 3;
  const Vec2 tangent = (corner[b] - corner[a]).normalized();
  Vec2 inward(-tangent.y(), tangent.x());
  if (inward.dot(corner[k] - corner[a]) < 0.0) inward = -inward;
  Vec3 row;
  if (interior) {
    const Vec3 edge = (x[b] - x[a]).normalized(), d = x[3 + k] - x[a];
    const double along = d.dot(edge), height = (d - along * edge).norm();
    const Vec2 xi = jinv * (corner[a] + along * tangent - height * inward);
    const Vec3 mu(1.0 - xi.sum(), xi.x(), xi.y());
    for (int j = 0; j < 3; ++j) row[j] = mu[(j + 1) % 3] * mu[(j + 2) % 3];
    return row;
  }
  const std::array<Mat2, 3> h = product_hessians();
  const Vec2 an = jinv * inward, at = jinv * tangent;  // n and t in ξ
  for (int j = 0; j < 3; ++j) row[j] = an.dot(h[j] * an) + nu * at.dot(h[j] * at);
  return row / row.cwiseAbs().maxCoeff();
}

}  // namespace

EdgeHeight::EdgeHeight(const Vec3& e, const Vec3& w) {
  // h² = N/L with N = ‖e‖²‖w‖² − (e·w)² (Lagrange's identity for ‖e × w‖²), L = ‖e‖².
  const double ee = e.squaredNorm(), ww = w.squaredNorm(), ew = e.dot(w);
  const double n = ee * ww - ew * ew;
  const Mat3 id = Mat3::Identity();
  Vector6 gn, gl = Vector6::Zero();
  gn << 2.0 * ww * e - 2.0 * ew * w, 2.0 * ee * w - 2.0 * ew * e;  // ∂N/∂(e, w)
  gl.head<3>() = 2.0 * e;                                          // ∂L/∂(e, w)
  Matrix6 hn, hl = Matrix6::Zero();
  hn.block<3, 3>(0, 0) = 2.0 * ww * id - 2.0 * w * w.transpose();
  hn.block<3, 3>(0, 3) = 4.0 * e * w.transpose() - 2.0 * w * e.transpose() - 2.0 * ew * id;
  hn.block<3, 3>(3, 0) = hn.block<3, 3>(0, 3).transpose();
  hn.block<3, 3>(3, 3) = 2.0 * ee * id - 2.0 * e * e.transpose();
  hl.block<3, 3>(0, 0) = 2.0 * id;
  // Quotient rule for h² = N/L, first and second order.
  const Vector6 g2 = gn / ee - (n / (ee * ee)) * gl;
  const Matrix6 h2 = hn / ee - (gn * gl.transpose() + gl * gn.transpose()) / (ee * ee) +
                     (2.0 * n / (ee * ee * ee)) * gl * gl.transpose() - (n / (ee * ee)) * hl;
  const double value = std::sqrt(n / ee);
  // h = √(h²): ∇h = ∇h²/(2h), ∇²h = ∇²h²/(2h) − ∇h ∇hᵀ/h.
  const Vector6 g = g2 / (2.0 * value);
  const Matrix6 hh = h2 / (2.0 * value) - g * g.transpose() / value;
  // (e, w) = A (x0, x1, x2) with A = [[−I, I, 0], [−I, 0, I]].
  Eigen::Matrix<double, 6, 9> a = Eigen::Matrix<double, 6, 9>::Zero();
  a.block<3, 3>(0, 0) = -id;
  a.block<3, 3>(0, 3) = id;
  a.block<3, 3>(3, 0) = -id;
  a.block<3, 3>(3, 6) = id;
  gradient = a.transpose() * g;
  hessian = a.transpose() * hh * a;
}

double height_sine(const Vector12& xh, Vector12* gradient, Matrix12* hessian) {
  const HingeFrame frame(xh);
  const double theta = frame.angle();
  const double sin_half = std::sin(0.5 * theta), cos_half = std::cos(0.5 * theta);
  const double h = std::sqrt(frame.n1_sq) / frame.length;  // ‖e × w‖/‖e‖
  if (!gradient) return 2.0 * h * sin_half;
  const EdgeHeight height(frame.e, frame.w);
  Vector12 dh = Vector12::Zero();
  dh.head<9>() = height.gradient;
  const Vector12 dtheta = frame.angle_gradient();
  // ∇s = 2 sin(θ/2) ∇h + h cos(θ/2) ∇θ.
  *gradient = 2.0 * sin_half * dh + h * cos_half * dtheta;
  if (hessian) {
    // ∇²s = 2 sin(θ/2) ∇²h + cos(θ/2)(∇h∇θᵀ + ∇θ∇hᵀ) + h cos(θ/2) ∇²θ − (h/2) sin(θ/2) ∇θ∇θᵀ.
    *hessian = (h * cos_half) * frame.angle_hessian();
    hessian->topLeftCorner<9, 9>() += (2.0 * sin_half) * height.hessian;
    hessian->noalias() += cos_half * (dh * dtheta.transpose() + dtheta * dh.transpose());
    hessian->noalias() -= (0.5 * h * sin_half) * dtheta * dtheta.transpose();
  }
  return 2.0 * h * sin_half;
}

double bending_modulus(const ShellMaterial& m) {
  return m.bending_youngs_modulus > 0.0 ? m.bending_youngs_modulus : m.youngs_modulus;
}

Mat3 face_stiffness(const Vec3& q0, const Vec3& q1, const Vec3& q2, const ShellMaterial& m, int f) {
  const Vec3 e1 = q1 - q0, e2 = q2 - q0;
  const double area = 0.5 * e1.cross(e2).norm();
  if (!(area > 0.0) || !std::isfinite(area))
    fail(Status::invalid_mesh, "bending: face " + std::to_string(f) + " has zero rest area");
  Mat2 abar;  // ā, the rest first fundamental form in the basis (e1, e2)
  abar << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
  const Mat2 abar_inverse = abar.inverse();
  const double eb = bending_modulus(m), nu = m.poisson_ratio, t = m.thickness;
  const double alpha = eb * nu / (1.0 - nu * nu);  // α = E ν/(1 − ν²)
  const double beta = eb / (2.0 * (1.0 + nu));     // β = E/(2(1 + ν))
  const double c = t * t * t * area / 12.0;
  Mat2 basis[3];
  basis[0] << 1.0, 1.0, 1.0, 1.0;
  basis[1] << 1.0, 0.0, 0.0, 0.0;
  basis[2] << 0.0, 0.0, 0.0, 1.0;
  Vec3 traces;
  Mat2 products[3];
  for (int k = 0; k < 3; ++k) {
    products[k] = abar_inverse * basis[k];
    traces[k] = products[k].trace();  // tr(ā⁻¹ B_k)
  }
  Mat3 pairs;  // tr(ā⁻¹B_k ā⁻¹B_l)
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) pairs(k, l) = (products[k] * products[l]).trace();
  return c * (alpha * traces * traces.transpose() + 2.0 * beta * pairs);
}

std::vector<Across> faces_across(const Faces& faces, const std::vector<Hinge>& hinges,
                                 int num_vertices, std::size_t num_materials) {
  if (num_materials != static_cast<std::size_t>(faces.rows()))
    fail(Status::invalid_argument, "bending: " + std::to_string(num_materials) +
                                       " face materials for " + std::to_string(faces.rows()) +
                                       " faces");
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= num_vertices)
        fail(Status::invalid_argument, "bending: face " + std::to_string(f) + " has vertex index " +
                                           std::to_string(faces(f, k)) + " out of range");
  std::vector<Across> across(faces.rows());
  const auto corner = [&](int f, int v) {
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) == v) return k;
    return -1;
  };
  for (std::size_t e = 0; e < hinges.size(); ++e) {
    const Hinge& hg = hinges[e];
    const int k0 = hg.f0 >= 0 && hg.f0 < faces.rows() ? corner(hg.f0, hg.v2) : -1;
    const int k1 = hg.f1 >= 0 && hg.f1 < faces.rows() ? corner(hg.f1, hg.v3) : -1;
    if (k0 < 0 || k1 < 0 || faces(hg.f0, (k0 + 1) % 3) != hg.v0 ||
        faces(hg.f0, (k0 + 2) % 3) != hg.v1 || faces(hg.f1, (k1 + 1) % 3) != hg.v1 ||
        faces(hg.f1, (k1 + 2) % 3) != hg.v0)
      fail(Status::invalid_argument,
           "bending: hinge " + std::to_string(e) + " does not match its faces");
    across[hg.f0].vertex[k0] = hg.v3;
    across[hg.f0].face[k0] = hg.f1;
    across[hg.f1].vertex[k1] = hg.v2;
    across[hg.f1].face[k1] = hg.f0;
  }
  return across;
}

QuadraticFit::QuadraticFit(const std::array<Vec3, 6>& x, const std::array<bool, 3>& interior,
                           double nu) {
  for (Mat2& k : curvatures) k.setZero();
  const Vec3 e1 = x[1] - x[0], e2 = x[2] - x[0];
  const Vec3 ex = e1.normalized(), ey = e1.cross(e2).cross(e1).normalized();
  corners = {Vec2::Zero(), Vec2(e1.dot(ex), e1.dot(ey)), Vec2(e2.dot(ex), e2.dot(ey))};
  Mat2 jac;
  jac << corners[1], corners[2];
  const Mat2 jinv = jac.inverse();
  Mat3 g;
  for (int k = 0; k < 3; ++k) g.row(k) = fit_row(x, corners, jinv, k, interior[k], nu);
  // Conditioned by the singular values (FullPivLU::rcond() estimates 0.25 for an exactly
  // singular G, e.g. six points on one circle); false for NaN (a degenerate face) too.
  const Eigen::JacobiSVD<Mat3> svd(g, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 sigma = svd.singularValues();
  unique = jinv.allFinite() && sigma.allFinite() && sigma[2] >= 1e-6 * sigma[0];
  if (!unique) return;
  // c = G⁻¹ η, κ_ξ = Σ_j c_j ∇²_ξ(λ_{j+1} λ_{j+2}), κ = J⁻ᵀ κ_ξ J⁻¹ (Cartesian).
  const Mat3 ginv = svd.matrixV() * sigma.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  const std::array<Mat2, 3> h = product_hessians();
  for (int k = 0; k < 3; ++k) {
    Mat2 xi = Mat2::Zero();
    if (interior[k])
      for (int j = 0; j < 3; ++j) xi += ginv(j, k) * h[j];
    curvatures[k] = jinv.transpose() * xi * jinv;
  }
}

}  // namespace progsim::midedge
