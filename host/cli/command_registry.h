// Lets each command group of the `engraver` tool add its subcommands from its own file.
#ifndef HOST_CLI_COMMAND_REGISTRY_H
#define HOST_CLI_COMMAND_REGISTRY_H

#include <CLI/CLI.hpp>  // CLI::App

#include <string>  // std::string

namespace host::cli {

// Adds a group's subcommands to the top-level app. Called once at start-up.
using AddCommands = void (*)(CLI::App& app);

// A static instance in a *_commands.cpp file registers that file's group.
struct CommandRegistrar {
  CommandRegistrar(const char* group, AddCommands add);
};

// Calls every registered group, in group-name order (stable --help); then every number option
// of every command refuses "nan", "inf" and what is not a plain decimal, and the board options
// take their one range from option_ranges() (usage errors naming the option).
void add_registered_commands(CLI::App& app);

// When the first argument is neither an option nor one of app's commands: a message that
// names it and lists the commands; "" otherwise (CLI11 alone says "A subcommand is
// required", which reads as if the word had been ignored).
std::string unknown_command_message(const CLI::App& app, int argc, const char* const* argv);

}  // namespace host::cli

#endif  // HOST_CLI_COMMAND_REGISTRY_H
