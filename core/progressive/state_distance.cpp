#include "progressive/state_distance.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"

namespace progsim {

StateDistance state_distance(const Positions& x, const Positions& reference, double length) {
  if (x.rows() != reference.rows() || x.rows() == 0)
    fail(Status::invalid_argument, "state distance: " + std::to_string(x.rows()) +
                                       " vertices against " + std::to_string(reference.rows()));
  if (!(length > 0.0)) fail(Status::invalid_argument, "state distance: length must be positive");
  const Eigen::VectorXd d = (x - reference).rowwise().norm();
  return {std::sqrt(d.squaredNorm() / static_cast<double>(d.size())) / length,
          d.maxCoeff() / length};
}

}  // namespace progsim
