#include "scene/choice_table.hpp"

#include <sstream>

#include "common/error.hpp"

namespace progsim {
namespace {

std::vector<std::string> split_options(const std::string& options) {
  std::vector<std::string> names;
  std::istringstream in(options);
  for (std::string name; std::getline(in, name, '|');) names.push_back(name);
  return names;
}

std::string joined(const std::vector<std::string>& names, const char* separator) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : separator) + name;
  return text;
}

/// spec with default_index set to the option named `default_option` (a typo in choices.def
/// fails on first use of the table, in every test).
ChoiceSpec with_default(ChoiceSpec spec, const std::string& default_option) {
  spec.default_index = -1;
  for (std::size_t k = 0; k < spec.options.size(); ++k)
    if (spec.options[k] == default_option) spec.default_index = static_cast<int>(k);
  if (spec.default_index < 0)
    fail(Status::internal, std::string("choices.def: ") + spec.group + "." + spec.name +
                               "'s default '" + default_option + "' is not one of its options");
  return spec;
}

}  // namespace

const std::vector<ChoiceSpec>& choice_table() {
  static const std::vector<ChoiceSpec> table = {
#define PROGSIM_CHOICE(group, name, options, default_option, doc) \
  with_default({#group, #name, split_options(options), 0, doc}, default_option),
#include "scene/choices.def"
#undef PROGSIM_CHOICE
  };
  return table;
}

const ChoiceSpec& find_choice(const std::string& group, const std::string& name) {
  std::vector<std::string> known;
  for (const ChoiceSpec& spec : choice_table()) {
    if (group == spec.group && name == spec.name) return spec;
    known.push_back(std::string(spec.group) + "." + spec.name);
  }
  fail(Status::invalid_argument,
       "unknown option '" + group + "." + name + "' (known: " + joined(known, ", ") + ")");
}

int choice_index(const ChoiceSpec& spec, const std::string& value, const std::string& label,
                 Status status) {
  for (std::size_t k = 0; k < spec.options.size(); ++k)
    if (value == spec.options[k]) return static_cast<int>(k);
  fail(status, (label.empty() ? std::string(spec.group) + "." + spec.name : label) + ": unknown '" +
                   value + "' (known: " + joined(spec.options, ", ") + ")");
}

std::string choice_table_markdown() {
  std::ostringstream out;
  out << "| option | values | default | meaning |\n|---|---|---|---|\n";
  for (const ChoiceSpec& s : choice_table())
    out << "| `" << s.group << "." << s.name << "` | `" << joined(s.options, "`, `") << "` | `"
        << s.options[s.default_index] << "` | " << s.doc << " |\n";
  return out.str();
}

}  // namespace progsim
