// The one range of every number option of the board commands, by name: every command that
// has the option (board, points, run, send, probe) checks it the same way, at parse time,
// naming the option and the range (a usage error, exit 2).
#ifndef HOST_CLI_OPTION_RANGES_H
#define HOST_CLI_OPTION_RANGES_H

#include <CLI/CLI.hpp>  // CLI::App

#include <string>  // std::string
#include <vector>  // std::vector

namespace host::cli {

struct OptionRange {
  const char* option;  // "--depth"
  double min, max;     // both allowed
  const char* unit;    // "mm", "mm/s", "" (a count or a fraction)
  bool integer;        // a count: the bounds are whole
};

// A number as written in the documentation: digits, an optional point and exponent. strtod
// and CLI11 also take hex floats (0x1p3), which no user means as a depth.
bool is_plain_decimal(const std::string& text);
// "'0x1p3' is not a decimal number", "'nan' is not a finite number", "" for a number.
std::string number_refusal(const std::string& value);

// The table, in the order the options appear in `board --help`.
const std::vector<OptionRange>& option_ranges();

// "0 is outside the allowed range 0.001 .. 5 mm" for a value outside `r`, "" inside (CLI11
// puts the option's name in front).
std::string range_refusal(const OptionRange& r, const std::string& value);

// The check of `r` for an option outside the table (spi diff, serve): the refusal above, and
// "in [0.001 .. 1024] MB" in --help.
CLI::Validator range_check(const OptionRange& r);

// Adds the table's check to every option of a table name in `app` and its commands, and to
// every number option a check that the value is a plain decimal (no hex float, no digit
// separators) and finite.
void add_option_checks(CLI::App* app);

// A word among `words`: "'middle' is not centre, left or right" (CLI11's IsMember said
// "middle not in {centre,left,right}"); "" is left to the empty-value check.
CLI::Validator one_of(const std::vector<std::string>& words);

// -o/--outdir: a folder, made if missing; an existing file there is a usage error (exit 2)
// before anything is planned, not a raw filesystem error after.
CLI::Validator output_folder();

}  // namespace host::cli

#endif  // HOST_CLI_OPTION_RANGES_H
