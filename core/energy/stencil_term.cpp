#include "energy/stencil_term.hpp"

#include "energy/psd_projection.hpp"

namespace progsim {

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
  return ordered_sum(num_elements(), [&](long e) {
    const int i = static_cast<int>(e);
    return element_value(i, gather(i, x));
  });
}

template <int K>
void StencilTerm<K>::add_gradient(const Vector& x, Vector& g) const {
#pragma omp parallel for schedule(static) num_threads(loop_threads(num_elements()))
  for (int e = 0; e < num_elements(); ++e) element_gradient(e, gather(e, x), element_gradients_[e]);
#pragma omp parallel for schedule(static) num_threads(loop_threads(num_vertices_))
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
#pragma omp parallel for schedule(static) num_threads(loop_threads(num_elements()))
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

template <int K>
void StencilTerm<K>::element_projected_hessian(int e, const LocalVector& xe, LocalMatrix& h) const {
  element_hessian(e, xe, h);
  project_psd(h);
}

template class StencilTerm<1>;
template class StencilTerm<2>;
template class StencilTerm<3>;
template class StencilTerm<4>;
template class StencilTerm<6>;
template class StencilTerm<12>;

}  // namespace progsim
