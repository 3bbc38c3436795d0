#include "sim/obstacle_script.hpp"

namespace progsim {

ObstacleScript::ObstacleScript(const Scene& scene) : obstacles_(scene.obstacles) {
  for (const Obstacle& o : obstacles_) moves_ = moves_ || o.motion.moves();
}

Positions ObstacleScript::at(double t) const {
  Eigen::Index rows = 0;
  for (const Obstacle& o : obstacles_) rows += o.mesh.num_vertices();
  Positions p(rows, 3);
  Eigen::Index row = 0;
  for (const Obstacle& o : obstacles_)
    for (Eigen::Index v = 0; v < o.mesh.vertices.rows(); ++v, ++row)
      p.row(row) = o.motion.position(o.mesh.vertices.row(v).transpose(), t).transpose();
  return p;
}

std::vector<ObstacleSurface> ObstacleScript::surfaces() const {
  std::vector<ObstacleSurface> out;
  for (const Obstacle& o : obstacles_) out.push_back({&o.mesh.vertices, &o.mesh.faces, o.friction});
  return out;
}

}  // namespace progsim
