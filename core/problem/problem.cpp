#include "problem/problem.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "common/timer.hpp"

namespace progsim {
namespace {

/// Pattern versions are unique across Problems, so a solver never mistakes a new Problem at a
/// reused address for the one it analysed.
long next_pattern_version() {
  static std::atomic<long> counter{0};
  return ++counter;
}

}  // namespace

Problem::Problem(int num_dofs) : num_dofs_(num_dofs), fixed_(num_dofs, false) {}

void Problem::add_term_impl(std::unique_ptr<EnergyTerm> term) {
  if (finalized_) fail(Status::wrong_call_order, "Problem: add_term after finalize");
  stats_.push_back(TermStats{term->name()});
  if (!term->has_fixed_pattern()) changing_terms_.push_back(terms_.size());
  if (auto* filter = dynamic_cast<StepFilter*>(term.get())) filters_.push_back(filter);
  terms_.push_back(std::move(term));
}

void Problem::set_fixed_dofs(const std::vector<bool>& fixed) {
  if (static_cast<int>(fixed.size()) != num_dofs_)
    fail(Status::invalid_argument, "Problem: fixed-DOF mask has " + std::to_string(fixed.size()) +
                                       " entries, expected " + std::to_string(num_dofs_));
  fixed_ = fixed;
  if (finalized_) finalize();
}

void Problem::finalize() {
  build_reduction();
  build_hessian_pattern();
  finalized_ = true;
  pattern_version_ = next_pattern_version();
}

void Problem::build_reduction() {
  full_to_free_.assign(num_dofs_, -1);
  free_to_full_.clear();
  for (int d = 0; d < num_dofs_; ++d) {
    if (fixed_[d]) continue;
    full_to_free_[d] = static_cast<int>(free_to_full_.size());
    free_to_full_.push_back(d);
  }
}

void Problem::build_hessian_pattern() {
  entry_offsets_.assign(1, 0);
  for (const auto& term : terms_)
    entry_offsets_.push_back(entry_offsets_.back() + term->hessian_entry_count());
  // Every DOF also gets a zero-valued diagonal entry, so that each free DOF has a diagonal
  // slot in the pattern (a diagonal shift then always has somewhere to go).
  const std::size_t term_entries = entry_offsets_.back();
  const std::size_t num_entries = term_entries + num_dofs_;
  entry_values_.assign(num_entries, 0.0);
  std::vector<int> rows(num_entries), cols(num_entries);
  for (std::size_t t = 0; t < terms_.size(); ++t)
    terms_[t]->hessian_pattern(rows.data() + entry_offsets_[t], cols.data() + entry_offsets_[t]);
  std::iota(rows.begin() + term_entries, rows.end(), 0);
  std::iota(cols.begin() + term_entries, cols.end(), 0);

  // Keep the lower triangle of the free block, in reduced indices.
  std::vector<std::size_t> kept;
  kept.reserve(num_entries / 2 + 1);
  for (std::size_t k = 0; k < num_entries; ++k) {
    const int r = full_to_free_[rows[k]], c = full_to_free_[cols[k]];
    if (r < 0 || c < 0 || r < c) continue;
    rows[k] = r;
    cols[k] = c;
    kept.push_back(k);
  }
  // Sort kept triplets by (column, row): consecutive equal keys share one nonzero.
  std::sort(kept.begin(), kept.end(), [&](std::size_t a, std::size_t b) {
    return cols[a] != cols[b] ? cols[a] < cols[b]
                              : (rows[a] != rows[b] ? rows[a] < rows[b] : a < b);
  });
  const int n = num_free();
  std::vector<int> outer(n + 1, 0), inner;
  nonzero_entry_offsets_.assign(1, 0);
  nonzero_entries_.clear();
  nonzero_entries_.reserve(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const std::size_t k = kept[i];
    const bool new_nonzero = i == 0 || rows[k] != rows[kept[i - 1]] || cols[k] != cols[kept[i - 1]];
    if (new_nonzero) {
      if (i > 0) nonzero_entry_offsets_.push_back(static_cast<int>(nonzero_entries_.size()));
      inner.push_back(rows[k]);
      ++outer[cols[k] + 1];
    }
    nonzero_entries_.push_back(k);
  }
  if (!kept.empty()) nonzero_entry_offsets_.push_back(static_cast<int>(nonzero_entries_.size()));
  std::partial_sum(outer.begin(), outer.end(), outer.begin());
  hessian_ = SparseMatrix(n, n);
  hessian_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), hessian_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), hessian_.innerIndexPtr());
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + inner.size(), 0.0);
}

double Problem::value(const Vector& x) {
  double total = 0.0;
  for (std::size_t t = 0; t < terms_.size(); ++t) {
    ScopedTimer timer(stats_[t].seconds);
    ++stats_[t].value_evaluations;
    total += terms_[t]->value(x);
  }
  return total;
}

void Problem::unreduced_gradient(const Vector& x, Vector& g) {
  g.setZero(num_dofs_);
  for (std::size_t t = 0; t < terms_.size(); ++t) {
    ScopedTimer timer(stats_[t].seconds);
    ++stats_[t].gradient_evaluations;
    terms_[t]->add_gradient(x, g);
  }
}

void Problem::gradient(const Vector& x, Vector& g) {
  unreduced_gradient(x, g);
  for (int d = 0; d < num_dofs_; ++d)
    if (fixed_[d]) g[d] = 0.0;
}

bool Problem::hessian_is_exact() const {
  return std::all_of(terms_.begin(), terms_.end(),
                     [](const auto& term) { return term->hessian_is_exact(); });
}

const Problem::SparseMatrix& Problem::hessian(const Vector& x, bool project_psd) {
  if (!finalized_) fail(Status::wrong_call_order, "Problem: hessian before finalize");
  for (std::size_t t = 0; t < terms_.size(); ++t) {
    ScopedTimer timer(stats_[t].seconds);
    ++stats_[t].hessian_evaluations;
    terms_[t]->hessian_values(x, project_psd, entry_values_.data() + entry_offsets_[t]);
  }
  double* values = hessian_.valuePtr();
  const int nnz = static_cast<int>(hessian_.nonZeros());
#pragma omp parallel for schedule(static) num_threads(loop_threads(nnz))
  for (int i = 0; i < nnz; ++i) {
    double sum = 0.0;
    for (int j = nonzero_entry_offsets_[i]; j < nonzero_entry_offsets_[i + 1]; ++j)
      sum += entry_values_[nonzero_entries_[j]];
    values[i] = sum;
  }
  return changing_terms_.empty() ? hessian_ : add_changing_pattern_terms(x, project_psd);
}

/// hessian_ + the reduced lower-triangle triplets of the terms whose pattern changes.
const Problem::SparseMatrix& Problem::add_changing_pattern_terms(const Vector& x,
                                                                 bool project_psd) {
  triplets_.clear();
  for (std::size_t t : changing_terms_) {
    ScopedTimer timer(stats_[t].seconds);
    ++stats_[t].hessian_evaluations;
    terms_[t]->append_hessian_triplets(x, project_psd, triplets_);
  }
  std::size_t kept = 0;
  for (const Eigen::Triplet<double>& e : triplets_) {
    const int r = full_to_free_[e.row()], c = full_to_free_[e.col()];
    if (r >= 0 && c >= 0 && r >= c) triplets_[kept++] = Eigen::Triplet<double>(r, c, e.value());
  }
  triplets_.resize(kept);
  changing_part_.resize(num_free(), num_free());
  changing_part_.setFromTriplets(triplets_.begin(), triplets_.end());
  SparseMatrix sum = hessian_ + changing_part_;
  sum.makeCompressed();
  const bool same_pattern = sum.nonZeros() == combined_.nonZeros() &&
                            sum.cols() == combined_.cols() &&
                            std::equal(sum.outerIndexPtr(), sum.outerIndexPtr() + sum.cols() + 1,
                                       combined_.outerIndexPtr()) &&
                            std::equal(sum.innerIndexPtr(), sum.innerIndexPtr() + sum.nonZeros(),
                                       combined_.innerIndexPtr());
  if (!same_pattern) pattern_version_ = next_pattern_version();
  combined_ = std::move(sum);
  return combined_;
}

void Problem::refresh_hessian() {
  for (auto& term : terms_) term->refresh_hessian();
}

void Problem::begin_solve(const Vector& x) {
  for (StepFilter* f : filters_) f->begin_solve(x);
}

double Problem::max_step(const Vector& x, const Vector& p) {
  double alpha = 1.0;
  for (StepFilter* f : filters_) {
    const double bound = f->max_step(x, p);
    if (std::isnan(bound)) return bound;  // a non-finite motion: no step is known to be safe
    alpha = std::min(alpha, bound);
  }
  return alpha;
}

bool Problem::end_iteration(const Vector& x) {
  bool changed = false;
  for (StepFilter* f : filters_) changed = f->end_iteration(x) || changed;
  return changed;
}

void Problem::restrict_to_free(const Vector& full, Vector& reduced) const {
  reduced.resize(num_free());
  for (int i = 0; i < num_free(); ++i) reduced[i] = full[free_to_full_[i]];
}

void Problem::expand_from_free(const Vector& reduced, Vector& full) const {
  full.setZero(num_dofs_);
  for (int i = 0; i < num_free(); ++i) full[free_to_full_[i]] = reduced[i];
}

EnergyTerm* Problem::find_term(const std::string& name) {
  for (auto& term : terms_)
    if (name == term->name()) return term.get();
  return nullptr;
}

}  // namespace progsim
