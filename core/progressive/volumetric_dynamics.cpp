#include "progressive/volumetric_dynamics.hpp"

#include <string>

#include "common/error.hpp"
#include "mesh/tet_boundary.hpp"
#include "progressive/level_refinement.hpp"
#include "progressive/scene_level_counts.hpp"

namespace progsim {
namespace {

/// Throws unless a handle's or load's `region` selects vertices on every level: the levels share
/// no vertices, so only a box says which of a coarse level's are meant.
void check_level_regions(const std::optional<VertexBox>& region, const TetHierarchy& hierarchy,
                         const std::string& scene_name, const char* kind, std::size_t index) {
  const std::string what = std::string(kind) + "[" + std::to_string(index) + "]";
  if (!region)
    fail(Status::unsupported, scene_name + ": " + what +
                                  " lists vertices of the finest mesh, which coarse tet levels "
                                  "do not share: select them by a 'box' instead");
  for (int level = 0; level + 1 < hierarchy.num_levels(); ++level)
    if (region->select(hierarchy.levels[level].vertices).empty())
      fail(Status::invalid_scene, scene_name + ": " + what + ".box holds no vertex of tet level " +
                                      std::to_string(level) +
                                      " (coarse boundaries may lie up to an edge inside the "
                                      "finest's: enlarge the box)");
}

/// Throws unless the driver can animate `scene` over `hierarchy`.
void check_volumetric_scene(const Scene& scene, const TetHierarchy& hierarchy) {
  validate_scene(scene);
  if (scene.mode != StepMode::dynamic)
    fail(Status::invalid_scene, scene.name +
                                    ": volumetric progressive dynamics animates dynamic "
                                    "scenes");
  if (scene.bodies.size() != 1 || !is_solid(scene.bodies[0]))
    fail(Status::unsupported, scene.name +
                                  ": volumetric progressive dynamics animates one "
                                  "volumetric body so far");
  if (hierarchy.levels.size() < 2 || hierarchy.to_finer.size() + 1 != hierarchy.levels.size())
    fail(Status::invalid_argument, scene.name +
                                       ": a tet hierarchy needs at least two levels and "
                                       "one prolongation between each pair");
  const TetMesh& finest = hierarchy.levels.back();
  const Body& body = scene.bodies[0];
  if (!same_array(finest.tets, body.tets) || !same_array(finest.vertices, body.mesh.vertices))
    fail(Status::invalid_argument,
         scene.name + ": the hierarchy's finest level is not the body's mesh");
  for (std::size_t i = 0; i < scene.handles.size(); ++i)
    check_level_regions(scene.handles[i].region, hierarchy, scene.name, "handles", i);
  for (std::size_t i = 0; i < scene.loads.size(); ++i)
    check_level_regions(scene.loads[i].region, hierarchy, scene.name, "loads", i);
}

/// `selections` (handles or loads) with the vertices their boxes hold on `vertices`.
template <class Selection>
void select_on_level(std::vector<Selection>& selections, const Positions& vertices) {
  for (Selection& s : selections) s.vertices = s.region->select(vertices);
}

/// W as a level transfer: positions and velocities alike (VPD §3.3: P = W, V = W).
LevelTransfer tet_transfer(const ProlongationMatrix& w) {
  const auto apply = [&w](const Vector& x) {
    return Vector(as_dofs(Positions(w * as_positions(x))));
  };
  return {apply, apply, &w, {}};
}

}  // namespace

TetHierarchy build_scene_tet_hierarchy(const Scene& scene, HierarchyProgress progress, void* user) {
  validate_scene(scene);
  if (scene.bodies.size() != 1 || !is_solid(scene.bodies[0]))
    fail(Status::unsupported, scene.name +
                                  ": volumetric progressive dynamics animates one "
                                  "volumetric body so far");
  const Body& body = scene.bodies[0];
  const TetMesh finest{body.mesh.vertices, body.tets};
  const int boundary_vertices = static_cast<int>(extract_tet_boundary(finest).volume_vertex.size());
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts = scene_coarse_counts(scene.progressive, boundary_vertices);
  return build_tet_hierarchy(finest, options, progress, user);
}

VolumetricDynamics::VolumetricDynamics(Scene scene, std::shared_ptr<const TetHierarchy> hierarchy)
    : scene_(std::move(scene)),
      hierarchy_(std::move(hierarchy)),
      levels_(hierarchy_ ? static_cast<int>(hierarchy_->levels.size()) - 1 : 0) {
  if (!hierarchy_) fail(Status::invalid_argument, "VolumetricDynamics: no tet hierarchy");
  check_volumetric_scene(scene_, *hierarchy_);
  for (const TetMesh& mesh : hierarchy_->levels) surface_faces_.push_back(tet_boundary_faces(mesh));
  restart();
}

VolumetricDynamics::~VolumetricDynamics() = default;

void VolumetricDynamics::update_scene(Scene scene) {
  check_volumetric_scene(scene, *hierarchy_);
  levels_.update_preview_scene(scene_, scene, level_scene(scene, 0));
  scene_ = std::move(scene);
}

Scene VolumetricDynamics::level_scene(const Scene& scene, int level) const {
  Scene s = scene;
  const TetMesh& mesh = hierarchy_->levels.at(level);
  Body& body = s.bodies[0];
  body.mesh.vertices = mesh.vertices;
  body.mesh.faces = surface_faces_.at(level);
  body.tets = mesh.tets;
  select_on_level(s.handles, mesh.vertices);  // by box: check_volumetric_scene saw them all
  select_on_level(s.loads, mesh.vertices);
  return s;
}

std::unique_ptr<LevelSimulation> VolumetricDynamics::make_level(int level, LevelStart start) const {
  SimulationLevel own;  // the level's own mesh and elastics (VPD §3.2)
  if (level > 0) own.consistency_weight = scene_.progressive.consistency_weight;
  return std::make_unique<LevelSimulation>(level_scene(level), std::move(own), std::move(start));
}

std::unique_ptr<LevelSimulation> VolumetricDynamics::direct_level(int level) const {
  check_level_exists(level, finest());
  return std::make_unique<LevelSimulation>(level_scene(level));
}

void VolumetricDynamics::refine_window(StepWindow window, const RefineProgress& progress) {
  levels_.check_refinable(window);
  const int coarse = level();
  levels_.refine([&](LevelStart start) { return make_level(coarse + 1, std::move(start)); },
                 tet_transfer(hierarchy_->to_finer[coarse]), scene_.progressive, scene_.time_step,
                 window, progress);
}

}  // namespace progsim
