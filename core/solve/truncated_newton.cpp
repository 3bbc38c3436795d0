#include "solve/truncated_newton.hpp"

#include <algorithm>
#include <cmath>

namespace progsim {

namespace {

/// τ ≥ 0 with ‖p + τd‖_M = Δ, from ‖p‖²_M, pᵀMd, ‖d‖²_M and Δ² (Steihaug's boundary step).
double to_boundary(double pp, double pd, double dd, double radius2) {
  return (-pd + std::sqrt(std::max(0.0, pd * pd + dd * (radius2 - pp)))) / dd;
}

}  // namespace

TruncatedNewtonStats truncated_newton_step(
    const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& h, const SparseCholesky& m,
    const Vector& g, const TruncatedNewtonSettings& settings, Vector& p, Vector (&work)[4]) {
  Vector& r = work[0];   // residual −g − H p
  Vector& z = work[1];   // preconditioned residual M⁻¹ r
  Vector& d = work[2];   // CG search direction
  Vector& hd = work[3];  // H d
  TruncatedNewtonStats stats;
  r = -g;
  m.solve(r, z);
  const double g_norm = g.norm();
  double rz = r.dot(z);
  if (!(g_norm > 0.0 && rz > 0.0)) {
    p = z;
    stats.relative_residual = 0.0;
    return stats;
  }
  p.setZero(g.size());
  d = z;
  // ‖p‖²_M, pᵀMd and ‖d‖²_M by Conn, Gould & Toint's recurrences (2000, §7.5.1); the
  // preconditioned step z₀ has ‖z₀‖²_M = r₀ᵀz₀.
  const double rz0 = rz, radius2 = settings.radius * settings.radius * rz0;
  double pp = 0.0, pd = 0.0, dd = rz;
  for (; stats.iterations < settings.max_iterations; ++stats.iterations) {
    hd.noalias() = h.selfadjointView<Eigen::Lower>() * d;
    const double curvature = d.dot(hd);
    if (!(curvature > 0.0)) {  // Nocedal & Wright Alg. 7.1: stop on negative curvature
      stats.negative_curvature = true;
      break;
    }
    const double step = rz / curvature;  // CG step length (Alg. 7.1, α_j = rᵀz / dᵀHd)
    const double pp_next = pp + 2.0 * step * pd + step * step * dd;
    if (pp_next >= radius2) {  // Steihaug: stop where the iterate leaves the trust region
      p += to_boundary(pp, pd, dd, radius2) * d;
      stats.on_boundary = true;
      pp = radius2;
      ++stats.iterations;
      break;
    }
    p += step * d;
    r -= step * hd;
    pp = pp_next;
    stats.relative_residual = r.norm() / g_norm;
    if (stats.relative_residual <= settings.relative_residual) {
      ++stats.iterations;
      break;
    }
    m.solve(r, z);
    const double rz_next = r.dot(z);
    const double beta = rz_next / rz;  // β_j = r_{j+1}ᵀz_{j+1} / r_jᵀz_j
    pd = beta * (pd + step * dd);
    dd = rz_next + beta * beta * dd;
    d = z + beta * d;
    rz = rz_next;
  }
  if (stats.iterations == 0) {  // no usable curvature at all: the preconditioned step
    p = z;
    pp = dd;
  }
  stats.length = std::sqrt(pp / rz0);
  return stats;
}

}  // namespace progsim
