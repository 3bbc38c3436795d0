#include "hierarchy/prolongation.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"

namespace progsim {
namespace {

/// Barycentric weights may undershoot 0 and miss a sum of 1 by this much (rounding of the
/// point location that produced them).

/// Throws Error(invalid_argument, "prolongation: fine vertex <i>: <problem>").
[[noreturn]] void reject_anchor(std::size_t i, const std::string& problem) {
  fail(Status::invalid_argument, "prolongation: fine vertex " + std::to_string(i) + ": " + problem);
}

/// Throws Error(invalid_argument, "prolongation: <operation>: <problem>").
[[noreturn]] void reject_shape(const char* operation, const std::string& problem) {
  fail(Status::invalid_argument, std::string("prolongation: ") + operation + ": " + problem);
}

/// Throws Error(invalid_mesh) naming the first coarse face with a corner outside [0, n).
void check_face_corners(const Faces& faces, int coarse_vertices) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (faces(f, k) < 0 || faces(f, k) >= coarse_vertices)
        fail(Status::invalid_mesh, "prolongation: coarse face " + std::to_string(f) +
                                       " has vertex index " + std::to_string(faces(f, k)) +
                                       " out of range [0, " + std::to_string(coarse_vertices) +
                                       ")");
}

/// "anchor weights (w0, w1, w2)", for messages.
std::string describe_weights(const Vec3& weights) {
  std::ostringstream text;
  text << "anchor weights (" << weights(0) << ", " << weights(1) << ", " << weights(2) << ")";
  return text.str();
}

/// Throws Error(invalid_argument) naming fine vertex i if its anchor is unusable.
void check_anchor(const SurfaceAnchor& anchor, std::size_t i, Eigen::Index num_faces) {
  if (anchor.face < 0 || anchor.face >= num_faces)
    reject_anchor(i, "anchor face " + std::to_string(anchor.face) + " out of range [0, " +
                         std::to_string(num_faces) + ")");
  const Vec3& w = anchor.weights;
  if (!w.allFinite()) reject_anchor(i, describe_weights(w) + " are not finite");
  if (w.minCoeff() < -kAnchorWeightTolerance)
    reject_anchor(i, describe_weights(w) + " have a negative entry");
  if (std::abs(w.sum() - 1.0) > kAnchorWeightTolerance)
    reject_anchor(i, describe_weights(w) + " do not sum to 1");
}

}  // namespace

ProlongationMatrix intrinsic_matrix(const SurfaceAnchors& anchors, const Faces& coarse_faces,
                                    int coarse_vertices) {
  if (coarse_vertices < 0)
    fail(Status::invalid_argument,
         "prolongation: negative coarse vertex count " + std::to_string(coarse_vertices));
  check_face_corners(coarse_faces, coarse_vertices);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * anchors.size());
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    check_anchor(anchors[i], i, coarse_faces.rows());
    for (int k = 0; k < 3; ++k)
      if (anchors[i].weights(k) != 0.0)
        entries.emplace_back(static_cast<int>(i), coarse_faces(anchors[i].face, k),
                             anchors[i].weights(k));
  }
  ProlongationMatrix u(static_cast<Eigen::Index>(anchors.size()), coarse_vertices);
  u.setFromTriplets(entries.begin(), entries.end());
  return u;
}

Positions Prolongation::restrict_gradient(const Positions& fine_gradient) const {
  if (fine_gradient.rows() != fine_vertices())
    fail(Status::invalid_argument, "prolongation: restrict_gradient got " +
                                       std::to_string(fine_gradient.rows()) + " rows for " +
                                       std::to_string(fine_vertices()) + " fine vertices");
  return intrinsic().transpose() * fine_gradient;
}

void Prolongation::check_shapes(const Positions& coarse, const Positions& out,
                                const char* operation) const {
  if (coarse.rows() != coarse_vertices())
    reject_shape(operation, "coarse positions have " + std::to_string(coarse.rows()) +
                                " rows, expected " + std::to_string(coarse_vertices()));
  if (out.rows() != fine_vertices())
    reject_shape(operation, "output has " + std::to_string(out.rows()) + " rows, expected " +
                                std::to_string(fine_vertices()));
  if (&coarse == &out) reject_shape(operation, "output aliases the input");
}

Vec3 Prolongation::intrinsic_point(const Positions& coarse, Eigen::Index i) const {
  Vec3 point = Vec3::Zero();
  for (ProlongationMatrix::InnerIterator it(intrinsic_, i); it; ++it)
    point += it.value() * coarse.row(it.col()).transpose();
  return point;
}

}  // namespace progsim
