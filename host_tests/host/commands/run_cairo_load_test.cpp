// `run` writes its plan plot (NAME.svg) as plain text: the process maps libcairo (and its
// pixman, fontconfig, freetype, X11...) only when a PNG is asked for (--png). This binary
// links the commands alone, as the engraver does, not cairo.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>  // temp_directory_path, file_size
#include <fstream>     // std::ifstream
#include <sstream>     // std::stringstream

#include "host/lib/commands/run_command.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::commands {
namespace {

namespace fs = std::filesystem;

bool cairo_mapped() {
  std::ifstream maps("/proc/self/maps");
  std::stringstream text;
  text << maps.rdbuf();
  return text.str().find("libcairo") != std::string::npos;
}

TEST(RunCairoLoad, ThePlanPlotLeavesCairoUnloadedThePngLoadsIt) {
  const std::string dir =
      (fs::temp_directory_path() / ("run_cairo_load_test_" + std::to_string(getpid()))).string();
  fs::remove_all(dir);
  const JobPlan plan = test::plan_of(
      test::drawing_of({test::line_curve(0, 0, 10, 0), test::line_curve(20, 5, 20, 15)}));
  RunOptions o;
  o.file = "two-lines.dxf";
  o.name = "two-lines";
  o.outdir = dir;
  o.feed_mm_s = 10.0;
  ASSERT_FALSE(cairo_mapped());
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  EXPECT_GT(fs::file_size(r.base + ".svg"), 0u);
  EXPECT_FALSE(cairo_mapped());
  o.png = true;
  const RunResult with_png = run_job(plan, o);
  EXPECT_GT(fs::file_size(with_png.base + ".png"), 0u);
  EXPECT_TRUE(cairo_mapped());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace host::commands
