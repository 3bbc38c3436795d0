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

/// The load's weight w_i of each of `vertices` (model numbering) by its distribution: the
/// lumped mass or area, or 1 with per_vertex.
Eigen::VectorXd load_weights(const Load& load, const std::vector<int>& vertices,
                             const ShellModel& model, const Eigen::VectorXd& areas) {
  const auto n = static_cast<Eigen::Index>(vertices.size());
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (load.distribution == LoadDistribution::mass) weights[j] = model.vertex_masses[vertices[j]];
    if (load.distribution == LoadDistribution::area) weights[j] = areas[vertices[j]];
  }
  return weights;
}

/// A total spread by the weights: total w_j / Σ w (or the total on each vertex with per_vertex).
template <class Total>
Total share(const Load& load, const Total& total, const Eigen::VectorXd& weights, Eigen::Index j) {
  if (load.distribution == LoadDistribution::per_vertex) return total;
  return total * weights[j] / weights.sum();
}

/// The forces of load k on its (model) vertices.
VertexForces forces_of(const Scene& scene, std::size_t k, const ShellModel& model,
                       const Eigen::VectorXd& areas) {
  const Load& load = scene.loads[k];
  VertexForces out;
  out.vertices = model_vertices(load, model);
  const auto n = static_cast<Eigen::Index>(out.vertices.size());
  const Eigen::VectorXd weights = load_weights(load, out.vertices, model, areas);
  Positions points(n, 3);
  out.forces.resize(n, 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    points.row(j) = model.rest.vertices.row(out.vertices[j]);
    out.forces.row(j) = share<Vec3>(load, load.force, weights, j).transpose();
  }
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

std::vector<NormalLoad> normal_loads(const Scene& scene, const ShellModel& model) {
  std::vector<NormalLoad> loads;
  const Eigen::VectorXd areas = lumped_vertex_areas(model.rest.vertices, model.rest.faces);
  for (const Load& load : scene.loads) {
    NormalLoad normal;
    if (load.normal_force != 0.0) {
      normal.vertices = model_vertices(load, model);
      const Eigen::VectorXd weights = load_weights(load, normal.vertices, model, areas);
      normal.magnitudes.resize(weights.size());
      for (Eigen::Index j = 0; j < weights.size(); ++j)
        normal.magnitudes[j] = share(load, load.normal_force, weights, j);
    }
    loads.push_back(std::move(normal));
  }
  return loads;
}

bool has_follower_loads(const Scene& scene) {
  for (const Load& load : scene.loads)
    if (load.normal_force != 0.0) return true;
  return false;
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
