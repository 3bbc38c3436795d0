#include "sim/handle_step_bound.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace progsim {
namespace {

/// The smallest root in (0, 1] of a α² + b α + c with c > 0 (where the quadratic first reaches
/// 0 from above), or 1 when it stays positive on [0, 1].
double first_root(double a, double b, double c) {
  if (a + b + c > 0.0 && (a <= 0.0 || b >= 0.0 || b * b < 4.0 * a * c)) return 1.0;
  if (std::abs(a) <= 1e-12 * std::abs(b)) return std::min(1.0, -c / b);  // linear: b α + c = 0
  const double root = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  // the two roots q/a and c/q, q = −(b + sign(b) √D)/2 (Numerical Recipes §5.6, stable form)
  const double q = -0.5 * (b + std::copysign(root, b));
  double first = 1.0;
  for (double r : {q / a, c / q})
    if (r > 0.0 && r < first) first = r;
  return first;
}

}  // namespace

double max_handle_step(const Faces& faces, const Vector& x, const Vector& step, double kept) {
  double alpha = 1.0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    int moved = 0;
    for (int k = 0; k < 3; ++k) moved += step.segment<3>(3 * faces(f, k)).isZero(0.0) ? 0 : 1;
    if (moved == 0 || moved == 3) continue;
    const auto at = [&](const Vector& v, int k) -> Vec3 { return v.segment<3>(3 * faces(f, k)); };
    const Vec3 e1 = at(x, 1) - at(x, 0), e2 = at(x, 2) - at(x, 0);
    const Vec3 d1 = at(step, 1) - at(step, 0), d2 = at(step, 2) - at(step, 0);
    const Vec3 n = e1.cross(e2);
    const double n2 = n.squaredNorm();
    if (!(n2 > 0.0)) continue;
    // n(α)·n/|n|² = 1 + b α + a α², n(α) = (e₁ + α d₁) × (e₂ + α d₂)
    const double b = (e1.cross(d2) + d1.cross(e2)).dot(n) / n2;
    const double a = d1.cross(d2).dot(n) / n2;
    alpha = std::min(alpha, first_root(a, b, 1.0 - kept));
  }
  return alpha;
}

}  // namespace progsim
