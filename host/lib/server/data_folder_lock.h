// One server per data folder: an exclusive lock (flock) on DATA/server.lock, held for the
// life of the process. The kernel drops it when the process ends, kill -9 included, so a
// crashed server never blocks its own restart; a second live server on the folder is refused
// before it touches anything (it would mark the first one's running jobs interrupted).
#ifndef HOST_LIB_SERVER_DATA_FOLDER_LOCK_H
#define HOST_LIB_SERVER_DATA_FOLDER_LOCK_H

#include <filesystem>  // std::filesystem::path
#include <stdexcept>   // std::runtime_error

namespace host::server {

// Another live server holds the folder. what() names the folder and that server's pid.
class FolderInUse : public std::runtime_error {
 public:
  explicit FolderInUse(const std::string& msg) : std::runtime_error(msg) {}
};

class DataFolderLock {
 public:
  // Creates the folder if needed and takes the lock. Throws FolderInUse when another process
  // holds it, std::runtime_error when the lock file cannot be made.
  explicit DataFolderLock(const std::filesystem::path& root);
  ~DataFolderLock();
  DataFolderLock(const DataFolderLock&) = delete;
  DataFolderLock& operator=(const DataFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace host::server

#endif  // HOST_LIB_SERVER_DATA_FOLDER_LOCK_H
