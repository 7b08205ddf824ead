// `engraver run` as a function: the stages on a small drawing, the report's fields against
// the simulation's figures, and the refusals.
#include <gtest/gtest.h>

#include <fmt/format.h>  // fmt::format

#include <filesystem>  // temp_directory_path, exists
#include <fstream>     // std::ifstream
#include <memory>      // std::make_shared
#include <sstream>     // std::stringstream
#include <string>      // std::string
#include <vector>      // std::vector

#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/run_command.h"
#include "host/lib/pcb/board_job.h"  // BoardJob
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host::commands {
namespace {

namespace fs = std::filesystem;

RunOptions small_run(const std::string& dir) {
  RunOptions o;
  o.file = "two-lines.dxf";
  o.name = "two-lines";
  o.outdir = dir;
  o.feed_mm_s = 10.0;
  o.chord_tolerance_mm = 0.01;
  o.encode.chord_tolerance_um = 10;
  return o;
}

JobPlan two_lines() {
  return test::plan_of(
      test::drawing_of({test::line_curve(0, 0, 10, 0), test::line_curve(20, 5, 20, 15)}));
}

TEST(RunCommand, ReportsTheSimulatedJobAndWritesItsPlots) {
  const std::string dir = (fs::temp_directory_path() / "run_command_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  const RunOptions o = small_run(dir);
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  EXPECT_EQ(r.base, (fs::path(dir) / "two-lines").string());
  EXPECT_TRUE(fs::exists(r.base + ".svg"));
  EXPECT_FALSE(fs::exists(r.base + ".png"));        // only with o.png (--png)
  EXPECT_FALSE(fs::exists(r.base + ".board.svg"));  // not a board
  EXPECT_FALSE(r.isolation);                        // nothing to check against copper

  const nlohmann::json j = run_report_json(plan, o, r);
  EXPECT_EQ(j["drawing"], "two-lines.dxf");
  EXPECT_EQ(j["outcome"], "completed");
  EXPECT_EQ(j["curves"], 2);
  EXPECT_EQ(j["commands"], r.sim.commands);
  EXPECT_EQ(j["job_id"], r.sim.job_id);
  EXPECT_EQ(j["job_wire_bytes"], r.sim.wire_bytes);
  EXPECT_EQ(j["feed_mm_per_s"], 10.0);
  EXPECT_EQ(j["chord_tolerance_mm"], 0.01);
  // 10 + 10 mm of lines at 10 mm/s; the tool traced them (to a tenth of a millimetre).
  EXPECT_NEAR(j["planned_cut_mm"].get<double>(), 20.0, 1e-9);
  EXPECT_NEAR(j["cut_length_over_feed_s"].get<double>(), 2.0, 1e-9);
  EXPECT_NEAR(j["traced_cut_mm"].get<double>(), 20.0, 0.1);
  // Straight lines: the controller generates a handful of points, each one G1 line.
  const PointCount n = count_points(plan, 0.01);
  EXPECT_EQ(j["points_generated"], n.points);
  EXPECT_EQ(j["gcode_g1_bytes_same_tolerance"], n.gcode_bytes);
  EXPECT_GE(n.points, 4u);
  EXPECT_FALSE(j.contains("height_map"));
  EXPECT_FALSE(j.contains("simulated_isolation_check"));
  EXPECT_FALSE(j.contains("flip"));
  EXPECT_EQ(j["pause_confirm_ms"], sim::SimOptions{}.pause_confirm_ms);

  const std::string text = run_report_text(plan, o, r);
  EXPECT_EQ(text.rfind("two-lines.dxf: 2 curves, ", 0), 0u) << text;
  EXPECT_NE(text.find("plot: " + r.base + ".svg"), std::string::npos) << text;
  EXPECT_NO_THROW(refuse_failed_run(o, r));
  write_run_report(j, r);
  EXPECT_TRUE(fs::exists(r.base + ".json"));
  fs::remove_all(dir);
}

TEST(RunCommand, WritesThePngPlotWhenAskedFor) {
  const std::string dir = (fs::temp_directory_path() / "run_command_png_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  RunOptions o = small_run(dir);
  o.png = true;
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  EXPECT_TRUE(fs::exists(r.base + ".svg"));
  EXPECT_GT(fs::file_size(r.base + ".png"), 0u);
  const std::string text = run_report_text(plan, o, r);
  EXPECT_NE(text.find("plot: " + r.base + ".svg, " + r.base + ".png; report:"), std::string::npos)
      << text;
}

// The progress line's total counts the commands sent before the job (here the height map's
// clearing); the report names them apart, so both add up to that total.
TEST(RunCommand, ReportCountsTheSetUpCommandsTheProgressTotalCounts) {
  const std::string dir = (fs::temp_directory_path() / "run_command_setup_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  RunOptions o = small_run(dir);
  size_t progress_total = 0;
  o.on_progress = [&progress_total](const Progress& p) { progress_total = p.total; };
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  EXPECT_EQ(r.sim.setup.commands, 1u);  // no map: one clearing
  const nlohmann::json j = run_report_json(plan, o, r);
  EXPECT_EQ(j["commands"].get<size_t>() + j["setup_commands"].get<size_t>(), progress_total);
  const std::string text = run_report_text(plan, o, r);
  EXPECT_NE(text.find(fmt::format("sent {} commands (and 1 set-up command before the job: the "
                                  "height map or its clearing) in ",
                                  r.sim.commands)),
            std::string::npos)
      << text;
  fs::remove_all(dir);
}

// A board's run reports what `board` does about it (issue 24's tester: a board without an
// outline said nothing of its missing cut-out in run's text or JSON, which had no `notes`).
TEST(RunCommand, ABoardsReportSaysWhyThereIsNoCutOutAndCarriesItsNotes) {
  const std::string dir = (fs::temp_directory_path() / "run_command_board_notes_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  RunOptions o = small_run(dir);
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  auto job = std::make_shared<pcb::BoardJob>();
  job->report.no_cutout = "no outline layer";
  job->report.notes = {"t-F.Cu.gbr: 3 openings in the copper hold no other island"};
  o.board = PlannedBoard{};
  o.board->job = job;
  const nlohmann::json j = run_report_json(plan, o, r);
  EXPECT_EQ(j["no_cutout"], "no outline layer");
  EXPECT_EQ(j["notes"], nlohmann::json::array({job->report.notes[0]}));
  const std::string text = run_report_text(plan, o, r);
  EXPECT_NE(text.find("\n  no cut-out: no outline layer\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n  note: t-F.Cu.gbr: 3 openings"), std::string::npos) << text;
  job->report.no_cutout.clear();  // cut out: no such line, the key ""
  EXPECT_EQ(run_report_json(plan, o, r)["no_cutout"], "");
  EXPECT_EQ(run_report_text(plan, o, r).find("no cut-out"), std::string::npos);
  o.board.reset();  // a drawing: neither key
  EXPECT_FALSE(run_report_json(plan, o, r).contains("no_cutout"));
  fs::remove_all(dir);
}

// The simulated isolation check's unseparated pairs are listed with where they are, as
// `board` lists them (an outside tester saw only "5 unseparated pairs").
TEST(RunCommand, TheSummaryListsTheIslandsNoCutSeparates) {
  const std::string dir = (fs::temp_directory_path() / "run_command_pairs_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  const RunOptions o = small_run(dir);
  RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  r.isolation = SimulatedIsolation{};
  EXPECT_EQ(run_report_text(plan, o, r).find("not separated by a cut"), std::string::npos);
  pcb::UnseparatedPair pair;
  pair.island_a = 9;
  pair.island_b = 11;
  pair.a_mm = Point2(23.5, 7.25);
  pair.b_mm = Point2(24.125, 7.5);
  r.isolation->check.unseparated = {pair};
  const std::string text = run_report_text(plan, o, r);
  EXPECT_NE(text.find("1 unseparated pair;"), std::string::npos) << text;
  EXPECT_NE(text.find("\n    islands 9 at (23.500, 7.250) and 11 at (24.125, 7.500) mm on the "
                      "machine are not separated by a cut\n"),
            std::string::npos)
      << text;
  fs::remove_all(dir);
}

// Every key of the run report (a board's with its simulated isolation check) is in the
// guide's list: `max_contour_error_at_mm` and seven others were written but not listed.
TEST(RunCommand, TheGuideNamesEveryKeyOfTheReport) {
  const std::string dir = (fs::temp_directory_path() / "run_command_guide_keys_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  RunOptions o = small_run(dir);
  RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  r.isolation = SimulatedIsolation{};
  r.isolation->clearing_min_clearance_um = 12.0;
  o.board = PlannedBoard{};
  o.board->job = std::make_shared<pcb::BoardJob>();
  const nlohmann::json j = run_report_json(plan, o, r);
  std::ifstream in(std::string(ENGRAVER_SOURCE_DIR) + "/docs/user-guide.md");
  std::stringstream guide;
  guide << in.rdbuf();
  ASSERT_FALSE(guide.str().empty());
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  for (const auto& [key, value] : j["simulated_isolation_check"].items()) keys.push_back(key);
  for (const std::string& key : keys)
    EXPECT_NE(guide.str().find("`" + key + "`"), std::string::npos) << key;
  EXPECT_NE(guide.str().find("**The machine frame.**"), std::string::npos);
  fs::remove_all(dir);
}

// The "plot:" line names every picture the run wrote: with a height map, its picture too.
TEST(RunCommand, PlotLineNamesEveryFileWritten) {
  const std::string dir = (fs::temp_directory_path() / "run_command_plot_files_test").string();
  fs::remove_all(dir);
  const JobPlan plan = two_lines();
  RunOptions o = small_run(dir);
  o.png = true;
  heightmap::HeightMap map;
  map.rows = map.cols = 2;
  map.pitch_x_mm = 40;
  map.pitch_y_mm = 30;
  map.heights_um = {0, 10, 5, 15};
  o.map = map;
  const RunResult r = run_job(plan, o);
  ASSERT_EQ(r.sim.outcome, JobOutcome::kCompleted) << r.sim.message;
  const std::vector<std::string> expected = {r.base + ".svg", r.base + ".png", r.base + ".map.svg"};
  EXPECT_EQ(r.plot_files, expected);
  for (const std::string& f : expected) EXPECT_TRUE(fs::exists(f)) << f;
  const std::string text = run_report_text(plan, o, r);
  EXPECT_NE(text.find("plot: " + r.base + ".svg, " + r.base + ".png, " + r.base +
                      ".map.svg; report: " + r.base + ".json"),
            std::string::npos)
      << text;
  fs::remove_all(dir);
}

TEST(RunCommand, ProbingWithoutASimulatedBlankIsAUsageErrorBeforeAnythingRuns) {
  const std::string dir = (fs::temp_directory_path() / "run_command_probe_test").string();
  fs::remove_all(dir);
  RunOptions o = small_run(dir);
  bool probed = false;
  o.probe = [&probed](Sender&) {
    probed = true;
    return heightmap::HeightMap{};
  };
  try {
    simulate_run(two_lines(), o);
    FAIL() << "probed nothing";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitUsage);
  }
  EXPECT_FALSE(probed);
  EXPECT_FALSE(fs::exists(dir));  // nothing written
}

TEST(RunCommand, AJobThatDidNotCompleteEndsWithItsOutcomesCode) {
  RunResult r;
  r.sim.outcome = JobOutcome::kAlarm;
  r.sim.message = "limit switch";
  try {
    refuse_failed_run(small_run("unused"), r);
    FAIL() << "an alarm passed";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitAlarm);
    EXPECT_EQ(std::string(e.what()), "job alarm: limit switch");
  }
}

TEST(RunCommand, PlotStepIsHalfAPixelOfTheJobAndAFloorForEmptyJobs) {
  EXPECT_DOUBLE_EQ(plot_step_mm(JobPlan{}), 0.05);
  const JobPlan plan = two_lines();  // about 25 x 20 mm with its 5 mm margin
  EXPECT_NEAR(plot_step_mm(plan), std::max(plan.extents_mm.max.x(), plan.extents_mm.max.y()) / 2000,
              1e-12);
}

}  // namespace
}  // namespace host::commands
