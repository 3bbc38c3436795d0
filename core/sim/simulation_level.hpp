#pragma once
/// @file Which level of a mesh hierarchy a simulation solves (PSQ §3.1: M_l), and that level
/// as a shell model of the scene's bodies.
#include <memory>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "sim/shell_model.hpp"

namespace progsim {

/// A level of a hierarchy built from the scene's merged bodies. The default (no hierarchy) is
/// the scene's own mesh.
struct SimulationLevel {
  std::shared_ptr<const MeshHierarchy> hierarchy;  ///< null: the scene's own mesh
  int level = 0;                                   ///< 0 = coarsest … hierarchy->finest()
  /// The prolongation to the finest level, as operators applied in turn (P^l alone, PSQ eq. 9,
  /// or P_{l+1}^l, …, P_L^{L−1}). Set: the shell energy is the proxy Ψ_L(P(x)) (PSQ eq. 2,
  /// progressive preview). Empty: the level's own shell energy (a direct solve at this level).
  std::vector<std::shared_ptr<const ShellProlongation>> to_finest;
  /// Weight of the consistency penalty toward the coarser level's prolonged frame (VPD eq. 4;
  /// progressive dynamics on levels above the coarsest); 0: no penalty term.
  double consistency_weight = 0.0;

  bool is_finest() const { return !hierarchy || level == hierarchy->finest(); }
};

/// Level `level` of `hierarchy` (built from `finest.rest`) as a model of the same bodies: the
/// level's rest mesh, its faces ordered by body with each body's material, and the level's
/// lumped masses and topology. Bodies map to levels by vertex id (decimation never merges two
/// connected components). Throws Error(invalid_argument) if the hierarchy's finest level is not
/// `finest.rest`.
ShellModel level_shell_model(const ShellModel& finest, const MeshHierarchy& hierarchy, int level);

/// The finest level's lumped masses restricted through the intrinsic parts of `to_finest`,
/// m_l = U_lᵀ ⋯ U_{L−1}ᵀ m_L: the masses whose centre of mass and momentum equal those of the
/// prolonged state U x_l under the finest masses (rows of U sum to 1, so the total is kept).
/// A dynamic preview's inertia and gravity use them (PD eq. 4 with consistent inertia).
Eigen::VectorXd prolonged_masses(
    const std::vector<std::shared_ptr<const ShellProlongation>>& to_finest,
    const Eigen::VectorXd& finest_masses);

/// Throws Error(invalid_argument) unless `hierarchy`'s finest level has exactly the vertices and
/// faces of `finest` and its vertex groups 0 .. num_handles − 1 are exactly `vertex_handle` (the
/// scene's handles: coarse levels keep handle vertices only where the hierarchy was built with
/// them). Groups from num_handles on are not handles (yet): their vertices are free.
void check_hierarchy_matches(const MeshHierarchy& hierarchy, const TriangleMesh& finest,
                             const std::vector<int>& vertex_handle, std::size_t num_handles);

}  // namespace progsim
