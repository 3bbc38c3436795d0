#pragma once
/// @file Levels of a tetrahedral solid and the prolongations between them (VPD §3.1.2, §3.3).
#include <vector>

#include "hierarchy/prolongation.hpp"
#include "hierarchy/tet_binding.hpp"
#include "mesh/tet_mesh.hpp"

namespace progsim {

/// Tet meshes of one solid from coarsest (0) to finest, with W_l (|V_{l+1}| × |V_l|) from
/// bind_to_tets between neighbours.
struct TetHierarchy {
  std::vector<TetMesh> levels;
  std::vector<ProlongationMatrix> to_finer;
  std::vector<std::vector<TetBinding>> bindings;
};

}  // namespace progsim
