// `spi expect --scenario job FILE`: a drawing streamed to the simulated machine gives a golden
// file that starts with the TMC428 init, carries the path controller's v_target writes, is
// bounded by --max-datagrams, and fits the recorder's own VCD of the same run.
#include <gtest/gtest.h>

#include <sstream>  // std::ostringstream

#include "host/spi/commands.h"  // run_expect, run_diff
#include "host/spi/golden.h"    // parse_golden
#include "host/spi/scenario.h"  // record_scenario
#include "host_tests/spi/test_util.h"

using namespace host::spi;

namespace {

// A 10 mm cubic arch in millimetres (one SPLINE, clamped knots): a job of about 4 s.
const char kArchDxf[] =
    "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n"
    "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n5\n2A\n8\n0\n70\n8\n71\n3\n72\n8\n73\n4\n"
    "40\n0\n40\n0\n40\n0\n40\n0\n40\n1\n40\n1\n40\n1\n40\n1\n"
    "10\n5\n20\n5\n30\n0\n10\n8\n20\n9\n30\n0\n10\n12\n20\n9\n30\n0\n10\n15\n20\n5\n30\n0\n"
    "0\nENDSEC\n0\nEOF\n";

// v_target of motor 1, 2, 3 written (address byte 0x08, 0x28, 0x48: docs/tmc428.md).
bool is_v_target_write(uint32_t mosi) {
  const uint32_t a = mosi >> 24;
  return a == 0x08 || a == 0x28 || a == 0x48;
}

struct JobGolden {
  std::string text;
  std::string vcd_path;
  std::vector<Expected> lines;
  int rc = -1;
};

// The arch's golden file and VCD, recorded once for the tests below.
const JobGolden& arch_job() {
  static JobGolden g = [] {
    JobGolden j;
    ExpectOptions o;
    o.scenario = "job";
    o.job_file = spi_test::temp_file("arch.dxf", kArchDxf);
    o.vcd_path = ::testing::TempDir() + "/arch_job_" + std::to_string(::getpid()) + ".vcd";
    o.max_datagrams = 1500;
    std::ostringstream out, err;
    j.rc = run_expect(o, out, err);
    EXPECT_EQ(j.rc, kExitOk) << err.str();
    j.text = out.str();
    j.vcd_path = o.vcd_path;
    EXPECT_TRUE(parse_golden(j.text, &j.lines).ok());
    return j;
  }();
  return g;
}

TEST(JobScenario, GoldenStartsWithTheInitSequence) {
  std::ostringstream init, err;
  ASSERT_EQ(run_expect(ExpectOptions(), init, err), kExitOk) << err.str();
  std::vector<Expected> init_lines;
  ASSERT_TRUE(parse_golden(init.str(), &init_lines).ok());
  const JobGolden& job = arch_job();
  ASSERT_GT(job.lines.size(), init_lines.size());
  for (size_t i = 0; i < init_lines.size(); ++i) {
    EXPECT_EQ(pattern_text(job.lines[i].mosi), pattern_text(init_lines[i].mosi)) << "line " << i;
    EXPECT_EQ(pattern_text(job.lines[i].miso), pattern_text(init_lines[i].miso)) << "line " << i;
  }
}

TEST(JobScenario, GoldenCarriesThePenLiftAsZVTargetWrites) {
  // The job starts by lifting Z to the travel height: M3.v_target ramps up from 0.
  int z_moving = 0;
  for (const Expected& e : arch_job().lines) {
    const uint32_t mosi = static_cast<uint32_t>(e.mosi.value);
    if ((mosi >> 24) == 0x48 && (mosi & 0xFFF) != 0) ++z_moving;
  }
  EXPECT_GT(z_moving, 100);
}

TEST(JobScenario, WholeJobWritesXAndYVelocitiesAndCompletes) {
  // The arch starts at the zero corner: lift, plunge, then X and Y move along the curve.
  ScenarioRequest job;
  job.name = "job";
  job.job_file = spi_test::temp_file("arch_whole.dxf", kArchDxf);
  job.max_job_datagrams = 0;
  ScenarioRecording rec;
  ASSERT_TRUE(record_scenario(job, false, &rec).ok());
  int moving_x = 0, moving_y = 0, v_target_writes = 0;
  for (const Exchange& x : rec.exchanges) {
    if (!is_v_target_write(x.mosi)) continue;
    ++v_target_writes;
    if ((x.mosi >> 24) == 0x08 && (x.mosi & 0xFFF) != 0) ++moving_x;
    if ((x.mosi >> 24) == 0x28 && (x.mosi & 0xFFF) != 0) ++moving_y;
  }
  EXPECT_GT(moving_x, 100);
  EXPECT_GT(moving_y, 100);
  EXPECT_GT(v_target_writes, 3000);  // three a tick over seconds of machine time
  EXPECT_NE(rec.note.find("completed"), std::string::npos) << rec.note;
}

TEST(JobScenario, SameDrawingGivesTheSameDatagrams) {
  ScenarioRequest job;
  job.name = "job";
  job.job_file = spi_test::temp_file("arch_twice.dxf", kArchDxf);
  job.max_job_datagrams = 4000;
  ScenarioRecording first, second;
  ASSERT_TRUE(record_scenario(job, false, &first).ok());
  ASSERT_TRUE(record_scenario(job, false, &second).ok());
  ASSERT_EQ(first.exchanges.size(), second.exchanges.size());
  for (size_t i = 0; i < first.exchanges.size(); ++i) {
    ASSERT_EQ(first.exchanges[i].mosi, second.exchanges[i].mosi) << i;
    ASSERT_EQ(first.exchanges[i].miso, second.exchanges[i].miso) << i;
  }
}

TEST(JobScenario, PositionReadsAreDontCares) {
  int x_actual_reads = 0;
  for (const Expected& e : arch_job().lines) {
    if ((e.mosi.value >> 24) != 0x03) continue;  // R M1.x_actual
    ++x_actual_reads;
    EXPECT_TRUE(e.miso.any) << e.line;
  }
  EXPECT_GT(x_actual_reads, 100);
}

TEST(JobScenario, MaxDatagramsBoundsTheRecordingAfterTheInit) {
  ScenarioRequest init;
  ScenarioRecording init_rec, job_rec;
  ASSERT_TRUE(record_scenario(init, false, &init_rec).ok());
  ScenarioRequest job;
  job.name = "job";
  job.job_file = spi_test::temp_file("arch_bound.dxf", kArchDxf);
  job.max_job_datagrams = 300;
  ASSERT_TRUE(record_scenario(job, false, &job_rec).ok()) << job_rec.note;
  EXPECT_EQ(job_rec.exchanges.size(), init_rec.exchanges.size() + 300);
  EXPECT_NE(job_rec.note.find("datagram limit"), std::string::npos) << job_rec.note;
}

TEST(JobScenario, RecorderVcdDiffsCleanAgainstTheGolden) {
  const JobGolden& job = arch_job();
  ASSERT_EQ(job.rc, kExitOk);
  DiffOptions d;
  d.capture = job.vcd_path;
  d.expected = spi_test::temp_file("arch_job.golden", job.text);
  std::ostringstream out, err;
  EXPECT_EQ(run_diff(d, out, err), kExitOk) << err.str();
  EXPECT_NE(out.str().find("MATCH:"), std::string::npos);
}

TEST(JobScenario, MissingDrawingIsAnOpenError) {
  ExpectOptions o;
  o.scenario = "job";
  o.job_file = "/nonexistent/x.dxf";
  std::ostringstream out, err;
  EXPECT_EQ(run_expect(o, out, err), kExitUnusable);
  EXPECT_NE(err.str().find("E_OPEN"), std::string::npos) << err.str();
}

TEST(JobScenario, JobWithoutDrawingSaysSo) {
  ExpectOptions o;
  o.scenario = "job";
  std::ostringstream out, err;
  EXPECT_EQ(run_expect(o, out, err), kExitUnusable);
  EXPECT_NE(err.str().find("needs a drawing"), std::string::npos) << err.str();
}

}  // namespace
