// Cycle counts on the proxy of the work the firmware repeats: one integer sqrt, one cubic
// 2-D De Boor point in fixed point and in float, one span setup, one stepping decision;
// and the RAM the core's objects take.
#include "firmware/core/curve_walker.h"    // CurveWalker
#include "firmware/core/divide.h"          // div_u32_u16, reciprocal_of, mul_reciprocal_q27
#include "firmware/core/fixed_point.h"     // mul_32x16_uq16
#include "firmware/core/isqrt.h"           // isqrt32
#include "firmware/core/span_evaluator.h"  // SpanEvaluator

#include "host_tests/target_proxy/float_deboor.h"
#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

namespace proxy {

namespace {

const uint8_t kSamples = 32;                   // parameters per span measured
const uint16_t kMaxStepPointsMeasured = 2000;  // next() calls measured per run

// min / average / max of a series of counts.
struct Stats {
  uint32_t min;
  uint32_t max;
  uint32_t sum;
  uint16_t n;
};

Stats g_stats;
volatile int32_t g_sink;  // results land here so the work is not optimised away

void stats_reset() {
  g_stats.min = 0xFFFFFFFFUL;
  g_stats.max = 0;
  g_stats.sum = 0;
  g_stats.n = 0;
}

void stats_add(uint32_t start, uint32_t stop) {
  uint32_t c = stop - start;
  c = c > cycles_overhead() ? c - cycles_overhead() : 0;
  if (c < g_stats.min) g_stats.min = c;
  if (c > g_stats.max) g_stats.max = c;
  g_stats.sum += c;
  ++g_stats.n;
}

// Prints "measure <name>: min .. avg .. max .. <unit> (n = ..)".
void stats_print(const char* name) {
  PROXY_PRINTF("measure ");
  PROXY_PRINT_STR(name);
  PROXY_PRINTF(": min %lu avg %lu max %lu %s (n = %u)\n", (unsigned long)g_stats.min,
               (unsigned long)(g_stats.n ? g_stats.sum / g_stats.n : 0), (unsigned long)g_stats.max,
               counter_unit(), (unsigned)g_stats.n);
}

// The measured curve: cubic, 7 control points, uniform clamped knots, +-100 mm (the same
// as reference curve 0), built here so measuring needs no reference data.
core::Spline* g_bench;

void build_bench_curve() {
  g_bench = scratch_spline();
  core::Spline& curve = *g_bench;
  static const int32_t kX[7] = {0, 20000, 60000, 100000, 140000, 170000, 200000};
  static const int32_t kY[7] = {0, 50000, -30000, 80000, 10000, -60000, 0};
  static const int32_t kKnots[11] = {0, 0, 0, 0, 1000, 2000, 3000, 4000, 4000, 4000, 4000};
  curve.degree = 3;
  curve.rational = false;
  curve.control_count = 7;
  curve.knot_count = 11;
  for (uint8_t i = 0; i < 7; ++i) {
    curve.control[i].x_um = kX[i];
    curve.control[i].y_um = kY[i];
    curve.control[i].weight_q14 = core::kWeightOneQ14;
  }
  for (uint8_t i = 0; i < 11; ++i) curve.knot[i] = kKnots[i];
}

void measure_isqrt() {
  stats_reset();
  uint32_t state = 0x9E3779B9UL;
  for (uint8_t i = 0; i < 64; ++i) {
    const uint32_t n = next_random(&state);
    const uint32_t a = cycles_now();
    const uint16_t r = core::isqrt32(n);
    const uint32_t b = cycles_now();
    g_sink = r;
    stats_add(a, b);
  }
  stats_print(PROXY_STR("isqrt32 (random 32-bit n)"));
}

void measure_span_setup(core::SpanEvaluator* evaluator) {
  stats_reset();
  for (uint16_t span = 3; span < 7; ++span) {
    const uint32_t a = cycles_now();
    const core::GeometryError e = evaluator->setup(*g_bench, span);
    const uint32_t b = cycles_now();
    g_sink = (int32_t)e;
    stats_add(a, b);
  }
  stats_print(PROXY_STR("fixed span setup, cubic 2-D (per span)"));
}

void measure_fixed_point(core::SpanEvaluator* evaluator, uint16_t span) {
  stats_reset();
  evaluator->setup(*g_bench, span);
  for (uint8_t i = 0; i < kSamples; ++i) {
    const uint32_t t = (uint32_t)i * (65536UL / kSamples) + 977U;
    const uint32_t a = cycles_now();
    const core::PointQ6 p = evaluator->evaluate_q6(t);
    const uint32_t b = cycles_now();
    g_sink = p.x_q6 + p.y_q6;
    stats_add(a, b);
  }
  stats_print(PROXY_STR("fixed De Boor point, cubic 2-D (evaluate_q6)"));
  stats_reset();
  for (uint8_t i = 0; i < kSamples; ++i) {
    const uint16_t t = (uint16_t)(i * (65536UL / kSamples) + 977U);
    const uint32_t a = cycles_now();
    const core::Direction d = evaluator->direction(t);
    const uint32_t b = cycles_now();
    g_sink = d.dx + d.dy;
    stats_add(a, b);
  }
  stats_print(PROXY_STR("derivative direction, cubic 2-D (direction, for tool offsets)"));
}

// The same curve made rational (weights 0.55..1.46, ratio < 3), span `span`.
void measure_fixed_rational(core::SpanEvaluator* evaluator, uint16_t span) {
  static const uint16_t kWeightQ14[7] = {16384, 12000, 20000, 16384, 9000, 24000, 16384};
  core::Spline& curve = *g_bench;
  curve.rational = true;
  for (uint8_t i = 0; i < 7; ++i) curve.control[i].weight_q14 = kWeightQ14[i];
  stats_reset();
  PROXY_CHECK(evaluator->setup(curve, span) == core::GeometryError::kOk);
  for (uint8_t i = 0; i < kSamples; ++i) {
    const uint32_t t = (uint32_t)i * (65536UL / kSamples) + 977U;
    const uint32_t a = cycles_now();
    const core::PointQ6 p = evaluator->evaluate_q6(t);
    const uint32_t b = cycles_now();
    g_sink = p.x_q6 + p.y_q6;
    stats_add(a, b);
  }
  stats_print(PROXY_STR("fixed De Boor point, rational cubic 2-D (evaluate_q6)"));
  build_bench_curve();  // back to the polynomial curve for the other measurements
}

void measure_float_point(const FloatCurve& curve, uint16_t span, core::SpanEvaluator* fixed) {
  stats_reset();
  const float left = curve.knot[span];
  const float width = curve.knot[span + 1] - left;
  int32_t worst_um = 0;
  for (uint8_t i = 0; i < kSamples; ++i) {
    const uint32_t t = (uint32_t)i * (65536UL / kSamples) + 977U;
    const float u = left + width * ((float)t / 65536.0f);
    float x = 0;
    float y = 0;
    const uint32_t a = cycles_now();
    float_deboor_point(curve, span, u, &x, &y);
    const uint32_t b = cycles_now();
    stats_add(a, b);
    // The float result must be the same point, or its timing means nothing.
    const core::PointUm q = core::round_point(fixed->evaluate_q6(t));
    const int32_t dx = (int32_t)(x + (x < 0 ? -0.5f : 0.5f)) - q.x_um;
    const int32_t dy = (int32_t)(y + (y < 0 ? -0.5f : 0.5f)) - q.y_um;
    const int32_t d =
        (dx < 0 ? -dx : dx) > (dy < 0 ? -dy : dy) ? (dx < 0 ? -dx : dx) : (dy < 0 ? -dy : dy);
    if (d > worst_um) worst_um = d;
  }
  stats_print(PROXY_STR("float De Boor point, cubic 2-D (textbook recursion)"));
  PROXY_CHECK(worst_um <= 2);  // float (24-bit mantissa) vs fixed at |coord| <= 2e5 um
}

void measure_float_horner(const FloatCurve& curve, uint16_t span) {
  FloatCubic cubic;
  float_cubic_from(curve, span, &cubic);
  stats_reset();
  for (uint8_t i = 0; i < kSamples; ++i) {
    const float t = ((float)i + 0.015f) / (float)kSamples;
    float x = 0;
    float y = 0;
    const uint32_t a = cycles_now();
    float_cubic_point(cubic, t, &x, &y);
    const uint32_t b = cycles_now();
    g_sink = (int32_t)(x + y);
    stats_add(a, b);
  }
  stats_print(PROXY_STR("float Horner point, cubic 2-D (span prepared)"));
}

// Cycles per next() call of a whole run (one step decision and its point each).
void measure_stepping(core::StepMode mode, int32_t offset_um, const char* name) {
  static core::CurveWalker walker;
  core::StepSettings settings = core::default_step_settings();
  settings.mode = mode;
  settings.tool_offset_um = offset_um;
  walker.begin(g_bench, settings);
  stats_reset();
  core::PointUm p = {0, 0};
  for (uint16_t i = 0; i < kMaxStepPointsMeasured; ++i) {
    const uint32_t a = cycles_now();
    const bool more = walker.next(&p);
    const uint32_t b = cycles_now();
    if (!more) break;
    stats_add(a, b);
    g_sink = p.x_um;
  }
  stats_print(name);
}

// Operands the compiler cannot see through (so each operation really runs).
volatile int32_t g_a32 = 123456789L;
volatile int32_t g_b32 = -98765L;
volatile int16_t g_a16 = -12345;
volatile uint16_t g_b16 = 54321U;
volatile float g_af = 1234.5678f;
volatile float g_bf = -0.98765f;

// Cost of single arithmetic primitives, to translate the proxy's cycle counts to the
// dsPIC (where a 16x16 multiply is one instruction and float is a library call).
void measure_primitives() {
  const uint8_t kRuns = 16;
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const int16_t a = g_a16;
    const uint16_t b = g_b16;
    const uint32_t t0 = cycles_now();
    const int32_t r = (int32_t)a * (uint32_t)b;
    const uint32_t t1 = cycles_now();
    g_sink = r;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive 16x16->32 multiply (widening)"));
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const int32_t a = g_a32;
    const int32_t b = g_b32;
    const uint32_t t0 = cycles_now();
    const int32_t r = a * b;
    const uint32_t t1 = cycles_now();
    g_sink = r;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive 32x32->32 multiply"));
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const int32_t a = g_a32;
    const uint16_t b = g_b16;
    const uint32_t t0 = cycles_now();
    const int32_t r = core::mul_32x16_uq16(a, b);
    const uint32_t t1 = cycles_now();
    g_sink = r;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive core::mul_32x16_uq16"));

  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const uint32_t n = (uint32_t)g_a32;
    const uint16_t d = g_b16;
    const uint32_t t0 = cycles_now();
    const uint16_t q = core::div_u32_u16(n, d, 0);  // n >> 16 < d
    const uint32_t t1 = cycles_now();
    g_sink = q;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive core::div_u32_u16 (32/16, DIV.UD on the dsPIC)"));
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const int32_t w = g_a32 >> 3;
    const uint32_t t0 = cycles_now();
    const core::Reciprocal r = core::reciprocal_of(w);
    const uint32_t t1 = cycles_now();
    g_sink = (int32_t)r.r_q62;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive core::reciprocal_of"));
  stats_reset();
  const core::Reciprocal inv = core::reciprocal_of(g_a32 >> 3);
  for (uint8_t i = 0; i < kRuns; ++i) {
    const int32_t x = g_b32;
    const uint32_t t0 = cycles_now();
    const int32_t q = core::mul_reciprocal_q27(x, inv);
    const uint32_t t1 = cycles_now();
    g_sink = q;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive core::mul_reciprocal_q27"));

  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const float a = g_af;
    const float b = g_bf;
    const uint32_t t0 = cycles_now();
    const float r = a * b;
    const uint32_t t1 = cycles_now();
    g_af = r;
    g_af = 1234.5678f;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive float multiply"));
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const float a = g_af;
    const float b = g_bf;
    const uint32_t t0 = cycles_now();
    const float r = a + b;
    const uint32_t t1 = cycles_now();
    g_af = r;
    g_af = 1234.5678f;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive float add"));
  stats_reset();
  for (uint8_t i = 0; i < kRuns; ++i) {
    const float a = g_af;
    const float b = g_bf;
    const uint32_t t0 = cycles_now();
    const float r = a / b;
    const uint32_t t1 = cycles_now();
    g_af = r;
    g_af = 1234.5678f;
    stats_add(t0, t1);
  }
  stats_print(PROXY_STR("primitive float divide"));
}

}  // namespace

void run_measurements() {
  begin_group(PROXY_STR("measurements"));
  build_bench_curve();
  static core::SpanEvaluator evaluator;
  static FloatCurve float_curve;
  PROXY_CHECK(float_curve_from(*g_bench, &float_curve));
  const uint16_t span = 4;
  measure_primitives();
  measure_isqrt();
  measure_span_setup(&evaluator);
  measure_fixed_point(&evaluator, span);
  measure_float_point(float_curve, span, &evaluator);
  measure_float_horner(float_curve, span);
  measure_fixed_rational(&evaluator, span);
  measure_stepping(core::StepMode::kAdaptive, 0, PROXY_STR("walker next(), adaptive 5 um"));
  measure_stepping(core::StepMode::kAdaptive, 500,
                   PROXY_STR("walker next(), adaptive 5 um, tool offset 0.5 mm"));
  PROXY_PRINTF("memory sizeof Spline %u, SpanEvaluator %u, CurveWalker %u bytes\n",
               (unsigned)sizeof(core::Spline), (unsigned)sizeof(core::SpanEvaluator),
               (unsigned)sizeof(core::CurveWalker));
  end_group();
}

}  // namespace proxy
