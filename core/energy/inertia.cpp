#include "energy/inertia.hpp"

#include "common/parallel.hpp"

namespace progsim {

Inertia::Inertia(Eigen::VectorXd vertex_masses, double time_step)
    : masses_(std::move(vertex_masses)),
      time_step_(time_step),
      target_(Vector::Zero(3 * masses_.size())) {}

double Inertia::value(const Vector& x) const {
  const double total = ordered_sum(masses_.size(), [&](long i) {
    return masses_[i] * (x.segment<3>(3 * i) - target_.segment<3>(3 * i)).squaredNorm();
  });
  return 0.5 * total / (time_step_ * time_step_);  // ½h⁻²‖x − x̂‖²_M
}

void Inertia::add_gradient(const Vector& x, Vector& g) const {
  const double inv_h2 = 1.0 / (time_step_ * time_step_);
  const Eigen::Index n = masses_.size();
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (Eigen::Index i = 0; i < n; ++i)
    g.segment<3>(3 * i) += masses_[i] * inv_h2 * (x.segment<3>(3 * i) - target_.segment<3>(3 * i));
}

void Inertia::hessian_pattern(int* rows, int* cols) const {
  for (Eigen::Index d = 0; d < 3 * masses_.size(); ++d) rows[d] = cols[d] = static_cast<int>(d);
}

void Inertia::hessian_values(const Vector&, bool, double* values) const {
  const double inv_h2 = 1.0 / (time_step_ * time_step_);
  for (Eigen::Index d = 0; d < 3 * masses_.size(); ++d) values[d] = masses_[d / 3] * inv_h2;
}

}  // namespace progsim
