// A workshop machine's link that freezes for 3 s mid-job (issue 25's workshop tester): the
// controller holds the job by its 2 s link watchdog; when the link is back the server's
// sender resumes it, and the job completes, cutting the path an uncut run cuts. Before, it
// waited out the 30 s stall limit and ended interrupted.
#include <gtest/gtest.h>

#include <atomic>    // std::atomic
#include <cstdio>    // std::printf
#include <optional>  // std::optional
#include <set>       // std::set
#include <thread>    // std::thread

#include "host/lib/server/job_planning.h"  // plan_file, encode_options
#include "host/lib/sim/sim_job.h"
#include "host_tests/host/freezing_proxy.h"
#include "host_tests/host/server/blinky_upload.h"  // blinky, post
#include "host_tests/host/server/server_test_rig.h"
#include "host_tests/host/sim/cut_path.h"

namespace host::server {
namespace {

using ::host::test::FreezingProxy;
using test::ServerRig;
using test::SimRig;

// The job runs on its machine and some of its commands have been executed.
bool cutting(const ServerRig& server, int64_t id) {
  const nlohmann::json p = server.running(id);
  return p.is_object() && p["machine_state"] == "running" && p["executed"].get<int>() > 0;
}

TEST(ServerLinkCut, AJobWhoseLinkFreezesFor3sCompletesCuttingTheSamePath) {
  test::TempDir dir;
  SimRig sim(true);  // real time: the machine cuts on while the link is frozen
  FreezingProxy proxy(sim.port());
  // The sender gives the link up after 10 s without a reply, as by default.
  ServerRig server(dir.path(), {test::machine("m1", proxy.address())}, 256 * 1024, {},
                   std::chrono::milliseconds(10000));
  const int64_t id = server.upload_ok("multi.ngc", test::squares_gcode(3, 8), "&feed_mm_s=10");
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json p = server.running(id);
        return p.is_object() && p["executed"].get<int>() * 2 >= p["total"].get<int>() &&
               p["executed"].get<int>() > 0;
      },
      30));
  proxy.freeze(true);
  std::this_thread::sleep_for(std::chrono::milliseconds(3000));
  proxy.freeze(false);
  ASSERT_TRUE(test::wait_until(
      [&] {
        const std::string s = server.job(id)["state"];
        return s != "running" && s != "queued";
      },
      60));
  const nlohmann::json j = server.job(id);
  ASSERT_EQ(j["state"], "completed") << j.dump();
  auto log = server.client().Get(fmt::format("/api/jobs/{}/files/machine.log", id).c_str());
  ASSERT_TRUE(log && log->status == 200);
  EXPECT_NE(log->body.find("link watchdog: the controller heard nothing for 2 s"),
            std::string::npos)
      << log->body;

  // The cut path is the uncut run's.
  const std::optional<JobRecord> rec = server.store().get(id);
  ASSERT_TRUE(rec);
  const MachineSpec spec = test::machine("m", "");
  const JobPlan plan =
      plan_file((server.data().job_dir(rec->key) / rec->input_file).string(), rec->name,
                rec->settings, spec.fit.work_width_mm, spec.fit.work_height_mm);
  sim::SimJobOptions so;
  so.encode = encode_options(*rec);
  const sim::SimJobResult ref = sim::run_sim_job(plan, so);
  ASSERT_EQ(ref.outcome, JobOutcome::kCompleted) << ref.message;
  const host::test::CutPath reference = host::test::cut_path(ref.trace, plan);
  const host::test::CutPath got = host::test::cut_path(sim.machine().trace(), plan);
  const double off_mm = host::test::max_distance_mm(got, reference);
  std::printf("link frozen 3 s: cut %.4f mm (uncut %.4f mm), farthest off %.4f mm\n", got.length_mm,
              reference.length_mm, off_mm);
  EXPECT_LT(off_mm, 0.010);
  EXPECT_LT(host::test::max_distance_mm(reference, got), 0.010);
  EXPECT_NEAR(got.length_mm, reference.length_mm, 0.02);
}

// A link that stays silent (the guide: how long `serve` waits): the sender gives it up after
// `serve`'s silence limit, 10 s without a reply, and the job ends interrupted, whether it
// was cutting or probing its blank (a lost link is not a height map that failed: continue
// probes again).
TEST(ServerLinkCut, ALinkSilentFor10sEndsTheJobInterruptedCuttingOrProbing) {
  const std::chrono::milliseconds serve_limit = SenderOptions{}.silence_limit;  // serve's
  ASSERT_EQ(serve_limit.count(), 10000);
  for (const bool probing : {false, true}) {
    SCOPED_TRACE(probing ? "probing" : "cutting");
    test::TempDir dir;
    sim::SimOptions blank;
    blank.surface_um = [](int32_t x_um, int32_t) { return x_um / 500; };
    SimRig sim(true, 0, blank);
    FreezingProxy proxy(sim.port());
    ServerRig server(dir.path(), {test::machine("m1", proxy.address())}, 256 * 1024, {},
                     serve_limit);
    const int64_t id =
        probing
            ? test::post(server, test::blinky({{"probe_first", "1"}, {"probe_spacing_mm", "12"}}))
            : server.upload_ok("multi.ngc", test::squares_gcode(3, 8), "&feed_mm_s=10");
    if (probing) {
      ASSERT_TRUE(test::wait_until(
          [&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
      ASSERT_EQ(server.control(id, R"({"action":"probe_ready"})")->status, 200);
    }
    ASSERT_TRUE(test::wait_until(
        [&] {
          const nlohmann::json p = server.running(id);
          if (!p.is_object()) return false;
          if (probing) return p.contains("probe") && p["probe"]["touches"].get<int>() >= 1;
          return p["executed"].get<int>() > 0 &&
                 p["executed"].get<int>() * 2 >= p["total"].get<int>();
        },
        60))
        << server.status().dump();
    proxy.freeze(true);
    const auto frozen_at = std::chrono::steady_clock::now();
    ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] != "running"; }, 40));
    const double waited_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - frozen_at).count();
    const nlohmann::json j = server.job(id);
    EXPECT_EQ(j["state"], "interrupted") << j.dump();
    EXPECT_NE(j["message"].get<std::string>().find(
                  fmt::format("{}: no reply for 10000 ms", proxy.address())),
              std::string::npos)
        << j.dump();
    if (!probing) {
      // The sender counts this run's stream; the message names the whole job's position too.
      const int64_t at = server.store().get(id)->resume_index;
      ASSERT_GE(at, 0) << j.dump();
      EXPECT_NE(
          j["message"].get<std::string>().find(fmt::format("the job is at job command {} of ", at)),
          std::string::npos)
          << j.dump();
    }
    EXPECT_GE(waited_s, 9.9);
    EXPECT_LT(waited_s, 14.0);
    std::printf("%s: link silent, the job ended %s %.1f s later: %s\n",
                probing ? "probing" : "cutting", j["state"].get<std::string>().c_str(), waited_s,
                j["message"].get<std::string>().c_str());
    proxy.freeze(false);
  }
}

// A machine killed while cutting (its socket closed; issue 25's outside tester got only
// "closed by the peer"): the message gives this run's counts and the whole job's position,
// as a silent link's does, and continue resumes there.
TEST(ServerLinkCut, AMachineKilledWhileCuttingSaysWhereTheJobStands) {
  test::TempDir dir;
  auto sim = std::make_unique<SimRig>(true);
  ServerRig server(dir.path(), {test::machine("m1", sim->address())});
  const int64_t id = server.upload_ok("multi.ngc", test::squares_gcode(3, 8), "&feed_mm_s=10");
  ASSERT_TRUE(test::wait_until([&] { return server.store().get(id)->resume_index >= 3; }, 60))
      << server.status().dump();
  sim->kill();
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] != "running"; }, 30));
  const JobRecord rec = *server.store().get(id);
  EXPECT_EQ(rec.state, JobState::kInterrupted) << rec.message;
  EXPECT_NE(rec.message.find(fmt::format("{}: closed by the peer after ", sim->address())),
            std::string::npos)
      << rec.message;
  EXPECT_NE(rec.message.find(" commands executed (counts of this run; the job is at job command "),
            std::string::npos)
      << rec.message;
  EXPECT_NE(rec.message.find(fmt::format("job command {} of ", rec.resume_index)),
            std::string::npos)
      << rec.message;
}

// The time left while long commands run and the link goes silent for a while (issue 25's
// outside tester: remaining_s climbed ~10 s a second inside one command, and through a
// silent link): sampled every 100 ms, it never rises while the same command runs.
TEST(ServerLinkCut, TheTimeLeftNeverRisesWithinACommandNorWhileTheLinkIsSilent) {
  test::TempDir dir;
  SimRig sim(true);
  FreezingProxy proxy(sim.port());
  ServerRig server(dir.path(), {test::machine("m1", proxy.address())}, 256 * 1024, {},
                   std::chrono::milliseconds(10000));
  // Sides of 75 and 55 mm at 10 mm/s: commands of 5.5 to 7.5 s.
  const std::string gcode =
      "G21\nG90\nG0 Z2\nG0 X5 Y5\nG1 Z-0.1 F100\nG1 X80 Y5 F600\nG1 X80 Y60\nG1 X5 Y60\n"
      "G1 X5 Y5\nG0 Z2\n";
  const int64_t id = server.upload_ok("long.ngc", gcode, "&feed_mm_s=10");
  ASSERT_TRUE(test::wait_until([&] { return cutting(server, id); }, 30)) << server.status().dump();
  std::vector<std::pair<int, double>> samples;  // executed, remaining_s
  for (int i = 0; i < 80; ++i) {
    if (i == 20) proxy.freeze(true);  // 2.5 s silent: the controller holds by its watchdog
    if (i == 45) proxy.freeze(false);
    const nlohmann::json p = server.running(id);
    if (!p.is_object()) break;
    samples.emplace_back(p["executed"].get<int>(), p["remaining_s"].get<double>());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_GE(samples.size(), 60u);
  size_t within = 0;
  for (size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].first != samples[i - 1].first) continue;
    ++within;
    EXPECT_LE(samples[i].second, samples[i - 1].second + 1e-6)
        << "sample " << i << " at executed " << samples[i].first;
  }
  EXPECT_GE(within, 50u);  // most samples inside one long command
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
}

// A continued run's time left starts from where it resumes (issue 25's outside tester: a
// job continued 39 % of the way showed nearly the whole job's planned time).
TEST(ServerLinkCut, AContinuedRunsTimeLeftIsThatOfWhatIsLeft) {
  test::TempDir dir;
  SimRig sim(true);
  int64_t id = 0;
  double planned_s = 0;
  {
    ServerRig server(dir.path(), {test::machine("m1", sim.address())});
    id = server.upload_ok("multi.ngc", test::squares_gcode(6, 8), "&feed_mm_s=10");
    planned_s = server.job(id)["planned_s"];
    ASSERT_TRUE(test::wait_until(
        [&] {
          const nlohmann::json p = server.running(id);
          return p.is_object() && p["executed"].get<int>() > 0 &&
                 p["executed"].get<int>() * 2 >= p["total"].get<int>();
        },
        60));
    server.shutdown();
    ASSERT_EQ(server.store().get(id)->state, JobState::kInterrupted);
  }
  ServerRig server(dir.path(), {test::machine("m1", sim.address())});
  ASSERT_EQ(server.control(id, R"({"action":"continue"})")->status, 200);
  // From the claim to the cut, sampled often: the machine is never shown idle (free) with
  // the job, and the run's total once known never falls back to 0 (the outside tester saw
  // both for a moment while the sender checked the zeroing).
  std::set<std::string> shown;
  size_t total_known = 0;
  bool total_lost = false;
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json status = server.status();
        const nlohmann::json& m = status["machines"][0];
        if (!m["job"].is_null()) shown.insert(m["state"].get<std::string>());
        for (const nlohmann::json& j : status["running"]) {
          if (j["id"] != id) continue;
          shown.insert("job " + j["machine_state"].get<std::string>());
          const size_t total = j["total"].get<size_t>();
          if (total_known > 0 && total == 0) total_lost = true;
          total_known = std::max(total_known, total);
        }
        return cutting(server, id);
      },
      30))
      << server.status().dump();
  EXPECT_EQ(shown.count("idle"), 0u) << ::testing::PrintToString(shown);
  EXPECT_EQ(shown.count("job idle"), 0u) << ::testing::PrintToString(shown);
  EXPECT_FALSE(total_lost);
  // Its first seconds of cutting too (the tester saw the whole job's time for 4 s, then a
  // pace measured from the job's start that made what was left look far shorter).
  for (int i = 0; i < 10; ++i) {
    const double left_s = server.running(id)["remaining_s"];
    EXPECT_GT(left_s, 0.1 * planned_s) << i;
    EXPECT_LT(left_s, 0.75 * planned_s) << i << ": planned " << planned_s;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_EQ(server.control(id, R"({"action":"abort"})")->status, 200);
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "aborted"; }, 30));
}

}  // namespace
}  // namespace host::server
