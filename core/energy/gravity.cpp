#include "energy/gravity.hpp"

namespace progsim {

Gravity::Gravity(Eigen::VectorXd vertex_masses, const Vec3& acceleration)
    : masses_(std::move(vertex_masses)), acceleration_(acceleration) {}

double Gravity::value(const Vector& x) const {
  double total = 0.0;
  for (Eigen::Index i = 0; i < masses_.size(); ++i)
    total -= masses_[i] * acceleration_.dot(x.segment<3>(3 * i));  // −m g·x
  return total;
}

void Gravity::add_gradient(const Vector&, Vector& g) const {
  for (Eigen::Index i = 0; i < masses_.size(); ++i)
    g.segment<3>(3 * i) -= masses_[i] * acceleration_;
}

}  // namespace progsim
