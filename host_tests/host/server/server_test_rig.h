// Test rigs for the workshop server: simulated machines on loopback ports, a whole server
// (store, workshop, intake, HTTP) on a temporary data folder, and small G-code jobs.
#ifndef HOST_TESTS_HOST_SERVER_SERVER_TEST_RIG_H
#define HOST_TESTS_HOST_SERVER_SERVER_TEST_RIG_H

#include <arpa/inet.h>   // inet_pton, htons
#include <fmt/format.h>  // fmt::format
#include <netinet/in.h>  // sockaddr_in

#include <nlohmann/json.hpp>  // nlohmann::json

#include <atomic>      // std::atomic
#include <chrono>      // std::chrono
#include <filesystem>  // std::filesystem
#include <functional>  // std::function
#include <memory>      // std::unique_ptr
#include <string>      // std::string
#include <thread>      // std::thread
#include <vector>      // std::vector

#include "host/lib/server/data_folder.h"
#include "host/lib/server/http_api.h"
#include "host/lib/server/job_intake.h"
#include "host/lib/server/sqlite_job_store.h"
#include "host/lib/server/workshop.h"
#include "host/lib/sim/sim_machine.h"
#include "host/lib/sim/sim_server.h"
#include "host_tests/host/temp_dir.h"  // TempDir

// Last: its system headers define macros (`res`) that break Eigen's templates.
#include <httplib.h>  // httplib::Client

namespace host::server::test {

namespace fs = std::filesystem;

using ::host::test::TempDir;

// One simulated machine serving a loopback port from a thread until kill().
class SimRig {
 public:
  explicit SimRig(bool realtime, uint16_t port = 0, sim::SimOptions options = sim::SimOptions{})
      : machine_(std::move(options)) {
    sim::ServerOptions so;
    so.port = port;
    so.realtime = realtime;
    server_ = std::make_unique<sim::SimServer>(machine_, so);
    port_ = server_->port();
    thread_ = std::thread([this] { server_->run(stop_); });
  }
  ~SimRig() { kill(); }
  // The machine goes away: its connection closes and its port stops listening.
  void kill() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    server_.reset();
  }
  uint16_t port() const { return port_; }
  std::string address() const { return fmt::format("tcp://127.0.0.1:{}", port_); }
  const sim::SimMachine& machine() const { return machine_; }

 private:
  sim::SimMachine machine_;
  std::unique_ptr<sim::SimServer> server_;
  uint16_t port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// 127.0.0.1:port, for the tests that speak raw TCP to the server.
inline sockaddr_in loopback_address(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  return a;
}

// A loopback port nobody listens on (bound once, then released).
inline uint16_t free_port() {
  sim::SimMachine m{sim::SimOptions{}};
  sim::ServerOptions so;
  so.port = 0;
  sim::SimServer s(m, so);
  return s.port();
}

inline MachineSpec machine(const std::string& name, const std::string& address) {
  MachineSpec m;
  m.name = name;
  m.address = address;
  return m;
}

// The whole server on a data folder, HTTP on a free loopback port.
class ServerRig {
 public:
  ServerRig(const fs::path& data_dir, std::vector<MachineSpec> machines,
            size_t max_bytes = 256 * 1024, ResumeEncoder resume = {},
            std::chrono::milliseconds silence_limit = std::chrono::milliseconds(1500),
            bool zero_first = true) {
    data_ = std::make_unique<DataFolder>(data_dir);
    bool created = false;
    token_ = data_->token(&created);
    store_ = std::make_unique<SqliteJobStore>(data_->database().string());
    WorkshopOptions wo;
    wo.owner = "test-server";
    wo.poll = std::chrono::milliseconds(20);
    wo.probe = std::chrono::milliseconds(300);
    wo.connect_timeout = std::chrono::milliseconds(500);
    wo.sender.status_interval = std::chrono::milliseconds(5);
    wo.sender.reply_timeout = std::chrono::milliseconds(500);
    wo.sender.silence_limit = silence_limit;
    wo.sender.zero_first = zero_first;                  // false: serve --no-zero
    if (resume) wo.resume_encoder = std::move(resume);  // else the default: continue_from_curve()
    workshop_ = std::make_unique<Workshop>(*store_, *data_, machines, wo);
    intake_ = std::make_unique<JobIntake>(*store_, *data_, workshop_->fits(), max_bytes);
    HttpOptions ho;
    ho.port = 0;
    ho.web_dir = ENGRAVER_WEB_DIR;
    ho.token = token_;
    http_ = std::make_unique<HttpApi>(*store_, *intake_, *workshop_, *data_, ho);
    port_ = http_->bind();
    workshop_->start();
    serving_ = std::thread([this] { http_->run(); });
  }
  ~ServerRig() { shutdown(); }
  void shutdown() {
    if (!http_) return;
    http_->stop();
    serving_.join();
    workshop_->stop();
    http_.reset();
  }

  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(10, 0);
    return c;
  }
  httplib::Headers auth() const { return {{"Authorization", "Bearer " + token_}}; }
  // POST /api/jobs with a raw body; `query` like "&priority=3".
  httplib::Result upload(const std::string& name, const std::string& content,
                         const std::string& query = "") const {
    return client().Post(
        ("/api/jobs?name=" + httplib::detail::encode_query_param(name) + query).c_str(), auth(),
        content, "application/octet-stream");
  }
  int64_t upload_ok(const std::string& name, const std::string& content,
                    const std::string& query = "") const {
    auto r = upload(name, content, query);
    if (!r || r->status != 201) {
      throw std::runtime_error("upload failed: " + (r ? r->body : std::string("no answer")));
    }
    return nlohmann::json::parse(r->body)["id"].get<int64_t>();
  }
  nlohmann::json job(int64_t id) const {
    auto r = client().Get(fmt::format("/api/jobs/{}", id).c_str());
    return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json();
  }
  nlohmann::json jobs() const {
    auto r = client().Get("/api/jobs");
    return r && r->status == 200 ? nlohmann::json::parse(r->body)["jobs"] : nlohmann::json();
  }
  nlohmann::json status() const {
    auto r = client().Get("/api/status");
    return r && r->status == 200 ? nlohmann::json::parse(r->body) : nlohmann::json();
  }
  httplib::Result control(int64_t id, const std::string& json_body) const {
    return client().Post(fmt::format("/api/jobs/{}/control", id).c_str(), auth(), json_body,
                         "application/json");
  }
  // The running job's live progress from /api/status (null when not running).
  nlohmann::json running(int64_t id) const {
    const nlohmann::json status_now = status();  // kept alive for the loop
    for (const auto& j : status_now["running"]) {
      if (j["id"] == id) return j;
    }
    return nlohmann::json();
  }

  const std::string& token() const { return token_; }
  int port() const { return port_; }
  const DataFolder& data() const { return *data_; }
  SqliteJobStore& store() { return *store_; }
  Workshop& workshop() { return *workshop_; }
  JobIntake& intake() { return *intake_; }

 private:
  std::unique_ptr<DataFolder> data_;
  std::string token_;
  std::unique_ptr<SqliteJobStore> store_;
  std::unique_ptr<Workshop> workshop_;
  std::unique_ptr<JobIntake> intake_;
  std::unique_ptr<HttpApi> http_;
  int port_ = 0;
  std::thread serving_;
};

// Polls until done() or the timeout; returns done()'s last answer.
inline bool wait_until(const std::function<bool()>& done, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

// A square of side `size_mm` at (x, y) with a half-circle on top, as G-code.
// `count` separate 0.5 mm lines on a grid as DXF: a job whose reading and planning take a
// while (some seconds for 100 000 in a debug build).
inline std::string separate_lines_dxf(int count) {
  std::string dxf = "0\nSECTION\n2\nENTITIES\n";
  for (int i = 0; i < count; ++i) {
    const std::string x = std::to_string(10 + i % 200), y = std::to_string(10 + i / 200 % 150);
    dxf += "0\nLINE\n8\n0\n10\n" + x + "\n20\n" + y + "\n11\n" + x + ".5\n21\n" + y + ".5\n";
  }
  return dxf + "0\nENDSEC\n0\nEOF\n";
}

inline std::string square_gcode(double x, double y, double size_mm) {
  return fmt::format(
      "G21\nG90\nG0 Z2\nG0 X{0} Y{1}\nG1 Z-0.1 F100\nG1 X{2} Y{1} F600\nG1 X{2} Y{3}\n"
      "G2 X{0} Y{3} I{4} J0\nG1 X{0} Y{1}\nG0 Z2\n",
      x, y, x + size_mm, y + size_mm, -size_mm / 2);
}

// Several separate squares in a row: a job of several curves (pen lifts between them).
inline std::string squares_gcode(int count, double size_mm) {
  std::string g = "G21\nG90\n";
  for (int i = 0; i < count; ++i) {
    const double x = 5 + i * (size_mm + 3), y = 5;
    g += fmt::format(
        "G0 Z2\nG0 X{0} Y{1}\nG1 Z-0.1 F100\nG1 X{2} Y{1} F600\nG1 X{2} Y{3}\nG1 X{0} Y{3}\n"
        "G1 X{0} Y{1}\n",
        x, y, x + size_mm, y + size_mm);
  }
  return g + "G0 Z2\n";
}

}  // namespace host::server::test

#endif  // HOST_TESTS_HOST_SERVER_SERVER_TEST_RIG_H
