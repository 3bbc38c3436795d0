#include "energy/galerkin_hessian.hpp"

#include <cmath>
#include <string>

#include "common/error.hpp"

namespace progsim {
namespace {

/// U ⊗ I₃: each entry U_ij acts on the three coordinates of coarse vertex j.
GalerkinHessian::SparseMatrix lifted(const ProlongationMatrix& intrinsic) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(3 * static_cast<std::size_t>(intrinsic.nonZeros()));
  for (int i = 0; i < intrinsic.outerSize(); ++i)
    for (ProlongationMatrix::InnerIterator it(intrinsic, i); it; ++it)
      for (int d = 0; d < 3; ++d) triplets.emplace_back(3 * i + d, 3 * it.col() + d, it.value());
  GalerkinHessian::SparseMatrix lift(3 * intrinsic.rows(), 3 * intrinsic.cols());
  lift.setFromTriplets(triplets.begin(), triplets.end());
  return lift;
}

}  // namespace

GalerkinHessian::GalerkinHessian(const ProlongationMatrix& intrinsic, Problem& finest,
                                 const Vector& at, double refresh_distance)
    : finest_(finest), lift_(lifted(intrinsic)), refresh_distance_(refresh_distance) {
  if (!(refresh_distance >= 0.0) || !std::isfinite(refresh_distance))
    fail(Status::invalid_argument, "Galerkin Hessian: the refresh distance " +
                                       std::to_string(refresh_distance) +
                                       " m must be a finite number >= 0");
  if (lift_.rows() != finest.num_dofs() || at.size() != finest.num_dofs() ||
      finest.num_free() != finest.num_dofs())
    fail(Status::invalid_argument,
         "Galerkin Hessian: the prolongation has " + std::to_string(lift_.rows()) +
             " fine DOFs, the finest problem " + std::to_string(finest.num_dofs()) +
             " (all of them free), the state " + std::to_string(at.size()));
  pattern_ = product(at, false, {});
}

GalerkinHessian::SparseMatrix GalerkinHessian::product(const Vector& fine_x, bool project_psd,
                                                       const std::vector<int>& pinned) {
  if (masked_lift_.size() == 0 || pinned != masked_pinned_) {  // M U and (M U)ᵀ, per pinned set
    Eigen::VectorXd mask = Eigen::VectorXd::Ones(lift_.rows());
    for (int d : pinned) mask[d] = 0.0;
    masked_lift_ = mask.asDiagonal() * lift_;
    masked_lift_transpose_ = masked_lift_.transpose();
    masked_pinned_ = pinned;
  }
  const SparseMatrix full = finest_.hessian(fine_x, project_psd).selfadjointView<Eigen::Lower>();
  const SparseMatrix h_lift = full * masked_lift_;
  return SparseMatrix(masked_lift_transpose_ * h_lift);  // (MU)ᵀ H (MU), frozen offsets
}

void GalerkinHessian::pattern(int* rows, int* cols) const {
  std::size_t k = 0;
  for (int c = 0; c < pattern_.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(pattern_, c); it; ++it, ++k) {
      rows[k] = it.row();
      cols[k] = it.col();
    }
}

bool GalerkinHessian::reusable(const Vector& fine_x, bool project_psd,
                               const std::vector<int>& pinned) const {
  if (refresh_distance_ <= 0.0 || last_x_.size() != fine_x.size() ||
      project_psd != last_projected_ || pinned != last_pinned_)
    return false;
  const Eigen::Index n = fine_x.size() / 3;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < n; ++v)
    translation += fine_x.segment<3>(3 * v) - last_x_.segment<3>(3 * v);
  translation /= static_cast<double>(n);
  for (Eigen::Index v = 0; v < n; ++v)
    if (!((fine_x.segment<3>(3 * v) - last_x_.segment<3>(3 * v) - translation).squaredNorm() <=
          refresh_distance_ * refresh_distance_))  // NaN: refresh
      return false;
  return true;
}

void GalerkinHessian::values(const Vector& fine_x, bool project_psd, const std::vector<int>& pinned,
                             double* out) {
  if (reusable(fine_x, project_psd, pinned)) {
    ++reuses_;
    std::copy(last_values_.begin(), last_values_.end(), out);
    return;
  }
  const SparseMatrix h = product(fine_x, project_psd, pinned);
  if (h.nonZeros() != pattern_.nonZeros() ||
      !std::equal(h.innerIndexPtr(), h.innerIndexPtr() + h.nonZeros(), pattern_.innerIndexPtr()))
    fail(Status::internal, "Galerkin Hessian: the pattern of Uᵀ H U changed between evaluations");
  std::copy(h.valuePtr(), h.valuePtr() + h.nonZeros(), out);
  ++assemblies_;
  if (refresh_distance_ <= 0.0) return;
  last_values_.assign(h.valuePtr(), h.valuePtr() + h.nonZeros());
  last_x_ = fine_x;
  last_projected_ = project_psd;
  last_pinned_ = pinned;
}

}  // namespace progsim
