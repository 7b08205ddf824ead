// The registry of command groups (see command_registry.h).
#include "host/cli/command_registry.h"

#include <cstring>  // std::strcmp
#include <map>      // std::map
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/cli/option_ranges.h"
#include "host/cli/terminal_text.h"  // printable

namespace host::cli {

namespace {

struct Group {
  std::vector<std::string> commands;
  AddCommands add;
};

// Function-local so that registrars in other translation units can use it during static
// initialisation, whatever the link order.
std::map<std::string, Group>& registry() {
  static std::map<std::string, Group> groups;
  return groups;
}

// The group that adds the command named `word`, or nullptr.
const Group* group_of(const std::string& word) {
  for (const auto& g : registry()) {
    for (const std::string& name : g.second.commands) {
      if (name == word) return &g.second;
    }
  }
  return nullptr;
}

}  // namespace

CommandRegistrar::CommandRegistrar(const char* group, std::initializer_list<const char*> commands,
                                   AddCommands add) {
  registry()[group] = Group{std::vector<std::string>(commands.begin(), commands.end()), add};
}

std::vector<std::string> registered_command_names() {
  std::vector<std::string> names;
  for (const auto& g : registry())
    names.insert(names.end(), g.second.commands.begin(), g.second.commands.end());
  return names;
}

// Building every command's options was 40 % of `engraver --version` (docs/performance.md). A
// command line runs one command; --help, no command and an unknown word list them all, so
// anything but an exact name builds them all. `--version` alone prints before any is read.
void add_registered_commands(CLI::App& app, int argc, const char* const* argv) {
  const Group* named = argc >= 2 ? group_of(argv[1]) : nullptr;
  if (named != nullptr) {
    named->add(app);
  } else if (!(argc == 2 && std::strcmp(argv[1], "--version") == 0)) {
    for (const auto& g : registry()) g.second.add(app);
  }
  add_option_checks(&app);
}

void add_registered_commands(CLI::App& app) {
  add_registered_commands(app, 0, nullptr);
}

std::string unknown_command_message(const CLI::App& app, int argc, const char* const* argv) {
  const auto names_of = [](const CLI::App* parent) {
    std::string names;
    for (const CLI::App* sub : parent->get_subcommands({}))
      names += (names.empty() ? "" : ", ") + sub->get_name();
    return names;
  };
  // Down the command words (`spi diff`), each among its parent's commands; -h and --help
  // may come before a word (`engraver -h board`, `engraver spi -h decode`).
  const CLI::App* at = &app;
  std::string path = "engraver";
  bool help = false;
  for (int i = 1; !at->get_subcommands({}).empty(); ++i) {
    const std::string hint = " (" + path + " --help; " + path + " COMMAND --help for each)";
    if (i == argc) {        // no word at all (`engraver`, `engraver spi`): CLI11 said "A subcommand
      if (help) return "";  // is required"
      return (at == &app ? "a command is needed: " : at->get_name() + " needs a command: ") +
             names_of(at) + hint;
    }
    const std::string word = argv[i];
    if (word == "-h" || word == "--help") {
      help = true;
      continue;
    }
    if (at == &app && word == "--version") return "";
    if (!word.empty() && word[0] == '-') {  // these levels have no options of their own
      return "'" + printable(word) + "' is not an option of " + path +
             " itself: a command comes first (" + path + " COMMAND --help lists its options)";
    }
    const CLI::App* found = nullptr;
    for (const CLI::App* sub : at->get_subcommands({}))
      if (!word.empty() && sub->check_name(word)) found = sub;
    if (found == nullptr) {
      return "'" + printable(word) + "' is not an " + path + " command; the commands are " +
             names_of(at) + hint;
    }
    at = found;
    path += " " + found->get_name();
  }
  return "";
}

}  // namespace host::cli
