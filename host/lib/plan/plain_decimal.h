// A number as written in the documentation: digits, an optional point and exponent. strtod
// and from_chars also take hex (0x10, 0x1p3), leading blanks, nan and inf, which no user
// means as a depth or a count: the command line's options and the server's upload fields
// refuse them by this one rule.
#ifndef HOST_LIB_PLAN_PLAIN_DECIMAL_H
#define HOST_LIB_PLAN_PLAIN_DECIMAL_H

#include <cmath>    // std::floor, std::isfinite
#include <cstddef>  // size_t
#include <cstdlib>  // std::strtod
#include <string>   // std::string

namespace host {

// True for "10", "-1.5", "+10", "10.", ".5e1"; false for "0x10", " 10", "nan", "1,5", "".
// The whole text must match [+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)? (read by hand:
// a std::regex built on the first option checked was 2 % of a small board's `board` command,
// docs/performance.md; PlainDecimal.AgreesWithTheRegexOnEveryShortText holds them equal).
inline bool is_plain_decimal(const std::string& text) {
  const size_t n = text.size();
  size_t i = 0;
  const auto digits = [&] {
    const size_t from = i;
    while (i < n && text[i] >= '0' && text[i] <= '9') ++i;
    return i - from;
  };
  if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
  size_t mantissa = digits();
  if (i < n && text[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == n;
}

// A count as every count option takes it: a plain decimal with nothing after the point
// ("2", "2.0", "1e1"; not "1.5", "0x2", "inf"). Huge ones (1e30) are whole too: the caller's
// range check refuses them, naming its range.
inline bool is_whole_decimal(const std::string& text) {
  if (!is_plain_decimal(text)) return false;
  const double v = std::strtod(text.c_str(), nullptr);
  return std::isfinite(v) && v == std::floor(v);
}

}  // namespace host

#endif  // HOST_LIB_PLAN_PLAIN_DECIMAL_H
