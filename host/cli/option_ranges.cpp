// The board options' ranges, by name (see option_ranges.h).
#include "host/cli/option_ranges.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>    // std::isfinite
#include <cstdlib>  // std::strtod
#include <regex>    // std::regex

#include "host/lib/plan/job_defaults.h"

namespace host::cli {

namespace {

using defaults::Range;

OptionRange real(const char* option, const Range& r, const char* unit) {
  return OptionRange{option, r.min, r.max, unit, false};
}

OptionRange count(const char* option, const Range& r) {
  return OptionRange{option, r.min, r.max, "", true};
}

// A number as written in the documentation: digits, an optional point and exponent. strtod
// and CLI11 also take hex floats (0x1p3), which no user means as a depth.
bool plain_decimal(const std::string& v) {
  static const std::regex decimal(R"([+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?)");
  return std::regex_match(v, decimal);
}

// "nan" and "inf" parse as numbers and pass every comparison-based check.
std::string refuse_non_number(std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end != value.c_str() && *end == '\0' && !std::isfinite(v))
    return "'" + value + "' is not a finite number";
  if (!plain_decimal(value)) return "'" + value + "' is not a decimal number";
  return "";
}

bool is_number_option(const CLI::Option* o) {
  const std::string t = o->get_type_name();
  return t.rfind("FLOAT", 0) == 0 || t.rfind("INT", 0) == 0 || t.rfind("UINT", 0) == 0;
}

std::string bound_text(double v) {
  return fmt::format("{:g}", v);
}

void add_checks(CLI::App* app) {
  for (CLI::Option* o : app->get_options()) {
    if (is_number_option(o)) o->check(CLI::Validator(refuse_non_number, "", "decimal"));
    for (const OptionRange& r : option_ranges()) {
      if (o->check_name(r.option)) {
        const std::string unit = *r.unit ? std::string(" ") + r.unit : std::string();
        o->check(CLI::Validator(
            [r](std::string& v) { return range_refusal(r, v); },
            "in [" + bound_text(r.min) + " .. " + bound_text(r.max) + "]" + unit, "range"));
      }
    }
  }
  for (CLI::App* sub : app->get_subcommands({})) add_checks(sub);
}

}  // namespace

const std::vector<OptionRange>& option_ranges() {
  using namespace defaults;
  static const std::vector<OptionRange> table = {
      real("--feed", kFeedRangeMmPerS, "mm/s"),
      real("--z-up", kHeightAboveBoardRangeMm, "mm"),
      real("--margin", kMarginRangeMm, "mm"),
      real("--work", kWorkAreaRangeMm, "mm"),
      real("--tool-width", kToolWidthRangeMm, "mm"),
      count("--passes", kPassesRange),
      real("--overlap", kOverlapRange, ""),
      real("--clearance", kClearanceRangeMm, "mm"),
      real("--clearing-tool", kClearingToolRangeMm, "mm"),
      count("--narrow-passes", kPassesRange),
      real("--depth", kIsolationDepthRangeMm, "mm"),
      real("--drill-depth", kDrillDepthRangeMm, "mm"),
      real("--drill-start", kHeightAboveBoardRangeMm, "mm"),
      real("--drill-feed", kFeedRangeMmPerS, "mm/s"),
      real("--cutter", kCutterRangeMm, "mm"),
      real("--cut-depth", kCutDepthRangeMm, "mm"),
      real("--cut-step", kCutDepthRangeMm, "mm"),
      real("--cut-feed", kFeedRangeMmPerS, "mm/s"),
      real("--tab-width", kTabWidthRangeMm, "mm"),
      count("--tabs", kTabsRange),
      real("--tab-spacing", kTabSpacingRangeMm, "mm"),
      real("--tab-height", kTabHeightRangeMm, "mm"),
      real("--align-diameter", kAlignDiameterRangeMm, "mm"),
      real("--align-depth", kAlignDepthRangeMm, "mm"),
      real("--align-measured", kMachinePositionRangeMm, "mm"),
  };
  return table;
}

std::string range_refusal(const OptionRange& r, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end == value.c_str()) return "";  // not a number: CLI11 says so
  if (v >= r.min && v <= r.max) return "";
  const std::string unit = *r.unit ? std::string(" ") + r.unit : std::string();
  return fmt::format("{} is outside the allowed range {} .. {}{}", value, bound_text(r.min),
                     bound_text(r.max), unit);
}

void add_option_checks(CLI::App* app) {
  add_checks(app);
}

}  // namespace host::cli
