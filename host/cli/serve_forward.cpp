// `engraver serve` in the `engraver` tool: runs engraver-serve (beside this executable) in
// this process's place. The server's libraries (HTTP with TLS, SQLite, PostgreSQL, libzip)
// are linked into engraver-serve alone, so every other command starts without loading them
// (docs/performance.md, "Start-up").
#include <unistd.h>     // execv
#include <CLI/CLI.hpp>  // CLI::App

#include <cerrno>      // errno
#include <cstring>     // std::strerror
#include <filesystem>  // std::filesystem::read_symlink
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/cli/command_registry.h"
#include "host/cli/exit_codes.h"
#include "host/cli/serve_summary.h"

namespace host::cli {

namespace {

// Replaces this process with engraver-serve given the same arguments after `serve`;
// returns only by throwing when it cannot.
void exec_serve(const std::vector<std::string>& args) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec)
    throw CommandFailure(kExitInternal, "cannot tell where this engraver is: " + ec.message());
  const std::string server = (exe.parent_path() / kServeExecutable).string();
  std::vector<std::string> words = {server, "serve"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execv(server.c_str(), argv.data());
  throw CommandFailure(kExitUsage, "serve needs " + server +
                                       " (installed beside engraver): " + std::strerror(errno));
}

void add_serve_forward(CLI::App& app) {
  CLI::App* serve = app.add_subcommand("serve", kServeSummary);
  // Everything after `serve`, --help included, is engraver-serve's to read.
  serve->set_help_flag();
  serve->prefix_command();
  serve->allow_extras();
  serve->callback([serve] { exec_serve(serve->remaining()); });
}

const CommandRegistrar registrar("serve", {"serve"}, add_serve_forward);

}  // namespace

}  // namespace host::cli
