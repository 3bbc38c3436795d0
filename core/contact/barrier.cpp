#include "contact/barrier.hpp"

#include <cmath>
#include <limits>

namespace progsim {

double barrier(double s, double s_hat) {
  if (s <= 0.0) return std::numeric_limits<double>::infinity();
  if (s >= s_hat) return 0.0;
  const double r = s - s_hat;
  return -r * r * std::log(s / s_hat);  // IPC eq. 6
}

double barrier_first_derivative(double s, double s_hat) {
  if (s >= s_hat) return 0.0;
  const double r = s - s_hat;
  return -2.0 * r * std::log(s / s_hat) - r * r / s;  // d/ds of IPC eq. 6
}

double barrier_second_derivative(double s, double s_hat) {
  if (s >= s_hat) return 0.0;
  const double r = s - s_hat;
  return -2.0 * std::log(s / s_hat) - 4.0 * r / s + r * r / (s * s);  // d²/ds² of IPC eq. 6
}

}  // namespace progsim
