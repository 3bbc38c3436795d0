#pragma once
/// @file A test-only load: a pure bending moment applied at the free end of a strip, as the
/// potential W = −Σ_pairs m φ_pair, with φ = atan2(Δz, Δx) the angle of the vector from the
/// second-to-last to the last vertex of each row in the x–z plane (work-conjugate of rotation
/// about y). Derivatives are checked against finite differences in the test that uses it.
#include <cmath>
#include <utility>
#include <vector>

#include "energy/stencil_term.hpp"

namespace progsim::test_support {

class EndMomentTerm : public StencilTerm<2> {
 public:
  /// @param pairs (a, b): the end vector runs from vertex a to b
  /// @param moment_per_pair m (N·m)
  EndMomentTerm(std::vector<std::array<int, 2>> pairs, int num_vertices, double moment_per_pair)
      : StencilTerm<2>(std::move(pairs), num_vertices), m_(moment_per_pair) {}
  const char* name() const override { return "end_moment"; }

 protected:
  double element_value(int, const LocalVector& xe) const override {
    const Vec3 d = xe.tail<3>() - xe.head<3>();
    return -m_ * std::atan2(d.z(), d.x());
  }
  void element_gradient(int, const LocalVector& xe, LocalVector& g) const override {
    const Vec3 d = xe.tail<3>() - xe.head<3>();
    const double r2 = d.x() * d.x() + d.z() * d.z();
    const Vec3 dphi(-d.z() / r2, 0.0, d.x() / r2);  // ∂φ/∂d
    g << m_ * dphi, -m_ * dphi;
  }
  void element_hessian(int, const LocalVector& xe, LocalMatrix& h) const override {
    const Vec3 d = xe.tail<3>() - xe.head<3>();
    const double r2 = d.x() * d.x() + d.z() * d.z(), r4 = r2 * r2;
    Mat3 hphi = Mat3::Zero();  // ∂²φ/∂d²
    hphi(0, 0) = 2.0 * d.x() * d.z() / r4;
    hphi(2, 2) = -2.0 * d.x() * d.z() / r4;
    hphi(0, 2) = hphi(2, 0) = (d.z() * d.z() - d.x() * d.x()) / r4;
    const Mat3 b = -m_ * hphi;
    h << b, -b, -b, b;
  }

 private:
  double m_;
};

}  // namespace progsim::test_support
