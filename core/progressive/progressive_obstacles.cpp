#include "progressive/progressive_obstacles.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "hierarchy/level_prolongation.hpp"

namespace progsim {
namespace {

/// Coarse level sizes round(n · √(shell[l] / shell.back())): the shell's coarsening, halved
/// in log scale. An obstacle coarsened as far as the shell would make each refinement push the
/// shell out by the sagitta of its coarse faces (about 1 cm on the drape's 0.25 m sphere at 40
/// vertices, stretching the cloth pinned over it past its strain limit); obstacles cost only
/// contact, so they can stay finer.
std::vector<int> coarse_counts(int n, const std::vector<int>& shell) {
  std::vector<int> counts;
  for (std::size_t l = 0; l + 1 < shell.size(); ++l)
    counts.push_back(
        static_cast<int>(std::lround(n * std::sqrt(static_cast<double>(shell[l]) / shell.back()))));
  return counts;
}

/// "sphere, lid": the names of the obstacles `which`, for messages.
std::string names(const Scene& scene, const std::vector<int>& which) {
  std::string out;
  for (int k : which) out += (out.empty() ? "" : ", ") + scene.obstacles[k].name;
  return out;
}

}  // namespace

ObstacleHierarchy::ObstacleHierarchy(const Scene& scene, const std::vector<int>& shell_vertices) {
  for (std::size_t k = 0; k < scene.obstacles.size(); ++k) {
    obstacle_vertices_.push_back(scene.obstacles[k].mesh.num_vertices());
    if (scene.obstacles[k].progressive) progressive_.push_back(static_cast<int>(k));
  }
  if (progressive_.empty()) return;
  std::vector<const TriangleMesh*> meshes;
  for (int k : progressive_) meshes.push_back(&scene.obstacles[k].mesh);
  const TriangleMesh merged = merge_meshes(meshes);
  HierarchyOptions options;
  options.coarse_vertex_counts = coarse_counts(merged.num_vertices(), shell_vertices);
  options.keep_input_positions = true;  // a coarse copy of a convex obstacle lies inside it
  try {
    hierarchy_ = std::make_shared<const MeshHierarchy>(build_hierarchy(merged, options));
  } catch (const Error& e) {
    if (e.status() == Status::cancelled) throw;
    fail(Status::invalid_scene, "progressive obstacles (" + names(scene, progressive_) +
                                    "): cannot build their coarse levels: " + e.what());
  }
  for (const HierarchyLevel& level : hierarchy_->levels) {
    std::vector<int> first{0};
    int input = 0;  // the first input vertex of the next obstacle in the merged mesh
    for (int k : progressive_) {
      input += obstacle_vertices_[k];
      first.push_back(static_cast<int>(
          std::lower_bound(level.input_vertex.begin(), level.input_vertex.end(), input) -
          level.input_vertex.begin()));
    }
    first_.push_back(std::move(first));
  }
}

int ObstacleHierarchy::num_levels() const {
  return hierarchy_ ? hierarchy_->num_levels() : 0;
}

int ObstacleHierarchy::progressive_index(int k) const {
  const auto p = std::find(progressive_.begin(), progressive_.end(), k) - progressive_.begin();
  return p < static_cast<std::ptrdiff_t>(progressive_.size()) ? static_cast<int>(p) : -1;
}

int ObstacleHierarchy::vertices_at(int k, int level) const {
  const int p = progressive_index(k);
  return p < 0 ? obstacle_vertices_[k] : first_[level][p + 1] - first_[level][p];
}

void ObstacleHierarchy::use_level(int level, Scene& scene) const {
  if (empty()) return;
  const TriangleMesh& rest = hierarchy_->levels[level].rest;
  for (std::size_t p = 0; p < progressive_.size(); ++p) {
    const int begin = first_[level][p], end = first_[level][p + 1];
    std::vector<int> faces;  // the level's faces on this obstacle (one component each)
    for (int f = 0; f < rest.num_faces(); ++f)
      if (rest.faces(f, 0) >= begin && rest.faces(f, 0) < end) faces.push_back(f);
    TriangleMesh mesh{rest.vertices.middleRows(begin, end - begin),
                      Faces(static_cast<Eigen::Index>(faces.size()), 3)};
    for (std::size_t f = 0; f < faces.size(); ++f)
      mesh.faces.row(f) = rest.faces.row(faces[f]).array() - begin;
    scene.obstacles[progressive_[p]].mesh = std::move(mesh);
  }
}

Positions ObstacleHierarchy::refine(int level, const Positions& stacked, const ShellSurface& shell,
                                    double dhat, SafeRefinementStats* stats) const {
  if (empty() || level < 0 || level + 1 >= num_levels())
    fail(Status::out_of_range, "obstacle refinement: no level " + std::to_string(level + 1));
  const int count = static_cast<int>(obstacle_vertices_.size());
  int rows = 0;
  for (int k = 0; k < count; ++k) rows += vertices_at(k, level);
  if (stacked.rows() != rows)
    fail(Status::invalid_argument, "obstacle refinement: " + std::to_string(stacked.rows()) +
                                       " obstacle positions for " + std::to_string(rows) +
                                       " obstacle vertices at level " + std::to_string(level));
  // The progressive obstacles' rows of `stacked`, in the merged level's order.
  Positions coarse(hierarchy_->levels[level].rest.num_vertices(), 3);
  for (int k = 0, at = 0; k < count; at += vertices_at(k, level), ++k) {
    const int p = progressive_index(k), n = vertices_at(k, level);
    if (p >= 0) coarse.middleRows(first_[level][p], n) = stacked.middleRows(at, n);
  }
  const Positions target = next_level_prolongation(*hierarchy_, level)(coarse);  // PSQ eq. 7
  RefinementSurroundings around;
  around.vertex_offset.assign(hierarchy_->levels[level + 1].rest.num_vertices(), shell.offset);
  around.obstacle_positions = *shell.positions;
  around.obstacle_faces = *shell.faces;
  around.dhat = dhat;
  const Positions fine = safe_refinement(*hierarchy_, level, coarse, target, around, {}, stats);
  Positions out(rows - coarse.rows() + fine.rows(), 3);
  for (int k = 0, at = 0, to = 0; k < count; ++k) {
    const int p = progressive_index(k), n = vertices_at(k, level + 1);
    if (p >= 0)
      out.middleRows(to, n) = fine.middleRows(first_[level + 1][p], n);
    else
      out.middleRows(to, n) = stacked.middleRows(at, n);
    at += vertices_at(k, level);
    to += n;
  }
  return out;
}

}  // namespace progsim
