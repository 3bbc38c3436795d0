#include "progressive/volumetric_dynamics.hpp"

#include <string>

#include "common/error.hpp"
#include "mesh/tet_boundary.hpp"
#include "progressive/level_refinement.hpp"

namespace progsim {
namespace {

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
  if (!scene.handles.empty() || !scene.loads.empty())
    fail(Status::unsupported, scene.name +
                                  ": handles and loads select vertices of the finest "
                                  "mesh, which coarse tet levels do not share yet");
  if (hierarchy.levels.size() < 2 || hierarchy.to_finer.size() + 1 != hierarchy.levels.size())
    fail(Status::invalid_argument, scene.name +
                                       ": a tet hierarchy needs at least two levels and "
                                       "one prolongation between each pair");
  const TetMesh& finest = hierarchy.levels.back();
  const Body& body = scene.bodies[0];
  if (finest.tets != body.tets || finest.vertices != body.mesh.vertices)
    fail(Status::invalid_argument,
         scene.name + ": the hierarchy's finest level is not the body's mesh");
}

/// W as a level transfer: positions and velocities alike (VPD §3.3: P = W, V = W).
LevelTransfer tet_transfer(const ProlongationMatrix& w) {
  const auto apply = [&w](const Vector& x) {
    return Vector(as_dofs(Positions(w * as_positions(x))));
  };
  return {apply, apply, &w};
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
  const ProgressiveSettings& p = scene.progressive;
  TetHierarchyOptions options;
  options.coarse_boundary_vertex_counts =
      !p.level_vertices.empty()
          ? p.level_vertices
          : geometric_level_counts(boundary_vertices, p.coarsening_ratio, p.coarse_levels);
  return build_tet_hierarchy(finest, options, progress, user);
}

VolumetricDynamics::VolumetricDynamics(Scene scene, std::shared_ptr<const TetHierarchy> hierarchy)
    : scene_(std::move(scene)), hierarchy_(std::move(hierarchy)) {
  if (!hierarchy_) fail(Status::invalid_argument, "VolumetricDynamics: no tet hierarchy");
  check_volumetric_scene(scene_, *hierarchy_);
  for (const TetMesh& mesh : hierarchy_->levels) surface_faces_.push_back(tet_boundary_faces(mesh));
  preview_ = make_level(0);
  trajectories_.emplace_back(0, preview_->model().rest.num_vertices());
  trajectories_[0].append(preview_->dofs(), preview_->velocities());
  records_.push_back(start_record(*preview_));
  masses_.push_back(preview_->model().vertex_masses);
}

VolumetricDynamics::~VolumetricDynamics() = default;

Scene VolumetricDynamics::level_scene(int level) const {
  Scene s = scene_;
  const TetMesh& mesh = hierarchy_->levels.at(level);
  Body& body = s.bodies[0];
  body.mesh.vertices = mesh.vertices;
  body.mesh.faces = surface_faces_.at(level);
  body.tets = mesh.tets;
  return s;
}

std::unique_ptr<LevelSimulation> VolumetricDynamics::make_level(int level) const {
  SimulationLevel own;  // the level's own mesh and elastics (VPD §3.2)
  if (level > 0) own.consistency_weight = scene_.progressive.consistency_weight;
  return std::make_unique<LevelSimulation>(level_scene(level), std::move(own));
}

void VolumetricDynamics::set_preview_velocities(const Vector& velocities) {
  if (trajectories_[0].num_frames() > 1)
    fail(Status::wrong_call_order, "set_preview_velocities: the preview has already stepped");
  preview_->set_velocities(velocities);
  trajectories_[0] = Trajectory(0, preview_->model().rest.num_vertices());
  trajectories_[0].append(preview_->dofs(), preview_->velocities());
}

StepRecord VolumetricDynamics::step_preview() {
  if (level() > 0)
    fail(Status::wrong_call_order,
         "step_preview: level " + std::to_string(level()) + " has been refined from this preview");
  StepRecord step = preview_->step();
  trajectories_[0].append(preview_->dofs(), preview_->velocities());
  add_dynamic_step(records_[0], step, 0.0, 0.0);
  records_[0].terms = preview_->term_totals();
  return step;
}

void VolumetricDynamics::refine(const RefineProgress& progress) {
  const int coarse = level(), fine = coarse + 1;
  if (coarse >= finest())
    fail(Status::out_of_range,
         "level " + std::to_string(coarse) + " is the finest level; there is nothing to refine");
  if (trajectories_[coarse].num_frames() < 2)
    fail(Status::wrong_call_order, "refine: preview at least one step first");
  std::unique_ptr<LevelSimulation> sim = make_level(fine);
  Trajectory frames(fine, sim->model().rest.num_vertices());
  DynamicLevelRecord record = start_record(*sim);
  const CoarserLevel from{&trajectories_[coarse], &masses_[coarse], &records_[0], coarse};
  animate_finer_level(*sim, from, tet_transfer(hierarchy_->to_finer[coarse]), scene_.progressive,
                      scene_.time_step, progress, frames, record);
  masses_.push_back(sim->model().vertex_masses);
  trajectories_.push_back(std::move(frames));
  records_.push_back(std::move(record));
}

void VolumetricDynamics::check_level(int level) const {
  if (level < 0 || level > this->level())
    fail(Status::out_of_range, "level " + std::to_string(level) +
                                   " has not been computed (levels 0 to " +
                                   std::to_string(this->level()) + " have)");
}

int VolumetricDynamics::num_frames(int level) const {
  check_level(level);
  return trajectories_[level].num_frames();
}

void VolumetricDynamics::read_frame(int level, int frame, Positions& positions,
                                    Positions& velocities) const {
  check_level(level);
  Vector x, v;
  trajectories_[level].read(frame, x, v);
  positions = as_positions(x);
  velocities = as_positions(v);
}

const DynamicLevelRecord& VolumetricDynamics::record(int level) const {
  check_level(level);
  return records_[level];
}

}  // namespace progsim
