// What the server answers about a job (issue 25's workshop tester): every control action
// answers the job with `requested`, one shape; `height_map_job` says from the upload on
// whose height map a job cuts with; the map's machine file is served with the job's other
// files; probe_ready before a machine asks for the clip says why it is refused.
#include <gtest/gtest.h>

#include <set>  // std::set

#include "host_tests/host/server/blinky_upload.h"
#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::blinky;
using test::post;
using test::ServerRig;
using test::SimRig;

std::set<std::string> keys_of(const nlohmann::json& j) {
  std::set<std::string> keys;
  for (const auto& item : j.items()) keys.insert(item.key());
  return keys;
}

// 200 and the answer's JSON.
nlohmann::json control_ok(const ServerRig& server, int64_t id, const std::string& action) {
  auto r = server.control(id, fmt::format(R"({{"action":"{}"}})", action));
  if (!r || r->status != 200) {
    ADD_FAILURE() << action << ": " << (r ? r->body : std::string("no answer"));
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(r->body);
}

TEST(ServerJobAnswers, EveryControlActionAnswersTheJobWithWhatWasRequested) {
  test::TempDir dir;
  SimRig sim(true);  // real time: the job is still running when it is held
  ServerRig server(dir.path(), {test::machine("m", sim.address())});
  const int64_t running = server.upload_ok("long.ngc", test::square_gcode(10, 10, 60));
  const int64_t queued = server.upload_ok("next.ngc", test::square_gcode(10, 10, 10));
  ASSERT_TRUE(test::wait_until([&] { return server.running(running).is_object(); }, 20));
  std::vector<nlohmann::json> answers;
  for (const char* action : {"hold", "resume"})
    answers.push_back(control_ok(server, running, action));
  auto r = server.control(running, R"({"action":"override","percent":50})");
  ASSERT_TRUE(r && r->status == 200) << (r ? r->body : "");
  answers.push_back(nlohmann::json::parse(r->body));
  answers.push_back(control_ok(server, queued, "cancel"));
  answers.push_back(control_ok(server, running, "abort"));
  const nlohmann::json listed = server.jobs().at(0);
  std::set<std::string> expected = keys_of(listed);
  expected.insert("requested");
  const char* const requested[] = {"hold", "resume", "override", "cancel", "abort"};
  for (size_t i = 0; i < answers.size(); ++i) {
    EXPECT_EQ(keys_of(answers[i]), expected) << answers[i].dump();
    EXPECT_EQ(answers[i]["requested"], requested[i]) << answers[i].dump();
  }
  EXPECT_EQ(answers[0]["id"], running);
  EXPECT_EQ(answers[3]["id"], queued);
  EXPECT_EQ(answers[3]["state"], "cancelled");  // a store action is done when it answers
  ASSERT_TRUE(test::wait_until([&] { return server.job(running)["state"] == "aborted"; }, 20));
  // The same shape for requeue.
  const nlohmann::json requeued = control_ok(server, running, "requeue");
  EXPECT_EQ(keys_of(requeued), expected) << requeued.dump();
  EXPECT_EQ(requeued["requested"], "requeue");
}

// A bottom side says it will cut with the top side's map from its upload's answer on, while
// it waits; the top side names itself; a board without a map and a drawing say null.
TEST(ServerJobAnswers, TheMapAJobCutsWithIsKnownFromItsUpload) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});  // no machine: every job stays queued
  const int64_t drawing = server.upload_ok("line.ngc", "G0 X0 Y0\nG1 X10 Y0 F100\n");
  const int64_t plain = post(server, blinky({}));
  auto top_answer = server.client().Post("/api/jobs", server.auth(),
                                         blinky({{"probe_first", "1"}, {"align_holes", "auto"}}));
  ASSERT_TRUE(top_answer && top_answer->status == 201);
  const nlohmann::json top = nlohmann::json::parse(top_answer->body);
  const int64_t top_id = top["id"];
  auto bottom_answer = server.client().Post("/api/jobs", server.auth(),
                                            blinky({{"side", "bottom"},
                                                    {"align_holes", "auto"},
                                                    {"height_map_from", std::to_string(top_id)}},
                                                   "blinky-B.Cu.gbr"));
  ASSERT_TRUE(bottom_answer && bottom_answer->status == 201);
  const nlohmann::json bottom = nlohmann::json::parse(bottom_answer->body);
  const int64_t bottom_id = bottom["id"];
  EXPECT_EQ(top["height_map_job"], top_id) << top.dump();
  EXPECT_EQ(bottom["height_map_job"], top_id) << bottom.dump();
  // The map is not made yet: height_map (the archive holds it) stays false until it is.
  EXPECT_EQ(bottom["height_map"], false);
  EXPECT_EQ(bottom["waiting"], fmt::format("waiting for the height map of job {}", top_id));
  EXPECT_EQ(server.job(bottom_id)["height_map_job"], top_id);
  EXPECT_EQ(server.job(top_id)["height_map_job"], top_id);
  EXPECT_TRUE(server.job(plain)["height_map_job"].is_null());
  EXPECT_TRUE(server.job(drawing)["height_map_job"].is_null());
  for (const nlohmann::json& j : server.jobs()) {
    const int64_t id = j["id"];
    EXPECT_EQ(j["height_map_job"], server.job(id)["height_map_job"]) << id;
  }
  // No machine will ask for the clip for a job that probes nothing (issue 25's tester: the
  // 409 said to wait for probe_clip, which never comes).
  for (const int64_t id : {bottom_id, drawing, plain}) {
    auto r = server.control(id, R"({"action":"probe_ready"})");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 409);
    EXPECT_EQ(nlohmann::json::parse(r->body)["error"],
              fmt::format("job {} is queued: {}: no machine asks for the probe clip, send no "
                          "probe_ready",
                          id,
                          id == drawing ? std::string("a drawing probes nothing")
                          : id == plain
                              ? std::string("a board uploaded without probe_first=1 probes nothing")
                              : fmt::format("it cuts with job {}'s height map and "
                                            "probes nothing",
                                            top_id)));
  }
}

// probe_ready says why no machine takes it, and when to send it; once a machine asks for
// the clip it is taken; the map's machine file is then served with the job's files.
TEST(ServerJobAnswers, ProbeReadyBeforeTheClipIsAskedForSaysWhyAndTheMapsMachineIsServed) {
  test::TempDir dir;
  sim::SimOptions blank;
  blank.surface_um = [](int32_t x_um, int32_t) { return x_um / 500; };
  SimRig sim(false, 0, blank);
  const int64_t id = [&] {
    ServerRig queue_only(dir.path(), {});  // no machine yet: the job stays queued
    const int64_t top =
        post(queue_only, blinky({{"probe_first", "1"}, {"probe_spacing_mm", "12"}}));
    auto r = queue_only.control(top, R"({"action":"probe_ready"})");
    EXPECT_TRUE(r);
    if (r) {
      EXPECT_EQ(r->status, 409) << r->body;
      EXPECT_EQ(nlohmann::json::parse(r->body)["error"],
                fmt::format("job {} is queued: no machine is waiting for its probe clip: no "
                            "machine has claimed it yet (send probe_ready once the job's "
                            "machine_state in /api/status is probe_clip)",
                            top));
    }
    return top;
  }();
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json j = server.running(id);
        return j.is_object() && j["machine_state"] == "probe_clip";
      },
      30));
  EXPECT_EQ(control_ok(server, id, "probe_ready")["requested"], "probe_ready");
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "completed"; }, 120))
      << server.job(id).dump();
  auto machine =
      server.client().Get(fmt::format("/api/jobs/{}/files/heightmap.machine", id).c_str());
  ASSERT_TRUE(machine);
  EXPECT_EQ(machine->status, 200) << machine->body;
  EXPECT_EQ(machine->body, "mill");
  EXPECT_EQ(machine->get_header_value("Content-Type"), "text/plain");
  auto again = server.control(id, R"({"action":"probe_ready"})");
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 409);
  EXPECT_NE(
      again->body.find(fmt::format(
          "job {} is completed: no machine is waiting for its probe clip: the job has ended", id)),
      std::string::npos)
      << again->body;
}

// The error of a request that must answer 409.
std::string refused(const httplib::Result& r) {
  if (!r) return "no answer";
  if (r->status != 409) return fmt::format("{} (not 409): {}", r->status, r->body);
  return nlohmann::json::parse(r->body)["error"].get<std::string>();
}

std::string refused(const ServerRig& server, int64_t id, const std::string& action) {
  const std::string body = action == "override"
                               ? std::string(R"({"action":"override","percent":50})")
                               : fmt::format(R"({{"action":"{}"}})", action);
  return refused(server.control(id, body));
}

// An action that cannot apply in the job's state answers 409 naming that state (issue 25's
// tester: resume of a queued job answered 200, a no-op that looked done; a failed job's 409
// did not say it had failed), for each action the job's state rules out.
TEST(ServerJobAnswers, AnActionThatCannotApplyAnswers409NamingTheJobsState) {
  test::TempDir queue_dir;
  {
    ServerRig server(queue_dir.path(), {});  // no machine: the job stays queued
    const int64_t id = server.upload_ok("line.ngc", "G0 X0 Y0\nG1 X10 Y0 F100\n");
    for (const char* action : {"hold", "resume", "abort", "override"}) {
      EXPECT_EQ(refused(server, id, action),
                fmt::format("job {} is queued: {} applies to a running job only", id, action));
    }
    EXPECT_EQ(refused(server, id, "requeue"),
              fmt::format("job {} is queued: only an interrupted, aborted or failed job can be "
                          "re-queued",
                          id));
    EXPECT_EQ(refused(server, id, "continue"),
              fmt::format("job {} is queued: only an interrupted job with a known curve can be "
                          "continued",
                          id));
    EXPECT_EQ(server.job(id)["state"], "queued");
    EXPECT_EQ(control_ok(server, id, "cancel")["state"], "cancelled");
    EXPECT_EQ(refused(server, id, "cancel"),
              fmt::format("job {} is cancelled: only a queued job can be cancelled", id));
    EXPECT_EQ(refused(server, id, "resume"),
              fmt::format("job {} is cancelled: resume applies to a running job only", id));
    EXPECT_EQ(refused(server.client().Post(fmt::format("/api/jobs/{}/priority", id).c_str(),
                                           server.auth(), R"({"priority":3})", "application/json")),
              fmt::format("job {} is cancelled: only a queued job's priority can change", id));
  }
  // A failed job: probe first on a simulated machine with no blank (`engraver sim` without
  // --surface), whose probe never closes.
  test::TempDir dir;
  SimRig sim(false);
  ServerRig server(dir.path(), {test::machine("mill", sim.address())});
  const int64_t id = post(server, blinky({{"probe_first", "1"}, {"probe_spacing_mm", "12"}}));
  ASSERT_TRUE(
      test::wait_until([&] { return server.running(id)["machine_state"] == "probe_clip"; }, 30));
  EXPECT_EQ(control_ok(server, id, "probe_ready")["requested"], "probe_ready");
  ASSERT_TRUE(test::wait_until([&] { return server.job(id)["state"] == "failed"; }, 60))
      << server.job(id).dump();
  const std::string message = server.job(id)["message"];
  EXPECT_EQ(message.rfind("height map: probing at (", 0), 0u) << message;
  EXPECT_NE(message.find(" mm: alarm: machine alarm: probe: no contact within the depth limit; "
                         "nothing was cut"),
            std::string::npos)
      << message;
  for (const char* action : {"hold", "resume", "abort", "override"}) {
    EXPECT_EQ(refused(server, id, action),
              fmt::format("job {} is failed: {} applies to a running job only", id, action));
  }
  EXPECT_EQ(refused(server, id, "cancel"),
            fmt::format("job {} is failed: only a queued job can be cancelled", id));
  EXPECT_EQ(refused(server, id, "continue"),
            fmt::format("job {} is failed: only an interrupted job with a known curve can be "
                        "continued",
                        id));
  EXPECT_EQ(refused(server, id, "probe_ready"),
            fmt::format("job {} is failed: no machine is waiting for its probe clip: the job has "
                        "ended",
                        id));
  EXPECT_EQ(control_ok(server, id, "requeue")["state"], "queued");
}

}  // namespace
}  // namespace host::server
