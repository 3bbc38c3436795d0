#include "hierarchy/shell_prolongation.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "energy/triangle_frame.hpp"

namespace progsim {
namespace {

/// The frame Q = [R(F) | n] (3 × 3, a rotation) of a coarse face with edges d₁ = x₁ − x₀,
/// d₂ = x₂ − x₀ and rest inverse D̄⁻¹ (2 × 2): n = d₁ × d₂ / |d₁ × d₂| its unit normal and R(F)
/// the polar factor of F = [d₁ d₂] D̄⁻¹ (PSQ eq. 5 and footnote 2). Returns false, leaving q
/// unspecified, if the face has zero or non-finite area or the frame is not finite.
///
/// R(F) = F (FᵀF)^{-1/2} = U Vᵀ of the thin SVD F = U Σ Vᵀ. F's columns span the face's plane,
/// so with the orthonormal B = [b₁ b₂] (b₁ = d₁ / |d₁|, b₂ = n × b₁), F = B G for the 2 × 2
/// G = BᵀF = [|d₁|, b₁·d₂; 0, |d₁ × d₂| / |d₁|] D̄⁻¹ (det G > 0), and R(F) = B polar(G), whose
/// rotation angle has (cos θ, sin θ) ∝ (G₀₀ + G₁₁, G₁₀ − G₀₁). Chosen over JacobiSVD
/// (iterative sweeps) and over F (FᵀF)^{-1/2} written out (which divides by |f₁ × f₂|: its
/// columns lose orthonormality by ~ε / sin∠(d₁, d₂) on slivers): exact, branch-free, every
/// factor normalized, so Q is orthonormal to rounding for any face of nonzero area. n and the
/// degeneracy test use the exact edge differences: a corner moved onto another gives exactly zero
/// area (F would carry rounding).
bool face_frame(const Vec3& d1, const Vec3& d2, const Mat2& rest_inverse, Mat3& q) {
  const Vec3 cross = d1.cross(d2);
  const double twice_area = cross.norm();
  if (!(twice_area > 0.0) || !std::isfinite(twice_area)) return false;
  const double length = d1.norm();
  const Vec3 b1 = d1 / length;
  // n made orthogonal to b₁: on slivers the cross product of nearly parallel edges is off by
  // ~ε / sin∠(d₁, d₂) in direction, which would otherwise leave Q non-orthonormal by as much.
  const Vec3 normal = cross - cross.dot(b1) * b1;
  q.col(2) = normal / normal.norm();
  const Vec3 b2 = q.col(2).cross(b1);
  Mat2 in_plane;  // BᵀD
  in_plane << length, b1.dot(d2), 0.0, twice_area / length;
  const Mat2 g = in_plane * rest_inverse;
  const Vec2 angle = Vec2(g(0, 0) + g(1, 1), g(1, 0) - g(0, 1)).normalized();
  q.col(0) = angle(0) * b1 + angle(1) * b2;
  q.col(1) = angle(0) * b2 - angle(1) * b1;
  return q.allFinite();
}

}  // namespace

ShellProlongation::ShellProlongation(const Positions& coarse_rest, const Faces& coarse_faces,
                                     const SurfaceAnchors& anchors, const Positions& fine_rest)
    : Prolongation(intrinsic_matrix(anchors, coarse_faces, static_cast<int>(coarse_rest.rows()))),
      coarse_faces_(coarse_faces) {
  const Eigen::Index n = fine_rest.rows();
  if (static_cast<Eigen::Index>(anchors.size()) != n)
    fail(Status::invalid_argument, "shell prolongation: " + std::to_string(anchors.size()) +
                                       " anchors for " + std::to_string(n) + " fine vertices");
  // F = Σ_a x_a β_aᵀ = D D̄⁻¹ with β₀ = −β₁ − β₂, so the rows of D̄⁻¹ are β₁ᵀ and β₂ᵀ.
  face_rest_inverse_.reserve(coarse_faces.rows());
  for (Eigen::Index f = 0; f < coarse_faces.rows(); ++f)
    face_rest_inverse_.push_back(
        rest_triangle_frame(coarse_rest, coarse_faces, f, "shell prolongation")
            .beta.bottomRows<2>());
  anchor_face_.resize(n);
  local_offset_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!fine_rest.row(i).allFinite())
      fail(Status::invalid_argument,
           "shell prolongation: fine rest vertex " + std::to_string(i) + " is not finite");
    anchor_face_[i] = anchors[i].face;
    // At rest F̄ = [ē, n̄ × ē] and n = n̄, so Q̄ = [ē, n̄ × ē, n̄]; Q̄ᵀ d̄ = (t₁, t₂, γ).
    Mat3 rest_frame;
    if (!frame_of(coarse_rest, anchor_face_[i], rest_frame))
      fail(Status::invalid_mesh, "shell prolongation: rest face " +
                                     std::to_string(anchor_face_[i]) +
                                     " is too small or too thin for a finite frame");
    const Vec3 rest_offset = fine_rest.row(i).transpose() - intrinsic_point(coarse_rest, i);
    local_offset_[i] = rest_frame.transpose() * rest_offset;
  }
}

bool ShellProlongation::frame_of(const Positions& x, int f, Mat3& frame) const {
  const Vec3 x0 = x.row(coarse_faces_(f, 0));
  return face_frame(Vec3(x.row(coarse_faces_(f, 1))) - x0, Vec3(x.row(coarse_faces_(f, 2))) - x0,
                    face_rest_inverse_[f], frame);
}

Vec3 ShellProlongation::offset(const Positions& coarse, Eigen::Index i) const {
  Mat3 frame;
  if (!frame_of(coarse, anchor_face_[i], frame)) return Vec3::Zero();
  return frame * local_offset_[i];
}

void ShellProlongation::offsets(const Positions& coarse, Positions& out) const {
  check_shapes(coarse, out, "offsets");
  const Eigen::Index n = out.rows();
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (Eigen::Index i = 0; i < n; ++i) out.row(i) = offset(coarse, i).transpose();
}

void ShellProlongation::apply(const Positions& coarse, Positions& fine) const {
  check_shapes(coarse, fine, "apply");
  const Eigen::Index n = fine.rows();
#pragma omp parallel for schedule(static) if (n >= kMinParallelItems)
  for (Eigen::Index i = 0; i < n; ++i)
    fine.row(i) = (intrinsic_point(coarse, i) + offset(coarse, i)).transpose();
}

}  // namespace progsim
