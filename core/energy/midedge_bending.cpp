#include "energy/midedge_bending.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "energy/dihedral_angle.hpp"
#include "energy/psd_projection.hpp"

namespace progsim {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Vector9 = Eigen::Matrix<double, 9, 1>;

/// Derivatives of the height h = ‖e × w‖/‖e‖ (m) of x2 over the line x0 x1: ∇h (9) and
/// ∇²h (9 × 9) in (x0, x1, x2), e = x1 − x0, w = x2 − x0.
struct EdgeHeight {
  Vector9 gradient;
  Matrix9 hessian;

  EdgeHeight(const Vec3& e, const Vec3& w) {
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
};

/// The local slots (x0, x1, x2, x3) of the hinge across the edge opposite q_i in the element
/// (q0, q1, q2, p0, p1, p2): x0 = q_{i+1}, x1 = q_{i+2}, x2 = q_i, x3 = p_i, so that the
/// face (x0, x1, x2) is the element's face in its own orientation.
std::array<int, 4> hinge_slots(int i) {
  return {(i + 1) % 3, (i + 2) % 3, i, 3 + i};
}

/// s = 2 h sin(θ/2) of one hinge (m), see MidedgeBending; with ∇s (12), ∇²s (12 × 12) if asked.
double hinge_edge_value(const Vector12& xh, Vector12* gradient, Matrix12* hessian) {
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

/// The element's hinge across the edge opposite q_i, stacked (12).
Vector12 hinge_positions(const StencilTerm<6>::LocalVector& xe, int i) {
  Vector12 xh;
  const std::array<int, 4> slots = hinge_slots(i);
  for (int k = 0; k < 4; ++k) xh.segment<3>(3 * k) = xe.segment<3>(3 * slots[k]);
  return xh;
}

/// Q (J/m²) with ½ Δsᵀ Q Δs = c [(α/2) tr²(M) + β tr(M²)], M = ā⁻¹ B(Δs), where
/// B(Δs) = −(Δs₀ [[1,1],[1,1]] + Δs₁ [[1,0],[0,0]] + Δs₂ [[0,0],[0,1]]) and c = t³ Ā/12.
Mat3 face_stiffness(const Mat2& abar_inverse, double c, double alpha, double beta) {
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

/// Bending Young's modulus E_b (Pa): bending_youngs_modulus when set, E otherwise.
double bending_modulus_of(const ShellMaterial& m) {
  return m.bending_youngs_modulus > 0.0 ? m.bending_youngs_modulus : m.youngs_modulus;
}

/// Per face, the vertex across the edge opposite each corner (−1 on a boundary), from the hinges.
std::vector<std::array<int, 3>> opposite_vertices(const Faces& faces,
                                                  const std::vector<Hinge>& hinges) {
  std::vector<std::array<int, 3>> opposite(faces.rows(), {-1, -1, -1});
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
    opposite[hg.f0][k0] = hg.v3;
    opposite[hg.f1][k1] = hg.v2;
  }
  return opposite;
}

/// Element stencils: (q0, q1, q2, p0, p1, p2), p_i = q_i where the edge opposite q_i is a
/// boundary (that slot then carries no derivative).
std::vector<StencilTerm<6>::Stencil> face_stencils(const Positions& rest, const Faces& faces,
                                                   const std::vector<Hinge>& hinges) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= rest.rows())
        fail(Status::invalid_argument, "bending: face " + std::to_string(f) + " has vertex index " +
                                           std::to_string(faces(f, k)) + " out of range");
  const std::vector<std::array<int, 3>> opposite = opposite_vertices(faces, hinges);
  std::vector<StencilTerm<6>::Stencil> stencils(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      stencils[f][k] = faces(f, k);
      stencils[f][3 + k] = opposite[f][k] >= 0 ? opposite[f][k] : faces(f, k);
    }
  return stencils;
}

}  // namespace

MidedgeBending::MidedgeBending(const Positions& rest, const Faces& faces,
                               const std::vector<Hinge>& hinges,
                               const std::vector<ShellMaterial>& face_materials)
    : StencilTerm<6>(face_stencils(rest, faces, hinges), static_cast<int>(rest.rows())) {
  const Eigen::Index num_faces = faces.rows();
  if (face_materials.size() != static_cast<std::size_t>(num_faces))
    fail(Status::invalid_argument, "bending: " + std::to_string(face_materials.size()) +
                                       " face materials for " + std::to_string(num_faces) +
                                       " faces");
  const std::vector<std::array<int, 3>> opposite = opposite_vertices(faces, hinges);
  const Vector rest_dofs = as_dofs(rest);
  elements_.resize(num_faces);
  for (int f = 0; f < static_cast<int>(num_faces); ++f) {
    Element& el = elements_[f];
    const Vec3 q0 = rest.row(faces(f, 0)), e1 = Vec3(rest.row(faces(f, 1))) - q0,
               e2 = Vec3(rest.row(faces(f, 2))) - q0;
    const double area = 0.5 * e1.cross(e2).norm();
    if (!(area > 0.0) || !std::isfinite(area))
      fail(Status::invalid_mesh, "bending: face " + std::to_string(f) + " has zero rest area");
    Mat2 abar;  // ā, the rest first fundamental form in the basis (e1, e2)
    abar << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
    const ShellMaterial& m = face_materials[f];
    const double eb = bending_modulus_of(m), nu = m.poisson_ratio, t = m.thickness;
    const double alpha = eb * nu / (1.0 - nu * nu);  // α = E ν/(1 − ν²)
    const double beta = eb / (2.0 * (1.0 + nu));     // β = E/(2(1 + ν))
    el.stiffness = face_stiffness(abar.inverse(), t * t * t * area / 12.0, alpha, beta);
    for (int i = 0; i < 3; ++i) el.interior[i] = opposite[f][i] >= 0;
    el.rest_values = edge_values(f, gather(f, rest_dofs), nullptr, nullptr);
  }
}

Vec3 MidedgeBending::edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                                 LocalMatrix* hessians) const {
  Vec3 s = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (gradients) gradients[i].setZero();
    if (hessians) hessians[i].setZero();
    if (!elements_[e].interior[i]) continue;  // boundary: m_i = the face normal, s_i ≡ 0
    Vector12 g;
    Matrix12 h;
    s[i] =
        hinge_edge_value(hinge_positions(xe, i), gradients ? &g : nullptr, hessians ? &h : nullptr);
    const std::array<int, 4> slots = hinge_slots(i);
    for (int a = 0; a < 4; ++a) {
      if (gradients) gradients[i].segment<3>(3 * slots[a]) = g.segment<3>(3 * a);
      if (hessians)
        for (int b = 0; b < 4; ++b)
          hessians[i].block<3, 3>(3 * slots[a], 3 * slots[b]) = h.block<3, 3>(3 * a, 3 * b);
    }
  }
  return s;
}

double MidedgeBending::element_value(int e, const LocalVector& xe) const {
  const Vec3 ds = edge_values(e, xe, nullptr, nullptr) - elements_[e].rest_values;
  return 0.5 * ds.dot(elements_[e].stiffness * ds);  // ½ Δsᵀ Q Δs
}

void MidedgeBending::element_gradient(int e, const LocalVector& xe, LocalVector& g) const {
  LocalVector ds_dx[3];
  const Vec3 ds = edge_values(e, xe, ds_dx, nullptr) - elements_[e].rest_values;
  const Vec3 force = elements_[e].stiffness * ds;  // ∂E/∂s = Q Δs
  g = force[0] * ds_dx[0] + force[1] * ds_dx[1] + force[2] * ds_dx[2];
}

void MidedgeBending::element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  LocalVector ds_dx[3];
  LocalMatrix d2s_dx2[3];
  const Vec3 ds = edge_values(e, xe, ds_dx, d2s_dx2) - elements_[e].rest_values;
  const Mat3& q = elements_[e].stiffness;
  const Vec3 force = q * ds;
  // ∇²E = Σ_ij Q_ij ∇s_i ∇s_jᵀ + Σ_i (Q Δs)_i ∇²s_i.
  Eigen::Matrix<double, kDofs, 3> jacobian;
  for (int i = 0; i < 3; ++i) jacobian.col(i) = ds_dx[i];
  h.noalias() = jacobian * q * jacobian.transpose();
  for (int i = 0; i < 3; ++i) h += force[i] * d2s_dx2[i];
}

void MidedgeBending::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  element_hessian(e, xe, h);
  // At s = s̄ the Hessian is Jᵀ Q J with Q PSD: nothing to clamp.
  if (edge_values(e, xe, nullptr, nullptr) != elements_[e].rest_values) project_psd(h);
}

}  // namespace progsim
