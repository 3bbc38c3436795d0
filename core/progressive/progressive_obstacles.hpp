#pragma once
/// @file Progressive collision objects (PSQ, Zhang et al. 2023, §4.6): obstacles decimated into a
/// hierarchy of their own, with as many levels as the shell's. Level l of the simulation meets
/// the obstacles' level-l meshes; refinement expands them with PSQ §4.4's safe refinement
/// against the refined shell, and the level's scripted-motion rounds then carry them to their
/// scripted positions (PSQ drives them there with an augmented Lagrangian instead).
#include <memory>
#include <vector>

#include "hierarchy/mesh_hierarchy.hpp"
#include "progressive/safe_refinement.hpp"
#include "scene/scene.hpp"

namespace progsim {

/// The shell a refinement of the obstacles must stay clear of.
struct ShellSurface {
  const Positions* positions;  ///< (|V| × 3) the shell's refined start
  const Faces* faces;          ///< (|F| × 3) its faces
  double offset;               ///< the largest contact offset ξ of its vertices (m)
};

/// The scene's progressive obstacles (Obstacle::progressive) merged into one mesh, and its
/// hierarchy. Obstacles that are not progressive keep their mesh on every level.
class ObstacleHierarchy {
 public:
  /// Decimates the progressive obstacles of `scene` along with the shell: level l keeps
  /// |V_obstacles| · √(shell_vertices[l] / shell_vertices.back()) vertices, each at the rest
  /// position of an input vertex (a convex obstacle's coarse copies lie inside it). Throws
  /// Error(invalid_scene) naming the obstacles if they cannot be decimated that far.
  ObstacleHierarchy(const Scene& scene, const std::vector<int>& shell_vertices);

  /// Whether any obstacle is progressive.
  bool empty() const { return progressive_.empty(); }
  int num_levels() const;
  /// Replaces each progressive obstacle's mesh in `scene` by its level-`level` mesh (a subset
  /// of its vertices, at their positions in the scene's mesh).
  void use_level(int level, Scene& scene) const;
  /// Refines the stacked obstacle positions of level `level` (scene order, as the contact term
  /// holds them) into those of level + 1: each progressive obstacle by safe_refinement() toward
  /// its prolongation P^l_{l+1} (its scripted position when its script is rigid), staying clear
  /// of `shell`; the others as they are. Throws like safe_refinement().
  Positions refine(int level, const Positions& stacked, const ShellSurface& shell, double dhat,
                   SafeRefinementStats* stats = nullptr) const;
  /// The merged obstacles' hierarchy (levels of all progressive obstacles in scene order).
  const MeshHierarchy& hierarchy() const { return *hierarchy_; }

 private:
  /// The index in progressive_ of scene obstacle `k`, −1 if it is not progressive.
  int progressive_index(int k) const;
  /// Vertices of scene obstacle `k` at `level`.
  int vertices_at(int k, int level) const;

  std::vector<int> progressive_;        // scene indices of the progressive obstacles
  std::vector<int> obstacle_vertices_;  // per scene obstacle, its mesh's vertex count
  /// first_[level][p]: the first vertex of progressive obstacle p in the merged level (size
  /// progressive_.size() + 1 per level).
  std::vector<std::vector<int>> first_;
  std::shared_ptr<const MeshHierarchy> hierarchy_;
};

}  // namespace progsim
