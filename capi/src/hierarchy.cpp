// ps_hierarchy_*: building, saving and loading a mesh hierarchy, reading its levels and
// prolonging positions to the finest level.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>

#include "common/error.hpp"
#include "handles.hpp"
#include "hierarchy/hierarchy_io.hpp"
#include "hierarchy/level_prolongation.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/tet_boundary.hpp"
#include "mesh/tet_mesh_io.hpp"
#include "mesh/tetrahedralize.hpp"
#include "percent_progress.hpp"

ps_hierarchy::ps_hierarchy(progsim::MeshHierarchy built)
    : ps_hierarchy(std::make_shared<const progsim::MeshHierarchy>(std::move(built))) {}

ps_hierarchy::ps_hierarchy(std::shared_ptr<const progsim::MeshHierarchy> built)
    : shared(std::move(built)) {
  to_finest.reserve(shared->finest());
  for (int l = 0; l < shared->finest(); ++l)
    to_finest.push_back(progsim::direct_prolongation(*shared, l));
}

ps_hierarchy::ps_hierarchy(std::shared_ptr<const progsim::TetHierarchy> built)
    : solid(std::move(built)) {
  for (const progsim::TetMesh& level : solid->levels)
    boundaries.push_back({level.vertices, progsim::tet_boundary_faces(level)});
}

int ps_hierarchy::num_levels() const {
  return solid ? solid->num_levels() : shared->num_levels();
}

const progsim::MeshHierarchy& ps_hierarchy::shells() const {
  if (solid)
    progsim::capi::api_fail(PS_ERROR_UNSUPPORTED,
                            "the call applies to a shell's hierarchy; this one is a solid's");
  return *shared;
}

namespace progsim::capi {
namespace {

// Faces are passed through the ABI without conversion.
static_assert(std::is_same_v<Faces::Scalar, int32_t>, "progsim::Faces must hold int32_t");

constexpr int32_t kHierarchyCookie = 0x50534844;  // "PSHD"

/// The pinned vertices of def as vertex group 0 of a mesh of `num_vertices` vertices.
std::vector<int> pinned_groups(const ps_hierarchy_def& def, std::size_t num_vertices) {
  if (def.num_pinned_vertices == 0) return {};
  require(def.pinned_vertices, "pinned_vertices (with num_pinned_vertices > 0)");
  std::vector<int> groups(num_vertices, -1);
  for (std::size_t k = 0; k < def.num_pinned_vertices; ++k) {
    const int32_t v = def.pinned_vertices[k];
    if (v < 0 || static_cast<std::size_t>(v) >= num_vertices)
      api_fail(PS_ERROR_OUT_OF_RANGE,
               "pinned_vertices[" + std::to_string(k) + "] = " + std::to_string(v) +
                   " is not a vertex (the mesh has " + std::to_string(num_vertices) + ")");
    groups[v] = 0;
  }
  return groups;
}

/// def's vertex_group_ids as the vertex groups of a mesh of `num_vertices` vertices: one id per
/// vertex, −1 or a group, the groups 0 .. G−1 each used.
std::vector<int> listed_groups(const ps_hierarchy_def& def, std::size_t num_vertices) {
  require(def.vertex_group_ids, "vertex_group_ids (with num_vertex_group_ids > 0)");
  if (def.num_pinned_vertices > 0)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "pinned_vertices and vertex_group_ids: give the groups one way, not both");
  if (def.num_vertex_group_ids != num_vertices)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "num_vertex_group_ids = " + std::to_string(def.num_vertex_group_ids) +
                 " must be the mesh's vertex count, " + std::to_string(num_vertices));
  std::vector<int> groups(def.vertex_group_ids, def.vertex_group_ids + num_vertices);
  for (std::size_t v = 0; v < num_vertices; ++v)  // gapless groups are fewer than the vertices
    if (groups[v] < -1 || static_cast<std::size_t>(std::max(groups[v], 0)) >= num_vertices)
      api_fail(PS_ERROR_INVALID_ARGUMENT, "vertex_group_ids[" + std::to_string(v) +
                                              "] = " + std::to_string(groups[v]) +
                                              " must be -1 (no group) or a group in [0, " +
                                              std::to_string(num_vertices) + ")");
  const int count = 1 + *std::max_element(groups.begin(), groups.end());
  std::vector<bool> used(static_cast<std::size_t>(count), false);
  for (int g : groups)
    if (g >= 0) used[g] = true;
  for (int g = 0; g < count; ++g)
    if (!used[g])
      api_fail(PS_ERROR_INVALID_ARGUMENT, "vertex_group_ids: group " + std::to_string(g) +
                                              " has no vertex (groups are numbered 0, 1, ... "
                                              "without gaps, as the handles they become)");
  return groups;
}

/// The build options of def (nullable: a single level) for a mesh of `num_vertices` vertices
/// (0: not known yet, pinned vertices unchecked); rejects defs nobody initialised.
HierarchyOptions hierarchy_options(const ps_hierarchy_def* def, std::size_t num_vertices) {
  HierarchyOptions options;
  if (!def) return options;
  require_initialized(def->internal_cookie, kHierarchyCookie, "ps_hierarchy_def");
  const std::vector<int32_t> counts =
      borrowed_array(def->coarse_vertex_counts, def->num_coarse_levels, "coarse_vertex_counts",
                     "num_coarse_levels", 64);
  options.coarse_vertex_counts.assign(counts.begin(), counts.end());
  if (num_vertices > 0)
    options.vertex_groups = def->num_vertex_group_ids > 0 ? listed_groups(*def, num_vertices)
                                                          : pinned_groups(*def, num_vertices);
  if (!(def->contact_offset >= 0.0) || !std::isfinite(def->contact_offset))
    api_fail(PS_ERROR_INVALID_ARGUMENT, "contact_offset = " + std::to_string(def->contact_offset) +
                                            " is invalid: it must be a finite length >= 0 (m)");
  if (def->contact_offset > 0.0) options.contact_offsets.assign(num_vertices, def->contact_offset);
  return options;
}

/// Validates mesh and builds the hierarchy def asks for.
std::unique_ptr<ps_hierarchy> build(const ps_hierarchy_def* def, const TriangleMesh& mesh) {
  const HierarchyOptions options =
      hierarchy_options(def, static_cast<std::size_t>(mesh.num_vertices()));
  PercentProgress forward{def ? def->progress : nullptr, def ? def->progress_user_data : nullptr};
  return std::make_unique<ps_hierarchy>(
      build_hierarchy(mesh, options, forward.fn ? PercentProgress::call : nullptr, &forward));
}

/// The tet hierarchy def asks for over `finest` (validated by build_tet_hierarchy).
std::unique_ptr<ps_hierarchy> build_solid(const ps_hierarchy_def* def, const TetMesh& finest) {
  const HierarchyOptions shell = hierarchy_options(def, 0);
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = shell.coarse_vertex_counts;
  if (def) options.size_factor = def->tet_size_factor;
  PercentProgress forward{def ? def->progress : nullptr, def ? def->progress_user_data : nullptr};
  return std::make_unique<ps_hierarchy>(std::make_shared<const TetHierarchy>(build_tet_hierarchy(
      finest, options, forward.fn ? PercentProgress::call : nullptr, &forward)));
}

/// Positions of `level` prolonged to the finest level: P^l for shells (PSQ eq. 9), the product
/// of the W of the levels above for solids (VPD §3.3).
Positions prolonged_to_finest(const ps_hierarchy& hierarchy, int32_t level, Positions x) {
  if (!hierarchy.solid)
    return level + 1 == hierarchy.num_levels() ? x : hierarchy.to_finest[level](x);
  return hierarchy.solid->prolong_to_finest(level, std::move(x));
}

/// A tet mesh from the C ABI's borrowed arrays, as borrowed_mesh for triangles.
TetMesh borrowed_tet_mesh(const double* vertices, std::size_t num_vertices, const int32_t* tets,
                          std::size_t num_tets) {
  require(vertices, "vertices");
  require(tets, "tets");
  constexpr size_t kMax = static_cast<size_t>(std::numeric_limits<int32_t>::max() / 4);
  if (num_vertices == 0 || num_tets == 0 || num_vertices > kMax || num_tets > kMax)
    api_fail(PS_ERROR_INVALID_MESH, "a tet mesh needs 1 to " + std::to_string(kMax) +
                                        " vertices and tets, got " + std::to_string(num_vertices) +
                                        " vertices and " + std::to_string(num_tets) + " tets");
  TetMesh mesh;
  mesh.vertices = Eigen::Map<const Positions>(vertices, static_cast<Eigen::Index>(num_vertices), 3);
  mesh.tets = Eigen::Map<const Tets>(tets, static_cast<Eigen::Index>(num_tets), 4);
  return mesh;
}

/// The solid `closed_surface` bounds, tetrahedralized with def's cell size.
TetMesh tetrahedralized(const ps_hierarchy_def* def, const TriangleMesh& closed_surface) {
  TetrahedralizeOptions options;
  if (def) {
    if (!(def->tet_cell_size >= 0.0) || !std::isfinite(def->tet_cell_size))
      api_fail(PS_ERROR_INVALID_ARGUMENT, "tet_cell_size = " + std::to_string(def->tet_cell_size) +
                                              " is invalid: it must be a finite length >= 0 (m)");
    options.cell_size = def->tet_cell_size;
  }
  return tetrahedralize_surface(closed_surface, options);
}

}  // namespace

TriangleMesh borrowed_mesh(const double* vertices, std::size_t num_vertices, const int32_t* faces,
                           std::size_t num_faces) {
  require(vertices, "vertices");
  require(faces, "faces");
  constexpr size_t kMax = static_cast<size_t>(std::numeric_limits<int32_t>::max() / 3);
  if (num_vertices == 0 || num_faces == 0 || num_vertices > kMax || num_faces > kMax)
    api_fail(PS_ERROR_INVALID_MESH, "a mesh needs 1 to " + std::to_string(kMax) +
                                        " vertices and faces, got " + std::to_string(num_vertices) +
                                        " vertices and " + std::to_string(num_faces) + " faces");
  TriangleMesh mesh;
  mesh.vertices = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      vertices, static_cast<Eigen::Index>(num_vertices), 3);
  mesh.faces = Eigen::Map<const Faces>(faces, static_cast<Eigen::Index>(num_faces), 3);
  return mesh;
}

const TriangleMesh& level_mesh(const ps_hierarchy& hierarchy, int32_t level) {
  const int32_t n = hierarchy.num_levels();
  if (level < 0 || level >= n)
    api_fail(PS_ERROR_OUT_OF_RANGE, "level " + std::to_string(level) +
                                        " does not exist (levels 0 to " + std::to_string(n - 1) +
                                        ")");
  return hierarchy.solid ? hierarchy.boundaries[level] : hierarchy.shared->levels[level].rest;
}

}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API void ps_hierarchy_def_init(ps_hierarchy_def* def) {
  if (!def) return;
  *def = ps_hierarchy_def{};
  def->tet_size_factor = TetHierarchyOptions{}.size_factor;
  def->internal_cookie = kHierarchyCookie;
}

PS_API int32_t ps_hierarchy_create(const ps_hierarchy_def* def, const double* vertices,
                                   size_t num_vertices, const int32_t* faces, size_t num_faces,
                                   ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create", [&] {
    require(out, "out");
    *out = build(def, borrowed_mesh(vertices, num_vertices, faces, num_faces)).release();
  });
}

PS_API int32_t ps_hierarchy_create_from_file(const ps_hierarchy_def* def, const char* path,
                                             ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create_from_file", [&] {
    require(out, "out");
    require(path, "path");
    hierarchy_options(def, 0);  // a bad def is reported before the file is read
    *out = build(def, read_mesh(path)).release();
  });
}

PS_API int32_t ps_hierarchy_create_solid(const ps_hierarchy_def* def, const double* vertices,
                                         size_t num_vertices, const int32_t* tets, size_t num_tets,
                                         ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create_solid", [&] {
    require(out, "out");
    *out = build_solid(def, borrowed_tet_mesh(vertices, num_vertices, tets, num_tets)).release();
  });
}

PS_API int32_t ps_hierarchy_create_solid_from_surface(const ps_hierarchy_def* def,
                                                      const double* vertices, size_t num_vertices,
                                                      const int32_t* faces, size_t num_faces,
                                                      ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create_solid_from_surface", [&] {
    require(out, "out");
    const TriangleMesh surface = borrowed_mesh(vertices, num_vertices, faces, num_faces);
    *out = build_solid(def, tetrahedralized(def, surface)).release();
  });
}

PS_API int32_t ps_hierarchy_create_solid_from_file(const ps_hierarchy_def* def, const char* path,
                                                   ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create_solid_from_file", [&] {
    require(out, "out");
    require(path, "path");
    hierarchy_options(def, 0);  // a bad def is reported before the file is read
    const TetMesh finest =
        is_tet_mesh_path(path) ? read_tet_mesh(path) : tetrahedralized(def, read_mesh(path));
    *out = build_solid(def, finest).release();
  });
}

PS_API int32_t ps_hierarchy_is_solid(const ps_hierarchy* hierarchy, int32_t* out) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_is_solid", [&] {
    require(hierarchy, "hierarchy");
    require(out, "out");
    *out = hierarchy->solid ? 1 : 0;
  });
}

PS_API int32_t ps_hierarchy_get_tets(const ps_hierarchy* hierarchy, int32_t level, int32_t* out,
                                     size_t capacity, size_t* count) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_get_tets", [&] {
    require(hierarchy, "hierarchy");
    level_mesh(*hierarchy, level);  // range check
    if (!hierarchy->solid)
      return copy_out(static_cast<const int32_t*>(nullptr), 0, out, capacity, count);
    const Tets& tets = hierarchy->solid->levels[level].tets;
    copy_out(tets.data(), static_cast<size_t>(tets.size()), out, capacity, count);
  });
}

PS_API int32_t ps_hierarchy_load(const char* path, ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_load", [&] {
    require(out, "out");
    require(path, "path");
    MeshHierarchy loaded = load_hierarchy(path);
    try {
      *out = std::make_unique<ps_hierarchy>(std::move(loaded)).release();
    } catch (const Error& e) {  // a coarse level that passes the checks but not a prolongation
      fail(e.status(), std::string(path) + ": " + e.what());
    }
  });
}

PS_API int32_t ps_hierarchy_save(const ps_hierarchy* hierarchy, const char* path) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_save", [&] {
    require(hierarchy, "hierarchy");
    require(path, "path");
    save_hierarchy(hierarchy->shells(), path);
  });
}

PS_API int32_t ps_hierarchy_destroy(ps_hierarchy* hierarchy) {
  return guarded(nullptr, "ps_hierarchy_destroy", [&] {
    if (!hierarchy) return;
    if (const int users = hierarchy->simulations.load(); users > 0)
      api_fail(PS_ERROR_WRONG_CALL_ORDER, std::to_string(users) +
                                              " simulation(s) still use this hierarchy; destroy "
                                              "them first");
    delete hierarchy;
  });
}

PS_API const char* ps_hierarchy_last_error(const ps_hierarchy* hierarchy) {
  return hierarchy ? hierarchy->last_error.c_str() : ps_last_error();
}

PS_API int32_t ps_hierarchy_num_levels(const ps_hierarchy* hierarchy, int32_t* out) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_num_levels", [&] {
    require(hierarchy, "hierarchy");
    require(out, "out");
    *out = hierarchy->num_levels();
  });
}

PS_API int32_t ps_hierarchy_level_size(const ps_hierarchy* hierarchy, int32_t level,
                                       size_t* num_vertices, size_t* num_faces) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_level_size", [&] {
    require(hierarchy, "hierarchy");
    const TriangleMesh& mesh = level_mesh(*hierarchy, level);
    if (num_vertices) *num_vertices = static_cast<size_t>(mesh.num_vertices());
    if (num_faces) *num_faces = static_cast<size_t>(mesh.num_faces());
  });
}

PS_API int32_t ps_hierarchy_get_rest_positions(const ps_hierarchy* hierarchy, int32_t level,
                                               double* out, size_t capacity, size_t* count) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_get_rest_positions",
                 [&] {
                   require(hierarchy, "hierarchy");
                   const TriangleMesh& mesh = level_mesh(*hierarchy, level);
                   copy_out(mesh.vertices.data(), static_cast<size_t>(mesh.vertices.size()), out,
                            capacity, count);
                 });
}

PS_API int32_t ps_hierarchy_get_faces(const ps_hierarchy* hierarchy, int32_t level, int32_t* out,
                                      size_t capacity, size_t* count) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_get_faces", [&] {
    require(hierarchy, "hierarchy");
    const TriangleMesh& mesh = level_mesh(*hierarchy, level);
    copy_out(mesh.faces.data(), static_cast<size_t>(mesh.faces.size()), out, capacity, count);
  });
}

PS_API int32_t ps_hierarchy_prolong(const ps_hierarchy* hierarchy, int32_t level,
                                    const double* positions, size_t count, double* out,
                                    size_t capacity, size_t* out_count) {
  return guarded(hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_prolong", [&] {
    require(hierarchy, "hierarchy");
    require(positions, "positions");
    const TriangleMesh& mesh = level_mesh(*hierarchy, level);
    if (count != static_cast<size_t>(mesh.vertices.size()))
      api_fail(PS_ERROR_INVALID_ARGUMENT, "positions has " + std::to_string(count) +
                                              " doubles; level " + std::to_string(level) +
                                              " needs " + std::to_string(mesh.vertices.size()) +
                                              " (3 per vertex)");
    const int32_t finest = hierarchy->num_levels() - 1;
    if (!out) {  // size query
      const auto n = static_cast<size_t>(level_mesh(*hierarchy, finest).vertices.size());
      copy_out(static_cast<const double*>(nullptr), n, out, capacity, out_count);
      return;
    }
    const Positions coarse = Eigen::Map<const Positions>(positions, mesh.num_vertices(), 3);
    if (!coarse.allFinite())
      api_fail(PS_ERROR_INVALID_ARGUMENT, "positions contain NaN or infinite values");
    const Positions fine = prolonged_to_finest(*hierarchy, level, coarse);
    copy_out(fine.data(), static_cast<size_t>(fine.size()), out, capacity, out_count);
  });
}

PS_API int32_t ps_hierarchy_num_expansion_batches(const ps_hierarchy* hierarchy, int32_t level,
                                                  int32_t* out) {
  return guarded(
      hierarchy ? &hierarchy->last_error : nullptr, "ps_hierarchy_num_expansion_batches", [&] {
        require(hierarchy, "hierarchy");
        require(out, "out");
        level_mesh(*hierarchy, level);  // range check
        const MeshHierarchy& h = hierarchy->shells();
        if (level == h.finest())
          api_fail(PS_ERROR_OUT_OF_RANGE,
                   "the finest level " + std::to_string(level) + " is not refined further");
        *out = static_cast<int32_t>(h.expansion_batches[level].size());
      });
}

}  // extern "C"
