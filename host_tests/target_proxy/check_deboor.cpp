// On-target checks of the fixed-point De Boor evaluator (core::SpanEvaluator) against points
// computed in double precision by Eigen on the host (reference_data.h).
#include "firmware/core/span_evaluator.h"  // SpanEvaluator
#include "firmware/core/spline.h"          // Spline, validate_spline

#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

#ifdef PROXY_HAVE_REFERENCE
#include "reference_data.h"  // kRefCurves, kRefPoints (generated)
#endif

namespace proxy {

namespace {

// Largest error accepted, in 1/64 um: a quarter micrometre before rounding to 1 um.
const int32_t kToleranceQ6 = 16;

core::Spline g_curve;  // the reference curve in use (RAM copy of a flash table)
uint8_t g_curve_index = 0xFF;

}  // namespace

core::Spline* scratch_spline() {
  g_curve_index = 0xFF;  // no longer holds a reference curve
  return &g_curve;
}

#ifdef PROXY_HAVE_REFERENCE

const core::Spline& reference_curve(uint8_t index) {
  if (index != g_curve_index) {
    PROXY_ROM_COPY(&g_curve, &kRefCurves[index], sizeof(g_curve));
    g_curve_index = index;
  }
  return g_curve;
}

uint8_t reference_curve_count() {
  return kRefCurveCount;
}

void run_deboor_checks() {
  begin_group(PROXY_STR("deboor_vs_eigen"));
  for (uint8_t c = 0; c < kRefCurveCount; ++c) {
    PROXY_CHECK_EQ((int)core::validate_spline(reference_curve(c)), (int)core::GeometryError::kOk);
  }
  core::SpanEvaluator evaluator;
  uint8_t set_curve = 0xFF;
  uint16_t set_span = 0xFFFF;
  bool set_ok = false;
  int32_t worst_q6 = 0;
  for (uint16_t i = 0; i < kRefPointCount; ++i) {
    PointRef ref;
    PROXY_ROM_COPY(&ref, &kRefPoints[i], sizeof(ref));
    if (ref.curve != set_curve || ref.span != set_span) {
      set_ok = evaluator.setup(reference_curve(ref.curve), ref.span) == core::GeometryError::kOk;
      PROXY_CHECK(set_ok);
      set_curve = ref.curve;
      set_span = ref.span;
    }
    if (!set_ok) continue;
    const core::PointQ6 p = evaluator.evaluate_q6(ref.t_q16);
    PROXY_CHECK_NEAR(p.x_q6, ref.x_q6, kToleranceQ6);
    PROXY_CHECK_NEAR(p.y_q6, ref.y_q6, kToleranceQ6);
    const int32_t dx = p.x_q6 > ref.x_q6 ? p.x_q6 - ref.x_q6 : ref.x_q6 - p.x_q6;
    const int32_t dy = p.y_q6 > ref.y_q6 ? p.y_q6 - ref.y_q6 : ref.y_q6 - p.y_q6;
    if (dx > worst_q6) worst_q6 = dx;
    if (dy > worst_q6) worst_q6 = dy;
  }
  PROXY_PRINTF("measure De Boor worst |error| vs Eigen: %ld/64 um over %u points\n", (long)worst_q6,
               (unsigned)kRefPointCount);
  end_group();
}

#else

const core::Spline& reference_curve(uint8_t) {
  return g_curve;
}

uint8_t reference_curve_count() {
  return 0;
}

void run_deboor_checks() {
  PROXY_PRINTF("group deboor_vs_eigen: skipped (no reference data; build via the host tree)\n");
}

#endif

}  // namespace proxy
