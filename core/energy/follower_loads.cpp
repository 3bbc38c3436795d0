#include "energy/follower_loads.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace progsim {
namespace {

/// Bounds of Aitken's relaxation factor ω (outside: ω = 1, plain lagging).
constexpr double kMinRelaxation = 0.05, kMaxRelaxation = 20.0;

/// DeadLoads of the loads' vertices with zero forces (aimed by aim()).
std::vector<VertexForces> unaimed(const std::vector<NormalLoad>& loads) {
  std::vector<VertexForces> out;
  for (const NormalLoad& load : loads) {
    if (load.magnitudes.size() != static_cast<Eigen::Index>(load.vertices.size()))
      fail(Status::invalid_argument, "FollowerLoads: " + std::to_string(load.magnitudes.size()) +
                                         " magnitudes for " + std::to_string(load.vertices.size()) +
                                         " vertices");
    out.push_back(
        {load.vertices, Positions::Zero(static_cast<Eigen::Index>(load.vertices.size()), 3)});
  }
  return out;
}

}  // namespace

FollowerLoads::FollowerLoads(std::vector<NormalLoad> loads, const Faces& faces, int num_vertices)
    : loads_(std::move(loads)), faces_(faces), aimed_(unaimed(loads_), num_vertices) {
  std::vector<std::vector<int>> faces_of(num_vertices);
  for (Eigen::Index f = 0; f < faces_.rows(); ++f)
    for (int c = 0; c < 3; ++c) faces_of.at(faces_(f, c)).push_back(static_cast<int>(f));
  for (const NormalLoad& load : loads_)
    for (int v : load.vertices) {
      if (faces_of[v].empty())
        fail(Status::invalid_argument,
             "FollowerLoads: vertex " + std::to_string(v) + " has no face, so no normal");
      vertex_faces_.push_back(faces_of[v]);
    }
  directions_ = Vector::Zero(3 * static_cast<Eigen::Index>(vertex_faces_.size()));
  for (const NormalLoad& load : loads_)
    forces_.emplace_back(static_cast<Eigen::Index>(load.vertices.size()), 3);
}

void FollowerLoads::measure_normals(const Vector& x) {
  target_.resize(directions_.size());
  for (std::size_t i = 0; i < vertex_faces_.size(); ++i) {
    Vec3 normal = Vec3::Zero();  // Σ over its faces of (x_b − x_a) × (x_c − x_a): area-weighted
    for (int f : vertex_faces_[i]) {
      const Vec3 a = x.segment<3>(3 * faces_(f, 0)), b = x.segment<3>(3 * faces_(f, 1)),
                 c = x.segment<3>(3 * faces_(f, 2));
      normal += (b - a).cross(c - a);
    }
    const auto at = 3 * static_cast<Eigen::Index>(i);
    // A vertex whose faces' normals cancel (or have no area) keeps its direction: a load that
    // vanished would read as settled.
    target_.segment<3>(at) =
        normal.squaredNorm() > 0.0 ? Vec3(normal.normalized()) : Vec3(directions_.segment<3>(at));
  }
}

double FollowerLoads::largest_turn() const {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < directions_.size(); i += 3) {
    const Vec3 a = directions_.segment<3>(i), b = target_.segment<3>(i);
    largest = std::max(largest, std::atan2(a.cross(b).norm(), a.dot(b)));  // accurate near 0
  }
  return largest;
}

void FollowerLoads::aim_forces() {
  Eigen::Index i = 0;
  for (std::size_t k = 0; k < loads_.size(); ++k) {
    Positions& forces = forces_[k];
    for (Eigen::Index j = 0; j < forces.rows(); ++j, i += 3)
      forces.row(j) = loads_[k].magnitudes[j] * directions_.segment<3>(i).transpose();  // a n
    aimed_.set_forces(k, forces);
  }
}

double FollowerLoads::aim(const Vector& x) {
  measure_normals(x);
  const double turn = lagged_ ? largest_turn() : kPi;
  directions_ = target_;
  lagged_ = true;
  have_residual_ = false;
  omega_ = 1.0;
  aim_forces();
  return turn;
}

double FollowerLoads::relax(const Vector& x, double settled) {
  measure_normals(x);
  const double turn = largest_turn();
  if (!(turn > settled)) return turn;  // settled (or NaN): the forces x was solved for stay
  residual_ = target_ - directions_;   // r = n̄ − n
  if (have_residual_) {                // Küttler and Wall 2008, eq. 44
    change_ = residual_ - previous_residual_;
    const double squared = change_.squaredNorm();
    if (squared > 0.0) omega_ = -omega_ * previous_residual_.dot(change_) / squared;
    // Safeguard: a factor outside [kMinRelaxation, kMaxRelaxation] (nearly equal residuals)
    // would tip directions into the surface or reverse them; plain lagging then.
    if (!(omega_ >= kMinRelaxation && omega_ <= kMaxRelaxation)) omega_ = 1.0;
  }
  directions_ += omega_ * residual_;
  for (Eigen::Index i = 0; i < directions_.size(); i += 3) directions_.segment<3>(i).normalize();
  previous_residual_ = residual_;
  have_residual_ = true;
  aim_forces();
  return turn;
}

}  // namespace progsim
