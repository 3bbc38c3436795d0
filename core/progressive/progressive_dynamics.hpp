#pragma once
/// @file Progressive Dynamics (PD, Zhang, James and Kaufman 2024, §4 and Algorithm 1, with
/// PD++'s velocity-only prolongation and consistency penalty as VPD §3.2 describes them): a
/// coarse animation preview, then each finer level animated over the previewed span, its
/// steps predicted from the coarser level's trajectory.
#include <functional>
#include <memory>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "hierarchy/shell_prolongation.hpp"
#include "progressive/level_operators.hpp"
#include "progressive/trajectory.hpp"
#include "scene/scene.hpp"
#include "sim/level_simulation.hpp"

namespace progsim {

/// One step of one level of a progressive animation.
struct DynamicStepRecord {
  int step = 0;               ///< 1-based
  double time = 0.0;          ///< s, after the step
  int newton_iterations = 0;  ///< this step's, script rounds included
  bool converged = false;     ///< the step's Newton solve met the tolerance
  double seconds = 0.0;       ///< wall time of the step
  MotionRecord motion;        ///< kinetic energy, centre of mass, continuity (PD++)
  /// ‖(CoM_lᵗ − CoM_l⁰) − (CoM_0ᵗ − CoM_0⁰)‖ (m): how far the level's centre of mass has moved
  /// away from the preview's since the start (PD Figs. 9, 19; each level's own start is
  /// subtracted, since decimation moves the rest centre of mass by a little); 0 on the preview.
  double com_deviation = 0.0;
  /// VPD App. C eq. 19 (PD++'s consistency): ‖Π x_l − x_{l−1}‖_{M_{l−1}} (m, mass-weighted RMS)
  /// with Π = (UᵀMU)⁻¹UᵀM the mass-weighted least-squares projection through the intrinsic
  /// part U of P_l^{l−1}; 0 on the preview.
  double consistency = 0.0;
  std::optional<ContactStats> contact;  ///< with contact: this step's counters
  std::optional<double> max_stretch;    ///< with a strain limit: the largest stretch after it
  std::optional<WindRecord> wind;       ///< with wind: the wind and its force after it
  /// Per handle, what its support applies (StepRecord::reactions; empty on the preview).
  std::vector<HandleReaction> reactions;
};

/// One level of a progressive animation: its size, work and per-step records.
struct DynamicLevelRecord {
  int vertices = 0;
  Vec3 start_center_of_mass = Vec3::Zero();  ///< at frame 0 (m)
  double seconds = 0.0;                      ///< wall time of the level's steps
  int newton_iterations = 0;                 ///< over its steps
  int converged_steps = 0;                   ///< steps whose solve met the tolerance
  std::vector<TermStats> terms;              ///< counters per term over the level's steps
  std::vector<DynamicStepRecord> steps;      ///< per step, in order (frame k + 1 after step k)
};

/// Adds a step's outcome to `record` with its metrics against other trajectories (the
/// centre-of-mass deviation and the consistency; 0 where there is none), and counts its work.
/// The direct baseline records its levels so too (progsim accuracy).
void add_dynamic_step(DynamicLevelRecord& record, const StepRecord& step, double com_deviation,
                      double consistency);

/// An empty record of the level `sim` animates, from its state at frame 0.
DynamicLevelRecord start_record(const LevelSimulation& sim);

/// DynamicStepRecord::com_deviation of a step of `level` ending with centre of mass `com`
/// against step `t` (0-based) of `reference`.
double com_deviation(const Vec3& com, const DynamicLevelRecord& level,
                     const DynamicLevelRecord& reference, int t);

/// Called during refine() after each step with (steps done, steps in all); returning false
/// cancels the refinement.
using RefineProgress = std::function<bool(int done, int total)>;

/// The Progressive Dynamics driver. Level 0 is the coarsest. The preview animates level 0 step
/// by step (PD eq. 4: the proxy energy, each step solved to the scene's tolerance); refine()
/// then animates the next level over every previewed step (PD eqs. 5–6, Alg. 1 lines 7–14).
/// Every level's frames are streamed to disk (Trajectory).
class ProgressiveDynamics {
 public:
  /// Builds the scene's hierarchy as ProgressiveSimulation does, or uses `hierarchy` (built
  /// from the scene's merged bodies with its handles as vertex groups). Throws
  /// Error(invalid_scene) for a quasistatic scene and as ProgressiveSimulation's constructor.
  explicit ProgressiveDynamics(Scene scene,
                               std::shared_ptr<const MeshHierarchy> hierarchy = nullptr,
                               HierarchyProgress progress = nullptr, void* user = nullptr);
  ~ProgressiveDynamics();
  ProgressiveDynamics(const ProgressiveDynamics&) = delete;
  ProgressiveDynamics& operator=(const ProgressiveDynamics&) = delete;

  /// One preview step on level 0; its frame is appended to level 0's trajectory. Throws
  /// Error(wrong_call_order) once a finer level has been computed (restart() first).
  StepRecord step_preview();
  /// Animates level level() + 1 over every previewed step: its first frame is the level's
  /// initial state (its rest shape, the prolonged initial velocities: P recovers rest shapes,
  /// so this is P(x_l^0), crossing-free as every level of the hierarchy is), and each step's
  /// x̂ is predicted from the coarser trajectory (scene.progressive.prediction) with the
  /// optional consistency penalty. Throws Error(out_of_range) at the finest level,
  /// Error(wrong_call_order) before any preview step, Error(cancelled) if `progress` says stop;
  /// on Error nothing changed.
  void refine(const RefineProgress& progress = nullptr);
  /// Discards every level's frames and starts the preview again from the initial state (after
  /// update_scene(), to preview a variation).
  void restart();
  /// Replaces the scene (materials, loads, effects, solver, prediction, penalty) for the
  /// preview from its current time on; the meshes, handles' vertex sets, levels and time step
  /// must stay. Throws Error(wrong_call_order) once a finer level has been computed (restart()
  /// first), Error(invalid_argument / invalid_scene) on a bad scene; on Error nothing changed.
  void update_scene(Scene scene);
  /// Sets the preview's velocities (3|V_0|, m/s) before its first step. Throws
  /// Error(wrong_call_order) after it, Error(invalid_argument) on a wrong size or non-finite
  /// entry.
  void set_preview_velocities(const Vector& velocities);

  /// The finest level computed so far (0: only the preview).
  int level() const { return static_cast<int>(trajectories_.size()) - 1; }
  int finest() const { return hierarchy_->finest(); }
  const MeshHierarchy& hierarchy() const { return *hierarchy_; }
  std::shared_ptr<const MeshHierarchy> shared_hierarchy() const { return hierarchy_; }
  const Scene& scene() const { return scene_; }
  /// Frames of level `level` (steps + 1: frame 0 is the initial state). Throws
  /// Error(out_of_range) for a level that does not exist or has not been computed.
  int num_frames(int level) const;
  /// Positions and velocities (|V_level| × 3) of frame `frame` of level `level`. Throws
  /// Error(out_of_range) for a level or frame not computed.
  void read_frame(int level, int frame, Positions& positions, Positions& velocities) const;
  /// What level `level` did, step by step. Throws Error(out_of_range) as num_frames().
  const DynamicLevelRecord& record(int level) const;
  /// The preview's simulation (level 0, live).
  const LevelSimulation& preview() const { return *preview_; }

 private:
  /// Level `level` at its initial state, solved with the scene's own solver (PD solves each
  /// step to the tolerance, unlike PSQ's capped previews): the proxy energy below the finest
  /// level, the consistency penalty above the coarsest.
  std::unique_ptr<LevelSimulation> make_level(int level) const;
  /// Throws Error(out_of_range) unless level `level` has been computed.
  void check_level(int level) const;
  /// Throws Error(wrong_call_order), naming `what`, once a finer level has been computed.
  void check_preview_open(const char* what) const;

  Scene scene_;
  std::shared_ptr<const MeshHierarchy> hierarchy_;
  std::unique_ptr<const LevelOperators> operators_;
  std::unique_ptr<LevelSimulation> preview_;
  std::vector<Trajectory> trajectories_;     // per computed level
  std::vector<DynamicLevelRecord> records_;  // per computed level
  std::vector<Eigen::VectorXd> masses_;      // per computed level, for eq. 19
};

}  // namespace progsim
