// The `engraver spi` subcommands as plain functions (the CLI binds options to these; tests
// call them directly). Exit codes: 0 fine/match, 1 frame errors/differ, 2 unusable input.
#ifndef HOST_SPI_COMMANDS_H
#define HOST_SPI_COMMANDS_H

#include <ostream>  // std::ostream
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/spi/framer.h"    // FramerOptions
#include "host/spi/report.h"    // DecodeInfo
#include "host/spi/scenario.h"  // kDefaultJobDatagrams

namespace host::spi {

enum ExitCode { kExitOk = 0, kExitDiffer = 1, kExitUnusable = 2 };

// Loads and frames a capture (any supported format). Errors: E_OPEN, E_FORMAT, E_CHANNEL...
Error capture_frames(const std::string& path, const FramerOptions& options,
                     std::vector<Frame>* frames, DecodeInfo* info);

struct DecodeOptions {
  std::string capture;
  FramerOptions framer;
  bool json = false;
  bool raw = false;
};
// 0: all frames clean, 1: some frames flagged, 2: unreadable or no frames.
int run_decode(const DecodeOptions& o, std::ostream& out, std::ostream& err);

struct DiffOptions {
  std::string capture;
  std::string expected;
  FramerOptions framer;
  bool json = false;
  bool raw = false;                  // no TMC428 register names
  bool within = false;               // expected lines anywhere in the capture
  double max_error_fraction = 0.25;  // more frames with errors than this: unusable (2)
};
// 0: match, 1: differ, 2: capture unusable (unreadable, no frames, too many frame errors).
int run_diff(const DiffOptions& o, std::ostream& out, std::ostream& err);

struct ExpectOptions {
  std::string scenario = "init";                // init | jog | job
  std::string job_file;                         // for job
  std::string vcd_path;                         // also write the recorded datagrams as a VCD here
  size_t max_datagrams = kDefaultJobDatagrams;  // job: datagrams after the init; 0 = all
};
// Prints the golden file of a scenario. 0, or 2 when the scenario cannot be produced.
int run_expect(const ExpectOptions& o, std::ostream& out, std::ostream& err);

}  // namespace host::spi

#endif  // HOST_SPI_COMMANDS_H
