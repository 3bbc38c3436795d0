#pragma once
/// @file Base class for energy terms that are a sum over small elements (stencils of K
/// vertices): triangles (K = 3), hinges (K = 4), ... Derived classes supply the per-element
/// value, gradient and Hessian; this class does the parallel, allocation-free assembly.
#include <array>
#include <vector>

#include "common/parallel.hpp"
#include "energy/energy_term.hpp"

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
  virtual void element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const;

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

// Compiled once, in stencil_term.cpp, for the stencil sizes progsim uses: each term's file
// would otherwise instantiate the PSD projection's 3K × 3K eigensolver again.
extern template class StencilTerm<1>;
extern template class StencilTerm<2>;
extern template class StencilTerm<3>;
extern template class StencilTerm<4>;
extern template class StencilTerm<6>;
extern template class StencilTerm<12>;

}  // namespace progsim
