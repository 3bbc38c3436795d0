#include "sim/load_forces.hpp"

#include <algorithm>
#include <string>

#include "energy/force_couple.hpp"
#include "energy/lumped_mass.hpp"
#include "hierarchy/prolongation.hpp"

namespace progsim {
namespace {

/// The load's vertices in the model's numbering, sorted, each once.
std::vector<int> model_vertices(const Load& load, const ShellModel& model) {
  std::vector<int> vertices;
  for (int v : load.vertices) vertices.push_back(model.vertex_offset[load.body] + v);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

/// The forces of load k on its (model) vertices.
VertexForces forces_of(const Scene& scene, std::size_t k, const ShellModel& model,
                       const Eigen::VectorXd& areas) {
  const Load& load = scene.loads[k];
  VertexForces out;
  out.vertices = model_vertices(load, model);
  const auto n = static_cast<Eigen::Index>(out.vertices.size());
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  Positions points(n, 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    const int v = out.vertices[j];
    points.row(j) = model.rest.vertices.row(v);
    if (load.distribution == LoadDistribution::mass) weights[j] = model.vertex_masses[v];
    if (load.distribution == LoadDistribution::area) weights[j] = areas[v];
  }
  const bool each = load.distribution == LoadDistribution::per_vertex;
  out.forces.resize(n, 3);
  for (Eigen::Index j = 0; j < n; ++j)  // f_i = F w_i / Σ w (or F on each vertex)
    out.forces.row(j) =
        (each ? load.force : Vec3(load.force * weights[j] / weights.sum())).transpose();
  out.forces += couple_forces(points, weights, load.moment_axis, load.moment,
                              "loads[" + std::to_string(k) + "].moment");
  return out;
}

}  // namespace

std::vector<VertexForces> load_forces(const Scene& scene, const ShellModel& model) {
  std::vector<VertexForces> loads;
  if (scene.loads.empty()) return loads;
  const Eigen::VectorXd areas = lumped_vertex_areas(model.rest.vertices, model.rest.faces);
  for (std::size_t k = 0; k < scene.loads.size(); ++k)
    loads.push_back(forces_of(scene, k, model, areas));
  return loads;
}

std::vector<VertexForces> restrict_loads(const std::vector<VertexForces>& loads,
                                         const MeshHierarchy& hierarchy, int level) {
  if (level == hierarchy.finest()) return loads;
  const TriangleMesh& coarse = hierarchy.levels[level].rest;
  const ProlongationMatrix u =
      intrinsic_matrix(hierarchy.to_finest[level], coarse.faces, coarse.num_vertices());
  std::vector<VertexForces> restricted;
  for (const VertexForces& load : loads) {
    Positions fine = Positions::Zero(u.rows(), 3);
    for (std::size_t j = 0; j < load.vertices.size(); ++j)
      fine.row(load.vertices[j]) = load.forces.row(j);
    const Positions gathered = u.transpose() * fine;  // f_l = Uᵀ f_L
    VertexForces out;
    for (Eigen::Index v = 0; v < gathered.rows(); ++v)
      if (!gathered.row(v).isZero(0.0)) out.vertices.push_back(static_cast<int>(v));
    out.forces.resize(static_cast<Eigen::Index>(out.vertices.size()), 3);
    for (std::size_t j = 0; j < out.vertices.size(); ++j)
      out.forces.row(j) = gathered.row(out.vertices[j]);
    restricted.push_back(std::move(out));
  }
  return restricted;
}

}  // namespace progsim
