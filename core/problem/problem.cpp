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

/// Index of entry (row, col) among m's stored nonzeros, or −1 when it has none.
int slot_of(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& m, int row, int col) {
  const int* begin = m.innerIndexPtr() + m.outerIndexPtr()[col];
  const int* end = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  return it != end && *it == row ? static_cast<int>(it - m.innerIndexPtr()) : -1;
}

/// A new solve keeps the pattern of the last one while at most this fraction of its entries go
/// unused (bounding the fill of stale contact entries).
constexpr double kMaxUnusedPatternFraction = 0.25;

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

void Problem::set_shared_dofs(std::vector<std::vector<int>> groups) {
  std::vector<bool> seen(num_dofs_, false);
  for (const std::vector<int>& group : groups)
    for (int d : group) {
      if (d < 0 || d >= num_dofs_ || seen[d] || fixed_[d])
        fail(Status::invalid_argument, "Problem: shared DOF " + std::to_string(d) +
                                           " is out of range, fixed or in two groups (" +
                                           std::to_string(num_dofs_) + " DOFs)");
      seen[d] = true;
    }
  shared_ = std::move(groups);
  if (finalized_) finalize();
}

void Problem::finalize() {
  build_reduction();
  build_hessian_pattern();
  finalized_ = true;
  pattern_version_ = next_pattern_version();
}

void Problem::build_reduction() {
  number_unknowns();
  list_unknown_dofs();
}

/// full_to_free_: free DOFs numbered in order, each shared group once, at its smallest DOF.
void Problem::number_unknowns() {
  full_to_free_.assign(num_dofs_, -1);
  for (const std::vector<int>& group : shared_) {
    if (group.empty()) continue;
    const int owner = *std::min_element(group.begin(), group.end());
    for (int d : group) {
      if (fixed_[d])
        fail(Status::invalid_argument, "Problem: shared DOF " + std::to_string(d) + " is fixed");
      full_to_free_[d] = -2 - owner;  // marks a group member until its owner is numbered
    }
  }
  int unknowns = 0;
  for (int d = 0; d < num_dofs_; ++d)
    if (!fixed_[d] && (full_to_free_[d] == -1 || full_to_free_[d] == -2 - d))
      full_to_free_[d] = unknowns++;
  for (int d = 0; d < num_dofs_; ++d)
    if (full_to_free_[d] < -1) full_to_free_[d] = full_to_free_[-2 - full_to_free_[d]];
}

/// free_offsets_ / free_dofs_: the DOFs of each unknown (CSR), ascending.
void Problem::list_unknown_dofs() {
  int unknowns = 0;
  for (int u : full_to_free_) unknowns = std::max(unknowns, u + 1);
  free_offsets_.assign(unknowns + 1, 0);
  for (int d = 0; d < num_dofs_; ++d)
    if (full_to_free_[d] >= 0) ++free_offsets_[full_to_free_[d] + 1];
  std::partial_sum(free_offsets_.begin(), free_offsets_.end(), free_offsets_.begin());
  free_dofs_.resize(free_offsets_.back());
  std::vector<int> next(free_offsets_.begin(), free_offsets_.end() - 1);
  for (int d = 0; d < num_dofs_; ++d)
    if (full_to_free_[d] >= 0) free_dofs_[next[full_to_free_[d]]++] = d;
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
  combined_ = SparseMatrix();  // hessian_slots_ referred to the old pattern
  combined_is_built_ = false;
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

/// hessian_ + the reduced lower-triangle triplets of the terms whose pattern changes, summed in
/// a pattern that keeps every entry this solve has used (issue 33 §2): a contact set that only
/// moves within it keeps the symbolic analysis, and no call builds a matrix from triplets.
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
  const bool fits = locate_triplets_in_combined() && (!combined_is_stale_ || few_unused_entries());
  if (!fits) grow_combined_pattern();
  scatter_combined_values();
  return combined_;
}

bool Problem::locate_triplets_in_combined() {
  if (!combined_is_built_) return false;  // none since finalize()
  const int n = static_cast<int>(triplets_.size());
  triplet_slots_.resize(n);
  int missing = 0;
#pragma omp parallel for reduction(+ : missing) schedule(static) num_threads(loop_threads(n))
  for (int i = 0; i < n; ++i) {
    triplet_slots_[i] = slot_of(combined_, triplets_[i].row(), triplets_[i].col());
    missing += triplet_slots_[i] < 0;
  }
  return missing == 0;
}

/// combined_'s pattern becomes hessian_'s, the entries kept in this solve (unless stale) and
/// the triplets'; a pattern that differs from the previous one gets a new version.
void Problem::grow_combined_pattern() {
  const bool restart = combined_is_stale_ || !combined_is_built_;
  const SparseMatrix& base = restart ? hessian_ : combined_;
  changing_part_.resize(num_free(), num_free());
  changing_part_.setFromTriplets(triplets_.begin(), triplets_.end());
  SparseMatrix grown = base + changing_part_;
  grown.makeCompressed();
  const bool same_pattern =
      grown.nonZeros() == combined_.nonZeros() && grown.cols() == combined_.cols() &&
      std::equal(grown.outerIndexPtr(), grown.outerIndexPtr() + grown.cols() + 1,
                 combined_.outerIndexPtr()) &&
      std::equal(grown.innerIndexPtr(), grown.innerIndexPtr() + grown.nonZeros(),
                 combined_.innerIndexPtr());
  if (!same_pattern) pattern_version_ = next_pattern_version();
  combined_ = std::move(grown);
  combined_is_stale_ = false;
  combined_is_built_ = true;
  const int nnz = static_cast<int>(hessian_.nonZeros());
  hessian_slots_.resize(nnz);
  for (int c = 0; c < hessian_.cols(); ++c)
    for (int i = hessian_.outerIndexPtr()[c]; i < hessian_.outerIndexPtr()[c + 1]; ++i)
      hessian_slots_[i] = slot_of(combined_, hessian_.innerIndexPtr()[i], c);
  locate_triplets_in_combined();
}

/// True when at most kMaxUnusedPatternFraction of combined_'s entries take no value now.
bool Problem::few_unused_entries() {
  used_.assign(combined_.nonZeros(), 0);
  for (int slot : hessian_slots_) used_[slot] = 1;
  for (int slot : triplet_slots_) used_[slot] = 1;
  const long used = std::count(used_.begin(), used_.end(), 1);
  const bool few = static_cast<double>(combined_.nonZeros() - used) <=
                   kMaxUnusedPatternFraction * static_cast<double>(combined_.nonZeros());
  combined_is_stale_ = !few;
  return few;
}

/// combined_ = hessian_ + Σ triplets, in place (the triplets' sum is serial: deterministic).
void Problem::scatter_combined_values() {
  double* values = combined_.valuePtr();
  std::fill(values, values + combined_.nonZeros(), 0.0);
  const double* fixed_values = hessian_.valuePtr();
  const int nnz = static_cast<int>(hessian_.nonZeros());
#pragma omp parallel for schedule(static) num_threads(loop_threads(nnz))
  for (int i = 0; i < nnz; ++i) values[hessian_slots_[i]] = fixed_values[i];
  for (std::size_t i = 0; i < triplets_.size(); ++i)
    values[triplet_slots_[i]] += triplets_[i].value();
}

void Problem::refresh_hessian() {
  for (auto& term : terms_) term->refresh_hessian();
}

void Problem::begin_solve(const Vector& x) {
  combined_is_stale_ = true;  // a new solve checks how much of the pattern it still uses
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
  for (int i = 0; i < num_free(); ++i) {
    double sum = 0.0;
    for (int k = free_offsets_[i]; k < free_offsets_[i + 1]; ++k) sum += full[free_dofs_[k]];
    reduced[i] = sum;
  }
}

void Problem::expand_from_free(const Vector& reduced, Vector& full) const {
  full.setZero(num_dofs_);
  for (int i = 0; i < num_free(); ++i)
    for (int k = free_offsets_[i]; k < free_offsets_[i + 1]; ++k) full[free_dofs_[k]] = reduced[i];
}

EnergyTerm* Problem::find_term(const std::string& name) {
  for (auto& term : terms_)
    if (name == term->name()) return term.get();
  return nullptr;
}

}  // namespace progsim
