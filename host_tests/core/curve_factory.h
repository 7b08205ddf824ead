// Test curves: random and pathological splines, and exact rational circles.
#ifndef HOST_TESTS_CORE_CURVE_FACTORY_H
#define HOST_TESTS_CORE_CURVE_FACTORY_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "firmware/core/spline.h"

namespace testcurves {

struct RandomOptions {
  int degree;        // 1..3, or 0 for random
  int max_controls;  // up to core::kMaxControlPoints
  bool rational;
  uint16_t weight_min_q14;   // inclusive
  uint16_t weight_max_q14;   // inclusive
  int32_t coord_limit_um;    // control points in [-limit, limit]
  int64_t knot_lo, knot_hi;  // knot range (clamped to int32)
};

inline RandomOptions default_options() {
  RandomOptions o;
  o.degree = 0;
  o.max_controls = 16;
  o.rational = false;
  o.weight_min_q14 = 8192;
  o.weight_max_q14 = 32768;
  o.coord_limit_um = core::kMaxCoordinateUm;
  o.knot_lo = -1000000;
  o.knot_hi = 1000000;
  return o;
}

inline core::Spline empty_spline() {
  core::Spline s;
  std::memset(&s, 0, sizeof s);
  return s;
}

// Random spline: clamped or not, interior knots with random multiplicities (up to degree:
// the curve stays continuous, so a span's end equals the next span's start),
// knots anywhere in [knot_lo, knot_hi], at least one non-empty span.
inline core::Spline random_spline(std::mt19937& rng, const RandomOptions& o) {
  core::Spline s = empty_spline();
  const int p = o.degree ? o.degree : (int)(rng() % 3) + 1;
  const int n = p + 1 + (int)(rng() % (o.max_controls - p));
  s.degree = (uint8_t)p;
  s.rational = o.rational;
  s.control_count = (uint16_t)n;
  s.knot_count = (uint16_t)(n + p + 1);
  std::uniform_int_distribution<int32_t> coord(-o.coord_limit_um, o.coord_limit_um);
  std::uniform_int_distribution<int> weight(o.weight_min_q14, o.weight_max_q14);
  for (int i = 0; i < n; ++i) {
    s.control[i].x_um = coord(rng);
    s.control[i].y_um = coord(rng);
    s.control[i].weight_q14 = o.rational ? (uint16_t)weight(rng) : core::kWeightOneQ14;
  }
  std::uniform_int_distribution<int64_t> knot(o.knot_lo, o.knot_hi);
  std::vector<int64_t> k(s.knot_count);
  for (auto& v : k) v = knot(rng);
  std::sort(k.begin(), k.end());
  // Random multiplicities: copy a knot onto its successors sometimes.
  for (size_t i = 1; i < k.size(); ++i)
    if (rng() % 4 == 0) k[i] = k[i - 1];
  // Make the values distinct where a run would exceed multiplicity p (p + 1 at the ends).
  for (size_t i = 1; i < k.size(); ++i) k[i] = std::max(k[i], k[i - 1]);
  for (size_t i = (size_t)p; i < k.size(); ++i) {
    k[i] = std::max(k[i], k[i - 1]);
    bool run = true;
    for (int j = 1; j <= p; ++j) run = run && k[i - j] == k[i];
    if (run && i + 1 < k.size() - p) k[i] = k[i] + 1 + (int64_t)(rng() % 1000);
  }
  if (rng() % 2) {  // clamped ends
    for (int i = 0; i <= p; ++i) k[i] = k[0];
    for (int i = 0; i <= p; ++i) k[k.size() - 1 - i] = k.back();
  }
  if (k[p] == k[n]) k[n] = k[p] + 1 + (int64_t)(rng() % 1000);  // keep the domain non-empty
  for (size_t i = 1; i < k.size(); ++i) k[i] = std::max(k[i], k[i - 1]);
  for (size_t i = 0; i < k.size(); ++i)
    s.knot[i] = (int32_t)std::min<int64_t>(std::max<int64_t>(k[i], INT32_MIN), INT32_MAX);
  if (s.knot[p] == s.knot[n]) s.knot[p] = s.knot[n] - 1;  // clipping could collapse it
  for (int i = p - 1; i >= 0; --i) s.knot[i] = std::min(s.knot[i], s.knot[i + 1]);
  return s;
}

// Exact circle of radius r about (cx, cy) as a rational quadratic: 4 quarter arcs,
// 9 control points, corner weights sqrt(1/2), knots 0 0 0 1 1 2 2 3 3 4 4 4 (scaled).
inline core::Spline circle(int32_t cx, int32_t cy, int32_t r, bool counter_clockwise = true) {
  core::Spline s = empty_spline();
  s.degree = 2;
  s.rational = true;
  s.control_count = 9;
  s.knot_count = 12;
  const int dx[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
  const int dy[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
  const uint16_t w_corner = (uint16_t)std::lround(16384.0 * std::sqrt(0.5));
  for (int i = 0; i < 9; ++i) {
    s.control[i].x_um = cx + dx[i] * r;
    s.control[i].y_um = cy + (counter_clockwise ? dy[i] : -dy[i]) * r;
    s.control[i].weight_q14 = (i % 2) ? w_corner : core::kWeightOneQ14;
  }
  const int32_t knots[12] = {0, 0, 0, 100, 100, 200, 200, 300, 300, 400, 400, 400};
  for (int i = 0; i < 12; ++i) s.knot[i] = knots[i];
  return s;
}

// Clamped B-spline of degree p through the given control points with uniform knots.
inline core::Spline clamped_uniform(int p, const std::vector<std::pair<int32_t, int32_t>>& pts) {
  core::Spline s = empty_spline();
  const int n = (int)pts.size();
  s.degree = (uint8_t)p;
  s.control_count = (uint16_t)n;
  s.knot_count = (uint16_t)(n + p + 1);
  for (int i = 0; i < n; ++i) {
    s.control[i].x_um = pts[i].first;
    s.control[i].y_um = pts[i].second;
    s.control[i].weight_q14 = core::kWeightOneQ14;
  }
  for (int i = 0; i < s.knot_count; ++i) {
    int v = i - p;
    if (v < 0) v = 0;
    if (v > n - p) v = n - p;
    s.knot[i] = v * 1000;
  }
  return s;
}

}  // namespace testcurves

#endif  // HOST_TESTS_CORE_CURVE_FACTORY_H
