// The whole-process guard: whatever a command throws, the user gets one line naming the
// command and its file, and the documented exit code (never a bare type name).
#include "host/cli/command_guard.h"

#include <gtest/gtest.h>

#include <new>        // std::bad_alloc, std::bad_array_new_length
#include <sstream>    // std::ostringstream
#include <stdexcept>  // std::out_of_range, std::runtime_error

#include "host/cli/exit_codes.h"
#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"

namespace host::cli {
namespace {

struct GuardRun {
  int code;
  std::string err;
};

// An app with `info FILE` and `spi diff CAPTURE` whose callbacks run `body`, run on argv.
template <typename Body>
GuardRun run_with(Body body, std::vector<const char*> argv) {
  CLI::App app{"test", "engraver"};
  app.require_subcommand(1);
  std::string file, capture;
  CLI::App* info = app.add_subcommand("info", "");
  info->add_option("file", file)->required();
  info->callback(body);
  CLI::App* spi = app.add_subcommand("spi", "");
  CLI::App* diff = spi->add_subcommand("diff", "");
  diff->add_option("capture", capture)->required();
  diff->callback(body);
  std::ostringstream err;
  argv.insert(argv.begin(), "engraver");
  const int code = run_guarded(app, static_cast<int>(argv.size()), argv.data(), err);
  return {code, err.str()};
}

GuardRun info_throwing(void (*thrower)()) {
  return run_with(thrower, {"info", "drawings/plate.dxf"});
}

TEST(CommandGuard, BadArrayNewLengthNamesTheCommandAndFile) {
  const GuardRun r = info_throwing([] { throw std::bad_array_new_length(); });
  EXPECT_EQ(r.code, kExitInternal);
  EXPECT_EQ(r.err,
            "engraver: internal error in 'engraver info drawings/plate.dxf': unexpected "
            "std::bad_array_new_length (std::bad_array_new_length); please report it with the "
            "input file\n");
}

TEST(CommandGuard, LogicErrorIsAnInternalError) {
  const GuardRun r = info_throwing([] { throw std::out_of_range("basic_string::substr"); });
  EXPECT_EQ(r.code, kExitInternal);
  EXPECT_EQ(r.err,
            "engraver: internal error in 'engraver info drawings/plate.dxf': unexpected "
            "std::out_of_range (basic_string::substr); please report it with the input file\n");
}

TEST(CommandGuard, OutOfMemoryNamesTheCommand) {
  const GuardRun r = info_throwing([] { throw std::bad_alloc(); });
  EXPECT_EQ(r.code, kExitInternal);
  EXPECT_EQ(r.err,
            "engraver: 'engraver info drawings/plate.dxf' ran out of memory (the input is too "
            "large, or a bug: please report it)\n");
}

TEST(CommandGuard, NonStandardExceptionIsNamed) {
  const GuardRun r = info_throwing([] { throw 42; });
  EXPECT_EQ(r.code, kExitInternal);
  EXPECT_EQ(r.err,
            "engraver: internal error in 'engraver info drawings/plate.dxf': unexpected int; "
            "please report it with the input file\n");
}

TEST(CommandGuard, RuntimeErrorIsAFailedJobNamingTheCommand) {
  const GuardRun r =
      info_throwing([] { throw std::runtime_error("out.svg: cannot write the plot"); });
  EXPECT_EQ(r.code, kExitJobFailed);
  EXPECT_EQ(r.err,
            "engraver: 'engraver info drawings/plate.dxf' failed: out.svg: cannot write the "
            "plot\n");
}

TEST(CommandGuard, NestedSubcommandIsNamedInFull) {
  const GuardRun r =
      run_with([] { throw std::logic_error("bug"); }, {"spi", "diff", "capture.vcd"});
  EXPECT_EQ(r.code, kExitInternal);
  EXPECT_EQ(r.err,
            "engraver: internal error in 'engraver spi diff capture.vcd': unexpected "
            "std::logic_error (bug); please report it with the input file\n");
}

TEST(CommandGuard, ImportErrorIsAnInputError) {
  const GuardRun r = info_throwing([] { throw ImportError("plate.dxf: line 3: bad"); });
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_EQ(r.err, "engraver: plate.dxf: line 3: bad\n");
}

// A reader's message may quote a line of a binary file: its control bytes and broken UTF-8
// reach the terminal as \xNN, never as escape sequences; UTF-8 text stays as it is.
TEST(CommandGuard, BytesThatWouldDisturbATerminalAreShownAsHex) {
  const GuardRun r = info_throwing(
      [] { throw ImportError("g.gbr:1: unexpected '\x1b[2J' in '\xff\xfe\t0.5 \xc2\xb5m'"); });
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_EQ(r.err, "engraver: g.gbr:1: unexpected '\\x1B[2J' in '\\xFF\\xFE\t0.5 \xc2\xb5m'\n");
}

TEST(CommandGuard, PlanErrorIsARefusedJob) {
  const GuardRun r = info_throwing([] { throw PlanError("outside the work area"); });
  EXPECT_EQ(r.code, kExitJobFailed);
  EXPECT_EQ(r.err, "engraver: job refused: outside the work area\n");
}

TEST(CommandGuard, CommandFailureKeepsItsCode) {
  const GuardRun r = info_throwing([] { throw CommandFailure(6, "link failed"); });
  EXPECT_EQ(r.code, 6);
  EXPECT_EQ(r.err, "engraver: link failed\n");
}

TEST(CommandGuard, SuccessIsZeroAndSilent) {
  const GuardRun r = info_throwing([] {});
  EXPECT_EQ(r.code, kExitOk);
  EXPECT_EQ(r.err, "");
}

TEST(CommandGuard, MissingArgumentIsAUsageError) {
  const GuardRun r = run_with([] {}, {"info"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_NE(r.err.find("file is required"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace host::cli
