// The server's data folder: the job database, the access token and one archive folder per
// job (input, plan, plot, report, machine log). Only names made here become paths.
#ifndef HOST_LIB_SERVER_DATA_FOLDER_H
#define HOST_LIB_SERVER_DATA_FOLDER_H

#include <filesystem>  // std::filesystem::path
#include <string>      // std::string

namespace host::server {

// Files a job's archive folder may hold: the API serves these names and no others.
extern const char* const kArchiveFiles[];  // ends with nullptr
bool is_archive_file(const std::string& name);

class DataFolder {
 public:
  // Creates the folder (and jobs/, tmp/) if needed; clears tmp/ (uploads a crash left).
  // archive: where the jobs' folders go instead of jobs/ ("" = jobs/): a folder shared by
  // the servers of one queue (a network mount), so that each serves every job's files.
  // Throws std::runtime_error naming the folder.
  explicit DataFolder(const std::filesystem::path& root, const std::filesystem::path& archive = {});
  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path database() const { return root_ / "jobs.sqlite"; }
  std::filesystem::path job_dir(const std::string& key) const { return jobs_ / key; }
  // A fresh, empty staging folder for an upload: tmp/<random>, or with a shared archive
  // ARCHIVE/.staging/<random> (on the archive's file system, so the finished job's folder
  // is renamed into place, never copied).
  std::filesystem::path new_staging_dir() const;
  // The access token; created (random, file mode 0600) on first use. *created tells whether
  // it was made now (the CLI shows it once).
  std::string token(bool* created) const;
  std::filesystem::path token_path() const { return root_ / "token"; }  // where token() keeps it

 private:
  std::filesystem::path root_;
  std::filesystem::path jobs_;
  std::filesystem::path staging_;
};

// A random lower-case hex string of 2 * bytes characters (from the OS's random source).
std::string random_hex(size_t bytes);

// Writes the whole file or throws std::runtime_error naming it.
void write_file(const std::filesystem::path& path, const std::string& content);
std::string read_file(const std::filesystem::path& path);
// The file's first `bytes` bytes (all of a shorter file); throws as read_file.
std::string read_file_head(const std::filesystem::path& path, size_t bytes);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_DATA_FOLDER_H
