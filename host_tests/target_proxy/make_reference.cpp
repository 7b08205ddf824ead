// Host generator of the proxy runner's reference tables: a few B-splines (cubic, quadratic,
// linear, rational, non-uniform, huge knots, a corner), their points computed in double
// precision by Eigen's unsupported/Eigen/Splines, and the point counts/hashes of the host
// build of core::CurveWalker. Writes a header the AVR build includes.
// Usage: make_reference OUTPUT.h
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <unsupported/Eigen/Splines>

#include "firmware/core/curve_walker.h"
#include "firmware/core/span_evaluator.h"
#include "firmware/core/spline.h"
#include "host_tests/target_proxy/reference_types.h"

namespace {

struct CurveSpec {
  const char* name;
  int degree;
  std::vector<long> knots;
  std::vector<std::array<long, 2>> points;
  std::vector<double> weights;  // empty: not rational
};

uint16_t weight_q14(double w) {
  return static_cast<uint16_t>(std::lround(w * 16384.0));
}

std::vector<CurveSpec> curve_specs() {
  const double r2 = std::sqrt(0.5);
  std::vector<CurveSpec> c;
  c.push_back({"cubic, uniform clamped knots, +-100 mm",
               3,
               {0, 0, 0, 0, 1000, 2000, 3000, 4000, 4000, 4000, 4000},
               {{0, 0},
                {20000, 50000},
                {60000, -30000},
                {100000, 80000},
                {140000, 10000},
                {170000, -60000},
                {200000, 0}},
               {}});
  c.push_back({"cubic, non-uniform knots, coordinates at the +-1 m limit",
               3,
               {0, 0, 0, 0, 7, 30, 31, 100, 100, 100, 100},
               {{-1000000, -1000000},
                {-400000, 900000},
                {500000, -950000},
                {1000000, 1000000},
                {-1000000, 500000},
                {999999, -999999},
                {0, 0}},
               {}});
  c.push_back({"quadratic, 5 control points",
               2,
               {0, 0, 0, 50, 100, 150, 150, 150},
               {{1000, 1000}, {31000, 51000}, {61000, 1000}, {91000, 51000}, {121000, 1000}},
               {}});
  c.push_back({"linear polyline",
               1,
               {0, 0, 10, 20, 30, 30},
               {{0, 0}, {12345, -6789}, {-50000, 70000}, {3, 4}},
               {}});
  c.push_back({"rational quadratic full circle, r = 50 mm",
               2,
               {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4},
               {{150000, 100000},
                {150000, 150000},
                {100000, 150000},
                {50000, 150000},
                {50000, 100000},
                {50000, 50000},
                {100000, 50000},
                {150000, 50000},
                {150000, 100000}},
               {1, r2, 1, r2, 1, r2, 1, r2, 1}});
  c.push_back(
      {"cubic with a corner (interior knot of multiplicity 3)",
       3,
       {0, 0, 0, 0, 500, 500, 500, 1000, 1000, 1000, 1000},
       {{0, 0}, {10000, 0}, {20000, 0}, {30000, 0}, {30000, 10000}, {30000, 20000}, {30000, 30000}},
       {}});
  c.push_back({"cubic, knots near 1e9 with spans of 3 and 300 units",
               3,
               {1000000000, 1000000000, 1000000000, 1000000000, 1000000003, 1000000303, 1000000303,
                1000000303, 1000000303},
               {{5000, 5000}, {25000, -15000}, {45000, 35000}, {65000, 5000}, {85000, 25000}},
               {}});
  return c;
}

core::Spline to_spline(const CurveSpec& spec) {
  core::Spline s = {};
  s.degree = static_cast<uint8_t>(spec.degree);
  s.rational = !spec.weights.empty();
  s.control_count = static_cast<uint16_t>(spec.points.size());
  s.knot_count = static_cast<uint16_t>(spec.knots.size());
  for (size_t i = 0; i < spec.points.size(); ++i) {
    s.control[i].x_um = static_cast<int32_t>(spec.points[i][0]);
    s.control[i].y_um = static_cast<int32_t>(spec.points[i][1]);
    s.control[i].weight_q14 = s.rational ? weight_q14(spec.weights[i]) : core::kWeightOneQ14;
  }
  for (size_t i = 0; i < spec.knots.size(); ++i) s.knot[i] = static_cast<int32_t>(spec.knots[i]);
  return s;
}

// The curve point at parameter u, in double precision, with the weights as stored (Q14).
Eigen::Vector2d eigen_point(const core::Spline& s, double u) {
  const int n = s.control_count;
  Eigen::RowVectorXd knots(s.knot_count);
  for (int i = 0; i < s.knot_count; ++i) knots(i) = s.knot[i];
  Eigen::MatrixXd homogeneous(3, n);
  for (int i = 0; i < n; ++i) {
    const double w = s.rational ? s.control[i].weight_q14 / 16384.0 : 1.0;
    homogeneous(0, i) = w * s.control[i].x_um;
    homogeneous(1, i) = w * s.control[i].y_um;
    homogeneous(2, i) = w;
  }
  // Knots near 1e9 lose nothing in double (53-bit mantissa); shift them anyway so the
  // basis functions are computed on small numbers.
  const double base = knots(0);
  knots.array() -= base;
  Eigen::Spline<double, 3> spline(knots, homogeneous);
  const Eigen::Vector3d p = spline(u - base);
  return Eigen::Vector2d(p(0) / p(2), p(1) / p(2));
}

long to_q6(double um) {
  return std::lround(um * 64.0);
}

core::PointUm to_um(const Eigen::Vector2d& p) {
  core::PointUm q;
  q.x_um = static_cast<int32_t>(std::floor(p(0) + 0.5));
  q.y_um = static_cast<int32_t>(std::floor(p(1) + 0.5));
  return q;
}

std::string point_text(const core::PointUm& p) {
  return "{" + std::to_string(p.x_um) + "L, " + std::to_string(p.y_um) + "L}";
}

void write_spline(std::ostream& out, const core::Spline& s, const char* name) {
  out << "  // " << name << "\n  {" << int(s.degree) << ", " << (s.rational ? "true" : "false")
      << ", " << s.control_count << ", " << s.knot_count << ",\n   {";
  for (int i = 0; i < s.control_count; ++i) {
    out << (i ? ", " : "") << "{" << s.control[i].x_um << "L, " << s.control[i].y_um << "L, "
        << s.control[i].weight_q14 << "U}";
  }
  out << "},\n   {";
  for (int i = 0; i < s.knot_count; ++i) out << (i ? ", " : "") << s.knot[i] << "L";
  out << "}},\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_reference OUTPUT.h\n";
    return 2;
  }
  const std::vector<CurveSpec> specs = curve_specs();
  std::vector<core::Spline> splines;
  for (const CurveSpec& spec : specs) {
    splines.push_back(to_spline(spec));
    if (core::validate_spline(splines.back()) != core::GeometryError::kOk) {
      std::cerr << "make_reference: curve \"" << spec.name << "\" rejected by validate_spline ("
                << int(core::validate_spline(splines.back())) << ")\n";
      return 1;
    }
  }

  std::ofstream out(argv[1]);
  out << "// Generated by host_tests/target_proxy/make_reference.cpp (Eigen, double precision)."
         "\n// Do not edit.\n#ifndef PROXY_REFERENCE_DATA_H\n#define PROXY_REFERENCE_DATA_H\n\n"
         "#include \"host_tests/target_proxy/proxy_platform.h\"\n"
         "#include \"host_tests/target_proxy/reference_types.h\"\n\nnamespace proxy {\n\n";
  out << "static const uint8_t kRefCurveCount = " << splines.size() << ";\n";
  out << "static const core::Spline kRefCurves[" << splines.size() << "] PROXY_ROM = {\n";
  for (size_t i = 0; i < splines.size(); ++i) write_spline(out, splines[i], specs[i].name);
  out << "};\n\n";

  // Points: every span at fixed and pseudo-random parameters, plus each curve's end.
  const uint32_t fixed_t[] = {0, 1, 255, 16384, 32768, 49151, 65535};
  uint32_t random_state = 0x2545F491u;
  std::vector<std::string> rows;
  for (size_t c = 0; c < splines.size(); ++c) {
    const core::Spline& s = splines[c];
    int last_span = -1;
    for (int span = s.degree; span < s.control_count; ++span) {
      if (s.knot[span] >= s.knot[span + 1]) continue;
      last_span = span;
      std::vector<uint32_t> ts(std::begin(fixed_t), std::end(fixed_t));
      for (int k = 0; k < 3; ++k) {
        random_state ^= random_state << 13;
        random_state ^= random_state >> 17;
        random_state ^= random_state << 5;
        ts.push_back(random_state & 0xFFFFu);
      }
      for (uint32_t t : ts) {
        const double u = s.knot[span] + (double(s.knot[span + 1]) - s.knot[span]) * t / 65536.0;
        const Eigen::Vector2d p = eigen_point(s, u);
        rows.push_back("  {" + std::to_string(c) + ", " + std::to_string(span) + ", " +
                       std::to_string(t) + "UL, " + std::to_string(to_q6(p(0))) + "L, " +
                       std::to_string(to_q6(p(1))) + "L},");
      }
    }
    const Eigen::Vector2d end = eigen_point(s, s.knot[s.control_count]);
    rows.push_back("  {" + std::to_string(c) + ", " + std::to_string(last_span) + ", 65536UL, " +
                   std::to_string(to_q6(end(0))) + "L, " + std::to_string(to_q6(end(1))) + "L},");
  }
  out << "static const uint16_t kRefPointCount = " << rows.size() << ";\n";
  out << "static const PointRef kRefPoints[" << rows.size() << "] PROXY_ROM = {\n";
  for (const std::string& r : rows) out << r << "\n";
  out << "};\n\n";

  // Stepping runs: uniform and adaptive on every curve, tool offsets on two.
  struct Run {
    size_t curve;
    core::StepMode mode;
    uint16_t tolerance;
    int32_t offset;
  };
  std::vector<Run> runs;
  for (size_t c = 0; c < splines.size(); ++c) {
    // Curve 1 spans metres: adaptive 5 um stepping gives ~150 000 points, too many for a
    // quick simulator run; it is stepped at a 1 mm tolerance.
    runs.push_back({c, core::StepMode::kAdaptive, (uint16_t)(c == 1 ? 1000 : 5), 0});
  }
  runs.push_back({0, core::StepMode::kAdaptive, 5, 500});
  runs.push_back({5, core::StepMode::kAdaptive, 5, -500});
  runs.push_back({5, core::StepMode::kAdaptive, 5, 500});
  out << "static const uint8_t kRefStepCount = " << runs.size() << ";\n";
  out << "static const StepRef kRefSteps[" << runs.size() << "] PROXY_ROM = {\n";
  for (const Run& run : runs) {
    const core::Spline& s = splines[run.curve];
    core::StepSettings settings = core::default_step_settings();
    settings.mode = run.mode;
    settings.chord_tolerance_um = run.tolerance;
    settings.tool_offset_um = run.offset;
    core::CurveWalker walker;
    walker.begin(&s, settings);
    core::PointUm p = {0, 0}, first = {0, 0}, last = {0, 0};
    uint32_t hash = proxy::kHashSeed;
    unsigned count = 0;
    while (count < proxy::kMaxStepPoints && walker.next(&p)) {
      if (count == 0) first = p;
      last = p;
      hash = proxy::hash_point(hash, p);
      ++count;
    }
    if (run.offset == 0) {
      first = to_um(eigen_point(s, s.knot[s.degree]));
      last = to_um(eigen_point(s, s.knot[s.control_count]));
    }
    out << "  {" << run.curve << ", " << int(run.mode) << ", " << int(walker.error()) << ", "
        << run.tolerance << ", " << run.offset << "L, " << count << ", " << hash << "UL, "
        << point_text(first) << ", " << point_text(last) << "},\n";
  }
  out << "};\n\n}  // namespace proxy\n\n#endif  // PROXY_REFERENCE_DATA_H\n";
  return out ? 0 : 1;
}
