#include "sim/run_summary.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "sim/record_json.hpp"

namespace progsim {

void RunSummary::add(const StepRecord& r) {
  ++steps_;
  iterations_ += r.newton.iterations;
  max_iterations_ = std::max(max_iterations_, r.newton.iterations);
  seconds_ += r.seconds;
  final_energy_ = r.newton.energy;
  final_gradient_norm_ = r.newton.gradient_norm;
  phases_ += r.newton.timings;
  ++stops_[stop_name(r.newton.stop)];
  final_reactions_ = r.reactions;
}

std::string RunSummary::to_json(const LevelSimulation& sim) const {
  nlohmann::json terms = nlohmann::json::array();
  for (const TermStats& t : sim.term_totals())
    terms.push_back({{"name", t.name},
                     {"value_evaluations", t.value_evaluations},
                     {"gradient_evaluations", t.gradient_evaluations},
                     {"hessian_evaluations", t.hessian_evaluations},
                     {"seconds", t.seconds}});
  nlohmann::json j = {{"scene", sim.scene().name},
                      {"mode", sim.scene().mode == StepMode::dynamic ? "dynamic" : "quasistatic"},
                      {"vertices", sim.model().rest.num_vertices()},
                      {"faces", sim.model().rest.num_faces()},
                      {"effects", effect_names(sim.scene().effects)},
                      {"steps", steps_},
                      {"simulated_time", sim.time()},
                      {"wall_seconds", seconds_},
                      {"newton_iterations", iterations_},
                      {"max_newton_iterations_in_a_step", max_iterations_},
                      {"stops", stops_},
                      {"final_energy", final_energy_},
                      {"final_gradient_norm", final_gradient_norm_},
                      {"phase_seconds",
                       {{"assembly", phases_.assembly},
                        {"analysis", phases_.analysis},
                        {"factorization", phases_.factorization},
                        {"solve", phases_.solve},
                        {"line_search", phases_.line_search}}},
                      {"terms", terms}};
  if (!final_reactions_.empty()) j["final_reactions"] = reactions_json(final_reactions_);
  return j.dump(2);
}

std::string RunSummary::to_text(const LevelSimulation& sim) const {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "scene %s: %d vertices, %d faces, %d steps, %.3f s simulated\n",
                sim.scene().name.c_str(), sim.model().rest.num_vertices(),
                sim.model().rest.num_faces(), steps_, sim.time());
  out += line;
  std::snprintf(line, sizeof line, "wall time %.3f s, Newton iterations %d (max %d per step)\n",
                seconds_, iterations_, max_iterations_);
  out += line;
  for (const auto& [stop, count] : stops_) {
    std::snprintf(line, sizeof line, "  steps ending '%s': %d\n", stop.c_str(), count);
    out += line;
  }
  std::snprintf(line, sizeof line,
                "phases: assembly %.3f s, analysis %.3f s, factorization %.3f s, solve %.3f s, "
                "line search %.3f s\n",
                phases_.assembly, phases_.analysis, phases_.factorization, phases_.solve,
                phases_.line_search);
  out += line;
  out += "term              value  gradient  hessian   seconds\n";
  for (const TermStats& t : sim.term_totals()) {
    std::snprintf(line, sizeof line, "%-14s %8lld %9lld %8lld %9.3f\n", t.name.c_str(),
                  static_cast<long long>(t.value_evaluations),
                  static_cast<long long>(t.gradient_evaluations),
                  static_cast<long long>(t.hessian_evaluations), t.seconds);
    out += line;
  }
  for (std::size_t h = 0; h < final_reactions_.size(); ++h) {
    const Vec3& f = final_reactions_[h].force;
    std::snprintf(line, sizeof line, "handle %zu reaction: force (%.6g, %.6g, %.6g) N\n", h, f.x(),
                  f.y(), f.z());
    out += line;
  }
  return out;
}

}  // namespace progsim
