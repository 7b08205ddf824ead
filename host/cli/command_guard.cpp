// The whole-process guard (see command_guard.h).
#include "host/cli/command_guard.h"

#include <cxxabi.h>  // abi::__cxa_demangle, abi::__cxa_current_exception_type
#include <unistd.h>  // _exit

#include <cstddef>    // std::ptrdiff_t
#include <cstdlib>    // std::free
#include <exception>  // std::set_terminate, std::current_exception
#include <iostream>   // std::cerr
#include <new>        // std::bad_alloc
#include <sstream>    // std::ostringstream
#include <typeinfo>   // std::type_info
#include <vector>     // std::vector

#include "host/cli/exit_codes.h"
#include "host/cli/terminal_text.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"
#if __has_include(<clipper.hpp>)  // the PCB readers are linked (host_pcb brings Clipper)
#include "host/lib/pcb/pcb_layer.h"
#define ENGRAVER_CLI_HAS_PCB 1
#endif

namespace host::cli {

namespace {

// The readable name of a type ("std::bad_array_new_length").
std::string type_name(const std::type_info* t) {
  if (t == nullptr) return "an exception of unknown type";
  int status = 0;
  char* d = abi::__cxa_demangle(t->name(), nullptr, nullptr, &status);
  const std::string name = status == 0 && d != nullptr ? d : t->name();
  std::free(d);
  return name;
}

void describe_into(const CLI::App& app, std::string& out) {
  for (const CLI::App* sub : app.get_subcommands()) {
    out += (out.empty() ? "" : " ") + sub->get_name();
    for (const CLI::Option* opt : sub->get_options()) {
      if (!opt->get_positional()) continue;
      for (const std::string& v : opt->results()) out += " " + v;
    }
    describe_into(*sub, out);
  }
}

// "'engraver info FILE'", or "engraver" when nothing was parsed yet.
std::string quoted(const std::string& command) {
  return command.empty() ? std::string("engraver") : "'engraver " + command + "'";
}

// "engraver: internal error in 'engraver info FILE': unexpected TYPE (WHAT); please ..."
std::string internal_error(const std::string& command, const std::type_info* type,
                           const char* what) {
  std::string m =
      "engraver: internal error in " + quoted(command) + ": unexpected " + type_name(type);
  if (what != nullptr) m += std::string(" (") + what + ")";
  return m + "; please report it with the input file\n";
}

std::string g_running;  // for the terminate handler: the command being run

[[noreturn]] void on_terminate() {
  std::string what;
  const std::string type = type_name(abi::__cxa_current_exception_type());
  try {
    if (std::current_exception()) std::rethrow_exception(std::current_exception());
    what = "std::terminate without an exception";
  } catch (const std::exception& e) {
    what = "unexpected " + type + ": " + e.what();
  } catch (...) {
    what = "unexpected " + type;
  }
  std::cerr << "engraver: internal error in " << quoted(g_running) << ": " << what
            << " (escaped a thread; please report it with the input file)" << std::endl;
  _exit(kExitInternal);
}

}  // namespace

std::string describe_command(const CLI::App& app) {
  std::string out;
  describe_into(app, out);
  return out;
}

void install_terminate_guard(CLI::App& app) {
  app.parse_complete_callback([&app]() { g_running = describe_command(app); });
  std::set_terminate(on_terminate);
}

namespace {

// The words nothing took, in the order given, of the app and the commands parsed (those that
// hand theirs on, as serve does, left out). CLI11 keeps a `--` among them: it names nothing.
void unexpected_words(const CLI::App& app, std::vector<std::string>& out) {
  if (!app.get_allow_extras()) {
    for (const std::string& w : app.remaining(false))
      if (w != "--") out.push_back(w);
  }
  for (const CLI::App* sub : app.get_subcommands()) unexpected_words(*sub, out);
}

// A word as a shell would take it back: '' for an empty one, in quotes when it holds a space
// or a quote, a newline or a tab as \n or \t (one message stays one line).
std::string shown_word(const std::string& word) {
  if (word.empty()) return "''";
  std::string s;
  bool quote = false;
  for (const char c : word) {
    if (c == '\n' || c == '\t') {
      s += c == '\n' ? "\\n" : "\\t";
      quote = true;
    } else {
      quote = quote || c == ' ' || c == '\'' || c == '"';
      s += c;
    }
  }
  s = printable(s);
  return quote ? "'" + s + "'" : s;
}

// An option the command does not have is the mistake to name: CLI11 checks the values it
// did take first (`board DIR --tool-side ''` gave the '' to FILES: "FILES: an empty value"),
// lists the words backwards and shows an empty one as nothing.
void say_parse_error(CLI::App& app, const CLI::ParseError& e, std::ostream& err) {
  std::vector<std::string> words;
  unexpected_words(app, words);
  // A word left over that is no option (`--tol= 0.01`: the 0.01) does not hide what was
  // wrong with the option before it.
  bool an_option = false;
  for (const std::string& w : words) an_option = an_option || (w.size() > 1 && w[0] == '-');
  if (words.empty() || (!an_option && dynamic_cast<const CLI::ExtrasError*>(&e) == nullptr)) {
    app.exit(e, std::cout, err);  // the message and the usage hint
    return;
  }
  std::string list;
  for (const std::string& w : words) list += " " + shown_word(w);
  const CLI::ExtrasError extras((words.size() > 1 ? "The following arguments were not expected:"
                                                  : "The following argument was not expected:") +
                                    list,
                                static_cast<int>(CLI::ExitCodes::ExtrasError));
  app.exit(extras, std::cout, err);
}

// Whether every option of this name, in the app and its commands, is a switch (no value).
bool only_switches_named(const CLI::App& app, const std::string& name, bool* found) {
  bool all = true;
  const CLI::Option* o = app.get_option_no_throw(name);
  if (o != nullptr) {
    *found = true;
    all = o->get_items_expected_max() == 0;
  }
  for (const CLI::App* sub : app.get_subcommands({}))
    all = only_switches_named(*sub, name, found) && all;
  return all;
}

// `--side=` is an empty value, not the option left out: CLI11 took the next word for it
// (`--side= board.gbr` said the file was not a side). Given as `--side ''`, the option's own
// check says so, and an option the command does not have is named as any other; a switch
// (`--json=`) takes no value at all. Words after `--` are not options.
std::vector<std::string> with_empty_values_apart(const CLI::App& app, int argc,
                                                 const char* const* argv) {
  std::vector<std::string> words(argv, argv + argc);
  for (size_t i = 1; i < words.size(); ++i) {
    if (words[i] == "--") break;
    const std::string& w = words[i];
    if (w.size() > 3 && w.compare(0, 2, "--") == 0 && w.find('=') == w.size() - 1) {
      const std::string name = w.substr(0, w.size() - 1);
      bool found = false;
      if (only_switches_named(app, name, &found) && found)
        throw CLI::ValidationError(name, "a switch takes no value (give it alone)");
      words[i] = name;
      words.insert(words.begin() + static_cast<std::ptrdiff_t>(i) + 1, std::string());
      ++i;
    }
  }
  return words;
}

int run_guarded_to(CLI::App& app, int argc, const char* const* argv, std::ostream& err) {
  try {
    const std::vector<std::string> words = with_empty_values_apart(app, argc, argv);
    std::vector<const char*> args;
    for (const std::string& w : words) args.push_back(w.c_str());
    app.parse(static_cast<int>(args.size()), args.data());
    return kExitOk;
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    err << "engraver: ";  // as every other message begins
    say_parse_error(app, e, err);
    return kExitUsage;
  } catch (const CommandFailure& e) {
    err << "engraver: " << e.what() << "\n";
    return e.code;
  } catch (const ImportError& e) {
    err << "engraver: " << e.what() << "\n";  // names the file, the place and the problem
    return kExitUsage;
#ifdef ENGRAVER_CLI_HAS_PCB
  } catch (const host::pcb::PcbReadError& e) {
    err << "engraver: " << e.what() << "\n";  // names the file, the line and the problem
    return kExitUsage;
#endif
  } catch (const PlanError& e) {
    err << "engraver: job refused: " << e.what() << "\n";
    return kExitJobFailed;
  } catch (const std::bad_array_new_length& e) {
    err << internal_error(describe_command(app), &typeid(e), e.what());  // a size computed wrong
    return kExitInternal;
  } catch (const std::bad_alloc&) {
    err << "engraver: " << quoted(describe_command(app))
        << " ran out of memory (the input is too large, or a bug: please report it)\n";
    return kExitInternal;
  } catch (const std::runtime_error& e) {
    // A failure the libraries report in words (a file that cannot be written, a port).
    err << "engraver: " << quoted(describe_command(app)) << " failed: " << e.what() << "\n";
    return kExitJobFailed;
  } catch (const std::exception& e) {
    err << internal_error(describe_command(app), &typeid(e), e.what());
    return kExitInternal;
  } catch (...) {
    err << internal_error(describe_command(app), abi::__cxa_current_exception_type(), nullptr);
    return kExitInternal;
  }
}

}  // namespace

int run_guarded(CLI::App& app, int argc, const char* const* argv, std::ostream& err) {
  std::ostringstream message;
  const int code = run_guarded_to(app, argc, argv, message);
  err << printable(message.str());
  return code;
}

}  // namespace host::cli
