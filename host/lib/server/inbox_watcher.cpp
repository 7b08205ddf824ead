// Inbox folder scanning.
#include "host/lib/server/inbox_watcher.h"

#include <fmt/format.h>  // fmt::format

#include <vector>  // std::vector

namespace host::server {

namespace fs = std::filesystem;

InboxWatcher::InboxWatcher(fs::path folder, JobIntake& intake, JobPlanSettings settings,
                           std::chrono::milliseconds interval, std::function<void()> on_queued)
    : folder_(std::move(folder)),
      intake_(intake),
      settings_(settings),
      interval_(interval),
      on_queued_(std::move(on_queued)) {
  fs::create_directories(folder_ / "refused");
}

InboxWatcher::~InboxWatcher() {
  stop();
}

void InboxWatcher::start() {
  stop_ = false;
  thread_ = std::thread([this] {
    while (!stop_) {
      scan();
      for (auto waited = std::chrono::milliseconds(0); waited < interval_ && !stop_;
           waited += std::chrono::milliseconds(50)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
  });
}

void InboxWatcher::stop() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void InboxWatcher::scan() {
  std::error_code ec;
  std::map<std::string, uintmax_t> seen;
  std::vector<fs::path> ready;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    const std::string name = e.path().filename().string();
    // Regular files only (no links out of the folder), no hidden or partial uploads.
    if (!e.is_regular_file(ec) || e.is_symlink(ec) || name.empty() || name[0] == '.') continue;
    const uintmax_t size = e.file_size(ec);
    if (ec) continue;
    seen[name] = size;
    const auto before = sizes_.find(name);
    if (before != sizes_.end() && before->second == size) ready.push_back(e.path());
  }
  sizes_ = seen;
  for (const fs::path& path : ready) {
    const std::string name = path.filename().string();
    Submission sub;
    sub.name = name;
    sub.settings = settings_;
    IntakeResult r;
    if (fs::file_size(path, ec) > intake_.max_bytes()) {
      r.status = 413;
      r.error = fmt::format("{}: larger than the limit of {} bytes", name, intake_.max_bytes());
    } else {
      try {
        sub.content = read_file(path);
        r = intake_.submit(sub);
      } catch (const std::exception& e) {
        r.status = 500;
        r.error = e.what();
      }
    }
    sizes_.erase(name);
    if (r.status == 201) {
      fs::remove(path, ec);
      if (on_queued_) on_queued_();
    } else {
      fs::rename(path, folder_ / "refused" / name, ec);
      try {
        write_file(folder_ / "refused" / (name + ".why.txt"), r.error + "\n");
      } catch (const std::exception&) {
        // The refused file itself is kept; the reason is in the server's log too.
      }
    }
  }
}

}  // namespace host::server
