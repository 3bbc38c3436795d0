#include "contact/contact_potential.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>

#include "common/error.hpp"
#include "common/parallel.hpp"
#include "common/timer.hpp"
#include "contact/barrier.hpp"
#include "contact/edge_edge_mollifier.hpp"
#include "energy/psd_projection.hpp"

namespace progsim {
namespace {

/// ACCD keeps every pair at least this fraction of its current gap apart after a step
/// (C-IPC Alg. 1, conservative rescaling s).
constexpr double kCcdRescaling = 0.1;
/// κ grows when the smallest gap falls below this fraction of d̂ (IPC §4.3).
constexpr double kSmallGapFraction = 0.01;
/// Cap on the adaptive growth of κ.
constexpr double kMaxStiffnessGrowth = 1e8;

/// found = min(found, t) for a shared running minimum (a NaN t leaves it unchanged).
void lower_to(std::atomic<double>& found, double t) {
  double current = found.load(std::memory_order_relaxed);
  while (t < current && !found.compare_exchange_weak(current, t, std::memory_order_relaxed)) {
  }
}

/// ∇ of a point's squared distance to the ground, (n·x − h)²: 2(n·x − h) n on the point (12).
Vec12 ground_distance_squared_gradient(const GroundPlane& ground, const Vec12& xs) {
  Vec12 grad = Vec12::Zero();
  grad.head<3>() = 2.0 * (ground.normal.dot(xs.head<3>()) - ground.height) * ground.normal;
  return grad;
}

}  // namespace

ContactPotential::ContactPotential(CollisionMesh mesh, double dhat, double stiffness,
                                   std::optional<GroundPlane> ground)
    : mesh_(std::move(mesh)),
      dhat_(dhat),
      stiffness_(stiffness),
      initial_stiffness_(stiffness),
      ground_(std::move(ground)) {
  if (!(dhat > 0.0) || !std::isfinite(dhat))
    fail(Status::invalid_argument, "contact: d̂ = " + std::to_string(dhat) + " must be > 0");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    fail(Status::invalid_argument,
         "contact: stiffness = " + std::to_string(stiffness) + " must be > 0");
  obstacle_positions_ = mesh_.rest.bottomRows(mesh_.num_obstacle_vertices);
}

double ContactPotential::stiffness_for_force(double force, double dhat, double offset) {
  // Force of κ b(s) on the closest points: 2 d κ |b'(s)| at s = ŝ/2, d = √(ξ² + s).
  const double s_hat = barrier_activation(offset, dhat);
  const double s = 0.5 * s_hat;
  return force /
         (2.0 * std::sqrt(offset * offset + s) * std::abs(barrier_first_derivative(s, s_hat)));
}

void ContactPotential::set_obstacle_positions(const Positions& positions) {
  if (positions.rows() != obstacle_positions_.rows())
    fail(Status::invalid_argument, "contact: obstacle positions have the wrong size");
  obstacle_positions_ = positions;
}

int ContactPotential::num_items() const {
  return static_cast<int>(candidates_.size()) + (ground_ ? mesh_.num_shell_points : 0);
}

ContactPotential::Pair ContactPotential::pair(int k) const {
  const int num_candidates = static_cast<int>(candidates_.size());
  Pair p = k < num_candidates ? candidate_pair(mesh_, candidates_, k)
                              : ground_pair(mesh_, mesh_.points[k - num_candidates]);
  if (!lowered_.empty())
    if (const auto it = lowered_.find(key_of(p)); it != lowered_.end()) p.offset = it->second;
  return p;
}

void ContactPotential::distance_squared_derivatives_of(const Pair& pair, const Vec12& xs,
                                                       const ClosestPair& closest, Vec12& grad,
                                                       Mat12& hess) const {
  if (pair.kind != Pair::Kind::ground) return distance_squared_derivatives(xs, closest, grad, hess);
  grad = ground_distance_squared_gradient(*ground_, xs);
  hess.setZero();
  hess.topLeftCorner<3, 3>() = 2.0 * ground_->normal * ground_->normal.transpose();
}

double ContactPotential::mollifier_threshold_of(const Pair& pair) const {
  return mollifier_threshold(stencil_positions(pair.vertices, mesh_.rest));
}

double ContactPotential::pair_energy(const Pair& pair, const Vec12& xs, Vec12& grad,
                                     Mat12* hess) const {
  ClosestPair closest{};
  const PairBarrier at = pair_barrier(pair, pair_distance_squared(pair, xs, ground(), &closest));
  if (!at.active) return at.b;
  const double s = at.s, s_hat = at.s_hat, b = at.b;
  const bool edge_edge = pair.kind == Pair::Kind::edge_edge;
  const double eps_x = edge_edge ? mollifier_threshold_of(pair) : 0.0;
  if (!hess) return pair_gradient(pair, xs, closest, s, s_hat, b, eps_x, grad);
  Vec12 gd;
  Mat12 hd;
  distance_squared_derivatives_of(pair, xs, closest, gd, hd);
  const double b1 = stiffness_ * barrier_first_derivative(s, s_hat);
  const double b2 = stiffness_ * barrier_second_derivative(s, s_hat);
  grad = b1 * gd;  // ∇(κb) = κ b' ∇d² (IPC eq. 7 per pair)
  *hess = b2 * gd * gd.transpose() + b1 * hd;
  if (!edge_edge) return b;
  double m;
  Vec12 gm;
  Mat12 hm;
  mollifier_derivatives(xs, eps_x, m, gm, hm);  // product rule for m·b (IPC eq. 23)
  *hess = b * hm + gm * grad.transpose() + grad * gm.transpose() + m * *hess;
  grad = b * gm + m * grad;
  return m * b;
}

double ContactPotential::pair_gradient(const Pair& pair, const Vec12& xs,
                                       const ClosestPair& closest, double s, double s_hat, double b,
                                       double eps_x, Vec12& grad) const {
  if (pair.kind == Pair::Kind::ground)
    grad = ground_distance_squared_gradient(*ground_, xs);
  else
    distance_squared_gradient(xs, closest, grad);
  grad *= stiffness_ * barrier_first_derivative(s, s_hat);  // ∇(κb) = κ b' ∇d² (IPC eq. 7)
  if (pair.kind != Pair::Kind::edge_edge) return b;
  Vec12 gm;
  const double m = mollifier_gradient(xs, eps_x, gm);
  grad = b * gm + m * grad;  // product rule for m·b (IPC eq. 23)
  return m * b;
}

void ContactPotential::gather_positions(const Vector& x, Positions& out) const {
  out.resize(mesh_.num_vertices(), 3);
  out.topRows(mesh_.num_shell_vertices) = as_positions(x);
  out.bottomRows(mesh_.num_obstacle_vertices) = obstacle_positions_;
}

ContactPotential::PairBarrier ContactPotential::pair_barrier(const Pair& pair, double d2) const {
  const double s = barrier_argument(d2, pair.offset);
  const double s_hat = barrier_activation(pair.offset, dhat_);
  if (s <= 0.0) return {s, s_hat, std::numeric_limits<double>::infinity(), false};
  if (s >= s_hat) return {s, s_hat, 0.0, false};
  return {s, s_hat, stiffness_ * barrier(s, s_hat), true};  // κ b(s, ŝ), IPC eq. 6
}

double ContactPotential::pair_value(const Pair& pair, double d2, const Positions& positions) const {
  const PairBarrier at = pair_barrier(pair, d2);
  if (!at.active || pair.kind != Pair::Kind::edge_edge) return at.b;
  return mollifier(stencil_positions(pair.vertices, positions), mollifier_threshold_of(pair)) *
         at.b;
}

double ContactPotential::value(const Vector& x) const {
  ScopedTimer timer(stats_.assembly_seconds);
  gather_positions(x, positions_);
  // Measured through the per-position cache: the gradient and Hessian at an accepted
  // line-search point then measure nothing again.
  measure_distances(positions_);
  return ordered_sum(num_items(), [&](long k) {
    return pair_value(pair(static_cast<int>(k)), distances_squared_[k], positions_);
  });
}

void ContactPotential::measure_distances(const Positions& positions) const {
  // Value, gradient and Hessian at one x measure the same pairs: measure them once.
  // The size check also catches a candidate set changed without resetting measured_.
  if (measured_ && distances_squared_.size() == static_cast<std::size_t>(num_items()) &&
      positions.rows() == measured_at_.rows() && positions == measured_at_)
    return;
  measured_at_ = positions;
  measured_ = true;
  const int n = num_items();
  distances_squared_.resize(n);
  closest_.resize(n);
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (int k = 0; k < n; ++k) {
    const Pair p = pair(k);
    distances_squared_[k] =
        pair_distance_squared(p, stencil_positions(p.vertices, positions), ground(), &closest_[k]);
  }
}

const std::vector<int>& ContactPotential::active_items(const Positions& positions) const {
  measure_distances(positions);
  const int n = static_cast<int>(distances_squared_.size());
  is_active_.resize(n);
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (int k = 0; k < n; ++k) {
    const double offset = pair(k).offset;
    is_active_[k] =
        barrier_argument(distances_squared_[k], offset) < barrier_activation(offset, dhat_);
  }
  active_.clear();
  for (int k = 0; k < n; ++k)
    if (is_active_[k]) active_.push_back(k);
  return active_;
}

/// An active item that evaluates a vertex–vertex or vertex–edge barrier, keyed by it.
struct ContactPotential::KeyedItem {
  /// distance type, the point, the other feature's sorted vertices; type −1: shares nothing
  std::array<int, 4> key;
  double offset;
  int index;  ///< into active_ (ascending in item)
  bool operator<(const KeyedItem& o) const {
    return std::tie(key, offset, index) < std::tie(o.key, o.offset, o.index);
  }
  bool same_barrier(const KeyedItem& o) const { return key == o.key && offset == o.offset; }
};

bool ContactPotential::evaluates_a_vertex_barrier(const Pair& p, const ClosestPair& c,
                                                  const Positions& positions) const {
  if (c.type != DistanceType::point_point && c.type != DistanceType::point_edge) return false;
  if (p.kind == Pair::Kind::vertex_face) return true;
  // An edge–edge pair nearest at an endpoint is that vertex–vertex or vertex–edge barrier
  // where its mollifier is 1 (IPC eq. 23: ∇m and ∇²m vanish there too).
  return p.kind == Pair::Kind::edge_edge &&
         mollifier(stencil_positions(p.vertices, positions), mollifier_threshold_of(p)) == 1.0;
}

ContactPotential::KeyedItem ContactPotential::keyed_item(int index,
                                                         const Positions& positions) const {
  const int k = active_[index];
  const Pair p = pair(k);
  const ClosestPair& c = closest_[k];
  if (!evaluates_a_vertex_barrier(p, c, positions)) return {{-1, -1, -1, -1}, p.offset, index};
  const int point = p.vertices[c.vertices[0]], other = p.vertices[c.vertices[1]];
  if (c.type == DistanceType::point_point)  // symmetric in its two vertices
    return {{0, std::min(point, other), std::max(point, other), -1}, p.offset, index};
  const int third = p.vertices[c.vertices[2]];
  return {{1, point, std::min(other, third), std::max(other, third)}, p.offset, index};
}

const std::vector<ContactPotential::ActiveGroup>& ContactPotential::active_groups(
    const Positions& positions) const {
  const int n = static_cast<int>(active_items(positions).size());
  groups_.clear();
  if (n == 0) return groups_;  // nothing in contact: no pass over the vertices
  keyed_.resize(n);            // reused buffers: no allocation once grown
  group_counts_.assign(n, 1);
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (int i = 0; i < n; ++i) keyed_[i] = keyed_item(i, positions);
  bucket_by_first_vertex();
  const int num_buckets = static_cast<int>(bucket_offsets_.size()) - 1;
  // The work is in the bucketed items' sorts; empty buckets cost a comparison each.
  const int sorted_items = static_cast<int>(bucketed_.size());
#pragma omp parallel for schedule(dynamic, 256) num_threads(loop_threads(sorted_items))
  for (int b = 0; b < num_buckets; ++b)
    count_bucket_groups(bucketed_.data() + bucket_offsets_[b],
                        bucketed_.data() + bucket_offsets_[b + 1]);
  for (int i = 0; i < n; ++i)
    if (group_counts_[i] > 0) groups_.push_back({active_[i], group_counts_[i]});
  return groups_;
}

/// bucketed_ = the keyed items that may share a barrier, by their key's first vertex (a
/// counting sort: bucket_offsets_ delimits each vertex's items).
void ContactPotential::bucket_by_first_vertex() const {
  bucket_offsets_.assign(mesh_.num_vertices() + 1, 0);
  for (const KeyedItem& item : keyed_)
    if (item.key[0] >= 0) ++bucket_offsets_[item.key[1] + 1];
  std::partial_sum(bucket_offsets_.begin(), bucket_offsets_.end(), bucket_offsets_.begin());
  bucketed_.resize(bucket_offsets_.back());
  bucket_cursor_.assign(bucket_offsets_.begin(), bucket_offsets_.end() - 1);
  for (const KeyedItem& item : keyed_)
    if (item.key[0] >= 0) bucketed_[bucket_cursor_[item.key[1]]++] = item;
}

/// Sorts one bucket and weights the first item of each same-barrier run by the run's length;
/// the others get weight 0 (they are not evaluated).
void ContactPotential::count_bucket_groups(KeyedItem* begin, KeyedItem* end) const {
  std::sort(begin, end);
  for (auto run = begin; run != end;) {
    auto next = run + 1;
    while (next != end && next->same_barrier(*run)) group_counts_[(next++)->index] = 0;
    group_counts_[run->index] = static_cast<int>(next - run);
    run = next;
  }
}

void ContactPotential::add_gradient(const Vector& x, Vector& g) const {
  ScopedTimer timer(stats_.assembly_seconds);
  gather_positions(x, positions_);
  const std::vector<ActiveGroup>& groups = active_groups(positions_);
  const int n = static_cast<int>(groups.size());
  std::vector<Vec12>& grads = gradients_;  // reused: no allocation once grown
  grads.resize(n);
#pragma omp parallel for schedule(static) num_threads(loop_threads(n))
  for (int i = 0; i < n; ++i) {
    const Pair p = pair(groups[i].item);
    pair_energy(p, stencil_positions(p.vertices, positions_), grads[i], nullptr);
    grads[i] *= groups[i].count;
  }
  for (int i = 0; i < n; ++i) {  // serial scatter: deterministic
    const Pair p = pair(groups[i].item);
    for (int k = 0; k < 4; ++k)
      if (p.vertices[k] >= 0 && !mesh_.is_obstacle(p.vertices[k]))
        g.segment<3>(3 * p.vertices[k]) += grads[i].segment<3>(3 * k);
  }
}

/// The Hessian of one pair restricted to the stencil slots that are shell DOFs and take part
/// (non-zero diagonal block): obstacle DOFs are not unknowns, so the PSD projection acts on
/// this restriction only (3 × 3 for a shell vertex against an obstacle face).
struct ContactPotential::LocalHessian {
  std::array<int, 4> vertices{};  ///< shell vertex of each kept slot
  int count = 0;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 12, 12> matrix;
};

ContactPotential::~ContactPotential() = default;

ContactPotential::LocalHessian ContactPotential::restricted_hessian(const Pair& p, const Mat12& h,
                                                                    bool project) const {
  LocalHessian local;
  std::array<int, 4> slots{};
  for (int k = 0; k < 4; ++k) {
    const int v = p.vertices[k];
    if (v < 0 || mesh_.is_obstacle(v) || h.block<3, 3>(3 * k, 3 * k).isZero(0.0)) continue;
    slots[local.count] = k;
    local.vertices[local.count++] = v;
  }
  local.matrix.resize(3 * local.count, 3 * local.count);
  for (int a = 0; a < local.count; ++a)
    for (int b = 0; b < local.count; ++b)
      local.matrix.block<3, 3>(3 * a, 3 * b) = h.block<3, 3>(3 * slots[a], 3 * slots[b]);
  if (project && local.count > 0) project_psd(local.matrix);
  return local;
}

void ContactPotential::append_hessian_triplets(const Vector& x, bool project,
                                               std::vector<Eigen::Triplet<double>>& out) const {
  ScopedTimer timer(stats_.assembly_seconds);
  gather_positions(x, positions_);
  const std::vector<ActiveGroup>& groups = active_groups(positions_);
  const int n = static_cast<int>(groups.size());
  stats_.active_pairs += static_cast<std::int64_t>(active_.size());
  std::vector<LocalHessian>& hessians = hessians_;  // reused: no allocation once grown
  hessians.resize(n);
#pragma omp parallel for schedule(static) num_threads(loop_threads(n, kMinParallelItems / 16))
  for (int i = 0; i < n; ++i) {
    const Pair p = pair(groups[i].item);
    Vec12 grad;
    Mat12 h;
    pair_energy(p, stencil_positions(p.vertices, positions_), grad, &h);
    hessians[i] = restricted_hessian(p, h, project);
    hessians[i].matrix *= groups[i].count;  // after the projection: it commutes with a count
  }
  for (const LocalHessian& local : hessians)
    for (int a = 0; a < local.count; ++a)
      for (int b = 0; b < local.count; ++b)
        for (int c = 0; c < 3; ++c)
          for (int r = 0; r < 3; ++r)
            out.emplace_back(3 * local.vertices[a] + r, 3 * local.vertices[b] + c,
                             local.matrix(3 * a + r, 3 * b + c));
}

void ContactPotential::update_candidates(const Positions& p0, const Positions& p1) {
  ScopedTimer timer(stats_.broad_phase_seconds);
  find_candidates(mesh_, p0, p1, dhat_ + 2.0 * mesh_.max_offset(), candidates_, moving());
  measured_ = false;
  ++stats_.broad_phase_runs;
  stats_.candidate_pairs += static_cast<std::int64_t>(candidates_.size());
}

double ContactPotential::min_gap(const Positions& positions, int* closest_item) const {
  measure_distances(positions);  // in parallel; the arg-min below is a cheap serial pass
  double best = std::numeric_limits<double>::infinity();
  int best_item = -1;
  for (int k = 0; k < static_cast<int>(distances_squared_.size()); ++k) {
    const double gap = std::sqrt(distances_squared_[k]) - pair(k).offset;
    if (gap < best) {
      best = gap;
      best_item = k;
    }
  }
  if (closest_item) *closest_item = best_item;
  return best;
}

double ContactPotential::ccd(const Positions& p0, const Positions& p1) {
  ScopedTimer timer(stats_.ccd_seconds);
  const int n = num_items();
  stats_.ccd_calls += n;
  int non_finite = 0;  // a NaN bound would vanish in the minimum and admit the whole step
  // α, the smallest step found so far: no pair needs to advance past it. Each pair returns
  // exactly min(its step, the bound it read), so α is the same in any order and on any thread
  // count.
  std::atomic<double> alpha{1.0};
#pragma omp parallel for reduction(+ : non_finite) schedule(dynamic, 64) \
    num_threads(loop_threads(n, kMinParallelItems / 16))
  for (int k = 0; k < n; ++k) {
    const Pair p = pair(k);
    const Vec12 xs = stencil_positions(p.vertices, p0);
    const Vec12 dx = stencil_positions(p.vertices, p1) - xs;
    const double t = pair_safe_step(p, xs, dx, p.offset, kCcdRescaling, ground(),
                                    ccd_max_iterations_, alpha.load(std::memory_order_relaxed));
    if (std::isnan(t)) ++non_finite;
    lower_to(alpha, t);
  }
  return non_finite > 0 ? std::numeric_limits<double>::quiet_NaN() : alpha.load();
}

void ContactPotential::begin_solve(const Vector& x) {
  gather_positions(x, positions_);
  update_candidates(positions_, positions_);
  last_min_gap_ = min_gap(positions_, nullptr);
  stats_.min_gap = std::min(stats_.min_gap, last_min_gap_);
}

double ContactPotential::max_step(const Vector& x, const Vector& p) {
  moved_ = x + p;
  if (!moved_.allFinite()) return std::numeric_limits<double>::quiet_NaN();  // before the boxes
  gather_positions(x, positions_);
  gather_positions(moved_, trial_positions_);
  update_candidates(positions_, trial_positions_);
  return ccd(positions_, trial_positions_);
}

double ContactPotential::max_scripted_step(const Vector& x, const Vector& p,
                                           const Positions& obstacle_target) {
  moved_ = x + p;
  if (!moved_.allFinite() || !obstacle_target.allFinite())
    return std::numeric_limits<double>::quiet_NaN();  // before the boxes
  gather_positions(x, positions_);
  gather_positions(moved_, trial_positions_);
  trial_positions_.bottomRows(mesh_.num_obstacle_vertices) = obstacle_target;
  update_candidates(positions_, trial_positions_);
  return ccd(positions_, trial_positions_);
}

Vector ContactPotential::carried_motion(const Vector& x, const Positions& obstacle_target) const {
  const int shell = mesh_.num_shell_vertices;
  Positions motion = Positions::Zero(shell, 3);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(shell);
  gather_positions(x, positions_);
  for (int item : active_items(positions_)) {
    const Pair p = pair(item);
    if (p.kind == Pair::Kind::ground) continue;
    Vec3 obstacle_motion = Vec3::Zero();
    int obstacle_vertices = 0;
    for (int v : p.vertices)
      if (v >= shell) {
        obstacle_motion +=
            (obstacle_target.row(v - shell) - obstacle_positions_.row(v - shell)).transpose();
        ++obstacle_vertices;
      }
    if (obstacle_vertices == 0 || obstacle_vertices == 4) continue;
    obstacle_motion /= obstacle_vertices;
    for (int v : p.vertices)
      if (v >= 0 && v < shell) {
        motion.row(v) += obstacle_motion.transpose();
        ++count[v];
      }
  }
  for (int v = 0; v < shell; ++v)
    if (count[v] > 0) motion.row(v) /= count[v];
  carry_through_shell_contacts(motion, count);
  return as_dofs(motion);
}

void ContactPotential::carry_through_shell_contacts(Positions& motion,
                                                    Eigen::VectorXi& carried) const {
  // A pushed layer pushes the layers it touches (a crushed can's folds stacked under the
  // plate): uncarried vertices of a shell pair with carried ones take their mean motion,
  // sweep after sweep until no pair adds any.
  const int shell = mesh_.num_shell_vertices;
  for (bool grew = true; grew;) {
    grew = false;
    for (int item : active_) {
      const Pair p = pair(item);
      // Pairs with an obstacle vertex were carried directly; the ground does not push.
      if (p.kind == Pair::Kind::ground ||
          std::any_of(p.vertices.begin(), p.vertices.end(), [&](int v) { return v >= shell; }))
        continue;
      Vec3 pushed = Vec3::Zero();
      int pushers = 0, free = 0;
      for (int v : p.vertices) {
        if (v < 0) continue;
        if (carried[v] > 0) {
          pushed += motion.row(v).transpose();
          ++pushers;
        } else {
          ++free;
        }
      }
      if (pushers == 0 || free == 0) continue;
      pushed /= pushers;
      for (int v : p.vertices)
        if (v >= 0 && carried[v] == 0) {
          motion.row(v) = pushed.transpose();
          carried[v] = 1;
        }
      grew = true;
    }
  }
}

bool ContactPotential::end_iteration(const Vector& x) {
  gather_positions(x, positions_);
  const double gap = min_gap(positions_, nullptr);
  stats_.min_gap = std::min(stats_.min_gap, gap);
  const bool grow = gap < kSmallGapFraction * dhat_ && gap < last_min_gap_ &&
                    stiffness_ < kMaxStiffnessGrowth * initial_stiffness_;
  last_min_gap_ = gap;
  if (!grow) return false;
  stiffness_ *= 2.0;  // IPC §4.3: stiffen while a gap keeps closing
  ++stats_.stiffness_updates;
  return true;
}

std::string ContactPotential::describe(int item) const {
  const Pair p = pair(item);
  auto vertex = [&](int k) { return describe_vertex(mesh_, p.vertices[k]); };
  if (p.kind == Pair::Kind::ground) return vertex(0) + " and the ground";
  if (p.kind == Pair::Kind::edge_edge)
    return "edge (" + vertex(0) + ", " + vertex(1) + ") and edge (" + vertex(2) + ", " + vertex(3) +
           ")";
  return vertex(0) + " and " + describe_face(mesh_, candidates_.vertex_face[item][1]);
}

void ContactPotential::check_separated(const Vector& x) {
  gather_positions(x, positions_);
  update_candidates(positions_, positions_);
  int item = -1;
  const double gap = min_gap(positions_, &item);
  if (gap > 0.0) return;
  std::ostringstream message;
  message << "the configuration intersects or touches: " << describe(item) << " are "
          << gap + pair(item).offset << " m apart, not more than their contact offset "
          << pair(item).offset << " m";
  fail(Status::intersecting, message.str());
}

std::size_t ContactPotential::PairKeyHash::operator()(const PairKey& key) const {
  std::size_t h = 0;
  for (int v : key) h = h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(v + 1);
  return h;
}

ContactPotential::PairKey ContactPotential::key_of(const Pair& pair) {
  return {static_cast<int>(pair.kind), pair.vertices[0], pair.vertices[1], pair.vertices[2],
          pair.vertices[3]};
}

void ContactPotential::set_moving_vertices(std::vector<char> moving) {
  if (!moving.empty() && static_cast<int>(moving.size()) != mesh_.num_vertices())
    fail(Status::invalid_argument, "contact: " + std::to_string(moving.size()) +
                                       " moving flags for " + std::to_string(mesh_.num_vertices()) +
                                       " vertices");
  moving_ = std::move(moving);
}

void ContactPotential::set_ccd_max_iterations(int max_iterations) {
  if (max_iterations <= 0)
    fail(Status::invalid_argument,
         "contact: CCD iteration cap " + std::to_string(max_iterations) + " is not positive");
  ccd_max_iterations_ = max_iterations;
}

int ContactPotential::fit_offsets(const Vector& x) {
  const auto previous = std::move(lowered_);
  lowered_.clear();  // pair() gives the full offsets below
  gather_positions(x, positions_);
  find_candidates(mesh_, positions_, positions_, 2.0 * mesh_.max_offset(), candidates_, moving());
  measured_ = false;  // new candidates
  for (int k = 0; k < num_items(); ++k) {
    const Pair p = pair(k);
    const double d =
        std::sqrt(pair_distance_squared(p, stencil_positions(p.vertices, positions_), ground()));
    const auto before = previous.find(key_of(p));
    const double now = before != previous.end() ? before->second : p.offset;
    const double allowed = now < d ? now + 0.5 * (d - now) : 0.8 * d;
    if (p.offset > allowed) lowered_.emplace(key_of(p), allowed);
  }
  return reduced_offsets();
}

std::vector<ContactPoint> ContactPotential::contact_points(const Vector& x) const {
  gather_positions(x, positions_);
  std::vector<ContactPoint> points;
  for (int k : active_items(positions_)) {
    const Pair p = pair(k);
    const Vec12 xs = stencil_positions(p.vertices, positions_);
    const int other = p.kind == Pair::Kind::edge_edge ? 2 : 1;
    const double mu_other =
        p.kind == Pair::Kind::ground ? ground_->friction : mesh_.vertex_friction[p.vertices[other]];
    const double mu = std::sqrt(mesh_.vertex_friction[p.vertices[0]] * mu_other);  // Box2D mix
    if (!(mu > 0.0)) continue;
    ContactPoint c{p.vertices, Eigen::Vector4d(1, 0, 0, 0), ground_ ? ground_->normal : Vec3(), 0.0,
                   mu};
    ClosestPair closest{};
    const double d2 = pair_distance_squared(p, xs, ground(), &closest);
    if (p.kind != Pair::Kind::ground) {
      c.weights = closest_point_weights(xs, closest);
      Vec3 r = Vec3::Zero();
      for (int j = 0; j < 4; ++j) r += c.weights[j] * xs.segment<3>(3 * j);
      c.normal = r.normalized();
    }
    const double s = barrier_argument(d2, p.offset);
    const double s_hat = barrier_activation(p.offset, dhat_);
    const double m =
        p.kind == Pair::Kind::edge_edge ? mollifier(xs, mollifier_threshold_of(p)) : 1.0;
    // λ = ‖∂(κ m b)/∂r‖ = 2 κ m |b'(s)| d (IPC §5, lagged normal force)
    c.normal_force =
        2.0 * stiffness_ * m * std::abs(barrier_first_derivative(s, s_hat)) * std::sqrt(d2);
    points.push_back(c);
  }
  return points;
}

}  // namespace progsim
