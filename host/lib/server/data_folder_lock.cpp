// flock on DATA/server.lock; the holder's pid is written into the file for the message.
#include "host/lib/server/data_folder_lock.h"

#include <errno.h>     // errno
#include <fcntl.h>     // open
#include <sys/file.h>  // flock
#include <unistd.h>    // ftruncate, write, close, getpid

#include <cstring>  // std::strerror
#include <string>   // std::string

namespace host::server {

namespace fs = std::filesystem;

DataFolderLock::DataFolderLock(const fs::path& root) {
  std::error_code ec;
  fs::create_directories(root, ec);
  const fs::path path = root / "server.lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error(path.string() +
                             ": cannot open the lock file: " + std::strerror(errno));
  }
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    char buf[32] = {};
    const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
    std::string pid = n > 0 ? std::string(buf, static_cast<size_t>(n)) : std::string();
    while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK) {
      throw std::runtime_error(path.string() + ": cannot lock: " + std::strerror(err));
    }
    throw FolderInUse(root.string() + ": another engraver serve uses this data folder" +
                      (pid.empty() ? std::string() : " (pid " + pid + ")") +
                      "; one folder serves one server: stop that one or give this one its own "
                      "--data");
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) == 0) {
    const ssize_t written = ::pwrite(fd_, pid.data(), pid.size(), 0);
    (void)written;  // the pid is only for the message above
  }
}

DataFolderLock::~DataFolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace host::server
