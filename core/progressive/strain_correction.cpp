#include "progressive/strain_correction.hpp"

#include <cmath>

#include "common/error.hpp"
#include "energy/inertia.hpp"
#include "energy/strain_limit.hpp"
#include "energy/stretch_excess.hpp"
#include "problem/problem.hpp"
#include "sim/contact_setup.hpp"
#include "solve/newton_solver.hpp"

namespace progsim {
namespace {

/// A_i = Σ_{f ∋ i} Ā_f / 3 (m², |V|).
Eigen::VectorXd lumped_areas(const TriangleMesh& rest) {
  const Eigen::VectorXd face_area = face_areas(rest.vertices, rest.faces);
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(rest.num_vertices());
  for (int f = 0; f < rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) areas[rest.faces(f, k)] += face_area[f] / 3.0;
  return areas;
}

/// Whether all three vertices of face row f of `faces` are held.
bool face_held(const Faces& faces, Eigen::Index f, const std::vector<bool>& fixed) {
  for (int k = 0; k < 3; ++k)
    if (!fixed[3 * faces(f, k)]) return false;
  return true;
}

/// How many of `beyond` (rows of `faces`) have all their vertices held.
int held_count(const std::vector<int>& beyond, const Faces& faces, const std::vector<bool>& fixed) {
  int held = 0;
  for (int f : beyond) held += face_held(faces, f, fixed);
  return held;
}

}  // namespace

StrainCorrectionStats correct_strain(const ShellModel& model, const std::vector<bool>& fixed,
                                     std::unique_ptr<ContactPotential> contact, double length,
                                     Vector& x, const StrainCorrectionSettings& settings) {
  const int n = model.rest.num_vertices();
  if (x.size() != 3 * n || fixed.size() != static_cast<std::size_t>(3 * n))
    fail(Status::invalid_argument, "correct_strain: " + std::to_string(x.size()) + " DOFs and " +
                                       std::to_string(fixed.size()) + " fixed flags for " +
                                       std::to_string(n) + " vertices");
  StrainCorrectionStats stats;
  const LimitedFaces limited = limited_faces(model);
  if (limited.limits.empty()) return stats;
  const StrainLimit limit(model.rest.vertices, limited.faces, limited.limits, limited.band,
                          limited.stiffness);  // measures σ₁ against s_f
  const std::vector<int> beyond = limit.faces_beyond_limit(x);
  stats.strained_faces = stats.over_limit_faces = static_cast<int>(beyond.size());
  stats.stretch_before = stats.stretch_after = limit.max_stretch(x);
  const int held = held_count(beyond, limited.faces, fixed);
  if (stats.strained_faces == held) return stats;  // nothing the free vertices can mend

  Problem problem(3 * n);
  const Eigen::VectorXd areas = lumped_areas(model.rest);
  const double mean_face_area = areas.sum() / model.rest.num_faces();
  // ½ Σ A_i ‖x_i − x_i⁰‖² / Ā: a move of one edge costs about what a unit stretch excess does.
  auto proximity = std::make_unique<Inertia>(areas, std::sqrt(mean_face_area));
  proximity->set_target(x);
  problem.add_term(std::move(proximity));
  std::vector<double> targets(limited.limits);
  for (double& t : targets) t -= settings.target_band_fraction * limited.band;
  StretchExcess& excess = problem.add_term(std::make_unique<StretchExcess>(
      model.rest.vertices, limited.faces, std::move(targets), settings.first_stiffness));
  if (contact) {
    std::vector<char> moving(contact->mesh().num_vertices(), 0);  // the held keep their gaps
    for (int v = 0; v < n; ++v) moving[v] = !fixed[3 * v];
    contact->set_moving_vertices(std::move(moving));
    contact->fit_offsets(x);
    // κ: a pair at half the gap resists the pull of a tenth of an edge (as the patch relaxation).
    const double edge = std::sqrt(mean_face_area);
    contact->set_stiffness(
        ContactPotential::stiffness_for_force(0.1 * edge * areas.mean() / mean_face_area,
                                              contact->dhat(), 2.0 * contact->mesh().max_offset()));
    problem.add_term(std::move(contact));
  }
  problem.set_fixed_dofs(fixed);
  problem.finalize();
  NewtonSettings newton;
  newton.max_iterations = settings.max_iterations;
  NewtonSolver solver;
  newton.tolerance = settings.tolerance;
  for (double rho = settings.first_stiffness;; rho *= settings.growth) {
    excess.set_stiffness(rho);  // PSQ §4.4.5: pull the new vertices in until the limits hold
    const NewtonReport report = solver.minimize(problem, x, newton, 1.0, length);
    stats.newton_iterations += report.iterations;
    const int before = stats.over_limit_faces;
    stats.over_limit_faces = static_cast<int>(limit.faces_beyond_limit(x).size());
    // Done, or stuck: a stiffer pull whose solve converged without bringing a face under its
    // limit is held by what it cannot move (held vertices, contact), not by the proximity term.
    const bool stuck = rho > settings.first_stiffness && report.stop == NewtonStop::converged &&
                       stats.over_limit_faces >= before;
    if (stats.over_limit_faces <= held || stuck || rho * settings.growth > settings.max_stiffness)
      break;
  }
  stats.stretch_after = limit.max_stretch(x);
  return stats;
}

}  // namespace progsim
