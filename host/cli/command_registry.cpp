// The registry of command groups (see command_registry.h).
#include "host/cli/command_registry.h"

#include <map>     // std::map
#include <string>  // std::string

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
}

}  // namespace host::cli
