#include "progressive/patch_relaxation.hpp"

#include <cmath>

#include "contact/contact_potential.hpp"
#include "energy/inertia.hpp"
#include "problem/problem.hpp"

namespace progsim {
namespace {

/// Additive CCD iterations per pair and step of a relaxation (ContactPotential default: 10⁶).
constexpr int kRelaxationCcdIterations = 10000;

}  // namespace

NewtonReport relax_toward_targets(const CollisionMesh& mesh, const Positions& targets,
                                  Positions& points, const std::vector<int>& free, double dhat,
                                  const std::optional<GroundPlane>& ground, double length) {
  const int n = mesh.num_shell_vertices;
  Problem problem(3 * n);
  auto spring = std::make_unique<Inertia>(Eigen::VectorXd::Ones(n), 1.0);  // ½‖x − x̂‖²
  spring->set_target(as_dofs(targets));
  problem.add_term(std::move(spring));
  // κ: a pair at half the gap resists a pull of a tenth of an edge toward the target.
  const double edge = length / std::sqrt(static_cast<double>(n));
  auto contact = std::make_unique<ContactPotential>(
      mesh, dhat, ContactPotential::stiffness_for_force(0.1 * edge, dhat, 2.0 * mesh.max_offset()),
      ground);
  contact->set_obstacle_positions(points.bottomRows(mesh.num_obstacle_vertices));
  std::vector<char> moving(mesh.num_vertices(), 0);  // the rest keep their distances
  for (int v : free) moving[v] = 1;
  contact->set_moving_vertices(std::move(moving));
  // A stuck split's new vertex can sit a fraction of a micrometre from its partner's faces and
  // be pulled millimetres toward its target: additive CCD then needs ~motion/gap iterations
  // per pair and line search (10⁵–10⁶; a relaxation on a real mesh took minutes, issue 28).
  // Capped, such a pair limits the step to ~9000 gaps instead, and the next iteration goes on
  // (10³ measured worse on the lion: more, shorter relaxation steps, 1.6 s → 5.8 s at level 1).
  contact->set_ccd_max_iterations(kRelaxationCcdIterations);
  Vector x = as_dofs(Positions(points.topRows(n)));
  contact->fit_offsets(x);
  problem.add_term(std::move(contact));
  std::vector<bool> fixed(3 * n, true);
  for (int v : free)
    for (int d = 0; d < 3; ++d) fixed[3 * v + d] = false;
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  NewtonSettings settings;
  settings.max_iterations = 50;
  NewtonSolver solver;
  const NewtonReport report = solver.minimize(problem, x, settings, 1.0, length);
  points.topRows(n) = as_positions(x);
  return report;
}

}  // namespace progsim
