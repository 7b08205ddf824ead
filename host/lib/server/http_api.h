// The server's HTTP side: the JSON API, server-sent events with live progress, and the web
// page (plain files from the repository's host/web). Every request that changes anything
// needs the token; uploads are size-limited; a malformed request gets a 4xx with a reason.
#ifndef HOST_LIB_SERVER_HTTP_API_H
#define HOST_LIB_SERVER_HTTP_API_H

#include <atomic>      // std::atomic
#include <cstdint>     // uint64_t
#include <filesystem>  // std::filesystem::path
#include <memory>      // std::unique_ptr
#include <mutex>       // std::mutex
#include <string>      // std::string
#include <vector>      // std::vector

#include <nlohmann/json.hpp>  // nlohmann::json

#include "host/lib/server/allowed_hosts.h"
#include "host/lib/server/data_folder.h"
#include "host/lib/server/job_intake.h"
#include "host/lib/server/job_store.h"
#include "host/lib/server/workshop.h"

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace host::server {

struct HttpOptions {
  std::string address = "127.0.0.1";  // loopback unless told otherwise
  int port = 8080;                    // 0 = any free port
  std::filesystem::path web_dir;      // index.html, app.js, style.css
  std::string token;
  // Host header names answered besides AllowedHosts' defaults (--allowed-host).
  std::vector<std::string> allowed_hosts;
  // Open event streams (pages) served at once; one more is answered 503 (each holds a
  // thread; control requests never wait for them).
  int max_event_streams = 1024;
};

// Every field an upload takes (multipart parts or query parameters): the file's, the job
// record's (job_record_fields.h), a board's.
std::vector<std::string> upload_field_names();

class HttpApi {
 public:
  HttpApi(JobStore& store, JobIntake& intake, Workshop& workshop, const DataFolder& data,
          HttpOptions options);
  ~HttpApi();
  HttpApi(const HttpApi&) = delete;
  HttpApi& operator=(const HttpApi&) = delete;
  // Binds the address; returns the port. Throws std::runtime_error naming the address.
  int bind();
  // Serves until stop() (call bind() first).
  void run();
  void stop();
  const AllowedHosts& allowed_hosts() const { return hosts_; }

 private:
  // The routes, by what they serve (http_api.cpp).
  void routes();
  void route_checks();
  void route_page();
  void route_status();
  void route_jobs();
  void route_job_files();
  void route_upload();
  void route_control();
  void route_priority();
  // The refusals the headers decide (wrong Host 403, wrong method 405, no token 401): true
  // with the answer in res.
  bool refused_from_headers(const httplib::Request& req, httplib::Response& res) const;
  // An upload's body may be this long (--max-upload-mb and a form's framing); the 413's text.
  size_t upload_limit_bytes() const;
  // The request's Content-Length in plain decimal digits; -1 for anything else.
  static int64_t declared_length(const httplib::Request& req);
  std::string upload_limit_text() const;
  // The 404's text for an archive file a job does not have (yet): where it is, or when.
  std::string missing_file_text(const JobRecord& job, const std::string& file) const;
  // Cancel, requeue, continue: answered from the store (true), else false.
  // Why a failed or aborted job cannot be requeued or continued: its height map source
  // ended without a map ("" when it can).
  std::string requeue_without_map_source(int64_t id, bool continue_job);
  bool store_control(int64_t id, const std::string& action, httplib::Response& res);
  bool has_height_map(const JobRecord& job) const;
  // A job as every answer gives it: its record's fields and those worked out now
  // (height_map, height_map_job, waiting).
  nlohmann::json job_answer(const JobRecord& job) const;
  // 200 to a control action: the job (job_answer) with `requested`, the action.
  void send_control_answer(int64_t id, const std::string& action, httplib::Response& res) const;
  void widen_backlog(int port);
  static const int kListenBacklog = 1024;  // connections waiting to be accepted
  // The server-sent event for the workshop's change counter `version`.
  std::string event_text(uint64_t version);
  JobStore& store_;
  JobIntake& intake_;
  Workshop& workshop_;
  const DataFolder& data_;
  HttpOptions options_;
  AllowedHosts hosts_;
  std::unique_ptr<httplib::Server> http_;
  std::atomic<bool> stopping_{false};
  std::atomic<int> open_streams_{0};
  int listen_fd_ = -1;      // the socket bind() listens on
  std::mutex event_mutex_;  // guards the two below
  uint64_t event_version_ = 0;
  std::string event_;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_HTTP_API_H
