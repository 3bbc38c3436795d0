#pragma once
/// @file What the C ABI's opaque handles hold.
#include <algorithm>
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "api_guard.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "hierarchy/tet_hierarchy.hpp"
#include "mesh/triangle_mesh.hpp"
#include "progressive/progressive_animation.hpp"
#include "progressive/progressive_simulation.hpp"
#include "progsim.h"
#include "scene/scene.hpp"

/// A hierarchy (level 0 the coarsest, the last one the user's mesh), exactly one of: a shell's
/// mesh hierarchy with the direct shell prolongation of every coarse level to the finest, or a
/// solid's tet hierarchy with each level's boundary surface. Immutable once created.
struct ps_hierarchy {
  explicit ps_hierarchy(progsim::MeshHierarchy built);
  explicit ps_hierarchy(std::shared_ptr<const progsim::MeshHierarchy> built);
  explicit ps_hierarchy(std::shared_ptr<const progsim::TetHierarchy> built);
  std::shared_ptr<const progsim::MeshHierarchy> shared;  ///< a shell's, shared with its sims
  std::shared_ptr<const progsim::TetHierarchy> solid;    ///< a solid's, shared with its sims
  std::vector<progsim::ShellProlongation> to_finest;     ///< shells: P^l, l < finest (PSQ eq. 9)
  std::vector<progsim::TriangleMesh> boundaries;         ///< solids: each level's boundary
  mutable std::atomic<int> simulations{0};               ///< live simulations created on it
  mutable std::string last_error;

  int num_levels() const;
  /// The shell hierarchy; throws ApiError(PS_ERROR_UNSUPPORTED) for a solid's.
  const progsim::MeshHierarchy& shells() const;
};

/// A simulation: exactly one driver is set. `simulation` is PSQ on several quasistatic levels
/// (a direct simulation on a single-level hierarchy); `animation` animates several dynamic
/// levels (Progressive Dynamics for a shell, VPD for a solid).
struct ps_sim {
  const ps_hierarchy* hierarchy = nullptr;
  std::unique_ptr<ps_hierarchy> owned_hierarchy;  ///< set when created from a scene
  std::unique_ptr<progsim::ProgressiveSimulation> simulation;
  std::unique_ptr<progsim::ProgressiveAnimation> animation;
  progsim::Scene scene;  ///< the scene as last set (parameters are edited here, then applied)
  bool busy = false;     ///< inside a long call (its progress callback may not call back)
  ps_progress_fn progress = nullptr;
  void* progress_user_data = nullptr;
  bool counts_as_user = false;  ///< counted in hierarchy->simulations
  mutable std::string last_error;

  ps_sim() = default;
  ps_sim(const ps_sim&) = delete;
  ps_sim& operator=(const ps_sim&) = delete;
  ~ps_sim() {
    if (counts_as_user) --hierarchy->simulations;
  }
};

namespace progsim::capi {

/// Checks sim is non-NULL and not inside one of its own long calls (a progress callback
/// calling back into the simulation that is running: PS_ERROR_WRONG_CALL_ORDER).
inline void require_idle(const ps_sim* sim) {
  require(sim, "sim");
  if (sim->busy)
    api_fail(PS_ERROR_WRONG_CALL_ORDER,
             "called from the progress callback of a running call on this simulation");
}

/// The sim's ps_sim_kind.
ps_sim_kind sim_kind(const ps_sim& sim);

/// The PSQ (or direct) driver; throws ApiError(PS_ERROR_INVALID_ARGUMENT) for a progressive
/// animation, whose levels are animated by ProgressiveDynamics instead.
ProgressiveSimulation& quasistatic_driver(const ps_sim& sim);

/// The progressive animation driver (PD or VPD); throws ApiError(PS_ERROR_INVALID_ARGUMENT)
/// naming the sim's kind for any other simulation.
ProgressiveAnimation& animation_driver(const ps_sim& sim);

/// Applies an edited copy of the scene; on failure the simulation keeps its old scene.
template <typename Edit>
void edit_scene(ps_sim& sim, Edit&& edit) {
  Scene scene = sim.scene;
  edit(scene);
  if (sim.animation)
    sim.animation->update_scene(scene);
  else
    sim.simulation->update_scene(scene);
  sim.scene = std::move(scene);
}

/// Replaces the simulation's driver by one built on its hierarchy for `scene`, which changes
/// what a driver fixes when it is built (handles: the hierarchy's vertex groups; obstacles: the
/// progressive obstacle levels). Throws ApiError(PS_ERROR_WRONG_CALL_ORDER) naming `what` once
/// the simulation has stepped; on any error nothing changed.
void rebuild_scene(ps_sim& sim, Scene scene, const char* what);

/// Applies a scene that differs in settings the driver fixes when it is built (the choice
/// table's options): before the first step by building a new driver (keeping a progressive
/// animation's initial velocities), later through the driver's update_scene like a parameter.
void apply_scene(ps_sim& sim, Scene scene);

/// A mesh from the C ABI's borrowed arrays (num_vertices × 3 doubles, num_faces × 3 indices);
/// throws ApiError(PS_ERROR_NULL_ARGUMENT / PS_ERROR_INVALID_MESH) for NULL arrays or sizes
/// outside [1, INT32_MAX / 3]. The mesh itself is validated by its user.
TriangleMesh borrowed_mesh(const double* vertices, std::size_t num_vertices, const int32_t* faces,
                           std::size_t num_faces);

/// The box [lo, hi]; throws ApiError(PS_ERROR_INVALID_ARGUMENT) for a non-finite corner or
/// lo above hi on some axis.
VertexBox checked_box(const double lo[3], const double hi[3]);

/// Marks sim busy for the lifetime of this guard.
class BusyGuard {
 public:
  explicit BusyGuard(ps_sim& sim) : sim_(sim) { sim_.busy = true; }
  ~BusyGuard() { sim_.busy = false; }
  BusyGuard(const BusyGuard&) = delete;
  BusyGuard& operator=(const BusyGuard&) = delete;

 private:
  ps_sim& sim_;
};

/// Where a call on sim stores its error message: the handle, or the thread for NULL.
inline std::string* error_slot(const ps_sim* sim) {
  return sim ? &sim->last_error : nullptr;
}

/// The level's surface (a solid's boundary); throws ApiError(PS_ERROR_OUT_OF_RANGE) naming the
/// valid range.
const TriangleMesh& level_mesh(const ps_hierarchy& hierarchy, int32_t level);

/// The size-then-fill protocol of the header: *count = n; copies n values into out unless
/// out is NULL (size query); out != NULL with capacity < n → PS_ERROR_BUFFER_TOO_SMALL.
template <typename T>
void copy_out(const T* values, std::size_t n, T* out, std::size_t capacity, std::size_t* count) {
  require(count, "count");
  if (out && capacity < n)
    api_fail(PS_ERROR_BUFFER_TOO_SMALL, "the buffer holds " + std::to_string(capacity) +
                                            " values but " + std::to_string(n) + " are needed");
  if (out) std::copy(values, values + n, out);
  *count = n;
}

}  // namespace progsim::capi
