// The number and yes/no fields of an upload (upload_numbers.h).
#include "host/lib/server/upload_numbers.h"

#include <fmt/format.h>  // fmt::format

#include <cmath>    // std::isfinite, std::floor, std::fmax, std::fmin
#include <cstdlib>  // std::strtod

#include "host/lib/plan/plain_decimal.h"  // is_plain_decimal

namespace host::server {

std::string read_decimal_field(const std::string& key, const std::string& text, double* out) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  // "nan", "inf" and 1e400 parse: refused here, naming the field, not by the planner after
  // every comparison with them was false.
  const bool parsed = end != text.c_str() && *end == '\0';
  if (parsed && !std::isfinite(v)) return fmt::format("{} '{}' is not a finite number", key, text);
  if (!parsed || !is_plain_decimal(text)) {
    return fmt::format("{} '{}' is not a decimal number (digits, an optional point and exponent)",
                       key, text);
  }
  *out = v;
  return "";
}

std::string read_whole_field(const std::string& key, const std::string& text, int64_t* out) {
  double v = 0;
  const std::string why = read_decimal_field(key, text, &v);
  if (!why.empty()) return why;
  if (v != std::floor(v)) return fmt::format("{} '{}' is not a whole number", key, text);
  // 1e18 is whole too: held at +-1e15 (beyond it a double's whole numbers have gaps), which
  // no count or job id reaches, so the caller's range check names the field's range.
  *out = static_cast<int64_t>(std::fmax(-1e15, std::fmin(v, 1e15)));
  return "";
}

std::string read_flag_field(const std::string& key, const std::string& text, bool* out) {
  for (const char* yes : {"1", "true", "yes", "on"}) {
    if (text == yes) {
      *out = true;
      return "";
    }
  }
  for (const char* no : {"0", "false", "no", "off"}) {
    if (text == no) {
      *out = false;
      return "";
    }
  }
  return fmt::format("{} '{}' must be 1, true, yes or on (or 0, false, no or off)", key, text);
}

}  // namespace host::server
