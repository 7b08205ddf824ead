// Lets each command group of the `engraver` tool add its subcommands from its own file.
#ifndef HOST_CLI_COMMAND_REGISTRY_H
#define HOST_CLI_COMMAND_REGISTRY_H

#include <CLI/CLI.hpp>  // CLI::App

#include <initializer_list>  // std::initializer_list
#include <string>            // std::string
#include <vector>            // std::vector

namespace host::cli {

// Adds a group's subcommands to the top-level app. Called once at start-up.
using AddCommands = void (*)(CLI::App& app);

// A static instance in a *_commands.cpp file registers that file's group and the names of
// the commands it adds (`commands`, in the order it adds them), so that a command line naming
// one of them builds that group alone.
struct CommandRegistrar {
  CommandRegistrar(const char* group, std::initializer_list<const char*> commands, AddCommands add);
};

// The command names of every registered group, in group-name order (as --help lists them).
std::vector<std::string> registered_command_names();

// Adds the commands the command line can reach: when argv[1] is a registered command's name,
// its group alone; for `engraver --version` alone, none; otherwise every group, in group-name
// order (stable --help; an unknown command's message lists them all). Then every number
// option of the added commands refuses "nan", "inf" and what is not a plain decimal, and the
// board options take their one range from option_ranges() (usage errors naming the option).
void add_registered_commands(CLI::App& app, int argc, const char* const* argv);
// Every group, as for `engraver --help`.
void add_registered_commands(CLI::App& app);

// When a command word (the first argument, one after -h, or a command's own command such as
// `spi diff`) is not one of its parent's commands, is empty, or is missing (`engraver`,
// `engraver spi`), or an option stands where only commands do: a message that names it
// (non-UTF-8 bytes as \xNN) and lists the commands; "" otherwise (CLI11 alone says "A
// subcommand is required", which reads as if the word had been ignored).
std::string unknown_command_message(const CLI::App& app, int argc, const char* const* argv);

}  // namespace host::cli

#endif  // HOST_CLI_COMMAND_REGISTRY_H
