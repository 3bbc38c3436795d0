#pragma once
/// @file Lumped (diagonal) vertex masses and areas of a shell.
#include <vector>

#include "common/types.hpp"
#include "energy/shell_material.hpp"

namespace progsim {

/// m_i = Σ_{f ∋ i} ρ_f t_f A_f / 3 (kg), one third of each incident face's mass (|V|).
Eigen::VectorXd lumped_vertex_masses(const Positions& rest, const Faces& faces,
                                     const std::vector<ShellMaterial>& face_materials);

/// A_i = Σ_{f ∋ i} A_f / 3 (m²), one third of each incident face's area (|V|); sums to the
/// mesh's area.
Eigen::VectorXd lumped_vertex_areas(const Positions& rest, const Faces& faces);

}  // namespace progsim
