// The watched inbox folder (the old FTP folder): a drawing dropped there becomes a job, and
// so does a sub-folder holding one board's Gerber/Excellon files (copper, drill, outline;
// other files in it are left out). A file is taken once its size has stayed the same for
// one scan, a sub-folder once its list of files and their sizes has (still being written
// otherwise); queued ones are removed, refused ones go to refused/ with a NAME.why.txt.
#ifndef HOST_LIB_SERVER_INBOX_WATCHER_H
#define HOST_LIB_SERVER_INBOX_WATCHER_H

#include <atomic>      // std::atomic
#include <chrono>      // std::chrono::milliseconds
#include <filesystem>  // std::filesystem::path
#include <functional>  // std::function
#include <map>         // std::map
#include <string>      // std::string
#include <thread>      // std::thread
#include <vector>      // std::vector

#include "host/lib/server/job_intake.h"

namespace host::server {

class InboxWatcher {
 public:
  // on_queued is called after each job the inbox queued (the page refreshes).
  InboxWatcher(std::filesystem::path folder, JobIntake& intake, JobPlanSettings settings,
               std::chrono::milliseconds interval, std::function<void()> on_queued);
  ~InboxWatcher();
  void start();
  void stop();
  // One pass over the folder (the thread calls this; tests may too).
  void scan();

 private:
  std::filesystem::path folder_;
  JobIntake& intake_;
  JobPlanSettings settings_;
  std::chrono::milliseconds interval_;
  std::function<void()> on_queued_;
  // A board's sub-folder: its files for the intake, or the reason it is refused.
  Submission board_folder(const std::filesystem::path& dir, IntakeResult* refused) const;
  // The files and board folders unchanged since the previous scan (an upload has finished).
  void find_settled(std::vector<std::filesystem::path>* ready,
                    std::vector<std::filesystem::path>* ready_folders);
  void take_folder(const std::filesystem::path& dir);
  void take_file(const std::filesystem::path& path);
  // Queued: the file or folder leaves the inbox; refused: to refused/ with NAME.why.txt.
  void settle(const std::filesystem::path& path, const IntakeResult& r);

  std::map<std::string, uintmax_t> sizes_;      // size seen at the previous scan
  std::map<std::string, std::string> folders_;  // sub-folder: its files and sizes then
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_INBOX_WATCHER_H
