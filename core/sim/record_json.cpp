#include "sim/record_json.hpp"

#include <cmath>

namespace progsim {

nlohmann::json contact_json(const ContactStats& c) {
  return {
      {"broad_phase_runs", c.broad_phase_runs},
      {"candidate_pairs", c.candidate_pairs},
      {"active_pairs", c.active_pairs},
      {"ccd_calls", c.ccd_calls},
      {"stiffness_updates", c.stiffness_updates},
      {"min_gap", std::isfinite(c.min_gap) ? nlohmann::json(c.min_gap) : nlohmann::json(nullptr)},
      {"broad_phase_seconds", c.broad_phase_seconds},
      {"ccd_seconds", c.ccd_seconds},
      {"assembly_seconds", c.assembly_seconds}};
}

nlohmann::json motion_json(const MotionRecord& m) {
  return {{"kinetic_energy", m.kinetic_energy},
          {"center_of_mass", {m.center_of_mass.x(), m.center_of_mass.y(), m.center_of_mass.z()}},
          {"continuity_error", m.continuity_error},
          {"continuity", m.continuity}};
}

nlohmann::json reactions_json(const std::vector<HandleReaction>& reactions) {
  nlohmann::json out = nlohmann::json::array();
  for (const HandleReaction& r : reactions)
    out.push_back({{"force", {r.force.x(), r.force.y(), r.force.z()}},
                   {"moment", {r.moment.x(), r.moment.y(), r.moment.z()}},
                   {"point", {r.point.x(), r.point.y(), r.point.z()}}});
  return out;
}

nlohmann::json wind_json(const WindRecord& w) {
  return {{"velocity", {w.velocity.x(), w.velocity.y(), w.velocity.z()}},
          {"force", {w.force.x(), w.force.y(), w.force.z()}}};
}

}  // namespace progsim
