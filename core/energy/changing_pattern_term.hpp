#pragma once
/// @file Base of the energy terms whose Hessian stencils change with x (contact, friction):
/// they have no fixed pattern and hand the Problem their triplets at every evaluation.
#include "energy/energy_term.hpp"

namespace progsim {

/// An EnergyTerm without a fixed Hessian pattern: implement append_hessian_triplets().
class ChangingPatternTerm : public EnergyTerm {
 public:
  std::size_t hessian_entry_count() const final { return 0; }
  void hessian_pattern(int*, int*) const final {}
  void hessian_values(const Vector&, bool, double*) const final {}
  bool has_fixed_pattern() const final { return false; }
};

}  // namespace progsim
