#pragma once
/// @file The IPC contact barrier over every primitive pair closer than d̂, with CCD bounding
/// every step so that no accepted configuration ever intersects (IPC, Li et al. 2020, §4;
/// codimensional offsets and additive CCD of C-IPC, Li et al. 2021, §4).
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/collision_mesh.hpp"
#include "contact/contact_pair.hpp"
#include "contact/contact_stats.hpp"
#include "contact/primitive_distance.hpp"
#include "energy/changing_pattern_term.hpp"
#include "solve/step_filter.hpp"

namespace progsim {

/// One active contact, as friction needs it (IPC §5): the 4 stencil vertices (−1 unused), the
/// weights w with r = Σ w_k x_k the vector between the closest points, the unit normal r/‖r‖,
/// the normal force magnitude λ (N) and the pair's μ.
struct ContactPoint {
  std::array<int, 4> vertices;
  Eigen::Vector4d weights;
  Vec3 normal;
  double normal_force;
  double friction;
};

/// B(x) = κ Σ_k m_k b(d_k² − ξ_k², ŝ_k) over vertex–face, edge–edge and vertex–ground pairs
/// with gap d_k − ξ_k < d̂ (IPC eq. 7; m_k the edge–edge mollifier, eq. 23; ξ_k the sum of
/// the two sides' offsets, C-IPC §4). value() is +∞ if a pair is at or inside its offset.
/// As a StepFilter it bounds every Newton step with additive CCD (C-IPC Alg. 1) and keeps the
/// candidate set of the segment it cleared; its Hessian pattern changes with the pairs.
class ContactPotential : public ChangingPatternTerm, public StepFilter {
 public:
  /// @param mesh shell (DOFs) + obstacles
  /// @param dhat activation gap d̂ (m), > 0
  /// @param stiffness κ (N/m³), > 0
  /// @param ground nullable: the analytic ground
  ContactPotential(CollisionMesh mesh, double dhat, double stiffness,
                   std::optional<GroundPlane> ground);
  ~ContactPotential() override;

  const char* name() const override { return "contact"; }
  double value(const Vector& x) const override;
  void add_gradient(const Vector& x, Vector& g) const override;
  void append_hessian_triplets(const Vector& x, bool project_psd,
                               std::vector<Eigen::Triplet<double>>& out) const override;

  void begin_solve(const Vector& x) override;
  double max_step(const Vector& x, const Vector& p) override;
  /// Grows κ ×2 (IPC §4.3 adaptive stiffness) when the smallest gap is below 1% of d̂ and
  /// still shrinking; returns true then.
  bool end_iteration(const Vector& x) override;

  /// The largest α ∈ [0, 1] for which shell DOFs moving by α·p and obstacles moving linearly
  /// from their current positions toward `obstacle_target` (|V_obstacle| × 3) stay apart
  /// (used to advance scripted handles and obstacles).
  double max_scripted_step(const Vector& x, const Vector& p, const Positions& obstacle_target);
  /// How the shell is carried along by obstacles moving toward `obstacle_target`: each shell
  /// vertex of an active pair with an obstacle moves as that pair's obstacle vertices do on
  /// average (3|V_shell| DOFs, zero elsewhere). Scripted rounds add it where an obstacle is
  /// blocked, so that a stiff shell is pushed instead of closing the gap tenfold per round.
  /// Uses the candidates of the last max_scripted_step() or max_step().
  Vector carried_motion(const Vector& x, const Positions& obstacle_target) const;
  /// Moves the obstacles (|V_obstacle| × 3).
  void set_obstacle_positions(const Positions& positions);
  /// Leaves out the pairs whose vertices are all still (`moving`: one flag per collision
  /// vertex, non-zero for moving; empty: none left out). Their distances do not change, so
  /// leaving them out changes the energy by a constant only. Valid only while the unflagged
  /// vertices, obstacles included, stay where they are (a local relaxation with the rest
  /// fixed): CCD, check_separated(), carried_motion() and the minimum gap then see only the
  /// pairs with a flagged vertex. Throws Error(invalid_argument) if `moving` is neither empty
  /// nor one flag per vertex.
  void set_moving_vertices(std::vector<char> moving);
  /// Caps the iterations of each pair's additive CCD in max_step() and max_scripted_step()
  /// (default kAccdMaxIterations): a pair sliding along at a gap far smaller than its motion
  /// then bounds the step to about 0.9 · cap gaps of its motion instead of costing ~motion/gap
  /// iterations. Throws Error(invalid_argument) unless positive.
  void set_ccd_max_iterations(int max_iterations);
  const Positions& obstacle_positions() const { return obstacle_positions_; }

  /// Throws Error(intersecting) naming the closest pair if any pair of x is at or inside its
  /// contact offset (a scene that starts intersecting or touching).
  void check_separated(const Vector& x);
  /// Offset homotopy for a start inside some contact offsets (a refined level whose split
  /// patches are not yet open, PSQ §4.4.3): each pair nearer than its offset ξ gets a lowered
  /// offset of its own, 80% of its distance on the first call, then (after a solve has pushed
  /// it open) halfway from its current offset to its distance; every other pair keeps its ξ.
  /// Call after each solve until it returns 0; returns how many pairs still have a lowered one.
  int fit_offsets(const Vector& x);
  /// Pairs whose offset fit_offsets() lowered (0: the full offsets hold).
  int reduced_offsets() const { return static_cast<int>(lowered_.size()); }
  /// The active contacts at x (for lagged friction).
  std::vector<ContactPoint> contact_points(const Vector& x) const;

  double dhat() const { return dhat_; }
  /// The ground, or nullptr.
  const GroundPlane* ground() const { return ground_ ? &*ground_ : nullptr; }
  double stiffness() const { return stiffness_; }
  void set_stiffness(double kappa) { stiffness_ = kappa; }
  const CollisionMesh& mesh() const { return mesh_; }
  const ContactStats& stats() const { return stats_; }
  /// Starts a new min_gap record (e.g. per step).
  void reset_min_gap() { stats_.min_gap = std::numeric_limits<double>::infinity(); }

  /// The κ at which a pair at half the activation gap (offset ξ) pushes with `force` (N).
  static double stiffness_for_force(double force, double dhat, double offset);

 private:
  using Pair = ContactPair;
  /// Items are the vertex–face candidates, then the edge–edge ones, then (with a ground)
  /// every shell vertex against the ground.
  int num_items() const;
  Pair pair(int item) const;
  void distance_squared_derivatives_of(const Pair& pair, const Vec12& xs,
                                       const ClosestPair& closest, Vec12& grad, Mat12& hess) const;
  double mollifier_threshold_of(const Pair& pair) const;
  /// κ m b of one pair at stencil positions xs, with its gradient, and its Hessian when
  /// non-null.
  double pair_energy(const Pair& pair, const Vec12& xs, Vec12& grad, Mat12* hess) const;
  /// A pair's barrier at squared distance d2: s = d² − ξ², its activation ŝ, and b = κ b(s, ŝ)
  /// when active (0 < s < ŝ); otherwise b is the energy (+∞ at contact, 0 beyond d̂).
  struct PairBarrier {
    double s, s_hat, b;
    bool active;
  };
  PairBarrier pair_barrier(const Pair& pair, double d2) const;
  /// κ m b of one pair whose squared distance d2 is known (IPC eqs. 6, 23): +∞ at contact, 0
  /// beyond d̂; the edge–edge mollifier from the pair's `positions`.
  double pair_value(const Pair& pair, double d2, const Positions& positions) const;
  /// pair_energy()'s gradient alone, from the pair's closest features, barrier argument s and
  /// activation ŝ, barrier value b = κ b(s, ŝ) and mollifier threshold ε_x (0 unless edge–edge).
  double pair_gradient(const Pair& pair, const Vec12& xs, const ClosestPair& closest, double s,
                       double s_hat, double b, double eps_x, Vec12& grad) const;
  /// Spreads carried_motion() through the active shell–shell pairs (of active_): a vertex
  /// touching carried ones is carried too. `carried` > 0 marks the carried vertices.
  void carry_through_shell_contacts(Positions& motion, Eigen::VectorXi& carried) const;
  /// Squared distance of every item at `positions` into distances_squared_ (parallel), and
  /// its closest features into closest_; nothing when the candidates are those of the last
  /// measurement and `positions` equal its positions.
  void measure_distances(const Positions& positions) const;
  /// The items within the activation gap (a reference to a reused buffer).
  const std::vector<int>& active_items(const Positions& positions) const;
  /// An active item standing for `count` items with the same barrier.
  struct ActiveGroup {
    int item;
    int count;
  };
  /// Whether pair p, whose closest features are c, evaluates the barrier of one vertex–vertex
  /// or vertex–edge pair (and may share it with other items).
  bool evaluates_a_vertex_barrier(const Pair& p, const ClosestPair& c,
                                  const Positions& positions) const;
  /// The active items, those with the same barrier grouped: pairs whose closest features are
  /// one vertex–vertex or vertex–edge pair at the same offset (a vertex nearest a mesh vertex
  /// or edge is a candidate of every face around it, and of the edge–edge pairs of its
  /// edges). Each group is evaluated once and weighted by its count, as IPC Toolkit weights
  /// duplicate collisions; the energy is the same. Ordered by item (a reused buffer).
  const std::vector<ActiveGroup>& active_groups(const Positions& positions) const;
  struct KeyedItem;
  /// active_[index] keyed by the barrier it evaluates (at measure_distances()' closest pair).
  KeyedItem keyed_item(int index, const Positions& positions) const;
  void bucket_by_first_vertex() const;
  void count_bucket_groups(KeyedItem* begin, KeyedItem* end) const;
  struct LocalHessian;
  LocalHessian restricted_hessian(const Pair& p, const Mat12& h, bool project) const;
  /// Positions of every collision vertex: shell from x, obstacles from obstacle_positions_.
  void gather_positions(const Vector& x, Positions& out) const;
  void update_candidates(const Positions& p0, const Positions& p1);
  /// The moving-vertex flags for find_candidates(), or nullptr for every pair.
  const std::vector<char>* moving() const { return moving_.empty() ? nullptr : &moving_; }
  double ccd(const Positions& p0, const Positions& p1);
  double min_gap(const Positions& positions, int* closest_item) const;
  std::string describe(int item) const;

  CollisionMesh mesh_;
  /// A pair's identity: its kind and stencil.
  using PairKey = std::array<int, 5>;
  struct PairKeyHash {
    std::size_t operator()(const PairKey& key) const;
  };
  static PairKey key_of(const Pair& pair);
  std::unordered_map<PairKey, double, PairKeyHash> lowered_;  // pair → offset, fit_offsets()
  double dhat_;
  double stiffness_;
  double initial_stiffness_;
  std::optional<GroundPlane> ground_;
  Positions obstacle_positions_;
  CandidateSet candidates_;
  std::vector<char> moving_;                     ///< set_moving_vertices(); empty: every pair
  int ccd_max_iterations_ = kAccdMaxIterations;  ///< set_ccd_max_iterations()
  double last_min_gap_ = std::numeric_limits<double>::infinity();
  mutable ContactStats stats_;
  mutable Positions positions_, trial_positions_;
  // Per-evaluation work buffers, reused so that Newton iterations do not reallocate them.
  mutable std::vector<double> distances_squared_;
  mutable std::vector<int> active_;
  mutable std::vector<ClosestPair> closest_;  ///< per item, by measure_distances()
  mutable Positions measured_at_;             ///< the positions of the last measure_distances()
  mutable bool measured_ = false;        ///< distances_squared_ and closest_ hold at measured_at_
  mutable std::vector<char> is_active_;  ///< per item, by active_items()
  mutable std::vector<ActiveGroup> groups_;
  // active_groups()' buffers: keyed active items, those that may share a barrier bucketed by
  // first vertex, and each active item's weight (0: counted by another).
  mutable std::vector<KeyedItem> keyed_, bucketed_;
  mutable std::vector<int> bucket_offsets_, bucket_cursor_, group_counts_;
  mutable std::vector<Vec12> gradients_;
  mutable std::vector<LocalHessian> hessians_;
  Vector moved_;
};

}  // namespace progsim
