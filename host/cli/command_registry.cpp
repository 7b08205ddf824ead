// The registry of command groups (see command_registry.h).
#include "host/cli/command_registry.h"

#include <cmath>    // std::isfinite
#include <cstdlib>  // std::strtod
#include <map>      // std::map
#include <string>   // std::string

namespace host::cli {

namespace {

// Function-local so that registrars in other translation units can use it during static
// initialisation, whatever the link order.
std::map<std::string, AddCommands>& registry() {
  static std::map<std::string, AddCommands> groups;
  return groups;
}

// "nan" and "inf" parse as numbers and pass CLI::Range (every comparison with NaN is false):
// refused for every number option, naming the option, before a command sees them.
std::string refuse_non_finite(std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end != value.c_str() && *end == '\0' && !std::isfinite(v))
    return "'" + value + "' is not a finite number";
  return "";
}

void refuse_non_finite_numbers(CLI::App* app) {
  for (CLI::Option* o : app->get_options()) {
    if (o->get_type_name().rfind("FLOAT", 0) == 0)
      o->check(CLI::Validator(refuse_non_finite, "", "finite"));
  }
  for (CLI::App* sub : app->get_subcommands({})) refuse_non_finite_numbers(sub);
}

}  // namespace

CommandRegistrar::CommandRegistrar(const char* group, AddCommands add) {
  registry()[group] = add;
}

void add_registered_commands(CLI::App& app) {
  for (const auto& g : registry()) g.second(app);
  refuse_non_finite_numbers(&app);
}

std::string unknown_command_message(const CLI::App& app, int argc, const char* const* argv) {
  if (argc < 2) return "";
  const std::string word = argv[1];
  if (word.empty() || word[0] == '-') return "";
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->check_name(word)) return "";
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return "'" + word + "' is not an engraver command; the commands are " + names +
         " (engraver --help; engraver COMMAND --help for each)";
}

}  // namespace host::cli
