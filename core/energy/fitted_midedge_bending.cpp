#include "energy/fitted_midedge_bending.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "energy/dihedral_angle.hpp"
#include "energy/midedge_parts.hpp"

namespace progsim {
namespace {

using Local = StencilTerm<12>;
using Slots = std::array<int, 4>;

// Element slots: q_k → k, p_k (across the edge opposite q_k) → 3 + k, and for the neighbour
// g_i = (q_{i+2}, q_{i+1}, p_i) across edge i, the vertices r_{i,0} and r_{i,1} across its edges
// opposite q_{i+2} and q_{i+1} → 6 + 2i and 7 + 2i.
//
// Hinge quantities τ_j = 2 h(x2) sin(θ/2) (midedge::height_sine) at hinge slots (x0..x3):
//   j = i      A_i: face f's own hinge i seen from f, height of q_i: (q_{i+1}, q_{i+2}, q_i, p_i);
//                   it is also g_i's fit height of its far vertex q_i
//   j = 3 + i  T_i: the same hinge seen from g_i, height of p_i (f's fit): (q_{i+2}, q_{i+1}, p_i,
//                   q_i)
//   j = 6 + 2i V_{i,0}: g_i's hinge with r_{i,0} (g_i's fit): (p_i, q_{i+1}, r_{i,0}, q_{i+2})
//   j = 7 + 2i V_{i,1}: g_i's hinge with r_{i,1} (g_i's fit): (q_{i+2}, p_i, r_{i,1}, q_{i+1})
Slots quantity_slots(int j) {
  const int i = j < 6 ? j % 3 : (j - 6) / 2, a = (i + 1) % 3, b = (i + 2) % 3;
  if (j < 3) return {a, b, i, 3 + i};
  if (j < 6) return {b, a, 3 + i, i};
  if ((j - 6) % 2 == 0) return {3 + i, a, 6 + 2 * i, b};
  return {b, 3 + i, 7 + 2 * i, a};
}

Vector12 hinge_positions(const Local::LocalVector& xe, const Slots& slots) {
  Vector12 xh;
  for (int k = 0; k < 4; ++k) xh.segment<3>(3 * k) = xe.segment<3>(3 * slots[k]);
  return xh;
}

/// out += w g, the hinge's 12 entries scattered to the element's slots.
void scatter(const Vector12& g, const Slots& slots, double w, Local::LocalVector& out) {
  for (int a = 0; a < 4; ++a) out.segment<3>(3 * slots[a]) += w * g.segment<3>(3 * a);
}

/// out += w h, the hinge's 12 × 12 (or 9 × 9, its first three slots) block scattered.
template <int N>
void scatter(const Eigen::Matrix<double, N, N>& h, const Slots& slots, double w,
             Local::LocalMatrix& out) {
  for (int a = 0; a < N / 3; ++a)
    for (int b = 0; b < N / 3; ++b)
      out.block<3, 3>(3 * slots[a], 3 * slots[b]) += w * h.template block<3, 3>(3 * a, 3 * b);
}

/// The corner of `faces` row g holding vertex v.
int corner_of(const Faces& faces, int g, int v) {
  for (int k = 0; k < 3; ++k)
    if (faces(g, k) == v) return k;
  return -1;
}

/// Element stencils (see above); a missing vertex repeats q_i and carries no derivative.
std::vector<Local::Stencil> face_stencils(const Faces& faces,
                                          const std::vector<midedge::Across>& across) {
  std::vector<Local::Stencil> stencils(faces.rows());
  for (int f = 0; f < static_cast<int>(faces.rows()); ++f) {
    Local::Stencil& s = stencils[f];
    for (int i = 0; i < 3; ++i) {
      s[i] = faces(f, i);
      s[3 + i] = across[f].vertex[i] >= 0 ? across[f].vertex[i] : faces(f, i);
      s[6 + 2 * i] = s[7 + 2 * i] = faces(f, i);
      const int g = across[f].face[i];
      if (g < 0) continue;
      const int far0 = across[g].vertex[corner_of(faces, g, faces(f, (i + 2) % 3))];
      const int far1 = across[g].vertex[corner_of(faces, g, faces(f, (i + 1) % 3))];
      if (far0 >= 0) s[6 + 2 * i] = far0;
      if (far1 >= 0) s[7 + 2 * i] = far1;
    }
  }
  return stencils;
}

/// The edge from corners[a] to corners[b] of a face's plane: its unit tangent t and unit
/// normal ν pointing away from `inside`, a point on the face's side (ν = −inward) when
/// `toward` is false, towards it when true.
Mat2 edge_frame(const std::array<Vec2, 3>& corners, int a, int b, int inside, bool toward) {
  const Vec2 t = (corners[b] - corners[a]).normalized();
  Vec2 nu(-t.y(), t.x());
  if ((nu.dot(corners[inside] - corners[a]) > 0.0) != toward) nu = -nu;
  Mat2 frame;
  frame << t, nu;
  return frame;
}

/// M = ½ d dᵀ − (L²/8) t tᵀ/h in the edge's (t, ν) frame, d the far vertex's offset from the
/// edge's midpoint and h = |d·ν| its height: Q(H)/h = ⟨M, H⟩ (see FittedMidedgeBending).
Mat2 slope_excess(const std::array<Vec2, 3>& corners, int a, int b, int far, const Mat2& frame) {
  const Vec2 d = frame.transpose() * (corners[far] - 0.5 * (corners[a] + corners[b]));
  const double length = (corners[b] - corners[a]).norm();
  Mat2 m = 0.5 * d * d.transpose();
  m(0, 0) -= length * length / 8.0;
  return m / std::abs(d.y());
}

/// ⟨A, B⟩ = Σ A_ab B_ab.
double inner(const Mat2& a, const Mat2& b) {
  return a.cwiseProduct(b).sum();
}

}  // namespace

FittedMidedgeBending::FittedMidedgeBending(const Positions& rest, const Faces& faces,
                                           const std::vector<Hinge>& hinges,
                                           const std::vector<ShellMaterial>& face_materials)
    : FittedMidedgeBending(rest, faces, face_materials,
                           midedge::faces_across(faces, hinges, static_cast<int>(rest.rows()),
                                                 face_materials.size())) {}

FittedMidedgeBending::FittedMidedgeBending(const Positions& rest, const Faces& faces,
                                           const std::vector<ShellMaterial>& face_materials,
                                           const std::vector<midedge::Across>& across)
    : EdgeQuadraticBending<12>(face_stencils(faces, across), static_cast<int>(rest.rows())) {
  const int num_faces = static_cast<int>(faces.rows());
  const Vector rest_dofs = as_dofs(rest);
  faces_.resize(num_faces);
  turns_.resize(num_faces);
  for (int f = 0; f < num_faces; ++f) {
    Turn& el = turns_[f];
    const LocalVector xe = gather(f, rest_dofs);
    std::array<Vec3, 12> x;
    for (int k = 0; k < 12; ++k) x[k] = xe.segment<3>(3 * k);
    faces_[f].stiffness = midedge::face_stiffness(x[0], x[1], x[2], face_materials[f], f);
    for (int i = 0; i < 3; ++i) el.interior[i] = across[f].vertex[i] >= 0;
    const midedge::QuadraticFit own({x[0], x[1], x[2], x[3], x[4], x[5]}, el.interior,
                                    face_materials[f].poisson_ratio);
    el.weights.setZero();
    for (int i = 0; i < 3; ++i) {
      if (!el.interior[i]) continue;  // boundary: the face's own normal, s_i ≡ 0
      const int a = (i + 1) % 3, b = (i + 2) % 3, g = across[f].face[i];
      // g_i = (q_b, q_a, p_i) with far vertices (r_{i,0}, r_{i,1}, q_i).
      const std::array<bool, 3> g_interior = {
          across[g].vertex[corner_of(faces, g, faces(f, b))] >= 0,
          across[g].vertex[corner_of(faces, g, faces(f, a))] >= 0, true};
      const midedge::QuadraticFit fit({x[b], x[a], x[3 + i], x[6 + 2 * i], x[7 + 2 * i], x[i]},
                                      g_interior, face_materials[g].poisson_ratio);
      // Without both fits the edge keeps the bisector (φ = 0, MidedgeBending's normal), on
      // both of its faces alike.
      if (!own.unique || !fit.unique) continue;
      const Mat2 frame_f = edge_frame(own.corners, a, b, i, true);
      const Mat2 frame_g = edge_frame(fit.corners, 1, 0, 2, false);
      // φ_i = ½ (ψ_f − ψ_g), ψ = ⟨M, H⟩, H = ½ (κ_f + κ_g) in the edge's frame.
      const Mat2 w = 0.25 * (slope_excess(own.corners, a, b, i, frame_f) -
                             slope_excess(fit.corners, 1, 0, 2, frame_g));
      const auto weight = [&w](const Mat2& curvature, const Mat2& frame) {
        return inner(w, frame.transpose() * curvature * frame);
      };
      for (int k = 0; k < 3; ++k) el.weights(i, 3 + k) = weight(own.curvatures[k], frame_f);
      el.weights(i, i) = weight(fit.curvatures[2], frame_g);
      el.weights(i, 6 + 2 * i) = weight(fit.curvatures[0], frame_g);
      el.weights(i, 7 + 2 * i) = weight(fit.curvatures[1], frame_g);
    }
    for (int j = 0; j < kQuantities; ++j) el.used[j] = !el.weights.col(j).isZero(0.0);
    faces_[f].rest_values = edge_values(f, xe, nullptr, nullptr);
  }
}

Vec3 FittedMidedgeBending::edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                                       LocalMatrix* hessians) const {
  const Turn& el = turns_[e];
  // φ_i = Σ_j w_ij τ_j with its derivatives.
  Vec3 phi = Vec3::Zero();
  LocalVector dphi[3];
  LocalMatrix d2phi[3];
  for (int i = 0; i < 3; ++i) {
    if (gradients) dphi[i].setZero();
    if (hessians) d2phi[i].setZero();
  }
  for (int j = 0; j < kQuantities; ++j) {
    if (!el.used[j]) continue;
    const Slots slots = quantity_slots(j);
    Vector12 g;
    Matrix12 h;
    const double tau = midedge::height_sine(hinge_positions(xe, slots), gradients ? &g : nullptr,
                                            hessians ? &h : nullptr);
    for (int i = 0; i < 3; ++i) {
      const double w = el.weights(i, j);
      if (w == 0.0) continue;
      phi[i] += w * tau;
      if (gradients) scatter(g, slots, w, dphi[i]);
      if (hessians) scatter<12>(h, slots, w, d2phi[i]);
    }
  }
  Vec3 s = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (gradients) gradients[i].setZero();
    if (hessians) hessians[i].setZero();
    if (!el.interior[i]) continue;
    const Slots slots = quantity_slots(i);
    const HingeFrame frame(hinge_positions(xe, slots));
    const double h = std::sqrt(frame.n1_sq) / frame.length;  // height of q_i
    const double beta = 0.5 * frame.angle() + phi[i];
    s[i] = 2.0 * h * std::sin(beta);  // s_i = 2 h sin(θ/2 + φ)
    if (!gradients) continue;
    const midedge::EdgeHeight height(frame.e, frame.w);
    LocalVector dh = LocalVector::Zero(), dbeta = dphi[i];
    for (int a = 0; a < 3; ++a) dh.segment<3>(3 * slots[a]) = height.gradient.segment<3>(3 * a);
    scatter(frame.angle_gradient(), slots, 0.5, dbeta);
    const double sin_b = std::sin(beta), cos_b = std::cos(beta);
    // ∇s = 2 sin β ∇h + 2 h cos β ∇β.
    gradients[i] = 2.0 * sin_b * dh + 2.0 * h * cos_b * dbeta;
    if (!hessians) continue;
    // ∇²s = 2 sin β ∇²h + 2 cos β (∇h∇βᵀ + ∇β∇hᵀ) − 2 h sin β ∇β∇βᵀ + 2 h cos β ∇²β,
    // ∇²β = ½ ∇²θ + ∇²φ.
    LocalMatrix& out = hessians[i];
    out = (2.0 * h * cos_b) * d2phi[i];
    scatter<12>(frame.angle_hessian(), slots, h * cos_b, out);
    scatter<9>(height.hessian, slots, 2.0 * sin_b, out);
    out.noalias() += (2.0 * cos_b) * (dh * dbeta.transpose() + dbeta * dh.transpose());
    out.noalias() -= (2.0 * h * sin_b) * dbeta * dbeta.transpose();
  }
  return s;
}

}  // namespace progsim
