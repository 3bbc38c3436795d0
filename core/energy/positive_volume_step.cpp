#include "energy/positive_volume_step.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace progsim {
namespace {

constexpr double kShrink = 0.8;

/// det(A + tB) = det A + t tr(adj(A) B) + t² tr(adj(B) A) + t³ det B, adj the adjugate
/// (the characteristic expansion of a 3×3 determinant along a line).
std::array<double, 4> determinant_cubic(const Mat3& a, const Mat3& b) {
  const auto adjugate = [](const Mat3& m) {
    Mat3 c;
    for (int j = 0; j < 3; ++j) c.col(j) = m.col((j + 1) % 3).cross(m.col((j + 2) % 3));
    return Mat3(c.transpose());  // adj M = (cof M)ᵀ
  };
  return {a.determinant(), (adjugate(a) * b).trace(), (adjugate(b) * a).trace(), b.determinant()};
}

/// Roots in (0, 1) of the derivative c₁ + 2c₂t + 3c₃t², ascending, then 1.
int breakpoints(const std::array<double, 4>& c, std::array<double, 3>& t) {
  int n = 0;
  const double a = 3.0 * c[3], b = 2.0 * c[2], q = c[1];
  const double scale = std::max({std::abs(a), std::abs(b), std::abs(q)});
  if (std::abs(a) > 1e-14 * scale) {
    const double disc = b * b - 4.0 * a * q;
    if (disc >= 0.0) {
      // Numerically stable quadratic roots (no cancellation between −b and √disc).
      const double root_term = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      std::array<double, 2> r = {root_term / a, root_term != 0.0 ? q / root_term : 0.0};
      std::sort(r.begin(), r.end());
      for (double ri : r)
        if (ri > 0.0 && ri < 1.0) t[n++] = ri;
    }
  } else if (std::abs(b) > 1e-14 * scale) {
    const double r = -q / b;
    if (r > 0.0 && r < 1.0) t[n++] = r;
  }
  t[n++] = 1.0;
  return n;
}

}  // namespace

double positive_volume_step(const Mat3& d, const Mat3& dd) {
  if (!d.allFinite() || !dd.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  const auto det_at = [&](double t) { return (d + t * dd).determinant(); };
  if (!(det_at(0.0) > 0.0)) return 0.0;
  std::array<double, 3> t;
  const int n = breakpoints(determinant_cubic(d, dd), t);
  // Between breakpoints the cubic is monotone: the first breakpoint where det(D + t dD) ≤ 0
  // brackets the first root; bisection keeps the positive end.
  double left = 0.0;
  for (int k = 0; k < n; ++k) {
    if (det_at(t[k]) > 0.0) {
      left = t[k];
      continue;
    }
    double right = t[k];
    for (int it = 0; it < 60 && right - left > 1e-12 * right; ++it) {
      const double mid = 0.5 * (left + right);
      (det_at(mid) > 0.0 ? left : right) = mid;
    }
    return kShrink * left;
  }
  return 1.0;
}

}  // namespace progsim
