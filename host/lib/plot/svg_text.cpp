// SVG documents as plain text (see svg_text.h).
#include "host/lib/plot/svg_text.h"

#include <cerrno>     // errno
#include <charconv>   // std::to_chars
#include <cmath>      // std::floor, std::fabs
#include <cstdio>     // std::snprintf, std::fopen
#include <cstring>    // std::strerror
#include <stdexcept>  // std::runtime_error

namespace host {

namespace {

// "%.2f" of v as printf gives it, trailing zeros dropped and "-0" as "0".
void append_fixed2_printf(std::string* out, double v) {
  // to_chars rounds as printf's "%.2f" does, without its format parsing and locale (snprintf
  // was nearly all of writing a board's SVG, docs/performance.md).
  char buf[64];
  const std::to_chars_result r =
      std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  int n = r.ec == std::errc() ? static_cast<int>(r.ptr - buf)
                              : std::snprintf(buf, sizeof buf, "%.2f", v);
  if (n < 0 || n >= static_cast<int>(sizeof buf)) n = 0;  // beyond any plot: drawn as 0
  while (n > 0 && buf[n - 1] == '0') --n;
  if (n > 0 && buf[n - 1] == '.') --n;
  if (n == 2 && buf[0] == '-' && buf[1] == '0') buf[0] = '0', n = 1;
  out->append(buf, n);
}

}  // namespace

// In hundredths as an integer: the same digits as "%.2f" unless v * 100 lies so near a half
// that its rounding needs the exact binary value (then printf's way). Formatting the double
// was most of writing a board's SVG.
SvgText& SvgText::operator<<(double v) {
  const double hundredths = v * 100;
  const double whole = std::floor(hundredths);
  // Below 1e9 the product is within 1e-7 of v's exact hundredths.
  if (!(std::fabs(hundredths) < 1e9) || std::fabs(hundredths - whole - 0.5) < 1e-6) {
    append_fixed2_printf(&out, v);
    return *this;
  }
  const long long h = static_cast<long long>(hundredths - whole < 0.5 ? whole : whole + 1);
  char buf[32];
  char* end = buf + sizeof buf;
  char* p = end;
  const bool negative = h < 0;
  unsigned long long u =
      negative ? 0ULL - static_cast<unsigned long long>(h) : static_cast<unsigned long long>(h);
  const unsigned cents = static_cast<unsigned>(u % 100);
  u /= 100;
  if (cents != 0) {
    if (cents % 10 != 0) *--p = static_cast<char>('0' + cents % 10);
    *--p = static_cast<char>('0' + cents / 10);
    *--p = '.';
  }
  do {
    *--p = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (negative) *--p = '-';  // h < 0: not zero as printed
  out.append(p, static_cast<size_t>(end - p));
  return *this;
}

SvgText& SvgText::colour(double r, double g, double b) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "rgb(%d,%d,%d)", static_cast<int>(r * 255 + 0.5),
                static_cast<int>(g * 255 + 0.5), static_cast<int>(b * 255 + 0.5));
  out += buf;
  return *this;
}

SvgText& SvgText::text(const std::string& s) {
  for (const char ch : s) {
    if (ch == '<')
      out += "&lt;";
    else if (ch == '>')
      out += "&gt;";
    else if (ch == '&')
      out += "&amp;";
    else if (ch == '"')
      out += "&quot;";
    else
      out += ch;
  }
  return *this;
}

void write_svg_file(const std::string& doc, const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) throw std::runtime_error(path + ": cannot write the plot: " + std::strerror(errno));
  const bool written = std::fwrite(doc.data(), 1, doc.size(), file) == doc.size();
  const int err = errno;
  if (std::fclose(file) != 0 || !written)
    throw std::runtime_error(path +
                             ": cannot write the plot: " + std::strerror(written ? errno : err));
}

}  // namespace host
