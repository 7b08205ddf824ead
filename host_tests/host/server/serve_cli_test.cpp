// `engraver serve` as a process: starts with its defaults on a fresh data folder, shows the
// token once, serves the page, stops on SIGTERM; refuses bad options with exit code 2.
#include <gtest/gtest.h>

#include <signal.h>    // kill
#include <sys/wait.h>  // waitpid
#include <unistd.h>    // fork, execv

#include <fstream>  // std::ifstream
#include <sstream>  // std::ostringstream

#include "host/lib/server/job_planning.h"
#include "host/lib/sim/sim_job.h"
#include "host_tests/host/server/server_test_rig.h"
#include "host_tests/host/sim/cut_path.h"

namespace host::server {
namespace {

namespace fs = std::filesystem;

// Runs the tool in the background with stderr to a file; stop() sends SIGTERM and waits.
class ServeProcess {
 public:
  ServeProcess(const std::vector<std::string>& args, const fs::path& log) {
    pid_ = fork();
    if (pid_ == 0) {
      FILE* f = std::freopen(log.c_str(), "w", stderr);
      (void)f;
      std::vector<char*> argv;
      std::string exe = ENGRAVER_EXE;
      argv.push_back(&exe[0]);
      std::vector<std::string> copy = args;
      for (std::string& a : copy) argv.push_back(&a[0]);
      argv.push_back(nullptr);
      execv(exe.c_str(), argv.data());
      _exit(127);
    }
  }
  ~ServeProcess() { stop(); }
  // The exit status (-1 when it had to be killed).
  int stop() {
    if (pid_ <= 0) return status_;
    kill(pid_, SIGTERM);
    for (int i = 0; i < 200; ++i) {
      int st = 0;
      if (waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = 0;
        status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
        return status_;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = 0;
    return status_ = -1;
  }
  // kill -9: the server dies mid-whatever, as in a crash.
  void crash() {
    if (pid_ <= 0) return;
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = 0;
  }
  // Waits up to `limit` for the process to end by itself: its exit status, or -2 (then it
  // is stopped).
  int wait_exit_within(std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      int st = 0;
      if (waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = 0;
        return status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    stop();
    return -2;
  }
  // Waits for the process to end by itself; its exit status.
  int wait_exit() {
    int st = 0;
    waitpid(pid_, &st, 0);
    pid_ = 0;
    return status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
};

std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ServeCommand, StartsOnAFreshFolderShowsTheTokenOnceAndStopsCleanly) {
  test::TempDir dir;
  const fs::path data = dir.path() / "data";
  const std::string port = std::to_string(test::free_port());
  for (int run = 0; run < 2; ++run) {
    const fs::path log = dir.path() / ("serve" + std::to_string(run) + ".log");
    ServeProcess serve({"serve", "--data", data.string(), "--listen", "127.0.0.1:" + port}, log);
    httplib::Client client("127.0.0.1", std::stoi(port));
    ASSERT_TRUE(test::wait_until(
        [&] {
          auto r = client.Get("/");
          return r && r->status == 200;
        },
        20))
        << text_of(log);
    auto page = client.Get("/");
    EXPECT_NE(page->body.find("Engraver workshop"), std::string::npos);
    EXPECT_EQ(serve.stop(), 0) << text_of(log);
    const std::string token = text_of(data / "token");
    ASSERT_GE(token.size(), 32u);
    const std::string out = text_of(log);
    // The token is printed on the first start only.
    if (run == 0) {
      EXPECT_NE(out.find(token.substr(0, 32)), std::string::npos) << out;
    } else {
      EXPECT_EQ(out.find(token.substr(0, 32)), std::string::npos) << out;
    }
    EXPECT_EQ(fs::status(data / "token").permissions() & fs::perms::others_read, fs::perms::none);
  }
}

TEST(ServeCommand, BadOptionsAreUsageErrors) {
  test::TempDir dir;
  const std::vector<std::vector<std::string>> bad = {
      {"serve", "--data", (dir.path() / "d").string(), "--machine", "ftp://x"},
      {"serve", "--data", (dir.path() / "d").string(), "--machine", "tcp://h:1 colour=red"},
      {"serve", "--data", (dir.path() / "d").string(), "--listen", "nowhere"},
      {"serve", "--data", (dir.path() / "d").string(), "--max-upload-mb", "0"}};
  for (const auto& args : bad) {
    ServeProcess p(args, dir.path() / "bad.log");
    EXPECT_EQ(p.wait_exit(), 2) << args.back() << ": " << text_of(dir.path() / "bad.log");
  }
}

bool answers(int port) {
  httplib::Client client("127.0.0.1", port);
  auto r = client.Get("/api/status");
  return r && r->status == 200;
}

TEST(ServeCommand, ASecondServerOnOneDataFolderIsRefusedAndACrashedOneRestarts) {
  test::TempDir dir;
  const fs::path data = dir.path() / "data";
  const int port = test::free_port();
  auto first = std::make_unique<ServeProcess>(
      std::vector<std::string>{"serve", "--data", data.string(), "--listen",
                               "127.0.0.1:" + std::to_string(port)},
      dir.path() / "first.log");
  ASSERT_TRUE(test::wait_until([&] { return answers(port); }, 20))
      << text_of(dir.path() / "first.log");

  ServeProcess second({"serve", "--data", data.string(), "--listen",
                       "127.0.0.1:" + std::to_string(test::free_port())},
                      dir.path() / "second.log");
  EXPECT_EQ(second.wait_exit_within(std::chrono::seconds(20)), 1);
  const std::string said = text_of(dir.path() / "second.log");
  EXPECT_NE(said.find("another engraver serve uses this data folder (pid "), std::string::npos)
      << said;
  EXPECT_TRUE(answers(port));  // the first one goes on

  first->crash();  // kill -9: the lock goes with the process
  ServeProcess third(
      {"serve", "--data", data.string(), "--listen", "127.0.0.1:" + std::to_string(port)},
      dir.path() / "third.log");
  EXPECT_TRUE(test::wait_until([&] { return answers(port); }, 20))
      << text_of(dir.path() / "third.log");
  EXPECT_EQ(third.stop(), 0);
}

// kill -9 of the server mid-job: its restart marks the job interrupted, "continue" is taken
// (the position was saved while it ran) and the machine, which still holds the job, goes on
// where it stopped: the cut path is that of an uninterrupted run, nothing skipped or cut twice.
TEST(ServeCommand, AfterAKilledServerContinueFinishesTheJobCuttingNothingTwice) {
  test::TempDir dir;
  const fs::path data = dir.path() / "data";
  test::SimRig sim(true);
  const int port = test::free_port();
  const std::vector<std::string> args = {"serve",
                                         "--data",
                                         data.string(),
                                         "--listen",
                                         "127.0.0.1:" + std::to_string(port),
                                         "--machine",
                                         sim.address() + " name=m1",
                                         "--poll-ms",
                                         "20"};
  auto server = std::make_unique<ServeProcess>(args, dir.path() / "serve1.log");
  ASSERT_TRUE(test::wait_until([&] { return answers(port); }, 20));
  const std::string token = text_of(data / "token").substr(0, 48);
  httplib::Client client("127.0.0.1", port);
  client.set_read_timeout(10, 0);
  const httplib::Headers auth = {{"Authorization", "Bearer " + token}};
  auto up = client.Post("/api/jobs?name=multi.ngc&feed_mm_s=10", auth, test::squares_gcode(3, 8),
                        "application/octet-stream");
  ASSERT_TRUE(up && up->status == 201) << (up ? up->body : "no answer");
  const int64_t id = nlohmann::json::parse(up->body)["id"].get<int64_t>();
  auto job = [&] {
    auto r = client.Get(fmt::format("/api/jobs/{}", id).c_str());
    return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json();
  };
  // Well into the second of three squares.
  ASSERT_TRUE(test::wait_until(
      [&] {
        auto r = client.Get("/api/status");
        if (!r || r->status != 200) return false;
        const nlohmann::json status = nlohmann::json::parse(r->body);  // alive for the loop
        for (const auto& j : status["running"]) {
          if (j["id"] == id) return j["executed"].get<int>() * 2 >= j["total"].get<int>();
        }
        return false;
      },
      30))
      << job().dump() << text_of(dir.path() / "serve1.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));  // a save since
  server->crash();

  server = std::make_unique<ServeProcess>(args, dir.path() / "serve2.log");
  ASSERT_TRUE(test::wait_until([&] { return answers(port); }, 20));
  const nlohmann::json stopped = job();
  ASSERT_EQ(stopped["state"], "interrupted") << stopped.dump();
  EXPECT_GT(stopped["executed"].get<int>(), 0) << stopped.dump();  // saved while it ran
  auto r = client.Post(fmt::format("/api/jobs/{}/control", id).c_str(), auth,
                       R"({"action": "continue"})", "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  ASSERT_TRUE(test::wait_until([&] { return job()["state"] == "completed"; }, 60))
      << job().dump() << text_of(dir.path() / "serve2.log");
  auto log = client.Get(fmt::format("/api/jobs/{}/files/machine.log", id).c_str());
  ASSERT_TRUE(log && log->status == 200);
  EXPECT_NE(log->body.find("where the machine stopped"), std::string::npos) << log->body;
  EXPECT_EQ(server->stop(), 0);
  sim.kill();  // its thread steps the machine: stop it before reading the trace

  // The plan the server made, run uninterrupted on a fresh simulated machine.
  SqliteJobStore store(DataFolder(data).database().string());
  const std::optional<JobRecord> rec = store.get(id);
  ASSERT_TRUE(rec);
  const MachineSpec spec = test::machine("m", "");
  const JobPlan plan = plan_file((data / "jobs" / rec->key / rec->input_file).string(), rec->name,
                                 rec->settings, spec.fit.work_width_mm, spec.fit.work_height_mm);
  sim::SimJobOptions so;
  so.encode = encode_options(*rec);
  const sim::SimJobResult ref = sim::run_sim_job(plan, so);
  const host::test::CutPath reference = host::test::cut_path(ref.trace, plan);
  const host::test::CutPath got = host::test::cut_path(sim.machine().trace(), plan);
  std::printf("kill -9 and continue: cut %.4f mm (uninterrupted %.4f mm), farthest off %.4f mm\n",
              got.length_mm, reference.length_mm, host::test::max_distance_mm(got, reference));
  EXPECT_LT(host::test::max_distance_mm(got, reference), 0.010);
  EXPECT_LT(host::test::max_distance_mm(reference, got), 0.010);
  EXPECT_NEAR(got.length_mm, reference.length_mm, 0.02);
}

}  // namespace
}  // namespace host::server
