#include "energy/midedge_bending.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"
#include "energy/dihedral_angle.hpp"
#include "energy/midedge_parts.hpp"

namespace progsim {
namespace {

/// The local slots (x0, x1, x2, x3) of the hinge across the edge opposite q_i in the element
/// (q0, q1, q2, p0, p1, p2): x0 = q_{i+1}, x1 = q_{i+2}, x2 = q_i, x3 = p_i, so that the
/// face (x0, x1, x2) is the element's face in its own orientation.
std::array<int, 4> hinge_slots(int i) {
  return {(i + 1) % 3, (i + 2) % 3, i, 3 + i};
}

/// The element's hinge across the edge opposite q_i, stacked (12).
Vector12 hinge_positions(const StencilTerm<6>::LocalVector& xe, int i) {
  Vector12 xh;
  const std::array<int, 4> slots = hinge_slots(i);
  for (int k = 0; k < 4; ++k) xh.segment<3>(3 * k) = xe.segment<3>(3 * slots[k]);
  return xh;
}

/// Element stencils: (q0, q1, q2, p0, p1, p2), p_i = q_i where the edge opposite q_i is a
/// boundary (that slot then carries no derivative).
std::vector<StencilTerm<6>::Stencil> face_stencils(const Faces& faces,
                                                   const std::vector<midedge::Across>& across) {
  std::vector<StencilTerm<6>::Stencil> stencils(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      stencils[f][k] = faces(f, k);
      stencils[f][3 + k] = across[f].vertex[k] >= 0 ? across[f].vertex[k] : faces(f, k);
    }
  return stencils;
}

}  // namespace

MidedgeBending::MidedgeBending(const Positions& rest, const Faces& faces,
                               const std::vector<Hinge>& hinges,
                               const std::vector<ShellMaterial>& face_materials)
    : MidedgeBending(rest, faces, face_materials,
                     midedge::faces_across(faces, hinges, static_cast<int>(rest.rows()),
                                           face_materials.size())) {}

MidedgeBending::MidedgeBending(const Positions& rest, const Faces& faces,
                               const std::vector<ShellMaterial>& face_materials,
                               const std::vector<midedge::Across>& across)
    : EdgeQuadraticBending<6>(face_stencils(faces, across), static_cast<int>(rest.rows())) {
  const Eigen::Index num_faces = faces.rows();
  const Vector rest_dofs = as_dofs(rest);
  faces_.resize(num_faces);
  interior_.resize(num_faces);
  for (int f = 0; f < static_cast<int>(num_faces); ++f) {
    faces_[f].stiffness = midedge::face_stiffness(rest.row(faces(f, 0)), rest.row(faces(f, 1)),
                                                  rest.row(faces(f, 2)), face_materials[f], f);
    for (int i = 0; i < 3; ++i) interior_[f][i] = across[f].vertex[i] >= 0;
    faces_[f].rest_values = edge_values(f, gather(f, rest_dofs), nullptr, nullptr);
  }
}

Vec3 MidedgeBending::edge_values(int e, const LocalVector& xe, LocalVector* gradients,
                                 LocalMatrix* hessians) const {
  Vec3 s = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (gradients) gradients[i].setZero();
    if (hessians) hessians[i].setZero();
    if (!interior_[e][i]) continue;  // boundary: m_i = the face normal, s_i ≡ 0
    Vector12 g;
    Matrix12 h;
    s[i] = midedge::height_sine(hinge_positions(xe, i), gradients ? &g : nullptr,
                                hessians ? &h : nullptr);
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

}  // namespace progsim
