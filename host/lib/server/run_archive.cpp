// A job's runs in its archive folder (see run_archive.h).
#include "host/lib/server/run_archive.h"

#include <fcntl.h>   // open
#include <unistd.h>  // write, close

#include <cerrno>     // errno
#include <cstring>    // std::strerror
#include <stdexcept>  // std::runtime_error

#include "host/lib/server/data_folder.h"  // write_file

namespace host::server {

namespace fs = std::filesystem;

namespace {

// The run number of a folder name ("12" -> 12), 0 when it is not one.
int run_number(const std::string& name) {
  if (name.empty() || name.size() > 6 || name[0] == '0') return 0;
  int n = 0;
  for (char c : name) {
    if (c < '0' || c > '9') return 0;
    n = n * 10 + (c - '0');
  }
  return n;
}

}  // namespace

int run_count(const fs::path& job_dir) {
  std::error_code ec;
  int last = 0;
  for (fs::directory_iterator it(job_dir / "runs", ec), end; !ec && it != end; it.increment(ec)) {
    last = std::max(last, run_number(it->path().filename().string()));
  }
  return last;
}

fs::path run_file(const fs::path& job_dir, int run, const std::string& name) {
  if (run == 0) run = run_count(job_dir);
  if (run == 0) return job_dir / name;
  return job_dir / "runs" / std::to_string(run) / name;
}

bool is_run_file(const std::string& name) {
  return name == "machine.log" || name == "report.json";
}

RunArchive::RunArchive(const fs::path& job_dir) {
  std::error_code ec;
  fs::create_directories(job_dir / "runs", ec);
  // create_directory fails on an existing folder: a number is never taken twice, even by
  // two servers sharing the archive.
  for (number_ = run_count(job_dir) + 1; !ec; ++number_) {
    dir_ = job_dir / "runs" / std::to_string(number_);
    if (fs::create_directory(dir_, ec)) break;
  }
  if (ec) throw std::runtime_error((job_dir / "runs").string() + ": " + ec.message());
  const fs::path log = dir_ / "machine.log";
  log_fd_ = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log_fd_ < 0) throw std::runtime_error(log.string() + ": " + std::strerror(errno));
}

RunArchive::~RunArchive() {
  if (log_fd_ >= 0) ::close(log_fd_);
}

void RunArchive::log(const std::string& line) {
  const std::string text = line + "\n";
  // One write per line: a reader (or a crash) sees whole lines only.
  if (::write(log_fd_, text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
    throw std::runtime_error((dir_ / "machine.log").string() + ": cannot write");
  }
}

void RunArchive::write_report(const nlohmann::json& report) const {
  write_file(dir_ / "report.json",
             report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace host::server
