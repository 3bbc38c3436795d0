#include "scene/scene.hpp"

#include <cmath>

#include "common/error.hpp"
#include "mesh/mesh_validation.hpp"
#include "scene/parameter_table.hpp"

namespace progsim {

int Scene::num_steps() const {
  return std::max(1, static_cast<int>(std::lround(duration / time_step)));
}

namespace {

void check(const char* group, const char* name, double value) {
  check_parameter(find_parameter(group, name), value);
}

void validate_material(const ShellMaterial& m) {
  check("material", "youngs_modulus", m.youngs_modulus);
  check("material", "poisson_ratio", m.poisson_ratio);
  check("material", "thickness", m.thickness);
  check("material", "density", m.density);
}

void validate_handle(const Scene& scene, std::size_t h) {
  const Handle& handle = scene.handles[h];
  const std::string where = "handles[" + std::to_string(h) + "]";
  if (handle.body < 0 || handle.body >= static_cast<int>(scene.bodies.size()))
    fail(Status::invalid_scene,
         where + ": body index " + std::to_string(handle.body) + " does not exist");
  const int n = scene.bodies[handle.body].mesh.num_vertices();
  if (handle.vertices.empty()) fail(Status::invalid_scene, where + ": selects no vertices");
  for (int v : handle.vertices)
    if (v < 0 || v >= n)
      fail(Status::invalid_scene, where + ": vertex " + std::to_string(v) +
                                      " is out of range [0, " + std::to_string(n) + ")");
  const HandleMotion& m = handle.motion;
  if (!m.velocity.allFinite() || !m.center.allFinite() || !m.offset.allFinite() ||
      !m.axis.allFinite() || !std::isfinite(m.angular_velocity))
    fail(Status::invalid_scene, where + ": motion has a non-finite value");
  if (m.angular_velocity != 0.0 && !(m.axis.norm() > 0.0))
    fail(Status::invalid_scene, where + ": rotation axis must be non-zero");
}

}  // namespace

void validate_scene(const Scene& scene) {
  check("simulation", "time_step", scene.time_step);
  check("simulation", "duration", scene.duration);
  check("simulation", "output_every", scene.output_every);
  check("solver", "newton_tolerance", scene.solver.tolerance);
  check("solver", "max_newton_iterations", scene.solver.max_iterations);
  if (!scene.gravity.allFinite()) fail(Status::invalid_scene, "gravity has a non-finite component");
  if (scene.bodies.empty()) fail(Status::invalid_scene, "the scene has no bodies");
  for (const Body& body : scene.bodies) {
    validate_material(body.material);
    validate_mesh(body.mesh, body.name);
    if (!std::isfinite(body.pressure) || !(body.pressure_ramp >= 0.0) ||
        !std::isfinite(body.pressure_ramp))
      fail(Status::invalid_scene,
           body.name + ": pressure and pressure_ramp must be finite, ramp ≥ 0");
  }
  for (std::size_t h = 0; h < scene.handles.size(); ++h) validate_handle(scene, h);
}

}  // namespace progsim
