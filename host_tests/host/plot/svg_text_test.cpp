// The SVG's numbers: hundredths of a pixel as printf's "%.2f" rounds them (its exact binary
// value decides a half), trailing zeros dropped, never "-0".
#include "host/lib/plot/svg_text.h"

#include <gtest/gtest.h>

#include <cstdio>  // std::snprintf
#include <random>  // std::mt19937_64
#include <string>  // std::string

namespace host {
namespace {

std::string printf_way(double v) {
  char buf[64];
  std::string s(buf, static_cast<size_t>(std::snprintf(buf, sizeof buf, "%.2f", v)));
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string svg_way(double v) {
  SvgText t;
  t << v;
  return t.out;
}

TEST(SvgText, NumbersAreHundredthsAsPrintfRoundsThem) {
  const double cases[] = {0,      -0.0,  0.004,  -0.004,  0.005,  -0.005, 0.125,
                          -0.125, 0.135, 1.005,  2.675,   10,     -10,    0.1,
                          0.01,   -0.01, 99.995, -99.995, 1234.5, 0.999,  -0.999,
                          1e8,    -1e8,  1e12,   -1e12,   5e-324, 0.045,  1.015};
  for (const double v : cases) EXPECT_EQ(svg_way(v), printf_way(v)) << v;
  EXPECT_EQ(svg_way(12.5), "12.5");
  EXPECT_EQ(svg_way(-3.07), "-3.07");
  EXPECT_EQ(svg_way(-0.001), "0");
  std::mt19937_64 random(24);
  std::uniform_real_distribution<double> wide(-5000, 5000);
  std::uniform_int_distribution<int> cents(-500000, 500000);
  for (int i = 0; i < 200000; ++i) {
    const double v = wide(random);
    ASSERT_EQ(svg_way(v), printf_way(v)) << v;
    const double half = (cents(random) + 0.5) / 100;  // a half-cent as near as a double gets
    ASSERT_EQ(svg_way(half), printf_way(half)) << half;
  }
}

}  // namespace
}  // namespace host
