// Reading and planning a drawing report each of their stages (the CLI's progress lines): a
// 200 000-line drawing printed "plan: 0/200000 curves ordered" as its only line for ~40 s,
// the import and the stages after ordering reported nothing.
#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <cstdio>   // std::remove
#include <fstream>  // std::ofstream
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/lib/drawing/drawing.h"
#include "host/lib/plan/job_plan.h"

namespace host {
namespace {

struct Report {
  std::string unit;
  size_t done, total;
};

// The stages in the order reported, each once (its first report).
std::vector<std::string> stages(const std::vector<Report>& reports) {
  std::vector<std::string> out;
  for (const Report& r : reports)
    if (out.empty() || out.back() != r.unit) out.push_back(r.unit);
  return out;
}

TEST(PlanProgress, ImportAndPlanningReportEveryStage) {
  const std::string path =
      testing::TempDir() + "/" + std::to_string(getpid()) + "-plan-progress.dxf";
  std::string dxf = "0\nSECTION\n2\nENTITIES\n";
  for (int i = 0; i < 3; ++i)
    dxf += "0\nLINE\n8\n0\n10\n" + std::to_string(i) + "\n20\n0\n11\n" + std::to_string(i) +
           "\n21\n5\n";
  dxf += "0\nENDSEC\n0\nEOF\n";
  std::ofstream(path) << dxf;
  std::vector<Report> reports;
  const WorkProgress note = [&reports](const char* unit, size_t done, size_t total) {
    reports.push_back(Report{unit, done, total});
  };
  Drawing d = import_drawing(path, note);
  ASSERT_EQ(d.curves.size(), 3u);
  EXPECT_EQ(stages(reports), (std::vector<std::string>{"bytes checked", "bytes read"}));
  EXPECT_EQ(reports.back().done, dxf.size());  // the last report: all of the file
  EXPECT_EQ(reports.back().total, dxf.size());

  reports.clear();
  PlanOptions o;
  o.progress = note;
  const JobPlan plan = plan_job(std::move(d), o);
  EXPECT_EQ(plan.curves.size(), 3u);
  EXPECT_EQ(
      stages(reports),
      (std::vector<std::string>{"curves measured", "curves moved to the margin",
                                "curve ends indexed", "curves ordered",
                                "curves checked against the work area", "curves made into steps"}));
  for (const Report& r : reports) EXPECT_EQ(r.total, 3u) << r.unit;
  std::remove(path.c_str());
}

}  // namespace
}  // namespace host
