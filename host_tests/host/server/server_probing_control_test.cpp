// The operator's controls while a probe-first board job probes (issue 25, the workshop):
// hold pauses the probing between touches with the tool retracted, resume goes on, abort
// and the server stopping end it at once with nothing cut; /api/status shows the machine
// probing where it is, and the machine's state after an abort at once.
#include <gtest/gtest.h>

#include <memory>  // std::unique_ptr
#include <set>     // std::set
#include <thread>  // std::this_thread

#include "host/lib/heightmap/controller_map.h"  // ProbeMotion
#include "host/lib/server/data_folder.h"
#include "host_tests/host/server/probe_first_job.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::ServerRig;
using test::SimRig;
using test::tilted_blank;
using test::touches;
namespace fs = std::filesystem;

// The blinky board probed first on a 2 mm grid (many touches: time to act while it probes).
int64_t post_probe_first(const ServerRig& server) {
  return test::post_probe_first(server, "2");
}

nlohmann::json machine_of(const ServerRig& server) {
  const nlohmann::json s = server.status();
  return s.is_object() && !s["machines"].empty() ? s["machines"][0] : nlohmann::json();
}

// Claimed, confirmed, and `n` touches into its grid.
void probe_until(const ServerRig& server, int64_t id, size_t n) {
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return touches(server, id) >= n; }, 30))
      << server.status().dump();
}

bool held_between_touches(const ServerRig& server, int64_t id) {
  const nlohmann::json j = server.running(id);
  return j.is_object() && j.contains("probe") && j["probe"].value("held", false) &&
         machine_of(server)["state"] == "held";
}

TEST(ServerProbingControl, HoldPausesTheProbingBetweenTouchesWithTheToolUpAndResumeGoesOn) {
  test::TempDir dir;
  SimRig sim(false, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  probe_until(server, id, 2);
  const size_t planned = server.running(id)["probe"]["planned"];
  auto r = server.control(id, R"({"action":"hold"})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  ASSERT_TRUE(test::wait_until([&] { return held_between_touches(server, id); }, 20))
      << server.status().dump();
  // Held at once; the touch under way ends (retracted) before the machine stands still.
  ASSERT_TRUE(test::wait_until(
      [&] {
        const sim::ToolSample a = sim.machine().position();
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        return sim.machine().position().z_mm == a.z_mm;
      },
      20));
  const size_t held_at = touches(server, id);
  EXPECT_LT(held_at, planned) << "the hold came after the grid";
  const sim::ToolSample tool = sim.machine().position();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(touches(server, id), held_at) << "no touch while held";
  EXPECT_EQ(sim.machine().position().z_mm, tool.z_mm) << "a held machine must not move";
  // Retracted above the last contact (0.5 mm), not resting on the copper.
  EXPECT_GT(tool.z_mm, test::tilted_copper_mm(tool.x_mm) + 0.4) << tool.x_mm << " " << tool.y_mm;
  EXPECT_TRUE(held_between_touches(server, id));
  r = server.control(id, R"({"action":"resume"})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 120))
      << server.job(id).dump();
}

TEST(ServerProbingControl, AbortWhileHeldInProbingEndsItWithNothingCut) {
  test::TempDir dir;
  SimRig sim(false, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  probe_until(server, id, 2);
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return held_between_touches(server, id); }, 20))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 20))
      << server.job(id).dump();
  const nlohmann::json j = server.job(id);
  EXPECT_NE(j["message"].get<std::string>().find("nothing was cut"), std::string::npos) << j.dump();
  EXPECT_EQ(j["executed"], 0);
  double lowest_mm = 1e9;
  for (const auto& s : sim.machine().trace()) lowest_mm = std::min(lowest_mm, s.z_mm);
  EXPECT_GT(lowest_mm, -0.01) << "only touches: never below the copper";
  // The machine's own state at once, and no job named.
  const nlohmann::json m = machine_of(server);
  EXPECT_EQ(m["state"], "idle") << m.dump();
  EXPECT_TRUE(m["job"].is_null()) << m.dump();
}

// /api/status while it probes: the machine is `probing`, where the tool stands, not idle at
// the origin.
TEST(ServerProbingControl, StatusShowsTheMachineProbingAndWhereItIs) {
  test::TempDir dir;
  SimRig sim(false, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  probe_until(server, id, 1);
  std::set<std::vector<double>> positions;
  test::wait_until(
      [&] {
        const nlohmann::json status = server.status();  // one snapshot for both
        if (!status.is_object() || status["running"].empty()) return false;
        const nlohmann::json m = status["machines"][0];
        const nlohmann::json j = status["running"][0];
        if (m["state"] != "probing" || j["machine_state"] != "probing") return false;
        EXPECT_EQ(m["job"], id);
        EXPECT_EQ(j["position_mm"], m["position_mm"]);
        positions.insert(m["position_mm"].get<std::vector<double>>());
        return positions.size() >= 3;
      },
      30);
  EXPECT_GE(positions.size(), 3u) << server.status().dump();
  EXPECT_EQ(positions.count({0.0, 0.0, 0.0}), 0u);
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 20));
}

// The server stopping (Ctrl-C to engraver serve) while it probes: the probing ends at once,
// not after its grid, and the job is interrupted (continuable) with nothing cut.
TEST(ServerProbingControl, StoppingTheServerEndsTheProbingAtOnce) {
  test::TempDir dir;
  SimRig sim(false, 0, tilted_blank());
  fs::path archive;
  int64_t id = 0;
  {
    ServerRig server(dir.path(), {test::machine("mill", sim.address())});
    id = post_probe_first(server);
    archive = server.data().job_dir(server.store().get(id)->key);
    probe_until(server, id, 2);
    server.shutdown();
  }
  // No map: the grid was not finished.
  EXPECT_FALSE(fs::exists(archive / "heightmap.json"));
  ServerRig again(dir.path(), {});
  const nlohmann::json j = again.job(id);
  EXPECT_EQ(j["state"], "interrupted") << j.dump();
  EXPECT_NE(j["message"].get<std::string>().find("nothing was cut"), std::string::npos) << j.dump();
  EXPECT_EQ(j["executed"], 0);
  // The server's words, not an operator's abort.
  const std::string message = j["message"];
  EXPECT_NE(message.find("the server stopped (interrupted) while probing"), std::string::npos)
      << message;
  EXPECT_EQ(message.find("aborted"), std::string::npos) << message;
  // The touch under way stopped where it was: the tool up before the server ended.
  EXPECT_NEAR(sim.machine().position().z_mm, heightmap::ProbeMotion{}.travel_z_mm, 0.01);
}

// A hold asked while the job waits for the clip shows at once (the machine held, the probe
// held), and no touch follows the clip until resume; before it the machine says it waits
// for the operator, not idle.
TEST(ServerProbingControl, AHoldWhileWaitingForTheClipIsShownAndKept) {
  test::TempDir dir;
  SimRig sim(false, 0, tilted_blank());
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30))
      << server.status().dump();
  EXPECT_EQ(machine_of(server)["state"], "probe_clip") << server.status().dump();
  EXPECT_EQ(server.running(id)["probe"]["held"], false);
  ASSERT_EQ(server.control(id, R"({"action":"hold"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return held_between_touches(server, id); }, 5))
      << server.status().dump();
  // The job says held as the machine does; its probe object keeps the stage.
  EXPECT_EQ(server.running(id)["machine_state"], "held");
  EXPECT_EQ(server.running(id)["probe"]["stage"], "probe_clip");
  ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(touches(server, id), 0u) << "no touch while held";
  EXPECT_TRUE(held_between_touches(server, id)) << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"resume"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return touches(server, id) >= 1; }, 30))
      << server.status().dump();
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 20));
}

// An abort in the middle of a touch (#X stops the descent where it is): the tool goes up
// to the travel height before the machine is free, as `engraver probe` does on Ctrl-C.
TEST(ServerProbingControl, AnAbortMidTouchRaisesTheTool) {
  test::TempDir dir;
  SimRig sim(true, 0, tilted_blank());  // real time: a descent takes about a second
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post_probe_first(server);
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
  ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
  // The first descent under way (from Z 1 mm towards the copper near Z 0).
  ASSERT_TRUE(test::wait_until(
      [&] {
        const double z = sim.machine().position().z_mm;
        return z < 0.7 && z > 0.2;
      },
      30));
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 20))
      << server.job(id).dump();
  const nlohmann::json j = server.job(id);
  const std::string message = j["message"];
  EXPECT_NE(message.find("aborted while probing; nothing was cut"), std::string::npos) << message;
  EXPECT_NE(message.find("the tool raised to Z 2.000 mm"), std::string::npos) << message;
  EXPECT_NEAR(sim.machine().position().z_mm, heightmap::ProbeMotion{}.travel_z_mm, 0.01);
  EXPECT_EQ(machine_of(server)["state"], "idle") << server.status().dump();
}

// After an abort the machine's state follows at once (not the run's last "running"), and
// the machine names no job 0.
TEST(ServerProbingControl, AfterAnAbortTheMachineStateFollowsAtOnce) {
  test::TempDir dir;
  SimRig sim(true);
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = server.upload_ok("squares.ngc", test::squares_gcode(6, 10));
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "running"; }, 30));
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 20));
  const nlohmann::json m = machine_of(server);
  EXPECT_EQ(m["state"], "idle") << m.dump();
  EXPECT_TRUE(m["job"].is_null()) << m.dump();
}

// A continued probe-first job (issue 25's outside tester: interrupted mid-cut on one machine,
// continued on another, which asks for the clip again; stopped there, the job said "nothing
// was cut"): a run that ends waiting for the clip or probing keeps the saved position and
// says what the earlier runs cut; the last run continues where the first stopped.
TEST(ServerProbingControl, ARunStoppedBeforeItCutsKeepsTheContinuedJobsPosition) {
  test::TempDir dir;
  SimRig left(true, 0, tilted_blank()), right(true, 0, tilted_blank());
  const MachineSpec on_left = test::machine("left", left.address());
  const MachineSpec on_right = test::machine("right", right.address());
  int64_t id = 0;
  JobRecord saved;  // the record after the mid-cut stop
  {
    ServerRig server(dir.path(), {on_left});
    id = test::post_probe_first(server, "12");
    probe_until(server, id, 0);
    // Cutting: the saved position some job commands into the job.
    ASSERT_TRUE(test::wait_until([&] { return server.store().get(id)->resume_index >= 5; }, 120))
        << server.status().dump();
    server.shutdown();
    saved = *server.store().get(id);
  }
  ASSERT_EQ(saved.state, JobState::kInterrupted) << saved.message;
  ASSERT_GT(saved.resume_index, 0) << saved.message;
  // The run's count and where the whole job stands (the next run counts another stream).
  EXPECT_NE(saved.message.find(fmt::format(" commands (counts of this run; the job is at job "
                                           "command {} of ",
                                           saved.resume_index)),
            std::string::npos)
      << saved.message;
  // Continued on the other machine: its clip wait, then its probing, stopped by the server.
  for (const bool probing : {false, true}) {
    SCOPED_TRACE(probing ? "while probing" : "while waiting for the clip");
    ServerRig server(dir.path(), {on_right});
    ASSERT_EQ(server.control(id, R"({"action":"continue"})")->status, 200);
    if (probing) {
      probe_until(server, id, 1);
    } else {
      ASSERT_TRUE(test::wait_until(
          [&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
    }
    server.shutdown();
    const JobRecord after = *server.store().get(id);
    EXPECT_EQ(after.state, JobState::kInterrupted);
    EXPECT_EQ(after.resume_index, saved.resume_index);
    EXPECT_EQ(after.resume_point, saved.resume_point);
    EXPECT_EQ(after.resume_job_id, saved.resume_job_id);
    EXPECT_EQ(after.resume_curve, saved.resume_curve);
    EXPECT_EQ(after.executed, 0);  // of this run's stream (the map's frames not yet sent)
    EXPECT_EQ(after.message.find("nothing was cut"), std::string::npos) << after.message;
    EXPECT_NE(after.message.find(fmt::format("nothing more was cut in this run (the job's earlier "
                                             "runs cut up to job command {} of ",
                                             saved.resume_index)),
              std::string::npos)
        << after.message;
  }
  // Back on the machine that probed: the job continues where the first run stopped.
  ServerRig server(dir.path(), {on_left});
  ASSERT_EQ(server.control(id, R"({"action":"continue"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["runs"] == 4; }, 30));
  const fs::path job_dir = server.data().job_dir(server.store().get(id)->key);
  ASSERT_TRUE(test::wait_until(
      [&] {
        std::error_code ec;
        return fs::exists(job_dir / "runs" / "4" / "machine.log", ec) &&
               read_file(job_dir / "runs" / "4" / "machine.log").find("planned:") !=
                   std::string::npos;
      },
      30));
  // Where the first run stopped: the saved position, or where the machine stopped (at or
  // past it, never before).
  const std::string log = read_file(job_dir / "runs" / "4" / "machine.log");
  const std::string continuing = "continuing at job command ";
  const size_t at = log.find(continuing);
  ASSERT_NE(at, std::string::npos) << log;
  EXPECT_GE(std::stoll(log.substr(at + continuing.size())), saved.resume_index) << log;
  // One count of job commands: the log's "J of N" and the message's (an outside tester saw
  // "job command 18 of 196" in the message, "of 139" in the log).
  const size_t of = log.find(" of ", at);
  ASSERT_NE(of, std::string::npos) << log;
  const long long log_total = std::stoll(log.substr(of + 4));
  EXPECT_NE(
      saved.message.find(fmt::format("the job is at job command {} of {}, where continue resumes)",
                                     saved.resume_index, log_total)),
      std::string::npos)
      << saved.message << "\n"
      << log;
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
}

// A continued probe-first job goes back to the machine that probed its blank (issue 25's
// outside tester: another free machine claimed it and asked for the clip again). With that
// machine down, the job waits and says for which; once it answers, it takes the job and
// cuts with the map it probed, never asking for the clip.
TEST(ServerProbingControl, AContinuedProbeFirstJobGoesBackToTheMachineThatProbedIt) {
  test::TempDir dir;
  auto left = std::make_unique<SimRig>(true, 0, tilted_blank());
  SimRig right(true, 0, tilted_blank());
  const uint16_t left_port = left->port();
  const MachineSpec on_left = test::machine("left", left->address());
  const MachineSpec on_right = test::machine("right", right.address());
  int64_t id = 0;
  {
    ServerRig server(dir.path(), {on_left});
    id = test::post_probe_first(server, "12");
    probe_until(server, id, 0);
    ASSERT_TRUE(test::wait_until([&] { return server.store().get(id)->resume_index >= 5; }, 120))
        << server.status().dump();
    server.shutdown();
  }
  left->kill();
  ServerRig server(dir.path(), {on_right, on_left});
  ASSERT_EQ(server.control(id, R"({"action":"continue"})")->status, 200);
  // The right machine is free and answers; the job stays queued for the left one.
  for (int i = 0; i < 15; ++i) {
    const nlohmann::json j = server.job(id);
    ASSERT_EQ(j["state"], "queued") << j.dump();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(server.job(id)["waiting"],
            "waiting for machine 'left' (offline), which probed this job's blank in an earlier "
            "run (the blank is clamped there)")
      << server.job(id).dump();
  left = std::make_unique<SimRig>(true, left_port, tilted_blank());  // the left one is back
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "running"; }, 30))
      << server.job(id).dump();
  EXPECT_EQ(server.store().get(id)->machine, "left");
  ASSERT_TRUE(test::wait_until([&] { return server.running(id)["executed"].get<int>() > 0; }, 60))
      << server.status().dump();
  const std::string log =
      read_file(server.data().job_dir(server.store().get(id)->key) / "runs" / "2" / "machine.log");
  EXPECT_NE(log.find("height map probed in an earlier run of this job"), std::string::npos) << log;
  EXPECT_EQ(log.find("waiting for the probe clip"), std::string::npos) << log;
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
}

}  // namespace
}  // namespace host::server
