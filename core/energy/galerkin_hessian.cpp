#include "energy/galerkin_hessian.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "common/parallel.hpp"

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
    : finest_(finest),
      finest_pattern_version_(finest.pattern_version()),
      lift_(lifted(intrinsic)),
      lift_rows_(lift_),
      refresh_distance_(refresh_distance) {
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
  index_full_hessian(finest.hessian(at, false));
  finest_pattern_version_ = finest.pattern_version();
  mask_.assign(lift_.rows(), 1.0);
  build_pattern();
}

void GalerkinHessian::index_full_hessian(const SparseMatrix& lower) {
  const int n = static_cast<int>(lower.cols());
  std::vector<int> count(n + 1, 0);
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(lower, c); it; ++it) {
      ++count[c + 1];
      if (it.row() != c) ++count[it.row() + 1];
    }
  full_start_.assign(n + 1, 0);
  for (int c = 0; c < n; ++c) full_start_[c + 1] = full_start_[c] + count[c + 1];
  full_rows_.resize(full_start_[n]);
  full_entries_.resize(full_start_[n]);
  std::vector<int> next(full_start_.begin(), full_start_.end() - 1);
  int entry = 0;
  for (int c = 0; c < n; ++c)
    for (SparseMatrix::InnerIterator it(lower, c); it; ++it, ++entry) {
      full_rows_[next[c]] = static_cast<int>(it.row());
      full_entries_[next[c]++] = entry;
      if (it.row() == c) continue;
      full_rows_[next[it.row()]] = c;
      full_entries_[next[it.row()]++] = entry;
    }
}

void GalerkinHessian::touch_column(int column, const double* h, Workspace& w) const {
  w.touched.clear();
  for (SparseMatrix::InnerIterator u(lift_, column); u; ++u) {
    const int j = static_cast<int>(u.row());
    const double weight = u.value() * mask_[j];
    for (int k = full_start_[j]; k < full_start_[j + 1]; ++k) {
      const int r = full_rows_[k];
      if (w.stamp[r] != column) {
        w.stamp[r] = column;
        w.fine[r] = 0.0;
        w.touched.push_back(r);
      }
      if (h) w.fine[r] += h[full_entries_[k]] * weight;  // (H M U)_{r,column}
    }
  }
}

void GalerkinHessian::build_pattern() {
  const int n_coarse = static_cast<int>(lift_.cols());
  Workspace w{std::vector<double>(lift_.rows()),
              std::vector<int>(lift_.rows(), -1),
              {},
              std::vector<double>(n_coarse)};
  std::vector<int> coarse_stamp(n_coarse, -1);
  coarse_start_.assign(1, 0);
  for (int column = 0; column < n_coarse; ++column) {
    touch_column(column, nullptr, w);
    const std::size_t first = coarse_rows_.size();
    for (int r : w.touched)
      for (decltype(lift_rows_)::InnerIterator u(lift_rows_, r); u; ++u)
        if (coarse_stamp[u.col()] != column) {
          coarse_stamp[u.col()] = column;
          coarse_rows_.push_back(static_cast<int>(u.col()));
        }
    std::sort(coarse_rows_.begin() + first, coarse_rows_.end());
    coarse_start_.push_back(static_cast<int>(coarse_rows_.size()));
  }
}

void GalerkinHessian::coarse_column(int column, const double* h, Workspace& w, double* out) const {
  touch_column(column, h, w);
  for (int r : w.touched) {
    const double t = w.fine[r] * mask_[r];
    for (decltype(lift_rows_)::InnerIterator u(lift_rows_, r); u; ++u)
      w.coarse[u.col()] += u.value() * t;  // (Uᵀ M H M U)_{·,column}
  }
  for (int k = coarse_start_[column]; k < coarse_start_[column + 1]; ++k) {
    out[k] = w.coarse[coarse_rows_[k]];
    w.coarse[coarse_rows_[k]] = 0.0;
  }
}

void GalerkinHessian::assemble(const Vector& fine_x, bool project_psd,
                               const std::vector<int>& pinned, double* out) {
  if (pinned != masked_pinned_) {
    std::fill(mask_.begin(), mask_.end(), 1.0);
    for (int d : pinned) mask_[d] = 0.0;
    masked_pinned_ = pinned;
  }
  const double* h = finest_.hessian(fine_x, project_psd).valuePtr();
  if (finest_.pattern_version() != finest_pattern_version_)
    fail(Status::internal, "Galerkin Hessian: the finest Hessian's pattern changed");
  const int threads = loop_threads(static_cast<long>(full_rows_.size()));
  while (static_cast<int>(workspaces_.size()) < threads)
    workspaces_.push_back({std::vector<double>(lift_.rows()),
                           std::vector<int>(lift_.rows(), -1),
                           {},
                           std::vector<double>(lift_.cols())});
  for (Workspace& w : workspaces_) {
    std::fill(w.stamp.begin(), w.stamp.end(), -1);
    w.touched.reserve(lift_.rows());
  }
  const int n_coarse = static_cast<int>(lift_.cols());
#pragma omp parallel num_threads(threads)
  {
    Workspace& w = workspaces_[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 8)
    for (int column = 0; column < n_coarse; ++column) coarse_column(column, h, w, out);
  }
}

void GalerkinHessian::pattern(int* rows, int* cols) const {
  for (int c = 0; c + 1 < static_cast<int>(coarse_start_.size()); ++c)
    for (int k = coarse_start_[c]; k < coarse_start_[c + 1]; ++k) {
      rows[k] = coarse_rows_[k];
      cols[k] = c;
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
  assemble(fine_x, project_psd, pinned, out);
  ++assemblies_;
  if (refresh_distance_ <= 0.0) return;
  last_values_.assign(out, out + entry_count());
  last_x_ = fine_x;
  last_projected_ = project_psd;
  last_pinned_ = pinned;
}

}  // namespace progsim
