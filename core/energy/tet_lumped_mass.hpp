#pragma once
/// @file Lumped (diagonal) vertex masses of a tetrahedral solid.
#include <vector>

#include "common/types.hpp"
#include "energy/solid_material.hpp"

namespace progsim {

/// m_i = Σ_{t ∋ i} ρ_t V̄_t / 4 (kg), a quarter of each incident tet's mass (|V|); sums to the
/// solid's mass. Precondition: tets indexed within rest and positively oriented.
Eigen::VectorXd lumped_tet_masses(const Positions& rest, const Tets& tets,
                                  const std::vector<SolidMaterial>& tet_materials);

}  // namespace progsim
