// The `engraver spi` command group: decode a logic-analyser capture, print what the firmware
// should send, and diff the two (see docs/bench-testing.md).
#include <CLI/CLI.hpp>  // CLI::App

#include <cmath>     // std::floor
#include <cstdlib>   // std::strtod
#include <iostream>  // std::cout, std::cerr
#include <string>    // std::string

#include "host/cli/command_registry.h"  // CommandRegistrar
#include "host/cli/exit_codes.h"        // CommandFailure
#include "host/cli/option_ranges.h"     // range_refusal
#include "host/spi/commands.h"          // run_decode, run_expect, run_diff
#include "host/spi/framer.h"            // parse_duration_ps
#include "host/spi/scenario.h"          // available_scenarios

namespace {

// --bits as a whole number 1 .. 64, read as every count is (a plain decimal: 32, 32.0,
// +32), else 0.
int bits_value(const std::string& bits) {
  if (!host::cli::is_plain_decimal(bits)) return 0;
  const double b = std::strtod(bits.c_str(), nullptr);
  return b >= 1 && b <= 64 && b == std::floor(b) ? static_cast<int>(b) : 0;
}

// Options shared by decode and diff, bound to a FramerOptions.
struct CaptureOptions {
  host::spi::FramerOptions framer;
  std::string bits = "32";
  std::string min_pulse = "auto";
};

void add_capture_options(CLI::App* cmd, CaptureOptions* o) {
  cmd->add_option("--cs", o->framer.names.cs,
                  "chip-select channel (name or #index; 'none' = cut the stream every --bits)");
  cmd->add_option("--sck", o->framer.names.sck, "clock channel (default: SCK, CLK, SCLK...)");
  cmd->add_option("--mosi", o->framer.names.mosi, "MOSI channel (default: MOSI, SDI_C, SDO1...)");
  cmd->add_option("--miso", o->framer.names.miso, "MISO channel (default: MISO, SDO_C, SDI1...)");
  cmd->add_option("--mode", o->framer.mode, "SPI mode 0..3 (TMC428: 3)")
      ->check(host::cli::range_check({"--mode", 0, 3, "", false}))
      ->capture_default_str();
  // Both checked as the line is read, naming the value, as every other option is.
  cmd->add_option("--bits", o->bits,
                  "bits per datagram, or 'any' for whatever each CS period holds")
      ->check(CLI::Validator(
          [](const std::string& bits) {
            return bits.empty() || bits == "any" || bits_value(bits) > 0
                       ? std::string()
                       : "'" + bits + "' is neither a whole number 1 .. 64 nor 'any'";
          },
          "", "bits"))
      ->capture_default_str();
  cmd->add_option("--min-pulse", o->min_pulse,
                  "shorter clock/CS pulses are glitches, e.g. 100ns; 'auto' = 40% of the "
                  "median clock pulse; 0 = off")
      ->check(CLI::Validator(
          [](const std::string& pulse) {
            int64_t ps = 0;
            return pulse.empty() || pulse == "auto" || host::spi::parse_duration_ps(pulse, &ps)
                       ? std::string()
                       : "'" + pulse + "' is not a duration like 100ns, 'auto' or 0";
          },
          "", "duration"))
      ->capture_default_str();
}

// Ends the command with a non-zero code (the message is already on stderr or stdout).
void finish_with(int rc, const char* what) {
  if (rc != host::spi::kExitOk) throw host::cli::CommandFailure(rc, what);
}

// Turns the text options, checked as the line was read, into numbers.
host::spi::FramerOptions finish(const CaptureOptions& o) {
  host::spi::FramerOptions f = o.framer;
  f.bits = o.bits == "any" ? 0 : bits_value(o.bits);
  if (o.min_pulse == "auto") {
    f.min_pulse_ps = -1;
  } else {
    host::spi::parse_duration_ps(o.min_pulse, &f.min_pulse_ps);
  }
  return f;
}

// decode and diff: a CAPTURE read with the capture options into Options::framer, then `run`
// (run_decode, run_diff); exit 1 ends the command saying `exit1_message`, exit 2 that the
// capture is unusable. The options outlive parsing: statics, one set per Options (each
// command is registered once).
template <typename Options>
struct CaptureCommand {
  CLI::App* cmd;
  Options* options;
};
template <typename Options>
CaptureCommand<Options> add_capture_command(
    CLI::App* spi, const std::string& name, const std::string& help,
    int (*run)(const Options&, std::ostream&, std::ostream&), const char* exit1_message) {
  static Options options;
  static CaptureOptions capture;
  CLI::App* cmd = spi->add_subcommand(name, help);
  cmd->add_option("CAPTURE", options.capture, "capture file")->required();
  add_capture_options(cmd, &capture);
  const std::string unusable = "spi " + name + ": capture unusable (exit 2)";
  cmd->callback([run, exit1_message, unusable]() {
    options.framer = finish(capture);
    const int rc = run(options, std::cout, std::cerr);
    finish_with(rc, rc == 1 ? exit1_message : unusable.c_str());
  });
  return {cmd, &options};
}

void add_spi_commands(CLI::App& app) {
  CLI::App* spi = app.add_subcommand("spi",
                                     "SPI bench testing: decode captures, expected "
                                     "datagrams, diff");
  spi->require_subcommand(1);
  spi->footer(
      "Examples:\n"
      "  engraver spi expect --scenario init > init.golden\n"
      "  engraver spi decode capture.vcd\n"
      "  engraver spi diff capture.vcd init.golden --within\n"
      "Errors: 'engraver spi: error CODE: message' (docs/bench-testing.md). Each command's "
      "--help lists its exit codes.");

  const auto [dec, decode] = add_capture_command<host::spi::DecodeOptions>(
      spi, "decode",
      "Decode a capture (VCD, sigrok .sr, Saleae digital CSV, Saleae SPI-analyser CSV) into "
      "datagrams. Exit 0 clean, 1 frames flagged, 2 unusable.",
      host::spi::run_decode, "spi decode: datagrams with frame errors (exit 1)");
  dec->footer(
      "Example: engraver spi decode capture.vcd --json > frames.json\n"
      "Exit: 0 every datagram clean, 1 some flagged as frame errors, 2 unusable (cannot read, "
      "unknown format, channels not found, no datagrams, an option it cannot read).");
  dec->add_flag("--json", decode->json, "JSON output with stable keys");
  dec->add_flag("--raw", decode->raw, "hex words only (non-TMC428 captures)");

  static host::spi::ExpectOptions expect_run;
  host::spi::ExpectOptions* expect = &expect_run;
  std::string have = host::spi::available_scenarios();
  CLI::App* exp = spi->add_subcommand(
      "expect",
      "Print the datagrams the firmware sends in a scenario, as a golden file for `spi diff`. "
      "Scenarios in this build: " +
          (have.empty() ? std::string("none (the TMC428 driver/fakes are not built)") : have) +
          ". 'job FILE' streams the drawing to the simulated machine and keeps the init plus "
          "the first --max-datagrams datagrams after it (a whole job is ~7 per ms).");
  exp->add_option("--scenario", expect->scenario, "init | jog | job")->capture_default_str();
  exp->add_option("FILE", expect->job_file, "drawing for --scenario job");
  exp->add_option("--max-datagrams", expect->max_datagrams,
                  "job: datagrams kept after the init (0 = the whole job, hundreds of "
                  "thousands)")
      ->capture_default_str();
  exp->add_option("--vcd", expect->vcd_path,
                  "also write the datagrams as the fake SPI recorder's VCD (a capture of a "
                  "correct board, for trying decode/diff)");
  exp->footer(
      "Example: engraver spi expect --scenario job samples/engraver-word.dxf --max-datagrams "
      "500 > job.golden\n"
      "Exit: 0 written, 2 the scenario cannot be recorded (unknown, its FILE unreadable, or a "
      "job the simulated machine refuses or does not finish).");
  exp->callback([expect]() {
    finish_with(host::spi::run_expect(*expect, std::cout, std::cerr), "spi expect: failed");
  });

  const auto [dif, diff] = add_capture_command<host::spi::DiffOptions>(
      spi, "diff",
      "Align a capture's datagrams with an expected (golden) file. Marks: = same, ~ changed "
      "(same address byte), - expected but missing, + extra. Exit 0 match, 1 differ, "
      "2 capture unusable.",
      host::spi::run_diff, "spi diff: the capture differs (exit 1)");
  dif->add_option("EXPECTED", diff->expected, "golden file (from `spi expect`)")->required();
  dif->add_option("--max-frame-errors", diff->max_error_fraction,
                  "fraction of datagrams with frame errors above which the capture is unusable")
      ->capture_default_str()
      ->check(host::cli::range_check({"--max-frame-errors", 0.0, 1.0, "", false}));
  dif->footer(
      "Example: engraver spi diff capture.vcd init.golden --within\n"
      "Exit: 0 match, 1 differ, 2 capture unusable (unreadable, no datagrams, more than "
      "--max-frame-errors of them with frame errors) or golden file unreadable.");
  dif->add_flag("--json", diff->json, "JSON output with stable keys");
  dif->add_flag("--raw", diff->raw, "no TMC428 register names");
  dif->add_flag("--within", diff->within,
                "the expected datagrams may lie anywhere in the capture: datagrams before "
                "and after them are not compared (e.g. init inside a long capture)");
}

const host::cli::CommandRegistrar kRegisterSpi("spi", {"spi"}, add_spi_commands);

}  // namespace
