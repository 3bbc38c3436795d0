#pragma once
/// @file The decimation's guard against collapses that make a level cross itself or bring two
/// of its primitives within their contact offset. Every coarse level is the start of a
/// simulation whose contact needs exactly that (IPC's invariant; PSQ §4.4 refines from it), so a
/// level is only usable if decimation never creates either (issue 28: homer's 500-vertex level
/// had 5 crossing face pairs without it).
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/types.hpp"

namespace progsim {

/// Mirrors the mesh being decimated (vertex and face ids as in the input, which CGAL's
/// Surface_mesh keeps without garbage collection) in a uniform hash grid of face boxes, and
/// tests a collapse's new faces against the faces around them: crossings with CGAL's exact
/// predicates (faces sharing a vertex or an edge cross when they overlap beyond it, as in
/// CGAL::Polygon_mesh_processing::self_intersections), offsets by point–triangle and
/// segment–segment distances of the pairs contact would form (no shared vertex).
class CollapseGuard {
 public:
  /// `vertices` (|V| × 3) and `faces` (|F| × 3): the input mesh. `offsets`: per vertex its
  /// contact offset ξ_v (m), or empty to test crossings only. A pair's offset is the sum of its
  /// two sides' largest ξ (C-IPC §4; at least what contact uses).
  CollapseGuard(const Positions& vertices, const Faces& faces, std::vector<double> offsets);

  /// Which crossings a collapse may leave: none at all, or none with a face that the faces it
  /// replaces did not already cross (an input that crosses itself keeps its crossings there,
  /// and decimation goes on around them).
  enum class CrossingRule { none, no_new_pair };

  /// Whether collapsing the edge (v0, v1) to the point `merged` keeps the mesh free of new
  /// crossings (per `rule`) and of offset violations. `around`: every live face incident to v0
  /// or v1.
  bool allows(int v0, int v1, const Vec3& merged, const std::vector<int>& around,
              CrossingRule rule = CrossingRule::no_new_pair) const;

  /// Records that collapse: `removed` merged into `kept`, which is now at `merged`.
  void collapsed(int removed, int kept, const Vec3& merged, const std::vector<int>& around);

  /// Whether vertex v is a corner of a face that crossed another in the input and has not been
  /// collapsed since (a crossing input, PSQ runs with contact.crossing_start): decimation
  /// collapses these first, so that coarse levels lose the crossing where the guard allows.
  bool on_input_crossing(int v) const { return on_crossing_[v] != 0; }

 private:
  using Corners = std::array<int, 3>;
  struct Box {
    Vec3 lo, hi;
  };
  /// A face of a tested configuration: its corners (vertex ids) and their positions.
  struct Placed {
    Corners corners;
    std::array<Vec3, 3> points;
  };

  Placed placed(int face) const;
  /// The faces of `around` after the collapse, with b replaced by a at `merged` (those with
  /// both endpoints vanish).
  std::vector<Placed> after_faces(int a, int b, const Vec3& merged,
                                  const std::vector<int>& around) const;
  /// Live faces whose grid cells meet `box` (each once), except those in `around`.
  void candidates(const Box& box, const std::vector<int>& around, std::vector<int>& out) const;
  /// Whether `other` crosses one of the faces `around` as they are now.
  bool crossed_before(const Placed& other, const std::vector<int>& around) const;
  /// Whether two faces cross beyond what they share (CGAL's exact predicates).
  bool cross(const Placed& a, const Placed& b) const;
  /// Whether a new pair of a and b (one with `merged`, the collapse's vertex, carried in their
  /// corners as v0) is within its offset; false without offsets.
  bool too_close(const Placed& a, const Placed& b, int merged) const;
  double face_offset(const Corners& corners) const;

  Box box_of(const std::array<Vec3, 3>& points, double margin) const;
  std::int64_t key(const Eigen::Vector3i& cell) const;
  Eigen::Vector3i cell_of(const Vec3& p) const;
  void insert(int face);
  /// Rebuilds the grid with cells of the live faces' mean edge length.
  void rebuild();

  Positions positions_;
  std::vector<Corners> faces_;
  std::vector<char> alive_;
  std::vector<std::uint32_t> stamp_;  ///< grid entries of a face with an older stamp are stale
  std::vector<double> offsets_;
  std::vector<char> on_crossing_;  ///< per vertex: on_input_crossing()
  double margin_ = 0.0;            ///< largest pair offset: how far boxes are grown for candidates
  double cell_ = 1.0;
  int live_faces_ = 0;
  int live_at_rebuild_ = 0;
  std::unordered_map<std::int64_t, std::vector<std::pair<int, std::uint32_t>>> grid_;
  mutable std::vector<std::uint32_t> seen_;  ///< per face: the query that last met it
  mutable std::uint32_t query_ = 0;
};

}  // namespace progsim
