#pragma once
/// @file Base class for energy terms that are a sum over small elements (stencils of K
/// vertices): triangles (K = 3), hinges (K = 4), ... Derived classes supply the per-element
/// value, gradient and Hessian; this class does the parallel, allocation-free assembly.
#include <array>
#include <vector>

#include "common/parallel.hpp"
#include "energy/energy_term.hpp"
#include "energy/psd_projection.hpp"

namespace progsim {

/// E(x) = Σ_e E_e(x_e) over stencils of K vertices. Evaluation is OpenMP-parallel over
/// elements and deterministic (no atomics: gradients are gathered per vertex in a fixed order).
template <int K>
class StencilTerm : public EnergyTerm {
 public:
  static constexpr int kDofs = 3 * K;
  using Stencil = std::array<int, K>;
  using LocalVector = Eigen::Matrix<double, kDofs, 1>;
  using LocalMatrix = Eigen::Matrix<double, kDofs, kDofs>;

  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  std::size_t hessian_entry_count() const override { return stencils_.size() * kDofs * kDofs; }
  void hessian_pattern(int* rows, int* cols) const override;
  void hessian_values(const Vector& x, bool project_psd, double* values) const override;

  int num_elements() const { return static_cast<int>(stencils_.size()); }
  const Stencil& stencil(int e) const { return stencils_[e]; }

 protected:
  /// @param stencils vertex indices of each element
  /// @param num_vertices |V|, the size of x is 3|V|
  StencilTerm(std::vector<Stencil> stencils, int num_vertices);

  /// E_e at the element's stacked positions xe (3K).
  virtual double element_value(int e, const LocalVector& xe) const = 0;
  /// ∇E_e (3K).
  virtual void element_gradient(int e, const LocalVector& xe, LocalVector& g) const = 0;
  /// ∇²E_e (3K × 3K), exact (not projected).
  virtual void element_hessian(int e, const LocalVector& xe, LocalMatrix& h) const = 0;
  /// PSD-projected ∇²E_e. Default: exact Hessian, then eigenvalue clamp. Terms with a
  /// cheaper exact projection (e.g. in deformation-gradient space) override it.
  virtual void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
    element_hessian(e, xe, h);
    project_psd(h);
  }

  /// Gathers an element's positions from x.
  LocalVector gather(int e, const Vector& x) const;

 private:
  std::vector<Stencil> stencils_;
  int num_vertices_;
  // vertex → (element·K + slot), CSR; built once, used to gather gradients per vertex.
  std::vector<int> incidence_offsets_;
  std::vector<int> incidence_slots_;
  mutable std::vector<LocalVector> element_gradients_;
};

// ---- implementation ----

template <int K>
StencilTerm<K>::StencilTerm(std::vector<Stencil> stencils, int num_vertices)
    : stencils_(std::move(stencils)),
      num_vertices_(num_vertices),
      incidence_offsets_(num_vertices + 1, 0),
      element_gradients_(stencils_.size()) {
  for (const Stencil& s : stencils_)
    for (int v : s) ++incidence_offsets_[v + 1];
  for (int v = 0; v < num_vertices; ++v) incidence_offsets_[v + 1] += incidence_offsets_[v];
  incidence_slots_.resize(incidence_offsets_.back());
  std::vector<int> fill(incidence_offsets_.begin(), incidence_offsets_.end() - 1);
  for (int e = 0; e < num_elements(); ++e)
    for (int k = 0; k < K; ++k) incidence_slots_[fill[stencils_[e][k]]++] = e * K + k;
}

template <int K>
typename StencilTerm<K>::LocalVector StencilTerm<K>::gather(int e, const Vector& x) const {
  LocalVector xe;
  for (int k = 0; k < K; ++k)
    xe.template segment<3>(3 * k) = x.template segment<3>(3 * stencils_[e][k]);
  return xe;
}

template <int K>
double StencilTerm<K>::value(const Vector& x) const {
  double total = 0.0;
#pragma omp parallel for reduction(+ : total) schedule(static) if (num_elements() >= kMinParallelItems)
  for (int e = 0; e < num_elements(); ++e) total += element_value(e, gather(e, x));
  return total;
}

template <int K>
void StencilTerm<K>::add_gradient(const Vector& x, Vector& g) const {
#pragma omp parallel for schedule(static) if (num_elements() >= kMinParallelItems)
  for (int e = 0; e < num_elements(); ++e) element_gradient(e, gather(e, x), element_gradients_[e]);
#pragma omp parallel for schedule(static) if (num_vertices_ >= kMinParallelItems)
  for (int v = 0; v < num_vertices_; ++v) {
    for (int i = incidence_offsets_[v]; i < incidence_offsets_[v + 1]; ++i) {
      const int slot = incidence_slots_[i];
      g.template segment<3>(3 * v) +=
          element_gradients_[slot / K].template segment<3>(3 * (slot % K));
    }
  }
}

template <int K>
void StencilTerm<K>::hessian_pattern(int* rows, int* cols) const {
  std::size_t n = 0;
  for (const Stencil& s : stencils_)
    for (int c = 0; c < kDofs; ++c)
      for (int r = 0; r < kDofs; ++r, ++n) {
        rows[n] = 3 * s[r / 3] + r % 3;
        cols[n] = 3 * s[c / 3] + c % 3;
      }
}

template <int K>
void StencilTerm<K>::hessian_values(const Vector& x, bool project_psd, double* values) const {
#pragma omp parallel for schedule(static) if (num_elements() >= kMinParallelItems)
  for (int e = 0; e < num_elements(); ++e) {
    Eigen::Map<LocalMatrix> h(values + static_cast<std::size_t>(e) * kDofs * kDofs);
    LocalMatrix local;
    if (project_psd)
      element_projected_hessian(e, gather(e, x), local);
    else
      element_hessian(e, gather(e, x), local);
    h = local;
  }
}

}  // namespace progsim
