// The registry of command groups (see command_registry.h).
#include "host/cli/command_registry.h"

#include <map>     // std::map
#include <string>  // std::string

#include "host/cli/option_ranges.h"

namespace host::cli {

namespace {

// Function-local so that registrars in other translation units can use it during static
// initialisation, whatever the link order.
std::map<std::string, AddCommands>& registry() {
  static std::map<std::string, AddCommands> groups;
  return groups;
}

}  // namespace

CommandRegistrar::CommandRegistrar(const char* group, AddCommands add) {
  registry()[group] = add;
}

void add_registered_commands(CLI::App& app) {
  for (const auto& g : registry()) g.second(app);
  add_option_checks(&app);
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
