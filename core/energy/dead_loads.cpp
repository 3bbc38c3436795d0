#include "energy/dead_loads.hpp"

#include <string>

#include "common/error.hpp"

namespace progsim {

DeadLoads::DeadLoads(std::vector<VertexForces> loads, int num_vertices)
    : loads_(std::move(loads)), factors_(loads_.size(), 1.0) {
  for (const VertexForces& load : loads_) {
    if (load.forces.rows() != static_cast<Eigen::Index>(load.vertices.size()))
      fail(Status::invalid_argument, "DeadLoads: " + std::to_string(load.forces.rows()) +
                                         " forces for " + std::to_string(load.vertices.size()) +
                                         " vertices");
    for (int v : load.vertices)
      if (v < 0 || v >= num_vertices)
        fail(Status::invalid_argument, "DeadLoads: vertex " + std::to_string(v) +
                                           " is out of range [0, " + std::to_string(num_vertices) +
                                           ")");
  }
}

double DeadLoads::value(const Vector& x) const {
  double total = 0.0;
  for (std::size_t k = 0; k < loads_.size(); ++k) {
    const VertexForces& load = loads_[k];
    double work = 0.0;
    for (std::size_t j = 0; j < load.vertices.size(); ++j)
      work += load.forces.row(j).dot(x.segment<3>(3 * load.vertices[j]));  // f·x
    total -= factors_[k] * work;                                           // E = −s Σ f·x
  }
  return total;
}

void DeadLoads::add_gradient(const Vector&, Vector& g) const {
  for (std::size_t k = 0; k < loads_.size(); ++k) {
    const VertexForces& load = loads_[k];
    for (std::size_t j = 0; j < load.vertices.size(); ++j)
      g.segment<3>(3 * load.vertices[j]) -= factors_[k] * load.forces.row(j).transpose();  // −s f
  }
}

void DeadLoads::set_forces(std::size_t k, const Positions& forces) {
  if (forces.rows() != loads_.at(k).forces.rows() || forces.cols() != 3)
    fail(Status::invalid_argument, "DeadLoads: load " + std::to_string(k) + " needs " +
                                       std::to_string(loads_[k].forces.rows()) + " × 3 forces");
  loads_[k].forces = forces;
}

Vec3 DeadLoads::total_force() const {
  Vec3 total = Vec3::Zero();
  for (std::size_t k = 0; k < loads_.size(); ++k)
    total += factors_[k] * loads_[k].forces.colwise().sum().transpose();
  return total;
}

}  // namespace progsim
