// What fitting G1 runs with cubic B-splines saves on the wire, on the pcb2gcode milling
// file in ../shared/samples (skipped when absent): the same plan with and without the fit,
// encoded as protocol frames. Only motion steps are encoded (pauses, dwells and spindle
// steps are the same in both and have no protocol v1 command).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <iostream>

#include "host/lib/plan/job_plan.h"
#include "host/lib/stream/job_encoder.h"

namespace host {
namespace {

size_t motion_bytes(JobPlan plan) {
  std::vector<PlanStep> motion;
  for (const PlanStep& s : plan.steps) {
    if (s.kind != PlanStep::kPause && s.kind != PlanStep::kDwell && s.kind != PlanStep::kSpindle)
      motion.push_back(s);
  }
  plan.steps = motion;
  return wire_bytes(encode_job(plan, EncodeOptions()));
}

TEST(FitBytes, Pcb2gcodeMillingFileTakesFewerBytesFitted) {
  const std::string f =
      std::string(ENGRAVER_SOURCE_DIR) + "/../shared/samples/pcb2gcode_example_board_back.ngc";
  struct stat st;
  if (stat(f.c_str(), &st) != 0) GTEST_SKIP() << f << " not present";
  const Drawing d = import_drawing(f);
  PlanOptions fitted, plain;
  plain.fit_tolerance_mm = 0;
  const size_t with_fit = motion_bytes(plan_job(d, fitted));
  const size_t without = motion_bytes(plan_job(d, plain));
  std::cout << "pcb2gcode_example_board_back.ngc: " << without << " bytes as G1 feeds, " << with_fit
            << " bytes with G1 runs fitted within " << fitted.fit_tolerance_mm << " mm\n";
  RecordProperty("bytes_feeds", static_cast<int>(without));
  RecordProperty("bytes_fitted", static_cast<int>(with_fit));
  EXPECT_LT(with_fit, without);
}

}  // namespace
}  // namespace host
