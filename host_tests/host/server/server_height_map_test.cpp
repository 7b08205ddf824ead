// Probe first (issue 25, the workshop): a board job that asks for it waits for the probe
// clip (on the page and in /api/status) until the operator confirms, probes the simulated
// warped blank over the job, keeps the map and its picture in the archive and cuts with it;
// probe failures fail the job with nothing cut; the bottom side reuses the top side's map.
#include <gtest/gtest.h>

#include <cmath>    // std::lround
#include <fstream>  // std::ofstream

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/probe_grid.h"
#include "host/lib/server/board_height_map.h"
#include "host/lib/server/data_folder.h"
#include "host_tests/host/server/blinky_upload.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::blinky;
using test::board_file;
using test::post;
using test::ServerRig;
using test::SimRig;
namespace fs = std::filesystem;

std::string archived(const ServerRig& server, int64_t id, const std::string& file) {
  auto r = server.client().Get(fmt::format("/api/jobs/{}/files/{}", id, file).c_str());
  return r && r->status == 200 ? r->body : std::string();
}

// A tilted and bowed blank (um above the zero corner's copper): 0.1 mm over 50 mm in x,
// a 40 um bow along y.
int32_t warped_um(int32_t x_um, int32_t y_um) {
  const double x = x_um / 1000.0, y = y_um / 1000.0;
  return static_cast<int32_t>(std::lround(2.0 * x + 40.0 * (y / 25.0) * (1.0 - y / 25.0)));
}

sim::SimOptions blank(std::function<int32_t(int32_t, int32_t)> surface) {
  sim::SimOptions o;
  o.surface_um = std::move(surface);
  return o;
}

bool waiting_for_clip(const ServerRig& server, int64_t id) {
  const nlohmann::json j = server.running(id);
  return j.is_object() && j["machine_state"] == "probe_clip";
}

double lowest_z_mm(const SimRig& sim) {
  double z = 1e9;
  for (const auto& s : sim.machine().trace()) z = std::min(z, s.z_mm);
  return z;
}

TEST(ServerHeightMap, ProbeFirstWaitsForTheClipProbesKeepsTheMapAndCutsWithIt) {
  test::TempDir dir;
  SimRig sim(false, 0, blank(warped_um));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post(server, blinky({{"probe_first", "1"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, id); }, 30))
      << server.status().dump();
  // It asks, and waits: nothing moved down while it does.
  const nlohmann::json asking = server.running(id);
  EXPECT_EQ(asking["probe"]["stage"], "probe_clip");
  EXPECT_NE(asking["probe"]["ask"].get<std::string>().find("probe clip"), std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_TRUE(waiting_for_clip(server, id));
  EXPECT_GE(lowest_z_mm(sim), 0.0);
  // A confirm for a job that is not waiting is refused.
  EXPECT_EQ(server.control(id + 1, R"({"action":"probe_ready"})")->status, 404);
  auto ok = server.control(id, R"({"action":"probe_ready"})");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 120))
      << server.job(id).dump();
  // The map in the archive: the blank's heights at its points.
  const heightmap::HeightMap map =
      heightmap::read_height_map_text(archived(server, id, "heightmap.json"), "heightmap.json");
  EXPECT_GE(map.rows * map.cols, 4);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      const double truth =
          warped_um(std::lround(map.x_mm(c) * 1000), std::lround(map.y_mm(r) * 1000));
      EXPECT_NEAR(map.height_um(r, c), truth, 3.0) << r << "," << c;
    }
  }
  const std::string svg = archived(server, id, "heightmap.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  const nlohmann::json report = nlohmann::json::parse(archived(server, id, "report.json"));
  EXPECT_EQ(report["height_map"]["rows"], map.rows);
  EXPECT_NE(archived(server, id, "machine.log").find("probe clip confirmed"), std::string::npos);
  // Cut with the map: every horizontal cut at the isolation depth is 50 um into the blank
  // (the V-bit's depth below the copper), where the blank rises by up to 50 um.
  double shallowest_um = 1e9, deepest_um = -1e9;
  const auto& trace = sim.machine().trace();
  for (size_t i = 1; i < trace.size(); ++i) {
    const auto &p = trace[i - 1], &q = trace[i];
    const bool horizontal =
        std::abs(q.z_mm - p.z_mm) < 0.0005 && std::hypot(q.x_mm - p.x_mm, q.y_mm - p.y_mm) > 0.0005;
    if (!horizontal || q.z_mm > -0.001 || q.z_mm < -0.3) continue;  // travel, cut-out passes
    const double depth_um =
        warped_um(std::lround(q.x_mm * 1000), std::lround(q.y_mm * 1000)) - q.z_mm * 1000;
    shallowest_um = std::min(shallowest_um, depth_um);
    deepest_um = std::max(deepest_um, depth_um);
  }
  EXPECT_GT(shallowest_um, 50 - 8);
  EXPECT_LT(deepest_um, 50 + 8);
}

// The grid's pitch is the upload's (engraver probe --probe-spacing), within the controller's.
TEST(ServerHeightMap, TheProbeSpacingIsTheUploads) {
  test::TempDir dir;
  SimRig sim(false, 0, blank(warped_um));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  auto refused = server.client().Post("/api/jobs", server.auth(),
                                      blinky({{"probe_first", "1"}, {"probe_spacing_mm", "0.5"}}));
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 400);
  EXPECT_NE(refused->body.find("probe_spacing_mm must be 1 .. 65.535"), std::string::npos);
  const int64_t id = post(server, blinky({{"probe_first", "1"}, {"probe_spacing_mm", "4"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, id); }, 30));
  server.control(id, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 120))
      << server.job(id).dump();
  const heightmap::HeightMap map =
      heightmap::read_height_map_text(archived(server, id, "heightmap.json"), "heightmap.json");
  EXPECT_LE(map.pitch_x_mm, 4.0);
  EXPECT_LE(map.pitch_y_mm, 4.0);
  EXPECT_GT(map.pitch_x_mm, 3.0);
  EXPECT_GE(map.cols, 6);
}

TEST(ServerHeightMap, NoContactFailsTheJobWithNothingCut) {
  test::TempDir dir;
  SimRig sim(false);  // no blank: the probe never closes
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post(server, blinky({{"probe_first", "1"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, id); }, 30));
  server.control(id, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "failed"; }, 60))
      << server.job(id).dump();
  const std::string message = server.job(id)["message"];
  EXPECT_NE(message.find("no contact"), std::string::npos) << message;
  EXPECT_NE(message.find("nothing was cut"), std::string::npos) << message;
  EXPECT_EQ(server.job(id)["executed"], 0);
  EXPECT_GT(lowest_z_mm(sim), -1.01);              // the probe's depth limit, never a cut below it
  EXPECT_EQ(sim.machine().pauses_confirmed(), 0);  // not even the first tool was asked for
}

TEST(ServerHeightMap, AnOutlierFailsTheJobNamingThePoint) {
  // Where the job probes: its grid over the area in board.json.
  heightmap::ProbeGrid grid;
  {
    test::TempDir plan_dir;
    ServerRig planner(plan_dir.path(), {});
    const int64_t id = post(planner, blinky({{"probe_first", "1"}}));
    const nlohmann::json m = nlohmann::json::parse(archived(planner, id, "board.json"));
    grid = heightmap::plan_probe_grid(area_of_json(m["probe_area_mm"]), heightmap::GridOptions{});
  }
  ASSERT_GE(grid.cols, 3);
  ASSERT_GE(grid.rows, 3);
  // A chip on the blank under one inner point: 200 um up within 0.3 mm of it.
  const double chip_x = grid.x_mm(1), chip_y = grid.y_mm(1);
  test::TempDir dir;
  SimRig sim(false, 0, blank([chip_x, chip_y](int32_t x_um, int32_t y_um) {
               const bool chip = std::hypot(x_um / 1000.0 - chip_x, y_um / 1000.0 - chip_y) < 0.3;
               return warped_um(x_um, y_um) + (chip ? 200 : 0);
             }));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post(server, blinky({{"probe_first", "1"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, id); }, 30));
  server.control(id, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "failed"; }, 60))
      << server.job(id).dump();
  const nlohmann::json j = server.job(id);
  const std::string message = j["message"];
  EXPECT_NE(message.find("row 1, col 1"), std::string::npos) << message;
  EXPECT_NE(message.find("nothing was cut"), std::string::npos) << message;
  // The server's words: no command line option (--outlier-limit) it does not take.
  EXPECT_EQ(message.find("--"), std::string::npos) << message;
  EXPECT_NE(message.find("requeue the job"), std::string::npos) << message;
  EXPECT_EQ(j["executed"], 0);
  EXPECT_GT(lowest_z_mm(sim), -1.01);
}

TEST(ServerHeightMap, AbortWhileWaitingForTheClipCutsNothing) {
  test::TempDir dir;
  SimRig sim(false, 0, blank(warped_um));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post(server, blinky({{"probe_first", "1"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, id); }, 30));
  EXPECT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30))
      << server.job(id).dump();
  EXPECT_NE(server.job(id)["message"].get<std::string>().find("nothing was cut"),
            std::string::npos);
  EXPECT_GE(lowest_z_mm(sim), 0.0);
}

// Double-sided: the top side probes (over both sides' places), the bottom side, flipped on
// its pins, is cut with the same map without probing.
TEST(ServerHeightMap, TheBottomSideReusesTheTopSidesMap) {
  test::TempDir dir;
  SimRig sim(false, 0, blank(warped_um));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
  server.control(top, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(top)["state"] == "completed"; }, 120))
      << server.job(top).dump();
  const int64_t bottom = post(server, blinky({{"side", "bottom"},
                                              {"align_holes", "auto"},
                                              {"height_map_from", std::to_string(top)}},
                                             "blinky-B.Cu.gbr"));
  ASSERT_TRUE(test::wait_until(
      [&] {
        const std::string s = server.job(bottom)["state"];
        return s == "completed" || s == "failed";
      },
      120));
  ASSERT_EQ(server.job(bottom)["state"], "completed") << server.job(bottom).dump();
  EXPECT_EQ(archived(server, bottom, "heightmap.json"), archived(server, top, "heightmap.json"));
  EXPECT_NE(archived(server, bottom, "machine.log").find(fmt::format("height map of job {}", top)),
            std::string::npos);
  // A job with no map to give (its map gone from the archive): refused at the run, nothing
  // cut. One that never probes is refused at upload (ServerUploadFields).
  fs::remove(server.data().job_dir(server.store().get(top)->key) / kHeightMapFile);
  const int64_t orphan = post(
      server,
      blinky({{"side", "bottom"}, {"height_map_from", std::to_string(top)}}, "blinky-B.Cu.gbr"));
  ASSERT_TRUE(test::wait_until([&] { return server.job(orphan)["state"] == "failed"; }, 60));
  EXPECT_NE(server.job(orphan)["message"].get<std::string>().find("has no height map"),
            std::string::npos);
  auto r = server.client().Post("/api/jobs", server.auth(), blinky({{"height_map_from", "999"}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
}

// A map belongs to the machine whose table it was probed on: a job on another machine does
// not cut with it (the map's machine, as kept beside it in the archive, made another's here).
TEST(ServerHeightMap, AMapProbedOnAnotherMachineIsNotUsed) {
  test::TempDir dir;
  SimRig sim(false, 0, blank(warped_um));
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
  server.control(top, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(top)["state"] == "completed"; }, 120))
      << server.job(top).dump();
  int marks = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir.path())) {
    if (e.path().filename() != kHeightMapMachineFile) continue;
    EXPECT_EQ(read_file(e.path()), "mill");
    std::ofstream(e.path(), std::ios::trunc) << "other mill";
    ++marks;
  }
  ASSERT_EQ(marks, 1);
  const size_t cut_before = sim.machine().trace().size();
  const int64_t bottom = post(server, blinky({{"side", "bottom"},
                                              {"align_holes", "auto"},
                                              {"height_map_from", std::to_string(top)}},
                                             "blinky-B.Cu.gbr"));
  ASSERT_TRUE(test::wait_until([&] { return server.job(bottom)["state"] == "failed"; }, 60))
      << server.job(bottom).dump();
  EXPECT_NE(server.job(bottom)["message"].get<std::string>().find(
                "was probed on machine 'other mill', this job runs on 'mill'"),
            std::string::npos)
      << server.job(bottom)["message"];
  const auto& trace = sim.machine().trace();
  for (size_t i = cut_before; i < trace.size(); ++i) EXPECT_GE(trace[i].z_mm, 0.0);
}

// The geometry of the flip. The top side's probe sees the blank's surface S (zeroed on the
// copper at the zero corner). Flipped on pins about x = a, a stiff bowed blank puts its
// place x at 2a - x upside down: S'(x, y) = c - S(2a - x, y); zeroed again at (0, 0). A thin
// blank held flat on a warped table keeps the table's heights at the same machine places.
TEST(ServerHeightMap, TheFlippedMapIsTheFlippedBlanksSurface) {
  const double a = 30.0;  // the flip axis (machine x, mm)
  // A tilted, twisted and bowed blank: the tilt survives the flip, the bow turns over.
  auto top_surface = [](double x, double y) {
    return 1.5 * x - 0.8 * y + 0.02 * x * y + 0.05 * (x - 30) * (x - 30);
  };
  heightmap::HeightMap top;
  top.origin_x_mm = 0;
  top.origin_y_mm = 0;
  top.pitch_x_mm = 10;
  top.pitch_y_mm = 8;
  top.cols = 7;  // x 0 .. 60: symmetric about a
  top.rows = 4;
  for (int r = 0; r < top.rows; ++r)
    for (int c = 0; c < top.cols; ++c)
      top.heights_um.push_back(top_surface(top.x_mm(c), top.y_mm(r)) - top_surface(0, 0));
  heightmap::validate(top, "top");

  const heightmap::HeightMap blank = map_after_flip(top, a, "blank");
  auto flipped_surface = [&](double x, double y) { return 7.0 - top_surface(2 * a - x, y); };
  double worst_unflipped_um = 0;
  for (int r = 0; r < blank.rows; ++r) {
    for (int c = 0; c < blank.cols; ++c) {
      const double x = blank.x_mm(c), y = blank.y_mm(r);
      const double truth = flipped_surface(x, y) - flipped_surface(0, 0);
      EXPECT_NEAR(blank.interpolate_um(x, y), truth, 1e-6) << x << "," << y;
      EXPECT_NEAR(blank.height_um(r, c), truth, 1e-6) << x << "," << y;
      worst_unflipped_um = std::max(worst_unflipped_um, std::abs(top.interpolate_um(x, y) - truth));
    }
  }
  // Taking the top map unchanged would be wrong by twice the bow.
  EXPECT_GT(worst_unflipped_um, 80.0);

  const heightmap::HeightMap table = map_after_flip(top, a, "table");
  EXPECT_EQ(table.heights_um, top.heights_um);
  EXPECT_EQ(table.origin_x_mm, top.origin_x_mm);
  EXPECT_THROW(map_after_flip(top, a, "sideways"), heightmap::HeightMapError);
}

}  // namespace
}  // namespace host::server
