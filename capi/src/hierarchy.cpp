// ps_hierarchy_*: building a mesh hierarchy and reading its levels.
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>

#include "handles.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_validation.hpp"

namespace progsim::capi {
namespace {

// Faces are passed through the ABI without conversion.
static_assert(std::is_same_v<Faces::Scalar, int32_t>, "progsim::Faces must hold int32_t");

constexpr int32_t kHierarchyCookie = 0x50534844;  // "PSHD"

/// Rejects defs nobody initialised and level requests this version cannot serve yet.
void check_hierarchy_def(const ps_hierarchy_def* def) {
  if (!def) return;
  if (def->internal_cookie != kHierarchyCookie)
    api_fail(PS_ERROR_UNINITIALIZED_DEF,
             "the ps_hierarchy_def was not filled by ps_hierarchy_def_init()");
  if (def->num_coarse_levels < 0)
    api_fail(PS_ERROR_INVALID_ARGUMENT,
             "num_coarse_levels = " + std::to_string(def->num_coarse_levels) + " is negative");
  if (def->num_coarse_levels > 0)
    api_fail(PS_ERROR_UNSUPPORTED,
             "coarse levels are not available in this version: only the single-level hierarchy "
             "(num_coarse_levels = 0) can be built");
}

/// Validates mesh and wraps it as a one-level hierarchy.
std::unique_ptr<ps_hierarchy> single_level(TriangleMesh mesh) {
  validate_mesh(mesh, "mesh");
  auto hierarchy = std::make_unique<ps_hierarchy>();
  hierarchy->levels.push_back(std::move(mesh));
  return hierarchy;
}

}  // namespace

const TriangleMesh& level_mesh(const ps_hierarchy& hierarchy, int32_t level) {
  const auto n = static_cast<int32_t>(hierarchy.levels.size());
  if (level < 0 || level >= n)
    api_fail(PS_ERROR_OUT_OF_RANGE, "level " + std::to_string(level) +
                                        " does not exist (levels 0 to " + std::to_string(n - 1) +
                                        ")");
  return hierarchy.levels[level];
}

}  // namespace progsim::capi

using namespace progsim;
using namespace progsim::capi;

extern "C" {

PS_API void ps_hierarchy_def_init(ps_hierarchy_def* def) {
  if (!def) return;
  *def = ps_hierarchy_def{};
  def->internal_cookie = kHierarchyCookie;
}

PS_API int32_t ps_hierarchy_create(const ps_hierarchy_def* def, const double* vertices,
                                   size_t num_vertices, const int32_t* faces, size_t num_faces,
                                   ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create", [&] {
    require(out, "out");
    require(vertices, "vertices");
    require(faces, "faces");
    check_hierarchy_def(def);
    constexpr size_t kMax = static_cast<size_t>(std::numeric_limits<int32_t>::max() / 3);
    if (num_vertices == 0 || num_faces == 0 || num_vertices > kMax || num_faces > kMax)
      api_fail(PS_ERROR_INVALID_MESH, "a mesh needs 1 to " + std::to_string(kMax) +
                                          " vertices and faces, got " +
                                          std::to_string(num_vertices) + " vertices and " +
                                          std::to_string(num_faces) + " faces");
    TriangleMesh mesh;
    mesh.vertices = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        vertices, static_cast<Eigen::Index>(num_vertices), 3);
    mesh.faces = Eigen::Map<const Faces>(faces, static_cast<Eigen::Index>(num_faces), 3);
    *out = single_level(std::move(mesh)).release();
  });
}

PS_API int32_t ps_hierarchy_create_from_file(const ps_hierarchy_def* def, const char* path,
                                             ps_hierarchy** out) {
  return guarded(nullptr, "ps_hierarchy_create_from_file", [&] {
    require(out, "out");
    require(path, "path");
    check_hierarchy_def(def);
    *out = single_level(read_mesh(path)).release();
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
    *out = static_cast<int32_t>(hierarchy->levels.size());
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

}  // extern "C"
