// `engraver serve` as a process: starts with its defaults on a fresh data folder, shows the
// token once, serves the page, stops on SIGTERM; refuses bad options with exit code 2.
#include <gtest/gtest.h>

#include <arpa/inet.h>   // htonl, ntohs
#include <netinet/in.h>  // sockaddr_in
#include <signal.h>      // kill
#include <sys/socket.h>  // socket, bind, listen
#include <sys/wait.h>    // waitpid
#include <unistd.h>      // fork, execv

#include <cstdlib>  // std::system
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
  ServeProcess(const std::vector<std::string>& args, const fs::path& log,
               const std::string& exe_path = ENGRAVER_EXE) {
    pid_ = fork();
    if (pid_ == 0) {
      FILE* f = std::freopen(log.c_str(), "w", stderr);
      (void)f;
      std::vector<char*> argv;
      std::string exe = exe_path;
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
  // Killed at once, as by a power cut or a crash of the server's process (SIGKILL).
  void kill9() {
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
  // Waits (up to 20 s) for the process to end by itself; its exit status (-1 when it had
  // to be stopped).
  int wait_exit() {
    const int st = wait_exit_within(std::chrono::seconds(20));
    return st == -2 ? status_ = -1 : st;
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

// True once GET `path` answers 200 (the server is up), within 20 s.
bool answers(httplib::Client& client, const char* path) {
  return test::wait_until(
      [&] {
        auto r = client.Get(path);
        return r && r->status == 200;
      },
      20);
}

TEST(ServeCommand, StartsOnAFreshFolderShowsTheTokenOnceAndStopsCleanly) {
  test::TempDir dir;
  const fs::path data = dir.path() / "data";
  const std::string port = std::to_string(test::free_port());
  for (int run = 0; run < 2; ++run) {
    const fs::path log = dir.path() / ("serve" + std::to_string(run) + ".log");
    ServeProcess serve({"serve", "--data", data.string(), "--listen", "127.0.0.1:" + port}, log);
    httplib::Client client("127.0.0.1", std::stoi(port));
    ASSERT_TRUE(answers(client, "/")) << text_of(log);
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

TEST(ServeCommand, AllowedHostAddsANameTheServerAnswersTo) {
  test::TempDir dir;
  const int port = test::free_port();
  const fs::path log = dir.path() / "serve.log";
  ServeProcess serve({"serve", "--data", (dir.path() / "data").string(), "--listen",
                      "127.0.0.1:" + std::to_string(port), "--allowed-host", "workshop.example"},
                     log);
  httplib::Client client("127.0.0.1", port);
  ASSERT_TRUE(answers(client, "/api/status")) << text_of(log);
  auto named = client.Get("/api/jobs", {{"Host", "workshop.example:" + std::to_string(port)}});
  ASSERT_TRUE(named);
  EXPECT_EQ(named->status, 200);
  auto other = client.Get("/api/jobs", {{"Host", "other.example"}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 403) << other->body;
  EXPECT_EQ(serve.stop(), 0);
  EXPECT_NE(text_of(log).find("workshop.example"), std::string::npos) << text_of(log);
}

// kill -9 mid-job: the machine log of the run is on disk up to the moment of the kill, and
// the run after the restart (continue) is a second run beside it.
TEST(ServeCommand, KilledMidJobTheRunsLogIsKept) {
  test::TempDir dir;
  test::SimRig sim(true);  // real time: the job is still running when the server is killed
  const int port = test::free_port();
  const fs::path data = dir.path() / "data";
  const std::vector<std::string> args = {"serve",
                                         "--data",
                                         data.string(),
                                         "--listen",
                                         "127.0.0.1:" + std::to_string(port),
                                         "--machine",
                                         sim.address() + " name=m1"};
  auto serve = std::make_unique<ServeProcess>(args, dir.path() / "serve1.log");
  httplib::Client client("127.0.0.1", port);
  ASSERT_TRUE(answers(client, "/api/status"));
  const std::string token = text_of(data / "token").substr(0, 48);
  auto up =
      client.Post("/api/jobs?name=slow.ngc&feed_mm_s=4", {{"Authorization", "Bearer " + token}},
                  test::square_gcode(10, 10, 40), "application/octet-stream");
  ASSERT_TRUE(up && up->status == 201) << (up ? up->body : "no answer");
  ASSERT_TRUE(test::wait_until(
      [&] {
        auto r = client.Get("/api/status");
        if (!r || r->status != 200) return false;
        const auto running = nlohmann::json::parse(r->body)["running"];
        return !running.empty() && running[0]["executed"].get<int>() >= 3;
      },
      20));
  serve->kill9();
  fs::path job_dir;
  for (const auto& e : fs::directory_iterator(data / "jobs")) job_dir = e.path();
  const std::string log = text_of(job_dir / "runs" / "1" / "machine.log");
  EXPECT_NE(log.find("planned:"), std::string::npos) << log;
  EXPECT_NE(log.find("machine running"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(job_dir / "runs" / "1" / "report.json"));  // it never ended

  // Started again: the job is interrupted; re-queued, it runs as run 2, run 1 untouched.
  serve = std::make_unique<ServeProcess>(args, dir.path() / "serve2.log");
  ASSERT_TRUE(test::wait_until(
      [&] {
        auto r = client.Get("/api/jobs/1");
        return r && r->status == 200 && nlohmann::json::parse(r->body)["state"] == "interrupted";
      },
      20));
  auto c = client.Post("/api/jobs/1/control", {{"Authorization", "Bearer " + token}},
                       R"({"action": "requeue"})", "application/json");
  ASSERT_TRUE(c && c->status == 200) << (c ? c->body : "no answer");
  EXPECT_TRUE(
      test::wait_until([&] { return fs::exists(job_dir / "runs" / "2" / "machine.log"); }, 20));
  EXPECT_EQ(text_of(job_dir / "runs" / "1" / "machine.log"), log);
  EXPECT_EQ(serve->stop(), 0);
  // Stopped (Ctrl-C) with run 2 going: the server stopped it, no operator did.
  const std::string run2 = text_of(job_dir / "runs" / "2" / "report.json");
  EXPECT_NE(run2.find("the server stopped while the job was running"), std::string::npos) << run2;
  for (const fs::path& f : {job_dir / "runs" / "2" / "report.json",
                            job_dir / "runs" / "2" / "machine.log", dir.path() / "serve2.log"}) {
    EXPECT_EQ(text_of(f).find("by the operator"), std::string::npos) << f << ": " << text_of(f);
  }
}

// `cmake --install` to a fresh prefix: the installed engraver serves the installed page,
// wherever the source checkout is; a copied engraver without the page refuses to start.
TEST(ServeCommand, TheInstalledEngraverServesTheInstalledPage) {
  test::TempDir dir;
  const fs::path prefix = dir.path() / "prefix";
  const std::string install = std::string(CMAKE_EXE) + " --install '" + ENGRAVER_BUILD_DIR +
                              "' --prefix '" + prefix.string() + "' > '" +
                              (dir.path() / "install.log").string() + "' 2>&1";
  ASSERT_EQ(std::system(install.c_str()), 0) << text_of(dir.path() / "install.log");
  const fs::path exe = prefix / "bin" / "engraver";
  ASSERT_TRUE(fs::exists(exe));
  // The installed page is the page of this checkout, a copy (not a link to it).
  const fs::path page = prefix / "share" / "engraver" / "web" / "index.html";
  EXPECT_EQ(text_of(page), text_of(fs::path(ENGRAVER_WEB_DIR) / "index.html"));
  EXPECT_FALSE(fs::is_symlink(page));
  const int port = test::free_port();
  const fs::path log = dir.path() / "serve.log";
  ServeProcess serve({"serve", "--data", (dir.path() / "data").string(), "--listen",
                      "127.0.0.1:" + std::to_string(port)},
                     log, exe.string());
  httplib::Client client("127.0.0.1", port);
  ASSERT_TRUE(answers(client, "/app.js")) << text_of(log);
  auto index = client.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->body, text_of(page));
  EXPECT_EQ(serve.stop(), 0);

  // The binaries copied alone: no page beside them, so it does not start (exit 2, says where).
  const fs::path alone = dir.path() / "alone" / "bin" / "engraver";
  fs::create_directories(alone.parent_path());
  fs::copy_file(exe, alone);
  fs::copy_file(prefix / "bin" / "engraver-serve", alone.parent_path() / "engraver-serve");
  ServeProcess copied({"serve", "--data", (dir.path() / "data2").string(), "--listen",
                       "127.0.0.1:" + std::to_string(port)},
                      dir.path() / "alone.log", alone.string());
  EXPECT_EQ(copied.wait_exit(), 2);
  const std::string why = text_of(dir.path() / "alone.log");
  EXPECT_NE(why.find("share/engraver/web lacks the page's index.html"), std::string::npos) << why;
  EXPECT_NE(why.find("--web"), std::string::npos) << why;
  // --web naming a folder without the page: the same.
  fs::create_directories(dir.path() / "empty");
  ServeProcess empty({"serve", "--data", (dir.path() / "data3").string(), "--web",
                      (dir.path() / "empty").string()},
                     dir.path() / "empty.log");
  EXPECT_EQ(empty.wait_exit(), 2);
  EXPECT_NE(text_of(dir.path() / "empty.log").find("lacks the page's"), std::string::npos);
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

// A port already listened on: exit 2 naming it, and nothing made in the data folder (a token
// made then would never be shown: the next start finds it and prints none).
TEST(ServeCommand, APortInUseIsAUsageErrorBeforeTheDataFolderIsMade) {
  test::TempDir dir;
  const int held = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(held, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t n = sizeof a;
  ASSERT_EQ(::bind(held, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(held, 1), 0);
  ASSERT_EQ(::getsockname(held, reinterpret_cast<sockaddr*>(&a), &n), 0);
  const std::string listen = "127.0.0.1:" + std::to_string(ntohs(a.sin_port));
  const fs::path data = dir.path() / "data";
  ServeProcess p({"serve", "--data", data.string(), "--listen", listen}, dir.path() / "in_use.log");
  EXPECT_EQ(p.wait_exit(), 2);
  ::close(held);
  const std::string said = text_of(dir.path() / "in_use.log");
  EXPECT_NE(said.find("--listen: '" + listen + "': cannot listen on " + listen), std::string::npos)
      << said;
  EXPECT_FALSE(fs::exists(data)) << said;
}

// A start that fails after the data folder is made (a database it cannot reach) takes back
// the token it made and never showed: the next start makes one and shows it (outside tester
// 17: the token was kept unseen, and no start ever printed it).
TEST(ServeCommand, AStartThatFailsKeepsNoTokenNobodyWasShown) {
  test::TempDir dir;
  const fs::path data = dir.path() / "data";
  const std::string port = std::to_string(test::free_port());
  ServeProcess failed({"serve", "--data", data.string(), "--listen", "127.0.0.1:" + port, "--db",
                       "host=127.0.0.1 port=1 connect_timeout=5"},
                      dir.path() / "failed.log");
  EXPECT_EQ(failed.wait_exit(), 1) << text_of(dir.path() / "failed.log");
  EXPECT_FALSE(fs::exists(data / "token")) << text_of(dir.path() / "failed.log");
  const fs::path log = dir.path() / "serve.log";
  ServeProcess serve({"serve", "--data", data.string(), "--listen", "127.0.0.1:" + port}, log);
  httplib::Client client("127.0.0.1", std::stoi(port));
  ASSERT_TRUE(answers(client, "/")) << text_of(log);
  EXPECT_EQ(serve.stop(), 0) << text_of(log);
  const std::string token = text_of(data / "token");
  ASSERT_GE(token.size(), 32u);
  EXPECT_NE(text_of(log).find(token.substr(0, 32)), std::string::npos) << text_of(log);
}

// `engraver serve` runs engraver-serve from beside engraver (the server's libraries stay out
// of the other commands' start-up); engraver copied without it says what is missing.
TEST(ServeCommand, EngraverWithoutEngraverServeSaysWhatIsMissing) {
  test::TempDir dir;
  const fs::path alone = dir.path() / "bin" / "engraver";
  fs::create_directories(alone.parent_path());
  fs::copy_file(ENGRAVER_EXE, alone);
  ServeProcess p({"serve", "--data", (dir.path() / "d").string()}, dir.path() / "alone.log",
                 alone.string());
  EXPECT_EQ(p.wait_exit(), 2);
  const std::string why = text_of(dir.path() / "alone.log");
  EXPECT_NE(why.find("engraver-serve"), std::string::npos) << why;
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

  first->kill9();  // kill -9: the lock goes with the process
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
  server->kill9();

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
