#pragma once
/// @file Parts of a step's log line as JSON, shared by every log that reports them.
#include <nlohmann/json.hpp>

#include "contact/contact_stats.hpp"
#include "sim/step_record.hpp"

namespace progsim {

/// A step's contact counters (min_gap null when no pair was near).
nlohmann::json contact_json(const ContactStats& contact);

/// A dynamic step's motion: kinetic energy, centre of mass [x, y, z], continuity error and
/// continuity.
nlohmann::json motion_json(const MotionRecord& motion);

/// Per handle, its reaction: force [x, y, z] (N), moment [x, y, z] (N·m) about point [x, y, z]
/// (m).
nlohmann::json reactions_json(const std::vector<HandleReaction>& reactions);

/// A step's wind: its velocity [x, y, z] (m/s) and its force on the shell [x, y, z] (N).
nlohmann::json wind_json(const WindRecord& wind);

}  // namespace progsim
