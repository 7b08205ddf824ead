// The board options' ranges, by name (see option_ranges.h).
#include "host/cli/option_ranges.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>       // std::isfinite, std::floor, std::fabs
#include <cstdlib>     // std::strtod
#include <filesystem>  // std::filesystem::status
#include <map>         // std::map

#include "host/lib/plan/job_defaults.h"
#include "host/lib/plan/plain_decimal.h"  // host::is_plain_decimal

namespace host::cli {

namespace {

using defaults::Range;

OptionRange real(const char* option, const Range& r) {
  return OptionRange{option, r.min, r.max, r.unit, false};
}

OptionRange count(const char* option, const Range& r) {
  return OptionRange{option, r.min, r.max, r.unit, true};
}

std::string refuse_non_number(std::string& value) {
  return number_refusal(value);
}

// A count given as 1.5 is refused (CLI11's own words were "Could not convert"); one given as
// 2.0 or 1e1 is a whole number, handed on as "2" or "10" (CLI11 converts digits only). Past
// 10^15 no count means anything (CLI11 wrapped 99999999999999999999 to 2^64 - 1).
std::string refuse_fraction(std::string& value) {
  const std::string refused = refuse_non_number(value);
  if (!refused.empty()) return refused;
  if (!host::is_whole_decimal(value)) return "'" + value + "' is not a whole number";
  const double v = std::strtod(value.c_str(), nullptr);
  if (std::fabs(v) >= 1e15) return "'" + value + "' is too large";
  value = fmt::format("{:.0f}", v);
  return "";
}

// An unsigned count: CLI11 took "-1" as 2^64 - 1.
std::string refuse_negative(std::string& value) {
  const double v = std::strtod(value.c_str(), nullptr);
  return v < 0 ? "'" + value + "' is negative: a count is 0 or more" : "";
}

// "" is not leaving an option out: CLI11 handed it on, and --side '' took the default side,
// serve --data '' the current folder.
const char* const kEmptyValue = "an empty value";
const char* const kLeaveItOut = " (leave the option out for its default)";

CLI::Validator refuse_empty(bool named_option) {
  const std::string said = std::string(kEmptyValue) + (named_option ? kLeaveItOut : "");
  return CLI::Validator(
      [said](const std::string& value) { return value.empty() ? said : std::string(); }, "",
      "not empty");
}

bool is_integer_option(const CLI::Option* o) {
  const std::string t = o->get_type_name();
  return t.rfind("INT", 0) == 0 || t.rfind("UINT", 0) == 0;
}

bool is_number_option(const CLI::Option* o) {
  return o->get_type_name().rfind("FLOAT", 0) == 0 || is_integer_option(o);
}

std::string bound_text(double v) {
  return fmt::format("{:g}", v);
}

// option_ranges() by long name without its dashes ("feed"): one look-up per option name
// (asking every option check_name() for every range was a third of `engraver --version`).
const std::map<std::string, const OptionRange*>& ranges_by_long_name() {
  static const std::map<std::string, const OptionRange*> by_name = [] {
    std::map<std::string, const OptionRange*> m;
    for (const OptionRange& r : option_ranges()) m.emplace(std::string(r.option).substr(2), &r);
    return m;
  }();
  return by_name;
}

void add_checks(CLI::App* app) {
  for (CLI::Option* o : app->get_options()) {
    // After the option's own checks, which may say more (--align-holes '': say auto).
    if (o->get_type_size_max() > 0) o->check(refuse_empty(!o->get_lnames().empty()));
    const bool whole = is_integer_option(o);
    if (whole && o->get_type_name().rfind("UINT", 0) == 0)
      o->transform(CLI::Validator(refuse_negative, "", "not negative"));  // after the fraction
    if (whole)
      o->transform(CLI::Validator(refuse_fraction, "", "whole"));  // may rewrite 2.0 as 2
    else if (is_number_option(o))
      o->check(CLI::Validator(refuse_non_number, "", "decimal"));
    for (const std::string& name : o->get_lnames()) {
      const auto found = ranges_by_long_name().find(name);
      if (found == ranges_by_long_name().end()) continue;
      // A count's range as a transform: CLI11 runs transforms first, the last added first,
      // so the range sees the value as typed (1e3), not as rewritten (1000).
      if (whole)
        o->transform(range_check(*found->second));
      else
        o->check(range_check(*found->second));
    }
  }
  for (CLI::App* sub : app->get_subcommands({})) add_checks(sub);
}

}  // namespace

bool is_plain_decimal(const std::string& v) {
  return host::is_plain_decimal(v);  // the server's upload fields take the same rule
}

// "nan" and "inf" parse as numbers and pass every comparison-based check.
std::string number_refusal(const std::string& value) {
  if (value.empty()) return std::string(kEmptyValue) + kLeaveItOut;
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (end != value.c_str() && *end == '\0' && !std::isfinite(v))
    return "'" + value + "' is not a finite number";
  if (!is_plain_decimal(value)) return "'" + value + "' is not a decimal number";
  return "";
}

const std::vector<OptionRange>& option_ranges() {
  using namespace defaults;
  static const std::vector<OptionRange> table = {
      real("--feed", kFeedRangeMmPerS),
      real("--z-up", kHeightAboveBoardRangeMm),
      real("--margin", kMarginRangeMm),
      real("--work", kWorkAreaRangeMm),
      real("--tool-width", kToolWidthRangeMm),
      count("--passes", kPassesRange),
      real("--overlap", kOverlapRange),
      real("--clearance", kClearanceRangeMm),
      real("--clearing-tool", kClearingToolRangeMm),
      count("--narrow-passes", kPassesRange),
      real("--depth", kIsolationDepthRangeMm),
      real("--drill-depth", kDrillDepthRangeMm),
      real("--drill-start", kHeightAboveBoardRangeMm),
      real("--drill-feed", kFeedRangeMmPerS),
      real("--cutter", kCutterRangeMm),
      real("--cut-depth", kCutDepthRangeMm),
      real("--cut-step", kCutDepthRangeMm),
      real("--cut-feed", kFeedRangeMmPerS),
      real("--tab-width", kTabWidthRangeMm),
      count("--tabs", kTabsRange),
      real("--tab-spacing", kTabSpacingRangeMm),
      real("--tab-height", kTabHeightRangeMm),
      real("--align-diameter", kAlignDiameterRangeMm),
      real("--align-depth", kAlignDepthRangeMm),
      real("--align-measured", kMachinePositionRangeMm),
      // Not board options: drawings', the link's and the height map's.
      real("--tol", kChordToleranceRangeMm),
      real("--scale", kScaleRange),
      real("--chain-tol", kChainToleranceRangeMm),
      real("--offset", offset_range_mm()),
      real("--tool-radius", kToolRadiusRangeMm),
      real("--z-down", kZDownRangeMm),
      real("--fit-tol", kFitToleranceRangeMm),
      count("--poll-ms", kPollIntervalRangeMs),
      real("--probe-spacing", kProbeSpacingRangeMm),
      count("--probe-grid", kProbeGridRange),
      real("--probe-margin", kProbeMarginRangeMm),
      real("--outlier-limit", kOutlierLimitRangeUm),
      real("--vbit-angle", kVbitAngleRangeDeg),
      real("--copper-um", kCopperRangeUm),
  };
  return table;
}

std::string range_refusal(const OptionRange& r, const std::string& value) {
  // Not a number, nan, hex: said as every number option says it ("nan is outside").
  const std::string not_a_number = number_refusal(value);
  if (!not_a_number.empty()) return not_a_number;
  const double v = std::strtod(value.c_str(), nullptr);
  if (v >= r.min && v <= r.max) return "";
  const std::string unit = *r.unit ? std::string(" ") + r.unit : std::string();
  return fmt::format("{} is outside the allowed range {} .. {}{}", value, bound_text(r.min),
                     bound_text(r.max), unit);
}

CLI::Validator range_check(const OptionRange& r) {
  const std::string unit = *r.unit ? std::string(" ") + r.unit : std::string();
  return CLI::Validator([r](std::string& v) { return range_refusal(r, v); },
                        "in [" + bound_text(r.min) + " .. " + bound_text(r.max) + "]" + unit,
                        "range");
}

CLI::Validator one_of(const std::vector<std::string>& words) {
  std::string list, braces;  // "a, b or c" for the message, "{a,b,c}" for --help as before
  for (size_t i = 0; i < words.size(); ++i) {
    list += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
    braces += (i == 0 ? "" : ",") + words[i];
  }
  return CLI::Validator(
      [words, list](const std::string& value) {
        for (const std::string& w : words)
          if (value == w) return std::string();
        return value.empty() ? std::string() : "'" + value + "' is not " + list;
      },
      "{" + braces + "}", "one of");
}

void add_option_checks(CLI::App* app) {
  add_checks(app);
}

CLI::Validator output_folder() {
  return CLI::Validator(
      [](const std::string& dir) -> std::string {
        std::error_code ec;
        const auto status = std::filesystem::status(dir, ec);
        if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
          return "'" + dir + "' is a file, not a folder";
        // A folder to be made under a file (out.json/x) fails only after the planning.
        for (std::filesystem::path up = std::filesystem::path(dir).parent_path(); !up.empty();
             up = up.parent_path()) {
          const auto s = std::filesystem::status(up, ec);
          if (std::filesystem::exists(s)) {
            if (!std::filesystem::is_directory(s))
              return "'" + dir + "' cannot be made: '" + up.string() + "' is a file";
            break;
          }
          if (up == up.parent_path()) break;
        }
        return "";
      },
      "FOLDER", "folder");
}

}  // namespace host::cli
