// The HTTP API on loopback: jobs spread over free simulated machines, a restart keeps the
// queue, and bad requests are refused with a reason and store nothing.
#include <gtest/gtest.h>

#include <map>  // std::map
#include <set>  // std::set

#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

using test::ServerRig;
using test::SimRig;
namespace fs = std::filesystem;

size_t files_under(const fs::path& dir) {
  size_t n = 0;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    if (it->is_regular_file()) ++n;
  }
  return n;
}

TEST(ServerApi, JobsSpreadOverFreeMachinesAndLandInTheArchive) {
  test::TempDir dir;
  std::vector<std::unique_ptr<SimRig>> sims;
  std::vector<MachineSpec> machines;
  for (int i = 0; i < 3; ++i) {
    sims.push_back(std::make_unique<SimRig>(false));
    machines.push_back(test::machine(fmt::format("m{}", i + 1), sims.back()->address()));
  }
  ServerRig server(dir.path(), machines);
  ASSERT_TRUE(test::wait_until(
      [&] {
        const nlohmann::json status_now = server.status();  // kept alive for the loop
        for (const auto& m : status_now["machines"]) {
          if (m["link"] != "online") return false;
        }
        return true;
      },
      10));
  std::vector<int64_t> ids;
  for (int i = 0; i < 9; ++i) {
    // Slow enough (2 mm/s) that one machine cannot take them all before the others start.
    ids.push_back(server.upload_ok(fmt::format("square{}.ngc", i), test::square_gcode(10, 10, 20),
                                   "&feed_mm_s=2"));
  }
  ASSERT_TRUE(test::wait_until(
      [&] {
        for (int64_t id : ids) {
          if (server.job(id)["state"] != "completed") return false;
        }
        return true;
      },
      90));
  std::map<std::string, int> per_machine;
  for (int64_t id : ids) {
    const nlohmann::json j = server.job(id);
    ++per_machine[j["machine"].get<std::string>()];
    EXPECT_EQ(j["executed"], j["total"]);
    // The archive: input, plan, plot, report and machine log, served by the API.
    for (const char* f : {"input.ngc", "plan.json", "plot.svg", "plot.png", "machine.log"}) {
      auto r = server.client().Get(fmt::format("/api/jobs/{}/files/{}", id, f).c_str());
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 200) << f;
      EXPECT_FALSE(r->body.empty()) << f;
    }
    auto report = server.client().Get(fmt::format("/api/jobs/{}/files/report.json", id).c_str());
    ASSERT_TRUE(report && report->status == 200);
    const nlohmann::json rep = nlohmann::json::parse(report->body);
    EXPECT_EQ(rep["state"], "completed");
    EXPECT_EQ(rep["machine"], j["machine"]);
  }
  EXPECT_EQ(per_machine.size(), 3u) << "every free machine should have taken jobs";
  // The simulated machines really cut: each one's trace left its zero corner.
  for (const auto& sim : sims) EXPECT_GT(sim->machine().trace().size(), 100u);
}

TEST(ServerApi, PriorityDecidesWhichQueuedJobRunsFirst) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});  // no machine yet: everything stays queued
  const int64_t low = server.upload_ok("low.ngc", test::square_gcode(10, 10, 10));
  const int64_t high = server.upload_ok("high.ngc", test::square_gcode(10, 10, 10), "&priority=5");
  auto r = server.client().Post(fmt::format("/api/jobs/{}/priority", low).c_str(), server.auth(),
                                R"({"priority": 9})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  const auto first =
      server.store().claim(MachineFit{}, "m", server.store().acquire_lease("x", "h", 30000));
  ASSERT_TRUE(first);
  EXPECT_EQ(first->id, low);
  EXPECT_EQ(server.job(high)["state"], "queued");
  // Cancel the queued one; cancelled jobs do not run.
  r = server.control(high, R"({"action": "cancel"})");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(server.job(high)["state"], "cancelled");
  EXPECT_FALSE(
      server.store().claim(MachineFit{}, "m", server.store().acquire_lease("x", "h", 30000)));
}

TEST(ServerApi, RestartKeepsQueuedJobsAndRunningOnesBecomeInterrupted) {
  test::TempDir dir;
  int64_t running = 0;
  std::vector<int64_t> queued;
  {
    SimRig slow(true);  // real time: the first job is still running when the server stops
    ServerRig server(dir.path(), {test::machine("m1", slow.address())});
    running = server.upload_ok("long.ngc", test::square_gcode(10, 10, 60), "&feed_mm_s=5");
    ASSERT_TRUE(test::wait_until([&] { return server.job(running)["state"] == "running"; }, 10));
    for (int i = 0; i < 3; ++i) {
      // The only machine is busy: they stay queued.
      queued.push_back(server.upload_ok(fmt::format("q{}.ngc", i), test::square_gcode(10, 10, 10)));
    }
  }  // server stops (aborting the running job), then the machine
  SimRig fast(false);
  ServerRig server(dir.path(), {test::machine("m2", fast.address())});
  const nlohmann::json r = server.job(running);
  EXPECT_EQ(r["state"], "interrupted");
  EXPECT_LT(r["executed"].get<int>(), r["total"].get<int>());
  EXPECT_GE(r["resume_curve"].get<int>(), 0);
  // Said as it happened: the server stopped; no operator aborted anything.
  EXPECT_NE(r["message"].get<std::string>().find("the server stopped"), std::string::npos) << r;
  auto log = server.client().Get(fmt::format("/api/jobs/{}/files/machine.log", running).c_str());
  ASSERT_TRUE(log && log->status == 200);
  EXPECT_NE(log->body.find("server stopped"), std::string::npos) << log->body;
  EXPECT_EQ(log->body.find("operator"), std::string::npos) << log->body;
  ASSERT_TRUE(test::wait_until(
      [&] {
        for (int64_t id : queued) {
          if (server.job(id)["state"] != "completed") return false;
        }
        return true;
      },
      60));
  // Re-queued, the interrupted job runs from the start on the machine there is now.
  auto c = server.control(running, R"({"action": "requeue"})");
  ASSERT_TRUE(c);
  EXPECT_EQ(c->status, 200) << c->body;
  EXPECT_TRUE(test::wait_until([&] { return server.job(running)["state"] == "completed"; }, 60));
}

TEST(ServerApi, BadRequestsAreRefusedWithAReasonAndStoreNothing) {
  test::TempDir dir;
  ServerRig server(dir.path(), {}, 4096);
  const std::string good = test::square_gcode(10, 10, 10);
  auto client = server.client();
  const fs::path jobs = dir.path() / "jobs";
  auto refused = [&](const httplib::Result& r, int status, const std::string& needle) {
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, status) << r->body;
    const nlohmann::json body = nlohmann::json::parse(r->body, nullptr, false);
    ASSERT_TRUE(body.is_object()) << r->body;
    EXPECT_NE(body.value("error", "").find(needle), std::string::npos) << r->body;
  };

  // No token, a wrong token, a token of the right length but wrong.
  refused(client.Post("/api/jobs?name=a.ngc", good, "application/octet-stream"), 401, "token");
  refused(client.Post("/api/jobs?name=a.ngc", {{"Authorization", "Bearer nope"}}, good,
                      "application/octet-stream"),
          401, "token");
  std::string wrong = server.token();
  wrong[0] = wrong[0] == 'a' ? 'b' : 'a';
  refused(
      client.Post("/api/jobs?name=a.ngc", {{"X-Token", wrong}}, good, "application/octet-stream"),
      401, "token");
  // Larger than the limit (4 KB here).
  std::string big = good;
  while (big.size() < 80 * 1024) big += "G1 X11 Y11\n";
  auto r = server.upload("big.ngc", big);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  std::string medium = good;
  while (medium.size() < 5000) medium += "(comment)\n";
  refused(server.upload("medium.ngc", medium), 413, "limit");
  // Names that try to leave the archive folder.
  for (const char* name : {"../../token", "../evil.ngc", "sub/dir.ngc", "..\\evil.ngc",
                           ".hidden.ngc", "/etc/passwd"}) {
    refused(server.upload(name, good), 400, "file name");
  }
  // Not a drawing; a drawing outside the work area (the planner's message).
  refused(server.upload("notes.txt", "Remember to buy milk.\n"), 422, "notes.txt");
  refused(server.upload("image.dxf", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)), 422,
          "image.dxf");
  refused(server.upload("empty.ngc", ""), 422, "empty.ngc");
  refused(server.upload("huge.ngc", test::square_gcode(0, 0, 400)), 422, "huge.ngc");
  // Bad settings and fields.
  refused(server.upload("a.ngc", good, "&feed_mm_s=abc"), 400, "feed_mm_s");
  refused(server.upload("a.ngc", good, "&feed_mm_s=1000"), 400, "feed_mm_s");
  refused(server.upload("a.ngc", good, "&priority=1e9"), 400, "priority");
  refused(server.upload("a.ngc", good, "&tag=../x"), 400, "tag");
  // A misspelt field is refused by its name, not ignored (raw upload and multipart form).
  refused(server.upload("a.ngc", good, "&priorty=5"), 400, "unknown field 'priorty'");
  httplib::MultipartFormDataItems form = {{"file", good, "a.ngc", "application/octet-stream"},
                                          {"feedrate", "5", "", ""}};
  refused(client.Post("/api/jobs", server.auth(), form), 400, "unknown field 'feedrate'");
  refused(client.Post("/api/jobs", server.auth(), good, "application/octet-stream"), 400, "name");

  EXPECT_TRUE(server.jobs().empty());
  EXPECT_EQ(files_under(jobs), 0u);
  EXPECT_EQ(files_under(dir.path() / "tmp"), 0u);

  // Controls: malformed JSON, wrong shapes, unknown actions, unknown jobs.
  const int64_t id = server.upload_ok("ok.ngc", good);
  const size_t files = files_under(jobs);
  refused(server.control(id, "{\"action\": "), 400, "malformed JSON");
  // Plain words, not the JSON library's internals.
  for (const std::string& bad :
       {std::string("{\"action\": "), std::string("{action: hold}"), std::string("")}) {
    auto c = server.control(id, bad);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->body.find("json.exception"), std::string::npos) << c->body;
    EXPECT_EQ(c->body.find("last read"), std::string::npos) << c->body;
  }
  refused(server.control(id, "{action: hold}"), 400, "unexpected text at byte 2: 'action: hold}'");
  refused(server.control(id, "{\"action\": "), 400, "ends before");
  // Anything after the object, a NUL byte included, refuses the whole request.
  refused(server.control(id, std::string("{\"action\": \"cancel\"}\0garbage", 28)), 400,
          "NUL byte at byte 21");
  refused(server.control(id, R"({"action": "cancel"} garbage)"), 400, "byte 22");
  refused(server.control(id, "[1, 2]"), 400, "object");
  refused(server.control(id, R"({"action": 3})"), 400, "action");
  refused(server.control(id, R"({"action": "explode"})"), 400, "explode");
  refused(server.control(id, R"({"action": "override", "percent": 500})"), 400, "percent");
  refused(server.control(id, R"({"action": "override", "percent": "fast"})"), 400, "percent");
  refused(server.control(999, R"({"action": "hold"})"), 404, "no such job");
  refused(server.control(id, R"({"action": "hold"})"), 409,
          "job 1 is queued: hold applies to a running job only");
  refused(server.control(id, R"({"action": "requeue"})"), 409, "re-queued");
  refused(client.Post(fmt::format("/api/jobs/{}/priority", id).c_str(), server.auth(),
                      R"({"priority": "high"})", "application/json"),
          400, "priority");
  refused(client.Post(fmt::format("/api/jobs/{}/control", id).c_str(), R"({"action": "cancel"})",
                      "application/json"),
          401, "token");
  EXPECT_EQ(server.job(id)["state"], "queued");
  EXPECT_EQ(server.job(id)["priority"], 0);
  EXPECT_EQ(server.jobs().size(), 1u);
  EXPECT_EQ(files_under(jobs), files);
  // Archive files: only the fixed names; nothing outside the job's folder.
  for (const char* path : {"/api/jobs/1/files/..%2F..%2Ftoken", "/api/jobs/1/files/token",
                           "/api/jobs/1/files/../../token", "/api/jobs/1/files/jobs.sqlite"}) {
    auto g = client.Get(path);
    ASSERT_TRUE(g);
    EXPECT_EQ(g->status, 404) << path;
    EXPECT_EQ(g->body.find(server.token()), std::string::npos) << path;
  }
}

TEST(ServerApi, MultipartUploadLikeThePageAndThePageFiles) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  httplib::MultipartFormDataItems form = {
      {"file", test::square_gcode(10, 10, 10), "Board (v2).ngc", "application/octet-stream"},
      {"priority", "4", "", ""},
      {"feed_mm_s", "7.5", "", ""}};
  auto r = server.client().Post("/api/jobs", server.auth(), form);
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const nlohmann::json j = nlohmann::json::parse(r->body);
  EXPECT_EQ(j["name"], "Board (v2).ngc");
  EXPECT_EQ(j["priority"], 4);
  EXPECT_DOUBLE_EQ(j["feed_mm_s"].get<double>(), 7.5);
  EXPECT_EQ(j["input_file"], "input.ngc");
  for (const char* page : {"/", "/app.js", "/style.css"}) {
    auto g = server.client().Get(page);
    ASSERT_TRUE(g);
    EXPECT_EQ(g->status, 200) << page;
    EXPECT_GT(g->body.size(), 100u) << page;
  }
}

TEST(ServerApi, EventStreamSendsTheStateAtOnceAndAgainWhenAJobIsQueued) {
  test::TempDir dir;
  ServerRig server(dir.path(), {test::machine("m1", "tcp://127.0.0.1:1")});
  std::vector<nlohmann::json> events;
  std::string buffer;
  std::atomic<bool> uploaded{false};
  std::thread uploader;
  auto client = server.client();
  // The receiver returns false to close the stream once the second event arrived.
  client.Get("/api/events", [&](const char* data, size_t size) {
    buffer.append(data, size);
    for (size_t end = buffer.find("\n\n"); end != std::string::npos; end = buffer.find("\n\n")) {
      const std::string event = buffer.substr(0, end);
      buffer.erase(0, end + 2);
      if (event.rfind("data: ", 0) == 0) events.push_back(nlohmann::json::parse(event.substr(6)));
    }
    if (events.size() == 1 && !uploaded.exchange(true)) {
      uploader = std::thread([&] { server.upload_ok("a.ngc", test::square_gcode(5, 5, 5)); });
    }
    return events.size() < 2 || events.back()["jobs_version"] == events.front()["jobs_version"];
  });
  if (uploader.joinable()) uploader.join();
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.front()["machines"][0]["name"], "m1");
  EXPECT_NE(events.back()["jobs_version"], events.front()["jobs_version"]);
}

}  // namespace
}  // namespace host::server

namespace host::server {
namespace {

// A field or key given twice, a control key the server does not know, a field in the query
// of a form upload: refused by name (400), nothing queued or changed.
TEST(ServerApi, DuplicateAndUnknownFieldsAndKeysAreRefusedByName) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  auto client = server.client();
  auto refused = [&](const httplib::Result& r, const std::string& needle) {
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 400) << r->body;
    EXPECT_NE(r->body.find(needle), std::string::npos) << r->body;
  };
  const std::string good = test::square_gcode(10, 10, 10);
  refused(server.upload("a.ngc", good, "&priority=1&priority=5"),
          "field 'priority' given more than once");
  refused(server.upload("a.ngc", good, "&name=b.ngc"), "field 'name' given more than once");
  // The same value twice is a repeat too (httplib's parameters keep it once), and "=1" has no
  // name (httplib named it "1"); a form's one file names its job: a `name` part is refused.
  refused(server.upload("a.ngc", good, "&priority=1&priority=1"),
          "field 'priority' given more than once");
  refused(server.upload("a.ngc", good, "&=1"), "a query field without a name");
  httplib::MultipartFormDataItems named = {{"file", good, "a.ngc", "application/octet-stream"},
                                           {"name", "zzz.ngc", "", ""}};
  refused(client.Post("/api/jobs", server.auth(), named),
          "field 'name' in a form upload of one file");
  refused(server.upload("a.ngc", good, "&file=x"), "field 'file' in the query");
  httplib::MultipartFormDataItems twice = {{"file", good, "a.ngc", "application/octet-stream"},
                                           {"priority", "1", "", ""},
                                           {"priority", "5", "", ""}};
  refused(client.Post("/api/jobs", server.auth(), twice), "field 'priority' given more than once");
  httplib::MultipartFormDataItems form = {{"file", good, "a.ngc", "application/octet-stream"}};
  refused(client.Post("/api/jobs?priority=5", server.auth(), form),
          "field 'priority' in the query of a form upload");
  EXPECT_TRUE(server.jobs().empty());

  const int64_t id = server.upload_ok("ok.ngc", good);
  refused(server.control(id, R"({"action": "cancel", "action": "hold"})"),
          "key 'action' given more than once");
  refused(server.control(id, R"({"action": "cancel", "force": true})"),
          "unknown key 'force' (this request takes action, percent)");
  refused(server.control(id, R"({"action": "cancel", "percent": 50})"),
          "percent goes with the override action only");
  refused(server.control(id, R"({"action": "override", "percnet": 50})"), "unknown key 'percnet'");
  refused(client.Post(fmt::format("/api/jobs/{}/priority", id).c_str(), server.auth(),
                      R"({"priority": 1, "priority": 9})", "application/json"),
          "key 'priority' given more than once");
  refused(client.Post(fmt::format("/api/jobs/{}/priority", id).c_str(), server.auth(),
                      R"({"priority": 1, "when": "now"})", "application/json"),
          "unknown key 'when'");
  // Nested objects may repeat keys of the top level: only the request's own keys count.
  refused(server.control(id, R"({"action": "cancel", "x": {"action": 1}})"), "unknown key 'x'");
  const nlohmann::json job = server.job(id);
  EXPECT_EQ(job["state"], "queued");
  EXPECT_EQ(job["priority"], 0);
  // A clean request still works.
  auto ok = server.control(id, R"({"action": "cancel"})");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
}

// A known path asked with a method it does not take answers 405 with Allow (before the
// token is asked for); an unknown path stays 404 (401 without the token).
TEST(ServerApi, WrongMethodsOnKnownPathsAnswer405WithAllow) {
  test::TempDir dir;
  ServerRig server(dir.path(), {});
  const int64_t id = server.upload_ok("ok.ngc", test::square_gcode(10, 10, 10));
  httplib::Client client("127.0.0.1", server.port());
  client.set_read_timeout(10, 0);
  struct Case {
    const char* method;
    std::string path;
    const char* allow;
  };
  const std::string job = fmt::format("/api/jobs/{}", id);
  const Case cases[] = {{"DELETE", "/api/status", "GET, HEAD"},
                        {"POST", "/api/status", "GET, HEAD"},
                        {"PUT", "/", "GET, HEAD"},
                        {"DELETE", "/api/jobs", "GET, HEAD, POST"},
                        {"DELETE", job, "GET, HEAD"},
                        {"PATCH", job + "/files/plot.svg", "GET, HEAD"},
                        {"POST", job + "/path", "GET, HEAD"},
                        {"GET", job + "/control", "POST"},
                        {"PUT", job + "/priority", "POST"},
                        {"OPTIONS", "/api/events", "GET, HEAD"}};
  for (const Case& c : cases) {
    httplib::Request req;
    req.method = c.method;
    req.path = c.path;
    auto r = client.send(req);
    ASSERT_TRUE(r) << c.method << " " << c.path;
    EXPECT_EQ(r->status, 405) << c.method << " " << c.path << ": " << r->body;
    EXPECT_EQ(r->get_header_value("Allow"), c.allow) << c.method << " " << c.path;
    EXPECT_NE(r->body.find(c.allow), std::string::npos) << r->body;
  }
  auto r = client.Get("/api/nothing");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(server.job(id)["state"], "queued");
}

}  // namespace
}  // namespace host::server
