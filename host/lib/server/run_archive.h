// One run of a job in its archive folder. Every start of a job (the first, a re-queue, a
// continue) is a new run with its own folder, runs/1/, runs/2/ ...: machine.log is written
// line by line while the job runs (each line handed to the OS at once, so a server killed
// mid-job leaves the log up to its last line) and report.json when the run ends.
#ifndef HOST_LIB_SERVER_RUN_ARCHIVE_H
#define HOST_LIB_SERVER_RUN_ARCHIVE_H

#include <nlohmann/json.hpp>  // nlohmann::json

#include <filesystem>  // std::filesystem::path
#include <string>      // std::string

namespace host::server {

class RunArchive {
 public:
  // Makes job_dir/runs/<n>/ with the next free number (1 for the first run) and opens its
  // machine.log. Throws std::runtime_error naming the folder.
  explicit RunArchive(const std::filesystem::path& job_dir);
  ~RunArchive();
  RunArchive(const RunArchive&) = delete;
  RunArchive& operator=(const RunArchive&) = delete;
  int number() const { return number_; }
  // Appends one line to machine.log (written through at once). Throws std::runtime_error.
  void log(const std::string& line);
  void write_report(const nlohmann::json& report) const;

 private:
  int number_ = 0;
  std::filesystem::path dir_;
  int log_fd_ = -1;
};

// How many runs a job's archive holds (0 before its first start).
int run_count(const std::filesystem::path& job_dir);
// A file of a run: runs/<run>/<name>; run 0 = the newest run (a job archived before runs
// were kept: the file in the job's folder itself).
std::filesystem::path run_file(const std::filesystem::path& job_dir, int run,
                               const std::string& name);
// Whether `name` is a file a run holds (machine.log, report.json).
bool is_run_file(const std::string& name);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_RUN_ARCHIVE_H
