#pragma once
/// @file Access to the table of named scene options in choices.def.
#include <string>
#include <vector>

#include "common/error.hpp"

namespace progsim {

/// One named option of a scene: its admissible names, which of them is the default, its doc.
struct ChoiceSpec {
  const char* group;  ///< "simulation", "material", "progressive"
  const char* name;
  std::vector<std::string> options;  ///< in the order of the C++ enum's values
  int default_index;                 ///< the option a scene that does not name one gets
  const char* doc;
};

/// Every named option, in table order.
const std::vector<ChoiceSpec>& choice_table();

/// The option group.name. Throws Error(invalid_argument) listing the known ones if there is
/// none.
const ChoiceSpec& find_choice(const std::string& group, const std::string& name);

/// The index of `value` among spec.options. Throws Error(status) naming `label` (group.name
/// if empty), the value and the known options otherwise.
int choice_index(const ChoiceSpec& spec, const std::string& value, const std::string& label = "",
                 Status status = Status::invalid_scene);

/// The table as Markdown (name, options, default, meaning) for docs and `progsim params`.
std::string choice_table_markdown();

}  // namespace progsim
