#pragma once
/// @file Newton directions on indefinite Hessians by preconditioned conjugate gradients,
/// truncated at negative curvature (Steihaug 1983; Nocedal & Wright 2006, Algorithm 7.1).
#include <Eigen/SparseCore>
#include <limits>

#include "common/types.hpp"
#include "solve/sparse_cholesky.hpp"

namespace progsim {

/// When the CG iterations of one direction stop.
struct TruncatedNewtonSettings {
  double relative_residual = 0.1;  ///< stop when ‖H p + g‖ ≤ this · ‖g‖ (forcing term η)
  int max_iterations = 50;         ///< CG iterations per direction
  /// Trust-region radius Δ in units of the preconditioned step: ‖p‖_M ≤ Δ·‖M⁻¹g‖_M (Steihaug
  /// 1983). 1 returns at most the preconditioned step's length; infinity: no bound.
  double radius = std::numeric_limits<double>::infinity();
};

/// What the CG iterations of one direction did.
struct TruncatedNewtonStats {
  int iterations = 0;               ///< CG steps taken (0: the preconditioned step returned)
  bool negative_curvature = false;  ///< stopped on a direction d with dᵀHd ≤ 0
  double relative_residual = 1.0;   ///< ‖H p + g‖ / ‖g‖ of the last interior iterate
  bool on_boundary = false;         ///< stopped where the iterates left the trust region
  double length = 1.0;              ///< ‖p‖_M / ‖M⁻¹g‖_M of the returned p
};

/// Approximates the Newton step p = −H⁻¹g of an indefinite H by CG preconditioned with M,
/// starting from p = 0 (Steihaug–Toint CG). `h` stores H's lower triangle; `m` holds the
/// factorization of M (the per-element PSD-projected Hessian, which is definite). Every
/// iterate is a descent direction (gᵀp < 0), so a line search can follow. Stops at the
/// residual or iteration bound; at the trust-region boundary, where the iterate is cut to
/// ‖p‖_M = Δ‖M⁻¹g‖_M (the M-norm of CG iterates grows monotonically); or when a CG direction
/// has non-positive curvature: then the last iterate is kept, or, at the first direction,
/// the preconditioned step −M⁻¹g itself (Algorithm 7.1's fallback in M's metric). Where the
/// projection discarded curvature (soft folding and twisting modes), the step grows to what
/// H says instead of creeping.
/// `work` holds four vectors between calls (no allocation once sized).
TruncatedNewtonStats truncated_newton_step(
    const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& h, const SparseCholesky& m,
    const Vector& g, const TruncatedNewtonSettings& settings, Vector& p, Vector (&work)[4]);

}  // namespace progsim
