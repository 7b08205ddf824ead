// `engraver` builds only the group of the command its command line names (start-up,
// docs/performance.md): built so, each command must be the same as when every group is built
// (the same options, types, checks and help), and --help, --version and an unknown word must
// still see every command.
#include <gtest/gtest.h>
#include <CLI/CLI.hpp>  // CLI::App

#include <algorithm>  // std::find
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/cli/command_registry.h"
#include "host_tests/host/cli/tool_run.h"

namespace {

using host::cli::add_registered_commands;
using host::cli::registered_command_names;

std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

// A command and its own commands, option by option (names, type, the names of its checks:
// the nan/inf and plain-decimal checks have no text in --help), then its --help.
std::string describe(CLI::App& cmd) {
  std::string out = cmd.get_name() + "\n";
  for (CLI::Option* o : cmd.get_options()) {
    out += o->get_name() + " " + o->get_type_name() + ":";
    for (int i = 0;; ++i) {
      try {
        out += " " + o->get_validator(i)->get_name();
      } catch (const CLI::OptionNotFound&) {
        break;
      }
    }
    out += "\n";
  }
  out += cmd.help();
  for (CLI::App* sub : cmd.get_subcommands({})) out += describe(*sub);
  return out;
}

TEST(CliRegistry, EveryCommandBuiltIsRegisteredByName) {
  CLI::App all;
  add_registered_commands(all);
  EXPECT_EQ(command_names(all), registered_command_names());
  // board, info, points, send, probe, sim, run, serve, spi
  EXPECT_GE(registered_command_names().size(), 9u);
}

TEST(CliRegistry, ACommandBuiltAloneIsTheSameAsBuiltWithAllTheOthers) {
  CLI::App all;
  add_registered_commands(all);
  for (const std::string& name : registered_command_names()) {
    CLI::App alone;
    const char* argv[] = {"engraver", name.c_str(), "--help"};
    add_registered_commands(alone, 3, argv);
    const std::vector<std::string> built = command_names(alone);
    ASSERT_NE(std::find(built.begin(), built.end(), name), built.end())
        << name << " is registered but its group does not add it";
    EXPECT_EQ(describe(*alone.get_subcommand(name)), describe(*all.get_subcommand(name))) << name;
    EXPECT_LT(alone.get_subcommands({}).size(), all.get_subcommands({}).size()) << name;
  }
}

TEST(CliRegistry, VersionAloneBuildsNoCommandAndAnythingElseNotACommandBuildsAll) {
  const size_t every = registered_command_names().size();
  const auto built = [](std::vector<const char*> argv) {
    CLI::App app;
    add_registered_commands(app, static_cast<int>(argv.size()), argv.data());
    return app.get_subcommands({}).size();
  };
  EXPECT_EQ(built({"engraver", "--version"}), 0u);
  EXPECT_EQ(built({"engraver"}), every);
  EXPECT_EQ(built({"engraver", "--help"}), every);
  EXPECT_EQ(built({"engraver", "--version", "--help"}), every);
  EXPECT_EQ(built({"engraver", "bord"}), every);
  EXPECT_EQ(built({"engraver", "--top", "board"}), every);
}

// The tool itself, as a user runs it.
host_tests::ToolRun engraver(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

std::string every_command() {
  std::string names;
  for (const std::string& n : registered_command_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

TEST(CliRegistry, TheToolsHelpListsEveryCommand) {
  const host_tests::ToolRun r = engraver("--help");
  EXPECT_EQ(r.code, 0) << r.err;
  const size_t list = r.out.find("\nSubcommands:\n");
  ASSERT_NE(list, std::string::npos) << r.out;
  for (const std::string& name : registered_command_names())
    EXPECT_NE(r.out.find("\n  " + name + " ", list), std::string::npos) << name << "\n" << r.out;
}

TEST(CliRegistry, AnUnknownCommandAndNoCommandStillSeeEveryCommand) {
  const host_tests::ToolRun r = engraver("bord --top x.gbr");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "engraver: 'bord' is not an engraver command; the commands are " +
                       every_command() + " (engraver --help; engraver COMMAND --help for each)\n");
  // No command at all lists them too (CLI11 said "A subcommand is required"; tester 17).
  const host_tests::ToolRun none = engraver("");
  EXPECT_EQ(none.code, 2);
  EXPECT_EQ(none.err, "engraver: a command is needed: " + every_command() +
                          " (engraver --help; engraver COMMAND --help for each)\n");
  const host_tests::ToolRun spi = engraver("spi");
  EXPECT_EQ(spi.code, 2);
  EXPECT_EQ(spi.err.rfind("engraver: spi needs a command: decode, expect, diff (engraver spi "
                          "--help; engraver spi COMMAND --help for each)",
                          0),
            0u)
      << spi.err;
  const host_tests::ToolRun version = engraver("--version");
  EXPECT_EQ(version.code, 0) << version.err;
  EXPECT_EQ(version.out.rfind("engraver ", 0), 0u) << version.out;
  EXPECT_EQ(version.err, "");
}

// Every command word is checked where it stands: after -h, and a command's own command
// (`spi frob` was "A subcommand is required", `-h frobnicate` the top-level help and exit 0);
// an option before any command is named; bytes that are not UTF-8 come back as \xNN.
TEST(CliRegistry, EveryUnknownCommandWordAndLeadingOptionIsNamed) {
  const host_tests::ToolRun help = engraver("-h frobnicate");
  EXPECT_EQ(help.code, 2);
  EXPECT_EQ(help.out, "");
  EXPECT_EQ(help.err.rfind("engraver: 'frobnicate' is not an engraver command; the commands are " +
                               every_command(),
                           0),
            0u)
      << help.err;
  const host_tests::ToolRun spi = engraver("spi frob x.vcd");
  EXPECT_EQ(spi.code, 2);
  EXPECT_EQ(spi.err.rfind("engraver: 'frob' is not an engraver spi command; the commands are ", 0),
            0u)
      << spi.err;
  EXPECT_NE(spi.err.find("diff"), std::string::npos) << spi.err;
  EXPECT_NE(spi.err.find("(engraver spi --help; engraver spi COMMAND --help for each)"),
            std::string::npos)
      << spi.err;
  const host_tests::ToolRun option = engraver("--frob board x.gbr");
  EXPECT_EQ(option.code, 2);
  EXPECT_EQ(option.err.rfind("engraver: '--frob' is not an option of engraver itself", 0), 0u)
      << option.err;
  const host_tests::ToolRun bytes = engraver("\"$(printf '\\377\\376board')\"");
  EXPECT_EQ(bytes.code, 2);
  EXPECT_EQ(bytes.err.rfind("engraver: '\\xFF\\xFEboard' is not an engraver command", 0), 0u)
      << bytes.err;
  // -h may stand before a word at any level; an empty word and an option at a level that
  // has only commands are named too (outside tester 18: `spi -h bogus` was spi's help,
  // `-h spi` "spi needs a command", `spi ''` and `spi -x` "A subcommand is required").
  for (const std::string args : {"spi -h bogus", "spi --help bogus"}) {
    const host_tests::ToolRun r = engraver(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err.rfind("engraver: 'bogus' is not an engraver spi command", 0), 0u) << r.err;
  }
  const host_tests::ToolRun empty = engraver("spi ''");
  EXPECT_EQ(empty.code, 2);
  EXPECT_EQ(empty.err.rfind("engraver: '' is not an engraver spi command", 0), 0u) << empty.err;
  const host_tests::ToolRun spi_option = engraver("spi -x");
  EXPECT_EQ(spi_option.code, 2);
  EXPECT_EQ(spi_option.err.rfind("engraver: '-x' is not an option of engraver spi itself", 0), 0u)
      << spi_option.err;
  const host_tests::ToolRun spi_help = engraver("-h spi");
  EXPECT_EQ(spi_help.code, 0) << spi_help.err;
  EXPECT_EQ(spi_help.out, engraver("spi --help").out);
  EXPECT_EQ(engraver("spi -h decode").out, engraver("spi decode --help").out);
  // What each known word does stays as it was.
  EXPECT_EQ(engraver("-h board").code, 0);
  EXPECT_EQ(engraver("spi --help").code, 0);
  EXPECT_EQ(engraver("spi diff --help").code, 0);
}

TEST(CliRegistry, TheNamedCommandsOptionsAreStillChecked) {
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"board x.gbr --tool-width nan", "engraver: --tool-width: 'nan' is not a finite number"},
      {"board x.gbr --tool-width 9", "engraver: --tool-width: 9 is outside the allowed range"},
      {"points x.dxf --tol inf", "engraver: --tol: 'inf' is not a finite number"},
      {"run x.dxf --passes 1.5", "engraver: --passes: '1.5' is not a whole number"},
      {"sim --pause-confirm-ms -5", "engraver: --pause-confirm-ms: -5 is outside"},
      {"spi decode x.csv --mode 1.5", "engraver: --mode: '1.5' is not a whole number"},
  };
  for (const Case& c : cases) {
    const host_tests::ToolRun r = engraver(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind(c.says, 0), 0u) << c.args << "\n" << r.err;
  }
}

}  // namespace
