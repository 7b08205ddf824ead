// Lets each command group of the `engraver` tool add its subcommands from its own file.
#ifndef HOST_CLI_COMMAND_REGISTRY_H
#define HOST_CLI_COMMAND_REGISTRY_H

#include <CLI/CLI.hpp>  // CLI::App

namespace host::cli {

// Adds a group's subcommands to the top-level app. Called once at start-up.
using AddCommands = void (*)(CLI::App& app);

// A static instance in a *_commands.cpp file registers that file's group.
struct CommandRegistrar {
  CommandRegistrar(const char* group, AddCommands add);
};

// Calls every registered group, in group-name order (stable --help).
void add_registered_commands(CLI::App& app);

}  // namespace host::cli

#endif  // HOST_CLI_COMMAND_REGISTRY_H
