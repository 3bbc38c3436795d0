#pragma once
/// @file Progressive Shell Quasistatics (PSQ, Zhang et al. 2023, §3 and Algorithm 1): a coarse
/// preview of a scene's equilibria on level l with the proxy energy, then refinement level by
/// level to the finest mesh, solved there to convergence with the full energy.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "progressive/level_operators.hpp"
#include "progressive/progressive_obstacles.hpp"
#include "progressive/safe_refinement.hpp"
#include "progressive/state_distance.hpp"
#include "progressive/strain_correction.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// What happened on one level: its work, and its state when it was left.
struct LevelRecord {
  int steps = 0;                ///< preview (or finest) steps taken on the level
  int settles = 0;              ///< solves at a fixed time (after refinement, to equilibrium)
  int newton_iterations = 0;    ///< over steps and settles
  int cg_iterations = 0;        ///< refining projected steps (NewtonSettings::max_cg_iterations)
  int extrapolated_steps = 0;   ///< whole steps the line search lengthened (extrapolate)
  int converged_solves = 0;     ///< steps and settles whose Newton solve met the tolerance
  double solve_seconds = 0.0;   ///< wall time of the level's steps and settles
  double refine_seconds = 0.0;  ///< wall time to build the level's start from the coarser one
  /// How the level's start was built from the coarser one (PSQ §4.4; zeros without contact).
  SafeRefinementStats refinement;
  /// How the refined start was brought under its strain limits (PSQ §4.4.5; zeros without).
  StrainCorrectionStats strain_correction;
  double energy = 0.0;          ///< E at the level's current or last state (J)
  double gradient_norm = 0.0;   ///< ‖∇E‖ over free DOFs there
  double simulated_time = 0.0;  ///< scene time of the last solve (s)
  /// Contact pairs whose offset is still lowered after the last solve: where contact kept a
  /// split patch from opening fully (StepRecord::reduced_offsets); 0 normally.
  int reduced_offsets = 0;
  /// Faces whose strain limit is still raised after the last solve (StepRecord::raised_limits).
  int raised_limits = 0;
  /// How the progressive obstacles were refined into this level (PSQ §4.6; zeros without).
  SafeRefinementStats obstacle_refinement;
  int obstacle_vertices = 0;  ///< obstacle vertices the level's contact meets
  /// The last solve needed no Newton step (PSQ Algorithm 1 line 21) and every script reached
  /// its place (after refinement, progressive obstacles may take several solves).
  bool equilibrium = false;
  Positions positions;  ///< the state when the level was left (empty while current)
  /// Per handle, what its support applied after the last solve (StepRecord::reactions; empty
  /// before any solve and on preview levels).
  std::vector<HandleReaction> reactions;
};

/// The PSQ driver. Level 0 is the coarsest; finest() is the scene's mesh. Quasistatic scenes
/// only; a dynamic scene on several levels is refused (Error(unsupported)): ProgressiveDynamics
/// animates it. On a single level either mode runs as a direct simulation.
class ProgressiveSimulation {
 public:
  /// Builds the scene's hierarchy from `scene.progressive` (its handles kept as vertex groups),
  /// or uses `hierarchy`, which must have been built from the scene's merged bodies with its
  /// handles as vertex groups. Starts at level 0 at rest. Throws Error(invalid_scene /
  /// invalid_argument / unsupported) on bad input, Error(intersecting) before building
  /// anything if contact is on and the finest rest shape crosses itself or an obstacle or
  /// touches within an offset (unless scene.contact.crossing_start), and also if a level's
  /// start does, Error(cancelled) if `progress` says stop.
  explicit ProgressiveSimulation(Scene scene,
                                 std::shared_ptr<const MeshHierarchy> hierarchy = nullptr,
                                 HierarchyProgress progress = nullptr, void* user = nullptr);
  ~ProgressiveSimulation();
  ProgressiveSimulation(const ProgressiveSimulation&) = delete;
  ProgressiveSimulation& operator=(const ProgressiveSimulation&) = delete;

  /// One step of the load script: a preview step with at most `preview_iterations` Newton
  /// iterations below the finest level (PSQ §4.5), a full step at the finest level.
  StepRecord step();
  /// Solves again at the current time (no load change): after a refinement or an edit.
  /// Below the finest level with the preview's iteration cap, at the finest to convergence.
  StepRecord settle();
  /// Settles until the current level is at equilibrium (PSQ Algorithm 1: a solve that needs no
  /// Newton step, StepRecord::equilibrium) or `max_solves` solves were made; returns whether
  /// equilibrium was reached. `after_solve` (nullable) is told how many solves are done after
  /// each, and may throw (a caller's cancel). Throws Error(invalid_argument) for max_solves < 1,
  /// Error(numerical_failure) if a solve left non-finite positions.
  bool settle_to_equilibrium(int max_solves, const std::function<void(int)>& after_solve = {});
  /// Refines the current level l into l+1 toward the hierarchy's P^l_{l+1}(x_l) (PSQ eq. 7) and
  /// continues there at the same scene time. Without contact the level starts at P^l_{l+1}(x_l).
  /// Progressive obstacles (PSQ §4.6) are then refined the same way against the refined shell,
  /// and the level's script rounds carry them on to their scripted places.
  /// With contact it starts where safe_refinement() (PSQ §4.4) takes it: split by split toward
  /// P^l_{l+1}(x_l), never crossing or entering a contact offset, even when the prolonged state
  /// itself intersects. With strain limits, the new vertices then move (the coarser level's
  /// held; all but the handles where that cannot reach the limits) until every face is under
  /// its limit (PSQ §4.4.5, correct_strain()). A face still left beyond (its vertices all
  /// handles, or contact in the way) gets a raised limit that the level's solves bring back
  /// down (StrainLimit::fit_limits).
  /// Throws Error(out_of_range) at the finest level, Error(intersecting) if no safe start is
  /// found. On Error nothing changed.
  void refine();

  int level() const { return level_; }
  int finest() const { return hierarchy_->finest(); }
  const MeshHierarchy& hierarchy() const { return *hierarchy_; }
  std::shared_ptr<const MeshHierarchy> shared_hierarchy() const { return hierarchy_; }
  /// The simulation of the current level.
  const LevelSimulation& current() const { return *sim_; }
  const std::vector<LevelRecord>& records() const { return records_; }
  const Scene& scene() const { return scene_; }
  /// Crossing face pairs of the finest rest shape among the obstacles at t = 0 (CGAL exact):
  /// nonzero only for a scene that opted into a crossing start (contact.crossing_start).
  int input_crossing_pairs() const { return input_crossing_pairs_; }
  /// Positions of level `level` (|V_level| × 3): the live state of the current level, the
  /// state a coarser level was left in, or the current state prolonged to a finer level (with
  /// P^l to the finest level, PSQ eq. 9, and P^k_{k+1} in turn to intermediate ones).
  /// Throws Error(out_of_range) for a level that does not exist.
  Positions positions(int level) const;
  /// Once the finest level is at equilibrium (the converged result): level `level`'s state,
  /// prolonged to the finest mesh, against it (over the finest rest bounding-box diagonal);
  /// zero for the finest level itself. Before that, or with a single level: nullopt.
  std::optional<StateDistance> error_against_finest(int level) const;
  /// Replaces the scene between steps (materials, loads, handle motions, effects, solver
  /// settings), keeping the level, state and time. The meshes and the handles' vertex sets
  /// must stay (they define the hierarchy). A switch to dynamic stepping is refused on several
  /// levels (Error(unsupported): Progressive Dynamics animates them from the initial state), as
  /// the constructor refuses a dynamic scene there; on a single level it is a direct
  /// simulation's switch. On Error nothing changed.
  void update_scene(Scene scene);
  /// The operators that take level `level` (< finest) to the finest mesh, applied in turn: the
  /// proxy energy's prolongation (scene.progressive.prolongation). Built once.
  std::vector<std::shared_ptr<const ShellProlongation>> to_finest(int level) const;
  /// A state of level `level` prolonged to the finest mesh with to_finest(level).
  Positions prolong_to_finest(int level, const Positions& x) const;

 private:
  /// The scene a level is solved with: the preview iteration cap below the finest level.
  Scene level_scene(int level) const;
  /// A new simulation of `level` from `start`.
  std::unique_ptr<LevelSimulation> make_level(int level, LevelStart start) const;
  /// P_{level+1}^level (PSQ eq. 7), built once.
  const ShellProlongation& next_operator(int level) const { return *operators_->next(level); }
  /// The shell model of `level` (the scene's merged bodies at the finest level).
  ShellModel level_model(int level) const;
  /// PSQ §4.4.5: moves the new vertices of level_ + 1's refined start `start` (`model` is that
  /// level's shell; the vertices of level_ and the handles held) until its faces are under their
  /// strain limits, against the obstacles at `obstacles`.
  StrainCorrectionStats correct_refined_strain(const ShellModel& model, Vector& start,
                                               const Positions& obstacles) const;
  /// Obstacle vertices the current level's contact meets (without copying their positions).
  int obstacle_vertex_count() const;
  /// Adds a solve's outcome to the current level's record.
  void record(const StepRecord& step, bool new_step);

  /// Refines the current level's obstacles to level_ + 1 against the refined shell `start`
  /// (progressive collision objects, PSQ §4.6); the obstacles as they are without any.
  Positions refined_obstacles(const Vector& start, const RefinementSurroundings& around,
                              SafeRefinementStats* stats) const;

  Scene scene_;
  std::shared_ptr<const MeshHierarchy> hierarchy_;
  std::unique_ptr<const ObstacleHierarchy> obstacle_levels_;  // null: no progressive obstacle
  std::unique_ptr<const LevelOperators> operators_;
  std::unique_ptr<LevelSimulation> sim_;
  std::vector<LevelRecord> records_;
  int level_ = 0;
  int input_crossing_pairs_ = 0;
};

/// Validates a scene for a progressive run and, with contact on, its finest shell at rest: a
/// shell that crosses itself or an obstacle (CGAL's exact predicates) or touches within a
/// contact offset is refused as on the direct path (Error(intersecting) naming a pair of the
/// input's faces), unless the scene opts into a crossing start (contact.crossing_start).
void check_progressive_scene(const Scene& scene);

/// Whether two settings ask for the same levels (and so the same hierarchy): a scene update
/// must keep them.
bool same_levels(const ProgressiveSettings& a, const ProgressiveSettings& b);

/// The scene's hierarchy as its `progressive` settings ask: the merged bodies decimated to the
/// requested coarse level sizes with the handles as vertex groups and, with contact on, their
/// contact offsets kept between the faces of every level (a single level when the settings ask
/// for none). Checks the scene first (check_progressive_scene).
MeshHierarchy build_scene_hierarchy(const Scene& scene, HierarchyProgress progress = nullptr,
                                    void* user = nullptr);

}  // namespace progsim
