// The height map's flow through the workshop (issue 25): a job that cuts with another job's
// map waits in the queue for it and runs on the machine it was probed on, fails with nothing
// cut when its source ends without one; height map fields refused at upload (400 naming the
// field, nothing queued); decimal fields and JSON numbers that are no number.
#include <gtest/gtest.h>

#include <fstream>  // std::ofstream
#include <set>      // std::set

#include "host/lib/heightmap/height_map.h"
#include "host/lib/server/board_height_map.h"
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

// A 400 naming `field`, and nothing queued.
void expect_refused(ServerRig& server, const httplib::MultipartFormDataItems& form,
                    const std::string& field, const std::string& words) {
  const size_t jobs_before = server.jobs().size();
  auto r = server.client().Post("/api/jobs", server.auth(), form);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_NE(r->body.find(field), std::string::npos) << r->body;
  EXPECT_NE(r->body.find(words), std::string::npos) << r->body;
  EXPECT_EQ(server.jobs().size(), jobs_before);
}

int32_t tilted_um(int32_t x_um, int32_t) {
  return x_um / 500;
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

// The fields of report.json's `height_map` as docs/user-guide.md lists them:
// "`report.json` has `height_map` (`file`, `rows`, ...)".
std::set<std::string> guide_report_map_fields() {
  const std::string guide = read_file(fs::path(ENGRAVER_SOURCE_DIR) / "docs" / "user-guide.md");
  const std::string intro = "`report.json` has `height_map` (";
  const size_t from = guide.find(intro);
  if (from == std::string::npos) return {};
  const size_t to = guide.find(')', from + intro.size());
  const std::string list = guide.substr(from + intro.size(), to - from - intro.size());
  std::set<std::string> fields;
  for (size_t open = list.find('`'); open != std::string::npos;) {
    const size_t close = list.find('`', open + 1);
    fields.insert(list.substr(open + 1, close - open - 1));
    open = list.find('`', close + 1);
  }
  return fields;
}

bool ended(const ServerRig& server, int64_t id) {
  const std::string s = server.job(id)["state"];
  return s == "completed" || s == "failed" || s == "aborted";
}

// The user guide's order: both sides uploaded at once, two machines free. The bottom side
// stays queued until the top side has its map, then runs where that map was probed.
TEST(ServerMapFlow, TheBottomSideWaitsForItsMapAndRunsWhereItWasProbed) {
  test::TempDir dir;
  SimRig left(false, 0, blank(tilted_um)), right(false, 0, blank(tilted_um));
  ServerRig server(
      dir.path(), {test::machine("left", left.address()), test::machine("right", right.address())});
  const int64_t top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  const int64_t bottom = post(server, blinky({{"side", "bottom"},
                                              {"align_holes", "auto"},
                                              {"height_map_from", std::to_string(top)}},
                                             "blinky-B.Cu.gbr"));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the other machine is free
  nlohmann::json j = server.job(bottom);
  EXPECT_EQ(j["state"], "queued") << j.dump();
  EXPECT_EQ(j["waiting"], fmt::format("waiting for the height map of job {}", top));
  EXPECT_EQ(j["height_map"], false);
  server.control(top, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return ended(server, top) && ended(server, bottom); }, 180));
  ASSERT_EQ(server.job(top)["state"], "completed") << server.job(top).dump();
  j = server.job(bottom);
  ASSERT_EQ(j["state"], "completed") << j.dump();
  EXPECT_EQ(j["machine"], server.job(top)["machine"]);
  EXPECT_EQ(j["waiting"], "");
  EXPECT_EQ(j["height_map"], true);
  // The top side's report names its map with the fields the guide lists.
  auto report = server.client().Get(fmt::format("/api/jobs/{}/files/report.json", top).c_str());
  ASSERT_TRUE(report && report->status == 200);
  std::set<std::string> keys;
  const nlohmann::json report_json = nlohmann::json::parse(report->body);
  for (const auto& [key, value] : report_json["height_map"].items()) keys.insert(key);
  EXPECT_EQ(keys, guide_report_map_fields());
}

// Once the map is made a job on the same side of the blank (no flip) waits for the machine
// that probed it, and says so, though another machine is idle; the bottom side (the blank
// turned over) waits for the top side to be completed. The simulated operators never confirm
// a tool pause: the top side, probed, stays on its machine at its first tool.
TEST(ServerMapFlow, ASameSideJobWaitsForTheMachineTheBottomSideForTheTopToComplete) {
  test::TempDir dir;
  sim::SimOptions never_confirms = blank(tilted_um);
  never_confirms.pause_confirm_ms = -1;
  SimRig left(false, 0, never_confirms), right(false, 0, never_confirms);
  ServerRig server(
      dir.path(), {test::machine("left", left.address()), test::machine("right", right.address())});
  const int64_t top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  const int64_t bottom = post(server, blinky({{"side", "bottom"},
                                              {"align_holes", "auto"},
                                              {"height_map_from", std::to_string(top)}},
                                             "blinky-B.Cu.gbr"));
  const int64_t same_side = post(
      server,
      blinky({{"side", "top"}, {"align_holes", "auto"}, {"height_map_from", std::to_string(top)}}));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
  server.control(top, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(top)["height_map"] == true; }, 60));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the other machine is free
  EXPECT_EQ(server.job(top)["state"], "running");
  const std::string machine = server.job(top)["machine"];
  nlohmann::json j = server.job(same_side);
  EXPECT_EQ(j["state"], "queued") << j.dump();
  EXPECT_EQ(j["waiting"], fmt::format("waiting for machine '{}' (busy), which probed the height "
                                      "map of job {}",
                                      machine, top));
  const nlohmann::json b = server.job(bottom);
  EXPECT_EQ(b["state"], "queued") << b.dump();
  EXPECT_EQ(b["waiting"], fmt::format("waiting for job {} to be completed (the blank is turned "
                                      "over after its side is cut)",
                                      top));
  bool listed = false;  // the list says the same
  for (const auto& each : server.jobs()) {
    if (each["id"] != same_side) continue;
    EXPECT_EQ(each["waiting"], j["waiting"]);
    listed = true;
  }
  EXPECT_TRUE(listed);
}

// The top side, its map made, interrupted by a server stop mid-job: after the restart the
// bottom side stays queued (the outside tester's restarted server gave it to the machine at
// once: the top's pin holes never drilled, the blank never turned over), while a job on the
// same side takes the map. The top side then continued and aborted: the bottom side fails in the
// queue naming it, nothing cut.
TEST(ServerMapFlow, TheBottomSideWaitsForAnInterruptedTopAndFailsWhenItIsAborted) {
  test::TempDir dir;
  sim::SimOptions never_confirms = blank(tilted_um);
  never_confirms.pause_confirm_ms = -1;
  SimRig left(false, 0, never_confirms);
  const std::vector<MachineSpec> machines = {test::machine("left", left.address())};
  int64_t top = 0, bottom = 0, same_side = 0;
  {
    ServerRig server(dir.path(), machines);
    top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
    bottom = post(server, blinky({{"side", "bottom"},
                                  {"align_holes", "auto"},
                                  {"height_map_from", std::to_string(top)}},
                                 "blinky-B.Cu.gbr"));
    ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
    server.control(top, R"({"action":"probe_ready"})");
    ASSERT_TRUE(test::wait_until([&] { return server.job(top)["height_map"] == true; }, 60));
    server.shutdown();
  }
  ServerRig server(dir.path(), machines);
  ASSERT_EQ(server.job(top)["state"], "interrupted") << server.job(top).dump();
  same_side = post(
      server,
      blinky({{"side", "top"}, {"align_holes", "auto"}, {"height_map_from", std::to_string(top)}}));
  // The same-side job is claimed (held at its first tool, never confirmed): the machine
  // looked at the queue and left the bottom side.
  ASSERT_TRUE(test::wait_until([&] { return server.job(same_side)["state"] == "running"; }, 30))
      << server.job(same_side).dump();
  nlohmann::json j = server.job(bottom);
  EXPECT_EQ(j["state"], "queued") << j.dump();
  EXPECT_EQ(j["waiting"], fmt::format("waiting for job {} to be completed (the blank is turned "
                                      "over after its side is cut)",
                                      top));
  server.control(same_side, R"({"action":"abort"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(same_side)["state"] == "aborted"; }, 30));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the machine is free
  EXPECT_EQ(server.job(bottom)["state"], "queued") << server.job(bottom).dump();
  // Continued, the top side runs again (not the bottom), and is aborted this time.
  auto r = server.control(top, R"({"action":"continue"})");
  ASSERT_TRUE(r && r->status == 200) << (r ? r->body : std::string("no answer"));
  ASSERT_TRUE(test::wait_until([&] { return server.job(top)["state"] == "running"; }, 30));
  EXPECT_EQ(server.job(bottom)["state"], "queued") << server.job(bottom).dump();
  server.control(top, R"({"action":"abort"})");
  ASSERT_TRUE(test::wait_until([&] { return server.job(bottom)["state"] == "failed"; }, 30));
  j = server.job(bottom);
  const std::string message = j["message"];
  EXPECT_NE(message.find(fmt::format("job {} ended aborted before its side was completed", top)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("nothing was cut"), std::string::npos) << message;
  EXPECT_EQ(j["runs"], 0) << j.dump();
  EXPECT_EQ(j["machine"], "") << j.dump();
}

// The top side fails (the probe never touches): the bottom side fails too, saying why, and
// neither machine cut anything.
TEST(ServerMapFlow, TheBottomSideFailsWithNothingCutWhenItsSourceFails) {
  test::TempDir dir;
  SimRig left(false), right(false);  // no blank: no contact
  ServerRig server(
      dir.path(), {test::machine("left", left.address()), test::machine("right", right.address())});
  const int64_t top = post(server, blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  const int64_t bottom = post(server, blinky({{"side", "bottom"},
                                              {"align_holes", "auto"},
                                              {"height_map_from", std::to_string(top)}},
                                             "blinky-B.Cu.gbr"));
  ASSERT_TRUE(test::wait_until([&] { return waiting_for_clip(server, top); }, 30));
  server.control(top, R"({"action":"probe_ready"})");
  ASSERT_TRUE(test::wait_until([&] { return ended(server, top) && ended(server, bottom); }, 120));
  EXPECT_EQ(server.job(top)["state"], "failed");
  const nlohmann::json j = server.job(bottom);
  EXPECT_EQ(j["state"], "failed");
  const std::string message = j["message"];
  EXPECT_NE(message.find(fmt::format("job {} ended failed without a height map", top)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("nothing was cut"), std::string::npos) << message;
  EXPECT_EQ(j["executed"], 0);
  EXPECT_EQ(j["height_map"], false);
  // Failed in the queue: no machine claimed it, no run was started.
  EXPECT_EQ(j["machine"], "") << j.dump();
  EXPECT_EQ(j["server"], "") << j.dump();
  EXPECT_EQ(j["runs"], 0) << j.dump();
  EXPECT_EQ(j["started_ms"], 0) << j.dump();
  for (const SimRig* sim : {&left, &right})
    for (const auto& s : sim->machine().trace()) EXPECT_GT(s.z_mm, -1.01);
  // Requeued, it would fail again at once (an outside tester got 200 and a job still
  // `failed`): refused, saying what to do first; the job stays as it was.
  auto r = server.control(bottom, R"({"action":"requeue"})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 409) << r->body;
  EXPECT_NE(r->body.find(fmt::format("job {} is failed: it cuts with job {}'s height map, and job "
                                     "{} ended failed without a height map",
                                     bottom, top, top)),
            std::string::npos)
      << r->body;
  EXPECT_NE(r->body.find(fmt::format("(requeue job {} first, which probes the blank again, then "
                                     "requeue this job)",
                                     top)),
            std::string::npos)
      << r->body;
  EXPECT_EQ(server.job(bottom)["state"], "failed");
  EXPECT_EQ(server.job(bottom)["message"], message);
}

TEST(ServerMapFlow, HeightMapFieldsAreCheckedAtUpload) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});  // no machine: every job stays queued
  // Over 16 points a side.
  expect_refused(server,
                 blinky({{"probe_first", "1"}, {"align_holes", "auto"}, {"probe_spacing_mm", "1"}}),
                 "probe_spacing_mm", "the controller keeps at most 16 a side");
  // A flip without a map to flip.
  expect_refused(server, blinky({{"height_map_flip", "table"}}), "height_map_flip",
                 "goes with height_map_from");
  // Mirrored about the flip axis of a job that has none.
  const int64_t plain = post(server, blinky({{"probe_first", "1"}}));
  expect_refused(server,
                 blinky({{"side", "bottom"},
                         {"height_map_from", std::to_string(plain)},
                         {"height_map_flip", "blank"}},
                        "blinky-B.Cu.gbr"),
                 "height_map_flip=blank", "has no alignment holes");
  // A source map (there already) that does not reach over this job.
  heightmap::HeightMap small;
  small.pitch_x_mm = small.pitch_y_mm = 2;
  small.rows = small.cols = 2;
  small.heights_um = {0, 0, 0, 0};
  small.probed_at = "2026-11-28T00:00:00Z";
  const fs::path plain_dir = server.data().job_dir(server.store().get(plain)->key);
  heightmap::write_height_map_file(small, (plain_dir / kHeightMapFile).string());
  expect_refused(
      server,
      blinky({{"side", "bottom"}, {"height_map_from", std::to_string(plain)}}, "blinky-B.Cu.gbr"),
      "height_map_from", "upload it with probe_first=1");
  // At upload the job is refused, not left unstarted.
  expect_refused(
      server,
      blinky({{"side", "bottom"}, {"height_map_from", std::to_string(plain)}}, "blinky-B.Cu.gbr"),
      "height_map_from", "the job was not queued");
  auto r = server.client().Post(
      "/api/jobs", server.auth(),
      blinky({{"side", "bottom"}, {"height_map_from", std::to_string(plain)}}, "blinky-B.Cu.gbr"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->body.find("--probe"), std::string::npos) << r->body;  // the server's words
  EXPECT_EQ(r->body.find("not started"), std::string::npos) << r->body;
}

TEST(ServerMapFlow, NumbersThatAreNoNumberAreRefusedNamingTheField) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  expect_refused(server, blinky({{"align_holes", "auto"}, {"align_measured", "NaN,0,1,2"}}),
                 "align_measured", "finite");
  expect_refused(server, blinky({{"tool_width_mm", "inf"}}), "tool_width_mm", "finite");
  expect_refused(server, blinky({{"probe_spacing_mm", "1e400"}}), "probe_spacing_mm", "finite");
  const int64_t id = post(server, blinky({}));
  auto r = server.control(id, R"({"action":"override","percent":1e400})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400) << r->body;
  EXPECT_NE(r->body.find("malformed JSON"), std::string::npos) << r->body;
}

// A map taken over from another job that does not cover this one is not kept: the job's
// archive holds only a map it was cut with (its record's height_map).
TEST(ServerMapFlow, AMapThatDoesNotCoverTheJobIsNotKept) {
  test::TempDir dir;
  DataFolder data(dir.path() / "data");
  SqliteJobStore store(data.database().string());
  JobRecord source;
  source.key = "source";
  source.name = "source";
  source.input_file = kBoardManifest;
  source.state = JobState::kCompleted;
  source.id = store.add(source, "");
  fs::create_directories(data.job_dir("source"));
  std::ofstream(data.job_dir("source") / kBoardManifest) << "{}";
  heightmap::HeightMap small;
  small.pitch_x_mm = small.pitch_y_mm = 2;
  small.rows = small.cols = 2;
  small.heights_um = {0, 0, 0, 0};
  small.probed_at = "2026-11-28T00:00:00Z";
  keep_height_map(data.job_dir("source"), small, "source", "mill");
  JobPlan plan;
  plan.extents_mm.add(Point2(10, 10));
  plan.extents_mm.add(Point2(30, 20));
  BoardSettings board;
  board.height_map_from = source.id;
  const fs::path job_dir = data.job_dir("bottom");
  fs::create_directories(job_dir);
  std::vector<std::string> notes;
  try {
    map_from_source_job(store, data, job_dir, "bottom", board, "mill", plan,
                        [&](const std::string& n) { notes.push_back(n); });
    ADD_FAILURE() << "a map over 0 .. 2 mm taken for a job over 10 .. 30 mm";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the job cuts over"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(job_dir / kHeightMapFile));
  EXPECT_FALSE(fs::exists(job_dir / kHeightMapPicture));
}

}  // namespace
}  // namespace host::server
