#include "progressive/safe_refinement.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/parallel.hpp"
#include "contact/contact_potential.hpp"
#include "hierarchy/expansion_coloring.hpp"
#include "mesh/intersection_check.hpp"
#include "progressive/patch_relaxation.hpp"
#include "sim/contact_setup.hpp"

namespace progsim {
namespace {

/// A pair's CCD bound, 0 (no step) when it is NaN: a non-finite motion (pair_safe_step()).
double no_step_if_nan(double bound) {
  return bound >= 0.0 ? bound : 0.0;
}

/// Directions per stratified round: a Fibonacci lattice covering the sphere evenly.
constexpr int kDirectionsPerRound = 64;
/// A perturbed vertex keeps its patch's other primitives at least this fraction of the
/// perturbation away.
constexpr double kMinClearance = 0.05;
/// Perturbation sizes tried per split, each a tenth of the one before.
constexpr int kScales = 8;

/// Direction k of a Fibonacci lattice of n points on the unit sphere.
Vec3 fibonacci_direction(int k, int n) {
  const double z = 1.0 - (2.0 * k + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = k * kPi * (3.0 - std::sqrt(5.0));  // golden angle
  return {r * std::cos(phi), r * std::sin(phi), z};
}

/// A uniformly random rotation (a normalised 4-D Gaussian as a quaternion).
Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

/// How ACCD treats a pair during a batch, by its distance d at the batch start (PSQ Alg. 4):
/// within its offset ξ (new in a split patch: it only must not cross), closer than ξ + g₀
/// (keeps nearly all its gap), or farther (keeps a tenth).
enum class PairClass { inside, close, far };

struct Gaps {
  double min_gap;                  ///< m
  int inside;                      ///< pairs at or within their offset
  std::vector<double> vertex_gap;  ///< per collision vertex: its pairs' smallest gap (m)
};

/// The smallest distance between a primitive with local vertex j and one of the patch's others
/// it shares no vertex with: vertex–face and edge–edge pairs of the patch `faces` at `points`.
double patch_clearance(const Positions& points, const Faces& faces, int j) {
  std::vector<std::array<int, 2>> edges;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      std::array<int, 2> e{faces(f, k), faces(f, (k + 1) % 3)};
      if (e[0] > e[1]) std::swap(e[0], e[1]);
      if (std::find(edges.begin(), edges.end(), e) == edges.end()) edges.push_back(e);
    }
  const auto stencil = [&points](std::array<int, 4> v) {
    Vec12 xs;
    for (int k = 0; k < 4; ++k) xs.segment<3>(3 * k) = points.row(v[k]).transpose();
    return xs;
  };
  double clearance = std::numeric_limits<double>::infinity();
  for (int v = 0; v < points.rows(); ++v)
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const auto face = faces.row(f);
      const bool touches_j = v == j || face[0] == j || face[1] == j || face[2] == j;
      if (!touches_j || v == face[0] || v == face[1] || v == face[2]) continue;
      const Vec12 xs = stencil({v, face[0], face[1], face[2]});
      clearance = std::min(clearance, distance_squared(xs, classify_point_triangle(xs)));
    }
  for (const auto& a : edges)
    for (const auto& b : edges) {
      const bool touches_j = a[0] == j || a[1] == j;
      if (!touches_j || a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
      const Vec12 xs = stencil({a[0], a[1], b[0], b[1]});
      clearance = std::min(clearance, distance_squared(xs, classify_edge_edge(xs)));
    }
  return std::sqrt(clearance);
}

/// The state of one refinement: the finer level's vertices present so far, their faces, and
/// the collision mesh over them (compact: absent vertices must not act as points).
class Expansion {
 public:
  Expansion(const MeshHierarchy& h, int level, const Positions& coarse, const Positions& target,
            const RefinementSurroundings& around, const SafeRefinementSettings& settings)
      : h_(h),
        target_(target),
        around_(around),
        settings_(settings),
        length_(bounding_box_diagonal(h.levels[level + 1].rest.vertices)) {
    const HierarchyLevel& fine = h.levels[level + 1];
    fine_index_ = level_vertex_index(h, level + 1);
    x_ = Positions::Zero(fine.rest.num_vertices(), 3);
    present_.assign(fine.rest.num_vertices(), 0);
    const std::vector<int>& ids = h.levels[level].input_vertex;
    for (int i = 0; i < static_cast<int>(ids.size()); ++i) {
      x_.row(fine_index_[ids[i]]) = coarse.row(i);
      present_[fine_index_[ids[i]]] = 1;
    }
    faces_ = level_input_faces(h.levels[level]);
    build_mesh();
  }

  /// One batch of PSQ Algorithm 3.
  void expand(const std::vector<int>& batch, SafeRefinementStats& stats) {
    const Gaps before = gaps();
    const double g0 = before.min_gap;
    // PSQ Alg. 3 line 6 moves new vertices by 0.01·g₀ with g₀ the global gap; here g₀ is the
    // smallest gap at the patch's vertices: as safe (a new vertex starts where its partner is,
    // so its pairs are its partner's), and not tiny everywhere because one pair is near.
    std::vector<double> sizes(batch.size());
    for (std::size_t b = 0; b < batch.size(); ++b)
      sizes[b] = settings_.perturbation * patch_gap(h_.collapses[batch[b]], before.vertex_gap);
    apply_splits(faces_, h_.collapses, batch);
    std::vector<int> movers;
    for (int r : batch) {
      const int j = fine_index_[h_.collapses[r].removed], k = fine_index_[h_.collapses[r].kept];
      x_.row(j) = x_.row(k);  // topological expansion: j starts where its partner is
      present_[j] = 1;
      movers.push_back(k);
      movers.push_back(j);
    }
    build_mesh();  // the new vertices present, at their partners
    const std::vector<char> done = perturb_along_targets(batch);
    perturb(batch, sizes, done, stats);
    refresh_positions(movers);
    advance(movers, g0, stats);
    ++stats.batches;
    stats.splits += static_cast<int>(batch.size());
  }

  const Positions& positions() const { return x_; }
  /// The smallest gap d − ξ over the pairs outside their offsets (capped at d̂), per collision
  /// vertex too, and how many pairs are within theirs (in split patches not yet open).
  Gaps gaps() const {
    CandidateSet candidates;
    find_candidates(mesh_, points_, points_, around_.dhat + 2.0 * mesh_.max_offset(), candidates);
    Gaps out{around_.dhat, 0, std::vector<double>(mesh_.num_vertices(), around_.dhat)};
    // A pair within its offset bounds the vertex gap by its distance: a perturbation larger
    // than that could carry a vertex through it.
    const auto add = [&out](const ContactPair& p, double distance) {
      const double gap = distance - p.offset;
      if (gap > 0.0)
        out.min_gap = std::min(out.min_gap, gap);
      else
        ++out.inside;
      for (int v : p.vertices)
        if (v >= 0) out.vertex_gap[v] = std::min(out.vertex_gap[v], gap > 0.0 ? gap : distance);
    };
    for (int k = 0; k < static_cast<int>(candidates.size()); ++k) {
      const ContactPair p = candidate_pair(mesh_, candidates, k);
      add(p, pair_distance(p));
    }
    if (around_.ground)
      for (int v = 0; v < mesh_.num_shell_vertices; ++v) {
        const ContactPair p = ground_pair(mesh_, v);
        add(p, pair_distance(p));
      }
    return out;
  }

 private:
  double pair_distance(const ContactPair& p) const {
    return std::sqrt(pair_distance_squared(p, stencil_positions(p.vertices, points_), ground()));
  }
  const GroundPlane* ground() const { return around_.ground ? &*around_.ground : nullptr; }

  /// The collision mesh of the present vertices and faces, plus the obstacles.
  void build_mesh() {
    compact_.assign(present_.size(), -1);
    present_list_.clear();
    for (int i = 0; i < static_cast<int>(present_.size()); ++i)
      if (present_[i])
        compact_[i] = static_cast<int>(present_list_.size()), present_list_.push_back(i);
    const int n = static_cast<int>(present_list_.size());
    Positions shell(n, 3);
    std::vector<double> offset(n), friction(n, 0.0);
    for (int c = 0; c < n; ++c) {
      shell.row(c) = x_.row(present_list_[c]);
      offset[c] = around_.vertex_offset[present_list_[c]];
    }
    Faces faces(static_cast<Eigen::Index>(faces_.size()), 3);
    for (std::size_t f = 0; f < faces_.size(); ++f)
      for (int k = 0; k < 3; ++k) faces(f, k) = compact_[fine_index_[faces_[f][k]]];
    std::vector<ObstacleSurface> obstacles;
    if (around_.obstacle_faces.rows() > 0)
      obstacles.push_back({&around_.obstacle_positions, &around_.obstacle_faces, 0.0});
    mesh_ = build_collision_mesh(shell, faces, offset, friction, obstacles);
    points_ = mesh_.rest;  // the current positions of every collision vertex
  }

  /// Copies the positions of the finer-level vertices `moved` into the collision mesh (its
  /// topology is unchanged: only positions moved since build_mesh()).
  void refresh_positions(const std::vector<int>& moved) {
    for (int v : moved) {
      const int c = compact_[v];
      mesh_.rest.row(c) = x_.row(v);
      points_.row(c) = x_.row(v);
    }
  }

  /// Moving the split's new vertex j by `size` made no intersection in its patch (its `before`
  /// faces, CGAL exact predicates), left none of j's triangles degenerate, and kept j's
  /// primitives at least kMinClearance·size from the patch's others (a pair nearly touching
  /// would stall every later CCD step). Pairs of faces without j are left out: moving j does
  /// not change them.
  bool patch_is_safe(const CollapseRecord& record, double size) const {
    const int j = fine_index_[record.removed];
    std::vector<int> vertices;  // a patch has a few tens of vertices: a linear search is fine
    Faces faces(static_cast<Eigen::Index>(record.before.size()), 3);
    std::vector<char> has_j(record.before.size(), 0);
    for (std::size_t f = 0; f < record.before.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int v = fine_index_[record.before[f][k]];
        auto at = std::find(vertices.begin(), vertices.end(), v);
        if (at == vertices.end()) at = vertices.insert(at, v);
        faces(f, k) = static_cast<int>(at - vertices.begin());
        has_j[f] |= v == j;
      }
    Positions points(static_cast<Eigen::Index>(vertices.size()), 3);
    for (std::size_t v = 0; v < vertices.size(); ++v) points.row(v) = x_.row(vertices[v]);
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      const Vec3 a = points.row(faces(f, 0)), b = points.row(faces(f, 1)),
                 c = points.row(faces(f, 2));
      if (has_j[f] && !((b - a).cross(c - a).squaredNorm() > 0.0)) return false;
    }
    for (const FacePair& pair : intersecting_faces(points, faces))
      if (has_j[pair.a] || has_j[pair.b]) return false;
    const int local_j =
        static_cast<int>(std::find(vertices.begin(), vertices.end(), j) - vertices.begin());
    return patch_clearance(points, faces, local_j) >= kMinClearance * size &&
           clear_of_ground(j, fine_index_[record.kept]);
  }

  /// The new vertex j keeps its partner k's gap to the ground: at least far_ratio of it above
  /// its offset, or, if k is within its offset, at least far_ratio of k's height (the patch
  /// check does not see the ground, and a vertex on or below it is 0 m from it).
  bool clear_of_ground(int j, int k) const {
    if (!around_.ground) return true;
    const auto height = [this](int v) {
      return around_.ground->normal.dot(x_.row(v).transpose()) - around_.ground->height;
    };
    const double offset = around_.vertex_offset[j], h_k = height(k), h_j = height(j);
    return h_k > offset ? h_j - offset >= settings_.far_ratio * (h_k - offset)
                        : h_j >= settings_.far_ratio * h_k && h_j > 0.0;
  }

  /// The smallest gap at the vertices of a split's patch that are present (before the split).
  double patch_gap(const CollapseRecord& record, const std::vector<double>& vertex_gap) const {
    double gap = around_.dhat;
    for (const FaceCorners& face : record.before)
      for (int id : face) {
        const int c = compact_[fine_index_[id]];
        if (c >= 0) gap = std::min(gap, vertex_gap[c]);
      }
    return gap;
  }

  /// PSQ Algorithm 5: the new vertex j of each split moves sizes[b] off its partner, toward its
  /// target if that keeps the patch safe, else along stratified random directions (rounds of a
  /// randomly rotated Fibonacci lattice, seeded per split).
  void perturb(const std::vector<int>& batch, const std::vector<double>& sizes,
               const std::vector<char>& done, SafeRefinementStats& stats) {
    const int n = static_cast<int>(batch.size());
    int random = 0, failed = -1;
#pragma omp parallel for reduction(+ : random) schedule(dynamic, 4) num_threads(thread_budget())
    for (int b = 0; b < n; ++b) {
      if (done[b]) continue;
      const int found = perturb_one(batch[b], sizes[b]);
      random += found > 0;
      if (found < 0) {
#pragma omp critical
        failed = std::max(failed, batch[b]);
      }
    }
    stats.random_directions += random;
    if (failed >= 0)
      fail(Status::intersecting, "safe refinement: no safe direction found for splitting vertex " +
                                     std::to_string(h_.collapses[failed].removed) + " off " +
                                     std::to_string(h_.collapses[failed].kept) + " after " +
                                     std::to_string(settings_.max_samples) + " samples");
  }

  /// The first try of PSQ Alg. 5, sized by CCD rather than by the gap: each new vertex j moves
  /// off its partner k along the direction of its target edge, by target_edge_fraction of that
  /// edge or as far as additive CCD clears against everything outside its patch (a vertex
  /// pressed on an obstacle may still slide along it), then its patch is checked. Returns, per
  /// split, whether j was placed (the others are back at their partners).
  std::vector<char> perturb_along_targets(const std::vector<int>& batch) {
    const int n = static_cast<int>(batch.size());
    std::vector<int> owner(mesh_.num_vertices(), -1), moved(n);
    std::vector<Vec3> step(n);
    Positions end = points_;
    for (int b = 0; b < n; ++b) {
      const CollapseRecord& record = h_.collapses[batch[b]];
      for (const FaceCorners& face : record.before)
        for (int id : face) owner[compact_[fine_index_[id]]] = b;
      const int j = fine_index_[record.removed], k = fine_index_[record.kept];
      step[b] = settings_.target_edge_fraction * (target_.row(j) - target_.row(k)).transpose();
      moved[b] = compact_[j];
      end.row(moved[b]) += step[b].transpose();
    }
    std::vector<char> moves(mesh_.num_vertices(), 0);
    for (int v = 0; v < mesh_.num_vertices(); ++v) moves[v] = owner[v] >= 0 && moved[owner[v]] == v;
    CandidateSet candidates;  // the pairs with a moved vertex
    find_candidates(mesh_, points_, end, 2.0 * mesh_.max_offset(), candidates, &moves);
    std::vector<double> t(n, 1.0);
    for (int c = 0; c < static_cast<int>(candidates.size()); ++c) {
      const ContactPair p = candidate_pair(mesh_, candidates, c);
      int first = -2;  // the patch of the pair's vertices: −1 for several or none
      for (int v : p.vertices)
        if (v >= 0) first = first == -2 ? owner[v] : (first == owner[v] ? first : -1);
      if (first >= 0) continue;  // inside one patch (checked below)
      const Vec12 xs = stencil_positions(p.vertices, points_);
      const double d = std::sqrt(pair_distance_squared(p, xs, ground()));
      const double bound = no_step_if_nan(
          pair_safe_step(p, xs, stencil_positions(p.vertices, end) - xs,
                         d > p.offset ? p.offset : 0.0, settings_.far_ratio, ground()));
      for (int v : p.vertices)
        if (v >= 0 && moves[v]) t[owner[v]] = std::min(t[owner[v]], bound);
    }
    if (around_.ground)  // the broad phase has no ground pairs: a target below it sank j
      for (int b = 0; b < n; ++b) {
        const ContactPair p = ground_pair(mesh_, moved[b]);
        const Vec12 xs = stencil_positions(p.vertices, points_);
        const double d = pair_distance(p);
        t[b] = std::min(t[b], no_step_if_nan(pair_safe_step(
                                  p, xs, stencil_positions(p.vertices, end) - xs,
                                  d > p.offset ? p.offset : 0.0, settings_.far_ratio, ground())));
      }
    std::vector<char> done(n, 0);
#pragma omp parallel for schedule(dynamic, 4) num_threads(thread_budget())
    for (int b = 0; b < n; ++b) {
      const CollapseRecord& record = h_.collapses[batch[b]];
      const int j = fine_index_[record.removed];
      const Vec3 origin = x_.row(j);
      const double size = t[b] * step[b].norm();
      if (!(size > 0.0)) continue;
      x_.row(j) = origin + t[b] * step[b];
      done[b] = patch_is_safe(record, size);
      if (!done[b]) x_.row(j) = origin;
    }
    return done;
  }

  /// Perturbs the new vertex of split `r` (Alg. 5). Each of kScales tries a tenth of the size
  /// of the one before (a patch with nearly coincident vertices, left by an earlier split that
  /// contact held closed, may only admit a small one): the target direction, then random ones.
  /// Returns 0 if the target direction was safe, 1 if a random one was, −1 if none was (j is
  /// then back at its partner).
  int perturb_one(int r, double size) {
    const CollapseRecord& record = h_.collapses[r];
    const int j = fine_index_[record.removed], k = fine_index_[record.kept];
    const Vec3 origin = x_.row(j);
    // Toward the target edge k→j: when the kept vertex moves too, j then separates from it
    // along the direction they end up apart (the target direction of PSQ Alg. 5 if k stays).
    const Vec3 toward = (target_.row(j) - target_.row(k)).transpose();
    std::mt19937_64 rng(settings_.seed ^ (0x9E3779B97F4A7C15ull * (r + 1)));
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    const int samples = std::max(1, settings_.max_samples / kScales);
    for (int scale = 0; scale < kScales; ++scale, size *= 0.1) {
      if (toward.norm() > 0.0) {
        x_.row(j) = origin + size * toward.normalized();
        if (patch_is_safe(record, size)) return scale == 0 ? 0 : 1;
      }
      for (int s = 0; s < samples; ++s) {
        if (s % kDirectionsPerRound == 0) rotation = random_rotation(rng);
        x_.row(j) = origin + size * rotation *
                                 fibonacci_direction(s % kDirectionsPerRound, kDirectionsPerRound);
        if (patch_is_safe(record, size)) return 1;
      }
    }
    x_.row(j) = origin;
    return -1;
  }

  /// PSQ Algorithms 3–4: moves the batch's vertices toward their targets in rounds, each by the
  /// largest step ACCD clears for every pair; the vertices of the pairs that bound it stop.
  void advance(const std::vector<int>& movers, double g0, SafeRefinementStats& stats) {
    std::vector<char> moving(mesh_.num_vertices(), 0);
    Positions end = points_;
    double start_distance = 0.0;
    Positions path_start(movers.size(), 3);  // where each mover started, for relax_stuck()
    for (std::size_t m = 0; m < movers.size(); ++m)
      path_start.row(m) = points_.row(compact_[movers[m]]);
    for (int v : movers) {
      const int c = compact_[v];
      moving[c] = 1;
      end.row(c) = target_.row(v);
      start_distance += (end.row(c) - points_.row(c)).norm();
    }
    CandidateSet candidates;  // the pairs with a mover
    find_candidates(mesh_, points_, end, 2.0 * mesh_.max_offset(), candidates, &moving);
    std::vector<ContactPair> pairs;
    for (int k = 0; k < static_cast<int>(candidates.size()); ++k)
      pairs.push_back(candidate_pair(mesh_, candidates, k));
    if (around_.ground)
      for (int v : movers) pairs.push_back(ground_pair(mesh_, compact_[v]));
    std::vector<PairClass> kind(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const double d = std::sqrt(
          pair_distance_squared(pairs[k], stencil_positions(pairs[k].vertices, points_), ground()));
      kind[k] = d <= pairs[k].offset       ? PairClass::inside
                : d - pairs[k].offset < g0 ? PairClass::close
                                           : PairClass::far;
    }
    std::vector<double> step(pairs.size());
    for (int round = 0; round < settings_.max_rounds; ++round) {
      ++stats.rounds;
      const double alpha = safe_step(pairs, kind, moving, end, step);
      for (int c = 0; c < mesh_.num_shell_vertices; ++c)
        if (moving[c]) points_.row(c) += alpha * (end.row(c) - points_.row(c));
      if (alpha >= 1.0) break;
      for (std::size_t k = 0; k < pairs.size(); ++k)  // the pairs that bound α stop (Alg. 3)
        if (step[k] <= alpha * (1.0 + 1e-9))
          for (int v : pairs[k].vertices)
            if (v >= 0 && moving[v]) stats.stopped_vertices += stop(v, moving, end);
      if (std::none_of(moving.begin(), moving.end(), [](char m) { return m != 0; })) break;
      if (round + 1 == settings_.max_rounds)  // out of rounds: everyone stops where it is
        for (int c = 0; c < mesh_.num_shell_vertices; ++c)
          if (moving[c]) stats.stopped_vertices += stop(c, moving, end);
    }
    relax_stuck(movers, path_start, stats);
    double remaining = 0.0;
    for (int v : movers) {
      x_.row(v) = points_.row(compact_[v]);
      remaining += (target_.row(v) - x_.row(v)).norm();
    }
    remaining_ += remaining;
    start_ += start_distance;
  }

  /// Vertex c stops where it is; returns 1 (one more stopped vertex).
  int stop(int c, std::vector<char>& moving, Positions& end) const {
    moving[c] = 0;
    end.row(c) = points_.row(c);
    return 1;
  }

  /// PSQ §4.4.3: the movers that contact stopped short (more than 1% of their way left, from
  /// `start` rows in the order of `movers`) relax locally toward their targets.
  void relax_stuck(const std::vector<int>& movers, const Positions& start,
                   SafeRefinementStats& stats) {
    std::vector<int> stuck;
    for (std::size_t m = 0; m < movers.size(); ++m) {
      const int c = compact_[movers[m]];
      const double path = (target_.row(movers[m]) - start.row(m)).norm();
      if ((target_.row(movers[m]) - points_.row(c)).norm() > 0.01 * path) stuck.push_back(c);
    }
    if (stuck.empty()) return;
    Positions targets = points_.topRows(mesh_.num_shell_vertices);
    for (int c : stuck) targets.row(c) = target_.row(present_list_[c]);
    const NewtonReport report =
        relax_toward_targets(mesh_, targets, points_, stuck, around_.dhat, around_.ground, length_);
    stats.relaxed_vertices += static_cast<int>(stuck.size());
    stats.relaxation_iterations += report.iterations;
  }

  static bool touches(const ContactPair& p, const std::vector<char>& moving) {
    for (int v : p.vertices)
      if (v >= 0 && moving[v]) return true;
    return false;
  }

  /// The largest α ∈ [0, 1] every pair with a moving vertex clears toward `end`; per pair its
  /// own bound in `step`. `kind` is each pair's class at the batch start (PairClass).
  double safe_step(const std::vector<ContactPair>& pairs, const std::vector<PairClass>& kind,
                   const std::vector<char>& moving, const Positions& end,
                   std::vector<double>& step) const {
    const int n = static_cast<int>(pairs.size());
    double alpha = 1.0;
#pragma omp parallel for reduction(min                            \
                                   : alpha) schedule(dynamic, 64) \
    num_threads(loop_threads(n, kMinParallelItems / 16))
    for (int k = 0; k < n; ++k) {
      step[k] = 1.0;
      if (!touches(pairs[k], moving)) continue;
      const ContactPair& p = pairs[k];
      const Vec12 xs = stencil_positions(p.vertices, points_);
      const Vec12 dx = stencil_positions(p.vertices, end) - xs;
      const bool inside = kind[k] == PairClass::inside;
      const double ratio = inside                        ? settings_.inside_ratio
                           : kind[k] == PairClass::close ? settings_.close_ratio
                                                         : settings_.far_ratio;
      step[k] = no_step_if_nan(pair_safe_step(p, xs, dx, inside ? 0.0 : p.offset, ratio, ground()));
      alpha = std::min(alpha, step[k]);
    }
    return alpha;
  }

 public:
  double reached() const {
    return start_ > 0.0 ? 1.0 - remaining_ / start_ : 1.0;
  }

 private:
  const MeshHierarchy& h_;
  const Positions& target_;
  const RefinementSurroundings& around_;
  SafeRefinementSettings settings_;
  std::vector<int> fine_index_;  // input vertex → finer-level vertex (−1: not on it)
  Positions x_;                  // finer-level positions (rows of absent vertices unused)
  std::vector<char> present_;
  std::vector<FaceCorners> faces_;  // the current faces, in input ids
  CollisionMesh mesh_;
  std::vector<int> compact_, present_list_;  // finer-level vertex ↔ collision vertex
  Positions points_;                         // collision vertex positions
  double length_;                            // the finer level's bounding-box diagonal
  double start_ = 0.0, remaining_ = 0.0;
};

void check_arguments(const MeshHierarchy& h, int level, const Positions& coarse,
                     const Positions& target, const RefinementSurroundings& around) {
  if (level < 0 || level >= h.finest())
    fail(Status::out_of_range, "safe refinement: level " + std::to_string(level) +
                                   " has no finer level (levels 0 to " +
                                   std::to_string(h.finest()) + ")");
  const Eigen::Index n = h.levels[level].rest.num_vertices();
  const Eigen::Index m = h.levels[level + 1].rest.num_vertices();
  if (coarse.rows() != n || target.rows() != m ||
      static_cast<Eigen::Index>(around.vertex_offset.size()) != m)
    fail(Status::invalid_argument,
         "safe refinement: expected " + std::to_string(n) + " coarse positions and " +
             std::to_string(m) + " targets and offsets, got " + std::to_string(coarse.rows()) +
             ", " + std::to_string(target.rows()) + " and " +
             std::to_string(around.vertex_offset.size()));
  // The CCD bounds below cannot bound a non-finite motion (additive_ccd_point_triangle()).
  if (!coarse.allFinite() || !target.allFinite() || !around.obstacle_positions.allFinite())
    fail(Status::numerical_failure,
         "safe refinement: the coarse state, its targets or the obstacles are not finite");
}

/// PSQ §4.4 keeps an intersection-free state so: its start must be one. Checked with CGAL's
/// exact predicates (the shell at `coarse` with the obstacles), independent of the CCD.
void check_start_crossing_free(const MeshHierarchy& h, int level, const Positions& coarse,
                               const RefinementSurroundings& around) {
  const TriangleMesh shell{coarse, h.levels[level].rest.faces};
  const TriangleMesh obstacles{around.obstacle_positions, around.obstacle_faces};
  const TriangleMesh start = merge_meshes({&shell, &obstacles});
  check_intersection_free(start.vertices, start.faces,
                          "safe refinement: the level-" + std::to_string(level) +
                              " state (shell faces first, then the obstacles')");
}

}  // namespace

Positions safe_refinement(const MeshHierarchy& hierarchy, int level, const Positions& coarse,
                          const Positions& target, const RefinementSurroundings& surroundings,
                          const SafeRefinementSettings& settings, SafeRefinementStats* stats) {
  check_arguments(hierarchy, level, coarse, target, surroundings);
  check_start_crossing_free(hierarchy, level, coarse, surroundings);
  SafeRefinementStats local;
  Expansion expansion(hierarchy, level, coarse, target, surroundings, settings);
  for (const std::vector<int>& batch : hierarchy.expansion_batches[level])
    expansion.expand(batch, local);
  local.reached = expansion.reached();
  const Gaps end = expansion.gaps();
  local.min_gap = end.min_gap;
  local.inside_pairs = end.inside;
  if (stats) *stats = local;
  return expansion.positions();
}

RefinementSurroundings refinement_surroundings(const ContactPotential& contact,
                                               const ShellModel& finer) {
  const CollisionMesh& mesh = contact.mesh();
  RefinementSurroundings around;
  around.vertex_offset = shell_contact_offsets(finer);
  around.obstacle_positions = contact.obstacle_positions();
  around.obstacle_faces = mesh.faces.bottomRows(mesh.faces.rows() - mesh.num_shell_faces).array() -
                          mesh.num_shell_vertices;
  if (contact.ground()) around.ground = *contact.ground();
  around.dhat = contact.dhat();
  return around;
}

}  // namespace progsim
