// Inbox folder scanning.
#include "host/lib/server/inbox_watcher.h"

#include <fmt/format.h>  // fmt::format

#include <algorithm>  // std::sort
#include <vector>     // std::vector

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

namespace {

// The regular, visible files of a sub-folder with their sizes, one "NAME SIZE" a line
// (sorted): equal in two scans means nobody is writing there.
std::string folder_signature(const fs::path& dir) {
  std::error_code ec;
  std::vector<std::string> lines;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file(ec) || e.is_symlink(ec) || name.empty() || name[0] == '.') continue;
    lines.push_back(fmt::format("{} {}", name, e.file_size(ec)));
  }
  if (ec) return "";
  std::sort(lines.begin(), lines.end());
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

}  // namespace

Submission InboxWatcher::board_folder(const fs::path& dir, IntakeResult* refused) const {
  Submission sub;
  sub.name = dir.filename().string();
  sub.name_source = "the folder name";
  sub.settings = settings_;
  sub.skip_other_files = true;
  std::error_code ec;
  uintmax_t total = 0;
  std::vector<fs::path> paths;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file(ec) || e.is_symlink(ec) || name.empty() || name[0] == '.') continue;
    total += e.file_size(ec);
    paths.push_back(e.path());
  }
  std::sort(paths.begin(), paths.end());
  if (total > intake_.max_bytes()) {
    refused->status = 413;
    refused->error = fmt::format("{}: {} bytes in all, more than the limit of {} bytes", sub.name,
                                 total, intake_.max_bytes());
    return sub;
  }
  if (paths.empty()) {
    refused->status = 400;
    refused->error = sub.name + ": an empty folder";
    return sub;
  }
  for (const fs::path& p : paths)
    sub.files.push_back(UploadFile{p.filename().string(), read_file(p)});
  return sub;
}

void InboxWatcher::scan() {
  std::vector<fs::path> ready, ready_folders;
  find_settled(&ready, &ready_folders);
  for (const fs::path& dir : ready_folders) take_folder(dir);
  for (const fs::path& path : ready) take_file(path);
}

void InboxWatcher::find_settled(std::vector<fs::path>* ready,
                                std::vector<fs::path>* ready_folders) {
  std::error_code ec;
  std::map<std::string, uintmax_t> seen;
  std::map<std::string, std::string> seen_folders;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    const std::string name = e.path().filename().string();
    // A board's sub-folder (not refused/, no link out of the inbox, none hidden).
    if (e.is_directory(ec) && !e.is_symlink(ec) && !name.empty() && name[0] != '.' &&
        name != "refused") {
      const std::string sig = folder_signature(e.path());
      if (sig.empty()) continue;
      seen_folders[name] = sig;
      const auto before = folders_.find(name);
      if (before != folders_.end() && before->second == sig) ready_folders->push_back(e.path());
      continue;
    }
    // Regular files only (no links out of the folder), no hidden or partial uploads.
    if (!e.is_regular_file(ec) || e.is_symlink(ec) || name.empty() || name[0] == '.') continue;
    const uintmax_t size = e.file_size(ec);
    if (ec) continue;
    seen[name] = size;
    const auto before = sizes_.find(name);
    if (before != sizes_.end() && before->second == size) ready->push_back(e.path());
  }
  sizes_ = seen;
  folders_ = seen_folders;
}

void InboxWatcher::take_folder(const fs::path& dir) {
  IntakeResult r;
  try {
    const Submission sub = board_folder(dir, &r);
    if (r.status == 0) r = intake_.submit(sub);
  } catch (const std::exception& e) {
    r.status = 500;
    r.error = e.what();
  }
  folders_.erase(dir.filename().string());
  settle(dir, r);
}

void InboxWatcher::take_file(const fs::path& path) {
  const std::string name = path.filename().string();
  Submission sub;
  sub.name = name;
  sub.settings = settings_;
  IntakeResult r;
  std::error_code ec;
  if (fs::file_size(path, ec) > intake_.max_bytes()) {
    r.status = 413;
    r.error = fmt::format("{}: larger than the limit of {} bytes", name, intake_.max_bytes());
  } else {
    try {
      sub.content_file = path;  // a drawing is copied, not read into memory
      r = intake_.submit(sub);
    } catch (const std::exception& e) {
      r.status = 500;
      r.error = e.what();
    }
  }
  sizes_.erase(name);
  settle(path, r);
}

void InboxWatcher::settle(const fs::path& path, const IntakeResult& r) {
  std::error_code ec;
  const std::string name = path.filename().string();
  if (r.status == 201) {
    fs::remove_all(path, ec);
    if (on_queued_) on_queued_();
    return;
  }
  if (r.status == 503) return;                     // the server stops: taken at its next start
  fs::remove_all(folder_ / "refused" / name, ec);  // a folder refused before under its name
  fs::rename(path, folder_ / "refused" / name, ec);
  try {
    write_file(folder_ / "refused" / (name + ".why.txt"), r.error + "\n");
  } catch (const std::exception&) {
    // The refused file or folder itself is kept; the reason is in the server's log too.
  }
}

}  // namespace host::server
