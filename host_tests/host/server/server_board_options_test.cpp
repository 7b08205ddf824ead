// A board job takes the board options the command line has (clearing tool, passes,
// alignment holes for a double-sided board, the measured alignment), within the same ranges
// (job_defaults.h); and what a board cannot use is refused, not ignored: feed_mm_s, a tol_mm
// other than the 1 um it is sent with, board fields on a drawing, the other side's copper.
#include <gtest/gtest.h>

#include "host/lib/server/data_folder.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::ServerRig;
namespace fs = std::filesystem;

std::string board_file(const std::string& name) {
  return read_file(fs::path(ENGRAVER_SOURCE_DIR) / "host_tests/host/server/data" / name);
}

// blinky's files; `copper` names the copper file (its name says its side).
httplib::MultipartFormDataItems blinky(const std::string& copper = "blinky-F.Cu.gbr") {
  return {{"file", board_file("blinky-F.Cu.gbr"), copper, "application/octet-stream"},
          {"file", board_file("blinky.drl"), "blinky.drl", "application/octet-stream"},
          {"file", board_file("blinky-Edge.Cuts.gbr"), "blinky-Edge.Cuts.gbr",
           "application/octet-stream"}};
}

httplib::MultipartFormDataItems with(httplib::MultipartFormDataItems form,
                                     const std::vector<std::pair<std::string, std::string>>& kv) {
  for (const auto& [k, v] : kv) form.push_back({k, v, "", ""});
  return form;
}

nlohmann::json posted(const ServerRig& server, const httplib::MultipartFormDataItems& form,
                      int status) {
  auto r = server.client().Post("/api/jobs", server.auth(), form);
  EXPECT_TRUE(r);
  if (!r) return nullptr;
  EXPECT_EQ(r->status, status) << r->body;
  return nlohmann::json::parse(r->body, nullptr, false);
}

nlohmann::json archived_json(const ServerRig& server, int64_t id, const std::string& file) {
  auto r = server.client().Get(fmt::format("/api/jobs/{}/files/{}", id, file).c_str());
  EXPECT_TRUE(r && r->status == 200) << file;
  return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json();
}

size_t steps_of(const nlohmann::json& plan, const std::string& kind) {
  size_t n = 0;
  for (const auto& s : plan["steps"]) n += s["kind"] == kind;
  return n;
}

void expect_error(const nlohmann::json& body, const std::string& needle) {
  ASSERT_TRUE(body.is_object());
  EXPECT_NE(body.value("error", "").find(needle), std::string::npos) << body.dump();
}

TEST(ServerBoardOptions, AClearingToolIsAToolOfTheJobAndItsPassesAreTheBoards) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  const nlohmann::json plain = posted(server, with(blinky(), {{"passes", "3"}}), 201);
  const nlohmann::json clearing = posted(
      server,
      with(blinky(), {{"passes", "3"}, {"clearing_tool_mm", "0.6"}, {"narrow_passes", "1"}}), 201);
  const nlohmann::json p = archived_json(server, plain["id"], "board.json");
  const nlohmann::json c = archived_json(server, clearing["id"], "board.json");
  EXPECT_EQ(c["clearing_tool_mm"], 0.6);
  EXPECT_EQ(c["passes"], 3);
  // The clearing tool is mounted after the V-bit: one more tool change.
  EXPECT_EQ(c["report"]["tool_changes"].get<int>(), p["report"]["tool_changes"].get<int>() + 1);
  EXPECT_EQ(steps_of(archived_json(server, clearing["id"], "plan.json"), "pause"),
            steps_of(archived_json(server, plain["id"], "plan.json"), "pause") + 1);
}

TEST(ServerBoardOptions, TheCommandLinesRangesAreTheServers) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  expect_error(posted(server, with(blinky(), {{"clearing_tool_mm", "10.5"}}), 400),
               "clearing_tool_mm must be 0 .. 10");
  expect_error(posted(server, with(blinky(), {{"passes", "0"}}), 400), "passes must be 1 .. 50");
  expect_error(posted(server, with(blinky(), {{"passes", "51"}}), 400), "passes must be 1 .. 50");
  expect_error(
      posted(server, with(blinky(), {{"align_holes", "auto"}, {"align_diameter_mm", "11"}}), 400),
      "align_diameter_mm must be 0.1 .. 10");
  expect_error(posted(server, with(blinky(), {{"tool_width_mm", "6"}}), 400),
               "tool_width_mm must be 0.01 .. 5");
  expect_error(posted(server, with(blinky(), {{"narrow_passes", "2"}}), 400),
               "narrow_passes goes with a clearing tool");
  expect_error(posted(server, with(blinky(), {{"align_holes", "3;4"}}), 400),
               "align_holes: '3' is not X,Y");
  expect_error(posted(server, with(blinky(), {{"align_measured", "1,2,3,4"}}), 400),
               "align_measured needs the job's align_holes");
}

// The server resolves its board settings with the command line's resolver
// (pcb/board_args.h): a clearing tool with no passes left for it is refused, not planned as
// if it were not there.
TEST(ServerBoardOptions, AClearingToolWithNoPassesForItIsRefusedAsOnTheCommandLine) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  expect_error(
      posted(server,
             with(blinky(), {{"passes", "2"}, {"clearing_tool_mm", "0.6"}, {"narrow_passes", "2"}}),
             422),
      "clearing_tool_mm cuts the passes beyond narrow_passes (2), but passes is 2: "
      "give more passes");
}

// Double-sided: the top job drills the alignment holes (and leaves the cut-out to the
// bottom); the bottom job, measured after the flip, is turned and shifted onto them.
TEST(ServerBoardOptions, AlignmentHolesAndTheMeasuredAlignmentPlanAsTheCommandLineDoes) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  const nlohmann::json top = posted(server, with(blinky(), {{"align_holes", "auto"}}), 201);
  const nlohmann::json plain = posted(server, blinky(), 201);
  const nlohmann::json tm = archived_json(server, top["id"], "board.json");
  EXPECT_EQ(tm["align_holes"], "auto");
  ASSERT_TRUE(tm.contains("flip_axis_machine_x_mm"));
  const nlohmann::json tp = archived_json(server, top["id"], "plan.json");
  EXPECT_EQ(steps_of(tp, "drill"), steps_of(archived_json(server, plain["id"], "plan.json"),
                                            "drill") +
                                       2);  // the two pin holes
  // Bottom: where holes 1 and 2 were found after the flip, 0.3 mm off in x.
  ASSERT_GE(tm["alignment_holes_mm"].size(), 2u) << tm.dump();
  const double x1 = tm["alignment_holes_mm"][0][0], y1 = tm["alignment_holes_mm"][0][1];
  const double x2 = tm["alignment_holes_mm"][1][0], y2 = tm["alignment_holes_mm"][1][1];
  auto bottom = [&](double dx) {
    return posted(server,
                  with(blinky("blinky-B.Cu.gbr"),
                       {{"side", "bottom"},
                        {"align_holes", "auto"},
                        {"align_measured", fmt::format("{},{},{},{}", x1 + dx, y1, x2 + dx, y2)}}),
                  201);
  };
  const nlohmann::json b0 = bottom(0), b3 = bottom(0.3);
  const nlohmann::json p0 = archived_json(server, b0["id"], "plan.json");
  const nlohmann::json p3 = archived_json(server, b3["id"], "plan.json");
  ASSERT_EQ(p0["steps"].size(), p3["steps"].size());
  size_t moved = 0;
  for (size_t i = 0; i < p0["steps"].size(); ++i) {
    const nlohmann::json& a = p0["steps"][i];
    const nlohmann::json& b = p3["steps"][i];
    if (a.contains("to_um") && b.contains("to_um") &&
        std::abs(b["to_um"][0].get<double>() - a["to_um"][0].get<double>() - 300) <= 1)
      ++moved;
  }
  EXPECT_GT(moved, 10u);
}

TEST(ServerBoardOptions, WhatABoardDoesNotUseIsRefusedNotIgnored) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  // Its feeds are the board planner's.
  expect_error(posted(server, with(blinky(), {{"feed_mm_s", "20"}}), 400),
               "feed_mm_s does not apply to a board");
  // It is sent with 1 um chords: a coarser tol_mm would be silently finer.
  expect_error(posted(server, with(blinky(), {{"tol_mm", "0.005"}}), 400),
               "tol_mm of a board must be 0.001");
  const nlohmann::json ok = posted(server, with(blinky(), {{"tol_mm", "0.001"}}), 201);
  EXPECT_EQ(ok["tol_mm"], 0.001);
  // Its record says what it is cut and sent with.
  const nlohmann::json plain = posted(server, blinky(), 201);
  EXPECT_EQ(plain["tol_mm"], 0.001);
  EXPECT_EQ(plain["feed_mm_s"], 5.0);
  // A drawing has no side, tool or map.
  auto r = server.upload("square.ngc", test::square_gcode(10, 10, 10), "&probe_first=1");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("probe_first applies to a board"), std::string::npos) << r->body;
}

// Bottom copper given to a top-side job would be drilled and cut out with no isolation:
// refused at upload, naming the side to ask for.
TEST(ServerBoardOptions, TheOtherSidesCopperAloneIsRefused) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  expect_error(posted(server, with(blinky("blinky-B.Cu.gbr"), {{"side", "top"}}), 422),
               "side=top but the files hold bottom copper only: ask for side=bottom");
  expect_error(posted(server, with(blinky(), {{"side", "bottom"}}), 422),
               "side=bottom but the files hold top copper only");
  EXPECT_EQ(server.jobs().size(), 0u);
  posted(server, with(blinky("blinky-B.Cu.gbr"), {{"side", "bottom"}}), 201);
}

}  // namespace
}  // namespace host::server
