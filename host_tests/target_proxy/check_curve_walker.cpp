// On-target checks of parameter stepping (core::CurveWalker): the first and last points
// are the curve ends computed by Eigen, and every run emits the same points (count and
// hash) as the host build of the same code, so 16-bit int changes nothing.
#include "firmware/core/curve_walker.h"  // CurveWalker, StepSettings

#include "host_tests/target_proxy/proxy_check.h"
#include "host_tests/target_proxy/proxy_checks.h"

#ifdef PROXY_HAVE_REFERENCE
#include "reference_data.h"  // kRefSteps (generated)
#endif

namespace proxy {

#ifdef PROXY_HAVE_REFERENCE

namespace {

// Runs one reference stepping run and compares it.
void check_run(const StepRef& ref) {
  core::StepSettings settings = core::default_step_settings();
  settings.mode = (core::StepMode)ref.mode;
  settings.chord_tolerance_um = ref.chord_tolerance_um;
  settings.tool_offset_um = ref.tool_offset_um;
  static core::CurveWalker walker;  // static: keeps the stack small
  const core::Spline& curve = reference_curve(ref.curve);
  PROXY_CHECK_EQ((int)walker.begin(&curve, settings), (int)core::GeometryError::kOk);
  core::PointUm p = {0, 0};
  core::PointUm first = {0, 0};
  core::PointUm last = {0, 0};
  uint32_t hash = kHashSeed;
  uint16_t count = 0;
  while (count < kMaxStepPoints && walker.next(&p)) {
    if (count == 0) first = p;
    last = p;
    hash = hash_point(hash, p);
    ++count;
  }
  PROXY_CHECK_EQ(count, ref.count);
  PROXY_CHECK(hash == ref.hash);
  PROXY_CHECK_EQ((int)walker.error(), ref.error);
  // Curve ends (Eigen) within 1 um for plain runs; the host's ends for offset runs.
  const int32_t tolerance_um = ref.tool_offset_um == 0 ? 1 : 0;
  PROXY_CHECK_NEAR(first.x_um, ref.first.x_um, tolerance_um);
  PROXY_CHECK_NEAR(first.y_um, ref.first.y_um, tolerance_um);
  PROXY_CHECK_NEAR(last.x_um, ref.last.x_um, tolerance_um);
  PROXY_CHECK_NEAR(last.y_um, ref.last.y_um, tolerance_um);
}

}  // namespace

void run_curve_walker_checks() {
  begin_group(PROXY_STR("walker"));
  for (uint8_t i = 0; i < kRefStepCount; ++i) {
    StepRef ref;
    PROXY_ROM_COPY(&ref, &kRefSteps[i], sizeof(ref));
    check_run(ref);
  }
  end_group();
}

#else

void run_curve_walker_checks() {
  PROXY_PRINTF("group walker: skipped (no reference data; build via the host tree)\n");
}

#endif

}  // namespace proxy
