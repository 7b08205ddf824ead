// A bad command line is a usage error (exit 2) found as the line is read, before anything
// is planned or a link opened, in a message that begins "engraver:" and names the option
// (issue 24's docs-only tester: a malformed --to exited 6 after planning, sim --listen took
// port 99999 as 34463, --z-down 5 cut above the surface, --pause-confirm-ms -5 meant never,
// -o FILE gave a raw filesystem error).
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <cstdio>   // std::remove
#include <fstream>  // std::ofstream
#include <string>   // std::string

#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

const std::string kWord = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

ToolRun engraver(const std::string& args) {
  return host_tests::run_tool(ENGRAVER_EXE, args);
}

// Exit 2, the message first: "engraver: " and then `says`; nothing on stdout (no planning).
void expect_usage_error(const std::string& args, const std::string& says) {
  const ToolRun r = engraver(args);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
  EXPECT_EQ(r.err.rfind("engraver: " + says, 0), 0u) << args << "\n" << r.err;
  EXPECT_EQ(r.out, "") << args;
}

TEST(CliUsage, AMalformedLinkAddressIsABadCommandLineBeforePlanning) {
  expect_usage_error("send " + kWord + " --to tcp:127.0.0.1:47199",
                     "--to: link 'tcp:127.0.0.1:47199': unknown kind");
  expect_usage_error("send " + kWord + " --to 127.0.0.1:47199",
                     "--to: link '127.0.0.1:47199': unknown kind");
  expect_usage_error("send " + kWord + " --to tcp://127.0.0.1:99999",
                     "--to: link 'tcp://127.0.0.1:99999': the port must be 1 .. 65535");
  expect_usage_error("send " + kWord + " --to tcp://127.0.0.1:47801:5",
                     "--to: link 'tcp://127.0.0.1:47801:5': '127.0.0.1:47801' is not a host name "
                     "or address");
  expect_usage_error("probe " + kWord + " --to serial:", "--to: link 'serial:': no device");
}

TEST(CliUsage, TheSimulatorsPortAndPauseConfirmAreChecked) {
  expect_usage_error("sim --listen 127.0.0.1:99999",
                     "--listen: '127.0.0.1:99999': the port must be 0 .. 65535");
  expect_usage_error("sim --listen localhost:47857",
                     "--listen: 'localhost:47857': listen address 'localhost' is not a numeric "
                     "address");
  expect_usage_error("sim --listen :47850",
                     "--listen: ':47850': no address before the port (e.g. 127.0.0.1:47850");
  expect_usage_error("sim --listen 127.0.0.1:000000099999",
                     "--listen: '127.0.0.1:000000099999': the port must be 0 .. 65535");
  expect_usage_error("sim --listen 127.0.0.1:10001x",
                     "--listen: '127.0.0.1:10001x': the port must be 0 .. 65535");
  expect_usage_error("sim --pause-confirm-ms -5",
                     "--pause-confirm-ms: -5 is outside the allowed range 0 .. 3600000 ms (or -1: "
                     "never)");
}

// --resume-at's errors read as every other option's: "--resume-at: VALUE: ..." (the colon
// after the option's name was missing).
TEST(CliUsage, ABadResumePositionNamesTheOptionLikeEveryOther) {
  for (const std::string bad : {"abc", "-1", "3:70000", "3:", "1.5", "99999999999", "+3"}) {
    expect_usage_error("send " + kWord + " --to tcp://127.0.0.1:9 --resume-at " + bad,
                       "--resume-at: '" + bad + "': expected INDEX or INDEX:POINT (job command");
  }
}

// An index beyond the job was refused only after connecting (exit 1, "the job has no such
// command"): now on the plan, before the link (nothing listens on port 9), with the count.
TEST(CliUsage, AResumeIndexBeyondTheJobIsRefusedBeforeTheLinkWithTheJobsCount) {
  const ToolRun r = engraver("send " + kWord + " --to tcp://127.0.0.1:9 --resume-at 100000");
  EXPECT_EQ(r.code, 2) << r.err;
  // The last line (a slow plan prints its progress first).
  const std::string says =
      "engraver: --resume-at: '100000': this job has 72 job commands (INDEX 0 .. 71) of its 111 "
      "commands; a progress line's 'job 72' means the job had finished\n";
  ASSERT_GE(r.err.size(), says.size()) << r.err;
  EXPECT_EQ(r.err.substr(r.err.size() - says.size()), says) << r.err;
}

// serve's --poll-ms had a check of its own beside the option table's: its help gave two
// ranges ("INT:in [0 .. 1000] ms:INT in [1 - 1000]") and 0, which send takes, was refused.
TEST(CliUsage, ServesPollIntervalHasTheOneRangeOfTheOptionTable) {
  const ToolRun help = engraver("serve --help");
  EXPECT_EQ(help.code, 0) << help.err;
  EXPECT_NE(help.out.find("--poll-ms INT:in [0 .. 1000] ms"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("[1 - 1000]"), std::string::npos) << help.out;
  expect_usage_error("serve --poll-ms 1001", "--poll-ms: 1001 is outside the allowed range");
}

TEST(CliUsage, TheCuttingDepthOfADrawingIsAtOrBelowZero) {
  expect_usage_error("run " + kWord + " --z-down 5",
                     "--z-down: 5 is outside the allowed range -20 .. 0 mm");
  expect_usage_error("run " + kWord + " --z-down 1e300",
                     "--z-down: 1e300 is outside the allowed range -20 .. 0 mm");
}

TEST(CliUsage, OptionValueErrorsBeginLikeEveryOtherMessage) {
  expect_usage_error("run " + kWord + " --passes 1.5", "--passes: '1.5' is not a whole number");
}

TEST(CliUsage, AnOutputFolderThatIsAFileIsABadCommandLine) {
  const std::string file = testing::TempDir() + "/cli_usage_" + std::to_string(getpid());
  std::ofstream(file) << "x";
  expect_usage_error("run " + kWord + " -o " + file,
                     "--outdir: '" + file + "' is a file, not a folder");
  expect_usage_error("board top.gbr -o " + file,  // found before any file is read
                     "--outdir: '" + file + "' is a file, not a folder");
  // A folder to be made under a file fails only after planning unless found here.
  expect_usage_error("run " + kWord + " -o " + file + "/out",
                     "--outdir: '" + file + "/out' cannot be made: '" + file + "' is a file");
  std::remove(file.c_str());
}

// An empty value is not the option left out (outside tester 15: --side '' took the copper's
// side, --resume-at '' opened the link, serve --data '' wrote into the current folder).
TEST(CliUsage, AnEmptyValueIsABadCommandLine) {
  expect_usage_error("board top.gbr --side ''",
                     "--side: an empty value (leave the option out for its default)");
  expect_usage_error("run " + kWord + " -o ''", "--outdir: an empty value");
  expect_usage_error("send " + kWord + " --to tcp://127.0.0.1:9 --resume-at ''",
                     "--resume-at: an empty value");
  expect_usage_error("serve --data '' --listen 127.0.0.1:0", "--data: an empty value");
  expect_usage_error("info ''", "FILE: an empty value\n");  // no option to leave out
}

// An option a command does not have is named before any value it was given is judged
// (outside tester 19: `board DIR --tool-side ''` said "FILES: an empty value", the '' taken
// as a file), the words in the order given, an empty one shown as ''.
TEST(CliUsage, AnOptionTheCommandHasNotIsNamedFirst) {
  expect_usage_error("board top.gbr --tool-side ''",
                     "The following argument was not expected: --tool-side\n");
  expect_usage_error("points top.gbr --tool-side ''",
                     "The following arguments were not expected: --tool-side ''\n");
  expect_usage_error("points top.gbr --tool-side left",
                     "The following arguments were not expected: --tool-side left\n");
  expect_usage_error("board --bogus top.gbr --side ''",
                     "The following argument was not expected: --bogus\n");
  // Without one, the value's own message as before.
  expect_usage_error("board top.gbr --side ''",
                     "--side: an empty value (leave the option out for its default)\n");
  // `--` names nothing (tester 20: `info -- ''` said "not expected: --").
  expect_usage_error("info -- ''", "FILE: an empty value\n");
  expect_usage_error("info -- " + kWord + " extra",
                     "The following argument was not expected: extra\n");
  // One message is one line: a newline or a tab in a word is written \n or \t, a word with
  // a space is quoted.
  expect_usage_error("info " + kWord + " \"$(printf '%s\\n%s' --bo gus)\" 'two words'",
                     "The following arguments were not expected: '--bo\\ngus' 'two words'\n");
}

// `--side=` is an empty value like `--side ''` (tester 20: CLI11 took the next word for it,
// `--side= board.gbr` said the file was not a side, `--tol= 0.01` was accepted).
TEST(CliUsage, AnOptionWithAnEmptyValueAfterItsEqualsSignIsRefused) {
  expect_usage_error("board --side= top.gbr",
                     "--side: an empty value (leave the option out for its default)\n");
  expect_usage_error("points " + kWord + " --tol= 0.01",
                     "--tol: an empty value (leave the option out for its default)\n");
  // One the command does not have is named as such (it was "an empty value" too).
  expect_usage_error("board --bogus= top.gbr",
                     "The following argument was not expected: --bogus\n");
  // A switch takes no value at all (tester 22: `--json=` said "FILES: an empty value").
  expect_usage_error("board top.gbr --json=", "--json: a switch takes no value (give it alone)\n");
  // After `--` it is a word like any other.
  expect_usage_error("info " + kWord + " -- --tol=",
                     "The following argument was not expected: --tol=\n");
}

// A side that is not one, before the files are read and their notes printed.
TEST(CliUsage, ASideThatIsNotOneIsRefusedAsTheLineIsRead) {
  for (const std::string command : {"board", "run", "points"})
    expect_usage_error(command + " no-such-board/ --side sideways",
                       "--side: 'sideways' is not top or bottom");
}

// An unsigned count: CLI11 took -1 and 20 digits as 2^64 - 1 (spi expect then wrote a
// header promising 18446744073709551615 datagrams); a fraction's range is its own.
TEST(CliUsage, ACountIsNotNegativeNorPastAnyMeaning) {
  expect_usage_error("spi expect --scenario job " + kWord + " --max-datagrams -1",
                     "--max-datagrams: '-1' is negative: a count is 0 or more");
  expect_usage_error("spi expect --scenario job " + kWord + " --max-datagrams 99999999999999999999",
                     "--max-datagrams: '99999999999999999999' is too large");
  expect_usage_error("spi diff a.vcd b.golden --max-frame-errors -1",
                     "--max-frame-errors: -1 is outside the allowed range 0 .. 1");
  // serve's ranges in the words of every other (CLI11's "Value 2000 not in range" before);
  // a port no server takes, so that a missed check cannot leave one running.
  expect_usage_error("serve --max-upload-mb 2000 --listen 127.0.0.1:99999",
                     "--max-upload-mb: 2000 is outside the allowed range 0.001 .. 1024 MB");
  expect_usage_error("serve --stale-s 1 --listen 127.0.0.1:99999",
                     "--stale-s: 1 is outside the allowed range 2 .. 3600 s");
}

// spi's capture options are checked as the line is read, naming the value, in the words of
// every other option (the error came after, as "engraver: spi: error E_OPTION", without the
// value; hex and underflowing durations were taken; outside testers 15 and 17).
TEST(CliUsage, ACaptureOptionSpiCannotReadIsNamedAsTheLineIsRead) {
  const struct {
    std::string option, says;
  } cases[] = {
      {"--bits 65", "--bits: '65' is neither a whole number 1 .. 64 nor 'any'\n"},
      {"--bits x", "--bits: 'x' is neither a whole number 1 .. 64 nor 'any'\n"},
      {"--bits ' 32'", "--bits: ' 32' is neither a whole number 1 .. 64 nor 'any'\n"},
      {"--min-pulse 5parsecs", "--min-pulse: '5parsecs' is not a duration like 100ns"},
      {"--min-pulse 0x10ns", "--min-pulse: '0x10ns' is not a duration like 100ns"},
      {"--min-pulse 1e-400s", "--min-pulse: '1e-400s' is not a duration like 100ns"},
      {"--mode 4", "--mode: 4 is outside the allowed range 0 .. 3\n"},
      {"--bits ''", "--bits: an empty value"},
      // Numbers read as every number option reads them (tester 18): an empty one said as
      // every empty value, nan not "outside the range", 32.0 a whole number.
      {"--mode ''", "--mode: an empty value (leave the option out for its default)\n"},
      {"--bits 32.5", "--bits: '32.5' is neither a whole number 1 .. 64 nor 'any'\n"},
  };
  for (const auto& c : cases) expect_usage_error("spi decode a.vcd " + c.option, c.says);
  expect_usage_error("spi diff a.vcd b.golden --max-frame-errors nan",
                     "--max-frame-errors: 'nan' is not a finite number\n");
  expect_usage_error("board x.gbr --passes ''",
                     "--passes: an empty value (leave the option out for its default)\n");
  // 32.0 and +32 are 32: the capture is then what fails (a.vcd does not exist), not --bits.
  for (const std::string bits : {"32.0", "+32", "3.2e1"}) {
    const ToolRun r = engraver("spi decode /nonexistent/a.vcd --bits " + bits);
    EXPECT_EQ(r.err.rfind("engraver spi: error E_OPEN", 0), 0u) << bits << "\n" << r.err;
  }
}

// A word among a few, refused in the project's words (CLI11's were "--tool-side:  not in
// {centre,left,right}" for ''), an empty one as every empty value is.
TEST(CliUsage, AWordOptionNamesTheWordsItTakes) {
  expect_usage_error("run " + kWord + " --tool-side middle",
                     "--tool-side: 'middle' is not centre, left or right\n");
  expect_usage_error("run " + kWord + " --tool-side ''",
                     "--tool-side: an empty value (leave the option out for its default)\n");
  EXPECT_NE(engraver("run --help").out.find("--tool-side TEXT:{centre,left,right}=centre"),
            std::string::npos);
}

// --db is 'sqlite' or a PostgreSQL connection, checked as the line is read (exit 1 with
// libpq's "missing \"=\" after \"bogus\"" before).
TEST(CliUsage, AJobStoreIsSqliteOrAPostgresConnection) {
  for (const std::string db : {"bogus", "sqlite3", "mysql://host/db", "SQLITE"}) {
    expect_usage_error("serve --db '" + db + "' --listen 127.0.0.1:99999",
                       "--db: '" + db + "' is neither 'sqlite' nor a PostgreSQL connection");
  }
  // key=value pairs and URIs as libpq reads them, without connecting (outside tester 17:
  // these passed the check and failed the start, after the data folder was made).
  for (const std::string db : {"=x", "x=", "host=127.0.0.1 port=1 bogus=1", "postgresql://[::1"}) {
    expect_usage_error("serve --db '" + db + "' --listen 127.0.0.1:99999",
                       "--db: not a PostgreSQL connection: ");
  }
}

// -h before the command is that command's help, as for every other command (run, send and
// probe checked their FILE before it: "FILE is required"; serve's was the forwarder's stub).
TEST(CliUsage, HelpBeforeTheCommandIsItsHelp) {
  for (const std::string command : {"run", "send", "probe", "info", "board", "serve"}) {
    const ToolRun r = engraver("-h " + command);
    EXPECT_EQ(r.code, 0) << command << "\n" << r.err;
    EXPECT_NE(r.out.find("Usage: engraver " + command + " [OPTIONS]"), std::string::npos) << r.out;
    EXPECT_EQ(r.out, engraver(command + " --help").out) << command;
  }
}

}  // namespace
