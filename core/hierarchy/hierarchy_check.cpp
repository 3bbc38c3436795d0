// check_hierarchy: the invariants of a MeshHierarchy, one small check per field. Counts are
// compared in 64 bits so that hostile values (from a corrupt file) cannot overflow.
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "hierarchy/expansion_coloring.hpp"
#include "hierarchy/mesh_hierarchy.hpp"
#include "mesh/mesh_validation.hpp"

namespace progsim {
namespace {

/// Barycentric weights may undershoot 0 and miss a sum of 1 by this much (rounding).

/// Throws invalid_argument with "hierarchy: <what>".
[[noreturn]] void reject(const std::string& what) {
  fail(Status::invalid_argument, "hierarchy: " + what);
}

std::string level_name(int l) {
  return "level " + std::to_string(l);
}

/// |V_l|, as a 64-bit count.
std::int64_t level_size(const MeshHierarchy& hierarchy, int l) {
  return hierarchy.levels[l].rest.num_vertices();
}

void check_level_count(const MeshHierarchy& hierarchy) {
  if (hierarchy.levels.empty()) reject("no levels (at least the input mesh is needed)");
}

void check_finite_vertices(const TriangleMesh& mesh, const std::string& label) {
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      if (std::isfinite(mesh.vertices(v, k))) continue;
      std::ostringstream s;
      s << label << " vertex " << v << " has a non-finite coordinate (" << mesh.vertices(v, k)
        << ')';
      reject(s.str());
    }
  }
}

void check_face_indices(const TriangleMesh& mesh, const std::string& label) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces(f, k);
      if (v >= 0 && v < mesh.num_vertices()) continue;
      reject(label + " face " + std::to_string(f) + " references vertex " + std::to_string(v) +
             ", but the level has " + std::to_string(mesh.num_vertices()) + " vertices");
    }
  }
}

/// input_vertex: one entry per level vertex, strictly increasing, within [0, num_input).
void check_input_vertex(const HierarchyLevel& level, const std::string& label,
                        std::int64_t num_input) {
  const std::vector<int>& ids = level.input_vertex;
  if (static_cast<std::int64_t>(ids.size()) != level.rest.num_vertices())
    reject(label + " has " + std::to_string(ids.size()) + " input_vertex entries for " +
           std::to_string(level.rest.num_vertices()) + " vertices");
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0 || ids[i] >= num_input)
      reject(label + " input_vertex[" + std::to_string(i) + "] = " + std::to_string(ids[i]) +
             " is not an input vertex in [0, " + std::to_string(num_input) + ")");
    if (i > 0 && ids[i] <= ids[i - 1])
      reject(label + " input_vertex is not strictly increasing at entry " + std::to_string(i) +
             " (" + std::to_string(ids[i - 1]) + ", then " + std::to_string(ids[i]) + ")");
  }
}

/// Each level's mesh and input_vertex. For the finest level, |V_L| strictly increasing ids in
/// [0, |V_L|) are exactly 0 … |V_L| − 1: the input mesh maps to itself.
void check_levels(const MeshHierarchy& hierarchy) {
  const std::int64_t num_input = level_size(hierarchy, hierarchy.finest());
  for (int l = 0; l < hierarchy.num_levels(); ++l) {
    const HierarchyLevel& level = hierarchy.levels[l];
    check_finite_vertices(level.rest, level_name(l));
    check_face_indices(level.rest, level_name(l));
    check_input_vertex(level, level_name(l), num_input);
  }
}

void check_level_sizes(const MeshHierarchy& hierarchy) {
  for (int l = 1; l < hierarchy.num_levels(); ++l) {
    if (level_size(hierarchy, l) > level_size(hierarchy, l - 1)) continue;
    reject(level_name(l) + " has " + std::to_string(level_size(hierarchy, l)) +
           " vertices, not more than " + level_name(l - 1) + "'s " +
           std::to_string(level_size(hierarchy, l - 1)));
  }
}

/// What is wrong with barycentric weights, or nullptr if they are valid.
const char* weights_problem(const Vec3& w) {
  if (!w.allFinite()) return "not all finite";
  if (w.minCoeff() < -kAnchorWeightTolerance) return "one of them negative";
  if (std::abs(w.sum() - 1.0) > kAnchorWeightTolerance) return "not summing to 1";
  return nullptr;
}

/// Anchor i of list `name`[l], on a face of level l (num_faces faces).
void check_anchor(const SurfaceAnchor& anchor, int num_faces, const std::string& name, int l,
                  std::size_t i) {
  const bool face_ok = anchor.face >= 0 && anchor.face < num_faces;
  const char* problem = weights_problem(anchor.weights);
  if (face_ok && !problem) return;
  const std::string label = name + "[" + std::to_string(l) + "] anchor " + std::to_string(i);
  if (!face_ok)
    reject(label + " is on face " + std::to_string(anchor.face) + ", but level " +
           std::to_string(l) + " has " + std::to_string(num_faces) + " faces");
  const Vec3& w = anchor.weights;
  std::ostringstream s;
  s.precision(17);
  s << label << " has weights (" << w[0] << ", " << w[1] << ", " << w[2] << "), " << problem;
  reject(s.str());
}

/// `lists` ("to_next" or "to_finest"): L lists, list l anchors `target_size(l)` vertices on
/// faces of level l.
template <class TargetSize>
void check_anchor_lists(const MeshHierarchy& hierarchy, const std::vector<SurfaceAnchors>& lists,
                        const std::string& name, TargetSize target_size) {
  if (static_cast<std::int64_t>(lists.size()) != hierarchy.finest())
    reject(name + " has " + std::to_string(lists.size()) + " entries for " +
           std::to_string(hierarchy.num_levels()) + " levels (it needs one per coarse level)");
  for (int l = 0; l < hierarchy.finest(); ++l) {
    const std::string label = name + "[" + std::to_string(l) + "]";
    if (static_cast<std::int64_t>(lists[l].size()) != target_size(l))
      reject(label + " has " + std::to_string(lists[l].size()) + " anchors, not " +
             std::to_string(target_size(l)));
    const int num_faces = hierarchy.levels[l].rest.num_faces();
    for (std::size_t i = 0; i < lists[l].size(); ++i)
      check_anchor(lists[l][i], num_faces, name, l, i);
  }
}

void check_anchors(const MeshHierarchy& hierarchy) {
  check_anchor_lists(hierarchy, hierarchy.to_next, "to_next",
                     [&](int l) { return level_size(hierarchy, l + 1); });
  check_anchor_lists(hierarchy, hierarchy.to_finest, "to_finest",
                     [&](int) { return level_size(hierarchy, hierarchy.finest()); });
}

/// first_collapse: L + 1 entries from collapses.size() down to 0, non-increasing, the span of
/// level l matching the vertices it adds.
void check_first_collapse(const MeshHierarchy& hierarchy) {
  const std::vector<int>& first = hierarchy.first_collapse;
  const int L = hierarchy.finest();
  if (static_cast<std::int64_t>(first.size()) != L + 1)
    reject("first_collapse has " + std::to_string(first.size()) + " entries for " +
           std::to_string(L + 1) + " levels");
  if (first[L] != 0)
    reject("first_collapse[" + std::to_string(L) + "] is " + std::to_string(first[L]) + ", not 0");
  if (first[0] != static_cast<std::int64_t>(hierarchy.collapses.size()))
    reject("first_collapse[0] is " + std::to_string(first[0]) + ", but there are " +
           std::to_string(hierarchy.collapses.size()) + " collapses");
  for (int l = 0; l < L; ++l) {
    const std::int64_t span = std::int64_t{first[l]} - first[l + 1];
    const std::int64_t added = level_size(hierarchy, l + 1) - level_size(hierarchy, l);
    if (span < 0)
      reject("first_collapse increases from level " + std::to_string(l) + " to " +
             std::to_string(l + 1));
    if (span != added)
      reject("first_collapse gives " + level_name(l) + " " + std::to_string(span) +
             " collapses, but " + level_name(l + 1) + " has " + std::to_string(added) +
             " more vertices");
  }
}

bool is_input_vertex(int v, std::int64_t num_input) {
  return v >= 0 && v < num_input;
}

void reject_vertex_id(int v, std::int64_t num_input, const std::string& label) {
  reject(label + " is vertex " + std::to_string(v) + ", not an input vertex in [0, " +
         std::to_string(num_input) + ")");
}

/// Corners of the faces `which` ("before" or "after") of collapse c.
void check_record_faces(const std::vector<FaceCorners>& faces, std::int64_t num_input,
                        std::size_t c, const char* which) {
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (!is_input_vertex(faces[f][k], num_input))
        reject_vertex_id(faces[f][k], num_input,
                         "collapse " + std::to_string(c) + " " + which + "[" + std::to_string(f) +
                             "] corner " + std::to_string(k));
}

void check_records(const MeshHierarchy& hierarchy) {
  const std::int64_t num_input = level_size(hierarchy, hierarchy.finest());
  for (std::size_t c = 0; c < hierarchy.collapses.size(); ++c) {
    const CollapseRecord& record = hierarchy.collapses[c];
    if (!is_input_vertex(record.removed, num_input))
      reject_vertex_id(record.removed, num_input, "collapse " + std::to_string(c) + " removed");
    if (!is_input_vertex(record.kept, num_input))
      reject_vertex_id(record.kept, num_input, "collapse " + std::to_string(c) + " kept");
    check_record_faces(record.before, num_input, c, "before");
    check_record_faces(record.after, num_input, c, "after");
  }
}

/// The batches of level l hold every collapse in [first_collapse[l+1], first_collapse[l])
/// exactly once (first_collapse is already checked).
void check_level_batches(const MeshHierarchy& hierarchy, int l) {
  const int begin = hierarchy.first_collapse[l + 1], end = hierarchy.first_collapse[l];
  const std::string label = "expansion_batches[" + std::to_string(l) + "]";
  std::vector<bool> seen(end - begin, false);
  const std::vector<std::vector<int>>& batches = hierarchy.expansion_batches[l];
  for (std::size_t b = 0; b < batches.size(); ++b) {
    for (const int c : batches[b]) {
      const auto where = [&] { return label + " batch " + std::to_string(b); };
      if (c < begin || c >= end)
        reject(where() + " holds collapse " + std::to_string(c) + ", outside the level's [" +
               std::to_string(begin) + ", " + std::to_string(end) + ")");
      if (seen[c - begin]) reject(where() + " repeats collapse " + std::to_string(c));
      seen[c - begin] = true;
    }
  }
  for (int c = begin; c < end; ++c)
    if (!seen[c - begin]) reject(label + " misses collapse " + std::to_string(c));
}

void check_batches(const MeshHierarchy& hierarchy) {
  if (static_cast<std::int64_t>(hierarchy.expansion_batches.size()) != hierarchy.finest())
    reject("expansion_batches has " + std::to_string(hierarchy.expansion_batches.size()) +
           " entries for " + std::to_string(hierarchy.num_levels()) +
           " levels (it needs one per coarse level)");
  for (int l = 0; l < hierarchy.finest(); ++l) check_level_batches(hierarchy, l);
}

/// Every level a valid mesh; each level's batches those the records give, refining it into
/// the next level (PSQ §4.4.4).
void check_refinement(const MeshHierarchy& h) {
  for (int l = 0; l < h.num_levels(); ++l)
    validate_mesh(h.levels[l].rest, "hierarchy level " + std::to_string(l));
  for (int l = 0; l < h.finest(); ++l) {
    const std::string level = std::to_string(l);
    std::vector<FaceCorners> faces = level_input_faces(h.levels[l]);
    try {
      if (expansion_batches(faces, h.collapses, h.first_collapse[l + 1], h.first_collapse[l]) !=
          h.expansion_batches[l])
        fail(Status::invalid_argument,
             "hierarchy: the expansion batches of level " + level + " differ from its records'");
      for (const auto& batch : h.expansion_batches[l]) apply_splits(faces, h.collapses, batch);
    } catch (const Error& e) {
      if (e.status() == Status::invalid_argument) throw;
      fail(Status::invalid_argument,
           "hierarchy: the collapse records of level " + level + " do not fit it: " + e.what());
    }
    if (!same_faces(faces, level_input_faces(h.levels[l + 1])))
      fail(Status::invalid_argument, "hierarchy: the collapse records of level " + level +
                                         " do not refine it into level " + std::to_string(l + 1));
  }
}

}  // namespace

/// input_group: one entry per input vertex, each -1 (free) or a group id.
void check_groups(const MeshHierarchy& hierarchy) {
  const std::vector<int>& group = hierarchy.input_group;
  const auto n = hierarchy.levels.back().rest.num_vertices();
  if (static_cast<std::int64_t>(group.size()) != n)
    reject("input_group has " + std::to_string(group.size()) + " entries for " + std::to_string(n) +
           " input vertices");
  for (std::size_t v = 0; v < group.size(); ++v)
    if (group[v] < -1)
      reject("input_group[" + std::to_string(v) + "] = " + std::to_string(group[v]) +
             " (groups are -1 or more)");
}

void check_hierarchy_structure(const MeshHierarchy& hierarchy) {
  check_level_count(hierarchy);
  check_levels(hierarchy);
  check_level_sizes(hierarchy);
  check_anchors(hierarchy);
  check_first_collapse(hierarchy);
  check_records(hierarchy);
  check_batches(hierarchy);
  check_groups(hierarchy);
}

void check_hierarchy(const MeshHierarchy& hierarchy) {
  check_hierarchy_structure(hierarchy);
  check_refinement(hierarchy);
}

}  // namespace progsim
