// Points per second of the fixed-point span evaluator and walker against Eigen's double
// B-spline evaluation (the reference the tests use). Figures go to docs/performance.md.
#include <benchmark/benchmark.h>

#include <cstring>
#include <unsupported/Eigen/Splines>  // Eigen::Spline

#include "firmware/core/curve_walker.h"
#include "firmware/core/span_evaluator.h"

namespace {

// A clamped cubic (or rational quadratic-weighted cubic) with 12 control points, ~A4 sized.
core::Spline bench_spline(bool rational) {
  core::Spline s;
  std::memset(&s, 0, sizeof s);
  s.degree = 3;
  s.rational = rational;
  s.control_count = 12;
  s.knot_count = 16;
  for (int i = 0; i < 12; ++i) {
    s.control[i].x_um = i * 25000;
    s.control[i].y_um = (i % 2 ? 150000 : 20000) + i * 3000;
    s.control[i].weight_q14 = rational ? (uint16_t)(12000 + 2000 * (i % 4)) : core::kWeightOneQ14;
  }
  for (int i = 0; i < 16; ++i) {
    int v = i - 3;
    if (v < 0) v = 0;
    if (v > 9) v = 9;
    s.knot[i] = v * 1000;
  }
  return s;
}

// One fixed-point point: Horner on a prepared span (the per-point path of the curve walker).
void BM_FixedPointPoint(benchmark::State& state) {
  const core::Spline s = bench_spline(state.range(0) != 0);
  core::SpanEvaluator e;
  e.setup(s, 5);
  uint16_t t = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.evaluate_q6(t));
    t = (uint16_t)(t + 997);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FixedPointPoint)->Arg(0)->Arg(1)->ArgName("rational");

// Span setup (blossoming + power basis): paid once per knot span.
void BM_FixedPointSpanSetup(benchmark::State& state) {
  const core::Spline s = bench_spline(state.range(0) != 0);
  core::SpanEvaluator e;
  uint16_t span = 3;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.setup(s, span));
    span = span == 11 ? 3 : (uint16_t)(span + 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FixedPointSpanSetup)->Arg(0)->Arg(1)->ArgName("rational");

// Eigen double evaluation at a parameter (homogeneous for the rational case).
void BM_EigenDoublePoint(benchmark::State& state) {
  const core::Spline s = bench_spline(state.range(0) != 0);
  typedef Eigen::Spline<double, 3> Spline3;
  Spline3::KnotVectorType knots(s.knot_count);
  for (int i = 0; i < s.knot_count; ++i) knots(i) = s.knot[i];
  Spline3::ControlPointVectorType ctrl(3, s.control_count);
  for (int i = 0; i < s.control_count; ++i) {
    const double w = s.control[i].weight_q14 / 16384.0;
    ctrl(0, i) = w * s.control[i].x_um;
    ctrl(1, i) = w * s.control[i].y_um;
    ctrl(2, i) = w;
  }
  const Spline3 spline(knots, ctrl);
  double u = 0;
  for (auto _ : state) {
    const Spline3::PointType h = spline(u);
    benchmark::DoNotOptimize(h(0) / h(2));
    benchmark::DoNotOptimize(h(1) / h(2));
    u += 0.997;
    if (u >= 9000) u = 0;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_EigenDoublePoint)->Arg(0)->Arg(1)->ArgName("rational");

// Whole walker, points per second (adaptive 5 or 50 um; offset 0 or 500 um): includes span
// setups, trial evaluations and offset normals.
void BM_CurveWalker(benchmark::State& state) {
  const core::Spline s = bench_spline(false);
  core::StepSettings st = core::default_step_settings();
  st.chord_tolerance_um = (uint16_t)state.range(0);
  st.tool_offset_um = (int32_t)state.range(1);
  int64_t points = 0;
  for (auto _ : state) {
    core::CurveWalker walker;
    walker.begin(&s, st);
    core::PointUm p;
    while (walker.next(&p)) {
      benchmark::DoNotOptimize(p);
      ++points;
    }
  }
  state.SetItemsProcessed(points);
}
BENCHMARK(BM_CurveWalker)
    ->Args({5, 0})
    ->Args({50, 0})
    ->Args({5, 500})
    ->Args({50, 500})
    ->ArgNames({"tolerance_um", "offset_um"});

}  // namespace

BENCHMARK_MAIN();
