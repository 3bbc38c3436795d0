#include "hierarchy/shell_prolongation.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <unsupported/Eigen/AutoDiff>

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
/// The value of a scalar (itself for double; the value part of an autodiff scalar).
inline double value_of(double x) {
  return x;
}
template <class Derivatives>
double value_of(const Eigen::AutoDiffScalar<Derivatives>& x) {
  return x.value();
}

template <class Scalar>
bool face_frame(const Eigen::Matrix<Scalar, 3, 1>& d1, const Eigen::Matrix<Scalar, 3, 1>& d2,
                const Mat2& rest_inverse, Eigen::Matrix<Scalar, 3, 3>& q) {
  using V3 = Eigen::Matrix<Scalar, 3, 1>;
  using M2 = Eigen::Matrix<Scalar, 2, 2>;
  const V3 cross = d1.cross(d2);
  const Scalar twice_area = cross.norm();
  if (!(value_of(twice_area) > 0.0) || !std::isfinite(value_of(twice_area))) return false;
  const Scalar length = d1.norm();
  const V3 b1 = d1 / length;
  // n made orthogonal to b₁: on slivers the cross product of nearly parallel edges is off by
  // ~ε / sin∠(d₁, d₂) in direction, which would otherwise leave Q non-orthonormal by as much.
  const V3 normal = cross - cross.dot(b1) * b1;
  q.col(2) = normal / normal.norm();
  const V3 b2 = q.col(2).cross(b1);
  M2 in_plane;  // BᵀD
  in_plane << length, b1.dot(d2), Scalar(0.0), twice_area / length;
  const M2 g = in_plane * rest_inverse.cast<Scalar>();
  const Eigen::Matrix<Scalar, 2, 1> unnormalized(g(0, 0) + g(1, 1), g(1, 0) - g(0, 1));
  const Eigen::Matrix<Scalar, 2, 1> angle = unnormalized / unnormalized.norm();
  q.col(0) = angle(0) * b1 + angle(1) * b2;
  q.col(1) = angle(0) * b2 - angle(1) * b1;
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(value_of(q(k)))) return false;
  return true;
}

/// ∂⟨Q(d₁, d₂), M⟩/∂(d₁, d₂) (6) for the frame Q of face_frame and a 3 × 3 weight M (forward
/// mode over the 6 edge coordinates); zero where the frame is undefined.
Eigen::Matrix<double, 6, 1> frame_gradient(const Vec3& d1, const Vec3& d2, const Mat2& rest_inverse,
                                           const Mat3& weight) {
  using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 6, 1>>;
  Eigen::Matrix<Dual, 3, 1> e1, e2;
  for (int k = 0; k < 3; ++k) {
    e1(k) = Dual(d1(k), 6, k);
    e2(k) = Dual(d2(k), 6, 3 + k);
  }
  Eigen::Matrix<Dual, 3, 3> q;
  if (!face_frame(e1, e2, rest_inverse, q)) return Eigen::Matrix<double, 6, 1>::Zero();
  Dual sum(0.0, Eigen::Matrix<double, 6, 1>::Zero());
  for (int k = 0; k < 9; ++k) sum += q(k) * weight(k);
  return sum.derivatives();
}

/// Start offsets (buckets + 1) of the items grouped by bucket, for bucket_items.
std::vector<int> bucket_starts(const std::vector<int>& bucket_of, int buckets) {
  std::vector<int> first(buckets + 1, 0);
  for (int b : bucket_of) ++first[b + 1];
  for (int b = 0; b < buckets; ++b) first[b + 1] += first[b];
  return first;
}

/// The item indices grouped by bucket (increasing within a bucket).
std::vector<int> bucket_items(const std::vector<int>& bucket_of, const std::vector<int>& first) {
  std::vector<int> items(bucket_of.size()), next(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < bucket_of.size(); ++i)
    items[next[bucket_of[i]]++] = static_cast<int>(i);
  return items;
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
  build_gather_lists(static_cast<int>(coarse_rest.rows()));
}

void ShellProlongation::build_gather_lists(int coarse_vertices) {
  intrinsic_transpose_ = intrinsic().transpose();
  face_fine_first_ = bucket_starts(anchor_face_, static_cast<int>(coarse_faces_.rows()));
  face_fine_ = bucket_items(anchor_face_, face_fine_first_);
  std::vector<int> corner_vertex(3 * coarse_faces_.rows());
  for (Eigen::Index c = 0; c < coarse_faces_.rows() * 3; ++c)
    corner_vertex[c] = coarse_faces_(c / 3, c % 3);
  vertex_corner_first_ = bucket_starts(corner_vertex, coarse_vertices);
  vertex_corner_ = bucket_items(corner_vertex, vertex_corner_first_);
}

bool ShellProlongation::frame_of(const Positions& x, int f, Mat3& frame) const {
  const Vec3 x0 = x.row(coarse_faces_(f, 0));
  const Vec3 d1 = Vec3(x.row(coarse_faces_(f, 1))) - x0, d2 = Vec3(x.row(coarse_faces_(f, 2))) - x0;
  return face_frame(d1, d2, face_rest_inverse_[f], frame);
}

Vec3 ShellProlongation::offset(const Positions& coarse, Eigen::Index i) const {
  Mat3 frame;
  if (!frame_of(coarse, anchor_face_[i], frame)) return Vec3::Zero();
  return frame * local_offset_[i];
}

void ShellProlongation::add_jacobian_transpose(
    const Positions& coarse, const Positions& fine_gradient, Positions& coarse_gradient,
    std::vector<Eigen::Matrix<double, 9, 1>>& workspace) const {
  check_shapes(coarse, fine_gradient, "add_jacobian_transpose");
  if (coarse_gradient.rows() != coarse.rows())
    fail(Status::invalid_argument,
         "shell prolongation: add_jacobian_transpose: the coarse gradient has " +
             std::to_string(coarse_gradient.rows()) + " rows, not " +
             std::to_string(coarse.rows()));
  // dP/dx = U + ∂a/∂x (PSQ eqs. 5 and 9): Jᵀg = Uᵀg + Σ_f ∂⟨Q_f(x), M_f⟩/∂x with
  // M_f = Σ_{i on f} g_i c_iᵀ, c_i = (t₁, t₂, γ): one derivative of the frame per coarse face.
  const Eigen::Index faces = coarse_faces_.rows(), n = coarse.rows();
  workspace.resize(faces);
#pragma omp parallel for schedule(static) num_threads(loop_threads(faces))
  for (Eigen::Index f = 0; f < faces; ++f) {
    Mat3 weight = Mat3::Zero();
    for (int k = face_fine_first_[f]; k < face_fine_first_[f + 1]; ++k)
      weight +=
          fine_gradient.row(face_fine_[k]).transpose() * local_offset_[face_fine_[k]].transpose();
    const Vec3 x0 = coarse.row(coarse_faces_(f, 0));
    const Vec3 d1 = Vec3(coarse.row(coarse_faces_(f, 1))) - x0;
    const Vec3 d2 = Vec3(coarse.row(coarse_faces_(f, 2))) - x0;
    const Eigen::Matrix<double, 6, 1> d = frame_gradient(d1, d2, face_rest_inverse_[f], weight);
    workspace[f] << -(d.head<3>() + d.tail<3>()), d.head<3>(), d.tail<3>();
  }
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (Eigen::Index v = 0; v < n; ++v) {
    Vec3 sum = Vec3::Zero();
    for (ProlongationMatrix::InnerIterator it(intrinsic_transpose_, v); it; ++it)
      sum += it.value() * fine_gradient.row(it.col()).transpose();
    for (int k = vertex_corner_first_[v]; k < vertex_corner_first_[v + 1]; ++k)
      sum += workspace[vertex_corner_[k] / 3].segment<3>(3 * (vertex_corner_[k] % 3));
    coarse_gradient.row(v) += sum.transpose();
  }
}

void ShellProlongation::offsets(const Positions& coarse, Positions& out) const {
  check_shapes(coarse, out, "offsets");
  const Eigen::Index n = out.rows();
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (Eigen::Index i = 0; i < n; ++i) out.row(i) = offset(coarse, i).transpose();
}

void ShellProlongation::apply(const Positions& coarse, Positions& fine) const {
  check_shapes(coarse, fine, "apply");
  const Eigen::Index n = fine.rows();
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (Eigen::Index i = 0; i < n; ++i)
    fine.row(i) = (intrinsic_point(coarse, i) + offset(coarse, i)).transpose();
}

}  // namespace progsim
