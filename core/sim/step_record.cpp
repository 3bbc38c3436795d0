#include "sim/step_record.hpp"

#include "sim/record_json.hpp"

namespace progsim {

std::string to_json_line(const StepRecord& r) {
  nlohmann::json terms = nlohmann::json::array();
  for (const TermStats& t : r.terms)
    terms.push_back({{"name", t.name},
                     {"value_evaluations", t.value_evaluations},
                     {"gradient_evaluations", t.gradient_evaluations},
                     {"hessian_evaluations", t.hessian_evaluations},
                     {"seconds", t.seconds}});
  const NewtonReport& n = r.newton;
  nlohmann::json line = {{"step", r.step},
                         {"time", r.time},
                         {"seconds", r.seconds},
                         {"newton_iterations", n.iterations},
                         {"stop", stop_name(n.stop)},
                         {"energy", n.energy},
                         {"gradient_norm", n.gradient_norm},
                         {"step_norm", n.step_norm},
                         {"max_diagonal_shift", n.max_shift},
                         {"exact_hessian_iterations", n.exact_steps},
                         {"cg_iterations", n.cg_iterations},
                         {"extrapolated_steps", n.extrapolated_steps},
                         {"capped_steps", n.capped_steps},
                         {"symbolic_analyses", n.symbolic_analyses},
                         {"phase_seconds",
                          {{"assembly", n.timings.assembly},
                           {"analysis", n.timings.analysis},
                           {"factorization", n.timings.factorization},
                           {"solve", n.timings.solve},
                           {"line_search", n.timings.line_search}}},
                         {"terms", terms},
                         {"script_reached", r.script_reached},
                         {"change_rms", r.change_rms},
                         {"equilibrium", r.equilibrium}};
  if (r.contact) line["contact"] = contact_json(*r.contact);
  if (r.friction_contacts) line["friction_contacts"] = *r.friction_contacts;
  if (r.max_stretch) line["max_stretch"] = *r.max_stretch;
  if (r.wind) line["wind"] = wind_json(*r.wind);
  if (r.follower_lags) line["follower_lags"] = *r.follower_lags;
  if (r.motion) line["motion"] = motion_json(*r.motion);
  if (!r.reactions.empty()) line["reactions"] = reactions_json(r.reactions);
  return line.dump();
}

}  // namespace progsim
