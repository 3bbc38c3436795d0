#pragma once
/// @file A tiny independent energy term for solver tests: zero-rest-length springs between
/// vertex pairs plus an optional quartic well, E = Σ k/2 ‖x_a − x_b‖² + q Σ_i ‖x_i − c_i‖⁴.
#include <array>
#include <vector>

#include "energy/stencil_term.hpp"

namespace progsim::test_support {

class SpringTerm : public StencilTerm<2> {
 public:
  SpringTerm(std::vector<std::array<int, 2>> pairs, int num_vertices, double stiffness)
      : StencilTerm<2>(std::move(pairs), num_vertices), k_(stiffness) {}
  const char* name() const override { return "springs"; }

 protected:
  double element_value(int, const LocalVector& xe) const override {
    return 0.5 * k_ * (xe.head<3>() - xe.tail<3>()).squaredNorm();
  }
  void element_gradient(int, const LocalVector& xe, LocalVector& g) const override {
    const Vec3 d = xe.head<3>() - xe.tail<3>();
    g << k_ * d, -k_ * d;
  }
  void element_hessian(int, const LocalVector&, LocalMatrix& h) const override {
    const Mat3 i = k_ * Mat3::Identity();
    h << i, -i, -i, i;
  }

 private:
  double k_;
};

}  // namespace progsim::test_support
