// A hold while a probe-first board job probes, at any instant of a touch (issue 25, Safety
// and the workshop): the touch under way finishes and retracts, so the held machine never
// leaves the bit at or near the copper; /api/status says held at once, the same in every
// field, with the machine's real position; resume goes on with no point lost or probed
// twice; machine.log records the hold and the resume with the point.
#include <gtest/gtest.h>

#include <cmath>  // std::lround, std::abs

#include <map>  // std::map
#include <set>  // std::set

#include "host/lib/heightmap/controller_map.h"  // ProbeMotion
#include "host/lib/server/data_folder.h"
#include "host_tests/host/server/probe_first_job.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::ServerRig;
using test::SimRig;
using test::tilted_blank;
using test::tilted_copper_mm;
using test::touches;
namespace fs = std::filesystem;

// The blinky board probed first on a coarse grid: a few touches in real time.
int64_t post_probe_first(const ServerRig& server) {
  return test::post_probe_first(server, "12");
}

// The job asks for the probe clip and the operator confirms it: probing starts.
bool clip_confirmed(ServerRig& server, int64_t id) {
  if (!test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30))
    return false;
  const auto r = server.control(id, R"({"action":"probe_ready"})");
  return r && r->status == 200;
}

// The instants of a touch at which the operator holds.
enum class Instant { kDescending, kAtContact, kRetracting, kTravelling };

// Waits (polling the simulated tool) until the next touch is at `when`.
bool reach(const SimRig& sim, Instant when) {
  double band_entered_mm = -1;  // descending: where the tool entered 0.2 .. 0.6 mm above
  bool touched = false;
  sim::ToolSample last{};  // travelling: the sample before
  return test::wait_until(
      [&] {
        for (int i = 0; i < 1000; ++i) {
          const sim::ToolSample t = sim.machine().position();
          const double above_mm = t.z_mm - tilted_copper_mm(t.x_mm);
          const bool closed = sim.machine().probe_closed();
          switch (when) {
            case Instant::kDescending:
              if (above_mm <= 0.2 || above_mm >= 0.6) {
                band_entered_mm = -1;
              } else if (band_entered_mm < 0) {
                band_entered_mm = t.z_mm;
              } else if (t.z_mm < band_entered_mm - 0.01) {
                return true;  // going down, 10 um into the band
              }
              break;
            case Instant::kAtContact:
              if (closed) return true;
              break;
            case Instant::kRetracting:
              if (closed) touched = true;
              if (touched && above_mm > 0.1 && above_mm < 0.35) return true;
              break;
            case Instant::kTravelling: {  // after a touch, moving in X/Y to the next point
              if (closed) touched = true;
              if (touched && above_mm > 0.8 && (t.x_mm != last.x_mm || t.y_mm != last.y_mm) &&
                  last.z_mm == t.z_mm)
                return true;
              last = t;
              break;
            }
          }
          std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
        return false;
      },
      60);
}

// The tool has not moved for 300 ms.
bool at_rest(const SimRig& sim) {
  return test::wait_until(
      [&] {
        const sim::ToolSample a = sim.machine().position();
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        const sim::ToolSample b = sim.machine().position();
        return a.x_mm == b.x_mm && a.y_mm == b.y_mm && a.z_mm == b.z_mm;
      },
      20);
}

TEST(ServerProbeHold, AHoldAtAnyInstantOfATouchLeavesTheToolRetractedAndResumeProbesEachPointOnce) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());  // real time: a descent takes about a second
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(clip_confirmed(server, id)) << server.status().dump();
  const double retract_mm = heightmap::ProbeMotion{}.retract_mm;
  for (const Instant when : {Instant::kDescending, Instant::kAtContact, Instant::kRetracting}) {
    SCOPED_TRACE(static_cast<int>(when));
    ASSERT_TRUE(reach(sim, when)) << server.status().dump();
    auto r = server.control(id, R"({"action":"hold"})");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    // Held at once, and every field says so.
    const nlohmann::json status = server.status();
    const nlohmann::json m = status["machines"][0];
    const nlohmann::json j = status["running"][0];
    EXPECT_EQ(m["state"], "held") << status.dump();
    EXPECT_EQ(j["machine_state"], "held") << status.dump();
    EXPECT_EQ(j["probe"]["held"], true) << status.dump();
    ASSERT_TRUE(at_rest(sim));
    const size_t held_at = touches(server, id);
    const sim::ToolSample tool = sim.machine().position();
    // The touch finished and retracted: the bit stands above its contact, not on the copper.
    EXPECT_GE(tool.z_mm, tilted_copper_mm(tool.x_mm) + retract_mm - 0.01)
        << "held at " << tool.x_mm << " " << tool.y_mm << " " << tool.z_mm;
    // /api/status shows where the machine stands, not a position from the touch.
    const nlohmann::json held = server.status();
    EXPECT_EQ(held["machines"][0]["state"], "held") << held.dump();
    EXPECT_EQ(held["running"][0]["machine_state"], "held") << held.dump();
    const std::vector<double> shown = held["machines"][0]["position_mm"];
    EXPECT_NEAR(shown[2], tool.z_mm, 0.001) << held.dump();
    EXPECT_EQ(held["running"][0]["position_mm"], held["machines"][0]["position_mm"]);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(touches(server, id), held_at) << "no touch while held";
    EXPECT_EQ(sim.machine().position().z_mm, tool.z_mm) << "a held machine must not move";
    r = server.control(id, R"({"action":"resume"})");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    EXPECT_NE(server.running(id)["machine_state"], "held");
  }
  // The grid done (the map kept), the cut in real time is not needed.
  const fs::path job_dir = server.data().job_dir(server.store().get(id)->key);
  ASSERT_TRUE(test::wait_until([&] { return fs::exists(job_dir / "heightmap.json"); }, 120))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30))
      << server.job(id).dump();

  // Each grid point touched exactly once: a contact is the tool tip reaching the copper.
  const nlohmann::json map = nlohmann::json::parse(read_file(job_dir / "heightmap.json"));
  const int points = map["grid"]["rows"].get<int>() * map["grid"]["cols"].get<int>();
  ASSERT_GE(points, 4);
  // Contacts at grid points only: the cut that began before the abort goes into the copper.
  const nlohmann::json& grid = map["grid"];
  auto on_grid = [&](double v_mm, int axis) {
    const double steps =
        (v_mm - grid["origin_mm"][axis].get<double>()) / grid["pitch_mm"][axis].get<double>();
    return std::abs(steps - std::lround(steps)) * grid["pitch_mm"][axis].get<double>() < 0.005;
  };
  std::map<std::pair<long, long>, int> contacts;
  bool above = true;
  for (const sim::ToolSample& s : sim.machine().trace()) {
    const bool on = s.z_mm <= tilted_copper_mm(s.x_mm) + 0.001;
    if (on && above && on_grid(s.x_mm, 0) && on_grid(s.y_mm, 1))
      ++contacts[{std::lround(s.x_mm * 100), std::lround(s.y_mm * 100)}];
    above = !on;
  }
  EXPECT_EQ(contacts.size(), static_cast<size_t>(points));
  for (const auto& c : contacts) EXPECT_EQ(c.second, 1) << c.first.first << " " << c.first.second;
  const std::string log = read_file(job_dir / "runs" / "1" / "machine.log");
  EXPECT_NE(log.find(fmt::format("({} touches)", points)), std::string::npos) << log;
  // Each hold and resume in the run's log, with the touches done.
  size_t holds = 0, resumes = 0;
  for (size_t at = 0;
       (at = log.find("probing held by the operator after touch ", at)) != std::string::npos; ++at)
    ++holds;
  for (size_t at = 0; (at = log.find("probing resumed after touch ", at)) != std::string::npos;
       ++at)
    ++resumes;
  EXPECT_EQ(holds, 3u) << log;
  EXPECT_EQ(resumes, 3u) << log;
}

// An abort of a held probing job (issue 25's tester: one poll showed `probing` between the
// hold and the end): from the abort's answer on, every status says `aborting` until the job
// leaves the machine, ended aborted with the tool raised; never `probing` or `held` again.
TEST(ServerProbeHold, AnAbortOfAHeldProbingJobNeverShowsProbingAgain) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(clip_confirmed(server, id)) << server.status().dump();
  ASSERT_TRUE(reach(sim, Instant::kDescending)) << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_TRUE(at_rest(sim));
  ASSERT_EQ(server.status()["machines"][0]["state"], "held");
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  std::set<std::string> machine_states, job_states;
  int polls = 0;
  const bool left = test::wait_until(
      [&] {
        const nlohmann::json status = server.status();
        ++polls;
        if (status["running"].empty()) return true;
        machine_states.insert(status["machines"][0]["state"].get<std::string>());
        job_states.insert(status["running"][0]["machine_state"].get<std::string>());
        EXPECT_EQ(status["running"][0]["probe"]["held"], false) << status.dump();
        return false;
      },
      30);
  ASSERT_TRUE(left);
  EXPECT_GT(polls, 1);  // the raise takes a while: some polls saw the job still there
  EXPECT_EQ(machine_states, std::set<std::string>({"aborting"}));
  EXPECT_EQ(job_states, std::set<std::string>({"aborting"}));
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
  EXPECT_NE(server.job(id)["message"].get<std::string>().find("the tool raised to Z 2.000 mm"),
            std::string::npos)
      << server.job(id).dump();
  const std::string state = server.status()["machines"][0]["state"];
  EXPECT_TRUE(state == "idle" || state == "ready") << state;
}

// A hold during the last touch (issue 25's outside tester: `executed` went 0 -> 5 -> 7 and
// `executed_mm` showed 22.48 mm, the tool never moving): the grid done, the job stays held
// before its first job command, the controller taking only the height map's frames (they
// move nothing); `executed_mm` stays 0 until the tool moves along the path; resume cuts.
TEST(ServerProbeHold, AHoldDuringTheLastTouchHoldsTheJobBeforeItsFirstCommand) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(clip_confirmed(server, id)) << server.status().dump();
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json j = server.running(id);
        return j.is_object() && j.contains("probe") && j["probe"]["planned"].get<size_t>() > 0 &&
               j["probe"]["touches"] == j["probe"]["planned"].get<size_t>() - 1;
      },
      120))
      << server.status().dump();
  ASSERT_TRUE(reach(sim, Instant::kDescending)) << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  const fs::path job_dir = server.data().job_dir(server.store().get(id)->key);
  // From the hold's answer on, every sample says held, with a position (the outside tester
  // saw the machine `idle`, the job `planning` and no position between probing and cut).
  std::set<std::string> machine_states, job_states;
  bool without_position = false;
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json status = server.status();
        const nlohmann::json j = server.running(id);
        machine_states.insert(status["machines"][0]["state"].get<std::string>());
        job_states.insert(j["machine_state"].get<std::string>());
        if (!j["position_mm"].is_array()) without_position = true;
        return j.is_object() && !j.contains("probe") && j["total"].get<size_t>() > 0 &&
               j["machine_state"] == "held" && j["position_mm"].is_array() &&
               fs::exists(job_dir / "heightmap.json");
      },
      60))
      << server.status().dump();
  EXPECT_EQ(machine_states, std::set<std::string>({"held"}));
  EXPECT_EQ(job_states, std::set<std::string>({"held"}));
  EXPECT_FALSE(without_position);
  ASSERT_TRUE(at_rest(sim));
  const sim::ToolSample tool = sim.machine().position();
  const nlohmann::json map = nlohmann::json::parse(read_file(job_dir / "heightmap.json"));
  const size_t points = map["grid"]["rows"].get<size_t>() * map["grid"]["cols"].get<size_t>();
  const size_t map_frames = 1 + (points + 7) / 8;  // header, 8 heights a frame
  const double held_left_s = server.running(id)["remaining_s"].get<double>();
  EXPECT_GT(held_left_s, 0.0);
  for (int i = 0; i < 10; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const nlohmann::json j = server.running(id);
    EXPECT_EQ(j["machine_state"], "held") << j.dump();
    EXPECT_LE(j["executed"].get<size_t>(), map_frames) << j.dump();
    EXPECT_EQ(j["executed_mm"].get<double>(), 0.0) << j.dump();
    EXPECT_EQ(j["remaining_s"].get<double>(), held_left_s) << j.dump();  // stands still
    const sim::ToolSample now = sim.machine().position();
    EXPECT_EQ(now.x_mm, tool.x_mm);
    EXPECT_EQ(now.y_mm, tool.y_mm);
    EXPECT_EQ(now.z_mm, tool.z_mm);
  }
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json j = server.running(id);
        return j.is_object() && j["executed_mm"].get<double>() > 0.0;
      },
      60))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
  // The hold is in machine.log too, as every probing hold is.
  const std::string log = read_file(job_dir / "runs" / "1" / "machine.log");
  EXPECT_NE(log.find(fmt::format("probing held by the operator after touch {} of {} (the last)",
                                 points, points)),
            std::string::npos)
      << log;
}

// A hold while the tool travels to the next point (issue 25's outside tester: status said
// held, yet the tool went down and touched): the travel ends above the point, the tool rests
// there, no descent until resume, and the log has the hold; resume touches that point.
TEST(ServerProbeHold, AHoldDuringTheTravelToAPointStopsAboveItWithNoDescentUntilResume) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(clip_confirmed(server, id)) << server.status().dump();
  // After a touch (the tool rests on the copper before the first: that is no touch).
  ASSERT_TRUE(test::wait_until([&] { return touches(server, id) >= 1; }, 60));
  ASSERT_TRUE(reach(sim, Instant::kTravelling)) << server.status().dump();
  const size_t before = touches(server, id);
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_TRUE(at_rest(sim));
  const sim::ToolSample tool = sim.machine().position();
  const double start_z_mm = heightmap::ProbeMotion{}.start_z_mm;
  EXPECT_NEAR(tool.z_mm, start_z_mm, 0.01) << "held at the travel height, not going down";
  const size_t trace_at = sim.machine().trace().size();
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(touches(server, id), before) << "no touch while held";
  EXPECT_EQ(sim.machine().position().z_mm, tool.z_mm) << "no descent while held";
  EXPECT_EQ(server.running(id)["machine_state"], "held");
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return touches(server, id) > before; }, 60))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
  // The touch after resume is at the point the tool stood above.
  bool touched_there = false;
  const std::vector<sim::ToolSample>& trace = sim.machine().trace();
  for (size_t i = trace_at; i < trace.size() && !touched_there; ++i) {
    const sim::ToolSample& s = trace[i];
    touched_there = s.z_mm <= tilted_copper_mm(s.x_mm) + 0.001 &&
                    std::abs(s.x_mm - tool.x_mm) < 0.001 && std::abs(s.y_mm - tool.y_mm) < 0.001;
  }
  EXPECT_TRUE(touched_there);
  const fs::path job_dir = server.data().job_dir(server.store().get(id)->key);
  const std::string log = read_file(job_dir / "runs" / "1" / "machine.log");
  EXPECT_NE(log.find(fmt::format("probing held by the operator after touch {} of", before)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find(fmt::format("probing resumed after touch {} of", before)), std::string::npos)
      << log;
}

// The time left of a probe-first job (issue 25's testers: it counted down while the job
// waited for the clip, was held or probed, reached 0 before the cut and stayed 0 once it
// began): the cut's planned time, standing still, until the cut starts (the probe object
// counts the touches); then counting down, not 0, while the cut goes on.
TEST(ServerProbeHold, TheTimeLeftIsTheCutsAndStandsStillUntilTheCutStarts) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  const double planned_s = server.job(id)["planned_s"];
  ASSERT_GT(planned_s, 10.0);
  auto left_s = [&] { return server.running(id)["remaining_s"].get<double>(); };
  // Sampled 5 times over a second: each the cut's planned time.
  auto stands_still = [&](const char* stage) {
    for (int i = 0; i < 5; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      EXPECT_NEAR(left_s(), planned_s, 1e-6) << stage << " " << server.status().dump();
    }
  };
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
  stands_still("waiting for the clip");
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  stands_still("held waiting for the clip");
  ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return touches(server, id) >= 1; }, 60));
  stands_still("probing");
  ASSERT_TRUE(reach(sim, Instant::kDescending)) << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_EQ(server.running(id)["machine_state"], "held");
  stands_still("probing held");
  stands_still("probing held, 2 s");
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  // The cut under way: counting down from the planned time, never 0 while it cuts.
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json j = server.running(id);
        return j.is_object() && j["machine_state"] == "running" && !j.contains("probe") &&
               j["executed"].get<int>() > 0;
      },
      120))
      << server.status().dump();
  const double cutting_s = left_s();
  EXPECT_GT(cutting_s, 0.5 * planned_s);
  EXPECT_LE(cutting_s, planned_s);
  // It counts down as the machine cuts (it stands still while the machine pauses for the
  // operator), and stays far from 0 this early in the cut.
  nlohmann::json later;
  EXPECT_TRUE(test::wait_until(
      [&] {
        later = server.running(id);
        return later["remaining_s"].get<double>() < cutting_s - 0.5;
      },
      20))
      << later.dump();
  EXPECT_GT(later["remaining_s"].get<double>(), 0.5 * planned_s) << later.dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30))
      << server.job(id).dump();
}

// probe_ready while the job is held waiting for the clip (the guide's Actions by job state):
// accepted, the job stays held with no touch until resume, then it probes.
TEST(ServerProbeHold, ProbeReadyWhileHeldInProbeClipWaitsForResumeBeforeTheFirstTouch) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_EQ(server.running(id)["machine_state"], "held");
  ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
  const double z_mm = sim.machine().position().z_mm;
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_EQ(server.running(id)["machine_state"], "held") << server.status().dump();
  EXPECT_EQ(server.status()["machines"][0]["state"], "held");
  EXPECT_EQ(touches(server, id), 0u);
  EXPECT_EQ(sim.machine().position().z_mm, z_mm);  // no touch started
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  EXPECT_TRUE(test::wait_until([&] { return touches(server, id) > 0; }, 60))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  EXPECT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
}

}  // namespace
}  // namespace host::server
